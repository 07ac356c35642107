//! (a) Samplers: nanoseconds per point against the largest error versus the exact integer
//! reference, for each method × number format × degree 3 and 7 × 64 and 1024 samples ×
//! control points at 10² and 10⁴ px.

use dunas::sampler::{BernsteinTable, DeCasteljau, ForwardDiff, Horner, Sampler, Subdivide};
use dunas::{Scalar, Vec2};

use crate::common::{ExactCurve, Rng};
use crate::report::{Run, Series, chart, csv, median_ns, num};

const METHODS: [&str; 5] = [
    "BernsteinTable",
    "DeCasteljau",
    "Horner",
    "ForwardDiff",
    "Subdivide",
];

/// (method, ns per point, max error px) for one format, degree, count and scale.
fn cell<S: Scalar, const N: usize, const M: usize>(
    run: &Run,
    scale: i64,
) -> Vec<(usize, f64, f64)> {
    let curves = if run.quick { 4 } else { 20 };
    let table = BernsteinTable::<S, N, M>::new();
    let samplers: [&dyn Sampler<Vec2<S>, N>; 5] = [
        &table,
        &DeCasteljau,
        &Horner,
        &ForwardDiff,
        &Subdivide::default(),
    ];
    let mut out = Vec::new();
    for (k, sampler) in samplers.iter().enumerate() {
        // Subdivide writes 2^k + 1 points: give it one more slot.
        let len = if k == 4 { M + 1 } else { M };
        let mut buf = vec![Vec2::<S>::default(); len];
        let mut rng = Rng(0xa11 ^ scale as u64 ^ ((N * M) as u64) << 20);
        let mut worst = 0.0f64;
        let mut first = None;
        for _ in 0..curves {
            let c = ExactCurve::<S, N>::new(rng.grid_points(scale));
            let n = sampler
                .sample(&c.curve, &mut buf)
                .expect("buffer is large enough");
            worst = worst.max(c.max_error(&buf[..n], (n - 1) as u64));
            first.get_or_insert(c);
        }
        let c = first.expect("at least one curve");
        let n = sampler
            .sample(&c.curve, &mut buf)
            .expect("buffer is large enough");
        let inner = (20_000 / n).max(1);
        let ns = median_ns(run.reps(), inner, || {
            std::hint::black_box(
                sampler
                    .sample(std::hint::black_box(&c.curve), &mut buf)
                    .ok(),
            );
        }) / n as f64;
        out.push((k, ns, worst));
    }
    out
}

fn format_rows<S: Scalar>(
    run: &Run,
    format: &str,
    rows: &mut Vec<Vec<String>>,
    points: &mut [Vec<(f64, f64)>; 5],
) {
    for scale in [100i64, 10_000] {
        let cells = [
            (3, 64, cell::<S, 4, 64>(run, scale)),
            (3, 1024, cell::<S, 4, 1024>(run, scale)),
            (7, 64, cell::<S, 8, 64>(run, scale)),
            (7, 1024, cell::<S, 8, 1024>(run, scale)),
        ];
        for (degree, count, results) in cells {
            for (k, ns, err) in results {
                rows.push(vec![
                    format.into(),
                    METHODS[k].into(),
                    degree.to_string(),
                    count.to_string(),
                    scale.to_string(),
                    format!("{ns:.3}"),
                    format!("{err:.3e}"),
                ]);
                points[k].push((ns, err));
            }
        }
    }
}

pub fn run(run: &mut Run) {
    let mut rows = Vec::new();
    let mut charts = Vec::new();
    for (format, name) in [
        ("f32", "samplers_f32.svg"),
        ("f64", "samplers_f64.svg"),
        ("Q16.16", "samplers_q16.svg"),
    ] {
        let mut points: [Vec<(f64, f64)>; 5] = Default::default();
        match format {
            "f32" => format_rows::<f32>(run, format, &mut rows, &mut points),
            "f64" => format_rows::<f64>(run, format, &mut rows, &mut points),
            _ => format_rows::<dunas::Q16>(run, format, &mut rows, &mut points),
        }
        let series: Vec<Series> = METHODS
            .iter()
            .zip(points)
            .map(|(m, p)| Series::dots(*m, p))
            .collect();
        let title = format!(
            "Samplers in {format}: cost against error (degree 3 and 7, 64 and 1024 points, 1e2 and 1e4 px)"
        );
        chart(
            &run.path(name),
            &title,
            "ns per point",
            "max error (px) vs exact",
            &series,
            true,
        );
        charts.push(name);
    }
    csv(
        &run.path("samplers.csv"),
        &[
            "format",
            "method",
            "degree",
            "samples",
            "scale_px",
            "ns_per_point",
            "max_error_px",
        ],
        &rows,
    );

    // Target: the default float sampler within 1.2x of forward differencing at <= 0.01 px, 1e4 px.
    let find = |format: &str, method: &str, degree: &str, count: &str| {
        rows.iter()
            .find(|r| {
                r[0] == format
                    && r[1] == method
                    && r[2] == degree
                    && r[3] == count
                    && r[4] == "10000"
            })
            .map(|r| {
                (
                    r[5].parse::<f64>().unwrap_or(f64::NAN),
                    r[6].parse::<f64>().unwrap_or(f64::NAN),
                )
            })
            .unwrap_or((f64::NAN, f64::NAN))
    };
    let mut table = String::from(
        "| f32, 10⁴ px, 1024 points | BernsteinTable ns | error px | ForwardDiff ns | error px | time ratio |\n|---|---|---|---|---|---|\n",
    );
    let mut met = true;
    let mut measured = Vec::new();
    for degree in ["3", "7"] {
        let (tb, eb) = find("f32", "BernsteinTable", degree, "1024");
        let (tf, ef) = find("f32", "ForwardDiff", degree, "1024");
        let ratio = tb / tf;
        met &= ratio <= 1.2 && eb <= 0.01;
        measured.push(format!("degree {degree}: {ratio:.2}× at {} px", num(eb)));
        table.push_str(&format!(
            "| degree {degree} | {tb:.2} | {} | {tf:.2} | {} | {ratio:.2} |\n",
            num(eb),
            num(ef)
        ));
    }
    run.target("default float sampler (BernsteinTable) within 1.2× of forward differencing's time at ≤ 0.01 px (f32, 10⁴ px)", measured.join("; "), met, "the table was slower than forward differencing here");
    let text = format!(
        "![f32](samplers_f32.svg)\n![f64](samplers_f64.svg)\n![Q16.16](samplers_q16.svg)\n\n\
         Each dot is one (degree, sample count, scale) cell; error is the largest distance to the exact \
         curve (128-bit integer Bernstein sums) over the random curves of the cell. Data: `samplers.csv`.\n\n{table}"
    );
    run.section("(a) Samplers: cost against error", &text);
}
