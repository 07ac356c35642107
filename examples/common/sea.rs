//! The boat scene's sea: a grid of water columns (`water::Sea`) with a swell, the fleet's
//! hulls floating on it and making waves, how a boat rides it, and the sea drawn as a smooth
//! shaded surface through a pinhole camera.

use crate::boats::{Boat, Camera, DEPTH_PER_METRE, LIGHT, SEA, SKY, fleet_view, lambert};
use crate::raster::Image;
use dunas::surface::SurfaceTable;
use dunas::water::{Hull, Sea};
use dunas::{Point, Smoothing, Vec3};

/// Columns a side, their spacing (m) and the sea's corner: 96 m square, from 6 m in front
/// of the camera.
pub const SIDE: usize = 32;
const SPACING: f32 = 3.0;
const CORNER: (f32, f32) = (-46.5, 6.0);
/// Drawn points a side (Catmull-Rom through every column, one point between).
pub const DRAWN: usize = 2 * SIDE - 1;
/// Hulls the sea carries: the fleet's, the others parked off the sea.
pub const HULLS: usize = 128;
/// A hull's footprint across and along, its height (m) and its mass (kg).
const HULL: (f32, f32, f32) = (3.0, 3.0, 0.55);
const HULL_MASS: f32 = 900.0;
const DENSITY: f32 = 1025.0;
/// The camera's height above the still sea (m), as `fleet_camera`'s.
const EYE: f32 = 6.0;

/// The sea and its hulls.
pub struct Harbour {
    pub sea: Sea<f32, SIDE, SIDE>,
    pub hulls: [Hull<f32>; HULLS],
    table: SurfaceTable<f32, SIDE, DRAWN>,
}

impl Harbour {
    /// A sea with a swell of three standing waves (up to 1.6 m from trough to crest), waves
    /// at 6 m/s, calming slowly; a hull under each boat, at rest where Archimedes puts it.
    pub fn new(boats: &[Boat]) -> Result<Harbour, String> {
        if boats.len() > HULLS {
            return Err(format!("at most {HULLS} boats ride the sea"));
        }
        let mut sea = Sea::new(CORNER, SPACING, 0.0, 6.0, DENSITY)
            .and_then(|s| s.with_damping(0.02))
            .map_err(|e| e.to_string())?;
        let mode = |m: f32, n: f32, i: usize, j: usize| {
            let phase = |k: f32, i: usize| {
                (std::f32::consts::PI * k * (i as f32 + 0.5) / SIDE as f32).cos()
            };
            phase(m, i) * phase(n, j)
        };
        for j in 0..SIDE {
            for i in 0..SIDE {
                let h = 0.35 * mode(5.0, 9.0, i, j)
                    + 0.3 * mode(11.0, 4.0, i, j)
                    + 0.15 * mode(14.0, 17.0, i, j);
                sea.set_height(i, j, h).map_err(|e| e.to_string())?;
            }
        }
        let (width, length, _) = HULL;
        let draft = HULL_MASS / (DENSITY * width * length);
        let parked = (1.0e4, 1.0e4);
        let hulls: Result<Vec<Hull<f32>>, _> = (0..HULLS)
            .map(|k| {
                let at = boats.get(k).map_or(parked, |b| (b.at[0], b.at[1]));
                Hull::new(at, -draft, HULL, HULL_MASS)
            })
            .collect();
        let hulls = hulls
            .map_err(|e| e.to_string())?
            .try_into()
            .map_err(|_| "a hull a slot".to_string())?;
        let table = SurfaceTable::new(Smoothing::CatmullRom, DRAWN).map_err(|e| e.to_string())?;
        Ok(Harbour { sea, hulls, table })
    }

    /// Steps the sea and its hulls by `dt` seconds.
    pub fn step(&mut self, dt: f32) -> Result<(), String> {
        self.sea
            .step(dt, 9.81, &mut self.hulls)
            .map(drop)
            .map_err(|e| e.to_string())
    }

    /// How boat `k` rides the sea: its heave (its hull's rise from where it floats on still
    /// water) and the surface's slopes across and along under it, for `Camera::lift`.
    pub fn lift(&self, k: usize) -> [f32; 3] {
        let hull = self.hulls[k];
        let draft = HULL_MASS / (DENSITY * hull.width * hull.length);
        let size = (hull.width, hull.length);
        let under = |dx: f32, dz: f32| self.sea.surface_under((hull.x + dx, hull.z + dz), size);
        let d = SPACING;
        let slope = |a: f32, b: f32| ((a - b) / (2.0 * d)).clamp(-0.2, 0.2);
        [
            hull.bottom + draft,
            slope(under(d, 0.0), under(-d, 0.0)),
            slope(under(0.0, d), under(0.0, -d)),
        ]
    }

    /// The sea's surface under `(x, z)` as a plane: its mean height over a spacing's square
    /// there, and its slopes along x and z (for what floats there and is not a hull).
    pub fn surface_plane(&self, x: f32, z: f32) -> [f32; 3] {
        let d = SPACING;
        let under = |dx: f32, dz: f32| self.sea.surface_under((x + dx, z + dz), (d, d));
        [
            under(0.0, 0.0),
            (under(d, 0.0) - under(-d, 0.0)) / (2.0 * d),
            (under(0.0, d) - under(0.0, -d)) / (2.0 * d),
        ]
    }

    /// The sea drawn into `img` (depth-tested with the boats' cameras): its surface through
    /// every column, Lambert-shaded with its normals, paler with distance, seen from a
    /// pinhole `EYE` metres up at the origin looking along z.
    pub fn draw(&self, img: &mut Image) {
        let w = img.width as f32;
        let (horizon, focal) = fleet_view(img.height);
        let (mut points, mut normals) = (
            vec![Vec3::default(); DRAWN * DRAWN],
            vec![Vec3::default(); DRAWN * DRAWN],
        );
        if self
            .sea
            .draw(&self.table, &self.table, &mut points, &mut normals)
            .is_err()
        {
            return;
        }
        let light = {
            let l = Vec3::new(LIGHT[0], LIGHT[1], LIGHT[2]);
            let l = l * (1.0 / (l.x * l.x + l.y * l.y + l.z * l.z).sqrt());
            [l.x, l.y, l.z]
        };
        let screen: Vec<[f32; 3]> = points
            .iter()
            .map(|p| {
                [
                    w / 2.0 + focal * p.x / p.z,
                    horizon + focal * (EYE - p.y) / p.z,
                    p.z * DEPTH_PER_METRE,
                ]
            })
            .collect();
        // Water's colour: its own deep blue, lit, mixed with the sky it reflects (more at a
        // glancing view, Schlick's Fresnel term) and the sun's glint.
        let colour = |k: usize| {
            let (p, n) = (points[k], normals[k]);
            let to_eye = Vec3::new(-p.x, EYE - p.y, -p.z);
            let v: Vec3<f32> = to_eye * (1.0 / to_eye.dot(to_eye).sqrt());
            let nv = n.dot(v).clamp(0.0, 1.0);
            let fresnel = 0.02 + 0.98 * (1.0 - nv).powi(5);
            let deep = lambert([n.x, n.y, n.z], light, SEA.map(|c| c * 0.8));
            let reflected = n * (2.0 * nv) - v;
            let glint = reflected
                .dot(Vec3::new(light[0], light[1], light[2]))
                .max(0.0)
                .powi(60);
            [0, 1, 2].map(|c| {
                let sky = SKY[c] as f32;
                deep[c] * (1.0 - fresnel) + sky * fresnel + 255.0 * glint
            })
        };
        let colours: Vec<[f32; 3]> = (0..points.len()).map(colour).collect();
        // Past the last row, to the horizon: from its mean colour to the sky's.
        let last = &colours[(DRAWN - 1) * DRAWN..];
        let far = [0, 1, 2].map(|c| last.iter().map(|k| k[c]).sum::<f32>() / DRAWN as f32);
        let edge = horizon + focal * EYE / (CORNER.1 + SPACING * (SIDE - 1) as f32);
        for y in horizon.max(0.0) as usize..=edge.ceil() as usize {
            let t = ((y as f32 - horizon) / (edge - horizon)).clamp(0.0, 1.0);
            let c = [0, 1, 2].map(|c| (SKY[c] as f32 * (1.0 - t) + far[c] * t) as u8);
            img.line([0.0, y as f32], [w, y as f32], c);
        }
        // The band is background: the boats draw over it.
        img.clear_depth();
        img.grid(&screen, DRAWN, |_, p| colours[p]);
    }
}

/// `cam` riding the sea with `lift`.
pub fn riding(mut cam: Camera, lift: [f32; 3]) -> Camera {
    cam.lift = lift;
    cam
}
