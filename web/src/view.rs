//! Where the world is on the canvas: a box of the world fitted to the canvas, aspect kept,
//! centred; y up in the world, down on the canvas.

use dunas::Vec2;

/// World metres to canvas pixels and back.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Pixels a metre.
    pub scale: f32,
    /// The canvas pixel of the world's origin.
    origin: [f32; 2],
}

impl View {
    /// Fits the world box `min..max` (m) into a `width × height` canvas (pixels, at least 1).
    pub fn fit(min: Vec2<f32>, max: Vec2<f32>, width: f32, height: f32) -> View {
        let (width, height) = (width.max(1.0), height.max(1.0));
        let size = max - min;
        let scale = (width / size.x).min(height / size.y);
        let centre = (min + max) * 0.5;
        View {
            scale,
            origin: [
                width / 2.0 - centre.x * scale,
                height / 2.0 + centre.y * scale,
            ],
        }
    }

    /// The canvas pixel of a world point.
    pub fn pixel(&self, p: Vec2<f32>) -> [f32; 2] {
        [
            self.origin[0] + p.x * self.scale,
            self.origin[1] - p.y * self.scale,
        ]
    }

    /// The world point under a canvas pixel.
    pub fn world(&self, x: f32, y: f32) -> Vec2<f32> {
        Vec2::new(
            (x - self.origin[0]) / self.scale,
            (self.origin[1] - y) / self.scale,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use dunas::Point as _;

    #[test]
    fn a_pixel_maps_back_to_its_world_point() {
        let view = View::fit(Vec2::new(-5.0, -3.5), Vec2::new(9.0, 3.0), 960.0, 540.0);
        let p = Vec2::new(1.25, -2.5);
        let [x, y] = view.pixel(p);
        assert!(view.world(x, y).distance(p) < 1e-5);
        // The box's corners are inside the canvas.
        for corner in [Vec2::new(-5.0, -3.5), Vec2::new(9.0, 3.0)] {
            let [x, y] = view.pixel(corner);
            assert!((-0.01..=960.01).contains(&x) && (-0.01..=540.01).contains(&y));
        }
    }
}
