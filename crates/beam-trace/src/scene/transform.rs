//! Affine placement of a leaf surface: `p_world = M · p_local + t` with `M = R · S` (scale
//! first, then rotate, then translate).
//!
//! A surface `f_local(x, y, z) = 0` is placed by substituting the local coordinates
//! `q = A · p + b` for `x`, `y`, `z`, where `A ≈ M⁻¹` and `b ≈ −A · t` are computed in
//! `f64` from the parts (`A = S⁻¹ · Rᵀ`). The coefficients of `A` and `b` enter the
//! expression graph as exact constants, so the rendered surface is, by definition,
//! `{ p : f_local(A · p + b) = 0 }` with those `f64` coefficients; `M` only serves to find
//! its bounding box.
//!
//! That box must enclose the exact preimage `A⁻¹ · (B − b)` of the local box `B`, and `A⁻¹`
//! is not exactly `M`. [`Affine::world_bounds`] therefore encloses `M · (B − b)` in
//! interval arithmetic and widens it by a proven bound on the error: with
//! `R = I − M · A` and `δ = ‖R‖∞ < 1`, `A⁻¹ = (I − R)⁻¹ · M`, so
//! `‖(A⁻¹ − M) · v‖∞ ≤ δ · ‖M‖∞ / (1 − δ) · ‖v‖∞` for every `v`; every quantity is bounded
//! with outward rounding.
//!
//! The scene file's `transform` tables are read into an [`Affine`] here ([`transform`]),
//! and the map is applied to a surface's graph here ([`local_coordinates`]).

use glam::DVec3;
use implicit_expr::{Context, NodeId};
use interval_core::Interval;

use super::diagnostics::Doc;
use super::schema::{RawRotate, RawScale, RawTransform};
use crate::error::Error;
use crate::ibox::{IBox, ipoint};

type Mat3 = [[f64; 3]; 3];

/// A rotation given in a scene file.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) enum Rotation {
    /// Degrees about `x`, then `y`, then `z` (fixed axes): `R = Rz · Ry · Rx`.
    Euler([f64; 3]),
    /// Degrees about an axis (right-handed); the axis need not have unit length.
    Axis([f64; 3], f64),
}

/// An affine map `p ↦ M · p + t` with `M = R · diag(s)`, and its `f64` inverse.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) struct Affine {
    /// The forward matrix `M = R · S`.
    pub m: Mat3,
    /// The translation `t`.
    pub t: [f64; 3],
    /// `A ≈ M⁻¹ = S⁻¹ · Rᵀ`, the coefficients of the substitution.
    pub a: Mat3,
    /// `b ≈ −A · t`.
    pub b: [f64; 3],
}

/// `(sin, cos)` of `deg` degrees, exact at multiples of 90°.
fn sin_cos_deg(deg: f64) -> (f64, f64) {
    let r = deg.rem_euclid(360.0);
    if r % 90.0 == 0.0 {
        // `rem_euclid` may round up to 360 for tiny negative angles.
        match (r / 90.0) as i64 {
            1 => (1.0, 0.0),
            2 => (0.0, -1.0),
            3 => (-1.0, 0.0),
            _ => (0.0, 1.0),
        }
    } else {
        r.to_radians().sin_cos()
    }
}

fn mat_mul(a: &Mat3, b: &Mat3) -> Mat3 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn rotation_matrix(r: Rotation) -> Option<Mat3> {
    match r {
        Rotation::Euler([ax, ay, az]) => {
            let (sx, cx) = sin_cos_deg(ax);
            let (sy, cy) = sin_cos_deg(ay);
            let (sz, cz) = sin_cos_deg(az);
            let rx = [[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]];
            let ry = [[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]];
            let rz = [[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]];
            Some(mat_mul(&rz, &mat_mul(&ry, &rx)))
        }
        Rotation::Axis(axis, deg) => {
            let u = DVec3::from_array(axis);
            let len = u.length();
            if !(len.is_finite() && len > 0.0) {
                return None;
            }
            let u = u / len;
            let (s, c) = sin_cos_deg(deg);
            let k = 1.0 - c;
            let (x, y, z) = (u.x, u.y, u.z);
            Some([
                [c + x * x * k, x * y * k - z * s, x * z * k + y * s],
                [y * x * k + z * s, c + y * y * k, y * z * k - x * s],
                [z * x * k - y * s, z * y * k + x * s, c + z * z * k],
            ])
        }
    }
}

impl Affine {
    /// The world point `M · p + t` of the local point `p`, computed in `f64` (each
    /// coordinate a sum of three products and the translation, left to right).
    pub fn map_point(&self, p: DVec3) -> DVec3 {
        let row =
            |i: usize| self.m[i][0] * p.x + self.m[i][1] * p.y + self.m[i][2] * p.z + self.t[i];
        DVec3::new(row(0), row(1), row(2))
    }

    /// `translate ∘ rotate ∘ scale`, or `None` when a part is not finite, an axis is zero
    /// or a scale factor is zero (a singular map).
    pub fn new(translate: [f64; 3], rotate: Option<Rotation>, scale: [f64; 3]) -> Option<Self> {
        if !translate.iter().chain(&scale).all(|v| v.is_finite()) || scale.contains(&0.0) {
            return None;
        }
        let r = match rotate {
            Some(r) => rotation_matrix(r)?,
            None => [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        };
        let m: Mat3 = std::array::from_fn(|i| std::array::from_fn(|j| r[i][j] * scale[j]));
        let a: Mat3 = std::array::from_fn(|i| std::array::from_fn(|j| r[j][i] / scale[i]));
        let b: [f64; 3] =
            std::array::from_fn(|i| -(0..3).map(|k| a[i][k] * translate[k]).sum::<f64>());
        let all = m.iter().chain(&a).flatten().chain(&b);
        if !all.clone().all(|v| v.is_finite()) {
            return None;
        }
        Some(Self {
            m,
            t: translate,
            a,
            b,
        })
    }

    /// Whether the map is the identity (no substitution needed).
    pub fn is_identity(&self) -> bool {
        let id = |i: usize, j: usize| if i == j { 1.0 } else { 0.0 };
        (0..3).all(|i| (0..3).all(|j| self.a[i][j] == id(i, j)) && self.b[i] == 0.0)
    }

    /// A box holding every world point `p` with `A · p + b` in the local box `local`
    /// (see the module documentation), or `None` when the map is too close to singular or
    /// the box overflows.
    pub fn world_bounds(&self, local: &IBox) -> Option<IBox> {
        let im = |i: usize, j: usize| ipoint(self.m[i][j]);
        // v = q − b over the local box.
        let v: IBox = std::array::from_fn(|i| local[i] - ipoint(self.b[i]));
        // R = I − M·A, δ = ‖R‖∞ (upper bound).
        let mut delta: Interval<f64> = Interval::ZERO;
        let mut norm_m: Interval<f64> = Interval::ZERO;
        for i in 0..3 {
            let mut row: Interval<f64> = Interval::ZERO;
            let mut row_m: Interval<f64> = Interval::ZERO;
            for j in 0..3 {
                let mut r = ipoint(if i == j { 1.0 } else { 0.0 });
                for k in 0..3 {
                    r = r - im(i, k) * ipoint(self.a[k][j]);
                }
                row = row + ipoint(r.mag());
                row_m = row_m + ipoint(self.m[i][j].abs());
            }
            delta = ipoint(delta.sup().max(row.sup()));
            norm_m = ipoint(norm_m.sup().max(row_m.sup()));
        }
        if delta.sup().is_nan() || delta.sup() >= 1.0 {
            return None;
        }
        let norm_v = v.iter().map(|x| x.mag()).fold(0.0, f64::max);
        let err = (delta * norm_m * ipoint(norm_v)) / (Interval::ONE - delta);
        let e = err.sup();
        if !e.is_finite() {
            return None;
        }
        let out: IBox = std::array::from_fn(|i| {
            let mut s = Interval::new_unchecked(-e, e);
            for (j, vj) in v.iter().enumerate() {
                s = s + im(i, j) * *vj;
            }
            s
        });
        out.iter()
            .all(|x| !x.is_empty() && x.inf().is_finite() && x.sup().is_finite())
            .then_some(out)
    }
}

pub(super) fn transform(doc: &Doc<'_>, path: &str, t: &RawTransform) -> Result<Affine, Error> {
    let translate = match t.translate {
        Some(v) => doc.vec3(&format!("{path}.translate"), v)?.to_array(),
        None => [0.0; 3],
    };
    let rp = format!("{path}.rotate");
    let rotate = match &t.rotate {
        None => None,
        Some(RawRotate::Euler(a)) => Some(Rotation::Euler(doc.vec3(&rp, *a)?.to_array())),
        Some(RawRotate::Axis(aa)) => {
            let axis = doc.vec3(&format!("{rp}.axis"), aa.axis)?;
            if axis == DVec3::ZERO {
                return Err(doc.err(&format!("{rp}.axis"), "must not be zero"));
            }
            let angle = doc.finite(&format!("{rp}.angle"), aa.angle)?;
            Some(Rotation::Axis(axis.to_array(), angle))
        }
    };
    let sp = format!("{path}.scale");
    let scale = match t.scale {
        None => [1.0; 3],
        Some(RawScale::Uniform(s)) => [doc.finite(&sp, s)?; 3],
        Some(RawScale::Axes(s)) => doc.vec3(&sp, s)?.to_array(),
    };
    if scale.contains(&0.0) {
        return Err(doc.err(&sp, "scale factors must not be zero"));
    }
    Affine::new(translate, rotate, scale).ok_or_else(|| {
        doc.err(
            path,
            "the transform cannot be inverted in floating point (a scale factor too small \
             or too large)",
        )
    })
}

/// The local coordinates `A · p + b` as nodes of `ctx`.
pub(super) fn local_coordinates(ctx: &mut Context, aff: &Affine) -> Result<[NodeId; 3], Error> {
    let xyz = [ctx.x(), ctx.y(), ctx.z()];
    if aff.is_identity() {
        return Ok(xyz);
    }
    let mut out = xyz;
    for (i, o) in out.iter_mut().enumerate() {
        let mut acc: Option<NodeId> = None;
        for (j, &v) in xyz.iter().enumerate() {
            let c = aff.a[i][j];
            let term = if c == 0.0 {
                continue;
            } else if c == 1.0 {
                v
            } else if c == -1.0 {
                ctx.neg(v)
            } else {
                let k = ctx.constant(c)?;
                ctx.mul(k, v)
            };
            acc = Some(match acc {
                None => term,
                Some(a) => ctx.add(a, term),
            });
        }
        let mut e = match acc {
            Some(e) => e,
            None => ctx.constant(0.0)?,
        };
        if aff.b[i] != 0.0 {
            let k = ctx.constant(aff.b[i])?;
            e = ctx.add(e, k);
        }
        *o = e;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ibox::ival;

    #[test]
    fn right_angles_are_exact() {
        let a = Affine::new([0.0; 3], Some(Rotation::Euler([0.0, 0.0, 90.0])), [1.0; 3]).unwrap();
        assert_eq!(a.m, [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]);
        let b = Affine::new(
            [0.0; 3],
            Some(Rotation::Euler([-360.0, 180.0, 0.0])),
            [1.0; 3],
        );
        assert_eq!(b.unwrap().m[0][0], -1.0);
    }

    #[test]
    fn inverse_undoes_the_map() {
        let aff = Affine::new(
            [1.0, -2.0, 0.5],
            Some(Rotation::Axis([1.0, 2.0, 3.0], 37.0)),
            [2.0, 0.5, -1.5],
        )
        .unwrap();
        let p = [0.3, -0.7, 1.1];
        let w: [f64; 3] =
            std::array::from_fn(|i| (0..3).map(|j| aff.m[i][j] * p[j]).sum::<f64>() + aff.t[i]);
        let q: [f64; 3] =
            std::array::from_fn(|i| (0..3).map(|j| aff.a[i][j] * w[j]).sum::<f64>() + aff.b[i]);
        for i in 0..3 {
            assert!((q[i] - p[i]).abs() < 1e-12, "{q:?} vs {p:?}");
        }
    }

    #[test]
    fn world_bounds_hold_the_corners() {
        let aff = Affine::new(
            [1.0, 2.0, 3.0],
            Some(Rotation::Euler([10.0, 20.0, 30.0])),
            [2.0; 3],
        )
        .unwrap();
        let local = [ival(-1.0, 1.0), ival(-0.5, 0.5), ival(0.0, 2.0)];
        let w = aff.world_bounds(&local).unwrap();
        for c in 0..8 {
            let p = [
                if c & 1 == 0 { -1.0 } else { 1.0 },
                if c & 2 == 0 { -0.5 } else { 0.5 },
                if c & 4 == 0 { 0.0 } else { 2.0 },
            ];
            for (i, wi) in w.iter().enumerate() {
                let x = (0..3).map(|j| aff.m[i][j] * p[j]).sum::<f64>() + aff.t[i];
                assert!(wi.inf() < x && x < wi.sup());
            }
        }
        // Not wildly larger than the exact box (a cube of side 4 rotated: < 4·√3 wide).
        assert!(w.iter().all(|x| x.wid() < 4.0 * 3f64.sqrt() + 1e-9));
    }

    #[test]
    fn singular_maps_are_refused() {
        assert!(Affine::new([0.0; 3], None, [1.0, 0.0, 1.0]).is_none());
        assert!(Affine::new([0.0; 3], Some(Rotation::Axis([0.0; 3], 10.0)), [1.0; 3]).is_none());
        assert!(Affine::new([f64::NAN, 0.0, 0.0], None, [1.0; 3]).is_none());
        assert!(Affine::new([0.0; 3], None, [1e-320, 1.0, 1.0]).is_none());
    }
}
