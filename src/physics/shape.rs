//! How particles are laid out in memory: a row (`Line`) or a grid (`Grid`).
//!
//! Stable Rust cannot write `U * V` in a type, so a cloth cannot store `[P; U * V]`. A
//! [`Shape`] names the fixed-size array for one value per particle (`[T; N]` or
//! `[[T; U]; V]`) and views it as a flat slice, so the physics is written once and its
//! scratch arrays have the right size on the stack.

/// A fixed particle layout. Implemented by [`Line`] and [`Grid`].
pub trait Shape {
    /// Number of particles.
    const LEN: usize;
    /// Particles a row: a grid's `U`, every particle of a line (one row).
    const COLUMNS: usize;
    /// The widest spring, in flat index offset, that a banded solve
    /// ([`DirectSprings`](crate::physics::integrator::DirectSprings)) keeps in its matrix: 2 for a
    /// line (its links and bending springs), `2U` for a grid (its structural, shear and
    /// bending springs).
    const BAND: usize;
    /// One `T` per particle.
    type PerParticle<T: Copy>: Copy;
    /// [`BAND`](Self::BAND) `T`s: one row of a banded matrix.
    type Band<T: Copy>: Copy;
    /// An array with every element `value`.
    fn filled<T: Copy>(value: T) -> Self::PerParticle<T>;
    /// The elements in order (row by row for a grid).
    fn flat<T: Copy>(a: &Self::PerParticle<T>) -> &[T];
    /// The elements in order, mutable.
    fn flat_mut<T: Copy>(a: &mut Self::PerParticle<T>) -> &mut [T];
    /// A band row with every element `value`.
    fn band<T: Copy>(value: T) -> Self::Band<T>;
    /// A band row's [`BAND`](Self::BAND) elements.
    fn band_flat<T: Copy>(a: &Self::Band<T>) -> &[T];
    /// A band row's [`BAND`](Self::BAND) elements, mutable.
    fn band_mut<T: Copy>(a: &mut Self::Band<T>) -> &mut [T];
}

/// `N` particles in a row: a rope. Storage `[T; N]`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Line<const N: usize>;

/// `V` rows of `U` particles: a cloth. Storage `[[T; U]; V]`, particle `(i, j)` at flat
/// index `j * U + i`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Grid<const U: usize, const V: usize>;

impl<const N: usize> Shape for Line<N> {
    const LEN: usize = N;
    const COLUMNS: usize = N;
    const BAND: usize = 2;
    type PerParticle<T: Copy> = [T; N];
    type Band<T: Copy> = [T; 2];
    #[inline]
    fn filled<T: Copy>(value: T) -> [T; N] {
        [value; N]
    }
    #[inline]
    fn flat<T: Copy>(a: &[T; N]) -> &[T] {
        a
    }
    #[inline]
    fn flat_mut<T: Copy>(a: &mut [T; N]) -> &mut [T] {
        a
    }
    #[inline]
    fn band<T: Copy>(value: T) -> [T; 2] {
        [value; 2]
    }
    #[inline]
    fn band_flat<T: Copy>(a: &[T; 2]) -> &[T] {
        a
    }
    #[inline]
    fn band_mut<T: Copy>(a: &mut [T; 2]) -> &mut [T] {
        a
    }
}

impl<const U: usize, const V: usize> Shape for Grid<U, V> {
    const LEN: usize = U * V;
    const COLUMNS: usize = U;
    const BAND: usize = 2 * U;
    type PerParticle<T: Copy> = [[T; U]; V];
    /// `2U` slots: stable Rust cannot write `[T; 2 * U]`.
    type Band<T: Copy> = [[T; U]; 2];
    #[inline]
    fn filled<T: Copy>(value: T) -> [[T; U]; V] {
        [[value; U]; V]
    }
    #[inline]
    fn flat<T: Copy>(a: &[[T; U]; V]) -> &[T] {
        a.as_flattened()
    }
    #[inline]
    fn flat_mut<T: Copy>(a: &mut [[T; U]; V]) -> &mut [T] {
        a.as_flattened_mut()
    }
    #[inline]
    fn band<T: Copy>(value: T) -> [[T; U]; 2] {
        [[value; U]; 2]
    }
    #[inline]
    fn band_flat<T: Copy>(a: &[[T; U]; 2]) -> &[T] {
        a.as_flattened()
    }
    #[inline]
    fn band_mut<T: Copy>(a: &mut [[T; U]; 2]) -> &mut [T] {
        a.as_flattened_mut()
    }
}
