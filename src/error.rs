//! The crate's one error type.

use crate::Scalar;
use core::fmt;

/// What went wrong. Every fallible call in the crate returns this; none of them panics.
/// Its `Display` text names the value, the limit it broke and, where there is one, what to
/// do about it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Error {
    /// An input coordinate or parameter is NaN, infinite, or a saturated `Q16`.
    NonFinite {
        /// What it is (`"position"`, `"wind velocity"`, ...).
        name: &'static str,
    },
    /// An input coordinate, or a result, is finite but beyond what the format holds safely:
    /// [`Scalar::SAFE_RANGE`](crate::Scalar::SAFE_RANGE) (`16 383` in `Q16`), or a system's
    /// [`bounds`](crate::Settings::bounds).
    OutOfRange {
        /// What it is.
        name: &'static str,
        /// The limit it is beyond (`±limit`).
        limit: f64,
    },
    /// The output buffer cannot hold what was asked for.
    BufferTooSmall {
        /// Elements the call needs.
        needed: usize,
        /// Elements the buffer has.
        got: usize,
    },
    /// A parameter is outside what the call accepts.
    InvalidParameter {
        /// Which parameter.
        name: &'static str,
        /// What it must be (`"finite and > 0"`, `"at most 4 096 steps a frame"`, ...).
        expected: &'static str,
    },
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
    /// The springs are so stiff that even [`MAX_SUBSTEPS`](crate::physics::system::MAX_SUBSTEPS)
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
            Error::NonFinite { name } => {
                write!(f, "{name} is NaN, infinite or a saturated Q16")
            }
            Error::OutOfRange { name, limit } => write!(
                f,
                "{name} is beyond ±{limit}, what the format holds safely: \
                 work in smaller units (metres, not pixels) or relative to an anchor"
            ),
            Error::BufferTooSmall { needed, got } => {
                write!(f, "buffer too small: needs {needed} elements, has {got}")
            }
            Error::InvalidParameter { name, expected } => write!(f, "{name} must be {expected}"),
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
            Error::Diverged => f.write_str(
                "the step left the scene's bounds or the format's range; \
                 the state before it was kept",
            ),
            Error::TooStiff => f.write_str(
                "the springs are too stiff for the substep limit in this format: \
                 soften them, add mass or use fewer particles; nothing changed",
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

/// What a finite, positive parameter must be.
pub(crate) const POSITIVE: &str = "finite and > 0";
/// What a finite, non-negative parameter must be.
pub(crate) const NON_NEGATIVE: &str = "finite and >= 0";
/// What a `Q16` parameter that saturated must be instead.
pub(crate) const SATURATED: &str =
    "within Q16's range (it saturated: Q16 holds -32 768 to 32 767.99998)";

/// The expectation a parameter `x` missed: [`SATURATED`] for a `Q16` value at the format's
/// limit (so the message says why), else `otherwise`.
fn missed<S: crate::Scalar>(x: S, otherwise: &'static str) -> &'static str {
    if S::FIXED_POINT && !x.is_finite() {
        SATURATED
    } else {
        otherwise
    }
}

/// [`Error::InvalidParameter`] for `name`, which must be `expected`.
pub(crate) const fn invalid(name: &'static str, expected: &'static str) -> Error {
    Error::InvalidParameter { name, expected }
}

/// [`Error::OutOfRange`] for `name` beyond the format's safe range.
pub(crate) fn out_of_range<S: crate::Scalar>(name: &'static str) -> Error {
    Error::OutOfRange {
        name,
        limit: S::SAFE_RANGE.to_f64(),
    }
}

/// Checks that every point (`name`) is finite and inside the safe range.
pub(crate) fn check_points<P: crate::Point>(points: &[P], name: &'static str) -> Result<(), Error> {
    for p in points {
        if !p.is_finite() {
            return Err(Error::NonFinite { name });
        }
        if !p.in_safe_range() {
            return Err(out_of_range::<P::Scalar>(name));
        }
    }
    Ok(())
}

/// [`Error::OutOfRange`] unless every coordinate of `points` (`name`) is within `±bounds`.
pub(crate) fn check_inside<P: crate::Point>(
    points: &[P],
    bounds: P::Scalar,
    name: &'static str,
) -> Result<(), Error> {
    let inside = points
        .iter()
        .all(|p| (0..P::DIM).all(|d| p.coord(d).abs() <= bounds));
    if inside {
        Ok(())
    } else {
        Err(Error::OutOfRange {
            name,
            limit: bounds.to_f64(),
        })
    }
}

/// `Ok(x)` when `x` is finite and `> 0`, else [`Error::InvalidParameter`] naming `name`.
pub(crate) fn check_positive<S: crate::Scalar>(x: S, name: &'static str) -> Result<S, Error> {
    if x > S::ZERO && x.is_finite() {
        Ok(x)
    } else {
        Err(invalid(name, missed(x, POSITIVE)))
    }
}

/// `Ok(x)` when `x` is finite and `>= 0`, else [`Error::InvalidParameter`] naming `name`.
pub(crate) fn check_non_negative<S: crate::Scalar>(x: S, name: &'static str) -> Result<S, Error> {
    if x >= S::ZERO && x.is_finite() {
        Ok(x)
    } else {
        Err(invalid(name, missed(x, NON_NEGATIVE)))
    }
}

/// `Ok(w)` for an inverse mass: 0 (pinned), or `> 0` and finite with a mass `1 / w` within
/// [`Scalar::SAFE_RANGE`](crate::Scalar::SAFE_RANGE) (in `Q16`, `w` of at least
/// `5 / 65 536`), so that a momentum, mass times a velocity in the safe range, fits the
/// format; else [`Error::InvalidParameter`].
pub(crate) fn check_inv_mass<S: crate::Scalar>(w: S) -> Result<S, Error> {
    const EXPECTED: &str =
        "0 (pinned) or the inverse of a mass within the safe range (Q16: 1/16383 to 13107)";
    if check_non_negative(w, "inverse mass").map_err(|_| invalid("inverse mass", EXPECTED))?
        == S::ZERO
        || (S::ONE / w).in_safe_range()
    {
        Ok(w)
    } else {
        Err(invalid("inverse mass", EXPECTED))
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
