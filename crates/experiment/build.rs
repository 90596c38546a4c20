//! The build's identity, which every provenance and `dicesim --version` state: the commit the
//! program was built from, and `modified` when its tracked files differed from that commit.
//!
//! It is read from git when the crate is built. Without git or outside a checkout (a
//! packaged crate) it is the stated `unknown commit`; a packager who knows the commit can
//! give it in `DICESIM_COMMIT` (e.g. `DICESIM_COMMIT=1a2b3c4d5e6f`), which is used as given.
//!
//! The script runs again when git's HEAD or the checked-out branch move (a commit, a
//! checkout) and when the sources of this crate and of the crates under it change, which
//! rebuild this crate anyway; a change elsewhere is seen at the next of those. It does not
//! watch git's index: `git status` rewrites it whenever a file's times changed, and a stamp
//! that followed it would rebuild this crate and every crate above it at each `git status`.

use std::path::{Path, PathBuf};
use std::process::Command;

fn main() {
    println!("cargo:rerun-if-env-changed=DICESIM_COMMIT");
    let manifest = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let given = std::env::var("DICESIM_COMMIT")
        .ok()
        .filter(|c| !c.trim().is_empty());
    let commit = given.or_else(|| from_git(&manifest));
    let (commit, build) = match commit {
        Some(c) => (
            c.clone(),
            format!("commit {}", c.replace(" modified", ", modified")),
        ),
        None => ("unknown".to_string(), "unknown commit".to_string()),
    };
    // `1a2b3c4d5e6f`, `1a2b3c4d5e6f modified` or `unknown`; the words `--version` prints.
    println!("cargo:rustc-env=DICESIM_COMMIT={commit}");
    println!("cargo:rustc-env=DICESIM_BUILD={build}");
}

/// The commit of the checkout holding `dir` (12 hexadecimal digits), with ` modified` when a
/// tracked file differs from it; `None` outside a git checkout or without git.
fn from_git(dir: &Path) -> Option<String> {
    let git = |args: &[&str]| -> Option<String> {
        // No optional locks: `status` would otherwise refresh the index, which this script
        // watches, and so run itself again at every build.
        let out = Command::new("git")
            .arg("--no-optional-locks")
            .args(args)
            .current_dir(dir)
            .output()
            .ok()?;
        out.status
            .success()
            .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
    };
    // Only a checkout that holds this very file: an unpacked crate inside some other
    // repository (a home folder kept in git, a package under `target/`) has no commit.
    git(&["ls-files", "--error-unmatch", "build.rs"])?;
    let commit = git(&["rev-parse", "--short=12", "HEAD"])?;
    // A worktree's HEAD is its own, its branches the repository's: ask git where they are.
    let mut watched: Vec<String> = ["HEAD", "packed-refs"]
        .iter()
        .filter_map(|p| git(&["rev-parse", "--git-path", p]))
        .collect();
    if let Some(branch) = git(&["symbolic-ref", "-q", "HEAD"]) {
        watched.extend(git(&["rev-parse", "--git-path", &branch]));
    }
    let top = git(&["rev-parse", "--show-toplevel"]).map(PathBuf::from);
    for path in watched {
        let path = PathBuf::from(path);
        let path = if path.is_absolute() { path } else { dir.join(path) };
        // Cargo runs a script whose watched file is missing at every build. A branch only
        // in packed-refs gets its own file at its next commit, in the folder watched instead.
        let watch = if path.exists() {
            Some(path.as_path())
        } else if path.ends_with("packed-refs") {
            None
        } else {
            path.parent()
        };
        if let Some(watch) = watch {
            println!("cargo:rerun-if-changed={}", watch.display());
        }
    }
    if let Some(top) = &top {
        for sources in [
            "crates/physics/src",
            "crates/setup/src",
            "crates/experiment/src",
            "presets",
        ] {
            let path = top.join(sources);
            if path.exists() {
                println!("cargo:rerun-if-changed={}", path.display());
            }
        }
    }
    let changes = git(&["status", "--porcelain", "--untracked-files=no"])?;
    Some(if changes.is_empty() {
        commit
    } else {
        format!("{commit} modified")
    })
}
