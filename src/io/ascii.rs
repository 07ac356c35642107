//! ASCII drawing into a caller's byte buffer: terminal demos, debug views, a device's serial
//! console. No heap, no floats beyond the scene's own format.
//!
//! ```
//! use dunas::ascii::{Canvas, View};
//! use dunas::Vec2;
//!
//! let mut cells = [0u8; 5 * 3];
//! let mut canvas = Canvas::new(&mut cells, 5, 3)?;
//! canvas.clear(b' ');
//! // World (0, 0) at the top-left cell, one unit per cell, y up.
//! let view = View::new(Vec2::new(0.0f32, 0.0), 1.0, 1.0)?;
//! canvas.polyline(&view, &[Vec2::new(0.0, 0.0), Vec2::new(4.0, -2.0)], b'#');
//! assert_eq!(canvas.row(0), Some(&b"#    "[..]));
//! assert_eq!(canvas.row(1), Some(&b" ##  "[..]));
//! assert_eq!(canvas.row(2), Some(&b"   ##"[..]));
//! # Ok::<(), dunas::Error>(())
//! ```

use crate::error::invalid;
pub use crate::io::view::View;
use crate::{Error, Point};

/// Cells beyond this distance off the canvas are clamped before a line is walked, so a
/// wild point costs at most a few thousand steps.
const REACH: i32 = 4096;

/// A `width × height` grid of bytes borrowed from the caller, row after row.
#[derive(Debug)]
pub struct Canvas<'a> {
    cells: &'a mut [u8],
    width: usize,
    height: usize,
}

impl<'a> Canvas<'a> {
    /// A canvas over the first `width * height` bytes of `cells`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a zero size; [`Error::BufferTooSmall`] when `cells`
    /// is shorter than `width * height`.
    pub fn new(cells: &'a mut [u8], width: usize, height: usize) -> Result<Self, Error> {
        let needed = width.checked_mul(height).filter(|&n| n > 0).ok_or(invalid(
            "canvas size",
            "non-zero, width · height within usize",
        ))?;
        if cells.len() < needed {
            return Err(Error::BufferTooSmall {
                needed,
                got: cells.len(),
            });
        }
        Ok(Canvas {
            cells,
            width,
            height,
        })
    }

    /// Width in cells.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in cells.
    pub fn height(&self) -> usize {
        self.height
    }

    /// Fills every cell with `ch`.
    pub fn clear(&mut self, ch: u8) {
        self.cells[..self.width * self.height].fill(ch);
    }

    /// Sets one cell; cells off the canvas are ignored.
    pub fn plot(&mut self, col: i32, row: i32, ch: u8) {
        if col >= 0 && row >= 0 && (col as usize) < self.width && (row as usize) < self.height {
            self.cells[row as usize * self.width + col as usize] = ch;
        }
    }

    /// A straight line of `ch` between two cells (Bresenham), clipped to the canvas.
    pub fn line(&mut self, from: (i32, i32), to: (i32, i32), ch: u8) {
        let clamp = |c: (i32, i32)| (c.0.clamp(-REACH, REACH), c.1.clamp(-REACH, REACH));
        let ((mut x, mut y), (x1, y1)) = (clamp(from), clamp(to));
        let (dx, dy) = ((x1 - x).abs(), -(y1 - y).abs());
        let (sx, sy) = (if x < x1 { 1 } else { -1 }, if y < y1 { 1 } else { -1 });
        let mut err = dx + dy;
        loop {
            self.plot(x, y, ch);
            if x == x1 && y == y1 {
                break;
            }
            let e2 = 2 * err;
            if e2 >= dy {
                err += dy;
                x += sx;
            }
            if e2 <= dx {
                err += dx;
                y += sy;
            }
        }
    }

    /// Joins consecutive points with lines of `ch`.
    pub fn polyline<P: Point>(&mut self, view: &View<P>, points: &[P], ch: u8) {
        for w in points.windows(2) {
            self.line(view.cell(w[0]), view.cell(w[1]), ch);
        }
        if let [only] = points {
            let (c, r) = view.cell(*only);
            self.plot(c, r, ch);
        }
    }

    /// Marks each point with `ch`.
    pub fn points<P: Point>(&mut self, view: &View<P>, points: &[P], ch: u8) {
        for &p in points {
            let (c, r) = view.cell(p);
            self.plot(c, r, ch);
        }
    }

    /// Writes `text` from cell `(col, row)` rightwards, clipped.
    pub fn text(&mut self, col: i32, row: i32, text: &[u8]) {
        for (i, &b) in text.iter().enumerate() {
            self.plot(col.saturating_add(i as i32), row, b);
        }
    }

    /// Row `r`, or `None` past the bottom.
    pub fn row(&self, r: usize) -> Option<&[u8]> {
        (r < self.height).then(|| &self.cells[r * self.width..(r + 1) * self.width])
    }

    /// The rows, top to bottom.
    pub fn rows(&self) -> impl Iterator<Item = &[u8]> {
        self.cells[..self.width * self.height].chunks(self.width)
    }
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::Vec2;

    #[test]
    fn lines_clip_and_wild_points_are_cheap() {
        let mut cells = [b'.'; 4 * 2];
        let mut c = Canvas::new(&mut cells, 4, 2).unwrap();
        c.line((-10, 0), (10, 0), b'-');
        assert_eq!(c.row(0), Some(&b"----"[..]));
        c.line((0, 1), (i32::MAX, 1), b'=');
        assert_eq!(c.row(1), Some(&b"===="[..]));
        let view = View::new(Vec2::new(0.0f32, 0.0), 1.0, 1.0).unwrap();
        c.polyline(
            &view,
            &[Vec2::new(1e30, -1e30), Vec2::new(-1e30, 1e30)],
            b'x',
        );
        c.points(&view, &[Vec2::new(f32::NAN, 0.0)], b'n'); // NaN maps to cell 0
        assert_eq!(c.row(0).unwrap()[0], b'n');
    }

    #[test]
    fn construction_errors() {
        let mut cells = [0u8; 4];
        assert_eq!(
            Canvas::new(&mut cells, 3, 2).err(),
            Some(Error::BufferTooSmall { needed: 6, got: 4 })
        );
        assert!(matches!(
            Canvas::new(&mut cells, 0, 2).err(),
            Some(Error::InvalidParameter { .. })
        ));
        assert!(View::new(Vec2::new(0.0f32, 0.0), 0.0, 1.0).is_err());
    }
}
