//! CounterBisection (to be written).

/// CounterBisection.
#[derive(Copy, Clone, Debug, Default)]
pub struct CounterBisection;

impl super::RootFinder for CounterBisection {
    fn name(&self) -> &'static str {
        "CounterBisection"
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
