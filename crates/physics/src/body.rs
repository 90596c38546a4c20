//! The die's geometry: corner numbering, faces, pips and contact spheres (docs/model.md,
//! "Faces" and "Real dice"). The explorer's drawing and any picture or export of the die
//! read these, so the body is defined once.

use super::params::Die;
use nalgebra::Vector3;

/// Signs of corners 1..8 in the body frame, `(x, y, z)/a`, in the authors' order.
pub const CORNER_SIGNS: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, 1.0, 1.0],
    [1.0, -1.0, -1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, -1.0],
    [1.0, 1.0, 1.0],
];

/// The four corners (0-based) of faces 1..6; opposite faces sum to 7.
pub const FACE_CORNERS: [[usize; 4]; 6] = [
    [0, 1, 2, 3], // 1: x = −a
    [0, 1, 4, 5], // 2: y = −a
    [0, 2, 4, 6], // 3: z = −a
    [1, 3, 5, 7], // 4: z = +a
    [2, 3, 6, 7], // 5: y = +a
    [4, 5, 6, 7], // 6: x = +a
];

/// Outward normals of faces 1..6 in the body frame.
pub(crate) const FACE_NORMALS: [[f64; 3]; 6] = [
    [-1.0, 0.0, 0.0],
    [0.0, -1.0, 0.0],
    [0.0, 0.0, -1.0],
    [0.0, 0.0, 1.0],
    [0.0, 1.0, 0.0],
    [1.0, 0.0, 0.0],
];

/// Pip centres of faces 1..6, in units of the face's half sizes along its two edge directions
/// (from its first corner in `FACE_CORNERS` to the second, and to the third): the layout of a
/// real die, with the off-centre pips halfway from the centre to the edges. The explorer's
/// drawing and every picture of the die read this one table.
pub const PIP_LAYOUT: [&[(f64, f64)]; 6] = [
    &[(0.0, 0.0)],
    &[(-0.5, -0.5), (0.5, 0.5)],
    &[(-0.5, -0.5), (0.0, 0.0), (0.5, 0.5)],
    &[(-0.5, -0.5), (-0.5, 0.5), (0.5, -0.5), (0.5, 0.5)],
    &[(-0.5, -0.5), (-0.5, 0.5), (0.0, 0.0), (0.5, -0.5), (0.5, 0.5)],
    &[
        (-0.5, -0.5),
        (-0.5, 0.0),
        (-0.5, 0.5),
        (0.5, -0.5),
        (0.5, 0.0),
        (0.5, 0.5),
    ],
];

/// A face's outward normal and its two edge directions (body frame, unit axis vectors): from
/// its first corner in [`FACE_CORNERS`] to the second, and to the third. `face` is 1..6.
pub fn face_frame(face: u8) -> [[f64; 3]; 3] {
    let corners = FACE_CORNERS[face as usize - 1];
    let along = |to: usize| -> [f64; 3] {
        std::array::from_fn(|i| (CORNER_SIGNS[corners[to]][i] - CORNER_SIGNS[corners[0]][i]) / 2.0)
    };
    [FACE_NORMALS[face as usize - 1], along(1), along(2)]
}

/// cm, body frame about the geometric centre: where the pips of `face` (1..6) open in its
/// plane, in [`PIP_LAYOUT`] order, for a body of these half sizes. The pips' places do not
/// depend on whether they are drilled, so a drawing of an undrilled die uses them too.
pub fn pip_centres(half_sizes: [f64; 3], face: u8) -> Vec<[f64; 3]> {
    let [n, e1, e2] = face_frame(face);
    PIP_LAYOUT[face as usize - 1]
        .iter()
        .map(|&(u, v)| std::array::from_fn(|i| (n[i] + u * e1[i] + v * e2[i]) * half_sizes[i]))
        .collect()
}

/// One drilled pip: a spherical-cap hole opening in a face (docs/model.md, "Real dice").
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Pip {
    /// cm, body frame about the geometric centre: the centre of the opening, in the face.
    pub(crate) centre: [f64; 3],
    /// The face's outward normal.
    pub(crate) normal: [f64; 3],
    /// cm, the opening's radius (half `die.pip_diameter`).
    pub(crate) radius: f64,
    /// cm, from the face to the bottom of the hole.
    pub(crate) depth: f64,
}

/// Every pip of `die` (21, faces 1..6 in order), or none for an undrilled die.
pub(crate) fn pips(die: &Die) -> Vec<Pip> {
    if !die.is_drilled() {
        return Vec::new();
    }
    (1..=6u8)
        .flat_map(|face| {
            pip_centres(die.half_sizes, face)
                .into_iter()
                .map(move |centre| Pip {
                    centre,
                    normal: FACE_NORMALS[face as usize - 1],
                    radius: 0.5 * die.pip_diameter,
                    depth: die.pip_depth,
                })
        })
        .collect()
}

/// cm, body frame about the geometric centre: the centres of the 8 corner spheres, the
/// sharp box shrunk by the corner radius (corners 1..8; for a sharp die, its corners). The
/// rounded body is this box grown by a ball of the corner radius, so against the table its
/// lowest point is always on one of these spheres.
pub fn contact_sphere_centres(die: &Die) -> [Vector3<f64>; 8] {
    let r = die.corner_radius;
    sphere_centres(die.half_sizes.map(|a| a - r))
}

/// cm, the corners 1..8 of the box of half sizes `flat` (`a − r`) the corner spheres sit on.
pub(crate) fn sphere_centres(flat: [f64; 3]) -> [Vector3<f64>; 8] {
    let b = flat;
    CORNER_SIGNS.map(|s| Vector3::new(s[0] * b[0], s[1] * b[1], s[2] * b[2]))
}

/// Corner offsets from the centre of mass at identity orientation, cm.
pub fn body_corner_offsets(half_size: f64) -> [Vector3<f64>; 8] {
    CORNER_SIGNS.map(|s| Vector3::new(s[0] * half_size, s[1] * half_size, s[2] * half_size))
}

/// The outcome rule: the face whose 4 corners are the 4 highest.
///
/// Ties keep the lower corner index first (the authors' stable sort). `None` when the 4 highest
/// corners do not form a face, which needs a die standing almost on a corner.
pub(crate) fn face_of_highest_corners(corner_heights: &[f64; 8]) -> Option<u8> {
    let mut order: [usize; 8] = [0, 1, 2, 3, 4, 5, 6, 7];
    // Stable, descending; NaN sorts last so a broken state never panics here.
    order.sort_by(|&a, &b| {
        corner_heights[b]
            .partial_cmp(&corner_heights[a])
            .unwrap_or_else(|| corner_heights[a].is_nan().cmp(&corner_heights[b].is_nan()))
    });
    let mut top = [order[0], order[1], order[2], order[3]];
    top.sort_unstable();
    FACE_CORNERS.iter().position(|f| *f == top).map(|i| i as u8 + 1)
}

/// The face whose outward normal points most nearly up, from the world corner offsets.
///
/// Mid-flight the 4 highest corners often do not form a face; this rule always answers, and
/// agrees with the outcome rule (the face of the 4 highest corners) at rest.
pub fn face_most_nearly_up(corner_offsets: &[Vector3<f64>; 8]) -> u8 {
    let up = face_normal_heights(corner_offsets);
    let mut best = 0;
    for (i, h) in up.iter().enumerate() {
        if *h > up[best] {
            best = i;
        }
    }
    best as u8 + 1
}

/// The z-component of each face's outward unit normal in the world frame (faces 1..6).
pub(crate) fn face_normal_heights(corner_offsets: &[Vector3<f64>; 8]) -> [f64; 6] {
    // Body axes in the world frame from corner differences: x from corner 1 to 5,
    // y from 1 to 3, z from 1 to 2 (each spans one side, 2a).
    let ex = corner_offsets[4] - corner_offsets[0];
    let ey = corner_offsets[2] - corner_offsets[0];
    let ez = corner_offsets[1] - corner_offsets[0];
    let (nx, ny, nz) = (ex.z / ex.norm(), ey.z / ey.norm(), ez.z / ez.norm());
    [-nx, -ny, -nz, nz, ny, nx]
}

/// The box's face opposite `face` (they sum to 7); a polyhedral die's is
/// [`Solid::opposite_number`](crate::Solid::opposite_number).
pub fn opposite_face(face: u8) -> u8 {
    7 - face
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identity_shows_four() {
        let r = body_corner_offsets(1.0);
        let z = r.map(|c| c.z);
        assert_eq!(face_of_highest_corners(&z), Some(4));
        assert_eq!(face_most_nearly_up(&r), 4);
    }

    #[test]
    fn face_corners_match_normals() {
        for (f, corners) in FACE_CORNERS.iter().enumerate() {
            let n = Vector3::from(FACE_NORMALS[f]);
            for &c in corners {
                assert_eq!(Vector3::from(CORNER_SIGNS[c]).dot(&n), 1.0, "face {}", f + 1);
            }
            assert_eq!(f as u8 + 1 + opposite_face(f as u8 + 1), 7);
        }
    }

    #[test]
    fn every_face_up_by_rotation() {
        use nalgebra::Rotation3;
        let r = body_corner_offsets(1.0);
        for (f, n) in FACE_NORMALS.iter().enumerate() {
            // Rotate the face's normal onto +z.
            let rot = Rotation3::rotation_between(&Vector3::from(*n), &Vector3::z())
                .unwrap_or_else(|| Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI));
            let w = r.map(|c| rot * c);
            assert_eq!(face_most_nearly_up(&w), f as u8 + 1);
            assert_eq!(face_of_highest_corners(&w.map(|c| c.z)), Some(f as u8 + 1));
        }
    }

    #[test]
    fn corner_standing_has_no_face() {
        // Corner 8 straight up, 1 straight down: the top four are 8 and three neighbours.
        let z = [-1.7, 0.6, 0.6, -0.6, 0.6, -0.6, -0.6, 1.7];
        assert_eq!(face_of_highest_corners(&z), None);
    }
}
