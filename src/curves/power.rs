//! A cubic in power form, for the floating-point searches that evaluate one span many times.

use crate::{Point, Scalar};

/// A cubic in power form about its start, `p(t) = p0 + t·(c1 + t·(c2 + t·c3))`: a point in 3
/// multiply-adds a coordinate, its tangent in 2, where de Casteljau takes 6 and 5 lerps.
/// For floats: in fixed point the coefficients can leave the format's range, where de
/// Casteljau's convex combinations cannot.
#[derive(Clone, Copy)]
pub(crate) struct Power<P>([P; 4]);

/// Newton steps of [`Power::nearest`] at most.
const NEAREST_STEPS: usize = 6;
/// The even steps [`Power::nearest`] samples a cubic in before its Newton steps.
const SAMPLES: u32 = 8;

impl<P: Point> Power<P> {
    /// The power form of the Bézier cubic with control points `p`.
    pub(crate) fn of([p0, p1, p2, p3]: [P; 4]) -> Self {
        let three = P::Scalar::from_i16(3);
        let (d1, d2, d3) = (p1 - p0, p2 - p1, p3 - p2);
        Power([p0, d1 * three, (d2 - d1) * three, d3 - d2 - d2 + d1])
    }

    /// The point at `t`.
    pub(crate) fn at(&self, t: P::Scalar) -> P {
        let [p0, c1, c2, c3] = self.0;
        p0 + (c1 + (c2 + c3 * t) * t) * t
    }

    /// The tangent (first derivative) at `t`.
    pub(crate) fn slope(&self, t: P::Scalar) -> P {
        let [_, c1, c2, c3] = self.0;
        c1 + (c2 + c2 + c3 * (t * P::Scalar::from_i16(3))) * t
    }

    /// The second derivative at `t`.
    fn bend(&self, t: P::Scalar) -> P {
        let [_, _, c2, c3] = self.0;
        (c2 + c3 * (t * P::Scalar::from_i16(3))) * P::Scalar::from_i16(2)
    }

    /// The parameter in `[0, 1]` of the point nearest `c`: the nearest of [`SAMPLES`] + 1
    /// evenly spaced points, then up to [`NEAREST_STEPS`] Newton steps on the squared
    /// distance inside the bracket of that point's two neighbours, a step that leaves the
    /// bracket (or meets no curvature) replaced by halving it towards the descent; a Newton
    /// step that moved less than `√ε` (which leaves about `ε`) or a halving that moved less
    /// than `ε` ends them. Finds the nearest point of the dip the best sample lies in, to
    /// the format's precision (the halving search of [`Bezier::deepest`](crate::Bezier)
    /// samples 5 points and stops at 1/1024). Cost: 9 points, then a point and two
    /// derivatives a step.
    pub(crate) fn nearest(&self, c: P) -> P::Scalar {
        let (zero, one) = (P::Scalar::ZERO, P::Scalar::ONE);
        let step = P::Scalar::ratio(1, SAMPLES);
        let d2 = |t: P::Scalar| {
            let d = self.at(t) - c;
            d.dot(d)
        };
        let mut best = (zero, d2(zero));
        for k in 1..=SAMPLES {
            let t = P::Scalar::ratio(k, SAMPLES);
            let e = d2(t);
            if e < best.1 {
                best = (t, e);
            }
        }
        let (mut lo, mut hi) = ((best.0 - step).max(zero), (best.0 + step).min(one));
        // The parameter and its point's offset from `c`, carried from one step to the next.
        let (mut t, mut d) = (best.0, self.at(best.0) - c);
        for _ in 0..NEAREST_STEPS {
            let slope = self.slope(t);
            let (g, h) = (d.dot(slope), slope.dot(slope) + d.dot(self.bend(t)));
            if g > zero {
                hi = t;
            } else if g < zero {
                lo = t;
            } else {
                break;
            }
            let newton = (h > zero).then(|| t - g / h).filter(|&n| n > lo && n < hi);
            let next = newton.unwrap_or((lo + hi) * P::Scalar::ratio(1, 2));
            let moved = (next - t).abs();
            (t, d) = (next, self.at(next) - c);
            let e = d.dot(d);
            if e < best.1 {
                best = (t, e);
            }
            // A Newton step squares the error: one that moved less than `√ε` left it
            // within about `ε`.
            let settled = match newton {
                Some(_) => moved * moved,
                None => moved,
            };
            if settled <= P::Scalar::EPSILON {
                break;
            }
        }
        best.0
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::Vec2;

    /// Numbers evenly spread over `[-2, 2)`, the same from the same `seed` (a 64-bit linear
    /// congruential generator): random control points for the curve searches' tests.
    pub(crate) fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
        }
    }

    /// `nearest` finds the least squared distance of the dip its best sample lies in (a
    /// dense sampling of that sample's neighbours' bracket, f64, 20 001 points) to 1e-9; on
    /// cubics as wiggly as random control points make them it is farther than the halving
    /// search of `Bezier::deepest` on the same key in at most 1 case in 100 (printed).
    #[test]
    fn the_nearest_point_is_found_in_its_dip() {
        let mut next = uniform(987654321);
        let mut worse = 0;
        for _ in 0..500 {
            let p: [Vec2<f64>; 4] = core::array::from_fn(|_| Vec2::new(next(), next()));
            let c = Vec2::new(next(), next());
            let power = Power::of(p);
            let d2 = |t: f64| (power.at(t) - c).dot(power.at(t) - c);
            let best = (0..=8)
                .map(|k| k as f64 / 8.0)
                .fold(0.0, |b, t| if d2(t) < d2(b) { t } else { b });
            let (lo, hi) = ((best - 0.125).max(0.0), (best + 0.125).min(1.0));
            let dense = (0..=20_000)
                .map(|i| d2(lo + (hi - lo) * i as f64 / 20_000.0))
                .fold(f64::INFINITY, f64::min);
            let t = power.nearest(c);
            assert!(
                (0.0..=1.0).contains(&t) && d2(t) <= dense + 1e-9,
                "{p:?} {c:?}"
            );
            let halving = crate::Bezier::new(p)
                .unwrap()
                .deepest(|x| (x - c).dot(x - c));
            worse += usize::from(d2(t) > d2(halving) + 1e-12);
        }
        std::eprintln!("farther than the halving search in {worse} of 500");
        assert!(worse <= 5, "{worse}");
    }
}
