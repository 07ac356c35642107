//! (e) Fixed against float: Q16.16 and f32 sampling error as the coordinate scale grows,
//! marking where Q16.16 fails.

use dunas::sampler::{DeCasteljau, Sampler, Subdivide};
use dunas::{Bezier, Error, Q16, Scalar, Vec2};

use crate::common::{DENOM, ExactCurve};
use crate::report::{Run, Series, chart, csv};

/// A fixed curve shape (grid points in ±1) scaled by `scale`: error of 65 points, or the
/// construction error.
fn error_at<S: Scalar>(scale: f64, sampler: &impl Sampler<Vec2<S>, 4>) -> Result<f64, Error> {
    let shape = [[-1.0, -0.5], [-0.3, 1.0], [0.6, -1.0], [1.0, 0.4]];
    let grid = shape.map(|[x, y]: [f64; 2]| {
        [
            (x * scale * DENOM as f64).round() as i64,
            (y * scale * DENOM as f64).round() as i64,
        ]
    });
    let pts =
        grid.map(|[x, y]| Vec2::<S>::from_f64(x as f64 / DENOM as f64, y as f64 / DENOM as f64));
    Bezier::new(pts)?;
    let c = ExactCurve::<S, 4>::new(grid);
    let mut out = [Vec2::<S>::default(); 65];
    let n = sampler.sample(&c.curve, &mut out)?;
    Ok(c.max_error(&out[..n], (n - 1) as u64))
}

pub fn run(run: &mut Run) {
    let scales: Vec<f64> = (0..=if run.quick { 9 } else { 36 })
        .map(|i| 10f64.powf(i as f64 * if run.quick { 0.5 } else { 0.125 }))
        .collect();
    let mut rows = Vec::new();
    let mut series: Vec<(String, Vec<(f64, f64)>)> = vec![
        ("f32 de Casteljau".into(), vec![]),
        ("Q16.16 subdivision (dyadic t)".into(), vec![]),
        ("Q16.16 de Casteljau (t = i/64 rounded)".into(), vec![]),
    ];
    let mut q16_fails = None;
    for &s in &scales {
        let results = [
            error_at::<f32>(s, &DeCasteljau),
            error_at::<Q16>(s, &Subdivide::default()),
            error_at::<Q16>(s, &DeCasteljau),
        ];
        for (k, r) in results.iter().enumerate() {
            match r {
                Ok(e) => series[k].1.push((s, *e)),
                Err(e) => {
                    if k > 0 && q16_fails.is_none() {
                        q16_fails = Some((s, *e));
                    }
                }
            }
            rows.push(vec![
                series[k].0.clone(),
                format!("{s:.4e}"),
                r.map_or_else(|e| format!("error: {e}"), |e| format!("{e:.4e}")),
            ]);
        }
    }
    let mut plotted: Vec<Series> = series
        .into_iter()
        .map(|(n, p)| Series::line(n, p))
        .collect();
    if let Some((s, _)) = q16_fails {
        plotted.push(Series::line(
            "Q16.16 refuses coordinates past 16383",
            vec![(s, 1e-6), (s, 10.0)],
        ));
    }
    chart(
        &run.path("fixed.svg"),
        "Sampling error as the coordinates grow: Q16.16 against f32 (a cubic, 65 points)",
        "coordinate scale (px)",
        "max error (px) vs exact",
        &plotted,
        true,
    );
    csv(
        &run.path("fixed.csv"),
        &["method", "scale_px", "max_error_px"],
        &rows,
    );
    let fail = q16_fails.map_or("never in range".into(), |(s, e)| {
        format!("from a scale of {s:.0} px ({e})")
    });
    run.section(
        "(e) Fixed against float",
        &format!(
            "![fixed](fixed.svg)\n\nQ16.16 with dyadic subdivision keeps a constant absolute error (a few 2⁻¹⁶ units) \
             until the range ends; de Casteljau with rounded `t` grows with the scale like f32 does, but \
             10⁴ times larger. Q16.16 fails {fail}: constructors refuse the curve. Data: `fixed.csv`."
        ),
    );
}
