//! Double-double arithmetic: [`Dd`] numbers (about 106 bits) and [`DdInterval`], intervals
//! with double-double bounds rounded outward, for the queries that `f64` intervals cannot
//! decide because rounding, not the width of the box, dominates their enclosures (large
//! terms that cancel).
//!
//! Sums and products are double-word algorithms with proven relative error bounds (Joldes,
//! Muller and Popescu, 2017), widened outward by eight times those bounds. Quotients and
//! square roots are approximated, then corrected until the exact residual (`a − q·b`,
//! `a − s²`) has the sign that puts them on the right side: the residual is an exact sum of
//! `f64` terms (an *expansion*: Shewchuk's nonoverlapping components, built with the
//! error-free transformations [`two_sum`](crate::float::two_sum) and
//! [`two_prod`](crate::float::two_prod)). `exp`, `sin` and
//! `cos` reduce their argument and sum a Taylor polynomial in these interval operations,
//! with an interval bound of the remainder.

mod elementary;
mod expansion;
mod interval;
mod number;

pub use interval::DdInterval;
pub use number::Dd;
