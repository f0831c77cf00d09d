//! A deterministic generator of 3D CSG models in the `.vm` format, of the kind fidget's
//! examples render: hundreds to thousands of operations, solids combined by `min` (union),
//! `max` (intersection) and `max(a, -b)` (difference), inside `[-1, 1]³` (`y` up).
//!
//! Two flavours ([`Flavour`]):
//!
//! * [`Flavour::City`], `min`/`max`-heavy: buildings on a ground slab, one per cell of a
//!   square grid taken in a random order. A building is a box (`max` of three `abs` slabs),
//!   sometimes with setbacks (a union of boxes), a pitched roof (the box cut by
//!   `y + k|x - c|`), a passage cut through it (a difference), an octagonal section (cut by
//!   `|x - a| + |z - b|`), or a cylindrical tower with a domed top.
//! * [`Flavour::Molecule`], `sqrt`/`square`-heavy: atoms (spheres `sqrt(dx² + dy² + dz²) -
//!   r`) grown as a random tree on a cubic lattice inside a ball, each joined to its parent
//!   by a bond (a capsule along an axis), some with a ring around them (a torus) or a cavity
//!   (a difference of spheres).
//!
//! The model grows object by object until the next one would take the operation count over
//! the target; the objects are then joined by a balanced tree of `min`. Every number comes
//! from a seeded [`SplitMix64`], so [`generate`] returns the same text on every machine.
//! `data/models/csg3d-660.vm` and `data/models/csg3d-2k.vm` are two of them (see
//! [`crate::models`]).

use std::fmt;
use std::str::FromStr;

use crate::vmgen::{SplitMix64, Val, VmWriter};

/// The kind of 3D model.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Flavour {
    /// Buildings on a ground slab: boxes and CSG, mostly `min`, `max` and `abs`.
    City,
    /// Atoms, bonds and rings: spheres, capsules and tori, mostly `square` and `sqrt`.
    Molecule,
}

impl Flavour {
    /// Every flavour.
    pub const ALL: [Flavour; 2] = [Flavour::City, Flavour::Molecule];

    /// The flavour's name (`city`, `molecule`).
    pub fn name(self) -> &'static str {
        match self {
            Flavour::City => "city",
            Flavour::Molecule => "molecule",
        }
    }
}

impl fmt::Display for Flavour {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Flavour {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Flavour::ALL
            .into_iter()
            .find(|f| f.name() == s)
            .ok_or_else(|| format!("unknown csg3d flavour '{s}' (city or molecule)"))
    }
}

/// Smallest operation target [`generate`] honours; smaller targets give the smallest model
/// (the ground slab and one building, or one atom).
pub const MIN_TARGET: usize = 100;

/// Largest operation target [`generate`] accepts (larger ones are treated as this one).
pub const MAX_TARGET: usize = 100_000;

/// 3D primitives, signed distances (exact or bounds of them) in `x`, `y`, `z` (inherent
/// methods: one namespace with the 2D primitives of `csg2d`).
impl VmWriter {
    /// `|v - c| - h`: the slab of half-width `h` around `c` along one axis.
    fn slab(&mut self, v: Val, c: f64, h: f64) -> Val {
        let d = self.offset(v, c);
        let a = self.abs(d);
        self.offset(a, h)
    }

    /// The box of centre `c` and half-sizes `h`: `max(|x - cx| - hx, |y - cy| - hy,
    /// |z - cz| - hz)`.
    fn cuboid(&mut self, c: [f64; 3], h: [f64; 3]) -> Val {
        let p = self.xyz();
        let sx = self.slab(p[0], c[0], h[0]);
        let sy = self.slab(p[1], c[1], h[1]);
        let sz = self.slab(p[2], c[2], h[2]);
        let m = self.max(sx, sy);
        self.max(m, sz)
    }

    /// The sphere of centre `c` and radius `r`.
    fn sphere(&mut self, c: [f64; 3], r: f64) -> Val {
        let p = self.xyz();
        let d: Vec<Val> = (0..3).map(|i| self.offset(p[i], c[i])).collect();
        let len = self.length(&d);
        self.offset(len, r)
    }

    /// The rod (a capsule) of radius `r` around the segment of centre `c` and half-length
    /// `h` along `axis` (0: `x`, 1: `y`, 2: `z`): `sqrt(di² + dj² + max(|da| - h, 0)²) - r`.
    fn rod(&mut self, axis: usize, c: [f64; 3], h: f64, r: f64) -> Val {
        let p = self.xyz();
        let [i, j] = Self::across(axis);
        let di = self.offset(p[i], c[i]);
        let dj = self.offset(p[j], c[j]);
        let along = self.slab(p[axis], c[axis], h);
        let zero = self.c(0.0);
        let beyond = self.max(along, zero);
        let len = self.length(&[di, dj, beyond]);
        self.offset(len, r)
    }

    /// The two axes other than `axis` (0: `x`, 1: `y`, 2: `z`).
    fn across(axis: usize) -> [usize; 2] {
        [(axis + 1) % 3, (axis + 2) % 3]
    }

    /// The cylinder of radius `r` and half-length `h` along `axis` (0: `x`, 1: `y`, 2:
    /// `z`) around the centre `c`.
    fn cylinder(&mut self, axis: usize, c: [f64; 3], r: f64, h: f64) -> Val {
        let p = self.xyz();
        let [i, j] = Self::across(axis);
        let di = self.offset(p[i], c[i]);
        let dj = self.offset(p[j], c[j]);
        let len = self.length(&[di, dj]);
        let side = self.offset(len, r);
        let caps = self.slab(p[axis], c[axis], h);
        self.max(side, caps)
    }

    /// The torus of centre `c` around `axis` (0: `x`, 1: `y`, 2: `z`), major radius `big`
    /// and tube radius `r`.
    fn torus(&mut self, axis: usize, c: [f64; 3], big: f64, r: f64) -> Val {
        let p = self.xyz();
        let [i, j] = Self::across(axis);
        let di = self.offset(p[i], c[i]);
        let dj = self.offset(p[j], c[j]);
        let da = self.offset(p[axis], c[axis]);
        let ring = self.length(&[di, dj]);
        let q = self.offset(ring, big);
        let len = self.length(&[q, da]);
        self.offset(len, r)
    }
}

/// The `.vm` text of a model of `flavour` with about `target_ops` operations (at most that
/// many, and within the cost of one object of it; see [`MIN_TARGET`], [`MAX_TARGET`]),
/// generated from `seed`.
pub fn generate(flavour: Flavour, target_ops: usize, seed: u64) -> String {
    let target = target_ops.min(MAX_TARGET);
    let what = match flavour {
        Flavour::City => "buildings on a ground slab: boxes and CSG (min/max-heavy)",
        Flavour::Molecule => "atoms, bonds and rings: spheres, capsules, tori (sqrt-heavy)",
    };
    let mut w = VmWriter::new_3d(&[
        format!("csg3d {flavour}: {what}"),
        format!(
            "generated by the benches package (csg3d::generate({flavour}, {target_ops}, seed {seed:#x}))"
        ),
    ]);
    let mut rng = SplitMix64::new(seed);
    let objects = match flavour {
        Flavour::City => city(&mut w, &mut rng, target),
        Flavour::Molecule => molecule(&mut w, &mut rng, target),
    };
    w.reduce("min", &objects);
    w.finish()
}

/// What grows a model object by object.
trait Grower {
    /// Writes the next object; `None` when there is nothing more to add.
    fn write_next(&mut self, w: &mut VmWriter) -> Option<Val>;

    /// The object just written stays in the model.
    fn keep(&mut self) {}
}

/// Consecutive objects [`fill`] tries, and takes back, before it stops.
const MISSES: usize = 16;

/// Adds the objects of `grower` to `objects` while the model stays within `target`
/// operations (counting the `min` that will join each object): an object that would take it
/// over is taken back, and the model is done after [`MISSES`] of them in a row. The model
/// keeps at least `min_objects` objects whatever the target.
fn fill(
    w: &mut VmWriter,
    target: usize,
    min_objects: usize,
    mut objects: Vec<Val>,
    grower: &mut impl Grower,
) -> Vec<Val> {
    let mut misses = 0;
    while misses < MISSES {
        let mark = w.mark();
        let Some(v) = grower.write_next(w) else {
            break;
        };
        // n objects are joined by n - 1 `min`.
        if w.ops() + objects.len() > target && objects.len() >= min_objects {
            w.rewind(mark);
            misses += 1;
        } else {
            grower.keep();
            objects.push(v);
            misses = 0;
        }
    }
    objects
}

/// Top of the ground slab of the city.
const GROUND: f64 = -0.82;
/// Highest roof of the city.
const SKY: f64 = 0.86;

/// The city: the ground slab and buildings.
fn city(w: &mut VmWriter, rng: &mut SplitMix64, target: usize) -> Vec<Val> {
    /// Buildings on the cells of an `n × n` grid of side `cell`, in the random `order`.
    struct City<'a> {
        rng: &'a mut SplitMix64,
        order: std::vec::IntoIter<usize>,
        n: usize,
        cell: f64,
    }
    impl Grower for City<'_> {
        fn write_next(&mut self, w: &mut VmWriter) -> Option<Val> {
            let k = self.order.next()?;
            let (i, j) = (k % self.n, k / self.n);
            let cx = -0.9 + (i as f64 + 0.5) * self.cell;
            let cz = -0.9 + (j as f64 + 0.5) * self.cell;
            Some(building(w, self.rng, cx, cz, self.cell))
        }
    }
    // About 24 operations per building: more cells than the target needs.
    let n = ((target as f64 / 16.0).sqrt().ceil() as usize).clamp(2, 200);
    let ground = w.cuboid([0.0, GROUND - 0.04, 0.0], [0.92, 0.04, 0.92]);
    let order = rng.permutation(n * n).into_iter();
    let mut city = City {
        rng,
        order,
        n,
        cell: 1.8 / n as f64,
    };
    fill(w, target, 2, vec![ground], &mut city)
}

/// One building on the cell of centre `(cx, cz)` and side `cell`.
fn building(w: &mut VmWriter, rng: &mut SplitMix64, cx: f64, cz: f64, cell: f64) -> Val {
    let hx = cell * rng.range(0.22, 0.42);
    let hz = cell * rng.range(0.22, 0.42);
    let cx = cx + rng.range(-1.0, 1.0) * (0.46 * cell - hx);
    let cz = cz + rng.range(-1.0, 1.0) * (0.46 * cell - hz);
    // Taller towards the middle of the city.
    let centrality = 1.0 - (cx * cx + cz * cz).sqrt() / 1.3;
    let height = (rng.range(0.08, 0.5) + centrality * rng.range(0.0, 1.1)).min(SKY - GROUND);
    let top = GROUND + height;
    let mid = 0.5 * (GROUND + top);
    let body = |w: &mut VmWriter| w.cuboid([cx, mid, cz], [hx, 0.5 * height, hz]);
    let roll = rng.range(0.0, 1.0);
    if roll < 0.3 {
        body(w)
    } else if roll < 0.5 {
        // Setbacks: two or three tiers, each narrower and taller than the one below.
        let tiers = 2 + rng.below(2);
        let mut parts = Vec::new();
        for t in 0..tiers {
            let s = 1.0 - 0.25 * t as f64;
            let up = GROUND + height * (0.45 + 0.55 * (t + 1) as f64 / tiers as f64);
            let c = [cx, 0.5 * (GROUND + up), cz];
            parts.push(w.cuboid(c, [hx * s, 0.5 * (up - GROUND), hz * s]));
        }
        w.reduce("min", &parts).expect("tiers")
    } else if roll < 0.65 {
        // A pitched roof: the box cut by y + k|x - cx| <= top.
        let b = body(w);
        let k = rng.range(0.5, 1.5);
        let (x, y) = (w.x(), w.y());
        let dx = w.offset(x, cx);
        let ax = w.abs(dx);
        let kc = w.c(k);
        let slope = w.mul(ax, kc);
        let dy = w.offset(y, top);
        let roof = w.add(dy, slope);
        w.max(b, roof)
    } else if roll < 0.8 {
        // A passage through the building along z.
        let b = body(w);
        let ph = height.min(0.3) * rng.range(0.3, 0.6);
        let hole = w.cuboid(
            [cx, GROUND + 0.5 * ph, cz],
            [hx * rng.range(0.3, 0.6), 0.5 * ph, hz + 0.02],
        );
        w.difference(b, hole)
    } else if roll < 0.9 {
        // An octagonal section: the box cut by |x - cx| + |z - cz| <= c.
        let b = body(w);
        let (x, z) = (w.x(), w.z());
        let dx = w.offset(x, cx);
        let dz = w.offset(z, cz);
        let ax = w.abs(dx);
        let az = w.abs(dz);
        let s = w.add(ax, az);
        let cut = w.offset(s, 1.4 * hx.min(hz));
        w.max(b, cut)
    } else {
        // A round tower with a dome.
        let r = hx.min(hz);
        let tower_top = (top - r).max(GROUND + 0.05);
        let tower = w.cylinder(
            1,
            [cx, 0.5 * (GROUND + tower_top), cz],
            r,
            0.5 * (tower_top - GROUND),
        );
        let dome = w.sphere([cx, tower_top, cz], r);
        w.min(tower, dome)
    }
}

/// Radius of the ball the molecule grows in.
const BALL: f64 = 0.8;

/// The six directions of the lattice of the molecule.
const DIRECTIONS: [[i32; 3]; 6] = [
    [1, 0, 0],
    [-1, 0, 0],
    [0, 1, 0],
    [0, -1, 0],
    [0, 0, 1],
    [0, 0, -1],
];

/// The molecule: atoms grown as a random tree on a cubic lattice (bonds along the axes),
/// with rings and cavities.
fn molecule(w: &mut VmWriter, rng: &mut SplitMix64, target: usize) -> Vec<Val> {
    /// Atoms on the lattice `sites` of spacing `bond`, of radius about `r0`; `written` is the
    /// site of the atom just written.
    struct Molecule<'a> {
        rng: &'a mut SplitMix64,
        sites: Vec<[i32; 3]>,
        written: Option<[i32; 3]>,
        r0: f64,
        bond: f64,
    }
    impl Grower for Molecule<'_> {
        fn write_next(&mut self, w: &mut VmWriter) -> Option<Val> {
            let (r0, bond) = (self.r0, self.bond);
            let (site, parent) = if self.sites.is_empty() {
                ([0; 3], None)
            } else {
                let (site, parent, axis) = grow(self.rng, &self.sites, bond)?;
                (site, Some((parent, axis)))
            };
            let pos = site.map(|k| f64::from(k) * bond);
            let rng = &mut *self.rng;
            let r = r0 * rng.range(0.75, 1.2);
            let mut obj = if rng.chance(0.1) {
                // A cavity: a smaller sphere cut out off-centre.
                let s = w.sphere(pos, r);
                let d = unit(rng);
                let c = [0, 1, 2].map(|i| pos[i] + d[i] * 0.8 * r);
                let hole = w.sphere(c, 0.55 * r);
                w.difference(s, hole)
            } else {
                w.sphere(pos, r)
            };
            if let Some((parent, axis)) = parent {
                let p = parent.map(|k| f64::from(k) * bond);
                let mid = [0, 1, 2].map(|i| 0.5 * (p[i] + pos[i]));
                let b = w.rod(axis, mid, 0.5 * bond, 0.3 * r0);
                obj = w.min(obj, b);
            }
            if rng.chance(0.12) {
                let ring = w.torus(rng.below(3), pos, 1.6 * r, 0.2 * r0);
                obj = w.min(obj, ring);
            }
            self.written = Some(site);
            Some(obj)
        }

        fn keep(&mut self) {
            if let Some(s) = self.written.take() {
                self.sites.push(s);
            }
        }
    }
    // About 30 operations per atom; atoms fill about 12 % of the ball.
    let atoms_expected = (target as f64 / 30.0).max(1.0);
    let r0 = BALL * (0.12 / atoms_expected).cbrt();
    let mut molecule = Molecule {
        rng,
        sites: Vec::new(),
        written: None,
        r0,
        bond: 2.5 * r0,
    };
    fill(w, target, 1, Vec::new(), &mut molecule)
}

/// A random unit vector.
fn unit(rng: &mut SplitMix64) -> [f64; 3] {
    loop {
        let v = [0; 3].map(|_| rng.range(-1.0, 1.0));
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if n > 0.1 && n <= 1.0 {
            return v.map(|c| c / n);
        }
    }
}

/// A free lattice site next to one of the newest atoms (mostly: chains with branches),
/// inside the ball, with that atom's site and the axis of the bond; `None` when no free
/// site is found.
fn grow(
    rng: &mut SplitMix64,
    sites: &[[i32; 3]],
    bond: f64,
) -> Option<([i32; 3], [i32; 3], usize)> {
    let inside = |s: [i32; 3]| {
        let p = s.map(|k| f64::from(k) * bond);
        (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() <= BALL
    };
    for tries in 0..256 {
        // The newest atoms first; any atom once those are crowded.
        let span = if tries < 32 { 6 } else { sites.len() };
        let parent = sites[sites.len() - 1 - rng.below(sites.len().min(span))];
        let d = rng.below(6);
        let s = [0, 1, 2].map(|i| parent[i] + DIRECTIONS[d][i]);
        if inside(s) && !sites.contains(&s) {
            return Some((s, parent, d / 2));
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vmgen::{op_count, op_histogram, sign_counts};

    #[test]
    fn same_seed_same_text() {
        for f in Flavour::ALL {
            assert_eq!(generate(f, 500, 3), generate(f, 500, 3));
            assert_ne!(generate(f, 500, 3), generate(f, 500, 4));
        }
    }

    #[test]
    fn operation_counts_near_the_target() {
        for f in Flavour::ALL {
            for target in [300, 660, 2_000, 5_000] {
                for seed in 0..3 {
                    let n = op_count(&generate(f, target, seed));
                    assert!(
                        n <= target && n * 10 >= target * 9,
                        "{f} {target} seed {seed}: {n} operations"
                    );
                }
            }
        }
    }

    #[test]
    fn small_targets_give_a_small_model() {
        for f in Flavour::ALL {
            let text = generate(f, 0, 1);
            assert!(op_count(&text) < 200, "{f}");
            let (inside, outside) = sign_counts(&text, 12, true).unwrap();
            assert!(inside > 0 && outside > 0, "{f}");
        }
    }

    #[test]
    fn surfaces_cross_zero_inside_the_cube() {
        for f in Flavour::ALL {
            for (target, seed) in [(660, 1), (2_000, 2)] {
                let (inside, outside) = sign_counts(&generate(f, target, seed), 16, true).unwrap();
                assert!(
                    inside > 40 && outside > 40,
                    "{f} {target}: {inside} in, {outside} out"
                );
            }
        }
    }

    #[test]
    fn flavours_have_their_mix() {
        let share = |f: Flavour, ops: &[&str]| {
            let text = generate(f, 2_000, 9);
            let h = op_histogram(&text);
            let n: usize = ops.iter().map(|op| h.get(*op).copied().unwrap_or(0)).sum();
            n as f64 / op_count(&text) as f64
        };
        let city_csg = share(Flavour::City, &["min", "max", "abs"]);
        let molecule_roots = share(Flavour::Molecule, &["square", "sqrt"]);
        assert!(city_csg > 0.35, "city: min, max, abs {city_csg}");
        assert!(
            molecule_roots > 0.25,
            "molecule: square, sqrt {molecule_roots}"
        );
        assert!(share(Flavour::City, &["square", "sqrt"]) < 0.1);
        assert!(share(Flavour::Molecule, &["min", "max", "abs"]) < 0.2);
    }

    #[test]
    fn flavour_names() {
        for f in Flavour::ALL {
            assert_eq!(f.name().parse::<Flavour>(), Ok(f));
        }
        assert!("town".parse::<Flavour>().is_err());
    }
}
