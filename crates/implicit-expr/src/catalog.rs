//! The named surfaces of the papers: the test scenes of the thesis (figures 4.9, 5.7, 5.14,
//! 5.24, 7.5, 7.14, 7.15 and Table 4.1) and of the soft-shadow paper, as formulas of the
//! [formula language](crate::parse) with their parameters and a bounding box.
//!
//! The papers name the surfaces but mostly do not print their equations; each entry uses the
//! standard published implicit equation and says where it comes from, and which constant was
//! chosen where sources differ.
//!
//! Sign convention: every formula is negative inside (`f < 0`) and positive outside, where
//! "inside" has a meaning; published equations with the other sign are negated (and say so).
//!
//! Bounding boxes are axis-aligned `[min, max]` boxes that hold the whole surface, except for
//! the surfaces that are unbounded or have parts reaching to infinity (thin "whiskers" of
//! their zero set): there the box is the part that is rendered, and
//! [`Surface::is_clipped`] says so.
//!
//! ```
//! use implicit_expr::{Context, Evaluator, Tape, catalog};
//!
//! let s = catalog::get("orthocircle")?;
//! let mut ctx = Context::new();
//! let f = s.build(&mut ctx)?;
//! let tape = Tape::new(&ctx, &[f])?;
//! // Inputs: x, y, z, then the parameters (a, b) at their default values.
//! let at = |p: [f64; 3]| [&p[..], &s.param_values()].concat();
//! let mut e = Evaluator::<f64>::new(&tape);
//! assert!(e.eval(&at([1.0, 0.0, 0.0]))? < 0.0); // on the unit circle: inside a tube
//! assert!(e.eval(&at([0.0, 0.0, 0.0]))? > 0.0); // the centre is outside
//! assert!(!s.is_clipped()); // the box holds the whole surface
//!
//! let err = catalog::get("sphre").unwrap_err();
//! assert_eq!(err.to_string(), "unknown surface 'sphre'; did you mean 'sphere'?");
//! # Ok::<(), implicit_expr::Error>(())
//! ```

use interval_core::Interval;

use crate::context::{Context, NodeId};
use crate::error::Error;
use crate::parse::{parse, suggest};

/// A named implicit surface `f(x, y, z) = 0` of the catalog.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// The catalog name (kebab-case), as accepted by [`get`].
    pub name: &'static str,
    /// The formula, in the [formula language](crate::parse); negative inside.
    pub formula: &'static str,
    /// The parameters the formula uses, with their default values, in declaration order.
    pub params: &'static [(&'static str, f64)],
    /// An axis-aligned box `([x, y, z] min, [x, y, z] max)` around the surface, or around the
    /// rendered part of it when [`is_clipped`](Surface::is_clipped).
    pub bounds: ([f64; 3], [f64; 3]),
    /// Where the formula comes from, and the choices made.
    pub source: &'static str,
}

impl Surface {
    /// Parses the formula into `ctx`, declaring the parameters, and returns the root node.
    ///
    /// In a fresh context the variable slots are `x`, `y`, `z`, then the parameters in the
    /// order of [`params`](Surface::params), so an evaluator's input is the point followed by
    /// [`param_values`](Surface::param_values).
    ///
    /// # Errors
    /// None for the catalog's own formulas (a test parses every one); the `Result` is the
    /// parser's.
    pub fn build(&self, ctx: &mut Context) -> Result<NodeId, Error> {
        parse(ctx, self.formula, &self.param_names())
    }

    /// The parameter names, in declaration order.
    pub fn param_names(&self) -> Vec<&'static str> {
        self.params.iter().map(|&(n, _)| n).collect()
    }

    /// The default parameter values, in declaration order (the inputs after `x`, `y`, `z`).
    pub fn param_values(&self) -> Vec<f64> {
        self.params.iter().map(|&(_, v)| v).collect()
    }

    /// The bounding box as three intervals (`x`, `y`, `z`).
    pub fn bounding_box(&self) -> [Interval<f64>; 3] {
        let (lo, hi) = self.bounds;
        std::array::from_fn(|i| Interval::new(lo[i], hi[i]).expect("ordered finite bounds"))
    }

    /// Whether the surface reaches beyond [`bounds`](Surface::bounds): it is unbounded, or its
    /// zero set holds lines to infinity. The box is then the rendered part.
    pub fn is_clipped(&self) -> bool {
        CLIPPED.contains(&self.name)
    }
}

/// The surfaces whose box is a clipping box rather than an enclosure.
const CLIPPED: [&str; 7] = [
    "drop",
    "crosscap",
    "horned-cube",
    "steiner",
    "tri-trumpet",
    "barth-sextic",
    "weird",
];

/// Every surface of the catalog, in the order of the thesis's figures.
pub fn all() -> &'static [Surface] {
    &ALL
}

/// The names of the catalog's surfaces.
pub fn names() -> impl Iterator<Item = &'static str> {
    ALL.iter().map(|s| s.name)
}

/// The surface called `name`.
///
/// # Errors
/// [`Error::UnknownSurface`] when there is none, with the closest name as a hint when one is
/// close (`did you mean 'sphere'?`).
pub fn get(name: &str) -> Result<&'static Surface, Error> {
    ALL.iter()
        .find(|s| s.name == name)
        .ok_or_else(|| Error::UnknownSurface {
            name: name.to_string(),
            hint: suggest::did_you_mean(name, names()),
        })
}

static ALL: [Surface; 16] = [
    SPHERE,
    DROP,
    KUSNER_SCHMITT,
    CROSSCAP,
    CHUBS,
    MCMULLEN_K3,
    HORNED_CUBE,
    GUMDROP_TORUS,
    ORTHOCIRCLE,
    STEINER,
    BLOBBY,
    TRI_TRUMPET,
    TANGLE_CUBE,
    BARTH_SEXTIC,
    WEIRD,
    TWIST,
];

/// The unit sphere `x² + y² + z² − 1 = 0` (thesis figures 4.9a, 5.7, 7.15a).
pub const SPHERE: Surface = Surface {
    name: "sphere",
    formula: "x^2 + y^2 + z^2 - 1",
    params: &[],
    bounds: ([-1.25; 3], [1.25; 3]),
    source: "the unit sphere",
};

/// The drop (teardrop) of thesis figures 4.9b, 5.14c, 5.21 and 7.14: `y² + z² = ½x⁵ + ½x⁴`,
/// the "Glob_5" quintic of POV-Ray's `shapesq.inc`. It is a surface of revolution about the
/// `x` axis with radius `√(½x⁴(x + 1))`: a drop on `−1 ≤ x ≤ 0` joined at the origin, by a
/// spindle of radius about `0.7x²`, to a body that opens without bound for `x > 0`. That
/// thin joint is the feature point sampling misses (thesis §5.6). The box clips the body at
/// `x = 1`.
pub const DROP: Surface = Surface {
    name: "drop",
    formula: "y^2 + z^2 - 0.5*x^5 - 0.5*x^4",
    params: &[],
    bounds: ([-1.25, -1.25, -1.25], [1.0, 1.25, 1.25]),
    source: "POV-Ray shapesq.inc Glob_5: y^2 + z^2 = 0.5 x^5 + 0.5 x^4; unbounded for x > 0, \
             clipped at x = 1",
};

/// The Kusner–Schmitt surface (thesis figures 4.9c, 7.15b; soft-shadow paper figure 6): the
/// sextic `x²y²z² + 3(x²y² + y²z² + z²x²) + 9(x² + y² + z²) − 32xyz − 5 = 0` of public
/// implicit-surface collections, written in its factored form
/// `(x² + 3)(y² + 3)(z² + 3) − 32(xyz + 1)`. Bounded, within `|x|, |y|, |z| ≤ 1`.
pub const KUSNER_SCHMITT: Surface = Surface {
    name: "kusner-schmitt",
    formula: "(x^2 + 3)*(y^2 + 3)*(z^2 + 3) - 32*(x*y*z + 1)",
    params: &[],
    bounds: ([-1.25; 3], [1.25; 3]),
    source: "Kusner-Schmitt sextic x^2y^2z^2 + 3(x^2y^2 + y^2z^2 + z^2x^2) + 9(x^2 + y^2 + z^2) \
             - 32xyz - 5 = 0, factored",
};

/// The cross-cap (thesis figures 4.5, 4.9d): the quartic
/// `4x²(x² + y² + z² + z) + y²(y² + z² − 1) = 0` (Wolfram MathWorld, "Cross-Cap"). Its zero
/// set also holds the whole `z` axis (`x = y = 0`), a line of measure zero that the box
/// clips; the surface proper lies in `|x| ≤ 0.5`, `|y|, |z| ≤ 1`.
pub const CROSSCAP: Surface = Surface {
    name: "crosscap",
    formula: "4*x^2*(x^2 + y^2 + z^2 + z) + y^2*(y^2 + z^2 - 1)",
    params: &[],
    bounds: ([-0.75, -1.25, -1.25], [0.75, 1.25, 1.25]),
    source: "MathWorld Cross-Cap quartic 4x^2(x^2 + y^2 + z^2 + z) + y^2(y^2 + z^2 - 1) = 0; \
             the z axis also lies on the zero set",
};

/// The chubs surface (thesis figure 4.9e; soft-shadow paper figure 6):
/// `x⁴ + y⁴ + z⁴ − x² − y² − z² + 0.5 = 0` (Wolfram MathWorld, "Chubs"). A hollow rounded
/// cube with holes along the axes: the origin is outside. Bounded, within `|x|, |y|, |z| ≤ 1`.
pub const CHUBS: Surface = Surface {
    name: "chubs",
    formula: "x^4 + y^4 + z^4 - x^2 - y^2 - z^2 + 0.5",
    params: &[],
    bounds: ([-1.25; 3], [1.25; 3]),
    source: "MathWorld Chubs: x^4 + y^4 + z^4 - x^2 - y^2 - z^2 + 0.5 = 0",
};

/// McMullen's K3 surface (thesis figure 4.9f; soft-shadow paper figure 6):
/// `(1 + x²)(1 + y²)(1 + z²) + 8xyz − 2 = 0`, as in public implicit-surface collections.
/// Bounded, within `|x|, |y|, |z| < 1.8`.
pub const MCMULLEN_K3: Surface = Surface {
    name: "mcmullen-k3",
    formula: "(1 + x^2)*(1 + y^2)*(1 + z^2) + 8*x*y*z - 2",
    params: &[],
    bounds: ([-2.0; 3], [2.0; 3]),
    source: "McMullen K3: (1 + x^2)(1 + y^2)(1 + z^2) + 8xyz - 2 = 0",
};

/// The horned cube (thesis figure 4.9g): the octic
/// `−3x⁸ − 3y⁸ − 2z⁸ + 5x⁴y²z² + 3x²y⁴z² + 1 = 0` of public implicit-surface collections,
/// negated here so that the inside is negative. A rounded cube whose corners grow horns
/// along the four body diagonals; the horns thin out but reach to infinity (on the
/// diagonals `f = −1`), so the box clips them: its eight corners are inside.
pub const HORNED_CUBE: Surface = Surface {
    name: "horned-cube",
    formula: "3*x^8 + 3*y^8 + 2*z^8 - 5*x^4*y^2*z^2 - 3*x^2*y^4*z^2 - 1",
    params: &[],
    bounds: ([-1.25; 3], [1.25; 3]),
    source: "horned cube octic -3x^8 - 3y^8 - 2z^8 + 5x^4y^2z^2 + 3x^2y^4z^2 + 1 = 0, negated; \
             horns along the diagonals clipped by the box",
};

/// The gumdrop torus (thesis figures 4.9h, 5.7, 7.15d): the quartic of public
/// implicit-surface collections `4(x⁴ + (y² + z²)²) + 17x²(y² + z²) − 20(x² + y² + z²) + 17 = 0`,
/// a surface of revolution about the `x` axis: a ring around the axis and two gumdrops on it.
/// Bounded, within `|x|, |y|, |z| < 2`.
pub const GUMDROP_TORUS: Surface = Surface {
    name: "gumdrop-torus",
    formula: "4*(x^4 + (y^2 + z^2)^2) + 17*x^2*(y^2 + z^2) - 20*(x^2 + y^2 + z^2) + 17",
    params: &[],
    bounds: ([-2.25; 3], [2.25; 3]),
    source: "gumdrop torus quartic 4(x^4 + (y^2 + z^2)^2) + 17x^2(y^2 + z^2) \
             - 20(x^2 + y^2 + z^2) + 17 = 0",
};

/// The orthocircle (thesis figures 5.14a, 6.7, 7.5a; soft-shadow paper figure 6), as printed
/// in thesis §6.5: `((x² + y² − 1)² + z²)((y² + z² − 1)² + x²)((z² + x² − 1)² + y²)
/// − a²(1 + b(x² + y² + z²)) = 0`, three orthogonal tubes around the unit circles, with the
/// parameters of public collections `a = 0.075`, `b = 3`. The box holds the surface for these
/// values (it reaches `|x| ≈ 1.15`); larger `a` or `b` thicken the tubes.
pub const ORTHOCIRCLE: Surface = Surface {
    name: "orthocircle",
    formula: "((x^2 + y^2 - 1)^2 + z^2)*((y^2 + z^2 - 1)^2 + x^2)*((z^2 + x^2 - 1)^2 + y^2) \
              - a^2*(1 + b*(x^2 + y^2 + z^2))",
    params: &[("a", 0.075), ("b", 3.0)],
    bounds: ([-1.5; 3], [1.5; 3]),
    source: "thesis section 6.5 (orthocircle with parameters a, b); a = 0.075, b = 3",
};

/// Steiner's Roman surface (thesis figures 5.7, 5.8, 7.5b): `x²y² + y²z² + z²x² − xyz = 0`.
/// The surface proper lies in `|x|, |y|, |z| ≤ 0.5`; the zero set also holds the three
/// coordinate axes, lines that the box clips.
pub const STEINER: Surface = Surface {
    name: "steiner",
    formula: "x^2*y^2 + y^2*z^2 + z^2*x^2 - x*y*z",
    params: &[],
    bounds: ([-0.75; 3], [0.75; 3]),
    source: "Steiner's Roman surface x^2y^2 + y^2z^2 + z^2x^2 - xyz = 0 (r = 1); the \
             coordinate axes also lie on the zero set",
};

/// A blobby surface (thesis figures 5.7, 5.14b, 5.17, 5.24c): Blinn's sum of Gaussians,
/// thesis equation 2.7, `Σ bᵢ exp(−aᵢ rᵢ²) − 1`, negated here (the equation is positive
/// inside). Three blended blobs (`a = 4`, `b = 2`) centred at `(±0.6, 0, 0)` and
/// `(0, 0.7, 0)`, and the small separate sphere of figure 5.17 (`a = 20`, `b = 2`) at
/// `(0, −0.85, 0.2)`. Bounded: the field is below the threshold outside the box.
pub const BLOBBY: Surface = Surface {
    name: "blobby",
    formula: "1 - 2*exp(-4*((x + 0.6)^2 + y^2 + z^2)) - 2*exp(-4*((x - 0.6)^2 + y^2 + z^2)) \
              - 2*exp(-4*(x^2 + (y - 0.7)^2 + z^2)) - 2*exp(-20*(x^2 + (y + 0.85)^2 + (z - 0.2)^2))",
    params: &[],
    bounds: ([-1.5, -1.5, -1.0], [1.5, 1.5, 1.0]),
    source: "thesis equation 2.7 (Blinn's blobs), negated: four Gaussians, one a small \
             separate sphere",
};

/// The tri-trumpet (thesis figures 5.24d–f, 7.14c–d): Paul Bourke's cubic
/// `8z² + (2x + 1)(3y² − (x − 1)²) = 0`. Its section `z = 0` is the equilateral triangle with
/// corners `(1, 0)`, `(−½, ±√3/2)`; at the corners the surface pinches to singular points
/// (the thin connections) and opens into three trumpets that reach to infinity, clipped by
/// the box.
pub const TRI_TRUMPET: Surface = Surface {
    name: "tri-trumpet",
    formula: "8*z^2 + (2*x + 1)*(3*y^2 - (x - 1)^2)",
    params: &[],
    bounds: ([-2.0; 3], [2.0; 3]),
    source: "Paul Bourke's tritrumpet 8z^2 + (2x + 1)(3y^2 - (x - 1)^2) = 0; the trumpets are \
             clipped by the box",
};

/// The tangle cube (thesis figure 7.15c): `x⁴ − 5x² + y⁴ − 5y² + z⁴ − 5z² + 11.8 = 0`
/// (Wolfram MathWorld, "Tanglecube"). Bounded, within `|x|, |y|, |z| < 2.3`.
pub const TANGLE_CUBE: Surface = Surface {
    name: "tangle-cube",
    formula: "x^4 - 5*x^2 + y^4 - 5*y^2 + z^4 - 5*z^2 + 11.8",
    params: &[],
    bounds: ([-2.5; 3], [2.5; 3]),
    source: "MathWorld Tanglecube: x^4 - 5x^2 + y^4 - 5y^2 + z^4 - 5z^2 + 11.8 = 0",
};

/// Barth's sextic (thesis figure 7.5c, "bath"): `4(φ²x² − y²)(φ²y² − z²)(φ²z² − x²)
/// − (1 + 2φ)(x² + y² + z² − 1)² = 0` with the golden ratio `φ = (1 + √5)/2` (Wolfram
/// MathWorld, "Barth Sextic", `w = 1`), written with the exact `φ² = (3 + √5)/2` and
/// `1 + 2φ = 2 + √5` rather than the rounded 2.62 and 4.24 of some collections. The zero set
/// is unbounded (the coordinate axes lie inside, touching it at `(±1, 0, 0)` and the like);
/// the box is the rendered part, holding the 20 double cones around the centre.
pub const BARTH_SEXTIC: Surface = Surface {
    name: "barth-sextic",
    formula: "4*((3 + sqrt(5))/2*x^2 - y^2)*((3 + sqrt(5))/2*y^2 - z^2)*((3 + sqrt(5))/2*z^2 - x^2) \
              - (2 + sqrt(5))*(x^2 + y^2 + z^2 - 1)^2",
    params: &[],
    bounds: ([-2.0; 3], [2.0; 3]),
    source: "MathWorld Barth sextic with the golden ratio exact (phi^2 = (3 + sqrt 5)/2, \
             1 + 2 phi = 2 + sqrt 5); unbounded, clipped by the box",
};

/// Nordstrand's "weird" surface (thesis figure 7.5d): the quartic
/// `25(x³(y + z) + y³(x + z) + z³(x + y)) + 50(x²y² + x²z² + y²z²)
/// − 125(x²yz + xy²z + xyz²) + 60xyz − 4(xy + xz + yz) = 0` of Tore Nordstrand's gallery,
/// with its published sign. Its zero set holds the coordinate axes and is unbounded; the box
/// is the rendered part. Two of its corners, `±(1, 1, 1)`, are on the negative side (on the
/// diagonal `f = −3t²(5t − 2)²`).
pub const WEIRD: Surface = Surface {
    name: "weird",
    formula: "25*(x^3*(y + z) + y^3*(x + z) + z^3*(x + y)) + 50*(x^2*y^2 + x^2*z^2 + y^2*z^2) \
              - 125*(x^2*y*z + x*y^2*z + x*y*z^2) + 60*x*y*z - 4*(x*y + x*z + y*z)",
    params: &[],
    bounds: ([-1.0; 3], [1.0; 3]),
    source: "Nordstrand's weird surface (published sign); the axes lie on the zero set, \
             clipped by the box",
};

/// A twisted ribbon, standing for the "twist" of thesis figure 5.24a–b and the "twister" of
/// the soft-shadow paper (figure 5), whose formulas are not printed: the rounded slab
/// `u⁴ + (v / 0.1)⁴ + (z / 1.5)⁴ ≤ 1` (half-width 1, half-thickness 0.1, half-height 1.5) in
/// coordinates `u = x cos kz + y sin kz`, `v = y cos kz − x sin kz` that turn by `k` radians
/// per unit of height (`k = 2`: a little under one turn over the height). A thin feature
/// whose shadow point sampling breaks up. Rotation keeps `x² + y² = u² + v² ≤ 1.01`, so the
/// box holds the surface for every `k`.
pub const TWIST: Surface = Surface {
    name: "twist",
    formula: "(x*cos(k*z) + y*sin(k*z))^4 + (10*(y*cos(k*z) - x*sin(k*z)))^4 + (z/1.5)^4 - 1",
    params: &[("k", 2.0)],
    bounds: ([-1.25, -1.25, -1.75], [1.25, 1.25, 1.75]),
    source: "a thin superquadric slab (1 x 0.1 x 1.5, power 4) twisted about z by k radians \
             per unit height, k = 2",
};
