//! The flatteners against the crates a game would otherwise draw with: the counts
//! `docs/summary.md` (f) states, held as bounds (a flattener that needs fewer still passes).

#[path = "../../tests/common/mod.rs"]
mod common;

use common::Rng;
use dunas::{Bezier, Vec2, lod};

/// Summary (f): the uniform flattener uses exactly lyon_geom's (Wang's) count, at most 2.3×
/// kurbo's, and the adaptive one (`flatten`) at most 1.3× kurbo's (the documented bounds; a
/// flattener that needs fewer still passes).
#[test]
fn flattening_counts_against_lyon_and_kurbo() {
    use kurbo::{CubicBez, PathEl, Point as KPoint};
    use lyon_geom::{CubicBezierSegment, point};
    let mut rng = Rng(0xf1a7);
    let (mut ours, mut adaptive, mut theirs) = (0usize, 0usize, 0usize);
    for _ in 0..100 {
        let p: [[f64; 2]; 4] =
            core::array::from_fn(|_| [rng.grid(200) as f64 / 16.0, rng.grid(200) as f64 / 16.0]);
        let c = Bezier::new(p.map(|[x, y]| Vec2::new(x, y))).unwrap();
        let n = lod::segments(&c, 0.25).unwrap();
        let l = CubicBezierSegment {
            from: point(p[0][0], p[0][1]),
            ctrl1: point(p[1][0], p[1][1]),
            ctrl2: point(p[2][0], p[2][1]),
            to: point(p[3][0], p[3][1]),
        };
        let mut lyon = 0;
        l.for_each_flattened(0.25, &mut |_| lyon += 1);
        assert_eq!(n, lyon, "Wang's count, as lyon_geom");
        let k = |q: [f64; 2]| KPoint::new(q[0], q[1]);
        let cubic = CubicBez::new(k(p[0]), k(p[1]), k(p[2]), k(p[3]));
        let mut kurbo = 0;
        kurbo::flatten(
            [
                PathEl::MoveTo(cubic.p0),
                PathEl::CurveTo(cubic.p1, cubic.p2, cubic.p3),
            ],
            0.25,
            |el| {
                if matches!(el, PathEl::LineTo(_)) {
                    kurbo += 1;
                }
            },
        );
        ours += n;
        adaptive += dunas::flatten::segments(&c, 0.25).unwrap();
        theirs += kurbo;
    }
    let ratio = ours as f64 / theirs as f64;
    eprintln!("dunas uses {ratio:.2}× kurbo's segments");
    assert!(ratio <= 2.3, "dunas uses {ratio:.2}× kurbo's segments");
    let ratio = adaptive as f64 / theirs as f64;
    eprintln!("dunas's adaptive flattening uses {ratio:.2}× kurbo's segments");
    assert!(ratio <= 1.3, "adaptive: {ratio:.2}× kurbo's segments");
}
