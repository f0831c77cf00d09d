//! Images: linear RGB in `f32`, written as 8-bit sRGB PNG, whole or not at all.

use std::fs;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use crate::error::Error;

/// An RGB image, row-major from the top-left pixel, channels in `[0, 1]` (linear).
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height` pixels.
    pub pixels: Vec<[f32; 3]>,
}

impl Image {
    /// An image filled with `color`.
    pub fn new(width: u32, height: u32, color: [f32; 3]) -> Self {
        Self {
            width,
            height,
            pixels: vec![color; width as usize * height as usize],
        }
    }

    /// The pixel at `(x, y)`.
    pub fn get(&self, x: u32, y: u32) -> [f32; 3] {
        self.pixels[(y * self.width + x) as usize]
    }

    /// Sets the pixel at `(x, y)`.
    pub fn set(&mut self, x: u32, y: u32, c: [f32; 3]) {
        self.pixels[(y * self.width + x) as usize] = c;
    }

    /// 8-bit RGB bytes (sRGB transfer curve, clamped).
    pub fn to_rgb8(&self) -> Vec<u8> {
        fn encode(c: f32) -> u8 {
            let c = c.clamp(0.0, 1.0);
            let s = if c <= 0.003_130_8 {
                12.92 * c
            } else {
                1.055 * c.powf(1.0 / 2.4) - 0.055
            };
            (s * 255.0 + 0.5) as u8
        }
        self.pixels
            .iter()
            .flat_map(|p| p.iter().map(|&c| encode(c)))
            .collect()
    }

    /// Writes the image as a PNG at `path`, whole or not at all (a temporary file in the
    /// same folder, then a rename).
    pub fn write_png(&self, path: &Path) -> Result<(), Error> {
        write_atomic(path, |file| {
            let mut enc = png::Encoder::new(BufWriter::new(file), self.width, self.height);
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Eight);
            let mut w = enc.write_header().map_err(std::io::Error::other)?;
            w.write_image_data(&self.to_rgb8())
                .map_err(std::io::Error::other)?;
            w.finish().map_err(std::io::Error::other)
        })
    }
}

/// Writes `frames` (all of one size) as an animated PNG (APNG) that plays at `rate` frames
/// per second and loops; browsers and most image viewers play it, and a viewer without
/// APNG shows the first frame. Written atomically, as [`Image::write_png`].
///
/// # Errors
///
/// [`Error::Io`] when there is no frame, the frames differ in size, the rate is not
/// positive, or the file cannot be written.
pub fn write_apng(frames: &[Image], rate: f64, path: &Path) -> Result<(), Error> {
    let size = frames.first().map_or((0, 0), |f| (f.width, f.height));
    if let Some(f) = frames.iter().find(|f| (f.width, f.height) != size) {
        return Err(invalid_input(
            path,
            format!(
                "frames of {} × {} and {} × {} pixels",
                size.0, size.1, f.width, f.height
            ),
        ));
    }
    let rgb: Vec<Vec<u8>> = frames.iter().map(Image::to_rgb8).collect();
    write_apng_rgb8(size.0, size.1, &rgb, rate, path)
}

/// [`write_apng`] of frames already encoded as 8-bit RGB rows ([`Image::to_rgb8`]), each
/// `width × height × 3` bytes: a long animation keeps a quarter of the memory of its
/// [`Image`]s.
///
/// # Errors
///
/// As [`write_apng`], and when a frame has another number of bytes.
pub fn write_apng_rgb8(
    width: u32,
    height: u32,
    frames: &[Vec<u8>],
    rate: f64,
    path: &Path,
) -> Result<(), Error> {
    if frames.is_empty() {
        return Err(invalid_input(
            path,
            "an animation needs at least one frame".into(),
        ));
    }
    let bytes = width as usize * height as usize * 3;
    if let Some(f) = frames.iter().find(|f| f.len() != bytes) {
        return Err(invalid_input(
            path,
            format!(
                "a frame of {} bytes, {width} × {height} RGB needs {bytes}",
                f.len()
            ),
        ));
    }
    if !(rate.is_finite() && rate > 0.0) {
        return Err(invalid_input(
            path,
            format!("frames per second must be positive, got {rate}"),
        ));
    }
    // The delay of each frame in seconds as a fraction: exactly 1/rate for whole rates,
    // else to the nearest thousandth.
    let (num, den) = if rate.fract() == 0.0 && rate <= f64::from(u16::MAX) {
        (1, rate as u16)
    } else {
        (
            (1000.0 / rate).round().clamp(1.0, f64::from(u16::MAX)) as u16,
            1000,
        )
    };
    write_atomic(path, |file| {
        let mut enc = png::Encoder::new(BufWriter::new(file), width, height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let n = u32::try_from(frames.len()).map_err(std::io::Error::other)?;
        enc.set_animated(n, 0).map_err(std::io::Error::other)?;
        enc.set_frame_delay(num, den)
            .map_err(std::io::Error::other)?;
        let mut w = enc.write_header().map_err(std::io::Error::other)?;
        for f in frames {
            w.write_image_data(f).map_err(std::io::Error::other)?;
        }
        w.finish().map_err(std::io::Error::other)
    })
}

/// An [`Error::Io`] for invalid input to a writer of `path`.
fn invalid_input(path: &Path, message: String) -> Error {
    Error::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidInput, message),
    }
}

fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// Writes a file through `write` into a temporary sibling, then renames it over `path`:
/// the file appears whole or not at all. The temporary file is removed on failure.
pub fn write_atomic(
    path: &Path,
    write: impl FnOnce(&mut fs::File) -> std::io::Result<()>,
) -> Result<(), Error> {
    let tmp = temp_path(path);
    let io = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let result = (|| {
        let mut f = fs::File::create(&tmp)?;
        write(&mut f)?;
        f.sync_all()?;
        fs::rename(&tmp, path)
    })();
    if let Err(e) = result {
        let _ = fs::remove_file(&tmp);
        return Err(io(e));
    }
    Ok(())
}

/// Checks before a long render that `path` can be written: it is not a folder, its folder
/// exists and a file can be created there (the probe is removed again).
pub fn check_writable(path: &Path) -> Result<(), Error> {
    let io = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    if path.is_dir() {
        return Err(io(std::io::Error::other("is a folder, not a file")));
    }
    let probe = temp_path(path);
    fs::File::create(&probe)
        .and_then(|_| fs::remove_file(&probe))
        .map_err(io)
}
