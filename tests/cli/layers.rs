//! The crates are layers: each depends only on those below it, in the order ARCHITECTURE.md
//! gives on its `Layer order:` line, and the physics on nalgebra and serde alone. Read from
//! `cargo metadata`, so a dependency added in any Cargo.toml is seen.

use serde_json::Value;
use std::path::Path;

/// What the physics may build on: linear algebra, and the derives that let setups be read.
const PHYSICS_DEPENDENCIES: [&str; 2] = ["nalgebra", "serde"];

/// The one crate that may build on Python (pyo3): the module, so that `cargo test` at the
/// root and every other crate build without Python.
const PYTHON_MODULE: &str = "dicesim-python";

/// The crates in ARCHITECTURE.md's `Layer order:` line, lowest first.
fn layer_order(architecture: &str) -> Result<Vec<String>, String> {
    let lines: Vec<&str> = architecture
        .lines()
        .filter_map(|l| l.trim().strip_prefix("Layer order:"))
        .collect();
    let [line] = lines[..] else {
        return Err(format!(
            "ARCHITECTURE.md has {} `Layer order:` lines, not one",
            lines.len()
        ));
    };
    Ok(line
        .split('<')
        .map(|name| name.trim().trim_matches('`').to_string())
        .collect())
}

/// Every way the workspace in `metadata` (`cargo metadata --no-deps`) breaks the layers in
/// `order`: a crate the order does not place (or places twice), a name in it that is no
/// crate, a normal or build dependency on a crate at or above the dependent's layer, a
/// physics dependency other than nalgebra and serde, and pyo3 under any crate but the
/// Python module. Tests and benches (dev-dependencies) may use any crate.
fn violations(metadata: &Value, order: &[String]) -> Vec<String> {
    let packages = metadata["packages"]
        .as_array()
        .map(Vec::as_slice)
        .unwrap_or_default();
    let names: Vec<&str> = packages.iter().filter_map(|p| p["name"].as_str()).collect();
    let rank = |name: &str| order.iter().position(|n| n == name);
    let mut found = Vec::new();
    for name in &names {
        match order.iter().filter(|n| n == name).count() {
            1 => {}
            0 => found.push(format!("{name} has no place in the layer order")),
            n => found.push(format!("{name} is placed {n} times in the layer order")),
        }
    }
    for name in order {
        if !names.contains(&name.as_str()) {
            found.push(format!(
                "the layer order names {name}, which is no crate of the workspace"
            ));
        }
    }
    for package in packages {
        let name = package["name"].as_str().unwrap_or_default();
        let built_with = package["dependencies"]
            .as_array()
            .map(Vec::as_slice)
            .unwrap_or_default()
            .iter()
            .filter(|d| d["kind"].is_null() || d["kind"] == "build");
        for dependency in built_with {
            let on = dependency["name"].as_str().unwrap_or_default();
            if let (Some(at), Some(below)) = (rank(name), rank(on))
                && below >= at
            {
                found.push(format!("{name} depends on {on}, which is not below it"));
            }
            if on.starts_with("pyo3") && name != PYTHON_MODULE {
                found.push(format!(
                    "{name} depends on {on}: only {PYTHON_MODULE} may build on Python"
                ));
            }
            if name == "dicesim-physics" && !PHYSICS_DEPENDENCIES.contains(&on) {
                found.push(format!(
                    "dicesim-physics depends on {on}: only nalgebra and serde may be under the model"
                ));
            }
        }
    }
    found
}

#[test]
fn every_crate_depends_only_on_the_layers_below_it() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let architecture = std::fs::read_to_string(root.join("ARCHITECTURE.md")).expect("ARCHITECTURE.md");
    let order = layer_order(&architecture).unwrap();
    let output = std::process::Command::new(env!("CARGO"))
        .args(["metadata", "--format-version", "1", "--no-deps", "--offline"])
        .current_dir(root)
        .output()
        .expect("cargo runs");
    assert!(
        output.status.success(),
        "cargo metadata failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let metadata: Value = serde_json::from_slice(&output.stdout).expect("metadata is JSON");
    let found = violations(&metadata, &order);
    assert!(found.is_empty(), "the layers are broken:\n{}", found.join("\n"));
}

/// A workspace of `packages`: (name, [(dependency, kind)]) with kind "normal", "dev" or
/// "build", as `cargo metadata` writes them.
fn workspace(packages: &[(&str, &[(&str, &str)])]) -> Value {
    let packages: Vec<Value> = packages
        .iter()
        .map(|(name, dependencies)| {
            let dependencies: Vec<Value> = dependencies
                .iter()
                .map(|(on, kind)| {
                    let kind = if *kind == "normal" {
                        Value::Null
                    } else {
                        Value::from(*kind)
                    };
                    serde_json::json!({ "name": on, "kind": kind })
                })
                .collect();
            serde_json::json!({ "name": name, "dependencies": dependencies })
        })
        .collect();
    serde_json::json!({ "packages": packages })
}

fn order(names: &[&str]) -> Vec<String> {
    names.iter().map(|n| n.to_string()).collect()
}

#[test]
fn the_order_is_read_from_its_one_line() {
    let doc = "# Architecture\n\nSome text < with a sign.\n\nLayer order: `dicesim-physics` < `dicesim-setup` < `dicesim`\n";
    assert_eq!(
        layer_order(doc).unwrap(),
        order(&["dicesim-physics", "dicesim-setup", "dicesim"])
    );
    assert!(layer_order("# Architecture\n").is_err());
    assert!(layer_order("Layer order: a < b\nLayer order: b < a\n").is_err());
}

#[test]
fn a_dependency_on_a_lower_layer_or_only_for_tests_breaks_nothing() {
    let metadata = workspace(&[
        (
            "dicesim-physics",
            &[("nalgebra", "normal"), ("serde", "normal"), ("proptest", "dev")],
        ),
        (
            "dicesim-setup",
            &[("dicesim-physics", "normal"), ("toml", "normal")],
        ),
        // A lower crate's tests may drive a higher one.
        (
            "dicesim-experiment",
            &[("dicesim-setup", "normal"), ("dicesim", "dev")],
        ),
        (
            "dicesim",
            &[("dicesim-experiment", "normal"), ("dicesim-physics", "build")],
        ),
    ]);
    let layers = order(&[
        "dicesim-physics",
        "dicesim-setup",
        "dicesim-experiment",
        "dicesim",
    ]);
    assert_eq!(violations(&metadata, &layers), Vec::<String>::new());
}

#[test]
fn a_normal_or_build_dependency_upwards_or_sideways_is_named() {
    let metadata = workspace(&[
        ("dicesim-physics", &[("dicesim-setup", "normal")]),
        ("dicesim-setup", &[("dicesim-experiment", "build")]),
        ("dicesim-experiment", &[("dicesim-experiment", "normal")]),
    ]);
    let layers = order(&["dicesim-physics", "dicesim-setup", "dicesim-experiment"]);
    assert_eq!(
        violations(&metadata, &layers),
        [
            "dicesim-physics depends on dicesim-setup, which is not below it",
            "dicesim-physics depends on dicesim-setup: only nalgebra and serde may be under the model",
            "dicesim-setup depends on dicesim-experiment, which is not below it",
            "dicesim-experiment depends on dicesim-experiment, which is not below it",
        ]
    );
}

#[test]
fn the_physics_builds_on_nalgebra_and_serde_alone() {
    let metadata = workspace(&[(
        "dicesim-physics",
        &[
            ("nalgebra", "normal"),
            ("rand", "normal"),
            ("cc", "build"),
            ("proptest", "dev"),
        ],
    )]);
    assert_eq!(
        violations(&metadata, &order(&["dicesim-physics"])),
        [
            "dicesim-physics depends on rand: only nalgebra and serde may be under the model",
            "dicesim-physics depends on cc: only nalgebra and serde may be under the model",
        ]
    );
}

#[test]
fn only_the_python_module_builds_on_pyo3() {
    let metadata = workspace(&[
        (
            "dicesim-experiment",
            &[("pyo3", "normal"), ("pyo3-build-config", "build")],
        ),
        (
            "dicesim-python",
            &[("dicesim-experiment", "normal"), ("pyo3", "normal")],
        ),
    ]);
    let layers = order(&["dicesim-experiment", "dicesim-python"]);
    assert_eq!(
        violations(&metadata, &layers),
        [
            "dicesim-experiment depends on pyo3: only dicesim-python may build on Python",
            "dicesim-experiment depends on pyo3-build-config: only dicesim-python may build on Python",
        ]
    );
}

#[test]
fn a_crate_the_order_leaves_out_and_a_name_it_invents_are_named() {
    let metadata = workspace(&[("dicesim-physics", &[]), ("dicesim-plots", &[]), ("dicesim", &[])]);
    assert_eq!(
        violations(
            &metadata,
            &order(&["dicesim-physics", "dicesim-figures", "dicesim", "dicesim"])
        ),
        [
            "dicesim-plots has no place in the layer order",
            "dicesim is placed 2 times in the layer order",
            "the layer order names dicesim-figures, which is no crate of the workspace",
        ]
    );
}
