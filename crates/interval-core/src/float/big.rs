//! A small unsigned big integer: just what exact comparisons and exact sums of floats need
//! (addition, subtraction, multiplication, shifts, comparison), without a dependency.
//!
//! Limbs are `u32`, least significant first, with no trailing zero limbs, so that products of
//! two limbs fit a `u64`. Sizes stay small here (a few thousand bits: the exponent range of
//! `f64` products, or the digits of a decimal literal), so schoolbook algorithms suffice.

use core::cmp::Ordering;

/// An unsigned integer of any size.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct BigUint {
    /// Little-endian limbs, normalized (no most significant zero limb).
    limbs: Vec<u32>,
}

impl BigUint {
    /// Zero.
    pub(crate) fn zero() -> Self {
        Self { limbs: Vec::new() }
    }

    /// The value `v`.
    pub(crate) fn from_u64(v: u64) -> Self {
        let mut r = Self {
            limbs: vec![v as u32, (v >> 32) as u32],
        };
        r.normalize();
        r
    }

    /// Drops most significant zero limbs.
    fn normalize(&mut self) {
        while self.limbs.last() == Some(&0) {
            self.limbs.pop();
        }
    }

    /// True for zero.
    pub(crate) fn is_zero(&self) -> bool {
        self.limbs.is_empty()
    }

    /// Number of significant bits (0 for zero).
    pub(crate) fn bits(&self) -> u64 {
        match self.limbs.last() {
            None => 0,
            Some(&top) => 32 * self.limbs.len() as u64 - u64::from(top.leading_zeros()),
        }
    }

    /// The value as `u64`, if it fits.
    pub(crate) fn to_u64(&self) -> Option<u64> {
        match self.limbs.len() {
            0 => Some(0),
            1 => Some(u64::from(self.limbs[0])),
            2 => Some(u64::from(self.limbs[0]) | (u64::from(self.limbs[1]) << 32)),
            _ => None,
        }
    }

    /// `self + other`.
    pub(crate) fn add(&self, other: &Self) -> Self {
        let n = self.limbs.len().max(other.limbs.len());
        let mut limbs = Vec::with_capacity(n + 1);
        let mut carry = 0u64;
        for i in 0..n {
            let s = u64::from(*self.limbs.get(i).unwrap_or(&0))
                + u64::from(*other.limbs.get(i).unwrap_or(&0))
                + carry;
            limbs.push(s as u32);
            carry = s >> 32;
        }
        limbs.push(carry as u32);
        let mut r = Self { limbs };
        r.normalize();
        r
    }

    /// `self − other`; the caller guarantees `self ≥ other`.
    pub(crate) fn sub(&self, other: &Self) -> Self {
        debug_assert!(self.cmp(other) != Ordering::Less);
        let mut limbs = Vec::with_capacity(self.limbs.len());
        let mut borrow = 0i64;
        for i in 0..self.limbs.len() {
            let mut d =
                i64::from(self.limbs[i]) - i64::from(*other.limbs.get(i).unwrap_or(&0)) - borrow;
            borrow = i64::from(d < 0);
            if d < 0 {
                d += 1 << 32;
            }
            limbs.push(d as u32);
        }
        let mut r = Self { limbs };
        r.normalize();
        r
    }

    /// `self · other`.
    pub(crate) fn mul(&self, other: &Self) -> Self {
        if self.is_zero() || other.is_zero() {
            return Self::zero();
        }
        let mut limbs = vec![0u32; self.limbs.len() + other.limbs.len()];
        for (i, &a) in self.limbs.iter().enumerate() {
            let mut carry = 0u64;
            for (j, &b) in other.limbs.iter().enumerate() {
                let t = u64::from(a) * u64::from(b) + u64::from(limbs[i + j]) + carry;
                limbs[i + j] = t as u32;
                carry = t >> 32;
            }
            limbs[i + other.limbs.len()] = carry as u32;
        }
        let mut r = Self { limbs };
        r.normalize();
        r
    }

    /// `self^k`, by squaring and multiplying.
    pub(crate) fn pow(&self, k: u64) -> Self {
        let mut acc = Self::from_u64(1);
        let mut base = self.clone();
        let mut e = k;
        while e > 0 {
            if e & 1 == 1 {
                acc = acc.mul(&base);
            }
            e >>= 1;
            if e > 0 {
                base = base.mul(&base);
            }
        }
        acc
    }

    /// `self · m` for a small factor.
    pub(crate) fn mul_small(&self, m: u32) -> Self {
        self.mul(&Self::from_u64(u64::from(m)))
    }

    /// `self · 2^n`.
    pub(crate) fn shl(&self, n: u64) -> Self {
        if self.is_zero() {
            return Self::zero();
        }
        let (words, bits) = ((n / 32) as usize, (n % 32) as u32);
        let mut limbs = vec![0u32; words];
        let mut carry = 0u32;
        for &l in &self.limbs {
            if bits == 0 {
                limbs.push(l);
            } else {
                limbs.push((l << bits) | carry);
                carry = l >> (32 - bits);
            }
        }
        limbs.push(carry);
        let mut r = Self { limbs };
        r.normalize();
        r
    }

    /// `⌊self / 2^n⌋` and whether the discarded bits were nonzero (the sticky bit).
    pub(crate) fn shr_sticky(&self, n: u64) -> (Self, bool) {
        let (words, bits) = ((n / 32) as usize, (n % 32) as u32);
        if words >= self.limbs.len() {
            return (Self::zero(), !self.is_zero());
        }
        let mut sticky = self.limbs[..words].iter().any(|&l| l != 0);
        if bits != 0 {
            sticky |= self.limbs[words] & ((1u32 << bits) - 1) != 0;
        }
        let src = &self.limbs[words..];
        let mut limbs = Vec::with_capacity(src.len());
        for i in 0..src.len() {
            let lo = src[i] >> bits;
            let hi = if bits == 0 {
                0
            } else {
                src.get(i + 1).map_or(0, |&h| h << (32 - bits))
            };
            limbs.push(lo | hi);
        }
        let mut r = Self { limbs };
        r.normalize();
        (r, sticky)
    }
}

impl PartialOrd for BigUint {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for BigUint {
    fn cmp(&self, other: &Self) -> Ordering {
        self.limbs
            .len()
            .cmp(&other.limbs.len())
            .then_with(|| self.limbs.iter().rev().cmp(other.limbs.iter().rev()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arithmetic_agrees_with_u128() {
        let vals = [
            0u64,
            1,
            7,
            0xffff_ffff,
            1 << 32,
            u64::MAX,
            0x1234_5678_9abc_def0,
        ];
        for &a in &vals {
            for &b in &vals {
                let (x, y) = (BigUint::from_u64(a), BigUint::from_u64(b));
                let p = x.mul(&y);
                let want = u128::from(a) * u128::from(b);
                let (lo, _) = p.shr_sticky(0);
                assert_eq!(lo, p);
                let (hi, _) = p.shr_sticky(64);
                assert_eq!(hi.to_u64(), Some((want >> 64) as u64));
                let s = x.add(&y);
                assert_eq!(
                    s.shr_sticky(1).0.to_u64(),
                    Some(((u128::from(a) + u128::from(b)) >> 1) as u64)
                );
                if a >= b {
                    assert_eq!(x.sub(&y).to_u64(), Some(a - b));
                }
                assert_eq!(x.cmp(&y), a.cmp(&b));
            }
        }
        let one = BigUint::from_u64(1);
        let big = one.shl(1000);
        assert_eq!(big.bits(), 1001);
        assert_eq!(big.shr_sticky(1000), (one.clone(), false));
        assert_eq!(big.add(&one).shr_sticky(1000), (one, true));
        assert_eq!(BigUint::from_u64(10).mul_small(10).to_u64(), Some(100));
    }
}
