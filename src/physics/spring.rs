//! Springs and the topologies that lay them out: chains, loops, hubs, grids, k-neighbourhood
//! "surface springs" and explicit connection lists.
//!
//! Every topology is checked when it is built: an index past the particle count, a spring
//! from a particle to itself, a repeated pair, a zero rest length or more springs than the
//! compile-time capacity is an [`Error`] then, never later in the game loop.

use crate::error::invalid;
use crate::error::{check_index, check_non_negative, check_positive};
use crate::{Error, Point, Scalar};

pub use super::grid_springs::{GridSprings, TorusSprings};

/// A spring between particles `a` and `b`, relaxed at length `rest`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spring<S> {
    /// First particle (flat index).
    pub a: u16,
    /// Second particle (flat index).
    pub b: u16,
    /// Rest length, in coordinate units.
    pub rest: S,
    /// The length past which the spring snaps (from its [`Snap`]); 0 for never.
    pub snap_at: S,
    /// `true` once the spring has snapped or been cut: it pulls no more, for good.
    pub broken: bool,
}

/// When a spring snaps: never, past a stretch ratio (`length / rest`, `> 1`), or past a
/// static tension (`stiffness · (length - rest)`, in force units, `> 0`). Both come down to
/// a length, checked once a step after the substeps: a snap costs no square root unless the
/// spring is within reach of it (a Manhattan-distance test first).
///
/// ```
/// use dunas::spring::Snap;
/// assert!(Snap::Stretch(1.5f32).check().is_ok());
/// assert!(Snap::Stretch(1.0f32).check().is_err()); // a ratio ≤ 1 would snap at rest
/// assert!(Snap::Tension(0.0f32).check().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum Snap<S> {
    /// The spring never snaps (the default).
    #[default]
    Never,
    /// Snaps once longer than `ratio · rest` (`ratio > 1`).
    Stretch(S),
    /// Snaps once its static tension `k · (length - rest)` passes this force (`> 0`).
    Tension(S),
}

impl<S: Scalar> Snap<S> {
    /// Checks the limit.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a stretch ratio that is not finite and above 1, or a
    /// tension that is not finite and positive.
    pub fn check(self) -> Result<Self, Error> {
        match self {
            Snap::Never => Ok(self),
            Snap::Stretch(ratio) if ratio > S::ONE && ratio.is_finite() => Ok(self),
            Snap::Tension(force) if force > S::ZERO && force.is_finite() => Ok(self),
            _ => Err(invalid(
                "snap",
                "a stretch ratio above 1 or a positive tension, finite",
            )),
        }
    }

    /// The length past which a spring of rest length `rest` and `material` snaps; 0 for
    /// never (and for a limit beyond the format's range).
    pub(crate) fn length(self, rest: S, material: Material<S>) -> S {
        let at = match self {
            Snap::Never => S::ZERO,
            Snap::Stretch(ratio) => rest * ratio,
            Snap::Tension(force) => rest + force / material.stiffness,
        };
        if at.is_finite() && at <= S::SAFE_RANGE {
            at
        } else {
            S::ZERO
        }
    }
}

/// Stiffness and damping shared by a group of springs. Written with named fields, so the
/// two numbers cannot be swapped unnoticed; checked when the springs enter a system
/// ([`MassSpring::new`](crate::MassSpring::new)) or a topology's setter.
///
/// ```
/// use dunas::Material;
/// let rope = Material { stiffness: 3000.0, damping: 1.0 };
/// assert!(rope.check().is_ok());
/// assert!(Material { stiffness: -1.0, damping: 1.0 }.check().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material<S> {
    /// Hooke constant `k`, force per unit of stretch (finite, `> 0`).
    pub stiffness: S,
    /// Damping `c` along the spring, force per unit of closing speed (finite, `>= 0`).
    pub damping: S,
}

impl<S: Scalar> Material<S> {
    /// Checks both numbers.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless the stiffness is positive and finite and the
    /// damping non-negative and finite.
    pub fn check(&self) -> Result<(), Error> {
        check_positive(self.stiffness, "stiffness")?;
        check_non_negative(self.damping, "damping")?;
        Ok(())
    }
}

/// Anything that lists springs to the physics: an explicit [`Springs`] list or the implied
/// springs of a [`GridSprings`] cloth.
pub trait Topology<S: Scalar> {
    /// Calls `f(a, b, rest, material)` once per spring, with `a`, `b` flat particle indices
    /// that were checked against the particle count when the topology was built.
    fn for_each_spring(&self, f: impl FnMut(usize, usize, S, Material<S>));
    /// Calls `f(a, b, count, rest, material)` for runs of springs in
    /// [`for_each_spring`](Self::for_each_spring)'s order: the springs from `a + k` to
    /// `b + k` for `k < count`, all of one rest length and material, so that a solver takes
    /// a run's numbers once and steps through its ends. By default every spring is a run
    /// of one; a grid's intact springs of a family come in runs of a row or more.
    fn for_each_run(&self, mut f: impl FnMut(usize, usize, usize, S, Material<S>)) {
        self.for_each_spring(|a, b, rest, material| f(a, b, 1, rest, material));
    }
    /// The number of springs.
    fn spring_count(&self) -> usize;
    /// Breaks every spring that has passed its [`Snap`] length at positions `x` (indexed as
    /// in [`for_each_spring`](Self::for_each_spring)); returns how many broke. Topologies
    /// that cannot break return 0.
    fn snap<P: Point<Scalar = S>>(&mut self, x: &[P]) -> usize {
        let _ = x;
        0
    }
    /// `key` with what the springs are mixed in by `mix`: every spring's ends and stiffness
    /// (torn springs as the topology marks them), so that equal springs give equal
    /// fingerprints. What a direct solver's factor depends on besides the masses. By default
    /// every spring's ends and stiffness are summed, each weighed by its place (a multiply or
    /// two each, none waiting on another), then mixed in once; a topology may mix less that
    /// says as much.
    fn fingerprint(&self, key: u64, mix: impl Fn(u64, u64) -> u64) -> u64 {
        let mut spread = Spread::default();
        self.for_each_spring(|a, b, _, m| {
            spread.add(((a as u64) << 32) | b as u64);
            spread.add(m.stiffness.bits());
        });
        mix(key, spread.sum())
    }
}

/// A sum of values each weighed by its place in the sequence, for a key: every value is
/// xored with its place and multiplied by an odd constant in two 32-bit lanes (a change of
/// one value always changes the sum), and no term waits on another, where a chain of mixes
/// waits on each one. Built for [`Topology::fingerprint`] and the direct solver's key.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Spread {
    lanes: (u32, u32),
    /// The place's weight: the golden ratio's 32 bits times the count of values so far.
    place: u32,
}

impl Spread {
    /// Adds `value` at the next place.
    #[inline]
    pub(crate) fn add(&mut self, value: u64) {
        let place = self.place;
        let (low, high) = (
            value as u32 ^ place,
            (value >> 32) as u32 ^ place.rotate_left(16),
        );
        self.lanes.0 = self.lanes.0.wrapping_add(low.wrapping_mul(0x85EB_CA77));
        self.lanes.1 = self.lanes.1.wrapping_add(high.wrapping_mul(0xC2B2_AE3D));
        self.place = place.wrapping_add(0x9E37_79B9);
    }

    /// The sum, with the count of values in it.
    pub(crate) fn sum(&self) -> u64 {
        ((u64::from(self.lanes.1 ^ self.place)) << 32) | u64::from(self.lanes.0)
    }
}

/// An explicit list of up to `CAP` springs of one material, stored inline. Springs snap
/// ([`Snap`], for the material or one spring) and are cut, but are never removed: a broken
/// spring keeps its slot and its index, and pulls no more.
///
/// Memory: `16 × CAP + 20` bytes in `f32`. Duplicate checks make building `O(CAP²)`, once.
#[derive(Clone, Debug)]
pub struct Springs<S, const CAP: usize> {
    list: heapless::Vec<Spring<S>, CAP, u16>,
    material: Material<S>,
    snap: Snap<S>,
}

impl<S: Scalar, const CAP: usize> Springs<S, CAP> {
    /// An empty list.
    pub fn new(material: Material<S>) -> Self {
        const { assert!(CAP <= u16::MAX as usize, "at most 65535 springs") };
        Springs {
            list: heapless::Vec::new(),
            material,
            snap: Snap::Never,
        }
    }

    /// The springs.
    pub fn as_slice(&self) -> &[Spring<S>] {
        &self.list
    }

    /// The shared material.
    pub fn material(&self) -> Material<S> {
        self.material
    }

    /// Changes the shared material (the springs' [`Snap`] lengths follow it).
    ///
    /// # Errors
    /// As [`Material::check`]; the old material stays.
    pub fn set_material(&mut self, material: Material<S>) -> Result<(), Error> {
        material.check()?;
        self.material = material;
        let snap = self.snap;
        for s in self.list.iter_mut() {
            s.snap_at = snap.length(s.rest, material);
        }
        Ok(())
    }

    /// The material's [`Snap`]: the limit of every spring, and of springs connected later.
    pub fn snap_limit(&self) -> Snap<S> {
        self.snap
    }

    /// Sets the material's [`Snap`] for every spring (overriding [`set_spring_snap`]) and
    /// for springs connected later.
    ///
    /// # Errors
    /// As [`Snap::check`]; nothing changes then.
    ///
    /// [`set_spring_snap`]: Self::set_spring_snap
    pub fn set_snap(&mut self, snap: Snap<S>) -> Result<(), Error> {
        self.snap = snap.check()?;
        for s in self.list.iter_mut() {
            s.snap_at = snap.length(s.rest, self.material);
        }
        Ok(())
    }

    /// Sets the [`Snap`] of spring `index` alone (a frayed strand, a weak link).
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`] for a missing spring; as [`Snap::check`]. Nothing changes
    /// on an error.
    pub fn set_spring_snap(&mut self, index: usize, snap: Snap<S>) -> Result<(), Error> {
        let snap = snap.check()?;
        let len = self.list.len();
        let material = self.material;
        let s = self
            .list
            .get_mut(index)
            .ok_or(Error::IndexOutOfRange { index, len })?;
        s.snap_at = snap.length(s.rest, material);
        Ok(())
    }

    /// Breaks every spring from a particle at or below `i` to one above it: what a cut
    /// between particles `i` and `i + 1` of a chain severs (the chain's spring and any hub
    /// or bending spring across it). Returns how many broke.
    pub fn cut_across(&mut self, i: usize) -> usize {
        let mut cut = 0;
        for s in self.list.iter_mut() {
            let (lo, hi) = (usize::from(s.a.min(s.b)), usize::from(s.a.max(s.b)));
            if !s.broken && lo <= i && i < hi {
                s.broken = true;
                cut += 1;
            }
        }
        cut
    }

    /// Whether any spring has snapped or been cut (one pass over the flags).
    pub(crate) fn any_broken(&self) -> bool {
        self.list.iter().any(|s| s.broken)
    }

    /// Live springs between neighbours along the chain (`i` to `i + 1`): a row of `N`
    /// particles is in `N - chain_links()` pieces (no pair has two springs).
    pub(crate) fn chain_links(&self) -> usize {
        let link = |s: &Spring<S>| !s.broken && s.a.abs_diff(s.b) == 1;
        self.list.iter().filter(|s| link(s)).count()
    }

    /// Whether a live (unbroken) spring joins `a` and `b`.
    pub fn joins(&self, a: usize, b: usize) -> bool {
        self.list.iter().any(|s| {
            let (sa, sb) = (usize::from(s.a), usize::from(s.b));
            !s.broken && ((sa, sb) == (a, b) || (sa, sb) == (b, a))
        })
    }

    /// Multiplies every rest length by `factor` (used to calibrate a rope's drawn length).
    ///
    /// # Errors
    /// [`Error::ZeroRestLength`] for the first spring whose new rest length would not be a
    /// valid one (see [`check_rest`]); nothing changes then.
    pub(crate) fn scale_rest(&mut self, factor: S) -> Result<(), Error> {
        for s in self.list.iter() {
            check_rest(s.a as usize, s.b as usize, s.rest * factor)?;
        }
        for s in self.list.iter_mut() {
            s.rest = s.rest * factor;
        }
        Ok(())
    }

    /// Connects `a` and `b` with the given rest length; `len` is the particle count.
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`], [`Error::DuplicateSpring`] (also for `a == b`),
    /// [`Error::ZeroRestLength`] (rest not positive and finite) or [`Error::CapacityExceeded`].
    pub fn connect_with_rest(
        &mut self,
        len: usize,
        a: usize,
        b: usize,
        rest: S,
    ) -> Result<(), Error> {
        for index in [a, b] {
            // Indices are stored as u16: one past that is out of range whatever `len` says.
            if index > u16::MAX as usize {
                return Err(Error::IndexOutOfRange { index, len });
            }
            check_index(index, len)?;
        }
        let (lo, hi) = if a < b {
            (a as u16, b as u16)
        } else {
            (b as u16, a as u16)
        };
        if a == b
            || self
                .list
                .iter()
                .any(|s| s.a.min(s.b) == lo && s.a.max(s.b) == hi)
        {
            return Err(Error::DuplicateSpring { a, b });
        }
        check_rest(a, b, rest)?;
        self.list
            .push(Spring {
                a: a as u16,
                b: b as u16,
                rest,
                snap_at: self.snap.length(rest, self.material),
                broken: false,
            })
            .map_err(|_| Error::CapacityExceeded { capacity: CAP })
    }

    /// Connects `a` and `b` at their current distance in `positions`.
    ///
    /// # Errors
    /// As [`connect_with_rest`](Self::connect_with_rest).
    pub fn connect<P: Point<Scalar = S>>(
        &mut self,
        positions: &[P],
        a: usize,
        b: usize,
    ) -> Result<(), Error> {
        let rest = match (positions.get(a), positions.get(b)) {
            (Some(pa), Some(pb)) => pa.distance(*pb),
            _ => S::ZERO,
        };
        self.connect_with_rest(positions.len(), a, b, rest)
    }

    /// Springs for every listed pair, at the current distances.
    ///
    /// # Errors
    /// As [`connect_with_rest`](Self::connect_with_rest), for the first bad pair.
    pub fn from_pairs<P: Point<Scalar = S>>(
        positions: &[P],
        pairs: &[(usize, usize)],
        material: Material<S>,
    ) -> Result<Self, Error> {
        let mut s = Springs::new(material);
        for &(a, b) in pairs {
            s.connect(positions, a, b)?;
        }
        Ok(s)
    }

    /// An open chain: `i` to `i + 1` (`N - 1` springs). A rope.
    ///
    /// # Errors
    /// As [`connect_with_rest`](Self::connect_with_rest).
    pub fn chain<P: Point<Scalar = S>>(
        positions: &[P],
        material: Material<S>,
    ) -> Result<Self, Error> {
        Self::surface_line(positions, 1, material)
    }

    /// A closed loop: the chain plus the last particle to the first (`N` springs).
    ///
    /// # Errors
    /// As [`connect_with_rest`](Self::connect_with_rest).
    pub fn closed_loop<P: Point<Scalar = S>>(
        positions: &[P],
        material: Material<S>,
    ) -> Result<Self, Error> {
        let mut s = Self::chain(positions, material)?;
        s.connect(positions, positions.len().saturating_sub(1), 0)?;
        Ok(s)
    }

    /// A hub: the chain plus every particle from the third on tied to the first
    /// (`2N - 3` springs), the thesis's Merlin rope. The hub keeps the rope from stretching
    /// away from its holder whatever the chain does.
    ///
    /// # Errors
    /// As [`connect_with_rest`](Self::connect_with_rest).
    pub fn hub<P: Point<Scalar = S>>(
        positions: &[P],
        material: Material<S>,
    ) -> Result<Self, Error> {
        let mut s = Self::chain(positions, material)?;
        for i in 2..positions.len() {
            s.connect(positions, 0, i)?;
        }
        Ok(s)
    }

    /// "Surface springs" along a row: every pair at most `k` apart in index (the thesis's
    /// rigidity factor; `k = 1` is the chain, `k = 2` adds bending springs). A `k` past the
    /// row's length is clamped to `len - 1` (every pair).
    ///
    /// # Errors
    /// As [`connect_with_rest`](Self::connect_with_rest); [`Error::InvalidParameter`] for `k = 0`.
    pub fn surface_line<P: Point<Scalar = S>>(
        positions: &[P],
        k: usize,
        material: Material<S>,
    ) -> Result<Self, Error> {
        if k == 0 {
            return Err(invalid("neighbourhood", "at least 1"));
        }
        let mut s = Springs::new(material);
        for d in 1..=k.min(positions.len().saturating_sub(1)) {
            for i in 0..positions.len() - d {
                s.connect(positions, i, i + d)?;
            }
        }
        Ok(s)
    }

    /// "Surface springs" on a `u × v` grid (flat index `j * u + i`): every pair whose
    /// shortest path along grid edges has at most `k` edges. `k = 1` gives the structural
    /// springs, `k = 2` adds shear (diagonal) and bending (two apart) springs. A `k` past
    /// the grid's longest such path, `(u - 1) + (v - 1)`, is clamped to it (every pair).
    ///
    /// # Errors
    /// As [`connect_with_rest`](Self::connect_with_rest); [`Error::InvalidParameter`] for
    /// `k = 0`, an empty grid, or `u * v != positions.len()`.
    pub fn surface_grid<P: Point<Scalar = S>>(
        positions: &[P],
        u: usize,
        v: usize,
        k: usize,
        material: Material<S>,
    ) -> Result<Self, Error> {
        if k == 0 || u == 0 || v == 0 || u.checked_mul(v) != Some(positions.len()) {
            return Err(invalid(
                "grid size",
                "non-zero, with u · v equal to the particle count",
            ));
        }
        let k = k.min((u - 1) + (v - 1));
        let mut s = Springs::new(material);
        for j in 0..v {
            for i in 0..u {
                for dj in 0..=k.min(v - 1 - j) {
                    let reach = k - dj;
                    // Forward neighbours only, so every pair is added once.
                    let i_lo = if dj == 0 {
                        i + 1
                    } else {
                        i.saturating_sub(reach)
                    };
                    let i_hi = (i + reach).min(u - 1);
                    for ni in i_lo..=i_hi {
                        s.connect(positions, j * u + i, (j + dj) * u + ni)?;
                    }
                }
            }
        }
        Ok(s)
    }
}

/// Checks a rest length: positive, finite and more than the format's resolution.
///
/// # Errors
/// [`Error::ZeroRestLength`] naming the spring `a`-`b`.
pub(crate) fn check_rest<S: Scalar>(a: usize, b: usize, rest: S) -> Result<(), Error> {
    if rest > S::EPSILON && rest.is_finite() && rest <= S::SAFE_RANGE {
        Ok(())
    } else {
        Err(Error::ZeroRestLength { a, b })
    }
}

impl<S: Scalar, const CAP: usize> Topology<S> for Springs<S, CAP> {
    #[inline]
    fn for_each_spring(&self, mut f: impl FnMut(usize, usize, S, Material<S>)) {
        for s in self.list.iter().filter(|s| !s.broken) {
            f(s.a as usize, s.b as usize, s.rest, self.material);
        }
    }
    fn spring_count(&self) -> usize {
        self.list.len()
    }
    /// The material's stiffness and every live spring's ends (one material for all).
    fn fingerprint(&self, key: u64, mix: impl Fn(u64, u64) -> u64) -> u64 {
        let mut spread = Spread::default();
        for s in self.list.iter().filter(|s| !s.broken) {
            spread.add((u64::from(s.a) << 16) | u64::from(s.b));
        }
        mix(mix(key, self.material.stiffness.bits()), spread.sum())
    }
    fn snap<P: Point<Scalar = S>>(&mut self, x: &[P]) -> usize {
        let mut snapped = 0;
        for s in self.list.iter_mut() {
            if s.broken || s.snap_at <= S::ZERO {
                continue;
            }
            let (Some(&pa), Some(&pb)) = (x.get(usize::from(s.a)), x.get(usize::from(s.b))) else {
                continue;
            };
            if past(pa, pb, s.snap_at) {
                s.broken = true;
                snapped += 1;
            }
        }
        snapped
    }
}

/// Whether `a` and `b` are farther apart than `limit`: the Manhattan distance (never less
/// than the true one) rules most springs out with no square root.
#[inline]
pub(crate) fn past<P: Point>(a: P, b: P, limit: P::Scalar) -> bool {
    let d = b - a;
    let mut manhattan = P::Scalar::ZERO;
    for axis in 0..P::DIM {
        manhattan += d.coord(axis).abs();
    }
    manhattan > limit && d.length() > limit
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::Vec2;

    fn row(n: usize) -> std::vec::Vec<Vec2<f32>> {
        (0..n).map(|i| Vec2::new(i as f32, 0.0)).collect()
    }

    fn mat() -> Material<f32> {
        Material {
            stiffness: 10.0,
            damping: 0.1,
        }
    }

    #[test]
    fn topologies_have_the_expected_counts() {
        let p = row(8);
        assert_eq!(
            Springs::<f32, 7>::chain(&p, mat()).unwrap().spring_count(),
            7
        );
        assert_eq!(
            Springs::<f32, 8>::closed_loop(&p, mat())
                .unwrap()
                .spring_count(),
            8
        );
        assert_eq!(
            Springs::<f32, 13>::hub(&p, mat()).unwrap().spring_count(),
            13
        );
        assert_eq!(
            Springs::<f32, 13>::surface_line(&p, 2, mat())
                .unwrap()
                .spring_count(),
            13
        );
        let grid: std::vec::Vec<_> = (0..64)
            .map(|k| Vec2::new((k % 8) as f32, (k / 8) as f32))
            .collect();
        let s = Springs::<f32, 400>::surface_grid(&grid, 8, 8, 2, mat()).unwrap();
        assert_eq!(s.spring_count(), GridSprings::<f32, 8, 8>::COUNT);
        assert_eq!(GridSprings::<f32, 8, 8>::COUNT, 306);
        assert_eq!(GridSprings::<f32, 20, 20>::COUNT, 2202);
        let s1 = Springs::<f32, 400>::surface_grid(&grid, 8, 8, 1, mat()).unwrap();
        assert_eq!(s1.spring_count(), 112);
    }

    #[test]
    fn implied_grid_springs_match_surface_springs() {
        let grid: std::vec::Vec<_> = (0..20)
            .map(|k| Vec2::new((k % 5) as f32, (k / 5) as f32))
            .collect();
        let explicit = Springs::<f32, 100>::surface_grid(&grid, 5, 4, 2, mat()).unwrap();
        let implied = GridSprings::<f32, 5, 4>::new(1.0, 1.0, [2f32.sqrt(); 2], [mat(); 3]);
        let mut pairs = std::vec::Vec::new();
        implied.for_each_spring(|a, b, rest, _| pairs.push((a.min(b), a.max(b), rest)));
        assert_eq!(pairs.len(), explicit.spring_count());
        for s in explicit.as_slice() {
            let (a, b) = (s.a.min(s.b) as usize, s.a.max(s.b) as usize);
            let found = pairs
                .iter()
                .find(|p| p.0 == a && p.1 == b)
                .expect("same pairs");
            assert!((found.2 - s.rest).abs() < 1e-6);
        }
    }

    #[test]
    fn construction_errors() {
        let p = row(4);
        let mut s = Springs::<f32, 3>::new(mat());
        assert_eq!(
            s.connect(&p, 0, 4),
            Err(Error::IndexOutOfRange { index: 4, len: 4 })
        );
        assert_eq!(
            s.connect(&p, 2, 2),
            Err(Error::DuplicateSpring { a: 2, b: 2 })
        );
        s.connect(&p, 0, 1).unwrap();
        assert_eq!(
            s.connect(&p, 1, 0),
            Err(Error::DuplicateSpring { a: 1, b: 0 })
        );
        let same = [Vec2::new(1.0f32, 1.0), Vec2::new(1.0, 1.0)];
        let mut fresh = Springs::<f32, 3>::new(mat());
        assert_eq!(
            fresh.connect(&same, 0, 1),
            Err(Error::ZeroRestLength { a: 0, b: 1 })
        );
        assert_eq!(
            fresh.connect_with_rest(2, 0, 1, f32::NAN),
            Err(Error::ZeroRestLength { a: 0, b: 1 })
        );
        s.connect(&p, 1, 2).unwrap();
        s.connect(&p, 2, 3).unwrap();
        assert_eq!(
            s.connect(&p, 0, 3),
            Err(Error::CapacityExceeded { capacity: 3 })
        );
        assert_eq!(
            Springs::<f32, 2>::chain(&p, mat()).err(),
            Some(Error::CapacityExceeded { capacity: 2 })
        );
        for (stiffness, damping) in [
            (0.0f32, 1.0),
            (1.0, -1.0),
            (f32::NAN, 1.0),
            (1.0, f32::INFINITY),
        ] {
            let m = Material { stiffness, damping };
            assert!(matches!(m.check(), Err(Error::InvalidParameter { .. })));
            assert!(matches!(
                s.clone().set_material(m),
                Err(Error::InvalidParameter { .. })
            ));
        }
    }

    #[test]
    fn a_reach_past_the_shape_is_clamped() {
        // Every pair, whatever the reach: 4 particles in a row have 6 pairs, a 3×2 grid 15.
        let p = row(4);
        let all = Springs::<f32, 6>::surface_line(&p, 3, mat()).unwrap();
        let huge = Springs::<f32, 6>::surface_line(&p, usize::MAX, mat()).unwrap();
        assert_eq!(huge.as_slice(), all.as_slice());
        assert_eq!(huge.spring_count(), 6);
        let grid: std::vec::Vec<_> = (0..6)
            .map(|k| Vec2::new((k % 3) as f32, (k / 3) as f32))
            .collect();
        let all = Springs::<f32, 15>::surface_grid(&grid, 3, 2, 3, mat()).unwrap();
        let huge = Springs::<f32, 15>::surface_grid(&grid, 3, 2, usize::MAX, mat()).unwrap();
        assert_eq!(huge.as_slice(), all.as_slice());
        assert_eq!(huge.spring_count(), 15);
        assert!(matches!(
            Springs::<f32, 15>::surface_grid(&grid[..0], 0, 2, 1, mat()).err(),
            Some(Error::InvalidParameter { .. })
        ));
    }

    /// A spread sum changes with any one value, with a value moved to another place, and
    /// with a value left off the end.
    #[test]
    fn a_spread_sum_follows_every_value_and_its_place() {
        let values: [u64; 40] = core::array::from_fn(|i| (i as u64 * 7_919) ^ (i as u64) << 40);
        let sum = |v: &[u64]| {
            let mut spread = Spread::default();
            v.iter().for_each(|&x| spread.add(x));
            spread.sum()
        };
        let base = sum(&values);
        assert_ne!(sum(&values[..39]), base);
        for i in 0..40 {
            for bit in [0, 17, 31, 32, 50, 63] {
                let mut changed = values;
                changed[i] ^= 1 << bit;
                assert_ne!(sum(&changed), base, "{i} {bit}");
            }
        }
        let mut swapped = values;
        swapped.swap(3, 4);
        assert_ne!(sum(&swapped), base);
    }
}
