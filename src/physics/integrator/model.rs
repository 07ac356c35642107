//! What an integrator sees: the moving state, and the forces at any state.

use crate::physics::force::{Accelerations, Bodies, ForceField};
use crate::physics::shape::Shape;
use crate::physics::spring::{Material, Topology};
use crate::{Point, Scalar};

/// What ends a step's substeps (its contacts): called with the state, the inverse masses,
/// the substep's length and the time left in the frame (`(h, lag)`), and where the
/// particles were at the frame's start.
pub(crate) trait SubstepEnd<P: Point, Sh: Shape>:
    FnMut(&mut State<P, Sh>, &Sh::PerParticle<P::Scalar>, (P::Scalar, P::Scalar), &Sh::PerParticle<P>)
{
}

impl<P: Point, Sh: Shape, F> SubstepEnd<P, Sh> for F where
    F: FnMut(
        &mut State<P, Sh>,
        &Sh::PerParticle<P::Scalar>,
        (P::Scalar, P::Scalar),
        &Sh::PerParticle<P>,
    )
{
}

/// Positions and velocities of every particle: what an integrator advances.
pub struct State<P: Point, Sh: Shape> {
    pub(crate) pos: Sh::PerParticle<P>,
    pub(crate) vel: Sh::PerParticle<P>,
}

impl<P: Point, Sh: Shape> Clone for State<P, Sh> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<P: Point, Sh: Shape> Copy for State<P, Sh> {}

/// What stays fixed during a substep: masses, springs, gravity, damping and the clock.
pub struct Model<'a, P: Point, Sh: Shape, T> {
    pub(crate) inv_mass: &'a Sh::PerParticle<P::Scalar>,
    pub(crate) topology: &'a T,
    pub(crate) gravity: P,
    pub(crate) damping: P::Scalar,
    pub(crate) time: P::Scalar,
    /// `true` when the free particles are where a substep that kept its method's
    /// tolerance left them (nothing else has moved them since): a method that holds its
    /// links need not check where they start.
    pub(crate) settled: bool,
    /// `true` when the step resolves contacts after each substep (`false`: its `touch` does
    /// nothing, and a direct solver's contact rounds need not look for what it moved).
    pub(crate) touching: bool,
}

/// Springs shorter than this have no direction: 16 units of rounding.
#[inline]
pub(crate) fn tiny_length<S: Scalar>() -> S {
    S::EPSILON * S::from_i16(16)
}

/// Force on particle `a` from a spring to `b` (the opposite acts on `b`), or `None` when the
/// two are closer than the format can resolve a direction for. The second value is `false`
/// when the force saturated (`Q16` only; a float overflow is caught as divergence).
#[inline]
fn spring_force<P: Point>(
    xa: P,
    xb: P,
    va: P,
    vb: P,
    rest: P::Scalar,
    m: Material<P::Scalar>,
) -> Option<(P, bool)> {
    let d = xb - xa;
    let l = d.length();
    if l <= tiny_length::<P::Scalar>() {
        return None;
    }
    let inv = P::Scalar::ONE / l;
    // f/l along d: one vector scale instead of normalising first.
    let f = m.stiffness * (l - rest) + m.damping * (vb - va).dot(d) * inv;
    Some((d * (f * inv), f.is_finite()))
}

impl<P: Point, Sh: Shape, T: Topology<P::Scalar>> Model<'_, P, Sh, T> {
    /// Inverse masses, in flat order.
    #[inline]
    pub(crate) fn inv_mass(&self) -> &[P::Scalar] {
        Sh::flat(self.inv_mass)
    }

    /// The shortest rest length of a spring with a free end (longer than
    /// [`tiny_length`]), `None` without one: what an iterating solve measures its
    /// [`residual`](super::Solved::residual) against. A pass over the springs' runs.
    pub(crate) fn shortest_rest(&self) -> Option<P::Scalar> {
        let w = self.inv_mass();
        let mut shortest: Option<P::Scalar> = None;
        self.topology.for_each_run(|a, b, count, rest, m| {
            let (ends_a, ends_b) = (w.get(a..a + count), w.get(b..b + count));
            let free = |ends: Option<&[P::Scalar]>| {
                ends.is_some_and(|w| w.iter().any(|&w| w > P::Scalar::ZERO))
            };
            if m.stiffness > P::Scalar::ZERO
                && rest > tiny_length::<P::Scalar>()
                && (free(ends_a) || free(ends_b))
            {
                shortest = Some(shortest.map_or(rest, |s| s.min(rest)));
            }
        });
        shortest
    }

    /// An iterating solve's [`Solved`](super::Solved) from what its free particles still
    /// owe to its equations, the largest coordinate of `owed[i] · scale · w[i]` (`owed` a
    /// force imbalance, `scale` what turns it into a distance), over `shortest`
    /// ([`shortest_rest`](Self::shortest_rest)): converged within
    /// [`TOLERANCE`](super::TOLERANCE).
    pub(crate) fn solved(
        &self,
        fits: bool,
        owed: &[P],
        scale: P::Scalar,
        shortest: Option<P::Scalar>,
    ) -> super::Solved<P::Scalar> {
        let mut largest = P::Scalar::ZERO;
        for (r, &w) in owed.iter().zip(self.inv_mass()) {
            if w > P::Scalar::ZERO {
                for axis in 0..P::DIM {
                    largest = largest.max(r.coord(axis).abs() * w);
                }
            }
        }
        let largest = largest * scale;
        let (n, d) = super::TOLERANCE;
        super::Solved {
            fits,
            converged: shortest.is_none_or(|s| largest <= s * P::Scalar::ratio(n, d)),
            stretch: P::Scalar::ZERO,
            residual: shortest.map_or(P::Scalar::ZERO, |s| largest / s),
        }
    }

    /// The energy of the motion at `(x, v)`: each free particle's kinetic and gravitational
    /// (relative to the origin) energy, and every spring's `½ k (l − rest)²` but the links'
    /// (from particle `i` to `i + 1`) when `held_links` (constraints store none). A held
    /// particle counts as infinitely heavy and still. A division a particle and a square root
    /// a spring; may saturate in `Q16`, and overflow to ±∞ in floats past the format's range.
    pub(crate) fn energy(&self, x: &[P], v: &[P], held_links: bool) -> P::Scalar {
        self.energy_less_damping(x, v, P::Scalar::ZERO, held_links)
    }

    /// [`energy`](Self::energy) less what the springs' damping takes over a solve of `h`
    /// from `(x, v)`: each spring's `c (dl/dt)² h`, its `c` clamped as
    /// [`DirectSprings`](super::DirectSprings) clamps it (`c ≤ 1 / (h (wa + wb))`); in the
    /// same pass over the springs.
    pub(crate) fn energy_less_damping(
        &self,
        x: &[P],
        v: &[P],
        h: P::Scalar,
        held_links: bool,
    ) -> P::Scalar {
        let (zero, one, half) = (P::Scalar::ZERO, P::Scalar::ONE, P::Scalar::ratio(1, 2));
        let w = self.inv_mass();
        let mut e = zero;
        for ((x, v), &w) in x.iter().zip(v).zip(w) {
            if w > zero {
                let m = one / w;
                e += m * (half * v.dot(*v) - self.gravity.dot(*x));
            }
        }
        self.topology.for_each_spring(|a, b, rest, m| {
            let (Some(&xa), Some(&xb)) = (x.get(a), x.get(b)) else {
                return;
            };
            if held_links && a.abs_diff(b) == 1 {
                return;
            }
            let d = xb - xa;
            let l = d.length();
            let s = l - rest;
            e += half * m.stiffness * s * s;
            let ends = (v.get(a), v.get(b), w.get(a), w.get(b));
            let (Some(&va), Some(&vb), Some(&wa), Some(&wb)) = ends else {
                return;
            };
            let wsum = wa + wb;
            if h > zero && m.damping > zero && wsum > zero && l > super::tiny_length::<P::Scalar>()
            {
                let closing = (vb - va).dot(d) / l;
                let c = if m.damping * h * wsum > one {
                    one / (h * wsum)
                } else {
                    m.damping
                };
                e -= c * closing * closing * h;
            }
        });
        e
    }

    /// Accelerations at state `(x, v)`: gravity, damping, springs (unless `springs` is
    /// false) and the force fields. Returns `false` when a `Q16` force or acceleration
    /// saturated.
    pub(crate) fn accelerations<F: ForceField<P>>(
        &self,
        x: &[P],
        v: &[P],
        forces: &mut F,
        acc: &mut [P],
        springs: bool,
    ) -> bool {
        // In Q16 a saturated value is not sticky (MAX - 1 is finite again), so every
        // product and sum is checked where it is made; floats need none of this (an
        // overflow stays infinite and is caught as divergence).
        let fixed = P::Scalar::FIXED_POINT;
        let w = self.inv_mass();
        let mut ok = true;
        // Springs sum forces; each particle's sum is then scaled by its inverse mass once
        // (one multiplication per particle instead of two per spring). Without them every
        // entry is written below: no clearing first.
        if springs {
            acc.fill(P::default());
            self.topology.for_each_spring(|a, b, rest, m| {
                if let Some((f, fine)) = spring_force(x[a], x[b], v[a], v[b], rest, m) {
                    acc[a] += f;
                    acc[b] -= f;
                    if fixed {
                        ok &= fine & f.is_finite() & acc[a].is_finite() & acc[b].is_finite();
                    }
                }
            });
        }
        for i in 0..acc.len() {
            // Pinned particles do not accelerate: skip their multiplications where they are
            // costly (fixed point); floats keep a branch-free loop.
            if fixed && w[i] <= P::Scalar::ZERO {
                acc[i] = P::default();
                continue;
            }
            let force = acc[i] * w[i];
            let pull = if springs {
                force + self.gravity
            } else {
                self.gravity
            };
            let drag = v[i] * self.damping;
            acc[i] = if w[i] > P::Scalar::ZERO {
                pull - drag
            } else {
                P::default()
            };
            if fixed {
                ok &= (!springs || force.is_finite()) & drag.is_finite() & acc[i].is_finite();
            }
        }
        let bodies = Bodies {
            pos: x,
            vel: v,
            inv_mass: w,
            columns: Sh::COLUMNS,
        };
        let mut out = Accelerations {
            acc,
            inv_mass: w,
            saturated: false,
        };
        forces.apply(self.time, &bodies, &mut out);
        ok && !out.saturated
    }

    /// Accelerations at `state`, in the layout's own array.
    pub(crate) fn accelerations_at<F: ForceField<P>>(
        &self,
        state: &State<P, Sh>,
        forces: &mut F,
        springs: bool,
    ) -> (Sh::PerParticle<P>, bool) {
        let mut a = Sh::filled(P::default());
        let ok = self.accelerations(
            Sh::flat(&state.pos),
            Sh::flat(&state.vel),
            forces,
            Sh::flat_mut(&mut a),
            springs,
        );
        (a, ok)
    }
}
