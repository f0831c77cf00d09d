//! A deterministic generator of a 2D text expression shaped like the public `prospero.vm`
//! benchmark (lines of text set in a font, about 8,000 operations), with nearly its mix of
//! operations: `max` 2,094, `sub` 1,427, `const` 1,406, `add` 1,102, `min` 784, `neg` 383,
//! `square` 362, `sqrt` 270, `mul` 36, and no `abs`.
//!
//! The font is an alphabet of [`LETTERS`] glyph designs drawn from the seed, each the union
//! (`min`) of a few strokes in the glyph's own coordinates `(u, v) = (x - x₀, y - y₀)`:
//!
//! * stems: `max(u - a, b - u)` clipped to a band of the line (`max` again), the side
//!   `b - u` written `-u + b` from the glyph's `-u` (`neg` once per glyph);
//! * bars: the intersection of four half-planes;
//! * round stems: `sqrt((u - c)²) - w`, the absolute value written as the square root of a
//!   square (the file has no `abs`);
//! * bowls and arcs: rings `sqrt((sqrt(du² + dv²) - r)²) - t`, arcs cut by a half-plane;
//! * dots: discs `sqrt(du² + dv²) - r`;
//! * diagonals: `max(s - a, -s + b)` with `s = u - k·v` (the only products);
//!
//! and some glyphs have a counter cut out (`max(g, -hole)`). A page of lines of words set in
//! that font fills `[-1, 1]²`; the lines are joined by `min`. Constants are multiples of a
//! font unit in glyph coordinates, so repeated letters share them, as in a real text. Every
//! number comes from a seeded [`SplitMix64`]; `data/models/text2d.vm` is
//! [`generate`]`(`[`SEED`]`)`.

use crate::vmgen::{SplitMix64, Val, VmWriter};

/// The seed of `data/models/text2d.vm`.
pub const SEED: u64 = 0x7e47_2d12;

/// Glyph designs of the font.
pub const LETTERS: usize = 26;

/// Lines of text on the page.
const LINES: usize = 10;

/// The operation mix of `prospero.vm` (opcode, lines), which [`generate`] approaches.
pub const PROSPERO_MIX: [(&str, usize); 9] = [
    ("max", 2094),
    ("sub", 1427),
    ("const", 1406),
    ("add", 1102),
    ("min", 784),
    ("neg", 383),
    ("square", 362),
    ("sqrt", 270),
    ("mul", 36),
];

/// A band of a line of text in `v`: where stems run.
#[derive(Copy, Clone, Debug)]
enum Band {
    /// From the baseline to the x-height.
    XHeight,
    /// From the baseline to the ascender.
    Ascender,
    /// From the descender to the x-height.
    Descender,
}

/// One stroke of a glyph design, in font units (multiples of [`UNIT`] of the em).
#[derive(Copy, Clone, Debug)]
enum Stroke {
    /// `a <= u <= b` within a band: `max(u - b, -u + a)`, or `max(u - b, -(u - a))` when
    /// `negated`.
    Stem {
        a: i32,
        b: i32,
        band: Band,
        negated: bool,
    },
    /// The box `[u0, u1] × [v0, v1]`.
    Bar { u0: i32, u1: i32, v0: i32, v1: i32 },
    /// `|u - c| <= w` within a band, the absolute value as `sqrt(square)`.
    Round { c: i32, w: i32, band: Band },
    /// The ring of centre `(cu, cv)`, radius `r`, half-thickness `t`, cut by a half-plane
    /// (`cut` 1 to 4: `u > cu`, `u < cu`, `v > cv`, `v < cv`) or whole (`cut` 0).
    Ring {
        cu: i32,
        cv: i32,
        r: i32,
        t: i32,
        cut: u8,
    },
    /// The disc of centre `(cu, cv)` and radius `r`.
    Dot { cu: i32, cv: i32, r: i32 },
    /// The slanted stroke `a <= u - k·v <= b` within a band, `k = num / 8`.
    Diagonal {
        a: i32,
        b: i32,
        num: i32,
        band: Band,
    },
}

/// A glyph design: its strokes and, maybe, a box cut out of it.
#[derive(Clone, Debug)]
struct Design {
    strokes: Vec<Stroke>,
    hole: Option<[i32; 4]>,
}

/// Font units per em: every constant of a glyph is a multiple of `1 / UNIT` em.
const UNIT: f64 = 128.0;
/// Heights in font units: x-height, ascender, descender.
const XH: i32 = 64;
const ASC: i32 = 96;
const DESC: i32 = -32;
/// Glyph advance in font units.
const ADVANCE: i32 = 80;

/// Probabilities of the kinds of strokes (dots: the rest) and of a hole in a glyph,
/// chosen for the operation mix of [`PROSPERO_MIX`].
const P_STEM: f64 = 0.13;
const P_BAR: f64 = 0.52;
const P_ROUND: f64 = 0.13;
const P_RING: f64 = 0.10;
const P_DIAGONAL: f64 = 0.09;
const P_HOLE: f64 = 0.75;
/// Probability that a stem is written with a negation.
const P_NEGATED: f64 = 0.05;
/// Probability that a glyph writes its offsets `t - k` as sums `t + (-k)`.
const P_SUMS: f64 = 0.4;
/// Probability that a glyph writes `k - t` as `-t + k` rather than as a difference.
const P_FLIPS: f64 = 0.5;

/// A random integer of `lo..=hi`.
fn int(rng: &mut SplitMix64, lo: i32, hi: i32) -> i32 {
    lo + rng.below((hi - lo + 1) as usize) as i32
}

/// The lines a glyph's strokes start from, in font units: vertical edges `u`, horizontal
/// edges `v`, and the stroke weight. Strokes meet at shared edges, as in a drawn font.
struct Edges {
    u: [i32; 6],
    v: [i32; 6],
    weight: i32,
}

impl Edges {
    fn random(rng: &mut SplitMix64) -> Self {
        let mut u = [0; 6].map(|_| int(rng, 0, 60));
        u.sort_unstable();
        let weight = int(rng, 8, 14);
        let v = [
            0,
            XH - weight,
            int(rng, 8, 48),
            int(rng, 8, 48),
            int(rng, 20, 56),
            int(rng, 20, 56),
        ];
        Edges { u, v, weight }
    }

    fn pick_u(&self, rng: &mut SplitMix64) -> i32 {
        self.u[rng.below(self.u.len())]
    }

    fn pick_v(&self, rng: &mut SplitMix64) -> i32 {
        self.v[rng.below(self.v.len())]
    }
}

/// A stroke of a random kind from the edges of a glyph design.
fn random_stroke(rng: &mut SplitMix64, e: &Edges) -> Stroke {
    let band = |rng: &mut SplitMix64| match rng.below(5) {
        0..=2 => Band::XHeight,
        3 => Band::Ascender,
        _ => Band::Descender,
    };
    let w = e.weight;
    let roll = rng.range(0.0, 1.0);
    if roll < P_STEM {
        let a = e.pick_u(rng);
        Stroke::Stem {
            a,
            b: a + w,
            band: band(rng),
            negated: rng.chance(P_NEGATED),
        }
    } else if roll < P_STEM + P_BAR {
        let (i, j) = (rng.below(e.u.len()), rng.below(e.u.len()));
        let v0 = e.pick_v(rng);
        Stroke::Bar {
            u0: e.u[i.min(j)],
            u1: e.u[i.max(j)] + w,
            v0,
            v1: v0 + w,
        }
    } else if roll < P_STEM + P_BAR + P_ROUND {
        Stroke::Round {
            c: e.pick_u(rng) + w / 2,
            w: w / 2,
            band: band(rng),
        }
    } else if roll < P_STEM + P_BAR + P_ROUND + P_RING {
        Stroke::Ring {
            cu: (e.u[0] + e.u[5] + w) / 2,
            cv: XH / 2 + int(rng, -4, 4),
            r: int(rng, 20, 30),
            t: w / 2,
            cut: if rng.chance(0.55) {
                1 + rng.below(4) as u8
            } else {
                0
            },
        }
    } else if roll < 1.0 - P_DIAGONAL {
        Stroke::Dot {
            cu: e.pick_u(rng) + w / 2,
            cv: if rng.chance(0.5) { XH + 20 } else { -4 } + int(rng, 0, 8),
            r: w / 2 + int(rng, 2, 4),
        }
    } else {
        let a = e.pick_u(rng);
        Stroke::Diagonal {
            a,
            b: a + w,
            num: [-6, -4, -3, 3, 4, 6][rng.below(6)],
            band: Band::XHeight,
        }
    }
}

/// The font: [`LETTERS`] designs of 3 to 6 strokes, some with a hole.
fn font(rng: &mut SplitMix64) -> Vec<Design> {
    (0..LETTERS)
        .map(|_| {
            let e = Edges::random(rng);
            let n = 3 + rng.below(4);
            let strokes = (0..n).map(|_| random_stroke(rng, &e)).collect();
            let hole = rng.chance(P_HOLE).then(|| {
                let u0 = e.u[rng.below(2)] + e.weight;
                let v0 = e.pick_v(rng) + e.weight;
                [u0, u0 + int(rng, 8, 20), v0, v0 + int(rng, 8, 20)]
            });
            Design { strokes, hole }
        })
        .collect()
}

/// What the strokes of one glyph refer to: its coordinates, their negations, the line's
/// bands, and the size of a font unit.
struct Frame {
    u: Val,
    nu: Val,
    v: Val,
    nv: Val,
    bands: [Val; 3],
    unit: f64,
    /// Whether `t - k` is written `t + (-k)`.
    sums: bool,
    /// Whether `k - t` is written `-t + k` (else as a difference).
    flips: bool,
}

impl Frame {
    fn band(&self, b: Band) -> Val {
        self.bands[b as usize]
    }

    /// `t - k` (`t` a glyph coordinate, `k` font units), or `t + (-k)` in a glyph whose
    /// offsets are written as sums.
    fn minus(&self, w: &mut VmWriter, t: Val, k: i32) -> Val {
        self.minus_value(w, t, f64::from(k) * self.unit)
    }

    /// `t - k`, or `t + (-k)` in a glyph whose offsets are written as sums.
    fn minus_value(&self, w: &mut VmWriter, t: Val, k: f64) -> Val {
        if self.sums {
            let c = w.c(-k);
            w.add(t, c)
        } else {
            w.offset(t, k)
        }
    }

    /// `k - t`, written `-t + k` from the negated coordinate `nt` in a glyph that flips.
    fn k_minus(&self, w: &mut VmWriter, t: Val, nt: Val, k: i32) -> Val {
        let c = w.c(f64::from(k) * self.unit);
        if self.flips {
            w.add(nt, c)
        } else {
            w.sub(c, t)
        }
    }

    /// `a <= u <= b` as `max(u - b, -u + a)`.
    fn u_slab(&self, w: &mut VmWriter, a: i32, b: i32) -> Val {
        let hi = self.minus(w, self.u, b);
        let lo = self.k_minus(w, self.u, self.nu, a);
        w.max(hi, lo)
    }

    /// `a <= v <= b` as `max(v - b, -v + a)`.
    fn v_slab(&self, w: &mut VmWriter, a: i32, b: i32) -> Val {
        let hi = self.minus(w, self.v, b);
        let lo = self.k_minus(w, self.v, self.nv, a);
        w.max(hi, lo)
    }

    /// `sqrt((u - cu)² + (v - cv)²)`, and `u - cu`, `v - cv`.
    fn radius(&self, w: &mut VmWriter, cu: i32, cv: i32) -> (Val, Val, Val) {
        let du = self.minus(w, self.u, cu);
        let dv = self.minus(w, self.v, cv);
        (w.length(&[du, dv]), du, dv)
    }

    fn stroke(&self, w: &mut VmWriter, s: Stroke) -> Val {
        match s {
            Stroke::Stem {
                a,
                b,
                band,
                negated,
            } => {
                let slab = if negated {
                    let hi = self.minus(w, self.u, b);
                    let lo = self.minus(w, self.u, a);
                    w.difference(hi, lo)
                } else {
                    self.u_slab(w, a, b)
                };
                w.max(slab, self.band(band))
            }
            Stroke::Bar { u0, u1, v0, v1 } => {
                let su = self.u_slab(w, u0, u1);
                let sv = self.v_slab(w, v0, v1);
                w.max(su, sv)
            }
            Stroke::Round { c, w: half, band } => {
                let d = self.minus(w, self.u, c);
                let sq = w.un("square", d);
                let abs = w.un("sqrt", sq);
                let slab = self.minus(w, abs, half);
                w.max(slab, self.band(band))
            }
            Stroke::Ring { cu, cv, r, t, cut } => {
                let (len, du, dv) = self.radius(w, cu, cv);
                let d = self.minus(w, len, r);
                let sq = w.un("square", d);
                let abs = w.un("sqrt", sq);
                let ring = self.minus(w, abs, t);
                match cut {
                    1 => w.max(ring, du),
                    2 => w.difference(ring, du),
                    3 => w.max(ring, dv),
                    4 => w.difference(ring, dv),
                    _ => ring,
                }
            }
            Stroke::Dot { cu, cv, r } => {
                let (len, _, _) = self.radius(w, cu, cv);
                self.minus(w, len, r)
            }
            Stroke::Diagonal { a, b, num, band } => {
                let k = w.c(f64::from(num) / 8.0);
                let kv = w.mul(self.v, k);
                let s = w.sub(self.u, kv);
                let ns = w.neg(s);
                let hi = self.minus(w, s, b);
                let lo = self.k_minus(w, s, ns, a);
                let slab = w.max(hi, lo);
                w.max(slab, self.band(band))
            }
        }
    }

    fn glyph(&self, w: &mut VmWriter, d: &Design) -> Val {
        let strokes: Vec<Val> = d.strokes.iter().map(|&s| self.stroke(w, s)).collect();
        // Strokes joined left to right, as a font compiler writes them.
        let mut g = w.reduce_left("min", &strokes).expect("a glyph has strokes");
        if let Some([u0, u1, v0, v1]) = d.hole {
            let su = self.u_slab(w, u0, u1);
            let sv = self.v_slab(w, v0, v1);
            let hole = w.max(su, sv);
            g = w.difference(g, hole);
        }
        g
    }
}

/// The `.vm` text of the page of text generated from `seed` (the committed file uses
/// [`SEED`]): about 8,000 lines, with the mix of [`PROSPERO_MIX`].
pub fn generate(seed: u64) -> String {
    let mut rng = SplitMix64::new(seed);
    let mut w = VmWriter::new_2d(&[
        "text2d: lines of text in a generated font, with the operation mix of prospero.vm".into(),
        format!("generated by the benches package (text2d::generate, seed {seed:#x})"),
    ])
    .share_operations()
    .with_decimals(6);
    let (left, right, top) = (-0.95, 0.95, 0.95);
    let line_height = 1.9 / LINES as f64;
    // The largest em: an ascender and a descender of the larger font fit in a line.
    let em = line_height / (f64::from(ASC - DESC) / UNIT) * 0.95 / 1.1;
    let (x, y) = (w.x(), w.y());
    let mut lines = Vec::new();
    for line in 0..LINES {
        // Each line in its own type size, with two fonts of its own (a regular and a bold
        // one size larger, say), as on a type specimen.
        let unit = em * rng.range(0.78, 1.0) / UNIT;
        let baseline = top - (line as f64 + 1.0) * line_height - f64::from(DESC) * unit;
        let v = w.offset(y, baseline);
        let nv = w.neg(v);
        let mut fonts = [1.0, rng.range(1.03, 1.1)].map(|size| {
            let mut f = Frame {
                u: x,
                nu: x,
                v,
                nv,
                bands: [v; 3],
                unit: unit * size,
                sums: false,
                flips: true,
            };
            f.bands = [(0, XH), (0, ASC), (DESC, XH)].map(|(a, b)| f.v_slab(&mut w, a, b));
            (f, font(&mut rng))
        });
        let mut glyphs = Vec::new();
        let mut x0 = left;
        'line: loop {
            // Words of 2 to 7 letters separated by a space, each in one of the fonts.
            let word = 2 + rng.below(6);
            let (frame, designs) = &mut fonts[rng.below(2)];
            let advance = f64::from(ADVANCE) * frame.unit;
            for _ in 0..word {
                if x0 + advance > right {
                    break 'line;
                }
                frame.sums = rng.chance(P_SUMS);
                frame.flips = rng.chance(P_FLIPS);
                frame.u = frame.minus_value(&mut w, x, x0);
                frame.nu = w.neg(frame.u);
                let letter = &designs[rng.below(LETTERS)];
                glyphs.push(frame.glyph(&mut w, letter));
                x0 += advance;
            }
            x0 += advance;
        }
        if let Some(l) = w.reduce_left("min", &glyphs) {
            lines.push(l);
        }
    }
    w.reduce("min", &lines);
    w.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vmgen::{op_histogram, sign_counts};

    #[test]
    fn operation_mix_close_to_prospero() {
        let h = op_histogram(&generate(SEED));
        for (op, n) in PROSPERO_MIX {
            let got = h.get(op).copied().unwrap_or(0);
            assert!(
                got * 4 >= n * 3 && got * 4 <= n * 5,
                "{op}: {got} lines, prospero.vm has {n}"
            );
        }
        assert_eq!(h.get("abs"), None);
        let lines: usize = h.values().sum();
        assert!((7_000..9_000).contains(&lines), "{lines} lines");
    }

    #[test]
    fn same_seed_same_text() {
        assert_eq!(generate(5), generate(5));
        assert_ne!(generate(5), generate(6));
    }

    #[test]
    fn text_crosses_zero() {
        let (inside, outside) = sign_counts(&generate(SEED), 200, false).unwrap();
        // Ink covers a part of the page, not all of it.
        assert!(
            inside > 2_000 && outside > 10_000,
            "{inside} in, {outside} out"
        );
    }
}
