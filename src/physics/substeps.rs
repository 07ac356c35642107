//! How many substeps a frame needs: a bound on the stiffest spring's frequency, and the
//! plan that keeps an explicit integrator inside its stability limit.

use crate::physics::integrator::Integrator;
use crate::physics::shape::Shape;
use crate::physics::spring::Topology;
use crate::{Accuracy, Error, Scalar};

/// Most substeps one [`MassSpring::step`](crate::MassSpring::step) takes; past this the step
/// simulates less time than asked (slow motion, reported in
/// [`StepInfo`](crate::physics::system::StepInfo)) instead of going unstable.
pub const MAX_SUBSTEPS: u16 = 64;

/// `(ω, γ)`: the highest angular frequency (rad/s) of the springs, by Gershgorin's bound,
/// and the highest damping rate (1/s) of the springs' damping, for particles of inverse
/// masses `w`. One pass over the springs and two square roots per particle.
pub(crate) fn spring_bound<S: Scalar, Sh: Shape>(
    w: &Sh::PerParticle<S>,
    topology: &impl Topology<S>,
) -> (S, S) {
    let w = Sh::flat(w);
    // Sums are kept divided by 64 and the roots taken separately, so that in Q16 neither
    // Σk nor w·Σk saturates before the square root (ω = 8·sqrt(w)·sqrt(Σk/64)).
    let (mut k_sums, mut c_sums) = (Sh::filled(S::ZERO), Sh::filled(S::ZERO));
    let (k, c) = (Sh::flat_mut(&mut k_sums), Sh::flat_mut(&mut c_sums));
    let (one, two) = (S::ratio(1, 64), S::ratio(2, 64));
    topology.for_each_spring(|a, b, _, m| {
        let (fa, fb) = (
            if w[b] > S::ZERO { two } else { one },
            if w[a] > S::ZERO { two } else { one },
        );
        k[a] += m.stiffness * fa;
        k[b] += m.stiffness * fb;
        c[a] += m.damping * fa;
        c[b] += m.damping * fb;
    });
    let (mut omega, mut gamma) = (S::ZERO, S::ZERO);
    for ((&wi, &ki), &ci) in w.iter().zip(k.iter()).zip(c.iter()) {
        omega = omega.max(wi.sqrt() * ki.sqrt());
        gamma = gamma.max(wi * ci);
    }
    (omega * S::from_i16(8), gamma * S::from_i16(64))
}

/// Substeps per unit of `rate · dt` (`rate = ω + γ`) that keep `integrator` at `accuracy`'s
/// fraction of its limit: `1 / (fraction · limit)`; zero when any step is stable.
pub(crate) fn substeps_per_rate<S: Scalar>(integrator: &impl Integrator, accuracy: Accuracy) -> S {
    match integrator.stability_limit::<S>() {
        Some(limit) if limit > S::ZERO => {
            let (num, den) = accuracy.fraction();
            S::ratio(den, num) / limit
        }
        _ => S::ZERO,
    }
}

/// The substep count and length for a frame of `dt >= 0` seconds, given the system's `rate`
/// (1/s) and [`substeps_per_rate`]: at most [`MAX_SUBSTEPS`], each at most
/// `1 / (rate · per_rate)` long; the flag is `true` when that cap cut the frame short (slow
/// motion, which keeps a stiff system stable). `floor` is the substeps a second that contacts
/// ask for: it raises the count up to [`MAX_SUBSTEPS`] but never slows time. A zero `dt` is
/// zero substeps.
///
/// # Errors
/// [`Error::TooStiff`] when `rate · per_rate` overflows the format (saturates in `Q16`) or
/// the substep length rounds to zero.
pub(crate) fn plan<S: Scalar>(
    dt: S,
    rate: S,
    per_rate: S,
    floor: S,
) -> Result<(u16, S, bool), Error> {
    if dt == S::ZERO {
        return Ok((0, S::ZERO, false));
    }
    let scale = rate * per_rate;
    if !scale.is_finite() {
        return Err(Error::TooStiff);
    }
    let stiff = if scale <= S::ZERO {
        1
    } else {
        (dt * scale).ceil_usize(MAX_SUBSTEPS as usize + 1).max(1)
    };
    let (n, h, capped) = if stiff > MAX_SUBSTEPS as usize {
        (MAX_SUBSTEPS, S::ONE / scale, true)
    } else {
        // A NaN or saturated contact demand counts as the cap.
        let contact = (dt * floor).ceil_usize(MAX_SUBSTEPS as usize);
        match stiff.max(contact) {
            0 | 1 => (1, dt, false),
            n => (n as u16, dt / S::from_i16(n as i16), false),
        }
    };
    if h > S::ZERO && h.is_finite() {
        Ok((n, h, capped))
    } else {
        Err(Error::TooStiff)
    }
}
