//! Helpers shared by the binary's tests: running it, forging a shard's part summary, reading
//! a PNG's text chunks and the authors' reference CSVs.

use dicesim_physics::InitialCondition;
use std::collections::HashMap;
use std::path::PathBuf;

/// One CSV file as rows of named numeric columns.
pub struct Table {
    pub rows: Vec<Vec<f64>>,
    index: HashMap<String, usize>,
}

impl Table {
    pub fn load(name: &str) -> Table {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("crates/physics/tests/data/reference")
            .join(name);
        let fail = |e: &dyn std::fmt::Display| -> ! { panic!("{}: {e}", path.display()) };
        let mut reader = csv::Reader::from_path(&path).unwrap_or_else(|e| fail(&e));
        let index = (reader.headers().unwrap_or_else(|e| fail(&e)).iter())
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

/// Runs `dicesim args` in `dir` and asserts that it succeeded; returns its stdout.
pub fn dicesim_ok(dir: &std::path::Path, args: &[&str]) -> String {
    let o = dicesim_in(dir, args);
    assert!(
        o.status.success(),
        "dicesim {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout).expect("stdout is UTF-8")
}

/// Runs `dicesim args` in `dir` and asserts a refusal for bad input (exit status 2); returns
/// its stderr.
pub fn dicesim_refused(dir: &std::path::Path, args: &[&str]) -> String {
    let o = dicesim_in(dir, args);
    let stderr = String::from_utf8(o.stderr).expect("stderr is UTF-8");
    assert_eq!(
        o.status.code(),
        Some(2),
        "dicesim {} should be refused: {stderr}",
        args.join(" ")
    );
    stderr
}

/// A records file's content hash as `part.json` states it: XXH64, seed 0, 16 hex digits
/// (computed by the twox-hash crate, not by dicesim).
pub fn records_hash(bytes: &[u8]) -> String {
    use std::hash::Hasher;
    let mut h = twox_hash::XxHash64::with_seed(0);
    h.write(bytes);
    format!("{:016x}", h.finish())
}

/// Makes a part summary agree with its records file's current bytes (size and hash), as a
/// forger would; leaves it alone when it no longer reads as JSON naming a readable records
/// file.
pub fn rehash_part(part: &std::path::Path) {
    let Ok(text) = std::fs::read(part) else { return };
    let Ok(mut v) = serde_json::from_slice::<serde_json::Value>(&text) else {
        return;
    };
    let Some(name) = v["records"].as_str() else { return };
    let Ok(bytes) = std::fs::read(part.parent().unwrap().join(name)) else {
        return;
    };
    v["records_bytes"] = bytes.len().into();
    v["records_hash"] = records_hash(&bytes).into();
    std::fs::write(part, serde_json::to_vec_pretty(&v).unwrap()).unwrap();
}

/// A PNG's iTXt chunks, keyword → text (read by the png decoder, not by dicesim).
pub fn png_text(path: &std::path::Path) -> std::collections::BTreeMap<String, String> {
    let file = std::fs::File::open(path).unwrap();
    let reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .unwrap();
    (reader.info().utf8_text.iter())
        .map(|c| (c.keyword.clone(), c.get_text().unwrap()))
        .collect()
}
