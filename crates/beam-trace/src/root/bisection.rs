//! Bisection (to be written).

/// Bisection.
#[derive(Copy, Clone, Debug, Default)]
pub struct Bisection;

impl super::RootFinder for Bisection {
    fn name(&self) -> &'static str {
        "Bisection"
    }
    fn is_reliable(&self) -> bool {
        true
    }
    fn first_root(
        &self,
        _g: &mut dyn super::RayFn,
        _t: interval_core::Interval<f64>,
        _s: &super::RootSettings,
        _c: &mut super::RootCounters,
    ) -> super::RootResult {
        unimplemented!()
    }
}
