//! The backend's scope of each pixel's box ([`BeamScope`]), kept once per box: the pixels
//! of a box share its scope, so each pixel holds only the index of its box's scope (4
//! bytes a pixel, where a scope of its own took 32, most of them empty).

use crate::beam::BeamScope;

/// The index of a pixel without a scope.
const NONE: u32 = u32::MAX;

/// Each pixel's scope (`None` for a Miss box's pixels, and where the box handed none on).
#[derive(Clone, Debug, Default)]
pub(super) struct PixelScopes {
    /// Pixel `p`'s scope is `scopes[of[p]]`, none where `of[p]` is [`NONE`].
    of: Vec<u32>,
    /// The scopes of the boxes.
    scopes: Vec<BeamScope>,
}

impl PixelScopes {
    /// `pixels` pixels, none with a scope yet.
    pub(super) fn none(pixels: usize) -> Self {
        Self {
            of: vec![NONE; pixels],
            scopes: Vec::new(),
        }
    }

    /// The pixels whose scopes are `scopes[of[p]]`, each `of[p]` made by
    /// [`PixelScopes::index`] (`index(None)`: the pixel has none).
    pub(super) fn from_parts(of: Vec<u32>, scopes: Vec<BeamScope>) -> Self {
        debug_assert!(of.iter().all(|&i| i == NONE || (i as usize) < scopes.len()));
        Self { of, scopes }
    }

    /// The index to give, in [`PixelScopes::from_parts`], to the pixels whose scope is the
    /// `k`-th of the list (`None`: no scope).
    pub(super) fn index(k: Option<usize>) -> u32 {
        // An image has fewer boxes than pixels, and fewer pixels than `u32::MAX`: a
        // window's pixels are indexed by `u32` throughout the renderer.
        k.map_or(NONE, |k| k as u32)
    }

    /// Gives the pixels `pixels` the scope `scope` (kept once for all of them).
    pub(super) fn set(&mut self, pixels: impl Iterator<Item = usize>, scope: Option<BeamScope>) {
        let index = match scope {
            Some(s) => {
                self.scopes.push(s);
                Self::index(Some(self.scopes.len() - 1))
            }
            None => NONE,
        };
        for p in pixels {
            self.of[p] = index;
        }
    }

    /// Pixel `p`'s scope.
    #[inline]
    pub(super) fn get(&self, p: usize) -> Option<&BeamScope> {
        match self.of[p] {
            NONE => None,
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
        let parts = PixelScopes::from_parts(
            vec![PixelScopes::index(Some(1)), PixelScopes::index(None)],
            vec![scope(5.0), scope(6.0)],
        );
        assert_eq!(parts.get(0).map(|s| s.t.inf()), Some(6.0));
        assert!(parts.get(1).is_none());
    }
}
