//! What the round-trip fuzz targets share.

/// Whether two evaluations of a graph and of its round-tripped copy agree: bit for bit, or
/// within a relative 1e-9, or either is not finite. Folded constants read back from their
/// printed values may enable or disable an identity (`0*a = 0` with an exact zero turns a
/// NaN into 0), so only finite values are compared.
pub fn same_value(vf: f64, vg: f64) -> bool {
    vf.to_bits() == vg.to_bits()
        || !vf.is_finite()
        || !vg.is_finite()
        || (vf - vg).abs() <= 1e-9 * vf.abs().max(vg.abs())
}
