//! A weight let go of: what [`MassSpring::release`](crate::MassSpring::release) hands back,
//! flying on its own under gravity.

use crate::{Point, Scalar};

/// A point mass in free flight: a penguin flung from the catapult, a candy cut loose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Body<P: Point> {
    /// Where it is (coordinate units).
    pub position: P,
    /// How fast it goes (units per second).
    pub velocity: P,
    /// Its mass (the rope's mass units).
    pub mass: P::Scalar,
}

impl<P: Point> Body<P> {
    /// Its linear momentum, `mass · velocity`.
    pub fn momentum(&self) -> P {
        self.velocity * self.mass
    }

    /// Advances `dt` seconds of ballistic flight under `gravity`, exactly (the parabola
    /// `p + v·dt + g·dt²/2`, however long `dt` is): no drag, no error but rounding.
    ///
    /// ```
    /// use dunas::{Vec2, body::Body};
    /// let mut stone = Body { position: Vec2::new(0.0f64, 0.0), velocity: Vec2::new(3.0, 4.0), mass: 1.0 };
    /// stone.fly(0.8, Vec2::new(0.0, -10.0)); // up and back down in 0.8 s
    /// assert!((stone.position.x - 2.4).abs() < 1e-12 && stone.position.y.abs() < 1e-12);
    /// ```
    pub fn fly(&mut self, dt: P::Scalar, gravity: P) {
        let half = P::Scalar::ratio(1, 2);
        self.position += self.velocity * dt + gravity * (dt * dt * half);
        self.velocity += gravity * dt;
    }
}
