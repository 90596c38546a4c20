//! The dice people roll, built exactly (docs/dice.md): the five regular solids, the d10 and
//! the d% as a pentagonal trapezohedron, and prisms (a d3, a thick coin), all standing
//! [`STANDARD_HEIGHT`] tall on a face unless told otherwise.

use super::die::Die;
use super::hull::{HullError, MAX_VERTICES, convex_hull};
use super::numbering::{Numbering, ReadAt, opposite_faces};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// cm, how tall a standard ("16 mm") die stands on a face: across its faces, or from a face
/// to the top vertex for the d4.
pub const STANDARD_HEIGHT: f64 = 1.6;

/// g/cm³, cast acrylic resin (PMMA), what most gaming dice are made of.
pub const RESIN_DENSITY: f64 = 1.18;

/// A regular gaming die.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum DieKind {
    #[serde(rename = "d4")]
    D4,
    #[serde(rename = "d6")]
    D6,
    #[serde(rename = "d8")]
    D8,
    #[serde(rename = "d10")]
    D10,
    /// The d10's shape labelled 00, 10, …, 90.
    #[serde(rename = "d%")]
    Percentile,
    #[serde(rename = "d12")]
    D12,
    #[serde(rename = "d20")]
    D20,
}

/// The golden ratio.
const PHI: f64 = 1.618_033_988_749_895;

impl DieKind {
    pub const ALL: [DieKind; 7] = [
        Self::D4,
        Self::D6,
        Self::D8,
        Self::D10,
        Self::Percentile,
        Self::D12,
        Self::D20,
    ];

    /// The name players use: `d4` … `d20`, `d%`.
    pub fn name(self) -> &'static str {
        match self {
            Self::D4 => "d4",
            Self::D6 => "d6",
            Self::D8 => "d8",
            Self::D10 => "d10",
            Self::Percentile => "d%",
            Self::D12 => "d12",
            Self::D20 => "d20",
        }
    }

    /// The kind a player names (`d4` … `d20`, `d%`), or the names there are.
    pub fn from_name(name: &str) -> Result<Self, String> {
        Self::ALL.into_iter().find(|k| k.name() == name).ok_or_else(|| {
            let names: Vec<&str> = Self::ALL.iter().map(|k| k.name()).collect();
            format!("no die called {name:?}: one of {}", names.join(", "))
        })
    }

    /// The exact vertices (cm) of the die standing `height` tall on a face, centred on the
    /// origin.
    pub fn vertices(self, height: f64) -> Vec<Vector3<f64>> {
        let signs = |v: [f64; 3]| -> Vec<Vector3<f64>> {
            let mut out = Vec::new();
            for sx in [-1.0, 1.0] {
                for sy in [-1.0, 1.0] {
                    for sz in [-1.0, 1.0] {
                        let p = Vector3::new(sx * v[0], sy * v[1], sz * v[2]);
                        if !out.contains(&p) {
                            out.push(p);
                        }
                    }
                }
            }
            out
        };
        let cyclic = |v: [f64; 3]| -> Vec<Vector3<f64>> {
            [v, [v[2], v[0], v[1]], [v[1], v[2], v[0]]]
                .into_iter()
                .flat_map(signs)
                .collect()
        };
        let (unit, inradius): (Vec<Vector3<f64>>, f64) = match self {
            Self::D4 => {
                let v = [
                    [1.0, 1.0, 1.0],
                    [1.0, -1.0, -1.0],
                    [-1.0, 1.0, -1.0],
                    [-1.0, -1.0, 1.0],
                ];
                // Edge 2√2, inradius 1/√3; it stands four inradii tall.
                return v
                    .iter()
                    .map(|&p| Vector3::from(p) * (height * 3f64.sqrt() / 4.0))
                    .collect();
            }
            Self::D6 => (signs([1.0; 3]), 1.0),
            Self::D8 => (cyclic([1.0, 0.0, 0.0]), 1.0 / 3f64.sqrt()),
            Self::D12 => {
                let mut v = signs([1.0; 3]);
                v.extend(cyclic([0.0, 1.0 / PHI, PHI]));
                // Edge 2/φ: inradius (a/2)·√((25 + 11√5)/10).
                (v, ((25.0 + 11.0 * 5f64.sqrt()) / 10.0).sqrt() / PHI)
            }
            Self::D20 => (cyclic([0.0, 1.0, PHI]), PHI * PHI / 3f64.sqrt()),
            Self::D10 | Self::Percentile => return trapezohedron(height),
        };
        unit.into_iter().map(|p| p * (height / 2.0 / inradius)).collect()
    }

    /// The die standing `height` (cm) tall, of uniform `density` (g/cm³), numbered as real
    /// dice are (docs/dice.md).
    pub fn die(self, height: f64, density: f64) -> Die {
        let shape = convex_hull(&self.vertices(height)).expect("a regular die is convex");
        let numbering = match self {
            Self::D4 => Numbering {
                // Vertex k is labelled k + 1; with a face down the vertex it misses is up.
                numbers: shape
                    .faces
                    .iter()
                    .map(|f| {
                        (0..4)
                            .find(|k| !f.vertices.contains(k))
                            .expect("a face misses a vertex") as u32
                            + 1
                    })
                    .collect(),
                read_at: ReadAt::TopVertex,
                opposite: vec![None; 4],
            },
            Self::D6 => Numbering {
                // The paper's: −x 1, −y 2, −z 3, +z 4, +y 5, +x 6.
                numbers: shape
                    .faces
                    .iter()
                    .map(|f| {
                        let n = f.normal;
                        let axis = (0..3)
                            .max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
                            .expect("3 axes");
                        if n[axis] < 0.0 {
                            axis as u32 + 1
                        } else {
                            6 - axis as u32
                        }
                    })
                    .collect(),
                read_at: ReadAt::TopFace,
                opposite: opposite_faces(&shape),
            },
            Self::D10 => Numbering::in_opposite_pairs(&shape, 0, 1).expect("the d10's faces pair"),
            Self::Percentile => Numbering::in_opposite_pairs(&shape, 0, 10).expect("the d%'s faces pair"),
            Self::D8 | Self::D12 | Self::D20 => {
                Numbering::in_opposite_pairs(&shape, 1, 1).expect("a regular die's faces pair")
            }
        };
        Die::new(shape, numbering, density)
    }

    /// The standard 16 mm die in resin.
    pub fn standard(self) -> Die {
        self.die(STANDARD_HEIGHT, RESIN_DENSITY)
    }
}

/// The d10's vertices: apexes `(0, 0, ±H)` and a zigzag of ten at radius `ρ = H`, heights
/// `±z_0 = ±H·(1 − cos 36°)/(1 + cos 36°)` (planar kites), `H` set so that the faces stand
/// `height` apart (docs/model.md, "The regular solids, by hand").
fn trapezohedron(height: f64) -> Vec<Vector3<f64>> {
    let c = (PI / 5.0).cos();
    let t = (1.0 - c) / (1.0 + c);
    // r_i = ρH/√((H + z_0)² + ρ²) with ρ = H.
    let h = height / 2.0 * ((1.0 + t).powi(2) + 1.0).sqrt();
    let mut v = vec![Vector3::new(0.0, 0.0, h), Vector3::new(0.0, 0.0, -h)];
    for k in 0..10 {
        let azimuth = PI / 5.0 * k as f64;
        let z = if k % 2 == 0 { t * h } else { -t * h };
        v.push(Vector3::new(h * azimuth.cos(), h * azimuth.sin(), z));
    }
    v
}

/// A right prism on a regular `sides`-gon of `circumradius` (cm), `height` (cm) along z,
/// centred on the origin: a d3 (3 sides, long), a thick coin (many sides, flat). Numbered as
/// any convex die ([`Numbering::for_shape`]).
pub fn prism(sides: usize, circumradius: f64, height: f64, density: f64) -> Result<Die, HullError> {
    if 2 * sides > MAX_VERTICES {
        return Err(HullError::TooMany { count: 2 * sides });
    }
    let vertices: Vec<Vector3<f64>> = [0.5, -0.5]
        .into_iter()
        .flat_map(|z| {
            (0..sides).map(move |k| {
                let azimuth = 2.0 * PI * k as f64 / sides as f64;
                Vector3::new(
                    circumradius * azimuth.cos(),
                    circumradius * azimuth.sin(),
                    z * height,
                )
            })
        })
        .collect();
    Die::from_vertices(&vertices, density)
}
