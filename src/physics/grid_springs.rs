//! The springs of a cloth grid, implied by the grid instead of stored.

use super::spring::{Material, Snap, Topology, past};
use crate::{Error, Point, Scalar};

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
    torn: TornBits<U, V, false>,
}

impl<S: Scalar, const U: usize, const V: usize> GridSprings<S, U, V> {
    /// The number of springs: `V(U-1) + U(V-1) + 2(U-1)(V-1) + V(U-2) + U(V-2)`.
    pub const COUNT: usize =
        V * (U - 1) + U * (V - 1) + 2 * (U - 1) * (V - 1) + V * (U - 2) + U * (V - 2);

    /// The six families of springs, each from particle `(i, j)` to `(i + di, j + dj)`, and
    /// its class (0 structural, 1 shear, 2 bending).
    pub const FAMILIES: [(isize, usize, usize); 6] = FAMILIES;

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
            torn: TornBits::default(),
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

    /// Whether family `f`'s spring from particle `(i, j)` is torn (`false` for a family,
    /// row or column that does not exist).
    pub fn is_torn(&self, f: usize, i: usize, j: usize) -> bool {
        self.torn.is_torn(f, i, j)
    }

    /// Tears every spring whose segment, seen along the first two coordinates, crosses the
    /// segment from `from` to `to` (a swipe across a cloth on the screen); returns how many.
    pub(crate) fn tear_across<P: Point<Scalar = S>>(
        &mut self,
        x: &[P],
        c: crate::Vec2<S>,
        d: crate::Vec2<S>,
    ) -> usize {
        self.torn.tear_across(x, c, d)
    }
}

impl<S: Scalar, const U: usize, const V: usize> Topology<S> for GridSprings<S, U, V> {
    fn for_each_spring(&self, mut f: impl FnMut(usize, usize, S, Material<S>)) {
        // Family by family: one call site, so the physics' closure inlines.
        let families: [(S, Material<S>); 6] = core::array::from_fn(|k| self.family(k));
        self.torn.each_intact(|family, _, a, b| {
            let (rest, material) = families[family];
            f(a, b, rest, material);
        });
    }
    /// A family's springs along a row are a run, and a family's that join rows (`di = 0`)
    /// a run down the whole grid, while none of the grid's springs is torn; a torn spring
    /// ends its run.
    fn for_each_run(&self, mut f: impl FnMut(usize, usize, usize, S, Material<S>)) {
        let families: [(S, Material<S>); 6] = core::array::from_fn(|k| self.family(k));
        self.torn.each_run(|family, a, b, count| {
            let (rest, material) = families[family];
            f(a, b, count, rest, material);
        });
    }
    fn spring_count(&self) -> usize {
        Self::COUNT
    }
    /// The grid's size, each class's stiffness and every torn bit (a torn spring is its
    /// bit; 10 particles' 6 bits to a mix): about 13 mixes for 8×8, where listing every
    /// spring took two mixes a spring.
    fn fingerprint(&self, key: u64, mix: impl Fn(u64, u64) -> u64) -> u64 {
        let classes = [self.structural, self.shear, self.bending];
        self.torn.fingerprint(classes, key, mix)
    }
    fn snap<P: Point<Scalar = S>>(&mut self, x: &[P]) -> usize {
        let limits: [S; 6] = core::array::from_fn(|k| {
            let (rest, material) = self.family(k);
            self.snap[FAMILIES[k].2].length(rest, material)
        });
        self.torn.snap(x, |f, _| limits[f])
    }
}

/// The springs of a `U × V` grid closed both ways, a [`Torus`](crate::Torus): each row is a
/// ring (its last particle joined to its first) and the last row is joined to the first.
/// The same six families as [`GridSprings`], every one starting at every particle:
/// `6·U·V` springs, implied by the grid. A surface of revolution has one rest length a
/// family and row ([`rest_length`](Self::rest_length), measured at the row's first
/// particle), where a flat cloth has one a family. `U, V ≥ 5`, so that the bending springs
/// two apart are distinct springs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TorusSprings<S, const U: usize, const V: usize> {
    /// Rest lengths: `rest[j][f]` is family `f`'s along row `j`.
    rest: [[S; 6]; V],
    /// Structural springs resist stretching.
    pub structural: Material<S>,
    /// Shear springs keep the squares square.
    pub shear: Material<S>,
    /// Bending springs resist folding.
    pub bending: Material<S>,
    /// When the structural, shear and bending springs tear.
    pub snap: [Snap<S>; 3],
    torn: TornBits<U, V, true>,
}

impl<S: Scalar, const U: usize, const V: usize> TorusSprings<S, U, V> {
    /// The number of springs: `6·U·V`.
    pub const COUNT: usize = 6 * U * V;

    /// The springs of the closed grid `x` (row `j` is `x[j]`), relaxed at the distances
    /// from each row's first particle, with the structural, shear and bending `materials`,
    /// none torn, none tearing.
    ///
    /// # Errors
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] for a position that is NaN, infinite or
    /// past [`Scalar::SAFE_RANGE`]; [`Error::ZeroRestLength`] for two particles at one
    /// place, naming the first such spring (flat indices `j·U + i`).
    pub fn measured<P: Point<Scalar = S>>(
        x: &[[P; U]; V],
        materials: [Material<S>; 3],
    ) -> Result<Self, Error> {
        const {
            assert!(
                U >= 5 && V >= 5,
                "a closed grid needs at least 5×5 particles"
            )
        };
        let flat = x.as_flattened();
        crate::error::check_points(flat, "position")?;
        let mut rest = [[S::ZERO; 6]; V];
        let mut zero = None;
        TornBits::<U, V, true>::each(|f, i, j, a, b| {
            let length = (flat[b] - flat[a]).length();
            if i == 0 {
                rest[j][f] = length;
            }
            if zero.is_none() && length <= S::ZERO {
                zero = Some(Error::ZeroRestLength { a, b });
            }
        });
        match zero {
            Some(error) => Err(error),
            None => Ok(TorusSprings {
                rest,
                structural: materials[0],
                shear: materials[1],
                bending: materials[2],
                snap: [Snap::Never; 3],
                torn: TornBits::default(),
            }),
        }
    }

    /// Family `f`'s rest length along row `j` (0 for a family or row that does not exist).
    pub fn rest_length(&self, f: usize, j: usize) -> S {
        self.rest
            .get(j)
            .and_then(|row| row.get(f))
            .copied()
            .unwrap_or(S::ZERO)
    }

    /// Whether family `f`'s spring from particle `(i, j)` is torn (`false` for a family,
    /// row or column that does not exist).
    pub fn is_torn(&self, f: usize, i: usize, j: usize) -> bool {
        self.torn.is_torn(f, i, j)
    }

    fn materials(&self) -> [Material<S>; 3] {
        [self.structural, self.shear, self.bending]
    }
}

impl<S: Scalar, const U: usize, const V: usize> Topology<S> for TorusSprings<S, U, V> {
    fn for_each_spring(&self, mut f: impl FnMut(usize, usize, S, Material<S>)) {
        let materials = self.materials();
        self.torn.each_intact(|family, j, a, b| {
            f(a, b, self.rest[j][family], materials[FAMILIES[family].2]);
        });
    }
    fn spring_count(&self) -> usize {
        Self::COUNT
    }
    fn fingerprint(&self, key: u64, mix: impl Fn(u64, u64) -> u64) -> u64 {
        self.torn.fingerprint(self.materials(), key, mix)
    }
    fn snap<P: Point<Scalar = S>>(&mut self, x: &[P]) -> usize {
        // Each family's limit along each row, once: not once a spring.
        let materials = self.materials();
        let limits: [[S; 6]; V] = core::array::from_fn(|j| {
            core::array::from_fn(|f| {
                let class = FAMILIES[f].2;
                self.snap[class].length(self.rest[j][f], materials[class])
            })
        });
        self.torn.snap(x, |f, j| limits[j][f])
    }
}

/// The six families of a grid's springs, each from particle `(i, j)` to `(i + di, j + dj)`,
/// and its class (0 structural, 1 shear, 2 bending).
const FAMILIES: [(isize, usize, usize); 6] = [
    (1, 0, 0),
    (0, 1, 0),
    (1, 1, 1),
    (-1, 1, 1),
    (2, 0, 2),
    (0, 2, 2),
];

/// Which of a `U × V` grid's implied springs are torn: bit `f` of `(i, j)` is family `f`'s
/// spring from particle `(i, j)` ([`FAMILIES`]), six bits a particle. `CLOSED` grids wrap
/// both ways (a torus): every particle starts a spring of every family.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TornBits<const U: usize, const V: usize, const CLOSED: bool>([[u8; U]; V]);

impl<const U: usize, const V: usize, const CLOSED: bool> Default for TornBits<U, V, CLOSED> {
    fn default() -> Self {
        TornBits([[0; U]; V])
    }
}

impl<const U: usize, const V: usize, const CLOSED: bool> TornBits<U, V, CLOSED> {
    /// Calls `f(family, i, j, a, b)` for every spring of the grid, torn or not, family by
    /// family: `a` is `(i, j)`'s flat index, `b` the other end's.
    #[inline]
    fn each(mut f: impl FnMut(usize, usize, usize, usize, usize)) {
        for (family, &(di, dj, _)) in FAMILIES.iter().enumerate() {
            if CLOSED {
                for j in 0..V {
                    let row = (j + dj) % V * U;
                    for i in 0..U {
                        let column = (i as isize + di).rem_euclid(U as isize) as usize;
                        f(family, i, j, j * U + i, row + column);
                    }
                }
            } else {
                let columns = usize::from(di < 0)..U.saturating_sub(di.max(0) as usize);
                for j in 0..V.saturating_sub(dj) {
                    for i in columns.clone() {
                        let a = j * U + i;
                        f(family, i, j, a, (a + dj * U).wrapping_add_signed(di));
                    }
                }
            }
        }
    }

    /// Calls `f(family, j, a, b)` for every spring that is not torn.
    #[inline]
    pub(crate) fn each_intact(&self, mut f: impl FnMut(usize, usize, usize, usize)) {
        Self::each(|family, i, j, a, b| {
            if self.0[j][i] & (1 << family) == 0 {
                f(family, j, a, b);
            }
        });
    }

    /// Calls `f(family, a, b, count)` for every run of intact springs `(a + k, b + k)`,
    /// `k < count`, in [`each_intact`](Self::each_intact)'s order. With nothing torn (one
    /// pass over the bits), an open grid's family is a run a row, or one run when it joins
    /// rows (`di = 0`); otherwise a torn spring ends its run. A closed grid's springs wrap
    /// and come one at a time.
    pub(crate) fn each_run(&self, mut f: impl FnMut(usize, usize, usize, usize)) {
        if CLOSED {
            return self.each_intact(|family, _, a, b| f(family, a, b, 1));
        }
        let whole = self.0.iter().flatten().fold(0, |all, &bits| all | bits) == 0;
        for (family, &(di, dj, _)) in FAMILIES.iter().enumerate() {
            let columns = usize::from(di < 0)..U.saturating_sub(di.max(0) as usize);
            let rows = V.saturating_sub(dj);
            let ends = |i: usize, j: usize| {
                let a = j * U + i;
                (a, (a + dj * U).wrapping_add_signed(di))
            };
            if whole && columns.len() == U {
                let (a, b) = ends(0, 0);
                f(family, a, b, rows * U);
                continue;
            }
            for j in 0..rows {
                if whole {
                    let (a, b) = ends(columns.start, j);
                    f(family, a, b, columns.len());
                    continue;
                }
                let mut run: Option<(usize, usize, usize)> = None;
                for i in columns.clone() {
                    if self.0[j][i] & (1 << family) == 0 {
                        match &mut run {
                            Some((_, _, count)) => *count += 1,
                            None => {
                                let (a, b) = ends(i, j);
                                run = Some((a, b, 1));
                            }
                        }
                    } else if let Some((a, b, count)) = run.take() {
                        f(family, a, b, count);
                    }
                }
                if let Some((a, b, count)) = run {
                    f(family, a, b, count);
                }
            }
        }
    }

    /// Whether family `f`'s spring from particle `(i, j)` is torn (`false` for a family,
    /// row or column that does not exist).
    pub(crate) fn is_torn(&self, f: usize, i: usize, j: usize) -> bool {
        f < FAMILIES.len()
            && self
                .0
                .get(j)
                .and_then(|row| row.get(i))
                .is_some_and(|bits| bits & (1 << f) != 0)
    }

    /// Tears every spring whose segment, seen along the first two coordinates, crosses the
    /// segment from `c` to `d`; returns how many.
    fn tear_across<P: Point>(
        &mut self,
        x: &[P],
        c: crate::Vec2<P::Scalar>,
        d: crate::Vec2<P::Scalar>,
    ) -> usize {
        let flat = |p: P| crate::Vec2::new(p.coord(0), p.coord(1));
        self.tear(x, |_, _, pa, pb| {
            crate::geometry::segment::crossing(flat(pa), flat(pb), c, d).is_some()
        })
    }

    /// Tears every spring that has passed its length `limit(family, row)` (0 or less: never).
    pub(crate) fn snap<P: Point>(
        &mut self,
        x: &[P],
        limit: impl Fn(usize, usize) -> P::Scalar,
    ) -> usize {
        let zero = P::Scalar::ZERO;
        if (0..FAMILIES.len()).all(|f| (0..V).all(|j| limit(f, j) <= zero)) {
            return 0;
        }
        self.tear(x, |f, j, pa, pb| {
            let limit = limit(f, j);
            limit > zero && past(pa, pb, limit)
        })
    }

    /// Tears every intact spring for which `cut(family, row, a, b)` holds; returns how many.
    fn tear<P: Point>(&mut self, x: &[P], cut: impl Fn(usize, usize, P, P) -> bool) -> usize {
        let mut torn = 0;
        let mut marks = self.0;
        Self::each(|f, i, j, a, b| {
            if marks[j][i] & (1 << f) == 0
                && let (Some(&pa), Some(&pb)) = (x.get(a), x.get(b))
                && cut(f, j, pa, pb)
            {
                marks[j][i] |= 1 << f;
                torn += 1;
            }
        });
        self.0 = marks;
        torn
    }

    /// `key` mixed with the grid's size, the classes' stiffness and every torn bit (10
    /// particles' 6 bits to a mix).
    pub(crate) fn fingerprint<S: Scalar>(
        &self,
        classes: [Material<S>; 3],
        key: u64,
        mix: impl Fn(u64, u64) -> u64,
    ) -> u64 {
        let size = ((U as u64) << 32) | ((V as u64) << 1) | u64::from(CLOSED);
        let key = classes
            .iter()
            .fold(mix(key, size), |key, m| mix(key, m.stiffness.bits()));
        self.0.as_flattened().chunks(10).fold(key, |key, chunk| {
            let bits = chunk.iter().fold(0u64, |acc, &b| (acc << 6) | u64::from(b));
            mix(key, bits)
        })
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

    /// A grid's runs list its intact springs in `for_each_spring`'s order with their rest
    /// lengths and materials: whole, and with springs torn here and there (a torn spring
    /// ends its run); a closed grid's runs are its springs one at a time.
    #[test]
    fn runs_are_the_intact_springs_in_order() {
        let materials = [1.0, 2.0, 3.0].map(|stiffness| Material {
            stiffness,
            damping: 0.5f64,
        });
        fn listed<T: Topology<f64>>(springs: &T) -> [std::vec::Vec<(usize, usize, f64, f64)>; 2] {
            let mut one = std::vec::Vec::new();
            springs.for_each_spring(|a, b, rest, m| one.push((a, b, rest, m.stiffness)));
            let mut runs = std::vec::Vec::new();
            springs.for_each_run(|a, b, count, rest, m| {
                assert!(count > 0);
                runs.extend((0..count).map(|k| (a + k, b + k, rest, m.stiffness)));
            });
            [one, runs]
        }
        let mut grid = GridSprings::<f64, 5, 4>::new(1.0, 1.5, [1.8, 1.9], materials);
        let [one, runs] = listed(&grid);
        assert_eq!(one.len(), GridSprings::<f64, 5, 4>::COUNT);
        assert_eq!(runs, one);
        // Tear the springs with a particle on the line x = 1.5 or y = 0.75 between them.
        let x: [Vec3<f64>; 20] =
            core::array::from_fn(|k| Vec3::new((k % 5) as f64, (k / 5) as f64 * 1.5, 0.0));
        let across = grid.tear_across(&x, Vec2::new(1.5, -1.0), Vec2::new(1.6, 9.0));
        let along = grid.tear_across(&x, Vec2::new(-1.0, 0.75), Vec2::new(0.5, 0.8));
        assert!(across > 0 && along > 0);
        let [one, runs] = listed(&grid);
        assert_eq!(one.len(), GridSprings::<f64, 5, 4>::COUNT - across - along);
        assert_eq!(runs, one);
        let closed: [[Vec3<f64>; 5]; 5] =
            core::array::from_fn(|j| core::array::from_fn(|i| Vec3::new(i as f64, j as f64, 0.0)));
        let torus = TorusSprings::<f64, 5, 5>::measured(&closed, materials).unwrap();
        let [one, runs] = listed(&torus);
        assert_eq!(runs, one);
    }

    /// A closed grid lists `6·U·V` springs, twelve at every particle, each pair once, with
    /// the rest lengths of its rows; two particles at one place are refused.
    #[test]
    fn a_closed_grid_wraps_every_family() {
        let m = Material {
            stiffness: 1.0f64,
            damping: 0.0,
        };
        let mut x: [[Vec3<f64>; 6]; 5] =
            core::array::from_fn(|j| core::array::from_fn(|i| Vec3::new(i as f64, j as f64, 0.0)));
        let springs = TorusSprings::<f64, 6, 5>::measured(&x, [m; 3]).unwrap();
        let (mut count, mut ends) = (0, [0; 30]);
        let mut pairs = std::vec::Vec::new();
        springs.for_each_spring(|a, b, rest, _| {
            count += 1;
            ends[a] += 1;
            ends[b] += 1;
            pairs.push((a.min(b), a.max(b), rest));
        });
        assert_eq!(count, TorusSprings::<f64, 6, 5>::COUNT);
        assert_eq!(count, 180);
        assert!(ends.iter().all(|&e| e == 12));
        pairs.sort_by_key(|p| (p.0, p.1));
        pairs.dedup_by(|p, q| (p.0, p.1) == (q.0, q.1));
        assert_eq!(pairs.len(), 180);
        // Row 4's structural spring along u, from (0, 4) to (1, 4): 1 m; its wrap back
        // along v to row 0: 4 m (the grid is flat here, not a torus).
        assert_eq!(springs.rest_length(0, 4), 1.0);
        assert_eq!(springs.rest_length(1, 4), 4.0);
        assert_eq!(springs.rest_length(9, 0), 0.0);
        x[1][1] = x[1][0];
        assert_eq!(
            TorusSprings::<f64, 6, 5>::measured(&x, [m; 3]),
            Err(crate::Error::ZeroRestLength { a: 6, b: 7 })
        );
    }
}
