//! Rounds of contacts after a direct solver's solve: a solve's step is a whole frame, and
//! its contacts' pushes are as large, so a push on one span moves particles that a span
//! pushed out before is drawn through.

use super::{Model, State, TOLERANCE};
use crate::physics::shape::Shape;
use crate::physics::spring::Topology;
use crate::{Point, Scalar};

/// Most rounds of contacts after a direct solver's solve, each with no time passing
/// ([`DirectChain`](super::DirectChain)'s with a hold of its links after each).
pub(super) const CONTACT_ROUNDS: u8 = 8;

/// A solve's contacts (`touch` at `times`: its length and the time left in the frame), then,
/// if they moved a particle, rounds of them with no time passing (`h` 0: no collider moves,
/// friction takes back no sliding) while the last round moved a particle by more than 0.1%
/// of `model`'s shortest spring ([`TOLERANCE`]) along an axis, up to [`CONTACT_ROUNDS`]: a
/// push on one part of the drawn curve or surface moves particles that parts already
/// pushed out are drawn through, and a long solve's pushes are large enough to pull those
/// back in. Contacts that push against each other (a rope pinched between two colliders)
/// stop the rounds once two rounds in a row moved a particle no less than the round before
/// each. Returns whether the last round moved no particle further than that (the contacts
/// agree). Costs a copy of the positions and a pass over them a round, in a step that
/// resolves contacts ([`Model::touching`]; nothing else in a plain step).
pub(super) fn contact_rounds<P: Point, Sh: Shape, T: Topology<P::Scalar>>(
    model: &Model<'_, P, Sh, T>,
    state: &mut State<P, Sh>,
    (h, lag): (P::Scalar, P::Scalar),
    touch: &mut impl FnMut(&mut State<P, Sh>, (P::Scalar, P::Scalar)),
) -> bool {
    if !model.touching {
        touch(state, (h, lag));
        return true;
    }
    let before = state.pos;
    touch(state, (h, lag));
    if Sh::flat(&state.pos) == Sh::flat(&before) {
        return true;
    }
    // The most a particle moved along an axis from `before` to now.
    let most = |now: &Sh::PerParticle<P>, before: &Sh::PerParticle<P>| {
        let pairs = Sh::flat(now).iter().zip(Sh::flat(before));
        pairs.into_iter().fold(P::Scalar::ZERO, |most, (x, b)| {
            (0..P::DIM).fold(most, |most, d| most.max((x.coord(d) - b.coord(d)).abs()))
        })
    };
    let (n, d) = TOLERANCE;
    let close = model.shortest_rest().unwrap_or(P::Scalar::ZERO) * P::Scalar::ratio(n, d);
    let (mut moved, mut stalled) = (most(&state.pos, &before), false);
    for _ in 0..CONTACT_ROUNDS {
        if moved <= close {
            return true;
        }
        let before = state.pos;
        touch(state, (P::Scalar::ZERO, lag));
        let again = most(&state.pos, &before);
        if again >= moved && stalled {
            return false;
        }
        (moved, stalled) = (again, again >= moved);
    }
    moved <= close
}
