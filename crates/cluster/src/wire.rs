//! The bytes that travel between ranks: a little-endian writer and a checked reader, and
//! the encoding of a rendered [`Piece`] (every per-pixel value bit for bit, so that rank
//! 0 assembles the very image one process renders).

use std::time::Duration;

use beam_trace::Coverage;
use beam_trace::beam::BoxClass;
use beam_trace::render::{BoxMap, Piece, PieceShadows, PixelBox};
use beam_trace::screen::PixelRect;
use beam_trace::shadow::ShadowClass;
use beam_trace::stats::PassStats;
use beam_trace::window::Window;
use interval_core::Interval;

/// Appends values to a byte buffer.
#[derive(Default)]
pub struct Writer(pub Vec<u8>);

impl Writer {
    /// A `u8`.
    pub fn u8(&mut self, v: u8) {
        self.0.push(v);
    }

    /// A `u32`.
    pub fn u32(&mut self, v: u32) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }

    /// A `u64`.
    pub fn u64(&mut self, v: u64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }

    /// An `f32`, bit for bit.
    pub fn f32(&mut self, v: f32) {
        self.u32(v.to_bits());
    }

    /// An `f64`, bit for bit.
    pub fn f64(&mut self, v: f64) {
        self.u64(v.to_bits());
    }

    /// A length.
    pub fn len(&mut self, n: usize) {
        self.u64(n as u64);
    }

    /// A string.
    pub fn str(&mut self, s: &str) {
        self.len(s.len());
        self.0.extend_from_slice(s.as_bytes());
    }

    /// A duration.
    pub fn duration(&mut self, d: Duration) {
        self.u64(d.as_nanos() as u64);
    }

    /// A rectangle of pixels.
    pub fn rect(&mut self, r: PixelRect) {
        for v in [r.x0, r.y0, r.x1, r.y1] {
            self.u32(v);
        }
    }
}

/// Reads values back, refusing a buffer that ends early.
pub struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

/// A reading error: what was being read.
pub type ReadError = String;

impl<'a> Reader<'a> {
    /// A reader at the start of `bytes`.
    pub fn new(bytes: &'a [u8]) -> Self {
        Self { bytes, at: 0 }
    }

    fn take<const N: usize>(&mut self, what: &str) -> Result<[u8; N], ReadError> {
        let end = self.at + N;
        let b = self
            .bytes
            .get(self.at..end)
            .ok_or_else(|| format!("ends at byte {} inside {what}", self.bytes.len()))?;
        self.at = end;
        Ok(b.try_into().expect("N bytes"))
    }

    /// A `u8`.
    pub fn u8(&mut self, what: &str) -> Result<u8, ReadError> {
        Ok(self.take::<1>(what)?[0])
    }

    /// A `u32`.
    pub fn u32(&mut self, what: &str) -> Result<u32, ReadError> {
        Ok(u32::from_le_bytes(self.take(what)?))
    }

    /// A `u64`.
    pub fn u64(&mut self, what: &str) -> Result<u64, ReadError> {
        Ok(u64::from_le_bytes(self.take(what)?))
    }

    /// An `f32`.
    pub fn f32(&mut self, what: &str) -> Result<f32, ReadError> {
        Ok(f32::from_bits(self.u32(what)?))
    }

    /// An `f64`.
    pub fn f64(&mut self, what: &str) -> Result<f64, ReadError> {
        Ok(f64::from_bits(self.u64(what)?))
    }

    /// A length, no more than the bytes left could hold at `min_size` bytes an item.
    pub fn len(&mut self, what: &str, min_size: usize) -> Result<usize, ReadError> {
        let n = self.u64(what)?;
        let left = (self.bytes.len() - self.at) as u64;
        if n.saturating_mul(min_size.max(1) as u64) > left {
            return Err(format!("{what}: {n} items in {left} bytes"));
        }
        Ok(n as usize)
    }

    /// A string.
    pub fn str(&mut self, what: &str) -> Result<String, ReadError> {
        let n = self.len(what, 1)?;
        let b = &self.bytes[self.at..self.at + n];
        self.at += n;
        String::from_utf8(b.to_vec()).map_err(|_| format!("{what}: not UTF-8"))
    }

    /// A duration.
    pub fn duration(&mut self, what: &str) -> Result<Duration, ReadError> {
        Ok(Duration::from_nanos(self.u64(what)?))
    }

    /// A rectangle of pixels.
    pub fn rect(&mut self, what: &str) -> Result<PixelRect, ReadError> {
        Ok(PixelRect {
            x0: self.u32(what)?,
            y0: self.u32(what)?,
            x1: self.u32(what)?,
            y1: self.u32(what)?,
        })
    }

    /// Checks that every byte was read.
    pub fn finish(&self, what: &str) -> Result<(), ReadError> {
        if self.at == self.bytes.len() {
            Ok(())
        } else {
            Err(format!(
                "{what}: {} bytes left over",
                self.bytes.len() - self.at
            ))
        }
    }
}

/// Writes the passes' names, times and counters.
pub fn write_stats(w: &mut Writer, stats: &[PassStats]) {
    w.len(stats.len());
    for p in stats {
        w.str(&p.name);
        w.u8(u8::from(p.ran));
        w.duration(p.time);
        w.len(p.counters.len());
        for (n, v) in &p.counters {
            w.str(n);
            w.u64(*v);
        }
        w.len(p.phases.len());
        for (n, t) in &p.phases {
            w.str(n);
            w.duration(*t);
        }
    }
}

/// Reads what [`write_stats`] wrote.
pub fn read_stats(r: &mut Reader<'_>) -> Result<Vec<PassStats>, ReadError> {
    let n = r.len("passes", 17)?;
    let mut out = Vec::with_capacity(n);
    for _ in 0..n {
        let name = r.str("pass name")?;
        let ran = r.u8("pass ran")? != 0;
        let time = r.duration("pass time")?;
        let k = r.len("counters", 16)?;
        let mut counters = Vec::with_capacity(k);
        for _ in 0..k {
            counters.push((r.str("counter name")?, r.u64("counter")?));
        }
        let k = r.len("phases", 16)?;
        let mut phases = Vec::with_capacity(k);
        for _ in 0..k {
            phases.push((r.str("phase name")?, r.duration("phase time")?));
        }
        out.push(PassStats {
            name,
            ran,
            time,
            counters,
            phases,
        });
    }
    Ok(out)
}

fn write_interval(w: &mut Writer, t: Interval<f64>) {
    w.f64(t.inf());
    w.f64(t.sup());
}

fn read_interval(r: &mut Reader<'_>) -> Result<Interval<f64>, ReadError> {
    let (lo, hi) = (r.f64("interval")?, r.f64("interval")?);
    if lo > hi {
        // What `inf` and `sup` give for the empty interval.
        return Ok(Interval::EMPTY);
    }
    Interval::new(lo, hi).map_err(|e| format!("interval [{lo}, {hi}]: {e}"))
}

const SHADOW_CLASSES: [ShadowClass; 4] = [
    ShadowClass::Lit,
    ShadowClass::Umbra,
    ShadowClass::Penumbra,
    ShadowClass::BackFacing,
];

fn shadow_tag(c: Option<ShadowClass>) -> u8 {
    c.map_or(0, |c| {
        1 + SHADOW_CLASSES
            .iter()
            .position(|&k| k == c)
            .expect("every class is listed") as u8
    })
}

/// Writes a rendered piece.
pub fn write_piece(w: &mut Writer, p: &Piece) {
    w.rect(p.window.rect());
    let (iw, ih) = p.window.image_size();
    w.u32(iw);
    w.u32(ih);
    for c in &p.colors {
        c.iter().for_each(|&v| w.f32(v));
    }
    for c in p.classes.iter() {
        match c.get() {
            None => w.u8(0),
            Some((BoxClass::Miss, edge)) => w.u8(1 | u8::from(edge) << 4),
            Some((BoxClass::Hit { t_final }, edge)) => {
                w.u8(2 | u8::from(edge) << 4);
                write_interval(w, t_final);
            }
            Some((BoxClass::Undecided { t }, edge)) => {
                w.u8(3 | u8::from(edge) << 4);
                write_interval(w, t);
            }
        }
    }
    for c in &p.coverage {
        w.f32(c.proven);
        w.f32(c.possible);
    }
    p.cost.iter().for_each(|&v| w.f32(v));
    match &p.shadows {
        None => w.u8(0),
        Some(s) => {
            w.u8(1);
            s.classes.iter().for_each(|&c| w.u8(shadow_tag(c)));
            w.len(s.fractions.len());
            for maps in [&s.fractions, &s.lower, &s.upper] {
                for m in maps {
                    m.iter().for_each(|&v| w.f32(v));
                }
            }
        }
    }
    write_stats(w, &p.passes);
    write_stats(w, &p.lights);
}

/// Reads what [`write_piece`] wrote, checking the window and the sizes.
pub fn read_piece(r: &mut Reader<'_>) -> Result<Piece, ReadError> {
    let rect = r.rect("window")?;
    let (iw, ih) = (r.u32("image width")?, r.u32("image height")?);
    let window = Window::new(rect, iw, ih).map_err(|e| e.to_string())?;
    let n = window.len();
    let colors = (0..n)
        .map(|_| Ok([r.f32("colour")?, r.f32("colour")?, r.f32("colour")?]))
        .collect::<Result<Vec<_>, ReadError>>()?;
    let mut classes = Vec::with_capacity(n);
    for _ in 0..n {
        let tag = r.u8("box class")?;
        let edge = tag >> 4 != 0;
        classes.push(PixelBox::from(match tag & 15 {
            0 => None,
            1 => Some((BoxClass::Miss, edge)),
            2 => Some((
                BoxClass::Hit {
                    t_final: read_interval(r)?,
                },
                edge,
            )),
            3 => Some((
                BoxClass::Undecided {
                    t: read_interval(r)?,
                },
                edge,
            )),
            t => return Err(format!("box class tag {t}")),
        }));
    }
    let classes = BoxMap::try_from_pixels(classes)
        .ok_or_else(|| "more than 2^31 screen boxes in a piece".to_string())?;
    let coverage = (0..n)
        .map(|_| {
            Ok(Coverage {
                proven: r.f32("coverage")?,
                possible: r.f32("coverage")?,
            })
        })
        .collect::<Result<Vec<_>, ReadError>>()?;
    let cost = (0..n)
        .map(|_| r.f32("cost"))
        .collect::<Result<Vec<_>, ReadError>>()?;
    let shadows = match r.u8("shadow maps")? {
        0 => None,
        _ => {
            let classes = (0..n)
                .map(|_| match r.u8("shadow class")? {
                    0 => Ok(None),
                    t if usize::from(t) <= SHADOW_CLASSES.len() => {
                        Ok(Some(SHADOW_CLASSES[usize::from(t) - 1]))
                    }
                    t => Err(format!("shadow class tag {t}")),
                })
                .collect::<Result<Vec<_>, ReadError>>()?;
            let lights = r.len("area lights", 12 * n)?;
            let mut maps = (0..3).map(|_| {
                (0..lights)
                    .map(|_| {
                        (0..n)
                            .map(|_| r.f32("shadow map"))
                            .collect::<Result<Vec<_>, ReadError>>()
                    })
                    .collect::<Result<Vec<_>, ReadError>>()
            });
            let fractions = maps.next().expect("three maps")?;
            let lower = maps.next().expect("three maps")?;
            let upper = maps.next().expect("three maps")?;
            Some(PieceShadows {
                classes,
                fractions,
                lower,
                upper,
            })
        }
    };
    let passes = read_stats(r)?;
    let lights = read_stats(r)?;
    Ok(Piece {
        window,
        colors,
        classes,
        coverage,
        cost,
        shadows,
        passes,
        lights,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use beam_trace::render::Pipeline;
    use beam_trace::{Cpu, NoProgress, Plan, Scene};

    #[test]
    fn pieces_travel_bit_for_bit() {
        let mut scene = Scene::load(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../../scenes/soft-shadows.toml"),
        )
        .expect("the scene loads");
        scene.camera = scene.camera.resized(80, 60).expect("a size");
        scene.settings.shadow_method = "stochastic:4".parse().expect("a method");
        let plan = Plan::for_scene(&scene);
        let pipeline = Pipeline::new(&scene, &Cpu, &plan).expect("prepares");
        let window = Window::new(
            PixelRect {
                x0: 64,
                y0: 0,
                x1: 80,
                y1: 60,
            },
            80,
            60,
        )
        .expect("a window");
        let piece = pipeline.render(&window, &NoProgress).expect("renders");
        assert!(piece.shadows.is_some());
        let mut w = Writer::default();
        write_piece(&mut w, &piece);
        let mut r = Reader::new(&w.0);
        let back = read_piece(&mut r).expect("reads");
        r.finish("piece").expect("every byte read");
        let bits = |p: &Piece| {
            let mut w = Writer::default();
            write_piece(&mut w, p);
            w.0
        };
        assert_eq!(bits(&back), w.0);
        assert_eq!(back.passes, piece.passes);
        // Every truncation is refused, never a panic.
        for cut in [0, 7, 100, w.0.len() / 2, w.0.len() - 1] {
            assert!(read_piece(&mut Reader::new(&w.0[..cut])).is_err());
        }
    }
}
