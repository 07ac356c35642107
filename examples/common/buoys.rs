//! Lifebuoys afloat in the harbour: closed cloths wrapped into tori (`Torus`) blown up by
//! the gas inside them (`force::Pressure`), held up by the sea under them and drawn
//! as closed smooth surfaces, banded red and white.

use crate::boats::{Camera, arr, fleet_camera, shade};
use crate::raster::Image;
use crate::sea::Harbour;
use dunas::force::{Accelerations, Bodies, ForceField, Pressure};
use dunas::spring::Material;
use dunas::surface::SurfaceTable;
use dunas::{Settings, Smoothing, Torus, Vec3};

/// Particles round the ring and round the tube; drawn points each way (4 a span, and the
/// closing point).
const U: usize = 12;
const V: usize = 8;
const NU: usize = 4 * U + 1;
const NV: usize = 4 * V + 1;
/// A lifebuoy's ring and tube radii (m), mass (kg) and gas pressure (N/m²).
const RING: f32 = 0.5;
const TUBE: f32 = 0.16;
const MASS: f32 = 8.0;
/// The water's drag on a particle under water (N·s/m).
const DRAG: f32 = 3.0;
const PRESSURE: f32 = 300.0;
const DENSITY: f32 = 1025.0;
const RED: [f32; 3] = [200.0, 40.0, 30.0];
const WHITE: [f32; 3] = [235.0, 232.0, 222.0];

/// A lifebuoy and the gas inside it.
pub struct Buoy {
    pub body: Torus<f32, U, V>,
    gas: Pressure<f32>,
}

/// The sea's hold on a buoy: each particle's share of the buoy's volume, under water by
/// how far the particle is below the surface (a plane through the sea's height and slopes
/// under the buoy; none at the surface, all a tube's radius down), is pushed up by the
/// water it displaces and slowed by the water's drag.
struct Afloat {
    /// Surface height at the buoy's centre `(x, z)`, and its slopes along x and z.
    plane: (f32, f32, f32, f32, f32),
    /// A particle's share of the buoy's volume (m³).
    share: f32,
}

impl ForceField<Vec3<f32>> for Afloat {
    fn apply(
        &mut self,
        _: f32,
        bodies: &Bodies<'_, Vec3<f32>>,
        out: &mut Accelerations<'_, Vec3<f32>>,
    ) {
        let (h, x0, z0, sx, sz) = self.plane;
        for (i, (p, v)) in bodies.pos.iter().zip(bodies.vel).enumerate() {
            let depth = h + sx * (p.x - x0) + sz * (p.z - z0) - p.y;
            let wet = (depth / TUBE).clamp(0.0, 1.0);
            if wet > 0.0 {
                let lift = DENSITY * 9.81 * self.share * wet;
                out.add_force(i, Vec3::new(0.0, lift, 0.0) - *v * (DRAG * wet));
            }
        }
    }
}

/// Three lifebuoys between the camera and the fleet's first row, lying flat on the sea's surface.
pub fn buoys(harbour: &Harbour) -> Vec<Buoy> {
    let settings = Settings {
        gravity: Vec3::new(0.0, -9.81, 0.0),
        damping: 0.05,
        ..Settings::default()
    };
    let material = |k: f32| Material {
        stiffness: k,
        damping: 0.5,
    };
    let springs = [material(3000.0), material(1200.0), material(300.0)];
    [(-4.5, 14.6), (4.6, 15.2), (13.4, 14.9)]
        .into_iter()
        .map(|(x, z)| {
            let [surface, _, _] = harbour.surface_plane(x, z);
            let body = Torus::new(
                Vec3::new(x, surface + TUBE, z),
                RING,
                TUBE,
                MASS,
                springs,
                settings,
            )
            .expect("a valid lifebuoy");
            let gas = Pressure::at(PRESSURE, body.volume()).expect("a valid gas");
            Buoy { body, gas }
        })
        .collect()
}

impl Buoy {
    /// Where the buoy is, across and away: its particles' mean.
    fn centre(&self) -> Vec3<f32> {
        let x = self.body.positions();
        x.iter().fold(Vec3::default(), |s, &p| s + p) * (1.0 / x.len() as f32)
    }

    /// Steps the buoy by `dt` seconds on the harbour's sea.
    pub fn step(&mut self, dt: f32, harbour: &Harbour) -> Result<(), String> {
        let c = self.centre();
        let [h, sx, sz] = harbour.surface_plane(c.x, c.z);
        let share = self.body.volume() / (U * V) as f32;
        let mut forces = (
            &mut self.gas,
            Afloat {
                plane: (h, c.x, c.z, sx, sz),
                share,
            },
        );
        self.body
            .step_with(dt, &mut forces)
            .map(drop)
            .map_err(|e| e.to_string())
    }

    /// Draws the buoy into `img` (a `w × h` fleet picture) through the fleet's camera at its
    /// place, shaded with its surface normals, in eight red and white bands.
    pub fn draw(&self, img: &mut Image, tables: &Tables) {
        let c = self.centre();
        // Seen from the fleet's pinhole, 6 m up: looking down on it by the sight line's angle.
        let cam = Camera {
            pitch: (6.0 / c.z).atan(),
            ..fleet_camera(img.width, img.height, [c.x, c.z], 0.0)
        };
        let (mut pos, mut nor) = (
            vec![Vec3::default(); NU * NV],
            vec![Vec3::default(); NU * NV],
        );
        if self
            .body
            .draw(&tables.0, &tables.1, &mut pos, &mut nor)
            .is_err()
        {
            return;
        }
        let local = |p: Vec3<f32>| cam.project([p.x - c.x, p.y, p.z - c.z]);
        let screen: Vec<[f32; 3]> = pos.iter().map(|&p| local(p)).collect();
        // Eight bands round the ring, each cell's colour its band's.
        img.grid(&screen, NU, |cell, p| {
            let band = (cell % NU) * 8 / (NU - 1);
            shade(
                arr(nor[p]),
                if band.is_multiple_of(2) { RED } else { WHITE },
            )
        });
    }
}

/// The closed tables a lifebuoy is drawn with, round its ring and round its tube.
pub type Tables = (SurfaceTable<f32, U, NU>, SurfaceTable<f32, V, NV>);

/// The [`Tables`], built once.
pub fn tables() -> Tables {
    (
        SurfaceTable::closed(Smoothing::CatmullRom, NU).expect("a valid table"),
        SurfaceTable::closed(Smoothing::CatmullRom, NV).expect("a valid table"),
    )
}
