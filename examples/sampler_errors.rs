//! Measures the worst error of every sampler against an exact integer reference, for each
//! number format, degree 3 and 7, 64 and 1024 samples, control points at 10² and 10⁴ px.
//!
//! Run: `cargo run --release --all-features --example sampler_errors`
//!
//! Prints a Markdown table of the largest distance (px) between a sample and the exact
//! curve over 40 random curves per cell. [`Subdivide`] writes `2^k + 1` points, so it gets
//! buffers of 65 and 1025.

#[path = "../tests/common/mod.rs"]
mod common;

use common::{ExactCurve, Rng};
use dunas::sampler::{BernsteinTable, DeCasteljau, ForwardDiff, Horner, Sampler, Subdivide};
use dunas::{Scalar, Vec2};

const CURVES: usize = 40;

fn worst<S: Scalar, const N: usize>(
    scale: i64,
    len: usize,
    sampler: &impl Sampler<Vec2<S>, N>,
) -> f64 {
    let mut rng = Rng(0x5eed ^ (scale as u64) ^ ((N as u64) << 32));
    let mut buf = vec![Vec2::<S>::default(); len];
    let mut worst = 0.0f64;
    for _ in 0..CURVES {
        let c = ExactCurve::<S, N>::new(rng.grid_points(scale));
        let n = sampler
            .sample(&c.curve, &mut buf)
            .expect("buffer is large enough");
        worst = worst.max(c.max_error(&buf[..n], (n - 1) as u64));
    }
    worst
}

fn row<S: Scalar, const N: usize, const M: usize>(format: &str, scale: i64) {
    let table = BernsteinTable::<S, N, M>::new();
    let cells = [
        worst::<S, N>(scale, M, &DeCasteljau),
        worst::<S, N>(scale, M, &table),
        worst::<S, N>(scale, M, &Horner),
        worst::<S, N>(scale, M, &ForwardDiff),
        worst::<S, N>(scale, M + 1, &Subdivide::default()),
    ];
    print!(
        "| {format} | {} | {M} | 1e{} |",
        N - 1,
        (scale as f64).log10()
    );
    for c in cells {
        print!(" {c:.2e} |");
    }
    println!();
}

fn rows<S: Scalar>(format: &str) {
    for scale in [100, 10_000] {
        row::<S, 4, 64>(format, scale);
        row::<S, 4, 1024>(format, scale);
        row::<S, 8, 64>(format, scale);
        row::<S, 8, 1024>(format, scale);
    }
}

fn main() {
    println!(
        "| format | degree | samples | coords (px) | de Casteljau | Bernstein table | Horner | forward diff | subdivide |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    rows::<f32>("f32");
    rows::<f64>("f64");
    #[cfg(feature = "fixed")]
    rows::<dunas::Q16>("Q16.16");
}
