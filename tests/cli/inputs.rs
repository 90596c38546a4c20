//! Bad sizes and bad preset files from the command line: refused at once with one clear line
//! and exit status 2, never a hang, an allocation failure or raw control characters.

use std::path::Path;
use std::process::{Command, Output};

fn dicesim_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_dicesim"))
        .args(args)
        .current_dir(dir)
        .env("DICESIM_PRESETS", dir.join("user-presets"))
        .output()
        .expect("the binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn refused(o: &Output, says: &str) {
    assert_eq!(o.status.code(), Some(2), "{}", stderr(o));
    assert_eq!(stderr(o).lines().count(), 1, "{}", stderr(o));
    assert!(stderr(o).contains(says), "{}", stderr(o));
}

#[test]
fn sizes_beyond_the_limits_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let o = dicesim_in(dir.path(), &["batch", "--rolls", "1000000000000"]);
    refused(&o, "--rolls 1000000000000: at most 10¹¹ rolls per batch");
    let o = dicesim_in(dir.path(), &["batch", "--rolls", "10", "--jobs", "100000"]);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    refused(
        &o,
        &format!(
            "--jobs 100000: at most {} (4 × the {cores} cores here)",
            4 * cores
        ),
    );
    let o = dicesim_in(
        dir.path(),
        &[
            "basin",
            "--x",
            "initial.height:1:2",
            "--y",
            "ground.friction:0:1",
            "--res",
            "10000x10000",
        ],
    );
    refused(&o, "--res 10000x10000: 100000000 cells would need about");
    assert!(stderr(&o).contains("GB of memory"), "{}", stderr(&o));
}

#[test]
fn over_long_arrays_in_a_file_are_refused_as_set_refuses_them() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("long.toml");
    std::fs::write(&file, "[initial]\nvelocity = [1, 2, 3, \"junk\", {a = 1}]\n").unwrap();
    let o = dicesim_in(dir.path(), &["roll", "--preset", "long.toml"]);
    refused(&o, "long.toml:2:");
    assert!(stderr(&o).contains("key `initial.velocity`"), "{}", stderr(&o));
    assert!(stderr(&o).contains("invalid length"), "{}", stderr(&o));
    let o = dicesim_in(dir.path(), &["roll", "--set", "initial.velocity=[1,2,3,4]"]);
    refused(&o, "invalid length");
}

#[cfg(unix)]
#[test]
fn special_files_are_never_read_as_presets() {
    let dir = tempfile::tempdir().unwrap();
    let o = dicesim_in(dir.path(), &["roll", "--preset", "/dev/zero"]);
    refused(&o, "/dev/zero: not a regular file");
    let user = dir.path().join("user-presets");
    std::fs::create_dir(&user).unwrap();
    let fifo = user.join("pipe.toml");
    nix::unistd::mkfifo(&fifo, nix::sys::stat::Mode::S_IRWXU).unwrap();
    std::fs::write(user.join("huge.toml"), vec![b'#'; 2 * 1024 * 1024]).unwrap();
    // A hang here would be the FIFO being opened.
    let o = dicesim_in(dir.path(), &["presets", "list"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let list = String::from_utf8_lossy(&o.stdout).into_owned();
    let line = |name: &str| {
        list.lines()
            .find(|l| l.starts_with(name))
            .unwrap_or_default()
            .to_string()
    };
    assert!(line("pipe ").contains("not a regular file"), "{list}");
    assert!(
        line("huge ").contains("larger than the 1048576 bytes allowed"),
        "{list}"
    );
    assert!(line("paper ").contains("shipped"), "{list}");
}

#[test]
fn control_characters_never_reach_the_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let user = dir.path().join("user-presets");
    std::fs::create_dir(&user).unwrap();
    std::fs::write(
        user.join("title.toml"),
        "description = \"retitled \\u001b]0;pwned\\u0007 window\"\n",
    )
    .unwrap();
    let o = dicesim_in(dir.path(), &["presets", "list"]);
    let list = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(!list.contains('\u{1b}') && !list.contains('\u{7}'), "{list:?}");
    assert!(list.contains("retitled \\u{1b}]0;pwned\\u{7} window"), "{list}");
    let o = dicesim_in(dir.path(), &["roll", "--set", "ground.\u{1b}]0;x\u{7}=1"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!stderr(&o).contains('\u{1b}'), "{:?}", stderr(&o));
}

/// A small seeded generator (xorshift), so every run tries the same cases.
struct Seeded(u64);

impl Seeded {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Breaks a preset file one way: a byte replaced by a TOML-significant one, a line
/// duplicated (a duplicate key) or cut in half, a value replaced by one out of range or of
/// the wrong kind, or an over-long array.
fn mutate(text: &str, rng: &mut Seeded) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let values = [
        "1e309",
        "nan",
        "\"x\"",
        "[1,2,3,4]",
        "-1e300",
        "{a=1}",
        "[",
        "true",
    ];
    let i = rng.below(lines.len());
    let mut out: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    match rng.below(4) {
        0 => {
            let bytes = ["=", "[", "]", "\"", "{", ",", "\u{0}"];
            let line = &out[i];
            let at = rng.below(line.len() + 1);
            let at = (0..=at).rev().find(|&k| line.is_char_boundary(k)).unwrap_or(0);
            out[i] = format!("{}{}{}", &line[..at], bytes[rng.below(bytes.len())], &line[at..]);
        }
        1 => {
            let line = out[i].clone();
            out.insert(i, line);
        }
        2 => {
            let line = out[i].clone();
            out[i] = line[..line.len() / 2].to_string();
        }
        _ => {
            if let Some(eq) = out[i].find(" = ") {
                out[i] = format!("{} = {}", &out[i][..eq], values[rng.below(values.len())]);
            }
        }
    }
    out.join("\n")
}

#[test]
fn mutated_shipped_presets_are_refused_with_one_line_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let shipped: Vec<_> = std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("presets"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    let mut rng = Seeded(0x5eed_d1ce);
    let (mut refusals, mut cases) = (0, 0);
    for case in 0..160 {
        let source = &shipped[case % shipped.len()];
        let text = mutate(&std::fs::read_to_string(source).unwrap(), &mut rng);
        let name = format!("case-{case}.toml");
        let file = dir.path().join(&name);
        std::fs::write(&file, &text).unwrap();
        cases += 1;
        let parsed = dicesim_setup::preset::Preset::from_toml_str(&text, &name);
        let o = dicesim_in(dir.path(), &["presets", "show", &name]);
        let err = stderr(&o);
        assert!(!err.contains("panicked"), "{name}: {err}\n{text}");
        match parsed {
            Ok(_) => assert!(o.status.success(), "{name}: {err}\n{text}"),
            Err(e) => {
                refusals += 1;
                assert_eq!(o.status.code(), Some(2), "{name}: {err}\n{text}");
                assert_eq!(err.lines().count(), 1, "{name}: {err}");
                assert!(err.starts_with(&format!("dicesim: {name}")), "{name}: {err}");
                if let dicesim_setup::preset::PresetError::Syntax { at, .. } = &e {
                    assert!(at.line.is_some() && at.column.is_some(), "{name}: {err}");
                    let position = format!("{name}:{}:{}:", at.line.unwrap(), at.column.unwrap());
                    assert!(err.starts_with(&format!("dicesim: {position}")), "{name}: {err}");
                }
            }
        }
    }
    // Many mutations land in comments and change nothing; enough must break the file.
    assert!(
        refusals * 4 > cases,
        "only {refusals} of {cases} mutations were refused"
    );
}
