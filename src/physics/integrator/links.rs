//! A rope's links as distance constraints solved together along the chain: Newton
//! iterations of one tridiagonal solve each (Thomas's algorithm), for [`DirectChain`].

use super::chain::{DirectChain, tolerance_of};
use super::{Model, tiny_length};
use crate::physics::shape::Shape;
use crate::physics::spring::Topology;
use crate::{Point, Scalar};

/// The links of a row of particles (link `i` joins particle `i` to `i + 1`; the last slot is
/// unused) and the scratch of their solve, in the particles' own layout.
pub(super) struct Links<P: Point, Sh: Shape> {
    pub(super) rest: Sh::PerParticle<P::Scalar>,
    compliance: Sh::PerParticle<P::Scalar>,
    pub(super) linked: Sh::PerParticle<bool>,
    /// Each link's multiplier, carried from one iteration to the next.
    lambda: Sh::PerParticle<P::Scalar>,
    dir: Sh::PerParticle<P>,
    /// Thomas's algorithm: each row's off-diagonal over its pivot, then its solution.
    ratio: Sh::PerParticle<P::Scalar>,
    solved: Sh::PerParticle<P::Scalar>,
    /// The positions before a Newton step, for its line search.
    before: Sh::PerParticle<P>,
    /// Each link's length and its inverse at the positions now, and their squared stretch,
    /// once measured (the line search measures them; the next iteration starts from them).
    length: Sh::PerParticle<P::Scalar>,
    inverse: Sh::PerParticle<P::Scalar>,
    pub(super) measured: Option<P::Scalar>,
    /// Whether the last iteration's line search took the whole Newton step.
    pub(super) took_whole: bool,
    /// The squared stretch within which held links are exact: that of 10⁻⁶ of the rope's
    /// length (springs stretch by design: they take every iteration).
    pub(super) exact: P::Scalar,
    /// The squared stretch within which every link is within half the tolerance: that of
    /// half of [`DirectChain::TOLERANCE`] of the shortest link (measured finely only; 0
    /// otherwise).
    pub(super) close: P::Scalar,
    /// Whether their stretch is measured finely ([`squared`]).
    fine: bool,
    /// One over the scale the multipliers are solved and kept in: in `Q16` the largest
    /// power of two up to the largest inverse mass (at most 1 024), so that a particle's
    /// move (its inverse mass times a change of its links' multipliers) and the pivots'
    /// inverses keep the format's resolution; 1 in floats. The links' matrix and
    /// compliances are kept times it, the multipliers over it.
    down: P::Scalar,
}

/// Most times a Newton step is halved before it is taken as it is.
const MAX_HALVINGS: u8 = 4;

/// A link's squared stretch `c²` as its solve measures it: measured `fine` in `Q16`, that
/// of `16 c` (a stretch under 4 mm squares to nothing there; 16 times longer, under
/// 0.25 mm).
fn squared<S: Scalar>(c: S, fine: bool) -> S {
    let c = match S::FIXED_POINT && fine {
        true => c * S::from_i16(16),
        false => c,
    };
    c * c
}

/// Each link's length and its inverse into `length`, and `Σ (l − rest)²` over the links
/// ([`squared`], `fine` for held links): what a Newton step must lower.
fn measure<P: Point>(
    x: &[P],
    (rest, linked, fine): (&[P::Scalar], &[bool], bool),
    (length, inverse): (&mut [P::Scalar], &mut [P::Scalar]),
) -> P::Scalar {
    let mut sum = P::Scalar::ZERO;
    for i in 0..x.len().saturating_sub(1) {
        if linked[i] {
            (length[i], inverse[i]) = (x[i + 1] - x[i]).length_and_inverse();
            let c = length[i] - rest[i];
            sum += squared(c, fine);
        }
    }
    sum
}

impl<P: Point, Sh: Shape> Links<P, Sh> {
    /// The links of `model`'s springs from particle `i` to `i + 1` that have a free end,
    /// each with its spring's compliance `1 / (k h²)` for a solve of `h` when given as
    /// `(1 / h, h)` (inextensible without).
    pub(super) fn new<T: Topology<P::Scalar>>(
        model: &Model<'_, P, Sh, T>,
        h: Option<(P::Scalar, P::Scalar)>,
    ) -> Self {
        let zero = P::Scalar::ZERO;
        let w = model.inv_mass();
        let mut links = Links::<P, Sh> {
            rest: Sh::filled(zero),
            compliance: Sh::filled(zero),
            linked: Sh::filled(false),
            lambda: Sh::filled(zero),
            dir: Sh::filled(P::default()),
            ratio: Sh::filled(zero),
            solved: Sh::filled(zero),
            before: Sh::filled(P::default()),
            length: Sh::filled(zero),
            inverse: Sh::filled(zero),
            measured: None,
            took_whole: false,
            exact: zero,
            close: zero,
            fine: false,
            down: P::Scalar::ONE,
        };
        if P::Scalar::FIXED_POINT {
            // In `Q16` a unit of the format times an inverse mass of 8 is a move of 8 units;
            // a multiplier solved 8 times larger moves it by one.
            let most = w.iter().fold(zero, |most, &w| most.max(w));
            let (half, least) = (P::Scalar::ratio(1, 2), P::Scalar::ratio(1, 1024));
            let mut scale = P::Scalar::ONE;
            while scale + scale <= most && links.down > least {
                (scale, links.down) = (scale + scale, links.down * half);
            }
        }
        model.topology.for_each_spring(|i, j, length, m| {
            if i.abs_diff(j) == 1 {
                let i = i.min(j);
                Sh::flat_mut(&mut links.rest)[i] = length;
                Sh::flat_mut(&mut links.linked)[i] = w[i] + w[i + 1] > zero;
                if let (Some((inv_h, h)), true) = (h, m.stiffness > zero) {
                    Sh::flat_mut(&mut links.compliance)[i] =
                        compliance(inv_h, h, m.stiffness) * links.down;
                }
            }
        });
        let rest: P::Scalar = Sh::flat(&links.rest).iter().fold(zero, |sum, &l| sum + l);
        let exact = rest * P::Scalar::ratio(1, 1_000_000);
        links.exact = squared(exact, false);
        links
    }

    /// The links with their stretch measured finely ([`squared`]) and within reach of
    /// [`close`](Self::close): for a hold after contacts, which must tell a tenth of the
    /// tolerance in `Q16` (a solve, whose `Q16` early exit that would delay, does not).
    pub(super) fn measured_finely(mut self) -> Self {
        let (n, d) = DirectChain::TOLERANCE;
        self.fine = true;
        self.close = squared(self.shortest() * P::Scalar::ratio(n, 2 * d), true);
        self
    }

    /// The shortest link's rest length (0 for none).
    pub(super) fn shortest(&self) -> P::Scalar {
        let linked = Sh::flat(&self.rest).iter().zip(Sh::flat(&self.linked));
        let rests = linked.filter(|&(_, &linked)| linked).map(|(&rest, _)| rest);
        rests
            .reduce(|least, rest| least.min(rest))
            .unwrap_or(P::Scalar::ZERO)
    }

    /// Whether the last iteration measured the links within 10⁻⁶ of the rope's length.
    pub(super) fn exact(&self) -> bool {
        self.measured.is_some_and(|r| r <= self.exact)
    }

    /// The largest distance of a link at `x` from its goal, relative to its rest length:
    /// `|l − g| / rest`, `g = rest − α̃ λ` its goal (its rest length when inextensible; a
    /// spring's multiplier is known to the format's resolution only, so 16 units of it, over
    /// the scale it is kept in, are allowed for: in `Q16`, at most 0.02% of a 1 m link under
    /// a compliance of 1). First from the
    /// squared lengths, `|l² − g²| / g²` (about twice the ratio): where every link is within
    /// twice the tolerance that way, only the largest is measured (one square root), and
    /// the ratio is the largest to within its own square; otherwise every link is measured
    /// ([`off_measured`](Self::off_measured)). About five multiplications a link.
    pub(super) fn off(&mut self, x: &[P]) -> P::Scalar {
        let zero = P::Scalar::ZERO;
        let (n, d) = DirectChain::TOLERANCE;
        let twice = P::Scalar::ratio(2 * n, d);
        let (rest, linked) = (Sh::flat(&self.rest), Sh::flat(&self.linked));
        let (compliance, lambda) = (Sh::flat(&self.compliance), Sh::flat(&self.lambda));
        // The largest ratio as its numerator and denominator, compared by products; a
        // link of the same goal as the one before (a rope's) reuses its square and limit.
        let (mut most, mut of, mut at) = (zero, P::Scalar::ONE, None);
        let (mut last, mut g2, mut limit) = (zero, zero, zero);
        for i in (0..x.len().saturating_sub(1)).filter(|&i| linked[i]) {
            let c = compliance[i];
            let g = if c > zero {
                rest[i] - c * lambda[i]
            } else {
                rest[i]
            };
            if g != last {
                (last, g2) = (g, g * g);
                limit = g2 * twice;
            }
            let d = x[i + 1] - x[i];
            let off = (d.dot(d) - g2).abs();
            if !(off.is_finite() && g2 > zero && off <= limit) {
                return self.off_measured(x);
            }
            let larger = if g2 == of {
                off >= most
            } else {
                off * of >= most * g2
            };
            if larger {
                (most, of, at) = (off, g2, Some(i));
            }
        }
        let Some(i) = at else {
            return zero;
        };
        let off = ((x[i + 1] - x[i]).length() - rest[i] + compliance[i] * lambda[i]).abs();
        (off - compliance[i] * tiny_length::<P::Scalar>()).max(zero) / rest[i]
    }

    /// [`off`](Self::off) from every link's length: measures the links unless the last
    /// iteration did. A multiplication a link and one division.
    #[cold]
    #[inline(never)]
    fn off_measured(&mut self, x: &[P]) -> P::Scalar {
        let zero = P::Scalar::ZERO;
        let (rest, linked) = (Sh::flat(&self.rest), Sh::flat(&self.linked));
        let (length, inverse) = (
            Sh::flat_mut(&mut self.length),
            Sh::flat_mut(&mut self.inverse),
        );
        if self.measured.is_none() {
            self.measured = Some(measure(x, (rest, linked, self.fine), (length, inverse)));
        }
        let (compliance, lambda) = (Sh::flat(&self.compliance), Sh::flat(&self.lambda));
        let rounding = tiny_length::<P::Scalar>();
        let (mut most, mut of) = (zero, P::Scalar::ONE);
        for i in (0..x.len().saturating_sub(1)).filter(|&i| linked[i]) {
            let off = (length[i] - rest[i] + compliance[i] * lambda[i]).abs();
            let off = (off - compliance[i] * rounding).max(zero);
            if off * of > most * rest[i] {
                (most, of) = (off, rest[i]);
            }
        }
        most / of
    }

    /// Moves the particles (positions only, as `w` lets them) towards every link within
    /// [`DirectChain::TOLERANCE`], in up to `4 · iterations` Newton iterations, stopping
    /// once the links' squared stretch is within `enough` ([`exact`](Self::exact) or
    /// [`close`](Self::close)) or an iteration takes less than `w`'s
    /// [`least_gain`](Mobility::least_gain) off it (nothing at all when it has none); how far
    /// off they end
    /// ([`off`](Self::off)). Does nothing when they are within already (about five
    /// multiplications a link to find out).
    #[inline(never)]
    pub(super) fn bring_back<M: Mobility<P> + ?Sized>(
        &mut self,
        x: &mut [P],
        w: &mut M,
        (iterations, enough): (u8, P::Scalar),
    ) -> P::Scalar {
        let off = self.off(x);
        if off <= tolerance_of(DirectChain::TOLERANCE) {
            return off;
        }
        for _ in 0..iterations.saturating_mul(4) {
            let start = self.measured;
            self.solve(x, w, false);
            let stuck = match (start, self.measured, w.least_gain()) {
                (Some(start), Some(now), Some((n, d))) => {
                    now >= start - start * P::Scalar::ratio(n, d)
                }
                (Some(start), Some(now), None) => now == start,
                _ => false,
            };
            if stuck || self.measured.is_some_and(|r| r <= enough) {
                break;
            }
        }
        Sh::flat_mut(&mut self.lambda).fill(P::Scalar::ZERO);
        self.off(x)
    }

    /// One Newton iteration: the links' tridiagonal system `(J W Jᵀ + α̃) Δλ = −C − α̃ λ` at
    /// `x` solved by Thomas's algorithm (one inverse a link), `W` the particles' mobility
    /// `w`, and the particles moved by it: with `whole`, by the whole step, unmeasured;
    /// otherwise the whole step or, while that would not lower the links' squared stretch,
    /// half of it and so on (a line search, [`took_whole`](Self::took_whole) unless it cut
    /// the step; after the last halving the step is taken as it is, or, where `w` bounds
    /// how far a step may go ([`Mobility::reach`]), not at all). A link too short to have a
    /// direction sits the iteration out.
    pub(super) fn solve<M: Mobility<P> + ?Sized>(&mut self, x: &mut [P], w: &mut M, whole: bool) {
        let zero = P::Scalar::ZERO;
        // The matrix `down` times the links', each move `down` times its particle's (see
        // `down`).
        let down = self.down;
        let (rest, compliance) = (Sh::flat(&self.rest), Sh::flat(&self.compliance));
        let (linked, lambda) = (Sh::flat(&self.linked), Sh::flat_mut(&mut self.lambda));
        let dir = Sh::flat_mut(&mut self.dir);
        let (ratio, solved) = (
            Sh::flat_mut(&mut self.ratio),
            Sh::flat_mut(&mut self.solved),
        );
        let links = x.len().saturating_sub(1);
        let length = Sh::flat_mut(&mut self.length);
        let inverse = Sh::flat_mut(&mut self.inverse);
        let residual = match self.measured {
            Some(residual) => residual,
            None => measure(x, (rest, linked, self.fine), (length, inverse)),
        };
        // Each link's direction and right-hand side `−C − α̃λ`; a zero direction marks one
        // too short to have a direction.
        for i in 0..links {
            (dir[i], solved[i]) = (P::default(), zero);
            if !linked[i] {
                continue;
            }
            let d = x[i + 1] - x[i];
            let l = length[i];
            let mut b = rest[i] - l;
            if compliance[i] > zero {
                b -= compliance[i] * lambda[i];
            }
            if l > tiny_length::<P::Scalar>() {
                (dir[i], solved[i]) = (d * inverse[i], b);
            } else {
                lambda[i] = zero;
            }
        }
        // How far the step may move a particle, when the mobility bounds it.
        let reach = w.reach().map(|k| {
            let most = solved.iter().fold(zero, |most, b| most.max(b.abs()));
            most * k
        });
        // Forward sweep; row i couples to link i + 1 through particle i + 1 by
        // `off_i = −w_{i+1} (n_i · n_{i+1})`.
        let (mut prev_ratio, mut prev_solved, mut prev_off) = (zero, zero, zero);
        for i in 0..links {
            ratio[i] = zero;
            if dir[i] == P::default() {
                (prev_ratio, prev_solved, prev_off) = (zero, zero, zero);
                continue;
            }
            let own = w.along_link(i, dir[i]).map(|own| own * down);
            let diag = own.unwrap_or(zero) + compliance[i] - prev_off * prev_ratio;
            if own.is_none() || diag <= zero {
                (dir[i], solved[i]) = (P::default(), zero);
                (prev_ratio, prev_solved, prev_off) = (zero, zero, zero);
                continue;
            }
            let inv = diag.approx_recip();
            let off = if i + 1 < links && dir[i + 1] != P::default() {
                -w.between(i + 1, dir[i], dir[i + 1]) * down
            } else {
                zero
            };
            ratio[i] = off * inv;
            solved[i] = (solved[i] - prev_off * prev_solved) * inv;
            (prev_ratio, prev_solved, prev_off) = (ratio[i], solved[i], off);
        }
        // Back substitution, then each particle moves by its links' pulls: the whole
        // Newton step, or half of it, and so on, until the links' squared stretch falls
        // (far from the solution, as in a whip, a full step can overshoot and feed on
        // itself).
        for i in (0..links.saturating_sub(1)).rev() {
            solved[i] -= ratio[i] * solved[i + 1];
        }
        if let Some(reach) = reach {
            let pulled = |i: usize| match i < links && dir[i] != P::default() {
                true => dir[i] * solved[i],
                false => P::default(),
            };
            let mut most = zero;
            for i in 0..x.len() {
                let pull = if i > 0 { pulled(i - 1) } else { P::default() };
                let moved = w.moved(i, pull - pulled(i)) * down;
                most = most.max(moved.dot(moved));
            }
            let most = most.sqrt();
            if most > reach {
                let scale = reach / most;
                for s in solved.iter_mut() {
                    *s = *s * scale;
                }
            }
        }
        let before = Sh::flat_mut(&mut self.before);
        if !whole {
            before.copy_from_slice(x);
        }
        self.took_whole = true;
        for halving in 0..=MAX_HALVINGS {
            // Each particle moves by the difference of its two links' pulls.
            let mut pull = P::default();
            for i in 0..x.len() {
                let out = if i < links && dir[i] != P::default() {
                    dir[i] * solved[i]
                } else {
                    P::default()
                };
                if w.free(i) {
                    x[i] += w.moved(i, pull - out) * down;
                    w.pulled(i, (pull - out) * down);
                }
                pull = out;
            }
            if whole {
                self.measured = None;
                return;
            }
            let after = measure(x, (rest, linked, self.fine), (length, inverse));
            self.measured = Some(after);
            if after <= residual {
                break;
            }
            if halving == MAX_HALVINGS {
                // A bounded step that does not lower the stretch is not taken.
                if reach.is_some() {
                    x.copy_from_slice(before);
                    self.measured = Some(residual);
                }
                break;
            }
            self.took_whole = false;
            x.copy_from_slice(before);
            for s in solved.iter_mut() {
                *s = *s * P::Scalar::ratio(1, 2);
            }
        }
        for i in 0..links {
            if dir[i] != P::default() {
                lambda[i] += solved[i];
            }
        }
    }
}

/// A spring's compliance `1 / (k h²)` in a solve of `h`, as `(1/h) / (k h)` from `1/h`: in
/// `Q16`, `h²` of a short solve is below the format's resolution, and a stiffness past its
/// range leaves 0 (held, inextensible).
pub(super) fn compliance<S: Scalar>(inv_h: S, h: S, k: S) -> S {
    inv_h / (k * h)
}

/// How a links' solve moves each particle under its links' pulls: by its inverse mass
/// (`&[S]`), or so with the particles a contact pushed held along their push ([`Held`]).
pub(super) trait Mobility<P: Point> {
    /// Whether particle `i` moves at all.
    fn free(&self, i: usize) -> bool;
    /// `dᵀ (W_i + W_{i+1}) d` for link `i`'s unit direction `d` (`W_i` particle `i`'s
    /// inverse mass), or `None` when the link can barely move its ends along itself.
    fn along_link(&self, i: usize, d: P) -> Option<P::Scalar>;
    /// `aᵀ W_i b` for unit `a` and `b`.
    fn between(&self, i: usize, a: P, b: P) -> P::Scalar;
    /// `W_i f`: how particle `i` moves under the pull `f`.
    fn moved(&self, i: usize, f: P) -> P;
    /// Particle `i` was moved by the pull `f`: a held particle pulled away from what holds
    /// it is let go for the iterations to come.
    fn pulled(&mut self, i: usize, f: P);
    /// The most a Newton step may move a particle, in multiples of the largest link's
    /// distance from its goal: `None` for no bound.
    fn reach(&self) -> Option<P::Scalar>;
    /// The least share `(n, d)` of the links' squared stretch a Newton iteration must take
    /// off for the iterations to go on (`None`: any).
    fn least_gain(&self) -> Option<(u32, u32)> {
        None
    }
}

impl<P: Point> Mobility<P> for &[P::Scalar] {
    fn free(&self, i: usize) -> bool {
        self[i] > P::Scalar::ZERO
    }

    fn along_link(&self, i: usize, _: P) -> Option<P::Scalar> {
        Some(self[i] + self[i + 1])
    }

    fn between(&self, i: usize, a: P, b: P) -> P::Scalar {
        self[i] * a.dot(b)
    }

    fn moved(&self, i: usize, f: P) -> P {
        f * self[i]
    }

    fn pulled(&mut self, _: usize, _: P) {}

    fn reach(&self) -> Option<P::Scalar> {
        None
    }
}

/// Inverse masses `w` with each particle that has a unit `normal` (the zero vector for
/// none) held along it: `W_i = w_i (I − n nᵀ)`, free across it. A link whose ends are held
/// so that it keeps less than 1/64 of its ends' mobility along itself (a link square to
/// what holds both its ends) sits the iteration out.
pub(super) struct Held<'a, P: Point> {
    pub(super) w: &'a [P::Scalar],
    pub(super) normal: &'a mut [P],
}

impl<P: Point> Mobility<P> for Held<'_, P> {
    fn free(&self, i: usize) -> bool {
        self.w[i] > P::Scalar::ZERO
    }

    fn along_link(&self, i: usize, d: P) -> Option<P::Scalar> {
        let full = self.w[i] + self.w[i + 1];
        let own = self.between(i, d, d) + self.between(i + 1, d, d);
        (own * P::Scalar::from_i16(64) >= full).then_some(own)
    }

    fn between(&self, i: usize, a: P, b: P) -> P::Scalar {
        let n = self.normal[i];
        self.w[i] * (a.dot(b) - a.dot(n) * b.dot(n))
    }

    fn moved(&self, i: usize, f: P) -> P {
        let n = self.normal[i];
        (f - n * f.dot(n)) * self.w[i]
    }

    fn pulled(&mut self, i: usize, f: P) {
        if f.dot(self.normal[i]) > P::Scalar::ZERO {
            self.normal[i] = P::default();
        }
    }

    fn reach(&self) -> Option<P::Scalar> {
        Some(P::Scalar::from_i16(REACH))
    }

    /// A sixteenth: links whose particles are held where they cannot reach their length
    /// gain less and less an iteration; the links then fall back to free particles sooner
    /// ([`DirectChain`]'s hold after contacts).
    fn least_gain(&self) -> Option<(u32, u32)> {
        Some((1, 16))
    }
}

/// How far a Newton step of held links may move a particle, in multiples of the largest
/// link's distance from its goal: where particles held across a link leave it barely
/// able to move along itself, its step would throw them across the scene.
const REACH: i16 = 4;
