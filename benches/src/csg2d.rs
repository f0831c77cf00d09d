//! A deterministic generator of large, `min`/`max`-heavy 2D CSG expressions in the `.vm`
//! format: the workload of the tape-pruning and rendering benchmarks.
//!
//! The picture is a page of "text": rows of glyphs in `[-1, 1]²`, each glyph the union
//! (`min`) of a few strokes (bars, rounded rectangles, discs, rings and capsules) in a cell,
//! some with a hole cut out (`max(a, -b)`), the rows joined by `min` and the page clipped to a
//! rounded frame (`max`). Every number comes from a seeded SplitMix64 generator and is
//! written with four decimals, so the text is the same on every machine and every version;
//! `data/models/csg2d.vm` is [`generate`]`(`[`SEED`]`)`, checked by a test.
//!
//! The text is written by a [`VmWriter`] (see [`crate::vmgen`] for the format) with the
//! opcodes `var-x`, `var-y`, `const`, `add`, `sub`, `mul`, `neg`, `square`, `sqrt`, `abs`,
//! `min` and `max`.

use crate::vmgen::{SplitMix64, Val, VmWriter};

/// The seed of `data/models/csg2d.vm`.
pub const SEED: u64 = 0x00c5_9d2d;

/// Rows of glyphs on the page.
const ROWS: usize = 11;
/// Glyphs per row.
const COLS: usize = 16;

/// The 2D primitives of the page, signed distances in the `x`-`y` plane.
impl VmWriter {
    /// The box `[x0, x1] × [y0, y1]`: `max(x0 - x, x - x1, y0 - y, y - y1)`.
    fn rect(&mut self, x0: f64, x1: f64, y0: f64, y1: f64) -> Val {
        let (cx0, cx1, cy0, cy1) = (self.c(x0), self.c(x1), self.c(y0), self.c(y1));
        let (x, y) = (self.x(), self.y());
        let a = self.sub(cx0, x);
        let b = self.sub(x, cx1);
        let c = self.sub(cy0, y);
        let d = self.sub(y, cy1);
        let ab = self.max(a, b);
        let cd = self.max(c, d);
        self.max(ab, cd)
    }

    /// The disc of centre `(cx, cy)` and radius `r` (a signed distance).
    fn disc(&mut self, cx: f64, cy: f64, r: f64) -> Val {
        let (x, y) = (self.x(), self.y());
        let dx = self.offset(x, cx);
        let dy = self.offset(y, cy);
        let len = self.length(&[dx, dy]);
        let r = self.c(r);
        self.sub(len, r)
    }

    /// The ring of centre `(cx, cy)`, radius `r` and half-thickness `t`.
    fn ring(&mut self, cx: f64, cy: f64, r: f64, t: f64) -> Val {
        let d = self.disc(cx, cy, r);
        let a = self.abs(d);
        let t = self.c(t);
        self.sub(a, t)
    }

    /// The rounded rectangle of centre `(cx, cy)`, half-sizes `hx`, `hy` and corner radius
    /// `r` (the exact signed distance of a box, minus `r`).
    fn rounded_rect(&mut self, cx: f64, cy: f64, hx: f64, hy: f64, r: f64) -> Val {
        let (x, y) = (self.x(), self.y());
        let dx = self.offset(x, cx);
        let dy = self.offset(y, cy);
        let ax = self.abs(dx);
        let ay = self.abs(dy);
        let qx = self.offset(ax, hx);
        let qy = self.offset(ay, hy);
        let zero = self.c(0.0);
        let ox = self.max(qx, zero);
        let oy = self.max(qy, zero);
        let outside = self.length(&[ox, oy]);
        let m = self.max(qx, qy);
        let inside = self.min(m, zero);
        let d = self.add(outside, inside);
        let r = self.c(r);
        self.sub(d, r)
    }

    /// The capsule around the segment `a b` with radius `r`.
    fn capsule(&mut self, ax: f64, ay: f64, bx: f64, by: f64, r: f64) -> Val {
        let (x, y) = (self.x(), self.y());
        let (bax, bay) = (bx - ax, by - ay);
        let l2 = (bax * bax + bay * bay).max(1e-6);
        let px = self.offset(x, ax);
        let py = self.offset(y, ay);
        // h = clamp(dot(p - a, b - a) / |b - a|², 0, 1)
        let kx = self.c(bax / l2);
        let ky = self.c(bay / l2);
        let tx = self.mul(px, kx);
        let ty = self.mul(py, ky);
        let t = self.add(tx, ty);
        let one = self.c(1.0);
        let zero = self.c(0.0);
        let t1 = self.min(t, one);
        let h = self.max(t1, zero);
        let cbx = self.c(bax);
        let cby = self.c(bay);
        let hx = self.mul(h, cbx);
        let hy = self.mul(h, cby);
        let qx = self.sub(px, hx);
        let qy = self.sub(py, hy);
        let len = self.length(&[qx, qy]);
        let r = self.c(r);
        self.sub(len, r)
    }
}

/// One stroke of a glyph in the unit cell `[0, 1]²`, mapped to the cell `(x0, y0)` of size
/// `(w, h)`.
fn stroke(w: &mut VmWriter, rng: &mut SplitMix64, x0: f64, y0: f64, cw: f64, ch: f64) -> Val {
    let px = |u: f64| x0 + u * cw;
    let py = |v: f64| y0 + v * ch;
    let thick = rng.range(0.07, 0.13);
    match rng.below(6) {
        0 => {
            // vertical bar
            let u = rng.range(0.15, 0.85);
            let (v0, v1) = (rng.range(0.0, 0.3), rng.range(0.7, 1.0));
            w.rect(px(u - thick), px(u + thick), py(v0), py(v1))
        }
        1 => {
            // horizontal bar
            let v = rng.range(0.1, 0.9);
            let (u0, u1) = (rng.range(0.0, 0.3), rng.range(0.6, 1.0));
            w.rect(px(u0), px(u1), py(v - thick), py(v + thick))
        }
        2 => {
            // bowl
            let (u, v) = (rng.range(0.35, 0.65), rng.range(0.3, 0.7));
            let r = rng.range(0.22, 0.32);
            w.ring(px(u), py(v), r * cw, thick * cw)
        }
        3 => {
            // dot
            let (u, v) = (rng.range(0.2, 0.8), rng.range(0.1, 0.9));
            w.disc(px(u), py(v), rng.range(0.1, 0.18) * cw)
        }
        4 => {
            // rounded block
            let (u, v) = (rng.range(0.3, 0.7), rng.range(0.3, 0.7));
            let (hu, hv) = (rng.range(0.1, 0.25), rng.range(0.1, 0.3));
            w.rounded_rect(px(u), py(v), hu * cw, hv * ch, rng.range(0.02, 0.08) * cw)
        }
        _ => {
            // diagonal
            let (u0, v0) = (rng.range(0.1, 0.4), rng.range(0.0, 0.3));
            let (u1, v1) = (rng.range(0.6, 0.9), rng.range(0.7, 1.0));
            let (u0, u1) = if rng.below(2) == 0 {
                (u0, u1)
            } else {
                (u1, u0)
            };
            w.capsule(px(u0), py(v0), px(u1), py(v1), thick * cw)
        }
    }
}

/// The `.vm` text of the page generated from `seed` (the committed file uses [`SEED`]):
/// about 7,000 operations besides the constants.
pub fn generate(seed: u64) -> String {
    let mut rng = SplitMix64::new(seed);
    let mut w = VmWriter::new_2d(&[
        "csg2d: a page of glyphs built from 2D CSG primitives".into(),
        format!("generated by the benches package (csg2d::generate, seed {seed:#x})"),
    ]);
    let (left, right, bottom, top) = (-0.92, 0.92, -0.9, 0.9);
    let cw = (right - left) / COLS as f64;
    let ch = (top - bottom) / ROWS as f64;
    let mut page: Option<Val> = None;
    for row in 0..ROWS {
        let y0 = top - (row + 1) as f64 * ch;
        let mut line: Option<Val> = None;
        let mut col = 0;
        while col < COLS {
            // Words of 2 to 6 glyphs separated by one blank cell.
            let word = 2 + rng.below(5);
            for _ in 0..word.min(COLS - col) {
                let x0 = left + col as f64 * cw;
                let strokes = 2 + rng.below(4);
                let mut glyph = stroke(&mut w, &mut rng, x0, y0, cw * 0.9, ch * 0.85);
                for _ in 1..strokes {
                    let s = stroke(&mut w, &mut rng, x0, y0, cw * 0.9, ch * 0.85);
                    glyph = w.min(glyph, s);
                }
                if rng.below(4) == 0 {
                    // a counter cut out of the glyph
                    let (u, v) = (rng.range(0.35, 0.65), rng.range(0.35, 0.65));
                    let hole = w.disc(x0 + u * cw * 0.9, y0 + v * ch * 0.85, 0.12 * cw);
                    let neg = w.neg(hole);
                    glyph = w.max(glyph, neg);
                }
                line = Some(match line {
                    Some(l) => w.min(l, glyph),
                    None => glyph,
                });
                col += 1;
            }
            col += 1;
        }
        if let Some(l) = line {
            page = Some(match page {
                Some(p) => w.min(p, l),
                None => l,
            });
        }
    }
    let page = page.expect("the page has rows");
    // A frame around the text, and everything clipped to a rounded sheet.
    let frame_out = w.rounded_rect(0.0, 0.0, 0.97, 0.95, 0.03);
    let frame_in = w.rounded_rect(0.0, 0.0, 0.94, 0.92, 0.02);
    let neg_in = w.neg(frame_in);
    let frame = w.max(frame_out, neg_in);
    let all = w.min(page, frame);
    let sheet = w.rounded_rect(0.0, 0.0, 0.98, 0.96, 0.04);
    w.max(all, sheet);
    w.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vmgen::op_count;

    #[test]
    fn same_seed_same_text() {
        assert_eq!(generate(7), generate(7));
        assert_ne!(generate(7), generate(8));
    }

    #[test]
    fn committed_file_is_reproducible() {
        let committed = include_str!("../../data/models/csg2d.vm");
        assert!(
            committed == generate(SEED),
            "regenerate with `cargo run -p benches --bin gen_models`"
        );
    }

    #[test]
    fn several_thousand_operations() {
        let n = op_count(&generate(SEED));
        assert!((5_000..10_000).contains(&n), "{n} operations");
    }
}
