//! A stable checksum of a simulation's state, for rollback netplay: compare it between
//! peers (or between a run and its replay) every frame to catch a desync the frame it
//! happens.

use crate::physics::integrator::Integrator;
use crate::physics::shape::Shape;
use crate::physics::spring::Topology;
use crate::{MassSpring, Point, Scalar};

/// A 64-bit checksum built from 32-bit words: FNV-1a over the words (each word xored in,
/// then the product with FNV's 64-bit prime), finished by SplitMix64's mixer. The same
/// words give the same value on every platform and in every build (no `Hash` trait, no
/// pointer width, no random seed), so peers can compare it over the network. Not a
/// cryptographic hash: it catches a desync, not an attacker.
///
/// Cost: a 64-bit multiply a word (on a Cortex-M0, about 40 instructions).
///
/// ```
/// use dunas::StateHash;
/// let mut a = StateHash::new();
/// a.add_u32(7);
/// a.add_scalar(1.5f32);
/// let mut b = StateHash::new();
/// b.add_u32(7);
/// b.add_scalar(1.5f32);
/// assert_eq!(a.finish(), b.finish());
/// b.add_u32(0);
/// assert_ne!(a.finish(), b.finish());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StateHash {
    state: u64,
}

impl Default for StateHash {
    fn default() -> Self {
        Self::new()
    }
}

impl StateHash {
    /// FNV-1a's 64-bit offset basis.
    const START: u64 = 0xcbf2_9ce4_8422_2325;
    /// FNV-1a's 64-bit prime.
    const PRIME: u64 = 0x0000_0100_0000_01b3;

    /// An empty checksum.
    pub const fn new() -> Self {
        StateHash { state: Self::START }
    }

    /// Adds a 32-bit word.
    #[inline]
    pub fn add_u32(&mut self, word: u32) {
        self.state = (self.state ^ u64::from(word)).wrapping_mul(Self::PRIME);
    }

    /// Adds a 64-bit value, its low word first.
    #[inline]
    pub fn add_u64(&mut self, value: u64) {
        self.add_u32(value as u32);
        self.add_u32((value >> 32) as u32);
    }

    /// Adds a scalar's bits ([`Scalar::bits`]: `0.0` and `-0.0` differ, as they may in
    /// what follows).
    #[inline]
    pub fn add_scalar<S: Scalar>(&mut self, x: S) {
        self.add_u64(x.bits());
    }

    /// Adds a point's coordinates, in order.
    #[inline]
    pub fn add_point<P: Point>(&mut self, p: P) {
        for axis in 0..P::DIM {
            self.add_scalar(p.coord(axis));
        }
    }

    /// What was added so far, unmixed (FNV-1a alone): enough to tell a change, and free of
    /// work when nothing was added.
    #[inline]
    pub(crate) fn unmixed(&self) -> u64 {
        self.state
    }

    /// The checksum of everything added so far (adding more afterwards goes on from it).
    pub fn finish(&self) -> u64 {
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
}

impl<P: Point, Sh: Shape, T: Topology<P::Scalar>, I: Integrator> MassSpring<P, Sh, T, I> {
    /// A checksum of everything that shapes the steps to come, for rollback netplay: the
    /// clock, every particle's position, velocity and inverse mass, every live spring's
    /// ends, rest length and material (a snapped or cut spring is gone from it), gravity,
    /// the drag, the integrator's memory ([`Integrator::hash_memory`]) and whether the
    /// last step left a held chain settled, and with [`Sleep`](crate::Sleep)
    /// on, its setting and state (off, it adds nothing). Not the settings' other fields, nor snap
    /// limits: a game sets those alike on every peer. See [`StateHash`] for the checksum.
    ///
    /// **Snapshots.** The system is `Clone` and holds no pointer and no heap: a clone is
    /// a snapshot, and assigning it back rolls the simulation back exactly (the test
    /// `rollback::a_replay_after_a_rollback_hashes_as_the_first_run`, in the style of
    /// GGRS's sync test). Its size is `size_of` the object: a `Rope<Vec2<f32>, 8>` takes
    /// 368 bytes (`Q16` the same), a `Rope<Vec3<f32>, 16>` 788, a `Cloth<Vec3<f32>, 8, 8>`
    /// 1 984 and with `DirectSprings` (its factor) 7 016 (`rollback::snapshots_are_*`).
    ///
    /// **Determinism.** The same state, inputs and calls give the same bits, so the same
    /// checksum: in `Q16` on every platform (integer arithmetic only); in CI the host, a
    /// `.wasm` under node and the Cortex-M0 (`Q16`) and M4F (`f32`) reproduce the
    /// scripted scene's golden checksums (`tests/golden.txt`); in `f32` and `f64` on every
    /// platform that rounds IEEE 754 operations alike, with the same build: ropes and cloth
    /// step with `+ − × ÷` and square roots, which IEEE 754 rounds exactly, so the `std`
    /// feature's math (the default on a hosted target) and `libm`'s (on a microcontroller)
    /// agree on them. What breaks it: functions past the square root taken from `std` on
    /// different platforms (`sin`, `atan2`, `exp` may differ in their last bit), the
    /// `micromath` feature (approximations), fused multiply-adds (`-C
    /// target-feature=+fma`, or a target whose compiler contracts `a·b + c`), a different
    /// feature set or crate version between peers, and calls in a different order.
    /// Cost: a 64-bit multiply a 32-bit word, `2·(2·DIM + 1)` words a particle and 8 a
    /// spring.
    ///
    /// ```
    /// use dunas::prelude::*;
    /// let settings = Settings { gravity: Vec2::new(0.0f32, -9.81), ..Settings::default() };
    /// let material = Material { stiffness: 400.0, damping: 0.5 };
    /// let mut rope: Rope<Vec2<f32>, 8> =
    ///     Rope::new(Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), 1.0, material, settings)?;
    /// let saved = rope.clone();
    /// let first: Vec<u64> = (0..8).map(|_| { rope.step(1.0 / 60.0).unwrap(); rope.state_hash() }).collect();
    /// rope = saved; // roll back
    /// let replay: Vec<u64> = (0..8).map(|_| { rope.step(1.0 / 60.0).unwrap(); rope.state_hash() }).collect();
    /// assert_eq!(first, replay);
    /// # Ok::<(), dunas::Error>(())
    /// ```
    pub fn state_hash(&self) -> u64 {
        let mut hash = StateHash::new();
        hash.add_scalar(self.time);
        let particles = Sh::flat(&self.state.pos)
            .iter()
            .zip(Sh::flat(&self.state.vel));
        for ((&x, &v), &w) in particles.zip(Sh::flat(&self.inv_mass)) {
            hash.add_point(x);
            hash.add_point(v);
            hash.add_scalar(w);
        }
        let mut live = 0u32;
        self.topology.for_each_spring(|a, b, rest, m| {
            hash.add_u32(a as u32);
            hash.add_u32(b as u32);
            for value in [rest, m.stiffness, m.damping] {
                hash.add_scalar(value);
            }
            live = live.wrapping_add(1);
        });
        hash.add_u32(live);
        hash.add_point(self.settings.gravity);
        hash.add_scalar(self.settings.damping);
        I::hash_memory(&self.memory, &mut hash);
        hash.add_u64(self.settled.map_or(0, |key| (1 << 32) | u64::from(key)));
        self.rest.hash(&mut hash);
        hash.finish()
    }
}
