//! Newton (to be written).

/// Newton.
#[derive(Copy, Clone, Debug, Default)]
pub struct Newton;

impl super::RootFinder for Newton {
    fn name(&self) -> &'static str {
        "Newton"
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
