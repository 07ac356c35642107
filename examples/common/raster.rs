//! A small software rasteriser for the host examples: lines, z-buffered Gouraud triangles, a
//! simple camera, and binary PPM (P6) and PNG output.
#![allow(dead_code)]

use std::io;
use std::path::Path;

/// An RGB image with a depth buffer.
pub struct Image {
    pub width: usize,
    pub height: usize,
    pub rgb: Vec<u8>,
    depth: Vec<f32>,
}

impl Image {
    pub fn new(width: usize, height: usize, background: [u8; 3]) -> Image {
        let mut rgb = Vec::with_capacity(width * height * 3);
        for _ in 0..width * height {
            rgb.extend_from_slice(&background);
        }
        Image {
            width,
            height,
            rgb,
            depth: vec![f32::INFINITY; width * height],
        }
    }

    pub fn pixel(&self, x: usize, y: usize) -> [u8; 3] {
        let i = 3 * (y * self.width + x);
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }

    fn put(&mut self, x: i64, y: i64, z: f32, color: [u8; 3]) {
        if x < 0 || y < 0 || x as usize >= self.width || y as usize >= self.height {
            return;
        }
        let k = y as usize * self.width + x as usize;
        if z <= self.depth[k] {
            self.depth[k] = z;
            self.rgb[3 * k..3 * k + 3].copy_from_slice(&color);
        }
    }

    /// A line drawn over everything (no depth test), clipped to the image.
    pub fn line(&mut self, a: [f32; 2], b: [f32; 2], color: [u8; 3]) {
        self.line_3d(
            [a[0], a[1], f32::NEG_INFINITY],
            [b[0], b[1], f32::NEG_INFINITY],
            color,
        );
    }

    /// A line between two screen points with depth, depth-tested like the triangles.
    pub fn line_3d(&mut self, a: [f32; 3], b: [f32; 3], color: [u8; 3]) {
        let steps = (b[0] - a[0])
            .abs()
            .max((b[1] - a[1]).abs())
            .ceil()
            .min(4096.0) as i64;
        for s in 0..=steps {
            let t = if steps == 0 {
                0.0
            } else {
                s as f32 / steps as f32
            };
            let at = |k: usize| a[k] + (b[k] - a[k]) * t;
            // Equal depths stay exact (an infinite one would interpolate to NaN).
            let z = if a[2] == b[2] { a[2] } else { at(2) };
            self.put(at(0).round() as i64, at(1).round() as i64, z, color);
        }
    }

    /// A grid of points on screen (`screen`, rows of `columns`, `[x, y, depth]`), each cell
    /// filled as two triangles; `colour(cell, point)` is the colour at a corner `point` of
    /// cell `cell` (both flat indices), so that a cell's own colour can change at its edge.
    pub fn grid(
        &mut self,
        screen: &[[f32; 3]],
        columns: usize,
        colour: impl Fn(usize, usize) -> [f32; 3],
    ) {
        let rows = screen.len().checked_div(columns).unwrap_or(0);
        for j in 0..rows.saturating_sub(1) {
            for i in 0..columns.saturating_sub(1) {
                let k = j * columns + i;
                let q = [k, k + 1, k + columns, k + columns + 1];
                let c = |p: usize| colour(k, p);
                for t in [[q[0], q[1], q[2]], [q[1], q[3], q[2]]] {
                    self.triangle(t.map(|p| screen[p]), t.map(c));
                }
            }
        }
    }

    /// A triangle with per-vertex colours, depth-tested (smaller `z` is nearer).
    pub fn triangle(&mut self, v: [[f32; 3]; 3], colors: [[f32; 3]; 3]) {
        let area =
            (v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) - (v[2][0] - v[0][0]) * (v[1][1] - v[0][1]);
        if area.abs() < 1e-12 || !area.is_finite() {
            return;
        }
        let min_x = v
            .iter()
            .map(|p| p[0])
            .fold(f32::INFINITY, f32::min)
            .floor()
            .max(0.0) as i64;
        let max_x = v
            .iter()
            .map(|p| p[0])
            .fold(f32::NEG_INFINITY, f32::max)
            .ceil()
            .min(self.width as f32 - 1.0) as i64;
        let min_y = v
            .iter()
            .map(|p| p[1])
            .fold(f32::INFINITY, f32::min)
            .floor()
            .max(0.0) as i64;
        let max_y = v
            .iter()
            .map(|p| p[1])
            .fold(f32::NEG_INFINITY, f32::max)
            .ceil()
            .min(self.height as f32 - 1.0) as i64;
        for y in min_y..=max_y {
            for x in min_x..=max_x {
                let (px, py) = (x as f32 + 0.5, y as f32 + 0.5);
                let w0 = ((v[1][0] - px) * (v[2][1] - py) - (v[2][0] - px) * (v[1][1] - py)) / area;
                let w1 = ((v[2][0] - px) * (v[0][1] - py) - (v[0][0] - px) * (v[2][1] - py)) / area;
                let w2 = 1.0 - w0 - w1;
                if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                    continue;
                }
                let z = w0 * v[0][2] + w1 * v[1][2] + w2 * v[2][2];
                let c = |k: usize| {
                    (w0 * colors[0][k] + w1 * colors[1][k] + w2 * colors[2][k]).clamp(0.0, 255.0)
                        as u8
                };
                self.put(x, y, z, [c(0), c(1), c(2)]);
            }
        }
    }

    /// Forgets every depth, so that what was drawn so far is background.
    pub fn clear_depth(&mut self) {
        self.depth.fill(f32::INFINITY);
    }

    /// Pastes `other` with its top-left corner at `(x, y)` (clipped).
    pub fn paste(&mut self, other: &Image, x: usize, y: usize) {
        for j in 0..other.height.min(self.height.saturating_sub(y)) {
            for i in 0..other.width.min(self.width.saturating_sub(x)) {
                let (a, b) = (
                    3 * ((y + j) * self.width + x + i),
                    3 * (j * other.width + i),
                );
                self.rgb[a..a + 3].copy_from_slice(&other.rgb[b..b + 3]);
            }
        }
    }

    /// Writes the image as a PNG.
    pub fn write_png(&self, path: &Path) -> io::Result<()> {
        let file = std::io::BufWriter::new(std::fs::File::create(path)?);
        let mut encoder = png::Encoder::new(file, self.width as u32, self.height as u32);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(io::Error::other)?;
        writer.write_image_data(&self.rgb).map_err(io::Error::other)
    }

    /// The image as a binary PPM (P6).
    pub fn to_ppm(&self) -> Vec<u8> {
        let mut out = format!("P6\n{} {}\n255\n", self.width, self.height).into_bytes();
        out.extend_from_slice(&self.rgb);
        out
    }

    pub fn write_ppm(&self, path: &Path) -> io::Result<()> {
        std::fs::write(path, self.to_ppm())
    }
}
