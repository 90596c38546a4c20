//! The documentation's links lead somewhere: every relative link in the README,
//! ARCHITECTURE.md and `docs/` names a file that exists and, with a `#fragment`, a heading in
//! it.

use std::path::{Path, PathBuf};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, ' ' | '-' | '_'))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchors of a Markdown file's headings, outside code blocks.
fn anchors(text: &str) -> Vec<String> {
    let mut fenced = false;
    let mut out = Vec::new();
    for line in text.lines() {
        if line.starts_with("```") {
            fenced = !fenced;
        } else if !fenced && line.starts_with('#') {
            out.push(slug(line.trim_start_matches('#')));
        }
    }
    out
}

/// `[text](target)` links outside code blocks, without web links.
fn links(text: &str) -> Vec<String> {
    let mut fenced = false;
    let mut out = Vec::new();
    for line in text.lines() {
        if line.starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        for (at, _) in line.match_indices("](") {
            let rest = &line[at + 2..];
            if let Some(end) = rest.find(')') {
                let target = &rest[..end];
                if !target.contains("://") && !target.starts_with("mailto:") {
                    out.push(target.to_string());
                }
            }
        }
    }
    out
}

fn documents() -> Vec<PathBuf> {
    let root = Path::new(ROOT);
    let mut files = vec![root.join("README.md"), root.join("ARCHITECTURE.md")];
    for entry in std::fs::read_dir(root.join("docs")).expect("docs/") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "md") {
            files.push(path);
        }
    }
    files
}

#[test]
fn slugs_follow_githubs_rule() {
    assert_eq!(slug(" The model in brief"), "the-model-in-brief");
    assert_eq!(
        slug("Agreement with the authors' program"),
        "agreement-with-the-authors-program"
    );
    assert_eq!(slug("Every key"), "every-key");
    assert_eq!(anchors("# A\n```\n# not a heading\n```\n## B c\n"), ["a", "b-c"]);
}

#[test]
fn every_relative_link_resolves_to_a_file_and_heading() {
    let mut broken = Vec::new();
    let mut checked = 0;
    for doc in documents() {
        let text = std::fs::read_to_string(&doc).expect("readable");
        for target in links(&text) {
            let (file, fragment) = match target.split_once('#') {
                Some((f, a)) => (f, Some(a)),
                None => (target.as_str(), None),
            };
            let path = if file.is_empty() {
                doc.clone()
            } else {
                doc.parent().expect("folder").join(file)
            };
            checked += 1;
            if !path.exists() {
                broken.push(format!("{}: `{target}`: no such file", doc.display()));
                continue;
            }
            if let Some(anchor) = fragment {
                let heads = anchors(&std::fs::read_to_string(&path).unwrap_or_default());
                if !heads.iter().any(|h| h == anchor) {
                    broken.push(format!("{}: `{target}`: no heading `#{anchor}`", doc.display()));
                }
            }
        }
    }
    assert!(checked > 20, "only {checked} links found");
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

/// The front page stays a front page.
#[test]
fn the_readme_is_at_most_400_lines() {
    let lines = include_str!("../../README.md").lines().count();
    assert!(lines <= 400, "README.md has {lines} lines");
}

// The documents that repeat what a crate defines. Each crate's package carries only what it
// owns, so the checks that hold a repository document to a crate live here.

/// The text of a repository file.
fn read(path: &str) -> String {
    std::fs::read_to_string(Path::new(ROOT).join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The README's lesson section as the explorer's lesson file (`crates/explorer/lesson.toml`,
/// whose steps the explorer's tests press) gives it.
#[test]
fn the_readmes_lesson_is_the_explorers_lesson_file() {
    let lesson: toml::Table = toml::from_str(&read("crates/explorer/lesson.toml")).expect("the lesson reads");
    let text = |table: &toml::Table, key: &str| -> String {
        table[key]
            .as_str()
            .unwrap_or_else(|| panic!("lesson.toml: `{key}` is not a string"))
            .trim()
            .to_string()
    };
    let mut expected = format!("## In the classroom\n\n{}\n\n", text(&lesson, "intro"));
    let steps = lesson["step"].as_array().expect("lesson.toml: [[step]] tables");
    assert!(steps.len() >= 5, "{} steps", steps.len());
    for (i, step) in steps.iter().enumerate() {
        let step = step.as_table().expect("a step is a table");
        let body = text(step, "text").replace('\n', "\n   ");
        expected.push_str(&format!("{}. **{}**\n   {body}\n", i + 1, text(step, "title")));
    }
    assert!(
        read("README.md").contains(&expected),
        "README.md's lesson differs from crates/explorer/lesson.toml; it should read:\n\n{expected}"
    );
}

/// The README's picture of the explorer is the explorer's snapshot of the `paper` roll at its
/// first impact (which the explorer's tests draw and compare).
#[test]
fn the_readmes_screenshot_is_the_explorers_first_impact_snapshot() {
    let snapshot = read(
        "crates/explorer/src/tui/render/snapshots/dicesim_explorer__tui__render__render_tests__mid_impact_120x36.snap",
    );
    // insta's header, then one quoted line per row of the screen.
    let (_, screen) = snapshot
        .strip_prefix("---\n")
        .and_then(|rest| rest.split_once("\n---\n"))
        .expect("an insta snapshot");
    let drawn: Vec<&str> = screen
        .lines()
        .map(|l| {
            l.strip_prefix('"')
                .and_then(|l| l.strip_suffix('"'))
                .expect("a quoted row")
                .trim_end()
        })
        .collect();
    assert_eq!(drawn.len(), 36);
    let readme = read("README.md");
    let block = readme
        .split_once("The `paper` preset's roll caught at its first impact:")
        .and_then(|(_, after)| after.split_once("```text\n"))
        .and_then(|(_, rest)| rest.split_once("```"))
        .expect("the README shows the explorer in a text block")
        .0;
    let shown: Vec<&str> = block.lines().map(str::trim_end).collect();
    assert_eq!(
        shown,
        drawn,
        "README.md's screenshot should read:\n{}",
        drawn.join("\n")
    );
}

/// docs/explorer.md's key tables are the explorer's key table, `crates/explorer/src/tui/vocabulary/key_table.rs`.
#[test]
fn the_explorer_docs_key_tables_are_the_key_table() {
    let expected = dicesim_explorer::tui::markdown_tables();
    assert!(expected.matches("\n|").count() > 30, "{expected}");
    assert!(
        read("docs/explorer.md").contains(&expected),
        "docs/explorer.md's key tables differ from crates/explorer/src/tui/vocabulary/key_table.rs; they should read:\n\n{expected}"
    );
}

/// docs/presets.md's table of keys is the parameter registry's.
#[test]
fn the_preset_docs_table_is_the_registrys() {
    let expected = dicesim_setup::registry::markdown_table();
    assert_eq!(
        expected.lines().count(),
        dicesim_setup::registry::ALL.len() + 2,
        "{expected}"
    );
    assert!(
        read("docs/presets.md").contains(&expected),
        "docs/presets.md's table of preset keys differs from the registry; it should read:\n{expected}"
    );
}

/// docs/dice.md's table of each die (each face's normal, its number and the number read with it
/// down) is the die the physics builds.
#[test]
fn the_tables_in_the_docs_are_the_dice() {
    let text = read("docs/dice.md");
    for kind in dicesim_physics::polyhedron::DieKind::ALL {
        let die = kind.standard();
        let heading = format!("### {}\n", kind.name());
        let section = text
            .split(&heading)
            .nth(1)
            .unwrap_or_else(|| panic!("no table for {}", kind.name()));
        let rows: Vec<Vec<String>> = section
            .lines()
            .take_while(|l| !l.starts_with("### "))
            .filter(|l| l.starts_with("| ") && !l.starts_with("| face"))
            .map(|l| {
                l.trim_matches('|')
                    .split(" | ")
                    .map(|c| c.trim().replace('−', "-"))
                    .collect()
            })
            .collect();
        assert_eq!(
            rows.len(),
            die.shape().faces().len(),
            "{}: one row per face",
            kind.name()
        );
        for row in rows {
            let normal: Vec<f64> = row[1]
                .trim_matches(|c| c == '(' || c == ')')
                .split(", ")
                .map(|x| x.parse().expect("a number"))
                .collect();
            let normal = nalgebra::Vector3::new(normal[0], normal[1], normal[2]);
            let f = die.face_most_nearly_down(&normal);
            assert!(
                (die.shape().faces()[f].normal - normal).norm() < 1e-4,
                "{}: no face {normal}",
                kind.name()
            );
            assert_eq!(
                row[2],
                die.numbering().numbers[f].to_string(),
                "{}: face {normal}",
                kind.name()
            );
            assert_eq!(
                row[3],
                die.numbering().read_with_down(f).to_string(),
                "{}: face {normal}",
                kind.name()
            );
        }
    }
}
