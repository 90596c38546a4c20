//! The hull of a list of vertices: its faces found and merged, and every bad list refused with
//! the vertex at fault.

use dicesim_physics::polyhedron::{DieKind, HullError, MAX_VERTICES, convex_hull, prism};
use nalgebra::Vector3;

fn cube() -> Vec<Vector3<f64>> {
    let mut v = Vec::new();
    for x in [-1.0, 1.0] {
        for y in [-1.0, 1.0] {
            for z in [-1.0, 1.0] {
                v.push(Vector3::new(x, y, z));
            }
        }
    }
    v
}

#[test]
fn coplanar_vertices_make_one_polygon_per_face() {
    for (kind, faces, sides) in [
        (DieKind::D4, 4, 3),
        (DieKind::D6, 6, 4),
        (DieKind::D8, 8, 3),
        (DieKind::D10, 10, 4),
        (DieKind::D12, 12, 5),
        (DieKind::D20, 20, 3),
    ] {
        let hull = convex_hull(&kind.vertices(1.6)).expect("a regular die is convex");
        assert_eq!(hull.faces().len(), faces, "{}", kind.name());
        assert_eq!(
            hull.edges().len(),
            hull.vertices().len() + faces - 2,
            "{}: Euler's formula",
            kind.name()
        );
        for face in hull.faces() {
            assert_eq!(face.vertices.len(), sides, "{}", kind.name());
            // Counter-clockwise from outside: each corner turns left about the outward normal.
            let n = face.vertices.len();
            for i in 0..n {
                let [a, b, c] = [0, 1, 2].map(|d| hull.vertices()[face.vertices[(i + d) % n]]);
                assert!(
                    (b - a).cross(&(c - b)).dot(&face.normal) > 0.0,
                    "{}: a face turns the wrong way",
                    kind.name()
                );
            }
            for &v in &face.vertices {
                assert!(
                    face.height_of(&hull.vertices()[v]).abs() < 1e-14,
                    "{}: a vertex off its face",
                    kind.name()
                );
            }
        }
    }
}

#[test]
fn a_point_inside_or_on_the_surface_is_not_a_corner() {
    let mut inside = cube();
    inside.insert(3, Vector3::new(0.1, 0.2, -0.3));
    assert_eq!(convex_hull(&inside), Err(HullError::NotConvex { vertex: 3 }));
    let mut on_face = cube();
    on_face.push(Vector3::new(1.0, 0.2, 0.3));
    assert_eq!(convex_hull(&on_face), Err(HullError::NotConvex { vertex: 8 }));
    let mut on_edge = cube();
    on_edge.push(Vector3::new(1.0, 1.0, 0.5));
    assert_eq!(convex_hull(&on_edge), Err(HullError::NotConvex { vertex: 8 }));
}

#[test]
fn degenerate_lists_are_refused() {
    let square = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.5, 2.0, 0.0],
    ];
    let flat: Vec<Vector3<f64>> = square.iter().map(|&p| Vector3::from(p)).collect();
    assert_eq!(convex_hull(&flat), Err(HullError::Flat));
    let line: Vec<Vector3<f64>> = (0..5)
        .map(|k| Vector3::new(k as f64, 2.0 * k as f64, 0.0))
        .collect();
    assert_eq!(convex_hull(&line), Err(HullError::Flat));
    assert_eq!(convex_hull(&cube()[..3]), Err(HullError::TooFew { count: 3 }));
    let mut twice = cube();
    twice.push(Vector3::new(-1.0, 1.0, -1.0));
    assert_eq!(
        convex_hull(&twice),
        Err(HullError::Duplicate { vertex: 8, of: 2 })
    );
    let mut nan = cube();
    nan[5].y = f64::NAN;
    assert_eq!(convex_hull(&nan), Err(HullError::NotFinite { vertex: 5 }));
}

#[test]
fn more_than_the_kernels_points_are_refused() {
    let sphere = |n: usize| -> Vec<Vector3<f64>> {
        // A Fibonacci lattice: every point a corner of the hull.
        (0..n)
            .map(|k| {
                let z = 1.0 - (2.0 * k as f64 + 1.0) / n as f64;
                let phi = k as f64 * std::f64::consts::PI * (3.0 - 5f64.sqrt());
                let r = (1.0 - z * z).sqrt();
                Vector3::new(r * phi.cos(), r * phi.sin(), z)
            })
            .collect()
    };
    let hull = convex_hull(&sphere(MAX_VERTICES)).expect("64 points on a sphere are a die");
    assert_eq!(hull.vertices().len(), 64);
    assert_eq!(
        convex_hull(&sphere(MAX_VERTICES + 1)),
        Err(HullError::TooMany { count: 65 })
    );
    assert_eq!(
        prism(33, 1.0, 1.0, 1.0).map(|_| ()),
        Err(HullError::TooMany { count: 66 })
    );
}

#[test]
fn prisms_are_dice() {
    let d3 = prism(3, 0.8, 2.5, 1.18).expect("a triangular prism");
    assert_eq!(d3.shape().faces().len(), 5);
    let coin = prism(32, 1.2, 0.3, 1.18).expect("a thick coin");
    assert_eq!(coin.shape().faces().len(), 34);
    // The coin's volume is its 32-gon's area times its thickness.
    let area = 0.5 * 32.0 * 1.2f64.powi(2) * (2.0 * std::f64::consts::PI / 32.0).sin();
    super::assert_close(
        "coin mass",
        coin.mass_properties().mass,
        area * 0.3 * 1.18,
        area * 0.3 * 1.18,
        1e-13,
    );
}
