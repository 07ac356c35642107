//! The crate's one error type.

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
        }
    }
}

#[cfg(feature = "std")]
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
