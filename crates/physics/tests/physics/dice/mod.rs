//! The dice of any convex shape (docs/model.md, "Dice of any convex shape"; docs/dice.md):
//! each regular solid's closed forms derived by hand, held against the hull and the integrals.

mod any_roll;
mod bias;
mod engines;
mod fairness;
mod flaws;
mod hull;
mod keys;
mod mass;
mod reading;
mod rest;
mod rolled;
mod speed;
mod stability;

use crate::common::random_start;
use dicesim_physics::polyhedron::DieKind;
use dicesim_physics::{InitialCondition, Params, RandomRanges};

/// The table the dice roll on: the paper's at a quarter of its step, where the d4's stiffest
/// contact mode has the margin the paper's cube has at 1 ms (docs/model.md, "Fair dice come out
/// fair": at 1 ms every throw of the d4 runs away).
pub fn dice_table() -> Params {
    let mut params = Params::default();
    params.integrator.dt = 0.000_25;
    params
}

/// Throw `index` of `seed`: the paper's throw (from 15 cm, velocity and spin uniform in ±50
/// cm/s and ±60 rad/s a component) from an orientation uniform over all rotations.
pub fn throw(seed: u64, index: u64) -> InitialCondition {
    let ranges = RandomRanges {
        random_orientation: true,
        ..RandomRanges::default()
    };
    random_start(&ranges, &InitialCondition::default(), seed, index)
}

/// A regular solid's closed forms per edge `a` (docs/model.md, "The regular solids, by hand").
pub struct Regular {
    pub kind: DieKind,
    /// Faces, and vertices per face.
    pub faces: usize,
    pub sides: usize,
    /// Inradius, centre-to-edge distance, volume and `I/(M a²)` over powers of the edge.
    pub inradius: f64,
    pub midradius: f64,
    pub volume: f64,
    pub inertia: f64,
    /// The height it stands on a face over its inradius: 4 for the d4, else 2.
    pub heights: f64,
}

pub fn regular() -> [Regular; 5] {
    let s5 = 5f64.sqrt();
    let s6 = 6f64.sqrt();
    let s2 = 2f64.sqrt();
    let s3 = 3f64.sqrt();
    [
        Regular {
            kind: DieKind::D4,
            faces: 4,
            sides: 3,
            inradius: 1.0 / (2.0 * s6),
            midradius: 1.0 / (2.0 * s2),
            volume: 1.0 / (6.0 * s2),
            inertia: 1.0 / 20.0,
            heights: 4.0,
        },
        Regular {
            kind: DieKind::D6,
            faces: 6,
            sides: 4,
            inradius: 0.5,
            midradius: 1.0 / s2,
            volume: 1.0,
            inertia: 1.0 / 6.0,
            heights: 2.0,
        },
        Regular {
            kind: DieKind::D8,
            faces: 8,
            sides: 3,
            inradius: 1.0 / s6,
            midradius: 0.5,
            volume: s2 / 3.0,
            inertia: 0.1,
            heights: 2.0,
        },
        Regular {
            kind: DieKind::D12,
            faces: 12,
            sides: 5,
            inradius: 0.5 * ((25.0 + 11.0 * s5) / 10.0).sqrt(),
            midradius: (3.0 + s5) / 4.0,
            volume: (15.0 + 7.0 * s5) / 4.0,
            inertia: (95.0 + 39.0 * s5) / 300.0,
            heights: 2.0,
        },
        Regular {
            kind: DieKind::D20,
            faces: 20,
            sides: 3,
            inradius: (3.0 + s5) / (4.0 * s3),
            midradius: (1.0 + s5) / 4.0,
            volume: 5.0 * (3.0 + s5) / 12.0,
            inertia: (3.0 + s5) / 20.0,
            heights: 2.0,
        },
    ]
}

impl Regular {
    /// cm, the edge of the die standing `height` tall.
    pub fn edge(&self, height: f64) -> f64 {
        height / (self.heights * self.inradius)
    }
}

/// The d10's closed forms for apex height `h` = ring radius: `(z_0, volume, I_zz/M, I_xx/M,
/// inradius, apex-edge distance, zigzag-edge distance)` (docs/model.md).
pub fn d10(h: f64) -> [f64; 7] {
    let c = 36f64.to_radians().cos();
    let s = 36f64.to_radians().sin();
    let rho = h;
    let z0 = h * (1.0 - c) / (1.0 + c);
    let volume = 10.0 / 3.0 * h * rho * rho * s;
    let izz = rho * rho * (2.0 + c) / 10.0;
    let ixx = rho * rho * (2.0 + c) / 20.0 + (h * h + z0 * z0) / 10.0;
    let inradius = rho * h / ((h + z0).powi(2) + rho * rho).sqrt();
    let apex = rho * h / (rho * rho + (h - z0).powi(2)).sqrt();
    let zigzag_num = z0 * z0 * rho * rho * (2.0 + 2.0 * c) + rho.powi(4) * s * s;
    let zigzag_den = rho * rho * (2.0 - 2.0 * c) + 4.0 * z0 * z0;
    [
        z0,
        volume,
        izz,
        ixx,
        inradius,
        apex,
        (zigzag_num / zigzag_den).sqrt(),
    ]
}

/// `|a − b| ≤ tol·|scale|`, with the numbers in the message.
pub fn assert_close(what: &str, a: f64, b: f64, scale: f64, tol: f64) {
    assert!(
        (a - b).abs() <= tol * scale.abs(),
        "{what}: {a} against {b} (difference {:e}, allowed {:e})",
        a - b,
        tol * scale.abs()
    );
}
