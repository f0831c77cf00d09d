//! The rectangle of the plane that the image shows.

/// The rectangle of the plane shown by the image.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Region {
    /// Left edge.
    pub x0: f64,
    /// Right edge.
    pub x1: f64,
    /// Bottom edge.
    pub y0: f64,
    /// Top edge.
    pub y1: f64,
}

impl Default for Region {
    /// `[-1, 1]²`.
    fn default() -> Self {
        Self {
            x0: -1.0,
            x1: 1.0,
            y0: -1.0,
            y1: 1.0,
        }
    }
}
