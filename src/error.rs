//! The crate's one error type.

use crate::Scalar;
use core::fmt;

/// What went wrong. Every fallible call in the crate returns this; none of them panics.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error {
    /// An input coordinate or parameter is NaN, infinite, or a saturated `Q16`.
    NonFinite,
    /// An input coordinate is finite but beyond [`Scalar::SAFE_RANGE`](crate::Scalar::SAFE_RANGE).
    OutOfRange,
    /// The output buffer cannot hold what was asked for.
    BufferTooSmall {
        /// Elements the call needs.
        needed: usize,
        /// Elements the buffer has.
        got: usize,
    },
    /// A tolerance or other parameter is zero, negative or otherwise unusable.
    InvalidParameter,
    /// A spring names a particle index at or past the particle count.
    IndexOutOfRange {
        /// The offending index.
        index: usize,
        /// The number of particles.
        len: usize,
    },
    /// A spring joins a particle to itself or repeats a pair already connected.
    DuplicateSpring {
        /// First particle.
        a: usize,
        /// Second particle.
        b: usize,
    },
    /// A spring's rest length is zero (its two particles start at the same place) or not finite.
    ZeroRestLength {
        /// First particle.
        a: usize,
        /// Second particle.
        b: usize,
    },
    /// More springs than the topology's compile-time capacity.
    CapacityExceeded {
        /// The capacity.
        capacity: usize,
    },
    /// The simulation blew up during a step (a position or velocity became non-finite or left
    /// the scene bounds). The state before the step was kept.
    Diverged,
    /// The springs are so stiff that even [`MAX_SUBSTEPS`](crate::system::MAX_SUBSTEPS)
    /// substeps would advance no time in this format (the scene would freeze). Nothing
    /// changed.
    TooStiff,
    /// The call needs a free particle, and this one is pinned (inverse mass 0).
    Pinned {
        /// The particle.
        index: usize,
    },
    /// The call draws one curve through the whole rope, and the rope has come apart: draw
    /// its pieces with [`Rope::draw`](crate::Rope::draw).
    Cut {
        /// How many pieces the rope is in.
        pieces: usize,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NonFinite => f.write_str("input is NaN, infinite or saturated"),
            Error::OutOfRange => f.write_str("input coordinate is beyond the format's safe range"),
            Error::BufferTooSmall { needed, got } => {
                write!(f, "buffer too small: needs {needed} elements, has {got}")
            }
            Error::InvalidParameter => f.write_str("parameter is zero, negative or not finite"),
            Error::IndexOutOfRange { index, len } => {
                write!(f, "particle index {index} out of range for {len} particles")
            }
            Error::DuplicateSpring { a, b } => {
                write!(
                    f,
                    "spring {a}-{b} repeats a connection or joins a particle to itself"
                )
            }
            Error::ZeroRestLength { a, b } => write!(f, "spring {a}-{b} has zero rest length"),
            Error::CapacityExceeded { capacity } => {
                write!(f, "more springs than the capacity of {capacity}")
            }
            Error::Diverged => {
                f.write_str("the simulation diverged; the state before the step was kept")
            }
            Error::TooStiff => f.write_str(
                "the springs are too stiff for the substep limit in this format; nothing changed",
            ),
            Error::Pinned { index } => write!(f, "particle {index} is pinned"),
            Error::Cut { pieces } => write!(
                f,
                "the rope is cut into {pieces} pieces: draw it with Rope::draw, one curve a piece"
            ),
        }
    }
}

#[cfg(dunas_std)]
impl std::error::Error for Error {}

/// Checks that every point is finite and inside the safe range.
pub(crate) fn check_points<P: crate::Point>(points: &[P]) -> Result<(), Error> {
    for p in points {
        if !p.is_finite() {
            return Err(Error::NonFinite);
        }
        if !p.in_safe_range() {
            return Err(Error::OutOfRange);
        }
    }
    Ok(())
}

/// [`Error::OutOfRange`] unless every coordinate of `points` is within `±bounds`.
pub(crate) fn check_inside<P: crate::Point>(points: &[P], bounds: P::Scalar) -> Result<(), Error> {
    let inside = points
        .iter()
        .all(|p| (0..P::DIM).all(|d| p.coord(d).abs() <= bounds));
    if inside {
        Ok(())
    } else {
        Err(Error::OutOfRange)
    }
}

/// `Ok(x)` when `x` is finite and `> 0`, else [`Error::InvalidParameter`].
pub(crate) fn check_positive<S: crate::Scalar>(x: S) -> Result<S, Error> {
    if x > S::ZERO && x.is_finite() {
        Ok(x)
    } else {
        Err(Error::InvalidParameter)
    }
}

/// `Ok(x)` when `x` is finite and `>= 0`, else [`Error::InvalidParameter`].
pub(crate) fn check_non_negative<S: crate::Scalar>(x: S) -> Result<S, Error> {
    if x >= S::ZERO && x.is_finite() {
        Ok(x)
    } else {
        Err(Error::InvalidParameter)
    }
}

/// `Ok(w)` for an inverse mass: 0 (pinned), or `> 0` and finite with a mass `1 / w` within
/// [`Scalar::SAFE_RANGE`](crate::Scalar::SAFE_RANGE) (in `Q16`, `w` of at least
/// `5 / 65 536`), so that a momentum, mass times a velocity in the safe range, fits the
/// format; else [`Error::InvalidParameter`].
pub(crate) fn check_inv_mass<S: crate::Scalar>(w: S) -> Result<S, Error> {
    if check_non_negative(w)? == S::ZERO || (S::ONE / w).in_safe_range() {
        Ok(w)
    } else {
        Err(Error::InvalidParameter)
    }
}

/// `Ok(index)` when `index < len`, else [`Error::IndexOutOfRange`].
pub(crate) fn check_index(index: usize, len: usize) -> Result<usize, Error> {
    if index < len {
        Ok(index)
    } else {
        Err(Error::IndexOutOfRange { index, len })
    }
}
