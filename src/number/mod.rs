//! Number formats: the [`Scalar`](crate::Scalar) trait over `f32`, `f64` and the Q16.16
//! fixed point [`Q16`](crate::Q16), and the float math behind them. Uses nothing else of the crate.

#[cfg(dunas_floats)]
pub(crate) mod math;
#[cfg(feature = "fixed")]
pub(crate) mod q16;
#[cfg(feature = "fixed")]
mod q16_bits;
pub mod scalar;
