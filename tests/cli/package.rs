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
    let metadata = metadata(false);
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

/// `cargo metadata` of the workspace for this platform (those of other platforms need not be
/// downloaded), locked. Not offline: the Python module's dependencies are in the lock file but
/// not in a `cargo test` build, so a fresh cargo home has not fetched their manifests yet.
fn metadata(no_deps: bool) -> serde_json::Value {
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".to_string());
    let about = std::process::Command::new(rustc)
        .arg("-vV")
        .output()
        .expect("rustc runs");
    let about = String::from_utf8_lossy(&about.stdout);
    let host = about
        .lines()
        .find_map(|l| l.strip_prefix("host: "))
        .expect("rustc -vV names the host")
        .to_string();
    let mut command = std::process::Command::new(env!("CARGO"));
    command
        .args(["metadata", "--format-version", "1", "--locked"])
        .args(["--filter-platform", &host])
        .current_dir(ROOT);
    if no_deps {
        command.arg("--no-deps");
    }
    let output = command.output().expect("cargo runs");
    assert!(
        output.status.success(),
        "cargo metadata failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).expect("metadata is JSON")
}

/// The workspace's packages: name and folder.
fn members() -> Vec<(String, PathBuf)> {
    let metadata = metadata(true);
    let packages = metadata["packages"].as_array().expect("a package list");
    packages
        .iter()
        .map(|p| {
            let manifest = PathBuf::from(p["manifest_path"].as_str().expect("a manifest path"));
            let dir = manifest.parent().expect("the manifest's folder").to_path_buf();
            (p["name"].as_str().expect("a name").to_string(), dir)
        })
        .collect()
}

/// `path` without its `.` and `..` parts, without asking the file system (a link stays a link).
fn normalized(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for part in path.components() {
        match part {
            std::path::Component::ParentDir => {
                out.pop();
            }
            std::path::Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// The string literal that starts right after `at` in `text` (`"…"`), if one does.
fn literal_after(text: &str, at: usize) -> Option<&str> {
    let rest = text[at..].trim_start().strip_prefix('"')?;
    Some(&rest[..rest.find('"')?])
}

/// Each crate's package holds every file it embeds (`include_str!`, `include_bytes!`) and
/// every path its tests open under `CARGO_MANIFEST_DIR`, inside its own folder: a path that
/// climbs out of the crate, or a file its package leaves out, breaks the published crate's
/// build or tests (`.ci/package` builds and tests every package from itself).
#[test]
fn every_crate_packages_the_files_it_embeds_or_reads() {
    let mut checked = 0;
    let mut missing = Vec::new();
    for (name, dir) in members() {
        let listed = std::process::Command::new(env!("CARGO"))
            .args(["package", "-p", &name, "--list", "--allow-dirty"])
            .current_dir(ROOT)
            .output()
            .expect("cargo runs");
        assert!(
            listed.status.success(),
            "cargo package --list -p {name}: {}",
            String::from_utf8_lossy(&listed.stderr)
        );
        let listed = String::from_utf8(listed.stdout).expect("a UTF-8 list");
        let listed: Vec<&str> = listed.lines().collect();
        // What the package compiles and tests: the binary's `tests/` are the repository's own.
        let mut sources = Vec::new();
        for part in ["src", "tests", "benches"] {
            let folder = dir.join(part);
            if folder.is_dir() && listed.iter().any(|l| l.starts_with(&format!("{part}/"))) {
                walk_rs(&folder, &mut sources);
            }
        }
        for source in sources {
            let text = std::fs::read_to_string(&source).expect("a source file");
            let mut paths = Vec::new();
            for needle in ["include_str!(", "include_bytes!("] {
                for (at, _) in text.match_indices(needle) {
                    if let Some(file) = literal_after(&text, at + needle.len()) {
                        paths.push(normalized(&source.parent().expect("a folder").join(file)));
                    }
                }
            }
            for (at, _) in text.match_indices("env!(\"CARGO_MANIFEST_DIR\")") {
                let window = &text[at..(at + 120).min(text.len())];
                if let Some(join) = window.find(".join(")
                    && let Some(file) = literal_after(window, join + ".join(".len())
                {
                    paths.push(normalized(&dir.join(file)));
                }
            }
            for path in paths {
                checked += 1;
                let inside = path.strip_prefix(&dir).ok().and_then(|p| p.to_str());
                let packaged =
                    inside.is_some_and(|p| listed.iter().any(|l| *l == p || l.starts_with(&format!("{p}/"))));
                if !packaged {
                    missing.push(format!(
                        "{}: {} (package {name})",
                        source.display(),
                        path.display()
                    ));
                }
            }
        }
    }
    assert!(checked > 20, "only {checked} embedded or read paths found");
    assert!(
        missing.is_empty(),
        "files outside their crate's package:\n{}",
        missing.join("\n")
    );
}

fn walk_rs(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("readable folder") {
        let path = entry.expect("folder entry").path();
        if path.is_dir() {
            walk_rs(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Every package names where it comes from, and the binary's README sits at its package's
/// root as at the repository's: the registry resolves its relative links and images against
/// `repository`, so they reach the same files (files, not folders: it links them as blobs).
#[test]
fn every_package_names_its_repository_and_the_readmes_links_resolve_from_it() {
    let metadata = metadata(true);
    for p in metadata["packages"].as_array().expect("a package list") {
        let name = p["name"].as_str().unwrap_or_default();
        assert_eq!(p["repository"], "https://github.com/dicesim/dicesim", "{name}");
        assert_eq!(p["homepage"], "https://github.com/dicesim/dicesim", "{name}");
        for field in ["documentation", "description", "license", "rust_version"] {
            assert!(
                p[field].as_str().is_some_and(|v| !v.is_empty()),
                "{name}: no {field}"
            );
        }
        if name == "dicesim" {
            let manifest = PathBuf::from(p["manifest_path"].as_str().unwrap_or_default());
            assert_eq!(p["readme"].as_str(), Some("README.md"), "{name}");
            assert_eq!(
                manifest.parent(),
                Some(Path::new(ROOT)),
                "{name} sits at the root"
            );
        }
    }
    let readme = std::fs::read_to_string(Path::new(ROOT).join("README.md")).expect("README.md");
    let targets = link_targets(&readme);
    assert!(targets.iter().any(|t| t.ends_with(".gif")), "{targets:?}");
    for target in targets {
        assert!(
            Path::new(ROOT).join(target).is_file(),
            "README.md links `{target}`, which is not a file of the repository"
        );
    }
}

/// Dependencies carried for little stay out: color-eyre (18 crates for two `wrap_err`), the
/// dejavu crate (5.3 MB for two fonts, now embedded), and a second bitflags or miniz_oxide (png
/// 0.17 brought both).
#[test]
fn no_dependency_carried_for_little_and_no_second_bitflags_or_miniz_oxide() {
    let metadata = metadata(false);
    let packages = metadata["packages"].as_array().expect("a package list");
    let ours: Vec<&str> = packages
        .iter()
        .filter(|p| p["source"].is_null())
        .filter_map(|p| p["id"].as_str())
        .collect();
    // What the workspace's builds compile for this platform: normal and build dependencies.
    let nodes = metadata["resolve"]["nodes"].as_array().expect("a resolve graph");
    let edges = |id: &str| -> Vec<String> {
        nodes
            .iter()
            .find(|n| n["id"] == id)
            .and_then(|n| n["deps"].as_array())
            .into_iter()
            .flatten()
            .filter(|d| {
                d["dep_kinds"]
                    .as_array()
                    .is_some_and(|kinds| kinds.iter().any(|k| k["kind"].as_str() != Some("dev")))
            })
            .filter_map(|d| d["pkg"].as_str().map(str::to_string))
            .collect()
    };
    let mut built: std::collections::BTreeSet<String> = ours.iter().map(|s| s.to_string()).collect();
    let mut todo: Vec<String> = built.iter().cloned().collect();
    while let Some(id) = todo.pop() {
        for dep in edges(&id) {
            if built.insert(dep.clone()) {
                todo.push(dep);
            }
        }
    }
    let name_of = |id: &str| -> String {
        packages
            .iter()
            .find(|p| p["id"] == id)
            .and_then(|p| p["name"].as_str())
            .unwrap_or_default()
            .to_string()
    };
    let names: Vec<String> = built.iter().map(|id| name_of(id)).collect();
    assert!(
        names.iter().any(|n| n == "png"),
        "the graph was not walked: {names:?}"
    );
    for carried in ["color-eyre", "eyre", "dejavu"] {
        assert!(
            !names.iter().any(|n| n == carried),
            "{carried} is a dependency again"
        );
    }
    for single in ["bitflags", "miniz_oxide"] {
        let versions = names.iter().filter(|n| *n == single).count();
        assert!(
            versions <= 1,
            "{versions} versions of {single} are built (`cargo tree -d`)"
        );
    }
}
