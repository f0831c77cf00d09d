//! Interval Newton with an HC4-revise contraction of every piece (constraint propagation
//! on the expression graph; Benhamou et al. 1999).
//!
//! The search is [`Newton`](super::newton::Newton)'s. Each piece that the rejection test
//! keeps is first narrowed by one forward-backward pass of `g = 0` through the formula's
//! graph ([`RayFn::contract`], implicit-expr's `Contractor`): the reverse operations of
//! interval-core (`sqrRev`, `mulRev`, `sinRev`, ...) remove the parameters that cannot
//! give `g = 0`, and an empty result rejects the piece. Then the Newton step or the
//! bisection runs on what is left. Contraction is strongest where one term of the formula
//! decides the zero set (a sphere's `x² + y² + z² − r²` far from its centre, the product
//! of factors of a quartic), and weakest where many terms cancel; it counts as two
//! evaluations of `g`.

use interval_core::Interval;

use super::finder::{RootCounters, RootFinder, RootResult, RootSettings};
use super::newton::{Variant, newton_search};
use crate::ray::RayFn;

/// Interval Newton on pieces narrowed by HC4-revise first.
#[derive(Copy, Clone, Debug, Default)]
pub struct NewtonHc4;

impl RootFinder for NewtonHc4 {
    fn name(&self) -> &'static str {
        "newton-hc4"
    }

    fn first_root(
        &self,
        g: &mut dyn RayFn,
        t: Interval<f64>,
        settings: &RootSettings,
        counters: &mut RootCounters,
    ) -> RootResult {
        let variant = Variant {
            extended: false,
            contract: true,
        };
        newton_search(g, t, settings, counters, variant)
    }
}
