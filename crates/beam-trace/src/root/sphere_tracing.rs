//! SphereTracing (to be written).

/// SphereTracing.
#[derive(Copy, Clone, Debug, Default)]
pub struct SphereTracing;

impl super::RootFinder for SphereTracing {
    fn name(&self) -> &'static str {
        "SphereTracing"
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
