//! Mitchell (to be written).

/// Mitchell.
#[derive(Copy, Clone, Debug, Default)]
pub struct Mitchell;

impl super::RootFinder for Mitchell {
    fn name(&self) -> &'static str {
        "Mitchell"
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
