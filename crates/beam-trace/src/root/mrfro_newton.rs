//! MrfroNewton (to be written).

/// MrfroNewton.
#[derive(Copy, Clone, Debug, Default)]
pub struct MrfroNewton;

impl super::RootFinder for MrfroNewton {
    fn name(&self) -> &'static str {
        "MrfroNewton"
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
