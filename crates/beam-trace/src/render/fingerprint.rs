//! A render's fingerprint: one hash of everything a render must reproduce bit for bit
//! whatever the thread count, the backend's batches or the windows it was cut into (the
//! images, the per-pixel classes, bounds and maps, the plan and the work counters), and of
//! nothing that may vary (times, the cost map).

use super::output::RenderOutput;
use crate::beam::BoxClass;
use crate::image::Image;

/// 64-bit FNV-1a over bytes.
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }

    fn bytes(&mut self, b: &[u8]) {
        for &x in b {
            self.0 ^= u64::from(x);
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }

    fn u64(&mut self, v: u64) {
        self.bytes(&v.to_le_bytes());
    }

    fn f32s(&mut self, v: impl IntoIterator<Item = f32>) {
        for x in v {
            self.bytes(&x.to_bits().to_le_bytes());
        }
    }

    fn image(&mut self, img: &Image) {
        self.u64(u64::from(img.width));
        self.u64(u64::from(img.height));
        self.f32s(img.pixels.iter().flatten().copied());
    }
}

impl RenderOutput {
    /// The hash of what the render must reproduce bit for bit: the image, the
    /// classification image, each pixel's box class, coverage and soft-shadow maps, the
    /// plan and every pass's counters; not the times nor the cost map.
    pub fn fingerprint(&self) -> u64 {
        let mut h = Fnv::new();
        h.image(&self.image);
        h.image(&self.classification());
        for c in &self.box_classes() {
            match c {
                None => h.u64(0),
                Some(BoxClass::Miss) => h.u64(1),
                Some(BoxClass::Hit { t_final: t }) | Some(BoxClass::Undecided { t }) => {
                    h.u64(if matches!(c, Some(BoxClass::Hit { .. })) {
                        2
                    } else {
                        3
                    });
                    h.u64(t.inf().to_bits());
                    h.u64(t.sup().to_bits());
                }
            }
        }
        h.f32s(self.coverage.iter().flat_map(|c| [c.proven, c.possible]));
        if let Some(s) = &self.shadows {
            h.bytes(format!("{:?}", s.classes).as_bytes());
            h.image(&s.image);
            for maps in [&s.fractions, &s.lower, &s.upper] {
                for m in maps {
                    h.f32s(m.iter().copied());
                }
            }
        }
        h.bytes(format!("{:?}", self.plan).as_bytes());
        for (pass, ran, counters) in self.stats.work() {
            h.bytes(pass.as_bytes());
            h.u64(u64::from(ran));
            for (n, v) in counters {
                h.bytes(n.as_bytes());
                h.u64(v);
            }
        }
        h.0
    }
}
