//! Exact references shared by the tests and the measuring examples.
#![allow(dead_code)]

use dunas::{Bezier, Point, Scalar, Vec2};

/// Control points on a grid of `1 / DENOM`: exactly representable in f32, f64 and Q16.
pub const DENOM: i64 = 16;

/// A curve with integer-grid control points, kept both exactly and in format `S`.
pub struct ExactCurve<S: Scalar, const N: usize> {
    /// Control point coordinates times `DENOM`.
    pub grid: [[i64; 2]; N],
    /// The same curve in the format under test.
    pub curve: Bezier<Vec2<S>, N>,
}

impl<S: Scalar, const N: usize> ExactCurve<S, N> {
    pub fn new(grid: [[i64; 2]; N]) -> Self {
        let pts =
            grid.map(|[x, y]| Vec2::from_f64(x as f64 / DENOM as f64, y as f64 / DENOM as f64));
        ExactCurve {
            grid,
            curve: Bezier::new(pts).expect("grid points are in range"),
        }
    }

    /// The exact point at `t = i / m`, rounded once to f64.
    ///
    /// `Σ C(d,k) (m-i)^(d-k) i^k P_k / (m^d · DENOM)` in 128-bit integers: exact while
    /// `m^d · 2^(d+1) · |P|·DENOM < 2^127` (d = 7, m = 1024, |P| = 10^4: about 2^93).
    pub fn exact(&self, i: u64, m: u64) -> [f64; 2] {
        let d = (N - 1) as u32;
        let (i, m) = (i as i128, m as i128);
        let mut num = [0i128; 2];
        let mut binom: i128 = 1;
        for k in 0..=d {
            let w = binom * (m - i).pow(d - k) * i.pow(k);
            for (c, n) in num.iter_mut().enumerate() {
                *n += w * self.grid[k as usize][c] as i128;
            }
            binom = binom * (d - k) as i128 / (k + 1) as i128;
        }
        let den = m.pow(d) * DENOM as i128;
        num.map(|n| n as f64 / den as f64)
    }

    /// Largest distance between `samples` (taken at `t = i / m`) and the exact curve.
    pub fn max_error(&self, samples: &[Vec2<S>], m: u64) -> f64 {
        samples
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let [x, y] = self.exact(i as u64, m);
                if !p.is_finite() {
                    return f64::INFINITY;
                }
                (p.x.to_f64() - x).hypot(p.y.to_f64() - y)
            })
            .fold(0.0, f64::max)
    }
}

/// A small deterministic generator (xorshift64*), so measurements repeat exactly.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// Uniform in `-scale..=scale` on the `1 / DENOM` grid.
    pub fn grid(&mut self, scale: i64) -> i64 {
        let span = (2 * scale * DENOM + 1) as u64;
        (self.next_u64() % span) as i64 - scale * DENOM
    }

    pub fn grid_points<const N: usize>(&mut self, scale: i64) -> [[i64; 2]; N] {
        core::array::from_fn(|_| [self.grid(scale), self.grid(scale)])
    }
}
