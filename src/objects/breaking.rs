//! Ropes that snap and are cut: [`Snap`] limits on the springs, the pieces a broken rope
//! falls into, each drawn as its own curve, and swipes that cut the rope where it was drawn.
//!
//! A rope never reallocates: a snapped or cut spring stays in its slot, broken for good, and
//! the particles it joined carry on in separate pieces. A piece is a run of particles still
//! joined to their neighbours along the chain (`i` to `i + 1`).
//!
//! ```
//! use dunas::prelude::*;
//! use dunas::breaking::Piece;
//! use dunas::spring::Snap;
//!
//! let settings = Settings { gravity: Vec2::new(0.0, -9.8), damping: 0.5, ..Settings::default() };
//! let m = Material { stiffness: 400.0, damping: 1.0 };
//! let mut rope: Rope<Vec2<f32>, 8> = Rope::new(Vec2::new(-3.5, 0.0), Vec2::new(3.5, 0.0), 1.0, m, settings)?;
//! rope.set_inv_mass(7, 0.0)?; // a rope bridge
//! rope.set_snap(Snap::Stretch(1.5))?;
//! let (mut points, mut pieces) = ([Vec2::default(); 64], [Piece::EMPTY; 8]);
//! assert_eq!(rope.draw(Smoothing::CatmullRom, &mut points, &mut pieces)?, 1);
//! // A swipe down through the middle of the drawn rope cuts it there.
//! let cut = rope.cut(&points, &pieces[..1], Vec2::new(0.2, 1.0), Vec2::new(0.2, -3.0))?;
//! assert_eq!(cut, Some(3)); // between particles 3 and 4
//! assert_eq!(rope.draw(Smoothing::CatmullRom, &mut points, &mut pieces)?, 2);
//! assert_eq!(pieces[0].particles, 0..4);
//! assert_eq!(points[pieces[1].points.start], rope.positions()[4]); // each piece ends on its particles
//! # Ok::<(), dunas::Error>(())
//! ```

use crate::error::invalid;
use core::ops::Range;

use crate::curves::smooth::{Smoothed, Smoothing};
use crate::error::check_points;
use crate::geometry::segment::crossing;
use crate::physics::integrator::Integrator;
use crate::physics::shape::Shape;
use crate::physics::spring::{Snap, Springs};
use crate::{Cloth, Error, MassSpring, Point, Rope, Scalar, Torus, Vec2};

/// One piece of a drawn rope: its particles and the points [`Rope::draw`] wrote for it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Piece {
    /// The piece's particles (indices into the rope).
    pub particles: Range<usize>,
    /// Its drawn points (indices into the points buffer); one point for a lone particle.
    pub points: Range<usize>,
}

impl Piece {
    /// No particles, no points: what a buffer of pieces starts as (`[Piece::EMPTY; 8]`).
    pub const EMPTY: Piece = Piece {
        particles: 0..0,
        points: 0..0,
    };
}

impl<P: Point, Sh: Shape, const CAP: usize, I: Integrator>
    MassSpring<P, Sh, Springs<P::Scalar, CAP>, I>
{
    /// Sets when every spring snaps (see [`Springs::set_snap`]); checked at the end of every
    /// step, and a snap reported in [`StepInfo::snapped`](crate::physics::system::StepInfo::snapped).
    ///
    /// # Errors
    /// As [`Snap::check`]; nothing changes then.
    pub fn set_snap(&mut self, snap: Snap<P::Scalar>) -> Result<(), Error> {
        snap.check()?;
        self.with_topology(|s| s.set_snap(snap))
    }

    /// Sets when spring `index` alone snaps (see [`Springs::set_spring_snap`]).
    ///
    /// # Errors
    /// As [`Springs::set_spring_snap`]; nothing changes then.
    pub fn set_spring_snap(&mut self, index: usize, snap: Snap<P::Scalar>) -> Result<(), Error> {
        snap.check()?;
        self.with_topology(|s| s.set_spring_snap(index, snap))
    }
}

impl<P: Point, const N: usize, const CAP: usize, I: Integrator> Rope<P, N, CAP, I> {
    /// The rope's pieces, in order: runs of particles joined by unbroken chain springs (one
    /// run, `0..N`, until something snaps or is cut).
    pub fn pieces(&self) -> impl Iterator<Item = Range<usize>> + '_ {
        let springs = self.topology();
        let mut start = 0;
        core::iter::from_fn(move || {
            if start >= N {
                return None;
            }
            let mut end = start + 1;
            while end < N && springs.joins(end - 1, end) {
                end += 1;
            }
            let run = start..end;
            start = end;
            Some(run)
        })
    }

    /// Draws every piece as its own curve (`smoothing` over the piece's particles, so each
    /// starts and ends on its end particles) into `out`, and describes them in `pieces`;
    /// returns the piece count. Points are shared by span: a piece of `m` particles gets at
    /// least `m` points, and `out`'s spare points go to the pieces by their spans. A lone
    /// particle is drawn as one point. With one piece this is [`sample`](Rope::sample).
    ///
    /// # Errors
    /// [`Error::BufferTooSmall`] when `out` holds fewer than `N` points or `pieces` fewer
    /// than the rope's pieces; the errors of [`Smoothed::open`].
    pub fn draw(
        &self,
        smoothing: Smoothing,
        out: &mut [P],
        pieces: &mut [Piece],
    ) -> Result<usize, Error> {
        if out.len() < N {
            return Err(Error::BufferTooSmall {
                needed: N,
                got: out.len(),
            });
        }
        let count = self.pieces().count();
        if pieces.len() < count {
            return Err(Error::BufferTooSmall {
                needed: count,
                got: pieces.len(),
            });
        }
        let spans: usize = self.pieces().map(|r| r.len() - 1).sum();
        let spare = out.len() - N;
        let positions = self.positions();
        let mut next = 0;
        for (piece, run) in pieces.iter_mut().zip(self.pieces()) {
            let m = run.len();
            let share = m + (spare * (m - 1)).checked_div(spans).unwrap_or(0);
            let written = if m == 1 {
                out[next] = positions[run.start];
                1
            } else {
                let mut row = [positions[run.start]; N];
                row[..m].copy_from_slice(&positions[run.clone()]);
                Smoothed::open_first(smoothing, &row, m)?.sample(&mut out[next..next + share])?
            };
            *piece = Piece {
                particles: run,
                points: next..next + written,
            };
            next += written;
        }
        Ok(count)
    }
}

impl<S: Scalar, const N: usize, const CAP: usize, I: Integrator> Rope<Vec2<S>, N, CAP, I> {
    /// Cuts the rope where a swipe from `from` to `to` first crosses it *as drawn*: `points`
    /// and `pieces` are what [`draw`](Rope::draw) wrote (the frame the player saw). The span
    /// of the drawn curve that the swipe hits is cut, however few particles the rope has: its
    /// chain spring `i`–`i + 1` and every spring across it break. Returns `i`, or `None`
    /// when the swipe misses (or hits a span already cut). Cost: one segment test per drawn
    /// point, and one pass over the springs on a hit.
    ///
    /// # Errors
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] for a swipe end that is NaN, infinite or
    /// beyond the safe range; [`Error::InvalidParameter`] for pieces that do not fit the
    /// rope or `points`. The rope is untouched on an error.
    pub fn cut(
        &mut self,
        points: &[Vec2<S>],
        pieces: &[Piece],
        from: Vec2<S>,
        to: Vec2<S>,
    ) -> Result<Option<usize>, Error> {
        check_points(&[from, to], "from or to")?;
        let (lo, hi) = (from.min_coords(to), from.max_coords(to));
        let mut first: Option<(S, usize)> = None;
        for piece in pieces {
            let (particles, drawn) = (&piece.particles, &piece.points);
            if particles.start >= particles.end
                || particles.end > N
                || drawn.start > drawn.end
                || drawn.end > points.len()
            {
                return Err(invalid(
                    "pieces",
                    "what Rope::draw wrote for this rope and these points (pass &pieces[..count])",
                ));
            }
            let (m, q) = (particles.len(), drawn.len());
            if m < 2 || q < 2 {
                continue;
            }
            for (j, pair) in points[drawn.clone()].windows(2).enumerate() {
                let (a, b) = (pair[0], pair[1]);
                // The swipe's box first: most of the curve is far from it.
                if a.x.max(b.x) < lo.x
                    || a.x.min(b.x) > hi.x
                    || a.y.max(b.y) < lo.y
                    || a.y.min(b.y) > hi.y
                {
                    continue;
                }
                let Some((along, across)) = crossing(a, b, from, to) else {
                    continue;
                };
                if first.is_some_and(|(best, _)| best <= across) {
                    continue;
                }
                // Where the hit lies along the piece, in particle spans.
                let spans = S::ratio((m - 1) as u32, 1);
                let at = (S::ratio(j as u32, 1) + along) * spans / S::ratio((q - 1) as u32, 1);
                let span = (at.floor_i32().max(0) as usize).min(m - 2);
                first = Some((across, particles.start + span));
            }
        }
        let Some((_, i)) = first else {
            return Ok(None);
        };
        let cut = self.break_springs(|s| s.cut_across(i));
        Ok((cut > 0).then_some(i))
    }
}

impl<P: Point, const U: usize, const V: usize, I: Integrator> Cloth<P, U, V, I> {
    /// Sets when the structural, shear and bending springs tear ([`Snap`] per class);
    /// checked at the end of every step like a rope's, reported in
    /// [`StepInfo::snapped`](crate::physics::system::StepInfo::snapped). A torn cloth keeps its grid:
    /// draw it raw ([`Smoothing::Polyline`]) or with the smooth surface, which spans the tear.
    ///
    /// # Errors
    /// As [`Snap::check`], for the first bad limit; nothing changes then.
    pub fn set_snap(&mut self, limits: [Snap<P::Scalar>; 3]) -> Result<(), Error> {
        let limits = checked(limits)?;
        self.with_topology(|g| g.snap = limits);
        Ok(())
    }

    /// Tears every spring whose segment, seen along the first two coordinates (the screen's
    /// x and y), crosses a swipe from `from` to `to`; returns how many tore. Cost: one
    /// segment test per spring.
    ///
    /// # Errors
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] for a swipe end that is NaN, infinite or
    /// beyond the safe range; nothing changes then.
    pub fn cut(&mut self, from: Vec2<P::Scalar>, to: Vec2<P::Scalar>) -> Result<usize, Error> {
        check_points(&[from, to], "from or to")?;
        let x = *self.position_array();
        let flat: &[P] = x.as_flattened();
        Ok(self.break_springs(|g| g.tear_across(flat, from, to)))
    }
}

impl<S: Scalar, const U: usize, const V: usize, I: Integrator> Torus<S, U, V, I> {
    /// Sets when the structural, shear and bending springs tear ([`Snap`] per class), as
    /// [`Cloth::set_snap`]: a torus blown past what its springs hold bursts. The gas cannot
    /// see the springs: when a step reports
    /// [`StepInfo::snapped`](crate::physics::system::StepInfo::snapped), let it out
    /// ([`Pressure::pop`](crate::force::Pressure::pop)).
    ///
    /// # Errors
    /// As [`Snap::check`], for the first bad limit; nothing changes then.
    pub fn set_snap(&mut self, limits: [Snap<S>; 3]) -> Result<(), Error> {
        let limits = checked(limits)?;
        self.with_topology(|t| t.snap = limits);
        Ok(())
    }
}

/// `limits` when every one passes [`Snap::check`].
fn checked<S: Scalar>(limits: [Snap<S>; 3]) -> Result<[Snap<S>; 3], Error> {
    for limit in limits {
        limit.check()?;
    }
    Ok(limits)
}
