//! Tensor-product Bézier patches: the smooth surface drawn over a grid of cloth particles.

use crate::curves::curve::{clamp_unit, eval_points, tangent_points};
use crate::error::check_points;
use crate::error::invalid;
use crate::{Aabb, Error, Point, Scalar, Vec3};

/// A Bézier patch with `U × V` control points: `V` rows of `U` points each.
///
/// `points()[j][i]` is the control point in row `j` (the `v` direction) and column `i` (the
/// `u` direction). An 8×8 patch is a sail of 64 particles. Construction checks the points
/// (finite, inside [`Scalar::SAFE_RANGE`]); `U < 2` or `V < 2` does not compile.
///
/// ```
/// use dunas::{Patch, Vec3};
/// let flat = Patch::new(core::array::from_fn::<_, 3, _>(|j| {
///     core::array::from_fn::<_, 3, _>(|i| Vec3::new(i as f32, j as f32, 0.0))
/// }))?;
/// assert_eq!(flat.eval(0.5, 0.5), Vec3::new(1.0, 1.0, 0.0));
/// assert_eq!(flat.normal(0.5, 0.5), Some(Vec3::new(0.0, 0.0, 1.0)));
/// # Ok::<(), dunas::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Patch<P, const U: usize, const V: usize> {
    points: [[P; U]; V],
}

/// A bicubic patch (4×4 control points).
pub type Bicubic<P> = Patch<P, 4, 4>;

impl<P: Point, const U: usize, const V: usize> Patch<P, U, V> {
    /// A patch over these control points (`V` rows of `U`).
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for a bad coordinate.
    pub fn new(points: [[P; U]; V]) -> Result<Self, Error> {
        const {
            assert!(
                U >= 2 && V >= 2,
                "a patch needs at least 2×2 control points"
            )
        };
        for row in &points {
            check_points(row, "control point")?;
        }
        Ok(Patch { points })
    }

    /// The control points, `V` rows of `U`.
    #[inline]
    pub fn points(&self) -> &[[P; U]; V] {
        &self.points
    }

    /// The `V` points where the rows' curves are at `u` (the control points of the
    /// iso-curve along `v`). Cost: `V·U²/2` lerps.
    #[inline]
    fn column_at(&self, u: P::Scalar) -> [P; V] {
        core::array::from_fn(|j| eval_points(&self.points[j], u))
    }

    /// The `V` row tangents `∂/∂u` at `u`.
    #[inline]
    fn column_tangents_at(&self, u: P::Scalar) -> [P; V] {
        core::array::from_fn(|j| tangent_points(&self.points[j], u))
    }

    /// The surface point at `(u, v)`, each clamped to `[0, 1]` (NaN as 0).
    /// Cost: `V·U²/2 + V²/2` lerps.
    pub fn eval(&self, u: P::Scalar, v: P::Scalar) -> P {
        eval_points(&self.column_at(clamp_unit(u)), clamp_unit(v))
    }

    /// The partial derivatives `(∂P/∂u, ∂P/∂v)` at `(u, v)`. Cost: about twice [`eval`](Self::eval).
    pub fn partials(&self, u: P::Scalar, v: P::Scalar) -> (P, P) {
        let (u, v) = (clamp_unit(u), clamp_unit(v));
        let du = eval_points(&self.column_tangents_at(u), v);
        let dv = tangent_points(&self.column_at(u), v);
        (du, dv)
    }

    /// The box around the control points, which contains the whole surface.
    pub fn bounding_box(&self) -> Aabb<P> {
        let mut b = Aabb::point(self.points[0][0]);
        for row in &self.points {
            for &p in row {
                b = b.including(p);
            }
        }
        b
    }

    /// Samples an `nu × nv` grid of surface points into `positions` (row-major: point
    /// `(i, j)` at `j * nu + i`, `u = i/(nu-1)`, `v = j/(nv-1)`) and returns `nu * nv`.
    ///
    /// Each of the `nu` columns evaluates the `V` rows once (`V·U²/2` lerps) and then walks
    /// `nv` points along `v` (`V²/2` lerps each), instead of redoing the rows per point.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when `nu` or `nv` is below 2 or the grid is over
    /// [`MAX_SAMPLES`](crate::curves::sampler::MAX_SAMPLES); [`Error::BufferTooSmall`] when
    /// `positions` holds fewer than `nu * nv`.
    pub fn sample_grid(&self, nu: usize, nv: usize, positions: &mut [P]) -> Result<usize, Error> {
        let count = grid_count(nu, nv, positions.len())?;
        for i in 0..nu {
            let col = self.column_at(grid_param(i, nu));
            for j in 0..nv {
                positions[j * nu + i] = eval_points(&col, grid_param(j, nv));
            }
        }
        Ok(count)
    }
}

impl<S: Scalar, const U: usize, const V: usize> Patch<Vec3<S>, U, V> {
    /// The unit normal `∂u × ∂v / |∂u × ∂v|` at `(u, v)`, or `None` where the surface is
    /// degenerate (a collapsed edge, a flat fold). The partials are normalised before the
    /// cross product, so `Q16` does not overflow on large patches.
    pub fn normal(&self, u: S, v: S) -> Option<Vec3<S>> {
        let (du, dv) = self.partials(u, v);
        unit_normal(du, dv)
    }

    /// Like [`sample_grid`](Patch::sample_grid), also writing the unit normal of every
    /// point into `normals` (the zero vector where the surface is degenerate). The row
    /// tangents come from the same first pass. Cost: about 2.5× `sample_grid`.
    ///
    /// # Errors
    /// As [`sample_grid`](Patch::sample_grid), for both buffers.
    pub fn sample_grid_with_normals(
        &self,
        nu: usize,
        nv: usize,
        positions: &mut [Vec3<S>],
        normals: &mut [Vec3<S>],
    ) -> Result<usize, Error> {
        let count = grid_count(nu, nv, positions.len().min(normals.len()))?;
        for i in 0..nu {
            let u = grid_param(i, nu);
            let col = self.column_at(u);
            let tangents = self.column_tangents_at(u);
            for j in 0..nv {
                let v = grid_param(j, nv);
                let k = j * nu + i;
                positions[k] = eval_points(&col, v);
                let du = eval_points(&tangents, v);
                let dv = tangent_points(&col, v);
                normals[k] = unit_normal(du, dv).unwrap_or_default();
            }
        }
        Ok(count)
    }
}

fn unit_normal<S: Scalar>(du: Vec3<S>, dv: Vec3<S>) -> Option<Vec3<S>> {
    du.normalize()?.cross(dv.normalize()?).normalize()
}

#[inline]
fn grid_param<S: Scalar>(i: usize, n: usize) -> S {
    if i + 1 >= n {
        S::ONE
    } else {
        S::ratio(i as u32, (n - 1) as u32)
    }
}

fn grid_count(nu: usize, nv: usize, len: usize) -> Result<usize, Error> {
    if nu < 2 || nv < 2 {
        return Err(invalid("grid size", "at least 2 points each way"));
    }
    let count = nu
        .checked_mul(nv)
        .filter(|&c| c <= crate::curves::sampler::MAX_SAMPLES);
    let count = count.ok_or(invalid("grid size", "at most MAX_SAMPLES points"))?;
    if len < count {
        return Err(Error::BufferTooSmall {
            needed: count,
            got: len,
        });
    }
    Ok(count)
}

/// Writes the indices of one triangle strip over an `nu × nv` grid (laid out as
/// [`Patch::sample_grid`] writes it) into `out` and returns how many it wrote:
/// `2·nu·(nv-1) + 2·(nv-2)`. Rows are joined by two repeated indices (degenerate
/// triangles), which keeps the winding consistent from row to row.
///
/// ```
/// let mut idx = [0u16; 16];
/// let n = dunas::patch::strip_indices(3, 3, &mut idx)?;
/// assert_eq!(&idx[..n], &[0, 3, 1, 4, 2, 5, 5, 3, 3, 6, 4, 7, 5, 8]);
/// # Ok::<(), dunas::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidParameter`] when `nu` or `nv` is below 2 or the grid has more than
/// 65536 points (`u16` indices); [`Error::BufferTooSmall`] when `out` is too short.
pub fn strip_indices(nu: usize, nv: usize, out: &mut [u16]) -> Result<usize, Error> {
    if nu < 2 || nv < 2 || nu.saturating_mul(nv) > 1 << 16 {
        return Err(invalid(
            "grid size",
            "at least 2 points each way and at most 65 536 points",
        ));
    }
    let needed = 2 * nu * (nv - 1) + 2 * (nv - 2);
    if out.len() < needed {
        return Err(Error::BufferTooSmall {
            needed,
            got: out.len(),
        });
    }
    let mut k = 0;
    let mut push = |i: usize| {
        out[k] = i as u16;
        k += 1;
    };
    for j in 0..nv - 1 {
        if j > 0 {
            push(j * nu + nu - 1); // repeat the last index of the previous row
            push(j * nu); // and the first of this one
        }
        for i in 0..nu {
            push(j * nu + i);
            push((j + 1) * nu + i);
        }
    }
    Ok(k)
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::Bezier;

    /// z = x·y over [0,2]² is exactly the bilinear patch of its corners.
    fn saddle() -> Patch<Vec3<f64>, 2, 2> {
        Patch::new([
            [Vec3::new(0.0, 0.0, 0.0), Vec3::new(2.0, 0.0, 0.0)],
            [Vec3::new(0.0, 2.0, 0.0), Vec3::new(2.0, 2.0, 4.0)],
        ])
        .unwrap()
    }

    fn wavy() -> Patch<Vec3<f64>, 4, 3> {
        Patch::new(core::array::from_fn(|j| {
            core::array::from_fn(|i| {
                Vec3::new(i as f64, j as f64, ((i * 3 + j * 5) % 4) as f64 * 0.5)
            })
        }))
        .unwrap()
    }

    #[test]
    fn saddle_matches_closed_form() {
        let p = saddle();
        for (u, v) in [(0.25, 0.5), (0.9, 0.1), (0.5, 0.5)] {
            let (x, y) = (2.0 * u, 2.0 * v);
            assert!((p.eval(u, v) - Vec3::new(x, y, x * y)).length() < 1e-12);
            let n = p.normal(u, v).unwrap();
            let exact = Vec3::new(-y, -x, 1.0).normalize().unwrap();
            assert!((n - exact).length() < 1e-12);
        }
    }

    #[test]
    fn rows_and_columns_are_bezier_curves() {
        let p = wavy();
        for j in 0..3 {
            let row = Bezier::new(p.points()[j]).unwrap();
            let v = j as f64 / 2.0;
            // Along v the patch interpolates only its first and last rows.
            if j != 1 {
                assert!((p.eval(0.3, v) - row.eval(0.3)).length() < 1e-12);
            }
        }
        let (du, dv) = p.partials(0.3, 0.6);
        let h = 1e-6;
        let fd_u = (p.eval(0.3 + h, 0.6) - p.eval(0.3 - h, 0.6)) * (0.5 / h);
        let fd_v = (p.eval(0.3, 0.6 + h) - p.eval(0.3, 0.6 - h)) * (0.5 / h);
        assert!((du - fd_u).length() < 1e-6);
        assert!((dv - fd_v).length() < 1e-6);
    }

    #[test]
    fn grid_matches_pointwise_eval() {
        let p = wavy();
        let (nu, nv) = (5, 4);
        let mut pos = [Vec3::default(); 20];
        let mut nor = [Vec3::default(); 20];
        assert_eq!(
            p.sample_grid_with_normals(nu, nv, &mut pos, &mut nor),
            Ok(20)
        );
        let mut pos2 = [Vec3::default(); 20];
        assert_eq!(p.sample_grid(nu, nv, &mut pos2), Ok(20));
        for j in 0..nv {
            for i in 0..nu {
                let (u, v) = (i as f64 / 4.0, j as f64 / 3.0);
                let k = j * nu + i;
                assert!((pos[k] - p.eval(u, v)).length() < 1e-12);
                assert_eq!(pos[k], pos2[k]);
                assert!((nor[k] - p.normal(u, v).unwrap()).length() < 1e-12);
                assert!(p.bounding_box().contains(pos[k]));
            }
        }
    }

    #[test]
    fn grid_errors() {
        let p = wavy();
        let mut pos = [Vec3::default(); 10];
        assert!(matches!(
            p.sample_grid(1, 5, &mut pos),
            Err(Error::InvalidParameter { .. })
        ));
        assert_eq!(
            p.sample_grid(4, 4, &mut pos),
            Err(Error::BufferTooSmall {
                needed: 16,
                got: 10
            })
        );
        assert!(matches!(
            p.sample_grid(usize::MAX, 2, &mut pos),
            Err(Error::InvalidParameter { .. })
        ));
    }

    #[test]
    fn degenerate_normal_is_none() {
        let mut pts = wavy().points;
        pts[0] = [Vec3::new(0.0, 0.0, 0.0); 4]; // collapse the first row to a point
        let p = Patch::new(pts).unwrap();
        assert_eq!(p.normal(0.5, 0.0), None);
    }

    #[test]
    fn strip_covers_every_quad_with_consistent_winding() {
        let (nu, nv) = (4, 3);
        let mut idx = [0u16; 32];
        let n = strip_indices(nu, nv, &mut idx).unwrap();
        assert_eq!(n, 2 * nu * (nv - 1) + 2 * (nv - 2));
        let mut area = 0;
        for w in 0..n - 2 {
            let t = [idx[w], idx[w + 1], idx[w + 2]];
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                continue; // degenerate joint
            }
            // Signed area on the grid (i, j), flipped on odd triangles of a strip.
            let xy = |k: u16| ((k as i32 % nu as i32), (k as i32 / nu as i32));
            let (a, b, c) = (xy(t[0]), xy(t[1]), xy(t[2]));
            let cross = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
            let cross = if w % 2 == 0 { cross } else { -cross };
            assert!(cross < 0, "triangle {w} {t:?} winds the wrong way");
            area += 1;
        }
        assert_eq!(area, 2 * (nu - 1) * (nv - 1));
        assert!(matches!(
            strip_indices(300, 300, &mut idx),
            Err(Error::InvalidParameter { .. })
        ));
    }
}
