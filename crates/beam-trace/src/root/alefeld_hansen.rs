//! NewtonAlefeldHansen (to be written).

/// NewtonAlefeldHansen.
#[derive(Copy, Clone, Debug, Default)]
pub struct NewtonAlefeldHansen;

impl super::RootFinder for NewtonAlefeldHansen {
    fn name(&self) -> &'static str {
        "NewtonAlefeldHansen"
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
