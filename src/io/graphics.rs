//! Drawing into any [embedded-graphics](embedded_graphics) `DrawTarget` (feature
//! `embedded-graphics`): a sampled curve is a [`Curve`] primitive and a sampled patch a
//! [`Wireframe`], styled and drawn the way that crate draws its own shapes. Positions map to
//! pixels through the same [`View`] as the ASCII canvas.
//!
//! ```
//! use dunas::{Bezier, Vec2, View, graphics::Curve};
//! use embedded_graphics::{mock_display::MockDisplay, pixelcolor::BinaryColor, prelude::*};
//! use embedded_graphics::primitives::PrimitiveStyle;
//!
//! let c = Bezier::new([Vec2::new(0.0f32, 0.0), Vec2::new(2.0, -6.0), Vec2::new(4.0, 0.0)])?;
//! let mut pts = [Vec2::default(); 5];
//! c.sample(&mut pts)?;
//! let view = View::new(Vec2::new(0.0f32, 0.0), 1.0, 1.0)?;
//! let mut display = MockDisplay::new(); // refuses a pixel drawn twice
//! Curve::new(&pts, view)
//!     .into_styled(PrimitiveStyle::with_stroke(BinaryColor::On, 1))
//!     .draw(&mut display)
//!     .unwrap();
//! // Samples at (0,0), (1,2), (2,3), (3,2), (4,0) in pixels (y grows downwards), joined.
//! display.assert_pattern(&[
//!     "#   #",
//!     "#  # ",
//!     " # # ",
//!     "  #  ",
//! ]);
//! # Ok::<(), dunas::Error>(())
//! ```

use embedded_graphics::Pixel as ColoredPixel;
use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::{Dimensions, Point as Pixel};
use embedded_graphics::pixelcolor::PixelColor;
use embedded_graphics::primitives::{
    Line, PointsIter, Primitive, PrimitiveStyle, Rectangle, StyledDimensions, StyledDrawable,
};

use crate::Point;
use crate::View;

fn pixel<P: Point>(view: &View<P>, p: P) -> Pixel {
    let (x, y) = view.cell(p);
    Pixel::new(x, y)
}

/// The smallest rectangle holding the pixels of `points` (empty for no points).
fn pixel_box<P: Point>(view: &View<P>, points: impl Iterator<Item = P>) -> Rectangle {
    let mut corners: Option<(Pixel, Pixel)> = None;
    for p in points.map(|p| pixel(view, p)) {
        corners = Some(match corners {
            None => (p, p),
            Some((lo, hi)) => (lo.component_min(p), hi.component_max(p)),
        });
    }
    corners.map_or(Rectangle::zero(), |(lo, hi)| {
        Rectangle::with_corners(lo, hi)
    })
}

/// `bounds` grown by half the stroke on every side.
fn widened<C: PixelColor>(bounds: Rectangle, style: &PrimitiveStyle<C>) -> Rectangle {
    bounds.offset((style.stroke_width / 2).min(i32::MAX as u32) as i32)
}

/// Paints `color` along the pixels from `a` to `b`, skipping the first pixel when `skip_start`
/// and the last when `skip_end` (a joint another segment paints).
fn thin_segment<D: DrawTarget>(
    target: &mut D,
    (a, b): (Pixel, Pixel),
    (skip_start, skip_end): (bool, bool),
    color: D::Color,
) -> Result<(), D::Error> {
    let mut pixels = Line::new(a, b)
        .points()
        .skip(usize::from(skip_start))
        .peekable();
    target.draw_iter(core::iter::from_fn(move || {
        let p = pixels.next()?;
        let last = pixels.peek().is_none();
        (!(skip_end && last)).then_some(ColoredPixel(p, color))
    }))
}

/// Strokes the polyline through `pixels`. A 1-pixel stroke paints every pixel once where the
/// polyline does not cross itself: each joint and each repeated point once. A wider stroke
/// draws each segment as a styled [`Line`] (joints overlap).
fn stroke<D: DrawTarget>(
    target: &mut D,
    style: &PrimitiveStyle<D::Color>,
    mut pixels: impl Iterator<Item = Pixel>,
    skip_ends: bool,
) -> Result<(), D::Error> {
    let (Some(color), width) = (style.stroke_color, style.stroke_width) else {
        return Ok(());
    };
    let Some(mut from) = pixels.next() else {
        return Ok(());
    };
    if width > 1 {
        return wide(target, style, from, pixels);
    }
    let mut first = true;
    for to in pixels {
        if to == from {
            continue;
        }
        if width == 1 {
            thin_segment(target, (from, to), (!first || skip_ends, skip_ends), color)?;
        }
        (from, first) = (to, false);
    }
    if first && !skip_ends && width > 0 {
        // Every point on one pixel: a dot.
        target.draw_iter(core::iter::once(ColoredPixel(from, color)))?;
    }
    Ok(())
}

/// Most distinct pixels of one wide-stroked run: a longer line is drawn in runs of this many,
/// each sharing its first point with the last run's end.
const WIDE_RUN: usize = 128;

/// A stroke wider than one pixel: every pixel whose centre is within half the width of the
/// polyline through `from` and `pixels`, each painted once (a run of [`WIDE_RUN`] distinct
/// pixels at a time). Cost: one distance test a segment for each pixel of the run's box.
fn wide<D: DrawTarget>(
    target: &mut D,
    style: &PrimitiveStyle<D::Color>,
    from: Pixel,
    pixels: impl Iterator<Item = Pixel>,
) -> Result<(), D::Error> {
    let mut run = [from; WIDE_RUN];
    let mut len = 1;
    for to in pixels {
        if to == run[len - 1] {
            continue;
        }
        run[len] = to;
        len += 1;
        if len == WIDE_RUN {
            fill_wide(target, style, &run)?;
            (run[0], len) = (to, 1);
        }
    }
    fill_wide(target, style, &run[..len])
}

/// Paints the pixels within half the stroke width of the polyline through `run`.
fn fill_wide<D: DrawTarget>(
    target: &mut D,
    style: &PrimitiveStyle<D::Color>,
    run: &[Pixel],
) -> Result<(), D::Error> {
    let (Some(color), Some(first)) = (style.stroke_color, run.first()) else {
        return Ok(());
    };
    let half = style.stroke_width as f32 * 0.5;
    let reach = style.stroke_width.div_ceil(2) as i32;
    let (mut lo, mut hi) = (*first, *first);
    for p in run {
        (lo.x, lo.y) = (lo.x.min(p.x), lo.y.min(p.y));
        (hi.x, hi.y) = (hi.x.max(p.x), hi.y.max(p.y));
    }
    let near = |x: i32, y: i32| {
        let segments = run.windows(2).map(|w| (w[0], w[1]));
        let mut segments = segments.chain((run.len() == 1).then_some((run[0], run[0])));
        segments.any(|(a, b)| {
            let (px, py) = ((x - a.x) as f32, (y - a.y) as f32);
            let (dx, dy) = ((b.x - a.x) as f32, (b.y - a.y) as f32);
            let span = dx * dx + dy * dy;
            let t = if span > 0.0 {
                ((px * dx + py * dy) / span).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let (ex, ey) = (px - t * dx, py - t * dy);
            ex * ex + ey * ey <= half * half
        })
    };
    let rows = (lo.y - reach)..=(hi.y + reach);
    let painted = rows.flat_map(|y| ((lo.x - reach)..=(hi.x + reach)).map(move |x| (x, y)));
    target.draw_iter(
        painted
            .filter(|&(x, y)| near(x, y))
            .map(|(x, y)| ColoredPixel(Pixel::new(x, y), color)),
    )
}

/// Sampled points of a curve seen through a [`View`]: an embedded-graphics primitive, drawn
/// as the polyline through them with a [`PrimitiveStyle`]'s stroke (the fill is ignored).
///
/// A stroke paints each pixel once, joints included, unless the curve crosses itself. A wider
/// stroke paints the pixels whose centres lie within half its width of the polyline, 128
/// distinct pixels of it at a time (a longer curve may paint around those joints twice).
#[derive(Clone, Copy, Debug)]
pub struct Curve<'a, P: Point> {
    points: &'a [P],
    view: View<P>,
}

impl<'a, P: Point> Curve<'a, P> {
    /// The curve through `points` (for example what [`crate::Rope::sample`] wrote).
    pub fn new(points: &'a [P], view: View<P>) -> Self {
        Curve { points, view }
    }
}

impl<P: Point> Dimensions for Curve<'_, P> {
    fn bounding_box(&self) -> Rectangle {
        pixel_box(&self.view, self.points.iter().copied())
    }
}

impl<P: Point> Primitive for Curve<'_, P> {}

impl<P: Point, C: PixelColor> StyledDimensions<PrimitiveStyle<C>> for Curve<'_, P> {
    fn styled_bounding_box(&self, style: &PrimitiveStyle<C>) -> Rectangle {
        widened(self.bounding_box(), style)
    }
}

impl<P: Point, C: PixelColor> StyledDrawable<PrimitiveStyle<C>> for Curve<'_, P> {
    type Color = C;
    type Output = ();

    fn draw_styled<D: DrawTarget<Color = C>>(
        &self,
        style: &PrimitiveStyle<C>,
        target: &mut D,
    ) -> Result<(), D::Error> {
        let view = &self.view;
        stroke(
            target,
            style,
            self.points.iter().map(|&p| pixel(view, p)),
            false,
        )
    }
}

/// An `nu × nv` grid of sampled points (laid out as
/// [`Patch::sample_grid`](crate::Patch::sample_grid) writes them) seen through a [`View`]: its
/// rows and columns drawn with a [`PrimitiveStyle`]'s stroke. A grid with fewer points than
/// `nu × nv` draws the rows and columns it has.
///
/// With a 1-pixel stroke, rows paint the grid points and columns paint only between them, so
/// a grid whose lines do not cross elsewhere paints each pixel once.
#[derive(Clone, Copy, Debug)]
pub struct Wireframe<'a, P: Point> {
    grid: &'a [P],
    nu: usize,
    nv: usize,
    view: View<P>,
}

impl<'a, P: Point> Wireframe<'a, P> {
    /// The wireframe of `grid`, `nu` points a row, `nv` rows.
    pub fn new(grid: &'a [P], nu: usize, nv: usize, view: View<P>) -> Self {
        Wireframe { grid, nu, nv, view }
    }

    /// The points present: at most `nu × nv`, whole rows only when `nu > 0`.
    fn present(&self) -> &'a [P] {
        let len = self.nu.saturating_mul(self.nv).min(self.grid.len());
        &self.grid[..len]
    }
}

impl<P: Point> Dimensions for Wireframe<'_, P> {
    fn bounding_box(&self) -> Rectangle {
        pixel_box(&self.view, self.present().iter().copied())
    }
}

impl<P: Point> Primitive for Wireframe<'_, P> {}

impl<P: Point, C: PixelColor> StyledDimensions<PrimitiveStyle<C>> for Wireframe<'_, P> {
    fn styled_bounding_box(&self, style: &PrimitiveStyle<C>) -> Rectangle {
        widened(self.bounding_box(), style)
    }
}

impl<P: Point, C: PixelColor> StyledDrawable<PrimitiveStyle<C>> for Wireframe<'_, P> {
    type Color = C;
    type Output = ();

    fn draw_styled<D: DrawTarget<Color = C>>(
        &self,
        style: &PrimitiveStyle<C>,
        target: &mut D,
    ) -> Result<(), D::Error> {
        let (grid, view, nu) = (self.present(), &self.view, self.nu);
        if nu == 0 {
            return Ok(());
        }
        for row in grid.chunks(nu) {
            stroke(target, style, row.iter().map(|&p| pixel(view, p)), false)?;
        }
        for i in 0..nu {
            let column = grid.iter().skip(i).step_by(nu).map(|&p| pixel(view, p));
            stroke(target, style, column, true)?;
        }
        Ok(())
    }
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::{Patch, Vec2, Vec3};
    use embedded_graphics::Drawable;
    use embedded_graphics::mock_display::MockDisplay;
    use embedded_graphics::pixelcolor::BinaryColor;

    fn thin() -> PrimitiveStyle<BinaryColor> {
        PrimitiveStyle::with_stroke(BinaryColor::On, 1)
    }

    #[test]
    fn a_flat_patch_draws_as_a_grid_each_pixel_once() {
        let patch = Patch::new(core::array::from_fn::<_, 2, _>(|j| {
            core::array::from_fn::<_, 2, _>(|i| Vec3::new(4.0 * i as f32, -4.0 * j as f32, 0.0))
        }))
        .unwrap();
        let mut grid = [Vec3::default(); 9];
        patch.sample_grid(3, 3, &mut grid).unwrap();
        let mut display = MockDisplay::new();
        let view = View::new(Vec3::new(0.0f32, 0.0, 0.0), 1.0, 1.0).unwrap();
        let wireframe = Wireframe::new(&grid, 3, 3, view);
        assert_eq!(
            wireframe.bounding_box(),
            Rectangle::with_corners(Pixel::new(0, 0), Pixel::new(4, 4))
        );
        wireframe.into_styled(thin()).draw(&mut display).unwrap();
        display.assert_pattern(&[
            "#####", //
            "# # #", "#####", "# # #", "#####",
        ]);
    }

    #[test]
    fn short_grids_draw_what_they_have() {
        let mut display = MockDisplay::new();
        let view = View::new(Vec2::new(0.0f32, 0.0), 1.0, 1.0).unwrap();
        let pts = [Vec2::new(0.0f32, 0.0), Vec2::new(2.0, 0.0)];
        Wireframe::new(&pts, 3, 3, view)
            .into_styled(thin())
            .draw(&mut display)
            .unwrap();
        display.assert_pattern(&["###"]);
    }

    /// A wide stroke paints each pixel of the crate's own curve once: `MockDisplay` refuses
    /// a pixel drawn twice (the segments used to overlap at every joint).
    #[test]
    fn a_wide_curve_paints_each_pixel_once() {
        use crate::Bezier;
        let c = Bezier::new([
            Vec2::new(2.0f32, 2.0),
            Vec2::new(20.0, 40.0),
            Vec2::new(40.0, -20.0),
            Vec2::new(58.0, 30.0),
        ])
        .unwrap();
        let mut pts = [Vec2::default(); 33];
        c.sample(&mut pts).unwrap();
        let view = View::new(Vec2::new(0.0f32, 45.0), 1.0, 1.0).unwrap();
        for width in [2, 3, 5] {
            let mut display = MockDisplay::new();
            Curve::new(&pts, view)
                .into_styled(PrimitiveStyle::with_stroke(BinaryColor::On, width))
                .draw(&mut display)
                .unwrap();
            assert!(display.affected_area().size.width > 50, "width {width}");
        }
    }

    #[test]
    fn repeated_points_and_dots_paint_once() {
        let view = View::new(Vec2::new(0.0f32, 0.0), 1.0, 1.0).unwrap();
        let pts = [
            Vec2::new(0.0f32, 0.0),
            Vec2::new(0.2, 0.0), // the same pixel
            Vec2::new(3.0, 0.0),
            Vec2::new(3.0, -2.0),
        ];
        let mut display = MockDisplay::new();
        Curve::new(&pts, view)
            .into_styled(thin())
            .draw(&mut display)
            .unwrap();
        display.assert_pattern(&["####", "   #", "   #"]);
        let mut dot = MockDisplay::new();
        Curve::new(&pts[..2], view)
            .into_styled(thin())
            .draw(&mut dot)
            .unwrap();
        dot.assert_pattern(&["#"]);
    }
}
