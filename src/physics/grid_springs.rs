//! The springs of a cloth grid, implied by the grid instead of stored.

use super::spring::{Material, Snap, Topology, past};
use crate::{Point, Scalar};

/// The springs of a `U × V` cloth grid, implied by the grid instead of stored: structural
/// (to the 4 neighbours), shear (diagonals) and bending (two apart), each class with its own
/// material, [`Snap`] limit and one rest length per direction. A torn spring is one bit (six
/// a particle); 8×8 has 306 springs and costs 152 bytes in `f32`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridSprings<S, const U: usize, const V: usize> {
    /// Rest length between neighbours along a row (`u`).
    pub rest_u: S,
    /// Rest length between neighbours along a column (`v`).
    pub rest_v: S,
    /// Rest lengths of the diagonals: `[0]` joins `(i, j)` to `(i+1, j+1)`, `[1]` joins
    /// `(i+1, j)` to `(i, j+1)` (equal on a rectangular grid).
    pub rest_diagonals: [S; 2],
    /// Structural springs resist stretching.
    pub structural: Material<S>,
    /// Shear springs keep the squares square.
    pub shear: Material<S>,
    /// Bending springs resist folding.
    pub bending: Material<S>,
    /// When the structural, shear and bending springs tear.
    pub snap: [Snap<S>; 3],
    /// Torn springs: bit `f` of `(i, j)` is family `f`'s spring from particle `(i, j)` (see
    /// [`FAMILIES`](Self::FAMILIES)).
    torn: [[u8; U]; V],
}

impl<S: Scalar, const U: usize, const V: usize> GridSprings<S, U, V> {
    /// The number of springs: `V(U-1) + U(V-1) + 2(U-1)(V-1) + V(U-2) + U(V-2)`.
    pub const COUNT: usize =
        V * (U - 1) + U * (V - 1) + 2 * (U - 1) * (V - 1) + V * (U - 2) + U * (V - 2);

    /// The six families of springs, each from particle `(i, j)` to `(i + di, j + dj)`, and
    /// its class (0 structural, 1 shear, 2 bending).
    pub const FAMILIES: [(isize, usize, usize); 6] = [
        (1, 0, 0),
        (0, 1, 0),
        (1, 1, 1),
        (-1, 1, 1),
        (2, 0, 2),
        (0, 2, 2),
    ];

    /// The springs of a grid with these rest lengths and materials, none torn, none tearing.
    pub fn new(rest_u: S, rest_v: S, rest_diagonals: [S; 2], materials: [Material<S>; 3]) -> Self {
        GridSprings {
            rest_u,
            rest_v,
            rest_diagonals,
            structural: materials[0],
            shear: materials[1],
            bending: materials[2],
            snap: [Snap::Never; 3],
            torn: [[0; U]; V],
        }
    }

    /// Family `f`'s rest length and material.
    fn family(&self, f: usize) -> (S, Material<S>) {
        let two = S::ONE + S::ONE;
        match f {
            0 => (self.rest_u, self.structural),
            1 => (self.rest_v, self.structural),
            2 => (self.rest_diagonals[0], self.shear),
            3 => (self.rest_diagonals[1], self.shear),
            4 => (self.rest_u * two, self.bending),
            _ => (self.rest_v * two, self.bending),
        }
    }

    /// Calls `f(family, i, j, a, b)` for every spring of the grid, torn or not.
    #[inline]
    fn each(mut f: impl FnMut(usize, usize, usize, usize, usize)) {
        for (family, &(di, dj, _)) in Self::FAMILIES.iter().enumerate() {
            let columns = usize::from(di < 0)..U.saturating_sub(di.max(0) as usize);
            for j in 0..V.saturating_sub(dj) {
                for i in columns.clone() {
                    let a = j * U + i;
                    f(family, i, j, a, (a + dj * U).wrapping_add_signed(di));
                }
            }
        }
    }

    /// Whether family `f`'s spring from particle `(i, j)` is torn (`false` for a family,
    /// row or column that does not exist).
    pub fn is_torn(&self, f: usize, i: usize, j: usize) -> bool {
        f < Self::FAMILIES.len()
            && self
                .torn
                .get(j)
                .and_then(|row| row.get(i))
                .is_some_and(|bits| bits & (1 << f) != 0)
    }

    /// Tears every spring whose segment, seen along the first two coordinates, crosses the
    /// segment from `from` to `to` (a swipe across a cloth on the screen); returns how many.
    pub(crate) fn tear_across<P: Point<Scalar = S>>(
        &mut self,
        x: &[P],
        c: crate::Vec2<S>,
        d: crate::Vec2<S>,
    ) -> usize {
        let mut torn = 0;
        let flat = |p: P| crate::Vec2::new(p.coord(0), p.coord(1));
        let mut marks = self.torn;
        Self::each(|f, i, j, a, b| {
            if marks[j][i] & (1 << f) == 0
                && let (Some(&pa), Some(&pb)) = (x.get(a), x.get(b))
                && crate::geometry::segment::crossing(flat(pa), flat(pb), c, d).is_some()
            {
                marks[j][i] |= 1 << f;
                torn += 1;
            }
        });
        self.torn = marks;
        torn
    }
}

impl<S: Scalar, const U: usize, const V: usize> Topology<S> for GridSprings<S, U, V> {
    fn for_each_spring(&self, mut f: impl FnMut(usize, usize, S, Material<S>)) {
        // Family by family: one call site, so the physics' closure inlines.
        let families: [(S, Material<S>); 6] = core::array::from_fn(|k| self.family(k));
        Self::each(|family, i, j, a, b| {
            if self.torn[j][i] & (1 << family) == 0 {
                let (rest, material) = families[family];
                f(a, b, rest, material);
            }
        });
    }
    fn spring_count(&self) -> usize {
        Self::COUNT
    }
    /// The grid's size, each class's stiffness and every torn bit (a torn spring is its
    /// bit; 10 particles' 6 bits to a mix): about 13 mixes for 8×8, where listing every
    /// spring took two mixes a spring.
    fn fingerprint(&self, key: u64, mix: impl Fn(u64, u64) -> u64) -> u64 {
        let size = ((U as u64) << 32) | V as u64;
        let classes = [self.structural, self.shear, self.bending];
        let key = classes
            .iter()
            .fold(mix(key, size), |key, m| mix(key, m.stiffness.bits()));
        self.torn.as_flattened().chunks(10).fold(key, |key, chunk| {
            let bits = chunk.iter().fold(0u64, |acc, &b| (acc << 6) | u64::from(b));
            mix(key, bits)
        })
    }
    fn snap<P: Point<Scalar = S>>(&mut self, x: &[P]) -> usize {
        let limits: [S; 6] = core::array::from_fn(|k| {
            let (rest, material) = self.family(k);
            self.snap[Self::FAMILIES[k].2].length(rest, material)
        });
        if limits.iter().all(|&l| l <= S::ZERO) {
            return 0;
        }
        let mut torn = 0;
        let mut marks = self.torn;
        Self::each(|f, i, j, a, b| {
            let limit = limits[f];
            if limit > S::ZERO
                && marks[j][i] & (1 << f) == 0
                && let (Some(&pa), Some(&pb)) = (x.get(a), x.get(b))
                && past(pa, pb, limit)
            {
                marks[j][i] |= 1 << f;
                torn += 1;
            }
        });
        self.torn = marks;
        torn
    }
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::{Vec2, Vec3};

    /// A fingerprint changes with a torn spring and a class's stiffness, and only then.
    #[test]
    fn fingerprint_follows_tears_and_stiffness() {
        let m = Material {
            stiffness: 100.0f32,
            damping: 1.0,
        };
        let grid = GridSprings::<f32, 12, 5>::new(1.0, 1.0, [1.5, 1.5], [m, m, m]);
        let mix = |key: u64, x: u64| {
            (key ^ x)
                .wrapping_mul(0x9E37_79B9_7F4A_7C15)
                .rotate_left(29)
        };
        let base = grid.fingerprint(7, mix);
        assert_eq!({ grid }.fingerprint(7, mix), base);
        // The springs up from row 3 at column 11: past the first ten particles of a row,
        // in the fingerprint's second chunk of torn bits.
        let x: [Vec3<f32>; 60] =
            core::array::from_fn(|k| Vec3::new((k % 12) as f32, (k / 12) as f32, 0.0));
        let mut torn = grid;
        let cut = torn.tear_across(&x, Vec2::new(10.5, 3.5), Vec2::new(11.5, 3.5));
        assert!(cut > 0);
        assert_ne!(torn.fingerprint(7, mix), base);
        let mut stiffer = grid;
        stiffer.bending.stiffness = 101.0;
        assert_ne!(stiffer.fingerprint(7, mix), base);
    }
}
