//! Drawing into any [embedded-graphics](embedded_graphics) `DrawTarget` (feature
//! `embedded-graphics`): sampled curves as polylines, patch samples as wireframes. Positions
//! map to pixels through the same [`View`] as the ASCII canvas.
//!
//! ```
//! use dunas::{Bezier, Vec2, ascii::View, graphics};
//! use embedded_graphics::{mock_display::MockDisplay, pixelcolor::BinaryColor};
//!
//! let c = Bezier::new([Vec2::new(0.0f32, 0.0), Vec2::new(2.0, -6.0), Vec2::new(4.0, 0.0)])?;
//! let mut pts = [Vec2::default(); 5];
//! c.sample(&mut pts)?;
//! let mut display = MockDisplay::new();
//! display.set_allow_overdraw(true);
//! let view = View::new(Vec2::new(0.0f32, 0.0), 1.0, 1.0)?;
//! graphics::draw_polyline(&mut display, &view, &pts, BinaryColor::On).unwrap();
//! // Samples at (0,0), (1,2), (2,3), (3,2), (4,0) in pixels (y grows downwards), joined.
//! display.assert_pattern(&[
//!     "#   #",
//!     "#  # ",
//!     " # # ",
//!     "  #  ",
//! ]);
//! # Ok::<(), dunas::Error>(())
//! ```

use embedded_graphics::Drawable;
use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::Point as Pixel;
use embedded_graphics::prelude::PixelColor;
use embedded_graphics::primitives::{Line, Primitive, PrimitiveStyle};

use crate::Point;
use crate::ascii::View;

fn pixel<P: Point>(view: &View<P>, p: P) -> Pixel {
    let (x, y) = view.cell(p);
    Pixel::new(x, y)
}

/// Joins consecutive `points` with 1-pixel lines of `color`.
///
/// # Errors
/// The target's own drawing error, at the first segment that fails.
pub fn draw_polyline<P: Point, D: DrawTarget<Color = C>, C: PixelColor>(
    target: &mut D,
    view: &View<P>,
    points: &[P],
    color: C,
) -> Result<(), D::Error> {
    let style = PrimitiveStyle::with_stroke(color, 1);
    for w in points.windows(2) {
        Line::new(pixel(view, w[0]), pixel(view, w[1]))
            .into_styled(style)
            .draw(target)?;
    }
    Ok(())
}

/// Draws the rows and columns of an `nu × nv` grid of points (laid out as
/// [`Patch::sample_grid`](crate::Patch::sample_grid) writes them) as a wireframe. A grid with
/// fewer points than `nu × nv` draws what it has.
///
/// # Errors
/// The target's own drawing error, at the first line that fails.
pub fn draw_wireframe<P: Point, D: DrawTarget<Color = C>, C: PixelColor>(
    target: &mut D,
    view: &View<P>,
    grid: &[P],
    nu: usize,
    nv: usize,
    color: C,
) -> Result<(), D::Error> {
    let style = PrimitiveStyle::with_stroke(color, 1);
    let at = |i: usize, j: usize| grid.get(j * nu + i).map(|&p| pixel(view, p));
    for j in 0..nv {
        for i in 0..nu {
            let Some(here) = at(i, j) else { continue };
            for next in [
                (i + 1 < nu).then(|| at(i + 1, j)).flatten(),
                (j + 1 < nv).then(|| at(i, j + 1)).flatten(),
            ]
            .into_iter()
            .flatten()
            {
                Line::new(here, next).into_styled(style).draw(target)?;
            }
        }
    }
    Ok(())
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::{Patch, Vec3};
    use embedded_graphics::mock_display::MockDisplay;
    use embedded_graphics::pixelcolor::BinaryColor;

    #[test]
    fn a_flat_patch_draws_as_a_grid() {
        let patch = Patch::new(core::array::from_fn::<_, 2, _>(|j| {
            core::array::from_fn::<_, 2, _>(|i| Vec3::new(4.0 * i as f32, -4.0 * j as f32, 0.0))
        }))
        .unwrap();
        let mut grid = [Vec3::default(); 9];
        patch.sample_grid(3, 3, &mut grid).unwrap();
        let mut display = MockDisplay::new();
        display.set_allow_overdraw(true);
        let view = View::new(Vec3::new(0.0f32, 0.0, 0.0), 1.0, 1.0).unwrap();
        draw_wireframe(&mut display, &view, &grid, 3, 3, BinaryColor::On).unwrap();
        display.assert_pattern(&[
            "#####", //
            "# # #", "#####", "# # #", "#####",
        ]);
    }

    #[test]
    fn short_grids_draw_what_they_have() {
        let mut display = MockDisplay::new();
        display.set_allow_overdraw(true);
        let view = View::new(crate::Vec2::new(0.0f32, 0.0), 1.0, 1.0).unwrap();
        let pts = [crate::Vec2::new(0.0f32, 0.0), crate::Vec2::new(2.0, 0.0)];
        draw_wireframe(&mut display, &view, &pts, 3, 3, BinaryColor::On).unwrap();
        display.assert_pattern(&["###"]);
    }
}
