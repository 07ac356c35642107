//! The nearest points of two spans of a drawn curve, for self-contact: searched from samples
//! of each span, or followed by Newton steps from where they were found before.

use super::drawn::DrawnSpans;
use super::memory::Places;
use crate::curves::power::Power;
use crate::{Point, Scalar};

/// What the pair search reads of one span, taken when a pair first needs it and kept until
/// the curve moves: a span's samples serve all its pairs.
#[derive(Clone, Copy)]
pub(super) struct Sampled<P: Point> {
    /// Its points at [`SAMPLES`] + 1 even steps: the ends of its chords.
    points: [P; SAMPLES + 1],
    /// How far it strays from those chords at most: `3/(4·SAMPLES²)` of its control points'
    /// largest second difference (a cubic's `|p''| / 6`), the bound of linear interpolation.
    bend: P::Scalar,
    /// Half its longest chord.
    half: P::Scalar,
    /// Its second derivative, `p''(t) = second[0] + t·second[1]`.
    second: [P; 2],
    /// In floating point, its cubic in power form.
    power: Option<Power<P>>,
}

/// Every span's [`Sampled`], and whether it is up to date.
pub(super) struct Samples<P: Point, const K: usize> {
    spans: [Sampled<P>; K],
    fresh: [bool; K],
}

impl<P: Point, const K: usize> Samples<P, K> {
    pub(super) fn new() -> Self {
        let zero = P::Scalar::ZERO;
        let empty = Sampled {
            points: [P::default(); SAMPLES + 1],
            bend: zero,
            half: zero,
            second: [P::default(); 2],
            power: None,
        };
        Samples {
            spans: [empty; K],
            fresh: [false; K],
        }
    }

    /// Brings span `span` of `curve` up to date. A span that is no cubic (one Bézier through
    /// every particle: a single span, which pairs with none) counts as unbent.
    fn take(&mut self, curve: &impl DrawnSpans<P, K>, span: usize) {
        if self.fresh[span] {
            return;
        }
        let cubic = curve.cubic(span);
        let s = &mut self.spans[span];
        // Fixed point keeps de Casteljau's convex combinations: the power form's
        // coefficients can leave the format's range.
        s.power = cubic.filter(|_| !P::Scalar::FIXED_POINT).map(Power::of);
        for (k, x) in s.points.iter_mut().enumerate() {
            let t = P::Scalar::ratio(k as u32, SAMPLES as u32);
            *x = s.power.map_or_else(|| curve.point(span, t), |c| c.at(t));
        }
        let (d0, d1) = cubic.map_or((P::default(), P::default()), |[p0, p1, p2, p3]| {
            (p2 - p1 - (p1 - p0), p3 - p2 - (p2 - p1))
        });
        let six = P::Scalar::from_i16(6);
        s.second = [d0 * six, (d1 - d0) * six];
        s.bend = d0.length().max(d1.length()) * P::Scalar::ratio(3, (4 * SAMPLES * SAMPLES) as u32);
        let longest = s
            .points
            .windows(2)
            .map(|c| (c[1] - c[0]).dot(c[1] - c[0]))
            .fold(P::Scalar::ZERO, P::Scalar::max);
        s.half = longest.sqrt() * P::Scalar::ratio(1, 2);
        self.fresh[span] = true;
    }

    /// Where spans `a` and `b` of `curve` come nearest, and whether it was searched afresh:
    /// followed by Newton steps ([`refine`]) from `places` (in the order `(a, b)`) when given,
    /// else searched from the spans' samples ([`nearest`]; `Err` when they are apart, by at
    /// least that much).
    pub(super) fn nearest(
        &mut self,
        curve: &impl DrawnSpans<P, K>,
        (a, b): (usize, usize),
        places: Option<Places<P::Scalar>>,
        gap: P::Scalar,
    ) -> Result<(Near<P::Scalar>, bool), P::Scalar> {
        self.take(curve, a);
        self.take(curve, b);
        let (sa, sb) = (&self.spans[a], &self.spans[b]);
        let point =
            |s: &Sampled<P>, span, t| s.power.map_or_else(|| curve.point(span, t), |c| c.at(t));
        let slope = |s: &Sampled<P>, span, t| {
            s.power
                .map_or_else(|| curve.tangent(span, t), |c| c.slope(t))
        };
        let bend = |s: &Sampled<P>, t| s.second[0] + s.second[1] * t;
        let span_a = (&|u| point(sa, a, u), &|u| slope(sa, a, u), &|u| bend(sa, u));
        let span_b = (&|v| point(sb, b, v), &|v| slope(sb, b, v), &|v| bend(sb, v));
        let Some((at, also)) = places else {
            return nearest((sa, span_a), (sb, span_b), gap).map(|near| (near, true));
        };
        let (e, u, v) = refine(span_a, span_b, at);
        let other = also.map(|also| refine(span_a, span_b, also));
        let (at, also) = match other {
            Some((f, nu, nv)) if f < e => ((nu, nv), Some((u, v))),
            other => ((u, v), other.map(|(_, nu, nv)| (nu, nv))),
        };
        Ok((
            Near {
                also,
                ..Near::only(at)
            },
            false,
        ))
    }

    /// Forgets the samples of `count` spans from `first` on, counted round the `n` (they
    /// were drawn again).
    pub(super) fn forget(&mut self, (first, count): (usize, usize), n: usize) {
        for j in 0..count.min(n) {
            self.fresh[(first + j) % n] = false;
        }
    }
}

/// The parameters `(u, v)` in `[0, 1]²` of the nearest points of two spans, `a(u)` and
/// `b(v)` with tangents `ta` and `tb`, sampled in `sa` and `sb`. Each span lies within its
/// `bend` of the chords between its samples, so the chords' exact distances (segment to
/// segment; a chord pair whose nearest corners are too far for it to matter is skipped
/// unmeasured) bound the spans' within the two bends. `Err`, without more, when no chord
/// pair comes within `gap` plus both bends: the spans are apart, by at least what it holds
/// (the nearest chords' distance less both bends; a chord pair skipped unmeasured counts as
/// its nearest corners less half of each chord). Otherwise the nearest chord
/// pair seeds [`refine`], and so does the nearest pair of chords that are no neighbours of
/// those, when it could still hold a nearer point pair (two arcs near each other in two
/// places); the nearest result wins. Cost: `(SAMPLES + 1)²` squared distances, up to
/// `SAMPLES²` segment distances, and 2 or 4 points and tangents a Newton step.
fn nearest<P: Point>(
    (sa, a): (
        &Sampled<P>,
        (
            &impl Fn(P::Scalar) -> P,
            &impl Fn(P::Scalar) -> P,
            &impl Fn(P::Scalar) -> P,
        ),
    ),
    (sb, b): (
        &Sampled<P>,
        (
            &impl Fn(P::Scalar) -> P,
            &impl Fn(P::Scalar) -> P,
            &impl Fn(P::Scalar) -> P,
        ),
    ),
    gap: P::Scalar,
) -> Result<Near<P::Scalar>, P::Scalar> {
    let d2 = |p: P| p.dot(p);
    let (pa, pb) = (&sa.points, &sb.points);
    let slack = sa.bend + sb.bend;
    let halves = sa.half + sb.half;
    let corner: [[P::Scalar; SAMPLES + 1]; SAMPLES + 1] =
        core::array::from_fn(|k| core::array::from_fn(|l| d2(pa[k] - pb[l])));
    // Each chord pair's squared distance and nearest parameters, once measured.
    let mut chords = [[None; SAMPLES]; SAMPLES];
    let mut best: Option<(P::Scalar, usize, usize)> = None;
    // Chords this far apart hold the spans apart.
    let far = gap + slack;
    // Farther than this, a chord pair neither touches nor beats the nearest by the bends.
    let mut limit = far;
    // The nearest corners of the chord pairs skipped unmeasured (squared).
    let mut skipped = [[None; SAMPLES]; SAMPLES];
    for i in 0..SAMPLES {
        for j in 0..SAMPLES {
            // Every point of a chord is within half of it from one of its ends.
            let near = corner[i][j]
                .min(corner[i + 1][j])
                .min(corner[i][j + 1])
                .min(corner[i + 1][j + 1]);
            let reach = limit + halves;
            if near >= reach * reach {
                skipped[i][j] = Some(near);
                continue;
            }
            let (s, t, apart) = segments_nearest((pa[i], pa[i + 1]), (pb[j], pb[j + 1]));
            let d = apart.dot(apart);
            chords[i][j] = Some((d, s, t));
            if best.is_none_or(|(kept, _, _)| d < kept) {
                best = Some((d, i, j));
                limit = limit.min(d.sqrt() + slack);
            }
        }
    }
    let param = |k: usize, s: P::Scalar| {
        (P::Scalar::from_i16(k as i16) + s) / P::Scalar::from_i16(SAMPLES as i16)
    };
    let seed = |k: usize, l: usize| chords[k][l].map(|(_, s, t)| (param(k, s), param(l, t)));
    // The spans are at least this far apart where no chord in `keep` is: the nearest
    // measured chords less the bends, or the nearest corners of those skipped less half of
    // each chord too.
    let clear_of = |keep: &dyn Fn(usize, usize) -> bool| {
        let (mut measured, mut corners): (Option<P::Scalar>, Option<P::Scalar>) = (None, None);
        for (k, (row, gaps)) in chords.iter().zip(&skipped).enumerate() {
            for (l, (c, g)) in row.iter().zip(gaps).enumerate() {
                if keep(k, l) {
                    continue;
                }
                if let Some((d, _, _)) = *c {
                    measured = Some(measured.map_or(d, |m| m.min(d)));
                }
                if let Some(g) = *g {
                    corners = Some(corners.map_or(g, |m| m.min(g)));
                }
            }
        }
        let corners = corners.map(|c| c.sqrt() - halves);
        let nearest = measured.map(P::Scalar::sqrt).into_iter().chain(corners);
        nearest.reduce(P::Scalar::min).map(|c| c - slack)
    };
    let Some(((_, i, j), start)) = best
        .filter(|&(d, _, _)| d < far * far)
        .and_then(|(d, i, j)| Some(((d, i, j), seed(i, j)?)))
    else {
        return Err(clear_of(&|_, _| false).unwrap_or(P::Scalar::ZERO));
    };
    let (found, u, v) = refine(a, b, start);
    // The nearest chord pair that is no neighbour of the first, refined when its bound could
    // beat what the first found.
    let mut other: Option<(P::Scalar, usize, usize)> = None;
    for (k, row) in chords.iter().enumerate() {
        for (l, c) in row.iter().enumerate() {
            if let Some((dc, _, _)) = *c
                && (k.abs_diff(i) >= 2 || l.abs_diff(j) >= 2)
                && other.is_none_or(|(kept, _, _)| dc < kept)
            {
                other = Some((dc, k, l));
            }
        }
    }
    let block =
        |(i, j): (usize, usize), (k, l): (usize, usize)| k.abs_diff(i) < 2 && l.abs_diff(j) < 2;
    if let Some((dc, k, l)) = other {
        let bound = dc.sqrt() - slack;
        if let Some(start) =
            seed(k, l).filter(|_| bound <= P::Scalar::ZERO || bound * bound < found)
        {
            let (e, nu, nv) = refine(a, b, start);
            let elsewhere = clear_of(&|m, n| block((i, j), (m, n)) || block((k, l), (m, n)));
            let (first, second) = ((u, v), (nu, nv));
            let near = if e < found {
                [second, first]
            } else {
                [first, second]
            };
            return Ok(Near {
                at: near[0],
                also: Some(near[1]),
                elsewhere,
            });
        }
    }
    Ok(Near {
        at: (u, v),
        also: None,
        elsewhere: clear_of(&|m, n| block((i, j), (m, n))),
    })
}

/// Where two spans come nearest: `at`, the nearest points' parameters, and `also`, those of
/// a second place where they come near; nowhere else nearer than `elsewhere` (`None`: there
/// is nowhere else).
#[derive(Clone, Copy)]
pub(super) struct Near<S> {
    pub(super) at: (S, S),
    pub(super) also: Option<(S, S)>,
    pub(super) elsewhere: Option<S>,
}

impl<S> Near<S> {
    /// Nearest at `at`, with nothing known of anywhere else.
    pub(super) fn only(at: (S, S)) -> Self {
        Near {
            at,
            also: None,
            elsewhere: None,
        }
    }
}

/// Newton steps from `(u, v)` on half the squared distance between the points of two spans,
/// each given as its point, tangent and second derivative at a parameter: the full Hessian
/// (curvature terms included, so two arcs side by side or bending away converge where
/// Gauss-Newton stalls), its least eigenvalue raised to 1/1024 of the tangents' squared
/// lengths, a parameter held at `[0, 1]`'s bound where the slope or the step pushes out of
/// it, and the step shortened to stay in `[0, 1]²` (a clamped step need not descend). A step that does not bring the points nearer is cut to the least of the
/// parabola through the distance there, at the start and the start's slope (to between
/// 1/10 and 1/2 of it), up to [`CUTS`] times. At most [`NEWTON_STEPS`] steps, stopped once
/// one moves less than 1/4096 of a span. Returns the squared distance and the parameters of
/// the nearest pair met.
fn refine<P: Point>(
    (a, ta, sa): (
        &impl Fn(P::Scalar) -> P,
        &impl Fn(P::Scalar) -> P,
        &impl Fn(P::Scalar) -> P,
    ),
    (b, tb, sb): (
        &impl Fn(P::Scalar) -> P,
        &impl Fn(P::Scalar) -> P,
        &impl Fn(P::Scalar) -> P,
    ),
    (mut u, mut v): (P::Scalar, P::Scalar),
) -> (P::Scalar, P::Scalar, P::Scalar) {
    let (zero, one) = (P::Scalar::ZERO, P::Scalar::ONE);
    let half = P::Scalar::ratio(1, 2);
    let clamp = |x: P::Scalar| x.max(zero).min(one);
    let small = P::Scalar::ratio(1, 4096);
    let mut f = a(u) - b(v);
    let mut e = f.dot(f);
    'steps: for _ in 0..NEWTON_STEPS {
        let (da, db) = (ta(u), tb(v));
        let (aa, bb) = (da.dot(da), db.dot(db));
        let (gu, gv) = (f.dot(da), -f.dot(db));
        let (mut huu, mut hvv, huv) = (aa + f.dot(sa(u)), bb - f.dot(sb(v)), -da.dot(db));
        // Raise the least eigenvalue of [[huu, huv], [huv, hvv]] to a floor: a descent step.
        let spread = (huu - hvv) * half;
        let least = (huu + hvv) * half - (spread * spread + huv * huv).sqrt();
        let raise = ((aa + bb) * P::Scalar::ratio(1, 1024) - least).max(zero);
        (huu, hvv) = (huu + raise, hvv + raise);
        // A parameter at a bound stays there when the slope, or the step, pushes out of it.
        let out = |x: P::Scalar, d: P::Scalar| (x <= zero && d < zero) || (x >= one && d > zero);
        let mut held = (out(u, -gu), out(v, -gv));
        let det = huu * hvv - huv * huv;
        let mut free = None;
        if held == (false, false) && det > zero {
            let (du, dv) = ((huv * gv - hvv * gu) / det, (huv * gu - huu * gv) / det);
            held = (out(u, du), out(v, dv));
            free = Some((du, dv)).filter(|_| held == (false, false));
        }
        let (mut du, mut dv) = match (free, held) {
            (Some(step), _) => step,
            (None, (true, false)) if hvv > zero => (zero, -gv / hvv),
            (None, (false, true)) if huu > zero => (-gu / huu, zero),
            _ => break,
        };
        // Shortened to stay in the box: still a descent direction, as a clamped one is not.
        let mut scale = one;
        for (x, d) in [(u, du), (v, dv)] {
            if x + d > one {
                scale = scale.min((one - x) / d);
            } else if x + d < zero {
                scale = scale.min(x / -d);
            }
        }
        (du, dv) = (du * scale, dv * scale);
        for _ in 0..=CUTS {
            let (nu, nv) = (clamp(u + du), clamp(v + dv));
            let nf = a(nu) - b(nv);
            let ne = nf.dot(nf);
            let (su, sv) = (nu - u, nv - v);
            if ne < e {
                (u, v, f, e) = (nu, nv, nf, ne);
                if su.abs().max(sv.abs()) < small {
                    break 'steps;
                }
                continue 'steps;
            }
            // The squared distance along the step: `e + slope·s + bend·s²`, `s` in [0, 1].
            let slope = (gu * su + gv * sv) * P::Scalar::from_i16(2);
            let bend = ne - e - slope;
            let cut = if slope < zero && bend > zero {
                (-slope / (bend + bend))
                    .max(P::Scalar::ratio(1, 10))
                    .min(half)
            } else {
                half
            };
            (du, dv) = (su * cut, sv * cut);
        }
        break;
    }
    (e, u, v)
}

/// Steps a span is sampled in to seed the search for its nearest points to another.
const SAMPLES: usize = 4;
/// Newton steps from a seed at most.
const NEWTON_STEPS: usize = 8;
/// Times a Newton step that does not bring the points nearer is cut at most.
const CUTS: usize = 4;
/// The nearest points of segments `p` and `q`: their parameters in `[0, 1]` and the first's
/// point less the second's (no root): the first's parameter where the lines come nearest (its start when
/// they are parallel), clamped; the second's nearest that point, and past an end that end
/// and the first's nearest it again. One division, and one a segment. In `Q16` the
/// parameters come from the vectors scaled by a power of two (exactly) so that their
/// largest coordinate is about 1: short segments' products of dot products would keep few
/// bits.
pub(super) fn segments_nearest<P: Point>(
    (p0, p1): (P, P),
    (q0, q1): (P, P),
) -> (P::Scalar, P::Scalar, P) {
    let (zero, one) = (P::Scalar::ZERO, P::Scalar::ONE);
    let clamp = |x: P::Scalar| x.max(zero).min(one);
    let (d1, d2, r) = (p1 - p0, q1 - q0, p0 - q0);
    let (u, v, w) = if P::Scalar::FIXED_POINT {
        let scale = unit_scale([d1, d2, r]);
        (d1 * scale, d2 * scale, r * scale)
    } else {
        (d1, d2, r)
    };
    let (a, b, e) = (u.dot(u), u.dot(v), v.dot(v));
    let (c, f) = (u.dot(w), v.dot(w));
    let over = |x: P::Scalar| if x > zero { one / x } else { zero };
    let denom = a * e - b * b;
    let s = if denom > zero {
        clamp((b * f - c * e) / denom)
    } else {
        zero
    };
    let t = (b * s + f) * over(e);
    let (s, t) = if t < zero {
        (clamp(-c * over(a)), zero)
    } else if t > one {
        (clamp((b - c) * over(a)), one)
    } else {
        (s, t)
    };
    (s, t, p0 + d1 * s - (q0 + d2 * t))
}

/// The power of two, up to 2¹², that brings the largest coordinate of `vectors` to at least
/// a half (1 when it is there already).
fn unit_scale<P: Point>(vectors: [P; 3]) -> P::Scalar {
    let largest = vectors.iter().fold(P::Scalar::ZERO, |m, v| {
        (0..P::DIM).fold(m, |m, d| m.max(v.coord(d).abs()))
    });
    let (mut m, mut scale) = (largest, P::Scalar::ONE);
    let (half, most) = (P::Scalar::ratio(1, 2), P::Scalar::from_i16(4096));
    while m < half && scale < most {
        (m, scale) = (m + m, scale + scale);
    }
    scale
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::Vec3;
    use crate::contact::memory::{PairMemory, Recall};
    use crate::curves::power::tests::uniform;
    use crate::curves::smooth::{Smoothed, Smoothing};

    /// The least distance of two segments in `f64`: each end against the other segment, and
    /// the lines' nearest points where both lie inside.
    fn segments_reference(p: (Vec3<f64>, Vec3<f64>), q: (Vec3<f64>, Vec3<f64>)) -> f64 {
        let onto = |x: Vec3<f64>, (a, b): (Vec3<f64>, Vec3<f64>)| {
            let d = b - a;
            let t = if d.dot(d) > 0.0 {
                ((x - a).dot(d) / d.dot(d)).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (x - (a + d * t)).length()
        };
        let ends = [onto(p.0, q), onto(p.1, q), onto(q.0, p), onto(q.1, p)];
        let (u, v, w) = (p.1 - p.0, q.1 - q.0, p.0 - q.0);
        let (a, b, c, d, e) = (u.dot(u), u.dot(v), v.dot(v), u.dot(w), v.dot(w));
        let det = a * c - b * b;
        let inner = (det > 1e-12 * a * c).then(|| ((b * e - c * d) / det, (a * e - b * d) / det));
        let inside = inner.filter(|&(s, t)| (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t));
        let lines = inside.map_or(f64::INFINITY, |(s, t)| {
            (p.0 + u * s - (q.0 + v * t)).length()
        });
        ends.into_iter().fold(lines, f64::min)
    }

    /// `segments_nearest` finds two segments' least distance: in `f64` within 1e-12 of the
    /// reference on 20 000 random pairs (a tenth parallel, a tenth with a point for a
    /// segment); in `Q16`, on pairs of segments up to 3.5 cm, 35 cm and 3.5 m long as near
    /// each other, the points it returns are within 1e-4 m of the least distance.
    #[test]
    fn segments_nearest_finds_the_least_distance() {
        let mut next = uniform(17);
        let mut point = |scale: f64| Vec3::new(next() * scale, next() * scale, next() * scale);
        for k in 0..20_000 {
            let (p0, q0) = (point(1.0), point(1.0));
            let p1 = if k % 10 == 1 { p0 } else { p0 + point(1.0) };
            let q1 = if k % 10 == 2 {
                q0 + (p1 - p0) * 0.7
            } else {
                q0 + point(1.0)
            };
            let (s, t, apart) = segments_nearest((p0, p1), (q0, q1));
            let reference = segments_reference((p0, p1), (q0, q1));
            assert!((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t));
            assert!(
                (apart.length() - reference).abs() <= 1e-12,
                "{k}: {} {reference}",
                apart.length()
            );
        }
        use crate::Q16;
        let q =
            |p: Vec3<f64>| Vec3::new(Q16::from_f64(p.x), Q16::from_f64(p.y), Q16::from_f64(p.z));
        let back = |p: Vec3<Q16>| Vec3::new(p.x.to_f64(), p.y.to_f64(), p.z.to_f64());
        // Segments up to 3.5 cm, 35 cm and 3.5 m long, as near each other.
        for size in [0.01, 0.1, 1.0] {
            let mut worst = 0.0f64;
            for k in 0..10_000 {
                let (p0, q0) = (q(point(size / 2.0)), q(point(size / 2.0)));
                let p1 = q(back(p0) + point(size));
                let q1 = if k % 10 == 2 {
                    q(back(q0) + (back(p1) - back(p0)) * 0.7)
                } else {
                    q(back(q0) + point(size))
                };
                let (s, t, _) = segments_nearest((p0, p1), (q0, q1));
                let (s, t) = (s.to_f64(), t.to_f64());
                let (p, r) = ((back(p0), back(p1)), (back(q0), back(q1)));
                let found = (p.0 + (p.1 - p.0) * s - (r.0 + (r.1 - r.0) * t)).length();
                worst = worst.max(found - segments_reference(p, r));
            }
            assert!(worst <= 1e-4, "{size}: {worst}");
        }
    }

    /// The least distance of spans `a` and `b` of `curve` on a 401 × 401 grid of parameters.
    fn dense(curve: &Smoothed<Vec3<f64>, 8>, (a, b): (usize, usize)) -> f64 {
        let at = |span, k: usize| curve.point(span, k as f64 / 400.0);
        let pb: [Vec3<f64>; 401] = core::array::from_fn(|l| at(b, l));
        (0..=400)
            .flat_map(|k| {
                let x = at(a, k);
                pb.iter().map(move |&y| (x - y).length())
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// On 300 random ropes of 8 particles (steps of about 1 m, a gap of 0.3 m), every pair
    /// of spans that the search finds apart is at least as far apart as it says; and after
    /// every particle moves up to 1 cm (half the ropes) or 10 cm along each axis, a pair
    /// that the memory follows from where it was found comes as near as a dense grid of
    /// both spans (within 1e-9 m) wherever that grid is nearer than the gap, and a pair it
    /// holds apart is farther than the gap.
    #[test]
    fn pairs_followed_or_held_apart_match_a_dense_search() {
        let mut next = uniform(24681357);
        let gap = 0.3;
        let (mut apart, mut followed, mut held) = (0, 0, 0);
        for rope in 0..300 {
            // Half the ropes move little, half far (pairs close the gap).
            let shake = if rope % 2 == 0 { 0.005 } else { 0.05 };
            let mut pos = [Vec3::default(); 8];
            for i in 1..8 {
                let step = Vec3::new(next(), next(), next()) * 0.5;
                pos[i] = pos[i - 1] + step;
            }
            let curve = Smoothed::open(Smoothing::CatmullRom, &pos).unwrap();
            let mut samples = Samples::<Vec3<f64>, 8>::new();
            let mut memory = PairMemory::<Vec3<f64>, 8>::new();
            let cubics = |c: &Smoothed<Vec3<f64>, 8>, (a, b)| (c.cubic(a), c.cubic(b));
            let pairs = (0..7).flat_map(|a| (a + 2..7).map(move |b| (a, b)));
            for pair in pairs.clone() {
                let _ = memory.recall(pair, cubics(&curve, pair));
                match samples.nearest(&curve, pair, None, gap) {
                    Err(clear) => {
                        assert!(dense(&curve, pair) >= clear - 1e-9, "{pos:?} {pair:?}");
                        memory.remember(pair, clear - gap, None);
                        apart += 1;
                    }
                    Ok((near, _)) => {
                        let (x, y) = (
                            curve.point(pair.0, near.at.0),
                            curve.point(pair.1, near.at.1),
                        );
                        let dist = (x - y).length();
                        let margin = near
                            .elsewhere
                            .map_or(gap, |e| (e - gap).max((e - dist) * 0.5).min(gap));
                        memory.remember(pair, margin, Some(((near.at, near.also), 0.0)));
                    }
                }
            }
            for p in &mut pos {
                *p += Vec3::new(next(), next(), next()) * shake;
            }
            let moved = Smoothed::open(Smoothing::CatmullRom, &pos).unwrap();
            let mut samples = Samples::<Vec3<f64>, 8>::new();
            for pair in pairs {
                match memory.recall(pair, cubics(&moved, pair)) {
                    Recall::Apart => {
                        assert!(dense(&moved, pair) > gap, "{pos:?} {pair:?}");
                        held += 1;
                    }
                    Recall::Near(places) => {
                        let Ok((near, false)) = samples.nearest(&moved, pair, Some(places), gap)
                        else {
                            panic!("followed pairs are never searched afresh");
                        };
                        let (x, y) = (
                            moved.point(pair.0, near.at.0),
                            moved.point(pair.1, near.at.1),
                        );
                        let grid = dense(&moved, pair);
                        if grid < gap {
                            assert!((x - y).length() <= grid + 1e-9, "{pos:?} {pair:?}");
                            followed += 1;
                        }
                    }
                    Recall::Unknown => {}
                }
            }
        }
        std::eprintln!("{apart} pairs found apart, {held} held apart, {followed} followed near");
        assert!(
            apart > 100 && held > 100 && followed > 30,
            "{apart} {held} {followed}"
        );
    }
}
