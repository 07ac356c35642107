//! The gas inside a closed body of particles: a jelly, a balloon, a tyre in 2D; an inner
//! tube in 3D.

use super::force::{Accelerations, Bodies, ForceField};
use super::hash::StateHash;
use crate::error::check_non_negative;
use crate::{Error, Point, Scalar, Vec2, Vec3};

/// The gas inside a closed body of particles, a force field in 2D and in 3D: Boyle's law at a
/// constant temperature, `p = amount / area` (2D) or `amount / volume` (3D), where `amount`
/// is `n R T` (pressure times area or volume: force × length). Squeezed to half its size,
/// the gas pushes twice as hard; the force is the gradient of `−amount · ln(size)`, so it
/// stores and returns energy as a spring does, and its pushes sum to zero, so the gas never
/// moves the body as a whole: held and thrown, a jelly's centre of mass flies the ballistic
/// arc.
///
/// **In 2D** (`Vec2`: a jelly, a balloon, a tyre) the gas pushes every edge of a closed loop
/// outwards. The loop is the system's particles in order, the last joined back to the first (a
/// [`Springs::closed_loop`](crate::spring::Springs::closed_loop) ring), in either direction.
/// Each edge's push, `p` times its length along its outward normal, is shared by its two
/// ends. A loop whose area is within rounding of 0 (collapsed, or turned inside out through
/// zero) gets no push that evaluation, never an infinite one; so does a `Q16` loop whose
/// area does not fit the format (past 32 767 square units), and the step reports it
/// `saturated`. A loop that crosses itself (a
/// figure eight) counts its lobes' areas with opposite signs, and the gas pushes as if their
/// difference were its area: build the ring without crossings. Cost: one cross product and
/// three multiply-adds a particle, and one division.
///
/// **In 3D** (`Vec3`: an inner tube, a swim ring) the gas pushes every particle of a closed
/// surface along the volume's gradient. The surface is the system's grid closed both ways (a
/// [`Torus`](crate::Torus)): rows of [`Bodies::columns`] particles, each row a ring, the last
/// row joined to the first, at least 3×3. Its volume ([`signed_volume`](Self::signed_volume))
/// is that of the grid's quadrilaterals, each the mean of its two splits into triangles (the
/// same whichever diagonal a renderer draws), positive when `∂u × ∂v` (along a row, then to
/// the next row) points out; the push is outwards either way. A volume within rounding of 0
/// gets no push, and neither does a system whose particles are not such a grid; a `Q16`
/// volume past the format's range gets none and the step reports it `saturated`. Cost: nine
/// cross products a particle (three for the volume, six for the pushes) and one division.
///
/// Measured (`tests/suite/pressure.rs`): a ring of 16 particles comes to rest at the radius
/// where its springs balance its gas (the closed form, by bisection) within 1% (to 5
/// digits); rolled along a floor it keeps its area within 2% (1.1% touching with its
/// particles, 0.4% with its drawn closed curve, `Touch::DrawnLoop`, which stays above the
/// floor). On a Cortex-M0 in
/// Q16.16 (`examples/mcu_jelly.rs`, 8 particles on a floor) a frame with its closed curve
/// takes 24 571 instructions on average and up to 26 757. In 3D (`tests/suite/torus.rs`): at
/// rest an 8×8 torus's springs balance its gas by the virial identity (`Σ k (l − r) l =
/// 3 · amount`) to 5 digits, and one undamped step changes the springs', gas's and motion's
/// energy by `O(h²)` (the pushes are the energy's gradient).
///
/// ```
/// use dunas::force::Pressure;
/// use dunas::prelude::*;
/// use dunas::spring::Springs;
///
/// // A ring of 16 particles, radius 1 m, 1 kg, in no gravity, blown up by its gas.
/// let ring: [Vec2<f32>; 16] = core::array::from_fn(|i| {
///     let a = core::f32::consts::TAU * i as f32 / 16.0;
///     Vec2::new(a.cos(), a.sin())
/// });
/// let springs = Springs::<f32, 16>::closed_loop(&ring, Material { stiffness: 200.0, damping: 1.0 })?;
/// let settings = Settings { damping: 1.0, ..Settings::default() };
/// let mut jelly = Rope::from_parts(ring, [16.0; 16], springs, settings)?;
/// let mut gas = Pressure::new(10.0)?; // 10 N·m: 3.2 N/m of pressure at its first area
/// for _ in 0..300 {
///     let _ = jelly.step_with(1.0 / 60.0, &mut gas)?;
/// }
/// assert!(Pressure::area(jelly.positions()) > 3.2); // blown up past π m²
/// # Ok::<(), dunas::Error>(())
/// ```
///
/// ```
/// use dunas::force::Pressure;
/// use dunas::prelude::*;
/// use dunas::Torus;
///
/// // An inner tube, 1 m round its ring, 0.3 m round its tube, 2 kg, blown up in no gravity.
/// let m = Material { stiffness: 300.0, damping: 1.0 };
/// let settings = Settings { damping: 1.0, ..Settings::default() };
/// let mut tube: Torus<f32, 8, 6> = Torus::new(Vec3::default(), 1.0, 0.3, 2.0, [m, m, m], settings)?;
/// let before = tube.volume();
/// let mut gas = Pressure::new(20.0)?; // 20 N·m: 11 N/m² of pressure at its 1.8 m³
/// for _ in 0..120 {
///     let _ = tube.step_with(1.0 / 60.0, &mut gas)?;
/// }
/// assert!(tube.volume() > before); // blown up
/// # Ok::<(), dunas::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pressure<S> {
    amount: S,
}

impl<S: Scalar> Pressure<S> {
    /// Gas of `amount` (`n R T`: pressure × area in 2D, pressure × volume in 3D, ≥ 0; 0 is
    /// no gas).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative, NaN or infinite amount.
    pub fn new(amount: S) -> Result<Self, Error> {
        Ok(Pressure {
            amount: check_non_negative(amount, "amount")?,
        })
    }

    /// The gas that pushes with `pressure` at `area` (in 3D, a volume): `amount = pressure ·
    /// area`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative, NaN or infinite pressure, area or product
    /// (a `Q16` product past the format's range).
    pub fn at(pressure: S, area: S) -> Result<Self, Error> {
        check_non_negative(pressure, "pressure")?;
        check_non_negative(area, "area")?;
        Self::new(pressure * area)
    }

    /// The gas's amount, `n R T`.
    pub fn amount(&self) -> S {
        self.amount
    }

    /// Lets the gas out: a balloon that bursts. The field cannot see the springs, so when a
    /// step reports a torn loop ([`StepInfo::snapped`](crate::system::StepInfo::snapped), or
    /// a cut) the game calls this, and the loop goes limp.
    pub fn pop(&mut self) {
        self.amount = S::ZERO;
    }

    /// The area the loop `points` encloses (the shoelace formula, taken about the first
    /// point so that `Q16` sums stay small): positive counter-clockwise, negative clockwise;
    /// in `Q16`, the format's limit (not finite) when it does not fit.
    pub fn signed_area(points: &[Vec2<S>]) -> S {
        let Some(&origin) = points.first() else {
            return S::ZERO;
        };
        let mut twice = S::ZERO;
        for pair in points.windows(2) {
            twice += (pair[0] - origin).cross(pair[1] - origin);
            if !twice.is_finite() {
                // A `Q16` sum past the format stays at its limit (a saturated value is not
                // sticky: later terms could bring it back inside).
                return twice;
            }
        }
        twice * S::ratio(1, 2)
    }

    /// The area the loop `points` encloses, whichever way round it goes.
    pub fn area(points: &[Vec2<S>]) -> S {
        Self::signed_area(points).abs()
    }

    /// The volume the closed grid `points` (rows of `columns` particles, see the type's
    /// docs) encloses, signed; 0 when `points` is not such a grid; in `Q16`, the format's
    /// limit (not finite) when it does not fit.
    pub fn signed_volume(points: &[Vec3<S>], columns: usize) -> S {
        let mut twelve = S::ZERO;
        let fits = quads(points, columns, |_, [a, b, c, d]| {
            let cd = c.cross(d);
            twelve += a.dot(b.cross(c) + cd + b.cross(d)) + b.dot(cd);
            twelve.is_finite()
        });
        if !fits {
            return twelve;
        }
        twelve * S::ratio(1, 12)
    }
}

impl<S: Scalar> ForceField<Vec2<S>> for Pressure<S> {
    /// Always steady: its amount of gas.
    fn steady(&self, key: &mut StateHash) -> bool {
        key.add_scalar(self.amount);
        true
    }

    fn apply(&mut self, _: S, bodies: &Bodies<'_, Vec2<S>>, out: &mut Accelerations<'_, Vec2<S>>) {
        let x = bodies.pos;
        let area = Self::signed_area(x);
        if !area.is_finite() {
            // A `Q16` loop too large for its area to fit the format: no push, reported.
            out.saturated = true;
            return;
        }
        // A signed area: the outward normal of a clockwise loop's edge points the other way,
        // and so does its pressure, so the push is outwards either way.
        if area.abs() <= S::EPSILON * S::from_i16(16) || self.amount == S::ZERO {
            return;
        }
        let half = self.amount / area * S::ratio(1, 2);
        if !half.is_finite() {
            out.saturated = true;
            return;
        }
        let n = x.len();
        for i in 0..n {
            let j = if i + 1 == n { 0 } else { i + 1 };
            let e = x[j] - x[i];
            // The edge's outward normal for a counter-clockwise loop, its length |e|.
            let push = Vec2::new(e.y, -e.x) * half;
            out.add_force(i, push);
            out.add_force(j, push);
        }
    }
}

/// Calls `f(corners, [a, b, c, d])` for every quadrilateral of the closed grid `x` (rows of
/// `columns`), corners `(i, j), (i+1, j), (i+1, j+1), (i, j+1)` wrapping, as flat indices
/// and as positions relative to `x[0]` (so that `Q16` products stay small), until `f`
/// returns `false`; returns whether every call returned `true` (`true` for no grid).
fn quads<S: Scalar>(
    x: &[Vec3<S>],
    columns: usize,
    mut f: impl FnMut([usize; 4], [Vec3<S>; 4]) -> bool,
) -> bool {
    let rows = x.len().checked_div(columns).unwrap_or(0);
    if columns < 3 || rows < 3 || rows * columns != x.len() {
        return true;
    }
    let origin = x[0];
    for j in 0..rows {
        let next_row = if j + 1 == rows { 0 } else { (j + 1) * columns };
        for i in 0..columns {
            let next = if i + 1 == columns { 0 } else { i + 1 };
            let corners = [
                j * columns + i,
                j * columns + next,
                next_row + next,
                next_row + i,
            ];
            if !f(corners, corners.map(|k| x[k] - origin)) {
                return false;
            }
        }
    }
    true
}

impl<S: Scalar> ForceField<Vec3<S>> for Pressure<S> {
    /// Always steady: its amount of gas.
    fn steady(&self, key: &mut StateHash) -> bool {
        key.add_scalar(self.amount);
        true
    }

    fn apply(&mut self, _: S, bodies: &Bodies<'_, Vec3<S>>, out: &mut Accelerations<'_, Vec3<S>>) {
        let twelve = Self::signed_volume(bodies.pos, bodies.columns) * S::from_i16(12);
        if !twelve.is_finite() {
            out.saturated = true;
            return;
        }
        if twelve.abs() <= S::EPSILON * S::from_i16(16) || self.amount == S::ZERO {
            return;
        }
        // amount / volume times the volume's gradient, the gradient's 1/12 taken in.
        let scale = self.amount / twelve;
        if !scale.is_finite() {
            out.saturated = true;
            return;
        }
        quads(bodies.pos, bodies.columns, |k, [a, b, c, d]| {
            let (ab, ac, ad) = (a.cross(b), a.cross(c), a.cross(d));
            let (bc, bd, cd) = (b.cross(c), b.cross(d), c.cross(d));
            out.add_force(k[0], (bc + cd + bd) * scale);
            out.add_force(k[1], (cd - ac - ad) * scale);
            out.add_force(k[2], (ab - ad - bd) * scale);
            out.add_force(k[3], (ab + ac + bc) * scale);
            true
        });
    }
}
