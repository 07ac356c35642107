//! Where the world meets the screen: [`View`] maps positions to cells, the characters of an
//! [`ascii`](crate::io::ascii) canvas or the pixels of an embedded-graphics display.

use crate::{Error, Point, Scalar};

/// Maps world positions to cells (a text canvas's characters, a display's pixels):
/// `top_left` is the world point at the top-left corner of cell (0, 0); `y` grows upwards
/// in the world and downwards in rows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View<P: Point> {
    top_left: P,
    inv_width: P::Scalar,
    inv_height: P::Scalar,
}

impl<P: Point> View<P> {
    /// A view with cells `cell_width × cell_height` world units wide and tall.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-positive or non-finite cell size.
    pub fn new(top_left: P, cell_width: P::Scalar, cell_height: P::Scalar) -> Result<Self, Error> {
        for c in [cell_width, cell_height] {
            crate::error::check_positive(c, "cell size")?;
        }
        Ok(View {
            top_left,
            inv_width: P::Scalar::ONE / cell_width,
            inv_height: P::Scalar::ONE / cell_height,
        })
    }

    /// The cell `(column, row)` a world point falls in (may be off the canvas).
    pub fn cell(&self, p: P) -> (i32, i32) {
        let col = ((p.coord(0) - self.top_left.coord(0)) * self.inv_width).floor_i32();
        let row = ((self.top_left.coord(1) - p.coord(1)) * self.inv_height).floor_i32();
        (col, row)
    }
}
