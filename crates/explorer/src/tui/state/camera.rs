//! The die screen's camera: orthographic, orbiting the die and zooming, the way the user
//! turned it; where it puts a point of the world on the view plane.

use nalgebra::Vector3;

/// An orthographic camera circling the die: yaw about the vertical, pitch looking down.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct OrbitCamera {
    /// °, turn about the vertical axis.
    pub(crate) yaw_deg: f64,
    /// °, elevation: 0 looks level, 90 straight down.
    pub(crate) pitch_deg: f64,
    /// Zoom steps; each makes the view 1.25 times closer.
    pub(crate) zoom: i32,
}

impl Default for OrbitCamera {
    fn default() -> Self {
        OrbitCamera {
            yaw_deg: 30.0,
            pitch_deg: 25.0,
            zoom: 0,
        }
    }
}

/// A point on the screen plane, cm, with its distance from the viewer (larger is farther).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Projected {
    pub(crate) x: f64,
    pub(crate) y: f64,
    pub(crate) depth: f64,
}

impl OrbitCamera {
    pub(crate) const MIN_PITCH: f64 = -10.0;
    pub(crate) const MAX_PITCH: f64 = 89.0;
    pub(crate) const MIN_ZOOM: i32 = -8;
    pub(crate) const MAX_ZOOM: i32 = 8;

    pub(crate) fn orbit(&mut self, d_yaw: f64, d_pitch: f64) {
        self.yaw_deg = (self.yaw_deg + d_yaw).rem_euclid(360.0);
        self.pitch_deg = (self.pitch_deg + d_pitch).clamp(Self::MIN_PITCH, Self::MAX_PITCH);
    }

    pub(crate) fn zoom_by(&mut self, steps: i32) {
        self.zoom = (self.zoom + steps).clamp(Self::MIN_ZOOM, Self::MAX_ZOOM);
    }

    /// cm of world shown across the view for a die of half size `a` cm.
    pub(crate) fn width_cm(&self, half_size: f64) -> f64 {
        9.0 * half_size * 1.25f64.powi(-self.zoom)
    }

    /// Projects `p` with the view's horizontal origin at `focus` (the camera follows the die
    /// across the table; heights stay absolute so the ground is z = 0 on screen too).
    pub(crate) fn project(&self, p: &Vector3<f64>, focus: &Vector3<f64>) -> Projected {
        let (sy, cy) = self.yaw_deg.to_radians().sin_cos();
        let (sp, cp) = self.pitch_deg.to_radians().sin_cos();
        let (dx, dy, z) = (p.x - focus.x, p.y - focus.y, p.z);
        let across = cy * dx + sy * dy;
        let away = -sy * dx + cy * dy;
        Projected {
            x: across,
            y: z * cp + away * sp,
            depth: away * cp - z * sp,
        }
    }

    /// The world vector of a step on the view plane (across, up), cm: the plane faces the
    /// camera, so the step has no depth. [`OrbitCamera::project`] takes it back.
    pub(crate) fn world_step(&self, step: (f64, f64)) -> Vector3<f64> {
        let (sy, cy) = self.yaw_deg.to_radians().sin_cos();
        let (sp, cp) = self.pitch_deg.to_radians().sin_cos();
        let across = Vector3::new(cy, sy, 0.0);
        let up = Vector3::new(-sy * sp, cy * sp, cp);
        step.0 * across + step.1 * up
    }

    /// The world vector of a step on the screen (across, up) laid on the table, cm: across
    /// stays across, up goes away from the viewer over the table, as a hand throwing across a
    /// table moves. Level, the step keeps its length; it has no height.
    pub(crate) fn table_step(&self, step: (f64, f64)) -> Vector3<f64> {
        let (sy, cy) = self.yaw_deg.to_radians().sin_cos();
        let across = Vector3::new(cy, sy, 0.0);
        let away = Vector3::new(-sy, cy, 0.0);
        step.0 * across + step.1 * away
    }

    /// How directly a world direction faces the viewer (1 straight at them, < 0 away).
    pub(crate) fn facing(&self, direction: &Vector3<f64>) -> f64 {
        let n = direction.normalize();
        if !n.iter().all(|c| c.is_finite()) {
            return -1.0;
        }
        -self.project(&n, &Vector3::zeros()).depth
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_top_faces_the_viewer_from_above_and_the_bottom_does_not() {
        let cam = OrbitCamera::default();
        assert!(cam.facing(&Vector3::z()) > 0.0);
        assert!(cam.facing(&-Vector3::z()) < 0.0);
        let level = OrbitCamera {
            pitch_deg: 0.0,
            ..cam
        };
        assert!(level.facing(&Vector3::z()).abs() < 1e-12);
        let p = cam.project(&Vector3::new(3.0, 4.0, 0.0), &Vector3::new(3.0, 4.0, 9.0));
        assert!(
            p.x.abs() < 1e-12 && p.y.abs() < 1e-12,
            "the focus' foot is the screen origin"
        );
    }

    #[test]
    fn a_step_on_the_view_plane_projects_back_onto_itself() {
        let cam = OrbitCamera::default();
        let w = cam.world_step((0.3, -0.7));
        let back = cam.project(&w, &Vector3::zeros());
        assert!(
            (back.x - 0.3).abs() < 1e-12 && (back.y + 0.7).abs() < 1e-12,
            "{back:?}"
        );
        assert!(back.depth.abs() < 1e-12, "no depth: {back:?}");
    }

    /// A step up the screen goes away over the table, level, whatever the camera's tilt: at
    /// yaw 90° the screen's across is +y and away from the viewer is −x.
    #[test]
    fn a_step_up_the_screen_goes_away_over_the_table() {
        for pitch_deg in [0.0, 30.0, 80.0] {
            let cam = OrbitCamera {
                yaw_deg: 90.0,
                pitch_deg,
                zoom: 0,
            };
            let w = cam.table_step((0.5, 2.0));
            assert!(w.z == 0.0, "level: {w:?}");
            assert!((w - Vector3::new(-2.0, 0.5, 0.0)).norm() < 1e-12, "{w:?}");
            // Projected, the step goes up the screen and across as the drag did.
            let back = cam.project(&w, &Vector3::zeros());
            assert!(back.y >= 0.0 && (back.x - 0.5).abs() < 1e-12, "{back:?}");
        }
    }
}
