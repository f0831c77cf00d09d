//! The backend's scope of each pixel's box ([`BeamScope`]), kept once per box: the pixels
//! of a box share its scope, so each pixel holds only the index of its box's scope (4
//! bytes a pixel, where a scope of its own took 32, most of them empty).

use super::buffers;
use crate::beam::BeamScope;

/// Each pixel's scope (`None` for a Miss box's pixels, and where the box handed none on).
#[derive(Clone, Debug, Default)]
pub(super) struct PixelScopes {
    /// Pixel `p`'s scope is `scopes[of[p]]`, none where `of[p]` is [`PixelScopes::NONE`].
    of: Vec<u32>,
    /// The scopes of the boxes.
    scopes: Vec<BeamScope>,
}

impl PixelScopes {
    /// The index of a pixel without a scope.
    pub(super) const NONE: u32 = u32::MAX;

    /// `pixels` pixels, none with a scope yet.
    pub(super) fn none(pixels: usize) -> Self {
        Self {
            of: buffers::filled(pixels, Self::NONE),
            scopes: Vec::new(),
        }
    }

    /// Keeps `scope` and returns the index its pixels take ([`PixelScopes::NONE`] for
    /// none).
    pub(super) fn keep(&mut self, scope: Option<BeamScope>) -> u32 {
        let Some(s) = scope else {
            return Self::NONE;
        };
        self.scopes.push(s);
        // An image has fewer boxes than pixels, and fewer pixels than `u32::MAX`: a
        // window's pixels are indexed by `u32` throughout the renderer.
        (self.scopes.len() - 1) as u32
    }

    /// Gives every pixel `p` the scope of index `of[p]` (from [`PixelScopes::keep`]).
    pub(super) fn assign(&mut self, of: Vec<u32>) {
        debug_assert!(
            of.iter()
                .all(|&i| i == Self::NONE || (i as usize) < self.scopes.len())
        );
        self.of = of;
    }

    /// Gives the pixels `pixels` the scope `scope` (kept once for all of them).
    pub(super) fn set(&mut self, pixels: impl Iterator<Item = usize>, scope: Option<BeamScope>) {
        let index = self.keep(scope);
        for p in pixels {
            self.of[p] = index;
        }
    }

    /// Pixel `p`'s scope.
    #[inline]
    pub(super) fn get(&self, p: usize) -> Option<&BeamScope> {
        match self.of[p] {
            Self::NONE => None,
            k => Some(&self.scopes[k as usize]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use implicit_expr::{Context, Tape};
    use interval_core::Interval;

    fn scope(t: f64) -> BeamScope {
        let mut ctx = Context::new();
        let x = ctx.x();
        BeamScope {
            tape: Tape::new(&ctx, &[x]).unwrap(),
            t: Interval::new(t, t + 1.0).unwrap(),
            escalated: false,
        }
    }

    #[test]
    fn pixels_share_the_scope_of_their_box() {
        let mut s = PixelScopes::none(6);
        s.set([0, 1, 4].into_iter(), Some(scope(1.0)));
        s.set([2].into_iter(), Some(scope(2.0)));
        s.set([3].into_iter(), None);
        let t = |s: &PixelScopes, p| s.get(p).map(|s| s.t.inf());
        assert_eq!(
            (0..6).map(|p| t(&s, p)).collect::<Vec<_>>(),
            [Some(1.0), Some(1.0), Some(2.0), None, Some(1.0), None]
        );
        // Set again, a pixel takes the new scope.
        s.set([4].into_iter(), Some(scope(3.0)));
        assert_eq!(t(&s, 4), Some(3.0));
        assert_eq!(t(&s, 0), Some(1.0));
        let mut parts = PixelScopes::default();
        parts.keep(Some(scope(5.0)));
        let kept = parts.keep(Some(scope(6.0)));
        let none = parts.keep(None);
        parts.assign(vec![kept, none]);
        assert_eq!(parts.get(0).map(|s| s.t.inf()), Some(6.0));
        assert!(parts.get(1).is_none());
    }
}
