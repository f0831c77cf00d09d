//! The work units: screen boxes (thesis 7.2.2), each carrying a share of the render's
//! credit so that the end of the render is detected without losing a box in transit.
//!
//! Termination by credit recovery (weight throwing): the whole render is worth
//! [`TOTAL_CREDIT`]; the initial parts share it, a bisected box gives each half half of its
//! credit (exactly, in integers), a donated box takes its credit along, and a rendered box
//! returns its credit to rank 0 with its pixels. Rank 0 has every pixel exactly when the
//! credit it got back is the total: no box can be in a list or in transit then, whatever
//! the order of the messages.

use beam_trace::screen::PixelRect;

use crate::error::Error;

/// The credit of the whole render.
pub const TOTAL_CREDIT: u64 = 1 << 62;

/// A screen box to render: its pixels, its credit and the rank whose initial part it
/// comes from (the thesis's Fig. 7.4).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct WorkBox {
    /// The box's pixels, on the window grid.
    pub rect: PixelRect,
    /// Its share of [`TOTAL_CREDIT`].
    pub credit: u64,
    /// The rank whose initial part it lies in.
    pub origin: u32,
}

impl WorkBox {
    /// Whether the box is larger than a final box of side `unit` (at least the grid's
    /// side, so that a box that splits has two cells across its longer side).
    pub fn splits(&self, unit: u32) -> bool {
        self.rect.x1 - self.rect.x0 > unit || self.rect.y1 - self.rect.y0 > unit
    }

    /// The number of final boxes of side `unit` the box holds (its load: a box larger than
    /// the final size counts for every final box it will be bisected into).
    pub fn units(&self, unit: u32) -> u64 {
        let r = self.rect;
        u64::from((r.x1 - r.x0).div_ceil(unit)) * u64::from((r.y1 - r.y0).div_ceil(unit))
    }

    /// The two halves of the box across its longer side, cut on the grid of side `grid`
    /// (the pipeline's window grid), each with half of its credit.
    ///
    /// # Errors
    ///
    /// [`Error::Setting`] when the credit is too small to halve (never for boxes of less
    /// than 2^60 pixels).
    pub fn bisect(&self, grid: u32) -> Result<[WorkBox; 2], Error> {
        if self.credit < 2 {
            return Err(Error::Setting {
                name: "credit",
                message: format!("box {:?} has credit {} to halve", self.rect, self.credit),
            });
        }
        let r = self.rect;
        let (w, h) = (r.x1 - r.x0, r.y1 - r.y0);
        let half = |lo: u32, len: u32| lo + len.div_ceil(grid) / 2 * grid;
        let (a, b) = if w >= h {
            let m = half(r.x0, w);
            (PixelRect { x1: m, ..r }, PixelRect { x0: m, ..r })
        } else {
            let m = half(r.y0, h);
            (PixelRect { y1: m, ..r }, PixelRect { y0: m, ..r })
        };
        let ca = self.credit / 2;
        Ok([
            WorkBox {
                rect: a,
                credit: ca,
                origin: self.origin,
            },
            WorkBox {
                rect: b,
                credit: self.credit - ca,
                origin: self.origin,
            },
        ])
    }
}

/// The screen of a `width × height` image cut into `parts` nearly equal rectangles on the
/// grid of side `grid`, in reading order (for four: the quadrants, upper left first). Fewer
/// when the image has fewer cells of the grid than parts.
pub fn equal_parts(width: u32, height: u32, parts: usize, grid: u32) -> Vec<PixelRect> {
    let mut out = Vec::new();
    cut(
        PixelRect {
            x0: 0,
            y0: 0,
            x1: width,
            y1: height,
        },
        parts.max(1),
        grid.max(1),
        &mut out,
    );
    out.sort_by_key(|r| (r.y0, r.x0));
    out
}

/// Cuts `r` into `parts` rectangles of areas as nearly proportional as the grid allows.
fn cut(r: PixelRect, parts: usize, grid: u32, out: &mut Vec<PixelRect>) {
    let (w, h) = (r.x1 - r.x0, r.y1 - r.y0);
    let cells = |len: u32| len.div_ceil(grid);
    if parts == 1 || (cells(w) < 2 && cells(h) < 2) {
        out.push(r);
        return;
    }
    let first = parts / 2;
    let at = |lo: u32, len: u32| {
        let k = (u64::from(cells(len)) * first as u64 + parts as u64 / 2) / parts as u64;
        lo + (k.clamp(1, u64::from(cells(len)) - 1) as u32) * grid
    };
    let (a, b) = if (w >= h && cells(w) >= 2) || cells(h) < 2 {
        let m = at(r.x0, w);
        (PixelRect { x1: m, ..r }, PixelRect { x0: m, ..r })
    } else {
        let m = at(r.y0, h);
        (PixelRect { y1: m, ..r }, PixelRect { y0: m, ..r })
    };
    cut(a, first, grid, out);
    cut(b, parts - first, grid, out);
}

/// The initial boxes of each of `ranks` ranks: `parts[k]` to rank `k`, the credit shared
/// so that it sums to [`TOTAL_CREDIT`] exactly.
pub fn initial_boxes(parts: &[PixelRect], ranks: usize) -> Vec<Vec<WorkBox>> {
    let mut lists = vec![Vec::new(); ranks];
    let n = parts.len() as u64;
    for (k, &rect) in parts.iter().enumerate() {
        let credit = TOTAL_CREDIT / n + u64::from((k as u64) < TOTAL_CREDIT % n);
        lists[k % ranks].push(WorkBox {
            rect,
            credit,
            origin: (k % ranks) as u32,
        });
    }
    lists
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(r: &PixelRect) -> u64 {
        r.area()
    }

    #[test]
    fn four_equal_parts_are_the_quadrants() {
        let p = equal_parts(512, 512, 4, 64);
        let q = |x0, y0| PixelRect {
            x0,
            y0,
            x1: x0 + 256,
            y1: y0 + 256,
        };
        assert_eq!(p, vec![q(0, 0), q(256, 0), q(0, 256), q(256, 256)]);
    }

    #[test]
    fn parts_tile_the_screen() {
        for (w, h) in [(512, 512), (300, 200), (64, 64), (130, 70), (1024, 100)] {
            for n in 1..=9 {
                let p = equal_parts(w, h, n, 32);
                assert!(p.len() <= n);
                assert_eq!(p.iter().map(area).sum::<u64>(), u64::from(w) * u64::from(h));
                for (i, a) in p.iter().enumerate() {
                    for b in &p[i + 1..] {
                        let overlap = a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
                        assert!(!overlap, "{a:?} {b:?}");
                    }
                }
                let boxes = initial_boxes(&p, n);
                let credit: u64 = boxes.iter().flatten().map(|b| b.credit).sum();
                assert_eq!(credit, TOTAL_CREDIT);
            }
        }
    }

    #[test]
    fn bisection_keeps_pixels_and_credit() {
        let mut list = vec![WorkBox {
            rect: PixelRect {
                x0: 0,
                y0: 0,
                x1: 1000,
                y1: 700,
            },
            credit: TOTAL_CREDIT,
            origin: 0,
        }];
        let mut finals = Vec::new();
        while let Some(b) = list.pop() {
            if b.splits(64) {
                list.extend(b.bisect(32).unwrap());
            } else {
                finals.push(b);
            }
        }
        assert_eq!(finals.iter().map(|b| area(&b.rect)).sum::<u64>(), 700_000);
        assert_eq!(finals.iter().map(|b| b.credit).sum::<u64>(), TOTAL_CREDIT);
        assert!(finals.iter().all(|b| b.credit > 0));
        for b in &finals {
            for v in [b.rect.x0, b.rect.y0] {
                assert_eq!(v % 32, 0);
            }
        }
    }
}
