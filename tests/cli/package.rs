//! The repository stands on its own: every file its code and docs name exists inside it, and
//! the declared rust-version is one every locked dependency builds with.

use std::path::{Path, PathBuf};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// Every text file of the project a reader meets: every crate's sources and tests, the
/// binary's, benches, docs, presets.
fn project_files() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).expect("readable folder") {
            let path = entry.expect("folder entry").path();
            if path.is_dir() {
                // Snapshots are rendered screens; the reference data has its own README.
                if !path.ends_with("snapshots") && !path.ends_with("data") {
                    walk(&path, out);
                }
            } else if path
                .extension()
                .is_some_and(|e| ["rs", "md", "toml"].contains(&e.to_str().unwrap_or_default()))
            {
                out.push(path);
            }
        }
    }
    let root = Path::new(ROOT);
    let mut files = vec![
        root.join("README.md"),
        root.join("ARCHITECTURE.md"),
        root.join("Cargo.toml"),
        root.join(".ci/run"),
    ];
    for dir in ["crates", "src", "tests", "benches", "docs", "presets"] {
        walk(&root.join(dir), &mut files);
    }
    files
}

#[test]
fn nothing_points_outside_the_repository() {
    for path in project_files() {
        if path.ends_with("tests/cli/package.rs") {
            continue; // the names below
        }
        let text = std::fs::read_to_string(&path).expect("text file");
        for outside in ["MODEL.md", "PRESETS.md", "CRATES.md", "../shared"] {
            assert!(
                !text.contains(outside),
                "{} mentions `{outside}`, which is not in the repository",
                path.display()
            );
        }
    }
}

/// The targets of `[text](target)` links, without their `#fragment`, skipping web links.
fn link_targets(text: &str) -> Vec<&str> {
    text.match_indices("](")
        .filter_map(|(at, _)| {
            let rest = &text[at + 2..];
            let target = &rest[..rest.find(')')?];
            let target = target.split('#').next().unwrap_or_default();
            (!target.is_empty() && !target.contains("://")).then_some(target)
        })
        .collect()
}

#[test]
fn every_link_and_named_document_resolves() {
    let root = Path::new(ROOT);
    for path in project_files() {
        let text = std::fs::read_to_string(&path).expect("text file");
        let dir = path.parent().expect("a file's folder");
        // Rust doc links name items, not files.
        let links = if path.extension().is_some_and(|e| e == "md") {
            link_targets(&text)
        } else {
            Vec::new()
        };
        for target in links {
            assert!(
                dir.join(target).exists(),
                "{}: the link to `{target}` leads nowhere",
                path.display()
            );
        }
        // Documents named in prose or comments, relative to the repository's root.
        for doc in [
            "docs/model.md",
            "docs/presets.md",
            "crates/physics/tests/data/reference/README.md",
        ] {
            if names_path(&text, doc) {
                assert!(
                    root.join(doc).is_file(),
                    "{} names a missing {doc}",
                    path.display()
                );
            }
        }
    }
}

/// Whether `text` names `path` as a path of its own, not as the tail of a longer one
/// (`crates/physics/tests/data/…` names no root `tests/data/…`).
fn names_path(text: &str, path: &str) -> bool {
    text.match_indices(path).any(|(at, _)| {
        !text[..at]
            .chars()
            .next_back()
            .is_some_and(|c| c.is_alphanumeric() || "/._-".contains(c))
    })
}

/// `1.89` or `1.89.0` as comparable numbers.
fn version(text: &str) -> (u64, u64, u64) {
    let mut parts = text.split('.').map(|p| p.parse::<u64>().unwrap_or(0));
    (
        parts.next().unwrap_or(0),
        parts.next().unwrap_or(0),
        parts.next().unwrap_or(0),
    )
}

#[test]
fn no_locked_dependency_needs_a_newer_rust_than_declared() {
    // This platform's dependencies: those of other platforms need not be downloaded.
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".to_string());
    let about = std::process::Command::new(rustc)
        .arg("-vV")
        .output()
        .expect("rustc runs");
    let about = String::from_utf8_lossy(&about.stdout);
    let host = about
        .lines()
        .find_map(|l| l.strip_prefix("host: "))
        .expect("rustc -vV names the host");
    let output = std::process::Command::new(env!("CARGO"))
        .args(["metadata", "--format-version", "1", "--locked", "--offline"])
        .args(["--filter-platform", host])
        .current_dir(ROOT)
        .output()
        .expect("cargo runs");
    assert!(
        output.status.success(),
        "cargo metadata failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let metadata: serde_json::Value = serde_json::from_slice(&output.stdout).expect("metadata is JSON");
    let packages = metadata["packages"].as_array().expect("a package list");
    let ours = packages
        .iter()
        .find(|p| p["name"] == "dicesim")
        .and_then(|p| p["rust_version"].as_str())
        .expect("Cargo.toml declares a rust-version");
    // Only what a build of dicesim compiles: normal and build dependencies of the resolve.
    let resolve = &metadata["resolve"]["nodes"];
    let built: std::collections::HashSet<&str> = resolve
        .as_array()
        .expect("a resolve graph")
        .iter()
        .filter_map(|n| n["id"].as_str())
        .collect();
    let mut too_new = Vec::new();
    for p in packages {
        let id = p["id"].as_str().unwrap_or_default();
        if let Some(needs) = p["rust_version"].as_str()
            && built.contains(id)
            && version(needs) > version(ours)
        {
            too_new.push(format!("{} {} needs {needs}", p["name"], p["version"]));
        }
    }
    assert!(
        too_new.is_empty(),
        "rust-version {ours} is too old for: {too_new:?}"
    );
}
