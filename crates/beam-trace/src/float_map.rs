//! One number per pixel, saved as a PFM file (the Portable Float Map: a text header
//! `Pf`, the size and a negative scale for little-endian data, then the rows of `f32`
//! values from the bottom row up), which image tools and a few lines of any language read.

use std::io::{BufWriter, Write};
use std::path::Path;

use crate::error::Error;
use crate::image::write_atomic;

/// A `width × height` map of `f32` values, row-major from the top row.
#[derive(Clone, Debug, PartialEq)]
pub struct FloatMap {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The values, row-major from the top-left pixel.
    pub values: Vec<f32>,
}

impl FloatMap {
    /// The map of `values` (row-major from the top), which must hold `width × height`.
    ///
    /// # Errors
    ///
    /// [`Error::Data`] when the count does not match.
    pub fn new(width: u32, height: u32, values: Vec<f32>) -> Result<Self, Error> {
        if values.len() != width as usize * height as usize {
            return Err(Error::Data(format!(
                "a {width} × {height} float map needs {} values, got {}",
                width as usize * height as usize,
                values.len()
            )));
        }
        Ok(Self {
            width,
            height,
            values,
        })
    }

    /// The file's bytes: the PFM header, then the rows bottom-up, little-endian.
    pub fn to_pfm(&self) -> Vec<u8> {
        let mut out = format!("Pf\n{} {}\n-1.0\n", self.width, self.height).into_bytes();
        let w = self.width as usize;
        for row in self.values.chunks(w.max(1)).rev() {
            for v in row {
                out.extend_from_slice(&v.to_le_bytes());
            }
        }
        out
    }

    /// Reads a greyscale PFM file's bytes (either byte order).
    ///
    /// # Errors
    ///
    /// [`Error::Data`] naming what is wrong with the header or the data's length.
    pub fn from_pfm(bytes: &[u8]) -> Result<Self, Error> {
        let bad = |what: &str| Error::Data(format!("not a greyscale PFM file: {what}"));
        // Three whitespace-separated header fields after the magic, then one byte.
        let mut fields = Vec::new();
        let mut at = 0;
        while fields.len() < 4 {
            while at < bytes.len() && bytes[at].is_ascii_whitespace() {
                at += 1;
            }
            let start = at;
            while at < bytes.len() && !bytes[at].is_ascii_whitespace() {
                at += 1;
            }
            if start == at {
                return Err(bad("the header ends early"));
            }
            fields.push(String::from_utf8_lossy(&bytes[start..at]).into_owned());
            if fields.len() == 4 {
                at += 1;
            }
        }
        if fields[0] != "Pf" {
            return Err(bad(&format!("the magic is '{}', not 'Pf'", fields[0])));
        }
        let size = |s: &str| s.parse::<u32>().map_err(|_| bad(&format!("size '{s}'")));
        let (width, height) = (size(&fields[1])?, size(&fields[2])?);
        let scale: f32 = fields[3]
            .parse()
            .map_err(|_| bad(&format!("scale '{}'", fields[3])))?;
        let data = &bytes[at.min(bytes.len())..];
        let n = width as usize * height as usize;
        if data.len() != 4 * n {
            return Err(bad(&format!(
                "{} bytes of data for {width} × {height} values",
                data.len()
            )));
        }
        let mut values = vec![0f32; n];
        let w = width as usize;
        for (k, chunk) in data.chunks_exact(4).enumerate() {
            let b = [chunk[0], chunk[1], chunk[2], chunk[3]];
            let v = if scale < 0.0 {
                f32::from_le_bytes(b)
            } else {
                f32::from_be_bytes(b)
            };
            let (row, col) = (k / w, k % w);
            values[(height as usize - 1 - row) * w + col] = v;
        }
        Self::new(width, height, values)
    }

    /// Writes the map as a PFM file at `path`, whole or not at all.
    ///
    /// # Errors
    ///
    /// [`Error::Io`] naming the path.
    pub fn write_pfm(&self, path: &Path) -> Result<(), Error> {
        let bytes = self.to_pfm();
        write_atomic(path, |file| {
            let mut w = BufWriter::new(file);
            w.write_all(&bytes)?;
            w.flush()
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pfm_round_trips_with_rows_bottom_up() {
        let m = FloatMap::new(3, 2, vec![0.0, 0.25, 0.5, 1.0, f32::NAN, -2.0]).unwrap();
        let bytes = m.to_pfm();
        assert!(bytes.starts_with(b"Pf\n3 2\n-1.0\n"));
        // The first value stored is the bottom-left pixel.
        assert_eq!(&bytes[12..16], &1.0f32.to_le_bytes());
        let back = FloatMap::from_pfm(&bytes).unwrap();
        assert_eq!(back.width, 3);
        assert_eq!(back.values[..4], m.values[..4]);
        assert!(back.values[4].is_nan());
        assert_eq!(back.values[5], -2.0);
    }

    #[test]
    fn bad_files_and_sizes_say_what_is_wrong() {
        let e = FloatMap::new(2, 2, vec![0.0; 3]).unwrap_err().to_string();
        assert!(e.contains("needs 4 values, got 3"), "{e}");
        let e = FloatMap::from_pfm(b"PF\n1 1\n-1.0\n0000")
            .unwrap_err()
            .to_string();
        assert!(e.contains("magic"), "{e}");
        let e = FloatMap::from_pfm(b"Pf\n2 1\n-1.0\n0000")
            .unwrap_err()
            .to_string();
        assert!(e.contains("4 bytes of data for 2 × 1"), "{e}");
    }
}
