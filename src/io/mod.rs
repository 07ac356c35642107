//! Drawing and loading: the [`View`](crate::View) from the world to cells or pixels, the
//! ASCII canvas, embedded-graphics drawing and the thesis's XML files. Uses the layers
//! below.

pub mod ascii;
#[cfg(feature = "embedded-graphics")]
pub mod graphics;
pub(crate) mod view;
#[cfg(all(feature = "xml", dunas_std))]
pub mod xml;
