//! Irradiance from the visible parts of a light: Lambert's formula for polygons.
//!
//! A Lambertian emitter of radiance `L` over a planar polygon `v_0 … v_{k−1}` gives a point
//! `x` with unit normal `n` the irradiance
//!
//! ```text
//! E = L · ½ Σ_i β_i (n · γ_i),
//! ```
//!
//! summed over the edges, where `β_i` is the angle that the edge `v_i → v_{i+1}` subtends at
//! `x` and `γ_i` the unit normal of the plane through `x` and that edge, `(v_i − x) ×
//! (v_{i+1} − x)` normalised (the polygon's vector irradiance, Lambert's integral of the
//! cosine over the solid angle, taken around the polygon's boundary by Stokes' theorem).
//! Divided by `π L` it is the point-to-polygon form factor: the share of a cosine-weighted
//! hemisphere the polygon covers. The polygon must lie wholly on the side of `x`'s tangent
//! plane that `n` points to (clip it there first); its winding then only flips the sum's
//! sign, which is taken positive.
//!
//! The angles are taken as `atan2(|a × b|, a · b)`, accurate at every angle, and the sum is
//! plain `f64`: like the fragments' areas, exact up to rounding, not a proven bound.

use glam::DVec3;

/// The form factor from the point `x` with unit normal `n` to the planar polygon `poly`
/// (any winding, wholly above `x`'s horizon): `E / (π L)` for a Lambertian emitter of
/// radiance `L`, between 0 and 1.
pub fn form_factor(x: DVec3, n: DVec3, poly: &[DVec3]) -> f64 {
    let k = poly.len();
    let sum: f64 = (0..k)
        .map(|i| {
            let (a, b) = (poly[i] - x, poly[(i + 1) % k] - x);
            let c = a.cross(b);
            let len = c.length();
            if len == 0.0 {
                // The edge's line passes through `x`: it subtends no angle.
                return 0.0;
            }
            len.atan2(a.dot(b)) * n.dot(c) / len
        })
        .sum();
    (sum / (2.0 * std::f64::consts::PI)).abs()
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::form_factor;
    use crate::shadow::exact::tests::rect;

    /// The form factor from a point to a rectangle `a × b` in a parallel plane at height
    /// `h`, one corner straight above the point (the closed form of the heat-transfer
    /// tables).
    fn corner_rectangle(a: f64, b: f64, h: f64) -> f64 {
        let (x, y) = (a / h, b / h);
        let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
        (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * std::f64::consts::PI)
    }

    #[test]
    fn a_rectangle_above_a_corner_matches_the_closed_form_either_winding() {
        for (a, b, h) in [
            (1.0, 1.0, 1.0),
            (0.3, 2.0, 0.7),
            (5.0, 0.1, 2.0),
            (1e3, 1e3, 1.0),
        ] {
            let mut poly = rect(0.0, a, 0.0, b, h);
            let want = corner_rectangle(a, b, h);
            let got = form_factor(DVec3::ZERO, DVec3::Y, &poly);
            assert!(
                (got - want).abs() < 1e-12,
                "{a} × {b} at {h}: {got} against {want}"
            );
            poly.reverse();
            assert!((form_factor(DVec3::ZERO, DVec3::Y, &poly) - want).abs() < 1e-12);
        }
        // A plane of infinite extent covers the whole hemisphere: the limit is 1/4 per
        // quadrant.
        assert!((corner_rectangle(1e9, 1e9, 1.0) - 0.25).abs() < 1e-6);
    }

    /// A rectangle anywhere is the signed sum of four rectangles with a corner above the
    /// point; the formula is additive over any split.
    #[test]
    fn rectangles_off_the_point_and_split_polygons_add_up() {
        let (x0, x1, z0, z1, h) = (0.4, 1.3, -0.2, 0.9, 0.8);
        let f = |x: f64, z: f64| corner_rectangle(x.abs(), z.abs(), h);
        // x0 > 0 while z0 < 0 < z1: [x0, x1] × [z0, z1] is the difference of the strips.
        let want = f(x1, z1) + f(x1, z0) - f(x0, z1) - f(x0, z0);
        let got = form_factor(DVec3::ZERO, DVec3::Y, &rect(x0, x1, z0, z1, h));
        assert!((got - want).abs() < 1e-12, "{got} against {want}");
        // A tilted normal and a triangle split into two.
        let n = DVec3::new(0.3, 1.0, -0.2).normalize();
        let x = DVec3::new(0.1, 0.0, 0.2);
        let tri = [
            DVec3::new(-0.5, 1.0, 0.0),
            DVec3::new(0.7, 1.2, 0.3),
            DVec3::new(0.0, 0.9, 1.0),
        ];
        let mid = 0.5 * (tri[1] + tri[2]);
        let whole = form_factor(x, n, &tri);
        let parts =
            form_factor(x, n, &[tri[0], tri[1], mid]) + form_factor(x, n, &[tri[0], mid, tri[2]]);
        assert!(
            whole > 0.0 && (whole - parts).abs() < 1e-14,
            "{whole} against {parts}"
        );
    }
}
