//! Timing, CSV and chart helpers shared by the sections of the evaluation.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use plotters::prelude::*;

/// Where the outputs go and how hard to try.
pub struct Run {
    pub quick: bool,
    pub out: PathBuf,
    /// Markdown of the summary, section by section.
    pub summary: String,
    /// Target lines: (target, measured, met, why when missed).
    pub targets: Vec<(String, String, bool, String)>,
}

impl Run {
    /// Repetitions for a median: fewer in quick mode.
    pub fn reps(&self) -> usize {
        if self.quick { 5 } else { 21 }
    }

    pub fn path(&self, name: &str) -> PathBuf {
        self.out.join(name)
    }

    pub fn section(&mut self, title: &str, text: &str) {
        let _ = writeln!(self.summary, "\n## {title}\n\n{text}");
    }

    /// Records a target; `why` explains a miss (ignored when met).
    pub fn target(&mut self, what: &str, measured: String, met: bool, why: &str) {
        self.targets.push((
            what.to_string(),
            measured,
            met,
            if met { String::new() } else { why.to_string() },
        ));
    }
}

/// Median nanoseconds per call of `f`, over `reps` timed batches of `inner` calls.
pub fn median_ns(reps: usize, inner: usize, f: impl FnMut()) -> f64 {
    fastest_and_median_ns(reps, inner, f).1
}

/// The fastest and the median batch's nanoseconds per call of `f`, over `reps` timed
/// batches of `inner` calls (on a shared machine the fastest is the steadier of the two).
pub fn fastest_and_median_ns(reps: usize, inner: usize, mut f: impl FnMut()) -> (f64, f64) {
    f(); // warm up caches and branch predictors
    let mut t: Vec<f64> = (0..reps.max(1))
        .map(|_| {
            let start = Instant::now();
            for _ in 0..inner.max(1) {
                f();
            }
            start.elapsed().as_nanos() as f64 / inner.max(1) as f64
        })
        .collect();
    t.sort_by(f64::total_cmp);
    (t[0], t[t.len() / 2])
}

/// Writes rows of already formatted cells as CSV with a header.
pub fn csv(path: &Path, header: &[&str], rows: &[Vec<String>]) {
    let mut s = header.join(",");
    s.push('\n');
    for r in rows {
        s.push_str(&r.join(","));
        s.push('\n');
    }
    std::fs::write(path, s).unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
}

/// One series of a chart: a name and its points; `line` joins them.
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub line: bool,
}

impl Series {
    pub fn dots(name: impl Into<String>, points: Vec<(f64, f64)>) -> Series {
        Series {
            name: name.into(),
            points,
            line: false,
        }
    }
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Series {
        Series {
            name: name.into(),
            points,
            line: true,
        }
    }
}

const COLORS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(90, 90, 90),
];

/// A log-log (or log-x, linear-y) scatter/line chart as SVG. Non-positive values are clamped to
/// the smallest positive one so that exact results still show.
pub fn chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    log_y: bool,
) {
    let all: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    let pos = |v: f64| v > 0.0;
    let floor_x = all
        .iter()
        .map(|p| p.0)
        .filter(|&v| pos(v))
        .fold(f64::INFINITY, f64::min);
    let floor_y = all
        .iter()
        .map(|p| p.1)
        .filter(|&v| pos(v))
        .fold(f64::INFINITY, f64::min);
    let (floor_x, floor_y) = (
        if floor_x.is_finite() { floor_x } else { 1e-3 },
        if floor_y.is_finite() { floor_y } else { 1e-3 },
    );
    let fix = |p: (f64, f64)| (p.0.max(floor_x), if log_y { p.1.max(floor_y) } else { p.1 });
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for p in all.iter().map(|&p| fix(p)) {
        x0 = x0.min(p.0);
        x1 = x1.max(p.0);
        y0 = y0.min(p.1);
        y1 = y1.max(p.1);
    }
    if x0.partial_cmp(&x1) != Some(std::cmp::Ordering::Less) {
        x1 = x0 * 2.0 + 1.0;
    }
    if y0.partial_cmp(&y1) != Some(std::cmp::Ordering::Less) {
        y1 = y0 * 2.0 + 1.0;
    }
    let (x0, x1) = (x0 / 1.5, x1 * 1.5);
    let (y0, y1) = if log_y {
        (y0 / 3.0, y1 * 3.0)
    } else {
        (y0 - 0.05 * (y1 - y0), y1 + 0.05 * (y1 - y0))
    };
    let root = SVGBackend::new(path, (900, 560)).into_drawing_area();
    root.fill(&WHITE).expect("svg");
    // One drawing body for both axis types (log or linear y).
    macro_rules! plot {
        ($y:expr) => {{
            let mut chart = ChartBuilder::on(&root)
                .caption(title, ("sans-serif", 20))
                .margin(12)
                .x_label_area_size(45)
                .y_label_area_size(70)
                .build_cartesian_2d((x0..x1).log_scale(), $y)
                .expect("svg");
            chart
                .configure_mesh()
                .x_desc(x_label)
                .y_desc(y_label)
                .draw()
                .expect("svg");
            for (k, s) in series.iter().enumerate() {
                let color = COLORS[k % COLORS.len()];
                let pts: Vec<(f64, f64)> = s
                    .points
                    .iter()
                    .copied()
                    .filter(|p| p.0.is_finite() && p.1.is_finite())
                    .map(fix)
                    .collect();
                let anno = if s.line {
                    chart
                        .draw_series(LineSeries::new(pts, color.stroke_width(2)))
                        .expect("svg")
                } else {
                    chart
                        .draw_series(pts.into_iter().map(|p| Circle::new(p, 4, color.filled())))
                        .expect("svg")
                };
                anno.label(s.name.clone()).legend(move |(x, y)| {
                    Rectangle::new([(x, y - 4), (x + 12, y + 4)], color.filled())
                });
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .draw()
                .expect("svg");
        }};
    }
    if log_y {
        plot!((y0..y1).log_scale());
    } else {
        plot!(y0..y1);
    }
    root.present().expect("svg");
}

/// A number in short scientific or plain form for tables.
pub fn num(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if !v.is_finite() {
        "fails".into()
    } else if (0.01..10_000.0).contains(&v.abs()) {
        format!("{v:.3}")
    } else {
        format!("{v:.2e}")
    }
}
