//! Helpers the physics tests share: the reference CSVs, the authors' setups, random starts,
//! and a state as bits.

use dicesim_physics::lanes::EndState;
use dicesim_physics::{FrictionLaw, InitialCondition, Params, RandomRanges, StopEnergy};
use nalgebra::{Quaternion, Rotation3, UnitQuaternion};
use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use std::collections::HashMap;
use std::path::PathBuf;

/// A file of this crate's test data (`crates/physics/tests/data/`).
pub fn data_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// One CSV file as rows of named numeric columns.
pub struct Table {
    pub rows: Vec<Vec<f64>>,
    index: HashMap<String, usize>,
}

impl Table {
    /// A file of `crates/physics/tests/data/reference/`.
    pub fn load(name: &str) -> Table {
        let path = data_path("reference").join(name);
        let fail = |e: &dyn std::fmt::Display| -> ! { panic!("{}: {e}", path.display()) };
        let mut reader = csv::Reader::from_path(&path).unwrap_or_else(|e| fail(&e));
        let index = reader
            .headers()
            .unwrap_or_else(|e| fail(&e))
            .iter()
            .enumerate()
            .map(|(i, h)| (h.to_string(), i))
            .collect();
        // Every cell is a number written with %.17g, so each parses to the bits written.
        let rows = reader
            .deserialize::<Vec<f64>>()
            .map(|row| row.unwrap_or_else(|e| fail(&e)))
            .collect();
        Table { rows, index }
    }

    pub fn col(&self, name: &str) -> usize {
        *self.index.get(name).unwrap_or_else(|| panic!("no column {name}"))
    }

    pub fn get(&self, row: &[f64], name: &str) -> f64 {
        row[self.col(name)]
    }

    pub fn vec3(&self, row: &[f64], prefix: &str) -> [f64; 3] {
        ["x", "y", "z"].map(|a| self.get(row, &format!("{prefix}_{a}")))
    }
}

/// The authors' program's setup for one reference initial condition.
pub fn reference_initial(table: &Table, row: &[f64]) -> InitialCondition {
    InitialCondition {
        height: 15.0,
        velocity: table.vec3(row, "v"),
        angular_momentum: Some(table.vec3(row, "L_phys")),
        ..InitialCondition::default()
    }
}

/// Parameters of a reference variant: `original` (whole-die-norm friction) or `paper`.
/// Both files were produced with the point-mass stop energy.
pub fn reference_params(variant: &str) -> Params {
    let mut p = Params::default();
    p.ground.friction_law = match variant {
        "original" => FrictionLaw::WholeDieNorm,
        "paper" => FrictionLaw::PerCorner,
        other => panic!("unknown variant {other}"),
    };
    p.integrator.stop_energy = StopEnergy::PointMasses;
    p
}

/// Start `index` of a set seeded with `seed`, drawn from `ranges` as a batch draws its
/// starts (one ChaCha stream per seed and index; height, velocity and spin uniform in their
/// ranges, in that order; the orientation uniform over all rotations by Shoemake's unit
/// quaternion, or `base`'s). The layer above owns that draw; it is written out here so the
/// physics tests build without it, and any spread of starts would serve them.
pub fn random_start(
    ranges: &RandomRanges,
    base: &InitialCondition,
    seed: u64,
    index: u64,
) -> InitialCondition {
    use std::f64::consts::TAU;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(index);
    let mut uniform = |r: [f64; 2]| rng.random_range(r[0]..=r[1]);
    let height = uniform(ranges.height);
    let velocity = [(); 3].map(|_| uniform(ranges.velocity));
    let angular_velocity = [(); 3].map(|_| uniform(ranges.angular_velocity));
    let orientation = if ranges.random_orientation {
        let [u1, u2, u3]: [f64; 3] = [(); 3].map(|_| rng.random_range(0.0..1.0));
        let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
        let q = Quaternion::new(
            b * (TAU * u3).cos(),
            a * (TAU * u2).sin(),
            a * (TAU * u2).cos(),
            b * (TAU * u3).sin(),
        );
        let rotation: Rotation3<f64> = UnitQuaternion::from_quaternion(q).to_rotation_matrix();
        let (roll, pitch, yaw) = rotation.euler_angles();
        [yaw.to_degrees(), pitch.to_degrees(), roll.to_degrees()]
    } else {
        base.orientation
    };
    InitialCondition {
        height,
        velocity,
        angular_velocity,
        angular_momentum: None,
        orientation,
    }
}

/// A state's every number as bits, and its step count: what two engines must agree on (a
/// law's memory at the points shows in the forces it gives).
pub fn state_bits(s: EndState<'_>) -> Vec<u64> {
    let mut v: Vec<f64> = Vec::with_capacity(96);
    v.extend(s.position.iter());
    v.extend(s.velocity.iter());
    v.extend(s.angular_momentum.iter());
    for k in 0..s.corner_offsets.len() {
        v.extend(s.corner_offsets[k].iter());
        v.extend(s.corner_forces[k].iter());
        v.push(s.corner_depths[k]);
    }
    v.push(s.time_s);
    let mut bits: Vec<u64> = v.into_iter().map(f64::to_bits).collect();
    bits.push(s.step);
    bits
}
