//! Cost per point of every sampler × number format × degree (3, 7) × sample count (64,
//! 1024), and of patch grids.
//!
//! Run: `cargo bench -p dunas-evaluate --bench samplers`; criterion reports time per sample
//! point (throughput "elements"). Control points are at the 10⁴ px scale (10² for `Q16`,
//! whose range ends at 32768).

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use dunas::sampler::{BernsteinTable, DeCasteljau, ForwardDiff, Horner, Sampler, Subdivide};
use dunas::{Bezier, Patch, Scalar, Vec2, Vec3};

fn curve<S: Scalar, const N: usize>(scale: f64) -> Bezier<Vec2<S>, N> {
    Bezier::new(core::array::from_fn(|i| {
        let a = i as f64 * 2.1;
        Vec2::from_f64(scale * a.cos(), scale * (a * 1.3).sin())
    }))
    .unwrap()
}

fn bench_one<S: Scalar, const N: usize>(
    c: &mut Criterion,
    format: &str,
    name: &str,
    len: usize,
    sampler: &impl Sampler<Vec2<S>, N>,
    scale: f64,
) {
    let curve = curve::<S, N>(scale);
    let mut out = vec![Vec2::<S>::default(); len];
    let n = sampler.sample(&curve, &mut out).unwrap();
    let mut g = c.benchmark_group(format!("sample/{format}/degree{}", N - 1));
    g.throughput(Throughput::Elements(n as u64));
    g.bench_function(BenchmarkId::new(name, n), |b| {
        b.iter(|| sampler.sample(black_box(&curve), black_box(&mut out)))
    });
    g.finish();
}

fn bench_format<S: Scalar, const N: usize, const M: usize>(
    c: &mut Criterion,
    format: &str,
    scale: f64,
) {
    let table = BernsteinTable::<S, N, M>::new();
    bench_one::<S, N>(c, format, "de_casteljau", M, &DeCasteljau, scale);
    bench_one::<S, N>(c, format, "bernstein_table", M, &table, scale);
    bench_one::<S, N>(c, format, "horner", M, &Horner, scale);
    bench_one::<S, N>(c, format, "forward_diff", M, &ForwardDiff, scale);
    bench_one::<S, N>(c, format, "subdivide", M + 1, &Subdivide::default(), scale);
}

fn bench_all<S: Scalar>(c: &mut Criterion, format: &str, scale: f64) {
    bench_format::<S, 4, 64>(c, format, scale);
    bench_format::<S, 4, 1024>(c, format, scale);
    bench_format::<S, 8, 64>(c, format, scale);
    bench_format::<S, 8, 1024>(c, format, scale);
}

fn samplers(c: &mut Criterion) {
    bench_all::<f32>(c, "f32", 1e4);
    bench_all::<f64>(c, "f64", 1e4);
    bench_all::<dunas::Q16>(c, "q16", 1e2);
}

fn patch<const U: usize, const V: usize>(c: &mut Criterion) {
    let p: Patch<Vec3<f32>, U, V> = Patch::new(core::array::from_fn(|j| {
        core::array::from_fn(|i| Vec3::new(i as f32, j as f32, ((i * j) % 3) as f32))
    }))
    .unwrap();
    let mut pos = [Vec3::default(); 256];
    let mut nor = [Vec3::default(); 256];
    let mut g = c.benchmark_group(format!("patch/f32/{U}x{V}"));
    g.throughput(Throughput::Elements(256));
    g.bench_function("grid16x16", |b| {
        b.iter(|| black_box(&p).sample_grid(16, 16, &mut pos))
    });
    g.bench_function("grid16x16_normals", |b| {
        b.iter(|| black_box(&p).sample_grid_with_normals(16, 16, &mut pos, &mut nor))
    });
    g.finish();
}

fn patches(c: &mut Criterion) {
    patch::<4, 4>(c);
    patch::<8, 8>(c);
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(800))
        .sample_size(30);
    targets = samplers, patches
}
criterion_main!(benches);
