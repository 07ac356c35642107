//! The boat scene's boats, shared by `examples/cloth.rs` (PPM frames) and the browser page
//! (`web/`): a gaff-rigged sail filled by gusty wind, the hull and spars it is drawn on, the
//! fleet's layout and the camera that sees it. Metres and seconds; y up, the wind along +z.
#![allow(dead_code)]
// `.ok().expect(..)` rather than `.expect(..)`: the message is the same, and `Error`'s
// `Debug` (with the float formatting it brings, 40 KB) stays out of the browser's .wasm.
#![allow(clippy::ok_expect)]

use dunas::force::{SailWind, Wind};
use dunas::integrator::{DirectSprings, Integrator};
use dunas::spring::Material;
use dunas::{Cloth, Settings, Vec3};

pub const MAST: [u8; 3] = [90, 70, 50];
pub const CANVAS: [f32; 3] = [240.0, 232.0, 210.0];
pub const HULL: [f32; 3] = [170.0, 45.0, 40.0];
pub const DECK: [f32; 3] = [200.0, 160.0, 110.0];
pub const SKY: [u8; 3] = [160, 200, 235];
pub const SEA: [f32; 3] = [30.0, 90.0, 140.0];
/// Sunlight, from the upper left and behind the camera.
pub const LIGHT: [f32; 3] = [0.35, 0.55, -0.75];
/// A gaff-rigged sail, 3 m on the boom and 4 m on the mast, 2 kg in all: its luff on the mast
/// (column 0), its head on the gaff (row 0), its foot on the boom (the last row), its leech
/// free. Spring stiffness does not change with the grid (a membrane), so sails of any size are
/// the same cloth. The wind blows along +z with a gust every 3 s, from `phase` seconds.
/// Stepped by `integrator`.
pub fn sail<I: Integrator, const U: usize, const V: usize>(
    integrator: I,
    wind_speed: f32,
    phase: f32,
) -> (Cloth<Vec3<f32>, U, V, I>, SailWind<f32>) {
    let settings = Settings {
        gravity: Vec3::new(0.0, -9.81, 0.0),
        damping: 0.3,
        ..Settings::default()
    }
    .with_integrator(integrator);
    let materials = [(900.0, 0.6), (300.0, 0.2), (60.0, 0.05)]
        .map(|(stiffness, damping)| Material { stiffness, damping });
    let mut cloth = Cloth::rectangle(
        Vec3::new(0.0, 4.5, 0.0),
        Vec3::new(3.0, 0.0, 0.0),
        Vec3::new(0.0, -4.0, 0.0),
        2.0,
        materials,
        settings,
    )
    .ok()
    .expect("valid sail");
    cloth.pin_column(0).ok().expect("column in range");
    cloth.pin_row(0).ok().expect("row in range");
    cloth.pin_row(V - 1).ok().expect("row in range");
    let mut air = Wind::still(0.02);
    air.velocity = Vec3::new(0.0, 0.0, wind_speed);
    air.gust = Vec3::new(0.0, 0.0, 0.8 * wind_speed);
    air.gust_start = phase;
    air.gust_length = 1.5;
    air.gust_every = 3.0;
    (cloth, SailWind::new(air, 0.7).ok().expect("valid wind"))
}

pub fn arr(p: Vec3<f32>) -> [f32; 3] {
    [p.x, p.y, p.z]
}

pub fn shade(normal: [f32; 3], base: [f32; 3]) -> [f32; 3] {
    let l = Vec3::new(LIGHT[0], LIGHT[1], LIGHT[2]);
    lambert(normal, arr(l.normalize().unwrap_or(l)), base)
}

/// The hull as flat triangles (a deck and two sides down to the keel) with their base
/// colours, in the boat's frame: its bow along +x, its mast at the origin, the waterline at 0.
pub fn hull() -> [([[f32; 3]; 3], [f32; 3]); 12] {
    let v = |x: f32, y: f32, z: f32| [x, y, z];
    let (bow, mid_port, mid_star) = (v(4.4, 0.45, 0.0), v(1.6, 0.5, -0.95), v(1.6, 0.5, 0.95));
    let (stern_port, stern_star) = (v(-1.0, 0.55, -0.75), v(-1.0, 0.55, 0.75));
    let (keel_bow, keel_mid, keel_stern) = (v(3.9, 0.0, 0.0), v(1.6, 0.0, 0.0), v(-0.8, 0.0, 0.0));
    [
        ([bow, mid_port, mid_star], DECK),
        ([mid_port, stern_port, stern_star], DECK),
        ([mid_port, stern_star, mid_star], DECK),
        ([bow, mid_port, keel_bow], HULL),
        ([mid_port, keel_mid, keel_bow], HULL),
        ([mid_port, stern_port, keel_mid], HULL),
        ([stern_port, keel_stern, keel_mid], HULL),
        ([bow, mid_star, keel_bow], HULL),
        ([mid_star, keel_mid, keel_bow], HULL),
        ([mid_star, stern_star, keel_mid], HULL),
        ([stern_star, keel_stern, keel_mid], HULL),
        ([stern_port, stern_star, keel_stern], HULL),
    ]
}

/// The mast, the boom and the gaff, as segments in the boat's frame.
pub const SPARS: [([f32; 3], [f32; 3]); 3] = [
    ([0.0, 0.5, 0.0], [0.0, 5.2, 0.0]), // mast
    ([0.0, 0.5, 0.0], [3.1, 0.5, 0.0]), // boom
    ([0.0, 4.5, 0.0], [3.1, 4.5, 0.0]), // gaff
];

/// A boat of the fleet: its sail and wind, where it sails (x across, z away from the
/// camera, metres) and its heading's yaw.
pub struct Boat {
    pub sail: Cloth<Vec3<f32>, 8, 8, DirectSprings>,
    pub wind: SailWind<f32>,
    pub at: [f32; 2],
    pub yaw: f32,
}

/// The fleet on a grid of lanes, staggered, from 16 m away and 9 m more a row.
pub fn fleet(boats: usize) -> Vec<Boat> {
    let per_row = (boats as f32).sqrt().ceil() as usize;
    (0..boats)
        .map(|k| {
            let (col, row) = (k % per_row, k / per_row);
            let (sail, wind) = sail::<_, 8, 8>(
                DirectSprings::default(),
                4.0 + (k % 5) as f32 * 0.5,
                k as f32 * 0.37,
            );
            let across = (col as f32 - (per_row - 1) as f32 / 2.0) * 9.0 + (row % 2) as f32 * 4.5;
            Boat {
                sail,
                wind,
                at: [across, 16.0 + row as f32 * 9.0],
                yaw: 0.45 + 0.08 * ((k * 7) % 5) as f32,
            }
        })
        .collect()
}

/// The horizon's height on screen and the fleet camera's focal length, pixels.
pub fn fleet_view(h: usize) -> (f32, f32) {
    (h as f32 * 0.3, h as f32 * 1.6)
}

/// A weak-perspective camera for an object `at` (x across, z away): its own scale, placed
/// where a pinhole 6 m above the sea would see it; nearer objects draw over farther ones.
pub fn fleet_camera(w: usize, h: usize, at: [f32; 2], yaw: f32) -> Camera {
    let (horizon, focal) = fleet_view(h);
    let eye_height = 6.0;
    let scale = focal / at[1];
    Camera {
        yaw,
        pitch: 0.12,
        scale,
        center: [w as f32 / 2.0 + at[0] * scale, horizon + eye_height * scale],
        depth: at[1] * DEPTH_PER_METRE,
        lift: [0.0; 3],
    }
}

/// Depth units a metre: every camera's depths, so that objects drawn with cameras of their
/// own and the sea drawn in world space share one depth buffer.
pub const DEPTH_PER_METRE: f32 = 100.0;

/// An orthographic camera turned by `yaw` about the vertical axis and tilted by `pitch`,
/// mapping world units to pixels with `scale` around the image point `center`.
pub struct Camera {
    pub yaw: f32,
    pub pitch: f32,
    pub scale: f32,
    pub center: [f32; 2],
    /// Added to every depth: orders the objects of a scene drawn with a camera each.
    pub depth: f32,
    /// How the object rides a sea: its heave (metres up) and the surface's slopes across
    /// and along under it, which shear its points up where the sea is higher.
    pub lift: [f32; 3],
}

impl Camera {
    /// Screen `[x, y, depth]` of a world point (y up in the world, down on screen).
    pub fn project(&self, p: [f32; 3]) -> [f32; 3] {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        let x = cy * p[0] + sy * p[2];
        let z = -sy * p[0] + cy * p[2];
        let [heave, across, along] = self.lift;
        let up = p[1] + heave + across * x + along * z;
        let y = cp * up - sp * z;
        let depth = sp * up + cp * z;
        [
            self.center[0] + self.scale * x,
            self.center[1] - self.scale * y,
            depth * DEPTH_PER_METRE + self.depth,
        ]
    }

    /// The direction from the scene towards the camera, in world space.
    pub fn towards_viewer(&self) -> [f32; 3] {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        [sy * cp, -sp, -cy * cp]
    }
}

/// Lambert shading of a two-sided surface: ambient plus diffuse from `light` (unit vector).
pub fn lambert(normal: [f32; 3], light: [f32; 3], base: [f32; 3]) -> [f32; 3] {
    let d = (normal[0] * light[0] + normal[1] * light[1] + normal[2] * light[2]).abs();
    let k = 0.25 + 0.75 * d;
    [base[0] * k, base[1] * k, base[2] * k]
}
