//! The rectangle of the plane that the image shows.

use std::str::FromStr;

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

impl FromStr for Region {
    type Err = String;

    /// Parses `xmin,xmax,ymin,ymax` (the `--region` option of the `render2d` example).
    ///
    /// Returns a message when a number does not parse, when there are not four of them, or
    /// when the bounds are not finite with `xmin < xmax` and `ymin < ymax`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let v: Vec<f64> = s
            .split(',')
            .map(|t| t.trim().parse::<f64>().map_err(|e| format!("'{t}': {e}")))
            .collect::<Result<_, _>>()?;
        match v[..] {
            [x0, x1, y0, y1]
                if [x0, x1, y0, y1].iter().all(|v| v.is_finite()) && x0 < x1 && y0 < y1 =>
            {
                Ok(Region { x0, x1, y0, y1 })
            }
            [_, _, _, _] => Err("need finite bounds with xmin < xmax and ymin < ymax".into()),
            _ => Err(format!(
                "need 4 numbers xmin,xmax,ymin,ymax, got {}",
                v.len()
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_four_ordered_finite_bounds() {
        assert_eq!("-1,1,-1,1".parse(), Ok(Region::default()));
        assert_eq!(
            " -2, 0.5 ,0,3".parse(),
            Ok(Region {
                x0: -2.0,
                x1: 0.5,
                y0: 0.0,
                y1: 3.0
            })
        );
        assert!(
            "1,0,0,1"
                .parse::<Region>()
                .unwrap_err()
                .contains("xmin < xmax")
        );
        assert!(
            "0,1,0,inf"
                .parse::<Region>()
                .unwrap_err()
                .contains("finite")
        );
        assert!("0,1,0".parse::<Region>().unwrap_err().contains("got 3"));
        assert!(
            "0,1,a,1"
                .parse::<Region>()
                .unwrap_err()
                .starts_with("'a': ")
        );
    }
}
