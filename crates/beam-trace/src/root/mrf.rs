//! MRF and MRFro (to be written).

/// MRF.
#[derive(Copy, Clone, Debug, Default)]
pub struct Mrf;
/// MRFro.
#[derive(Copy, Clone, Debug, Default)]
pub struct Mrfro;

impl super::RootFinder for Mrf {
    fn name(&self) -> &'static str {
        "mrf"
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
impl super::RootFinder for Mrfro {
    fn name(&self) -> &'static str {
        "mrfro"
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
