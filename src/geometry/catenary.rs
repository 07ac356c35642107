//! The catenary through two points: where a rope of a given length hangs at rest.
//!
//! Computed once at load time in `f64` with nothing but arithmetic (no `std` or `libm`
//! needed), so every build, `Q16` on a Cortex-M0 included, places the same rope. Relative
//! error below 1e-12 on every quantity.

/// `e^x` for `|x| <= 700`: halved until below 1/2, a 20-term Taylor series, squared back.
fn exp(x: f64) -> f64 {
    let mut r = x;
    let mut halvings = 0;
    while r.abs() > 0.5 && halvings < 12 {
        r *= 0.5;
        halvings += 1;
    }
    let (mut term, mut sum) = (1.0, 1.0);
    for k in 1..=20 {
        term *= r / k as f64;
        sum += term;
    }
    for _ in 0..halvings {
        sum *= sum;
    }
    sum
}

/// `ln y` for `y > 0`: the binary exponent read off the bits, then `2·atanh((m-1)/(m+1))`
/// for the mantissa `m` in `[1, 2)`.
fn ln(y: f64) -> f64 {
    let bits = y.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as i64 - 1023;
    let m = f64::from_bits((bits & !(0x7ff << 52)) | (1023 << 52));
    let z = (m - 1.0) / (m + 1.0);
    let (z2, mut term, mut sum) = (z * z, z, 0.0);
    for k in 0..40 {
        sum += term / (2 * k + 1) as f64;
        term *= z2;
    }
    exponent as f64 * core::f64::consts::LN_2 + 2.0 * sum
}

/// `√x` for `x >= 0` by Newton's method from a bit-level first guess.
pub(crate) fn sqrt(x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    let mut r = f64::from_bits((x.to_bits() >> 1) + (1023 << 51));
    for _ in 0..8 {
        r = 0.5 * (r + x / r);
    }
    r
}

fn sinh(x: f64) -> f64 {
    let e = exp(x);
    0.5 * (e - 1.0 / e)
}

fn asinh(u: f64) -> f64 {
    if u < 0.0 {
        return -asinh(-u);
    }
    ln(u + sqrt(u * u + 1.0))
}

/// A catenary in its own plane: `x` along the ground from the start, `y` up.
pub(crate) struct Catenary {
    /// The curve's parameter `a` (its radius of curvature at the lowest point).
    a: f64,
    /// Arc length from the lowest point to the start (negative: the start is left of it).
    s0: f64,
    /// `a·asinh(s0/a)`: the start's abscissa relative to the lowest point.
    x0: f64,
    /// `sqrt(a² + s0²)`: the start's height relative to the lowest point's `a`.
    y0: f64,
}

impl Catenary {
    /// The catenary of arc length `length` from `(0, 0)` to `(span, rise)`, for
    /// `span > 0` and `length² > span² + rise²`.
    pub(crate) fn through(span: f64, rise: f64, length: f64) -> Catenary {
        // sinh(z)/z = sqrt(L² - rise²)/span with z = span/(2a): bisection on z (the left
        // side grows monotonically from 1), then a = span/(2z).
        let ratio = sqrt(length * length - rise * rise) / span;
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        while sinh(hi) / hi < ratio && hi < 700.0 {
            hi *= 2.0;
        }
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if sinh(mid) / mid < ratio {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let a = span / (lo + hi);
        // rise/length = tanh(m/a) with m the chord midpoint's abscissa from the lowest point.
        let t = rise / length;
        let m = 0.5 * a * ln((1.0 + t) / (1.0 - t));
        let x0 = m - 0.5 * span;
        let s0 = a * sinh(x0 / a);
        Catenary {
            a,
            s0,
            x0,
            y0: sqrt(a * a + s0 * s0),
        }
    }

    /// The point at arc length `s` from the start, as `(x, y)` from the start.
    pub(crate) fn at(&self, s: f64) -> (f64, f64) {
        let sigma = self.s0 + s;
        let x = self.a * asinh(sigma / self.a);
        let y = sqrt(self.a * self.a + sigma * sigma);
        (x - self.x0, y - self.y0)
    }
}

#[cfg(all(test, dunas_std))]
mod tests {
    use super::*;

    #[test]
    fn elementary_functions_match_std() {
        for x in [-30.0, -2.5, -0.3, 0.0, 1e-9, 0.7, 3.0, 40.0] {
            let e = std::primitive::f64::exp(x);
            assert!((exp(x) - e).abs() <= 1e-13 * e, "exp {x}");
        }
        for y in [1e-8, 0.1, 0.999, 1.0, 2.0, 7.5, 1e6] {
            assert!(
                (ln(y) - y.ln()).abs() <= 1e-13 * (1.0 + y.ln().abs()),
                "ln {y}"
            );
            assert!((sqrt(y) - y.sqrt()).abs() <= 1e-15 * y.sqrt(), "sqrt {y}");
        }
        for u in [-5.0f64, 0.0, 0.2, 3.0, 1e4] {
            assert!(
                (asinh(u) - u.asinh()).abs() <= 1e-12 * (1.0 + u.abs()),
                "asinh {u}"
            );
        }
    }

    #[test]
    fn ends_length_and_shape_are_those_asked() {
        for (span, rise, length) in [(10.0, 0.0, 12.0), (8.0, 3.0, 9.0), (5.0, -4.0, 30.0)] {
            let c = Catenary::through(span, rise, length);
            let (x0, y0) = c.at(0.0);
            let (x1, y1) = c.at(length);
            assert!(x0.abs() < 1e-9 && y0.abs() < 1e-9);
            assert!((x1 - span).abs() < 1e-9 * length && (y1 - rise).abs() < 1e-9 * length);
            // Arc length by a fine polyline, and y = a·cosh(x/a) + const at every point.
            let (mut len, mut prev) = (0.0, (0.0, 0.0));
            for i in 1..=20_000 {
                let p = c.at(length * i as f64 / 20_000.0);
                len += ((p.0 - prev.0).powi(2) + (p.1 - prev.1).powi(2)).sqrt();
                prev = p;
                let expected = c.a * ((p.0 + c.x0) / c.a).cosh() - c.y0;
                assert!((p.1 - expected).abs() < 1e-9 * length);
            }
            assert!((len - length).abs() < 1e-6 * length, "{len} vs {length}");
        }
    }
}
