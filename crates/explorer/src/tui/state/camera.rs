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
}
