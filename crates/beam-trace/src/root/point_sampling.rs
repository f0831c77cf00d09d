//! PointSampling (to be written).

/// PointSampling.
#[derive(Copy, Clone, Debug, Default)]
pub struct PointSampling;

impl super::RootFinder for PointSampling {
    fn name(&self) -> &'static str {
        "PointSampling"
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
