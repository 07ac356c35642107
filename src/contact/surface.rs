//! Contacts on a cloth's or a torus's drawn surface: each cell's deepest point in every
//! collider, pushed out through the particles' weights in it.

use super::drawn::{SurfacePoint, deepest_in_cell, point_inv_mass, spread};
use super::itself::SELF_ROUNDS;
use super::{Contacts, Timing, Touch};
use crate::curves::smooth::Smoothing;
use crate::{Point, Scalar};

impl<P: Point> Contacts<'_, P> {
    /// Pushes the drawn surface of a grid of particles (row `j` is `pos[j]`) out of every
    /// collider (see the module docs), particle contacts when [`Touch::Particles`]; then, when
    /// self-contact is on, the surface off itself (with [`Touch::Particles`], the flat
    /// triangles between the particles), in rounds as a rope's curve.
    pub(crate) fn resolve_surface<const U: usize, const V: usize>(
        &self,
        pos: &mut [[P; U]; V],
        vel: &mut [[P; U]; V],
        inv_mass: &[[P::Scalar; U]; V],
        timing: Timing<'_, P>,
        closed: bool,
    ) {
        // The points whose boxes hold the cells: the particles, or a natural spline's
        // control net (it passes through the particles but bulges past them).
        let mut controls = (self.touch == Touch::Drawn(Smoothing::NaturalSpline)).then(|| {
            let mut net = *pos;
            crate::curves::surface::natural_net(&mut net, closed, closed);
            net
        });
        let (pos, vel, inv_mass) = (
            pos.as_flattened_mut(),
            vel.as_flattened_mut(),
            inv_mass.as_flattened(),
        );
        let (smoothing, on_surface) = match self.touch {
            Touch::Drawn(smoothing) => (smoothing, true),
            _ => (Smoothing::Polyline, false),
        };
        let drawn = (
            smoothing,
            match smoothing {
                Smoothing::CatmullRom => P::Scalar::ratio(25, 16),
                _ => P::Scalar::ONE,
            },
        );
        self.rounds(SELF_ROUNDS, || {
            if on_surface {
                self.surface_colliders::<U, V>(
                    (&mut *pos, &mut *vel, inv_mass),
                    timing,
                    (drawn, closed),
                    &mut controls,
                );
            } else {
                self.resolve_particles(pos, vel, inv_mass, timing);
            }
            // Self-contact walks an open grid's cells: a closed one has none.
            (!closed).then(|| {
                let parts = (&mut *pos, &mut *vel, inv_mass);
                self.resolve_self_surface::<U, V>(parts, timing, drawn.0, &mut controls)
            })
        });
    }

    /// Pushes the surface `drawn` (its smoothing and its cells' overshoot) through the
    /// particles `pos` of a `U × V` grid (`closed`: its rows and columns close on themselves,
    /// a torus) out of every collider; `controls`: a natural spline's control net, kept up
    /// to date.
    fn surface_colliders<const U: usize, const V: usize>(
        &self,
        (pos, vel, inv_mass): (&mut [P], &mut [P], &[P::Scalar]),
        timing: Timing<'_, P>,
        ((smoothing, overshoot), closed): ((Smoothing, P::Scalar), bool),
        controls: &mut Option<[[P; U]; V]>,
    ) {
        let mut surface = SurfacePoint::<P::Scalar, U, V>::new(smoothing, closed);
        let columns = if closed { U } else { U - 1 };
        let rows = if closed { V } else { V - 1 };
        for (k, collider) in self.colliders.iter().enumerate() {
            let shift = self.offset(k, collider, timing.lag);
            let reach = collider.bounds().moved(-shift).grown(self.thickness);
            for cell in 0..columns * rows {
                let (cu, cv) = (cell % columns, cell / columns);
                let points = controls.as_ref().map_or(&*pos, |c| c.as_flattened());
                let Some(hull) = surface.cell_bounds(points, (cu, cv), overshoot) else {
                    continue;
                };
                if !hull.overlaps(&reach) {
                    continue;
                }
                let Some(scale) = self.near(collider, hull, shift) else {
                    continue;
                };
                let Some((u, v)) = deepest_in_cell(
                    |u, v| {
                        surface.at((cu, cv), (u, v));
                        let x = surface.point(pos) + shift;
                        (x, collider.search_key(x, scale))
                    },
                    |x, spacing| collider.gap(x) < self.thickness + spacing,
                ) else {
                    continue;
                };
                surface.at((cu, cv), (u, v));
                let Some(touch) = self.touching(collider, surface.point(pos) + shift) else {
                    continue;
                };
                let w = (0..U * V).map(|i| (i, surface.wu[i % U] * surface.wv[i / U]));
                let Some(mobility) = point_inv_mass(inv_mass, w.clone()) else {
                    continue;
                };
                let body = self.body(k, collider);
                let v = surface.point(vel);
                let braking = || timing.braking(w.clone(), body.0);
                let (dx, dv, moved) = self.response(collider, body, (touch, v, mobility), braking);
                if let Some(given) = spread(pos, vel, inv_mass, w, (dx, dv)) {
                    self.report(k, given, moved);
                    if let Some(net) = controls {
                        let grid = pos.as_chunks::<U>().0;
                        *net = core::array::from_fn(|j| grid[j]);
                        crate::curves::surface::natural_net(net, closed, closed);
                    }
                }
            }
        }
    }
}
