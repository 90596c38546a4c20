//! No source file imports another that imports it back, directly or through others: within
//! each crate the files form layers too (ARCHITECTURE.md). Test modules aside: files named
//! `tests.rs` or `*_tests.rs` and `#[cfg(test)]` items are not read.
//!
//! An import is any path to another file's item: a `use` (grouped, nested, renamed, glob,
//! `pub use` alike) or a `crate::…`, `super::…`, `self::…` or child-module path in code. A path
//! through a re-export leads to the file that defines the item, so a `mod.rs` that only
//! re-exports ties no file to another.

use std::collections::{BTreeMap, BTreeSet, VecDeque};
use std::path::{Path, PathBuf};

/// What a file's text means to its imports: names, `::` and punctuation. Comments, string
/// and character literals and numbers are gone, so a path quoted in them imports nothing.
#[derive(Clone, Debug, PartialEq)]
enum Token {
    Word(String),
    PathSep,
    Punct(char),
}

fn tokens(text: &str) -> Vec<Token> {
    let c: Vec<char> = text.chars().collect();
    let at = |i: usize| c.get(i).copied().unwrap_or('\0');
    let word_char = |ch: char| ch.is_alphanumeric() || ch == '_';
    let mut out = Vec::new();
    let mut i = 0;
    while i < c.len() {
        let ch = c[i];
        if ch.is_whitespace() {
            i += 1;
        } else if ch == '/' && at(i + 1) == '/' {
            while i < c.len() && c[i] != '\n' {
                i += 1;
            }
        } else if ch == '/' && at(i + 1) == '*' {
            // Block comments nest.
            let mut depth = 0;
            while i < c.len() {
                if c[i] == '/' && at(i + 1) == '*' {
                    depth += 1;
                    i += 2;
                } else if c[i] == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if ch == '"' {
            i = after_string(&c, i);
        } else if ch == '\'' {
            i = after_quote(&c, i);
        } else if let Some(end) = after_raw_string(&c, i) {
            i = end;
        } else if ch.is_ascii_digit() {
            while i < c.len() && word_char(c[i]) {
                i += 1;
            }
        } else if word_char(ch) {
            let start = i;
            while i < c.len() && word_char(c[i]) {
                i += 1;
            }
            let word: String = c[start..i].iter().collect();
            // `b"…"`, `c"…"` and `b'x'`: the prefix belongs to the literal after it.
            let prefix = matches!(word.as_str(), "b" | "c") && (at(i) == '"' || at(i) == '\'');
            if !prefix {
                out.push(Token::Word(word));
            }
        } else if ch == ':' && at(i + 1) == ':' {
            out.push(Token::PathSep);
            i += 2;
        } else {
            out.push(Token::Punct(ch));
            i += 1;
        }
    }
    out
}

/// The index after the string literal opening at `i`.
fn after_string(c: &[char], i: usize) -> usize {
    let mut j = i + 1;
    while j < c.len() {
        match c[j] {
            '\\' => j += 2,
            '"' => return j + 1,
            _ => j += 1,
        }
    }
    c.len()
}

/// The index after the character literal opening at `i`, or after the `'` of a lifetime
/// or label (whose name is then read as a word).
fn after_quote(c: &[char], i: usize) -> usize {
    if c.get(i + 1) == Some(&'\\') {
        let mut j = i + 3;
        while j < c.len() && c[j] != '\'' {
            j += 1;
        }
        j + 1
    } else if c.get(i + 2) == Some(&'\'') {
        i + 3
    } else {
        i + 1
    }
}

/// The index after a raw string literal (`r"…"`, `r#"…"#`, `br#"…"#`, …) opening at `i`.
fn after_raw_string(c: &[char], i: usize) -> Option<usize> {
    let mut j = i;
    if matches!(c.get(j), Some('b' | 'c')) {
        j += 1;
    }
    if c.get(j) != Some(&'r') {
        return None;
    }
    j += 1;
    let hashes = c[j..].iter().take_while(|&&ch| ch == '#').count();
    j += hashes;
    if c.get(j) != Some(&'"') {
        return None;
    }
    j += 1;
    while j < c.len() {
        if c[j] == '"' && c[j + 1..].iter().take(hashes).filter(|&&ch| ch == '#').count() == hashes {
            return Some(j + 1 + hashes);
        }
        j += 1;
    }
    Some(c.len())
}

fn is(token: Option<&Token>, punct: char) -> bool {
    token == Some(&Token::Punct(punct))
}

fn word(token: Option<&Token>) -> Option<&str> {
    match token {
        Some(Token::Word(w)) => Some(w),
        _ => None,
    }
}

/// The index after the bracket group opening at `open`.
fn after_group(t: &[Token], open: usize) -> usize {
    let mut nesting = 0usize;
    for (i, token) in t.iter().enumerate().skip(open) {
        match token {
            Token::Punct('(' | '[' | '{') => nesting += 1,
            Token::Punct(')' | ']' | '}') => {
                nesting -= 1;
                if nesting == 0 {
                    return i + 1;
                }
            }
            _ => {}
        }
    }
    t.len()
}

/// The index after the item starting at `i`: its `;` or its closing brace.
fn after_item(t: &[Token], mut i: usize) -> usize {
    let mut nesting = 0usize;
    while i < t.len() {
        match &t[i] {
            Token::Punct('(' | '[' | '{') => nesting += 1,
            Token::Punct(')' | ']') => nesting = nesting.saturating_sub(1),
            Token::Punct('}') => {
                nesting = nesting.saturating_sub(1);
                if nesting == 0 {
                    return i + 1;
                }
            }
            Token::Punct(';') if nesting == 0 => return i + 1,
            _ => {}
        }
        i += 1;
    }
    t.len()
}

/// One leaf of a `use` tree: the path, and the name it brings in (none for a glob or `_`).
#[derive(Clone, Debug, PartialEq)]
struct UseLeaf {
    path: Vec<String>,
    name: Option<String>,
    glob: bool,
}

/// Reads the `use` tree starting at `i` (after `use`) into `out`; returns the index after it.
fn use_tree(t: &[Token], mut i: usize, mut prefix: Vec<String>, out: &mut Vec<UseLeaf>) -> usize {
    loop {
        match t.get(i) {
            Some(Token::Punct('{')) => {
                i += 1;
                while i < t.len() && !is(t.get(i), '}') {
                    i = use_tree(t, i, prefix.clone(), out);
                    if is(t.get(i), ',') {
                        i += 1;
                    }
                }
                return i + 1;
            }
            Some(Token::Punct('*')) => {
                out.push(UseLeaf {
                    path: prefix,
                    name: None,
                    glob: true,
                });
                return i + 1;
            }
            Some(Token::PathSep) => i += 1,
            Some(Token::Word(segment)) => {
                prefix.push(segment.clone());
                i += 1;
                if t.get(i) == Some(&Token::PathSep) {
                    i += 1;
                    continue;
                }
                if prefix.last().is_some_and(|s| s == "self") {
                    prefix.pop();
                }
                let mut name = prefix.last().cloned();
                if word(t.get(i)) == Some("as") {
                    name = word(t.get(i + 1)).filter(|w| *w != "_").map(str::to_string);
                    i += 2;
                }
                out.push(UseLeaf {
                    path: prefix,
                    name,
                    glob: false,
                });
                return i;
            }
            _ => return i,
        }
    }
}

/// A module of a crate: the file it is written in, its place in the tree, and the names it
/// defines or brings in.
#[derive(Debug, Default)]
struct Module {
    file: usize,
    parent: Option<usize>,
    /// Where its child modules' files are.
    dir: PathBuf,
    children: BTreeMap<String, usize>,
    items: BTreeSet<String>,
    /// Names brought in by a module-level `use`, with their paths.
    uses: BTreeMap<String, Vec<String>>,
    globs: Vec<Vec<String>>,
}

/// A path written in a module, to be followed to the file it leads to.
#[derive(Debug)]
struct Reference {
    module: usize,
    path: Vec<String>,
    /// A glob brings in all a module has, not one name.
    glob: bool,
}

/// Where a path leads: a module, a named item of one, or out of the crate.
#[derive(Clone, Debug, PartialEq)]
enum Target {
    Module(usize),
    Item(usize, String),
    Outside,
}

/// One crate's source files, modules and the paths written in them.
#[derive(Debug, Default)]
struct Crate {
    files: Vec<PathBuf>,
    modules: Vec<Module>,
    references: Vec<Reference>,
}

const ITEM_KEYWORDS: [&str; 8] = [
    "struct", "enum", "union", "trait", "type", "fn", "const", "static",
];

/// Test modules are not part of the layers.
fn is_test_file(path: &Path) -> bool {
    path.file_stem()
        .and_then(|s| s.to_str())
        .is_some_and(|s| s == "tests" || s.ends_with("_tests"))
}

impl Crate {
    /// Reads the crate whose root file (`lib.rs` or `main.rs`) is `root`, following its
    /// `mod` declarations.
    fn read(root: &Path) -> Crate {
        let mut krate = Crate::default();
        krate.add_file(root.to_path_buf(), None);
        krate
    }

    fn add_file(&mut self, path: PathBuf, parent: Option<usize>) -> usize {
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or_default();
        let dir = if ["lib", "main", "mod"].contains(&stem) {
            path.parent().expect("a folder").to_path_buf()
        } else {
            path.with_extension("")
        };
        let file = self.files.len();
        self.files.push(path);
        let module = self.modules.len();
        self.modules.push(Module {
            file,
            parent,
            dir,
            ..Module::default()
        });
        let t = tokens(&text);
        self.body(&t, 0, module);
        module
    }

    /// Reads a module's body from `i` to its closing brace (or the file's end); returns the
    /// index after it.
    fn body(&mut self, t: &[Token], mut i: usize, module: usize) -> usize {
        let mut depth = 0usize;
        let mut test_only = false;
        while i < t.len() {
            if is(t.get(i), '#') {
                let open = if is(t.get(i + 1), '!') { i + 2 } else { i + 1 };
                let close = after_group(t, open);
                let attribute = &t[open..close];
                test_only |= word(attribute.get(1)) == Some("cfg")
                    && attribute.contains(&Token::Word("test".into()))
                    && !attribute.contains(&Token::Word("not".into()));
                i = close;
                continue;
            }
            if test_only {
                i = after_item(t, i);
                test_only = false;
                continue;
            }
            match &t[i] {
                Token::Punct('{') => depth += 1,
                Token::Punct('}') if depth == 0 => return i + 1,
                Token::Punct('}') => depth -= 1,
                Token::Word(w) if w == "mod" && depth == 0 => {
                    if let Some(name) = word(t.get(i + 1)) {
                        let name = name.to_string();
                        if is(t.get(i + 2), '{') {
                            let dir = self.modules[module].dir.join(&name);
                            let file = self.modules[module].file;
                            let child = self.modules.len();
                            self.modules.push(Module {
                                file,
                                parent: Some(module),
                                dir,
                                ..Module::default()
                            });
                            self.modules[module].children.insert(name, child);
                            i = self.body(t, i + 3, child);
                        } else {
                            self.declare(module, name);
                            i += 3;
                        }
                        continue;
                    }
                }
                Token::Word(w) if w == "use" => {
                    let mut leaves = Vec::new();
                    i = use_tree(t, i + 1, Vec::new(), &mut leaves);
                    for leaf in leaves {
                        if depth == 0 {
                            let m = &mut self.modules[module];
                            match &leaf.name {
                                _ if leaf.glob => m.globs.push(leaf.path.clone()),
                                Some(name) => {
                                    m.uses.insert(name.clone(), leaf.path.clone());
                                }
                                None => {}
                            }
                        }
                        self.references.push(Reference {
                            module,
                            path: leaf.path,
                            glob: leaf.glob,
                        });
                    }
                    continue;
                }
                Token::Word(w) if depth == 0 && ITEM_KEYWORDS.contains(&w.as_str()) => {
                    if let Some(name) = word(t.get(i + 1)) {
                        self.modules[module].items.insert(name.to_string());
                    }
                }
                Token::Word(first)
                    if t.get(i + 1) == Some(&Token::PathSep)
                        && t.get(i.wrapping_sub(1)) != Some(&Token::PathSep) =>
                {
                    let mut path = vec![first.clone()];
                    let mut j = i + 1;
                    while t.get(j) == Some(&Token::PathSep) {
                        let Some(segment) = word(t.get(j + 1)) else { break };
                        path.push(segment.to_string());
                        j += 2;
                    }
                    self.references.push(Reference {
                        module,
                        path,
                        glob: false,
                    });
                    i = j;
                    continue;
                }
                _ => {}
            }
            i += 1;
        }
        t.len()
    }

    /// `mod name;` in `module`: reads the child's file, unless it is a test module.
    fn declare(&mut self, module: usize, name: String) {
        let dir = self.modules[module].dir.clone();
        let path = [dir.join(format!("{name}.rs")), dir.join(&name).join("mod.rs")]
            .into_iter()
            .find(|p| p.is_file())
            .unwrap_or_else(|| panic!("`mod {name};` in {}: no file for it", dir.display()));
        if !is_test_file(&path) {
            let child = self.add_file(path, Some(module));
            self.modules[module].children.insert(name, child);
        }
    }

    /// Where `path`, written in `module`, leads. A path that starts with no module of the
    /// crate nor a name brought into `module` is another crate's (or a local name's).
    fn resolve(&self, module: usize, path: &[String], depth: u32) -> Target {
        // A `use` naming itself (`use nalgebra;`) would recurse forever.
        let Some((first, rest)) = path.split_first().filter(|_| depth <= 32) else {
            return Target::Outside;
        };
        match first.as_str() {
            "crate" => self.walk(0, rest, depth),
            "self" => self.walk(module, rest, depth),
            "super" => {
                let mut at = module;
                let mut rest = path;
                while rest.first().is_some_and(|s| s == "super") {
                    let Some(parent) = self.modules[at].parent else {
                        return Target::Outside;
                    };
                    at = parent;
                    rest = &rest[1..];
                }
                self.walk(at, rest, depth)
            }
            _ => {
                let m = &self.modules[module];
                if let Some(&child) = m.children.get(first) {
                    self.walk(child, rest, depth)
                } else if let Some(imported) = m.uses.get(first) {
                    match self.resolve(module, imported, depth + 1) {
                        Target::Module(at) => self.walk(at, rest, depth),
                        target => target,
                    }
                } else {
                    Target::Outside
                }
            }
        }
    }

    /// Follows `rest` down from `module`: through child modules, and through re-exports to
    /// the module that defines the item.
    fn walk(&self, module: usize, rest: &[String], depth: u32) -> Target {
        let Some((segment, deeper)) = rest.split_first() else {
            return Target::Module(module);
        };
        let found = self
            .find(module, segment, depth)
            .unwrap_or(Target::Item(module, segment.clone()));
        match found {
            Target::Module(at) if !deeper.is_empty() => self.walk(at, deeper, depth),
            target => target,
        }
    }

    /// The module or item `name` is in `module`, if the module defines or brings it in.
    fn find(&self, module: usize, name: &str, depth: u32) -> Option<Target> {
        if depth > 32 {
            return None;
        }
        let m = &self.modules[module];
        if let Some(&child) = m.children.get(name) {
            return Some(Target::Module(child));
        }
        if let Some(path) = m.uses.get(name) {
            return Some(self.resolve(module, path, depth + 1));
        }
        if m.items.contains(name) {
            return Some(Target::Item(module, name.to_string()));
        }
        m.globs
            .iter()
            .find_map(|glob| match self.resolve(module, glob, depth + 1) {
                Target::Module(at) => self.find(at, name, depth + 1),
                Target::Item(..) | Target::Outside => None,
            })
    }

    /// Every import from one file to another, as (from, to) → the names that tie them.
    fn imports(&self) -> BTreeMap<(usize, usize), BTreeSet<String>> {
        let mut edges: BTreeMap<(usize, usize), BTreeSet<String>> = BTreeMap::new();
        for r in &self.references {
            let (to, name) = match self.resolve(r.module, &r.path, 0) {
                Target::Module(at) => (self.modules[at].file, r.path.last().cloned().unwrap_or_default()),
                Target::Item(at, name) => (self.modules[at].file, name),
                Target::Outside => continue,
            };
            let from = self.modules[r.module].file;
            // A glob names no item: say what it was taken from.
            let name = if r.glob { format!("{name}::*") } else { name };
            if from != to {
                edges.entry((from, to)).or_default().insert(name);
            }
        }
        edges
    }
}

/// The circles of a directed graph: each largest set of two or more nodes that all reach one
/// another, sorted. A node reaching only itself is in none.
fn circles<N: Ord + Clone>(edges: &[(N, N)]) -> Vec<BTreeSet<N>> {
    let mut next: BTreeMap<&N, Vec<&N>> = BTreeMap::new();
    for (a, b) in edges {
        next.entry(a).or_default().push(b);
        next.entry(b).or_default();
    }
    let reach = |start: &N| -> BTreeSet<N> {
        let mut seen = BTreeSet::new();
        let mut queue: VecDeque<&N> = next[start].iter().copied().collect();
        while let Some(n) = queue.pop_front() {
            if seen.insert(n.clone()) {
                queue.extend(next[n].iter().copied());
            }
        }
        seen
    };
    let reached: BTreeMap<&N, BTreeSet<N>> = next.keys().map(|&n| (n, reach(n))).collect();
    let mut out: Vec<BTreeSet<N>> = Vec::new();
    for (&n, from_n) in &reached {
        let circle: BTreeSet<N> = from_n
            .iter()
            .filter(|m| reached[m].contains(n))
            .cloned()
            .collect();
        if circle.len() >= 2 && !out.contains(&circle) {
            out.push(circle);
        }
    }
    out.sort();
    out
}

/// The crates of the workspace, by their root files: the binary's and each library's.
fn crate_roots(root: &Path) -> Vec<PathBuf> {
    let mut roots: Vec<PathBuf> = std::fs::read_dir(root.join("crates"))
        .expect("a crates folder")
        .map(|e| e.expect("folder entry").path().join("src/lib.rs"))
        .filter(|p| p.is_file())
        .collect();
    roots.sort();
    roots.extend(
        ["src/lib.rs", "src/main.rs"]
            .map(|p| root.join(p))
            .into_iter()
            .filter(|p| p.is_file()),
    );
    roots
}

/// Each import circle of `krate`, as lines naming its files (relative to `shown_from`) and,
/// for each import between them, the names that tie them; and how many files are in circles.
fn circles_report(krate: &Crate, shown_from: &Path) -> (Vec<String>, usize) {
    let imports = krate.imports();
    let shown = |file: usize| {
        let path = &krate.files[file];
        path.strip_prefix(shown_from)
            .unwrap_or(path)
            .display()
            .to_string()
    };
    let edges: Vec<(usize, usize)> = imports.keys().copied().collect();
    let mut lines = Vec::new();
    let mut files = 0;
    for circle in circles(&edges) {
        files += circle.len();
        let names: Vec<String> = circle.iter().map(|&f| shown(f)).collect();
        lines.push(format!("{} files: {}", circle.len(), names.join(", ")));
        for ((from, to), names) in &imports {
            if circle.contains(from) && circle.contains(to) {
                let names: Vec<&str> = names.iter().map(String::as_str).collect();
                lines.push(format!(
                    "    {} → {}: {}",
                    shown(*from),
                    shown(*to),
                    names.join(", ")
                ));
            }
        }
    }
    (lines, files)
}

#[test]
fn no_source_file_imports_one_that_imports_it_back() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut report = Vec::new();
    let mut files_in_circles = 0;
    for crate_root in crate_roots(root) {
        let krate = Crate::read(&crate_root);
        // A reader that found no imports would find no circles either: it must see them.
        assert!(
            krate.files.len() < 3 || !krate.imports().is_empty(),
            "{}: {} files and not one import read",
            crate_root.display(),
            krate.files.len()
        );
        let (lines, files) = circles_report(&krate, root);
        report.extend(lines);
        files_in_circles += files;
    }
    assert!(
        report.is_empty(),
        "{files_in_circles} files are in import circles:\n{}",
        report.join("\n")
    );
}

#[test]
fn a_graph_without_a_way_back_has_no_circle() {
    assert!(circles(&[("a", "b"), ("b", "c"), ("a", "c"), ("c", "d")]).is_empty());
    assert!(circles::<&str>(&[]).is_empty());
}

#[test]
fn a_file_importing_itself_is_no_circle() {
    assert!(circles(&[("a", "a"), ("a", "b")]).is_empty());
}

#[test]
fn two_files_importing_each_other_are_a_circle() {
    assert_eq!(
        circles(&[("a", "b"), ("b", "a"), ("b", "c")]),
        [BTreeSet::from(["a", "b"])]
    );
}

#[test]
fn a_circle_through_others_is_found_whole_and_its_tail_left_out() {
    // t → a → b → c → a, and c → d: the circle is a, b, c; t and d are on no way back.
    let edges = [("t", "a"), ("a", "b"), ("b", "c"), ("c", "a"), ("c", "d")];
    assert_eq!(circles(&edges), [BTreeSet::from(["a", "b", "c"])]);
}

#[test]
fn separate_circles_are_named_apart_and_circles_sharing_a_file_are_one() {
    // a ↔ b, and c → d → e → c: two circles.
    let apart = [
        ("a", "b"),
        ("b", "a"),
        ("b", "c"),
        ("c", "d"),
        ("d", "e"),
        ("e", "c"),
    ];
    assert_eq!(
        circles(&apart),
        [BTreeSet::from(["a", "b"]), BTreeSet::from(["c", "d", "e"])]
    );
    // a → b → a and a → c → a share a: all three reach one another.
    let shared = [("a", "b"), ("b", "a"), ("a", "c"), ("c", "a")];
    assert_eq!(circles(&shared), [BTreeSet::from(["a", "b", "c"])]);
}

#[test]
fn literals_and_comments_hold_no_paths() {
    let t = tokens(
        "// use crate::a;\n/* crate::b /* nested */ crate::c */ let s = \"crate::d \\\" crate::e\";\n\
         let r = r#\"crate::f \"quoted\" \"#; let q = '\"'; let b = b'x'; fn f<'a>(x: &'a str) {}\n\
         let c = c\"crate::g\"; crate::h::H",
    );
    let words: Vec<&str> = t.iter().filter_map(|t| word(Some(t))).collect();
    assert_eq!(
        words,
        [
            "let", "s", "let", "r", "let", "q", "let", "b", "fn", "f", "a", "x", "a", "str", "let", "c",
            "crate", "h", "H"
        ]
    );
}

#[test]
fn a_use_tree_gives_every_leaf_its_path_and_name() {
    let t = tokens("use super::{x::{self, Y, Z as W}, v::*, u::T as _};");
    let mut leaves = Vec::new();
    let end = use_tree(&t, 1, Vec::new(), &mut leaves);
    assert!(is(t.get(end), ';'));
    let leaf = |path: &[&str], name: Option<&str>, glob| UseLeaf {
        path: path.iter().map(|s| s.to_string()).collect(),
        name: name.map(str::to_string),
        glob,
    };
    assert_eq!(
        leaves,
        [
            leaf(&["super", "x"], Some("x"), false),
            leaf(&["super", "x", "Y"], Some("Y"), false),
            leaf(&["super", "x", "Z"], Some("W"), false),
            leaf(&["super", "v"], None, true),
            leaf(&["super", "u", "T"], None, false),
        ]
    );
}

/// Writes `files` (path, text) under a new folder; returns the folder.
fn crate_of(files: &[(&str, &str)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (path, text) in files {
        let path = dir.path().join(path);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    dir
}

/// The imports of the crate in `dir` as "from → to: names" lines, sorted.
fn imports_of(dir: &Path) -> Vec<String> {
    let krate = Crate::read(&dir.join("lib.rs"));
    let shown = |f: usize| krate.files[f].strip_prefix(dir).unwrap().display().to_string();
    let mut lines: Vec<String> = (krate.imports().into_iter())
        .map(|((from, to), names)| {
            let names: Vec<String> = names.into_iter().collect();
            format!("{} → {}: {}", shown(from), shown(to), names.join(", "))
        })
        .collect();
    lines.sort();
    lines
}

#[test]
fn grouped_uses_and_paths_in_code_lead_to_the_defining_file_and_tests_are_not_read() {
    let dir = crate_of(&[
        (
            "lib.rs",
            "mod a;\nmod b;\nmod c;\nmod d;\n#[cfg(test)]\nmod tests;\nmod e_tests;\npub use a::Alpha;\n",
        ),
        (
            "a.rs",
            "use crate::{b::Beta, c::Gamma};\n// use crate::d::Delta;\nconst S: &str = \"crate::d::Delta\";\npub struct Alpha;\n",
        ),
        // Through the crate root's re-export to the file that defines Alpha.
        ("b.rs", "pub struct Beta;\nfn f() { let _ = crate::Alpha; }\n"),
        (
            "c.rs",
            "pub struct Gamma;\n#[cfg(test)]\nmod tests {\n    use crate::d::Delta;\n}\n#[cfg(test)]\nfn only_in_tests() { crate::a::Alpha; }\n",
        ),
        ("d.rs", "use super::c::*;\npub struct Delta;\n"),
        ("tests.rs", "use crate::a::Alpha;\nuse crate::d::Delta;\n"),
        ("e_tests.rs", "use crate::d::Delta;\n"),
    ]);
    assert_eq!(
        imports_of(dir.path()),
        [
            "a.rs → b.rs: Beta",
            "a.rs → c.rs: Gamma",
            "b.rs → a.rs: Alpha",
            "d.rs → c.rs: c::*",
            "lib.rs → a.rs: Alpha",
        ]
    );
    let krate = Crate::read(&dir.path().join("lib.rs"));
    let edges: Vec<(usize, usize)> = krate.imports().into_keys().collect();
    let names = |circle: &BTreeSet<usize>| -> Vec<String> {
        circle
            .iter()
            .map(|&f| krate.files[f].file_name().unwrap().to_string_lossy().into_owned())
            .collect()
    };
    let found: Vec<Vec<String>> = circles(&edges).iter().map(names).collect();
    assert_eq!(found, [["a.rs", "b.rs"]]);
}

#[test]
fn super_paths_in_a_folder_module_and_a_circle_report_naming_the_ties() {
    let dir = crate_of(&[
        ("lib.rs", "pub mod worker;\n"),
        ("worker/mod.rs", "mod live;\nmod twin;\npub struct Snapshot;\n"),
        (
            "worker/live.rs",
            "use super::twin::Twin;\nuse super::Snapshot;\npub fn played_out() {}\n\
             fn quote<'a>(s: &'a str) -> char { '\"' }\n",
        ),
        (
            "worker/twin.rs",
            "pub struct Twin;\nfn g() { super::live::played_out(); }\n\
             const TEXT: &str = r#\"use super::Snapshot;\"#;\n",
        ),
    ]);
    assert_eq!(
        imports_of(dir.path()),
        [
            "worker/live.rs → worker/mod.rs: Snapshot",
            "worker/live.rs → worker/twin.rs: Twin",
            "worker/twin.rs → worker/live.rs: played_out",
        ]
    );
    let (lines, files) = circles_report(&Crate::read(&dir.path().join("lib.rs")), dir.path());
    assert_eq!(files, 2);
    assert_eq!(
        lines,
        [
            "2 files: worker/live.rs, worker/twin.rs",
            "    worker/live.rs → worker/twin.rs: Twin",
            "    worker/twin.rs → worker/live.rs: played_out",
        ]
    );
}
