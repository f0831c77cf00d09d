//! Exact sums of a few `f64` (Shewchuk's nonoverlapping expansions) and their rounding to a
//! [`Dd`] in a chosen direction: how the double-double interval operations get their bounds.

use super::number::Dd;
use crate::float::{two_prod, two_sum};

/// Most steps of the trailing part when rounding (see [`Expansion::round`]).
const MAX_STEPS: usize = 8;

/// Most components an expansion holds: the largest sum here (a quotient's residual) has 10.
const CAPACITY: usize = 24;

/// Products below this magnitude are not split exactly (their TwoProd error term could fall
/// below the subnormal quantum): they are bounded by [`TINY_BOUND`] instead.
const TINY_PRODUCT: f64 = f64::from_bits((1023 - 960) << 52);
/// A bound of the magnitude of a product below [`TINY_PRODUCT`].
const TINY_BOUND: f64 = f64::from_bits((1023 - 950) << 52);

/// An exact sum `Σ c[i]` of nonoverlapping components in increasing magnitude (no zeros),
/// plus a slack `s ≥ 0`: the value `v` of the terms added satisfies `|v − Σ c| ≤ s`.
#[derive(Clone, Debug)]
pub(crate) struct Expansion {
    c: [f64; CAPACITY],
    n: usize,
    slack: f64,
}

impl Expansion {
    /// The empty sum.
    pub fn new() -> Self {
        Self {
            c: [0.0; CAPACITY],
            n: 0,
            slack: 0.0,
        }
    }

    /// Adds the `f64` `b` exactly (Shewchuk's Grow-Expansion with zero elimination).
    pub fn add(&mut self, b: f64) {
        let mut q = b;
        let mut k = 0;
        for i in 0..self.n {
            let (s, e) = two_sum(q, self.c[i]);
            q = s;
            if e != 0.0 {
                self.c[k] = e;
                k += 1;
            }
        }
        if q != 0.0 {
            self.c[k] = q;
            k += 1;
        }
        debug_assert!(k <= CAPACITY);
        self.n = k;
    }

    /// Adds the exact product `a · b` (a bounded slack for products too small to split).
    pub fn add_product(&mut self, a: f64, b: f64) {
        if a == 0.0 || b == 0.0 {
            return;
        }
        let (p, e) = two_prod(a, b);
        if p.abs() < TINY_PRODUCT {
            self.slack += TINY_BOUND;
        } else {
            self.add(p);
            self.add(e);
        }
    }

    /// Adds the double-double `x` exactly.
    pub fn add_dd(&mut self, x: Dd) {
        self.add(x.hi());
        self.add(x.lo());
    }

    /// Adds `x · y` for double-doubles (four products).
    pub fn add_dd_product(&mut self, x: Dd, y: Dd) {
        self.add_product(x.hi(), y.hi());
        self.add_product(x.hi(), y.lo());
        self.add_product(x.lo(), y.hi());
        self.add_product(x.lo(), y.lo());
    }

    /// The sum rounded to nearest, approximately (components added in increasing order).
    fn approx(&self) -> f64 {
        self.c[..self.n].iter().sum()
    }

    /// The sign of the exact sum `Σ c` (its largest component's): `-1`, `0` or `1`.
    fn sign(&self) -> i8 {
        match self.n {
            0 => 0,
            n if self.c[n - 1] > 0.0 => 1,
            _ => -1,
        }
    }

    /// Whether the value is proven `≥ 0` (`> 0` when `strict`), slack included.
    pub fn is_nonnegative(&self, strict: bool) -> bool {
        let mut e = self.clone();
        e.add(-self.slack);
        if strict { e.sign() > 0 } else { e.sign() >= 0 }
    }

    /// Whether the value is proven `≤ 0` (`< 0` when `strict`), slack included.
    pub fn is_nonpositive(&self, strict: bool) -> bool {
        let mut e = self.clone();
        e.add(self.slack);
        if strict { e.sign() < 0 } else { e.sign() <= 0 }
    }

    /// A double-double at most the value (`up = false`) or at least it (`up = true`); `None`
    /// when a step overflows.
    ///
    /// The leading part is the sum rounded approximately, the trailing part the remainder
    /// rounded approximately, then stepped (each step exact: the difference of adjacent
    /// floats) until the exact remainder left has the sign the direction needs.
    pub fn round(&self, up: bool) -> Option<Dd> {
        let mut r = self.clone();
        r.add(if up { self.slack } else { -self.slack });
        let h = r.approx();
        r.add(-h);
        let mut l = r.approx();
        r.add(-l);
        // The approximate remainder is within a few ulps: a few steps suffice (more would
        // mean a slow creep from a tiny `l`; the caller then takes its f64 path).
        for _ in 0..=MAX_STEPS {
            let next = match r.sign() {
                s if up && s > 0 => l.next_up(),
                s if !up && s < 0 => l.next_down(),
                _ => return Dd::from_sum(h, l),
            };
            if !next.is_finite() {
                return None;
            }
            r.add(l - next);
            l = next;
        }
        None
    }
}
