//! The boat scene on the page: the fleet of `examples/common/boats.rs`, every 8×8 sail
//! stepped once a frame (`DirectSprings`) in its gusty wind and drawn as a 12×12 smooth
//! surface, shaded, over a painted sea. A click sends a gust through the fleet.
// `.ok().expect(..)` rather than `.expect(..)`: the message is the same, and `Error`'s
// `Debug` (with the float formatting it brings, 40 KB) stays out of the browser's .wasm.
#![allow(clippy::ok_expect)]

use dunas::surface::SurfaceTable;
use dunas::{Smoothing, Vec3};

use crate::boats::{
    Boat, CANVAS, Camera, SPARS, arr, fleet, fleet_camera, fleet_view, hull, shade,
};
use crate::draw_list::{DrawList, Style};

/// Samples a side of a drawn sail.
const DRAWN: usize = 12;
/// The frame step (s).
const STEP: f32 = 1.0 / 60.0;

/// A fleet on a canvas.
pub struct Harbour {
    boats: Vec<Boat>,
    table: SurfaceTable<f32, 8, DRAWN>,
    size: [f32; 2],
    time: f32,
    /// Sail steps that hit the substep cap or were refused (none is expected: one solve a
    /// frame).
    pub slow_frames: u32,
    /// A sail's drawn points and normals, and a frame's triangles with their depths (reused).
    points: [Vec3<f32>; DRAWN * DRAWN],
    normals: [Vec3<f32>; DRAWN * DRAWN],
    triangles: Vec<(f32, [f32; 9])>,
}

impl Harbour {
    /// `boats` boats (at least 1) on a `width × height` canvas.
    pub fn new(boats: usize, width: f32, height: f32) -> Harbour {
        Harbour {
            boats: fleet(boats.max(1)),
            table: SurfaceTable::new(Smoothing::NaturalSpline, DRAWN)
                .ok()
                .expect("2..=DRAWN samples"),
            size: [width.max(1.0), height.max(1.0)],
            time: 0.0,
            slow_frames: 0,
            points: [Vec3::default(); DRAWN * DRAWN],
            normals: [Vec3::default(); DRAWN * DRAWN],
            triangles: Vec::new(),
        }
    }

    /// The canvas changed size (pixels).
    pub fn resize(&mut self, width: f32, height: f32) {
        self.size = [width.max(1.0), height.max(1.0)];
    }

    /// Simulated seconds.
    pub fn time(&self) -> f32 {
        self.time
    }

    /// One frame: every sail steps once.
    pub fn step(&mut self) {
        self.time += STEP;
        for boat in &mut self.boats {
            match boat.sail.step_with(STEP, &mut boat.wind) {
                Ok(info) => self.slow_frames += u32::from(info.slow_motion),
                // A refused step leaves the sail as it was: the boat waits a frame.
                Err(_) => self.slow_frames += 1,
            }
        }
    }

    /// A gust through the whole fleet, from now.
    pub fn gust(&mut self) {
        for boat in &mut self.boats {
            let mut air = *boat.wind.air();
            air.gust_start = boat.sail.time();
            let _ = boat.wind.set_air(air);
        }
    }

    /// The frame's records: the sea, then the boats from the farthest, each boat's
    /// triangles from its back.
    pub fn draw(&mut self, list: &mut DrawList) {
        let [w, h] = self.size;
        let (horizon, _) = fleet_view(h as usize);
        list.push(Style::Sea, &[horizon, self.time]);
        // The fleet is laid out row by row away from the camera: the last boat is the farthest.
        for boat in self.boats.iter().rev() {
            let cam = fleet_camera(w as usize, h as usize, boat.at, boat.yaw);
            self.triangles.clear();
            for (tri, base) in hull() {
                let [a, b, c] = tri.map(|p| Vec3::new(p[0], p[1], p[2]));
                let n = (b - a).cross(c - a).normalize().unwrap_or_default();
                self.triangles
                    .push(triangle(&cam, tri, shade(arr(n), base)));
            }
            let drawn = boat.sail.draw(
                &self.table,
                &self.table,
                &mut self.points,
                &mut self.normals,
            );
            if drawn.is_ok() {
                for j in 0..DRAWN - 1 {
                    for i in 0..DRAWN - 1 {
                        let k = j * DRAWN + i;
                        for q in [[k, k + 1, k + DRAWN], [k + 1, k + DRAWN + 1, k + DRAWN]] {
                            let normal = q
                                .iter()
                                .fold(Vec3::default(), |sum, &k| sum + self.normals[k]);
                            let color = shade(arr(normal.normalize().unwrap_or(normal)), CANVAS);
                            self.triangles.push(triangle(
                                &cam,
                                q.map(|k| arr(self.points[k])),
                                color,
                            ));
                        }
                    }
                }
            }
            self.triangles.sort_unstable_by(|a, b| b.0.total_cmp(&a.0));
            for (_, numbers) in &self.triangles {
                list.push(Style::Triangle, numbers);
            }
            let width = (cam.scale / 20.0).clamp(1.0, 5.0);
            for (a, b) in SPARS {
                let (a, b) = (cam.project(a), cam.project(b));
                list.push(Style::Spar, &[a[0], a[1], b[0], b[1], width]);
            }
        }
    }
}

/// A triangle's depth (its mean) and its record.
fn triangle(cam: &Camera, corners: [[f32; 3]; 3], color: [f32; 3]) -> (f32, [f32; 9]) {
    let [a, b, c] = corners.map(|p| cam.project(p));
    let depth = (a[2] + b[2] + c[2]) / 3.0;
    (
        depth,
        [
            a[0], a[1], b[0], b[1], c[0], c[1], color[0], color[1], color[2],
        ],
    )
}
