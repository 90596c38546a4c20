//! A throw by hand (docs/explorer.md, "A throw by hand"): a drag on the die, or its keys, in
//! throw mode. Where on the die the drag starts and how far and which way it goes give the
//! start's velocity and spin, written into the setup so the throw is saved and replayed like
//! any other start.
//!
//! The drag is an impulse `J = M·v` given at the grab point. The die leaves across the table
//! as the hand moved: the drag laid on the table ([`OrbitCamera::table_step`]: across stays
//! across, up the screen goes away from the viewer), covered in τ = [`THROW_TIME_S`], is the
//! velocity `v = d / τ`, level. The spin is the one that impulse gives at the grab point,
//! `ω = r × J / I = M·(r × v) / I`, `r` from the centre of the die to the grab point on the
//! view plane and `I` the body's one moment of inertia
//! ([`dicesim_physics::Params::inertia`]). A drag through the centre throws without spin;
//! one started above or below the centre gives top- or backspin, one beside it a twist.

use super::camera::OrbitCamera;
use crate::tui::vocabulary::format::fmt_num;
use crate::tui::vocabulary::solid::Flat;
use dicesim_physics::initial::limits::{ANGULAR_VELOCITY, VELOCITY};
use dicesim_physics::{InitialCondition, Params};
use nalgebra::Vector3;

/// s: a throw is as fast as covering its drag in this time. A column is about 0.2 cm of the
/// view at 80×24, so a hundredth of a second makes a drag of 5 to 15 columns a throw of 1
/// to 3 m/s, a hand's throw across a table.
pub(crate) const THROW_TIME_S: f64 = 0.01;

/// Cells one coarse (Shift) aiming key moves.
pub(crate) const COARSE_CELLS: f64 = 4.0;

/// A throw being aimed: where the die is grabbed and where the drag has got to.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Throw {
    /// cm on the view plane (across, up), from the die's centre to the grab point.
    pub(crate) grab: Flat,
    /// cm on the view plane, from the grab point to the drag's end.
    pub(crate) drag: Flat,
    /// The cell a mouse drag was pressed in, until it is released.
    pub(crate) pressed: Option<(u16, u16)>,
    /// Begun by a drag with Ctrl or Alt held outside throw mode: it ends with the drag.
    pub(crate) passing: bool,
}

/// What a throw gives the start: cm/s and rad/s, world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Thrown {
    pub(crate) velocity: Vector3<f64>,
    pub(crate) spin: Vector3<f64>,
}

impl Thrown {
    /// The velocity and spin in words, as the parameter list rounds them.
    pub(crate) fn words(&self) -> String {
        let (v, w) = self.rounded();
        format!("v {v} cm/s · ω {w} rad/s")
    }

    /// [`Thrown::words`] shorter, for a narrower footer: the vectors, then their sizes
    /// alone, always with their units.
    pub(crate) fn short_words(&self) -> [String; 2] {
        let (v, w) = self.rounded();
        [
            format!("v {v} cm/s ω {w} rad/s"),
            format!(
                "v {} cm/s ω {} rad/s",
                fmt_num((self.velocity.norm() * 10.0).round() / 10.0),
                fmt_num((self.spin.norm() * 100.0).round() / 100.0)
            ),
        ]
    }

    /// The velocity and spin as the parameter list rounds them, each `(x, y, z)`.
    fn rounded(&self) -> (String, String) {
        let v = |x: Vector3<f64>, per: f64| {
            let c = x.map(|c| (c * per).round() / per + 0.0);
            format!("({}, {}, {})", fmt_num(c.x), fmt_num(c.y), fmt_num(c.z))
        };
        (v(self.velocity, 10.0), v(self.spin, 100.0))
    }
}

impl Throw {
    /// The drag's end moved by `cells` (across, down) cells of `cell` cm (across, up) each.
    pub(crate) fn aim(&mut self, cell: (f64, f64), cells: (f64, f64)) {
        self.drag = (self.drag.0 + cells.0 * cell.0, self.drag.1 - cells.1 * cell.1);
    }

    /// The grab point moved by `cells` (across, down) cells of `cell` cm each.
    pub(crate) fn move_grab(&mut self, cell: (f64, f64), cells: (f64, f64)) {
        self.grab = (self.grab.0 + cells.0 * cell.0, self.grab.1 - cells.1 * cell.1);
    }

    /// The velocity and spin this throw gives the die of `params` seen by `camera`.
    pub(crate) fn thrown(&self, camera: &OrbitCamera, params: &Params) -> Thrown {
        let velocity = camera.table_step(self.drag) / THROW_TIME_S;
        let r = camera.world_step(self.grab);
        let spin = params.total_mass() * r.cross(&velocity) / params.inertia();
        Thrown { velocity, spin }
    }

    /// `initial` thrown: its velocity and spin this throw's, to 0.1 cm/s and 0.01 rad/s (so
    /// the parameter list and a saved preset read them plainly) and inside their ranges;
    /// the height and orientation stay.
    pub(crate) fn start(
        &self,
        camera: &OrbitCamera,
        params: &Params,
        initial: &InitialCondition,
    ) -> InitialCondition {
        let t = self.thrown(camera, params);
        // `+ 0.0`: a component rounded to zero reads 0, not -0.
        let round = |v: f64, per: f64, most: f64| ((v * per).round() / per).clamp(-most, most) + 0.0;
        InitialCondition {
            velocity: t.velocity.map(|v| round(v, 10.0, VELOCITY.max)).into(),
            angular_velocity: t.spin.map(|w| round(w, 100.0, ANGULAR_VELOCITY.max)).into(),
            angular_momentum: None,
            ..*initial
        }
    }
}
