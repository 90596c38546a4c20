//! Helpers shared by the integration tests: reading the reference CSVs, running the binary.
#![allow(dead_code)]

use dicesim::physics::{FrictionLaw, InitialCondition, Params, StopEnergy};
use std::collections::HashMap;
use std::path::PathBuf;

/// One CSV file as rows of named numeric columns.
pub struct Table {
    pub header: Vec<String>,
    pub rows: Vec<Vec<f64>>,
    index: HashMap<String, usize>,
}

impl Table {
    pub fn load(name: &str) -> Table {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data/reference")
            .join(name);
        let fail = |e: &dyn std::fmt::Display| -> ! { panic!("{}: {e}", path.display()) };
        let mut reader = csv::Reader::from_path(&path).unwrap_or_else(|e| fail(&e));
        let header: Vec<String> = reader
            .headers()
            .unwrap_or_else(|e| fail(&e))
            .iter()
            .map(str::to_string)
            .collect();
        let index = header.iter().enumerate().map(|(i, h)| (h.clone(), i)).collect();
        // Every cell is a number written with %.17g, so each parses to the bits written.
        let rows = reader
            .deserialize::<Vec<f64>>()
            .map(|row| row.unwrap_or_else(|e| fail(&e)))
            .collect();
        Table { header, rows, index }
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

/// Runs the `dicesim` binary in `dir`, with a user preset folder that does not exist, so
/// that only the shipped presets are found.
pub fn dicesim_in(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_dicesim"))
        .args(args)
        .current_dir(dir)
        .env("DICESIM_PRESETS", dir.join("no-user-presets"))
        .output()
        .expect("the binary runs")
}
