//! `dicesim man`: a page for the program and one for every command, each with the options
//! and examples its `--help` shows, printed one at a time or written into a folder.

use super::common::{dicesim_in, dicesim_ok, dicesim_refused};
use std::path::Path;

/// The commands a `--help` lists (its `Commands:` section, without clap's `help`).
fn commands_in_help(help: &str) -> Vec<String> {
    help.lines()
        .skip_while(|l| l.trim() != "Commands:")
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|name| *name != "help")
        .map(str::to_string)
        .collect()
}

/// The long options a `--help` lists (`--rolls`, `--no-color`; `--help` and `--version` too).
fn options_in_help(help: &str) -> Vec<String> {
    help.lines()
        .skip_while(|l| l.trim() != "Options:")
        .filter_map(|l| {
            let l = l.trim_start();
            let l = l
                .strip_prefix("-")
                .and_then(|_| l.split(", ").last())
                .unwrap_or(l);
            l.starts_with("--")
                .then(|| l.split([' ', '=']).next().unwrap_or(l).to_string())
        })
        .collect()
}

/// Every command under `dicesim`, as the words that name it (`["presets", "save"]`), found
/// through `--help` alone.
fn every_command(dir: &Path) -> Vec<Vec<String>> {
    let mut all = Vec::new();
    let mut todo = vec![Vec::<String>::new()];
    while let Some(path) = todo.pop() {
        let mut args: Vec<&str> = path.iter().map(String::as_str).collect();
        args.push("--help");
        for name in commands_in_help(&dicesim_ok(dir, &args)) {
            let mut sub = path.clone();
            sub.push(name);
            todo.push(sub.clone());
            all.push(sub);
        }
    }
    all
}

#[test]
fn the_program_page_is_roff_and_names_every_command() {
    let dir = tempfile::tempdir().unwrap();
    let page = dicesim_ok(dir.path(), &["man"]);
    assert!(page.contains(".TH dicesim 1"), "{}", &page[..page.len().min(300)]);
    for section in [".SH NAME", ".SH SYNOPSIS", ".SH DESCRIPTION", ".SH SUBCOMMANDS"] {
        assert!(page.contains(section), "no {section}");
    }
    let commands = commands_in_help(&dicesim_ok(dir.path(), &["--help"]));
    assert!(
        commands.len() >= 10 && commands.iter().any(|c| c == "batch"),
        "{commands:?}"
    );
    for command in commands {
        assert!(page.contains(&format!("dicesim\\-{command}(1)")), "no {command}");
    }
}

#[test]
fn every_command_has_a_page_with_every_option_and_example_of_its_help() {
    let dir = tempfile::tempdir().unwrap();
    let pages = dir.path().join("man1");
    std::fs::create_dir(&pages).unwrap();
    let said = dicesim_ok(dir.path(), &["man", "--out-dir", "man1"]);
    let commands = every_command(dir.path());
    assert!(commands.iter().any(|c| c == &["presets", "save"]), "{commands:?}");
    // One page per command and the program's, nothing else.
    let mut expected: Vec<String> = commands
        .iter()
        .map(|words| format!("dicesim-{}.1", words.join("-")))
        .chain(["dicesim.1".to_string()])
        .collect();
    expected.sort();
    let mut written: Vec<String> = std::fs::read_dir(&pages)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    written.sort();
    assert_eq!(written, expected);
    assert!(
        said.contains(&format!("wrote {} manual pages", expected.len())),
        "{said}"
    );

    for words in &commands {
        let name = format!("dicesim-{}", words.join("-"));
        let page = std::fs::read_to_string(pages.join(format!("{name}.1"))).unwrap();
        let mut args: Vec<&str> = words.iter().map(String::as_str).collect();
        args.push("--help");
        let help = dicesim_ok(dir.path(), &args);
        assert!(
            page.contains(&format!(".TH {name} 1")),
            "{name}: {}",
            &page[..page.len().min(200)]
        );
        let options = options_in_help(&help);
        assert!(options.iter().any(|o| o == "--help"), "{name}: {options:?}");
        for option in options {
            // roff escapes each hyphen.
            let roff = option.replace('-', "\\-");
            assert!(
                page.contains(&format!("\\fB{roff}\\fR")),
                "{name}'s page lacks {option}"
            );
        }
        // The examples of its help, where it has some.
        if let Some((_, examples)) = help.split_once("Examples:\n") {
            let first = examples.lines().next().unwrap().trim();
            let first = first.split_whitespace().take(2).collect::<Vec<_>>().join(" ");
            assert!(
                page.contains("Examples:") && page.contains(&first.replace('-', "\\-")),
                "{name}'s page lacks the example `{first}`"
            );
        }
        // `dicesim man WORDS…` prints the same page.
        let mut args = vec!["man"];
        args.extend(words.iter().map(String::as_str));
        assert_eq!(
            dicesim_ok(dir.path(), &args),
            page,
            "dicesim man {}",
            words.join(" ")
        );
    }
}

#[test]
fn pages_in_a_folder_are_never_replaced_without_force_and_all_or_none_are_written() {
    let dir = tempfile::tempdir().unwrap();
    let pages = dir.path().join("man1");
    std::fs::create_dir(&pages).unwrap();
    std::fs::write(pages.join("dicesim-batch.1"), "mine").unwrap();
    let e = dicesim_refused(dir.path(), &["man", "--out-dir", "man1"]);
    assert!(
        e.contains("dicesim-batch.1: the file exists (--force replaces it)"),
        "{e}"
    );
    let left: Vec<_> = std::fs::read_dir(&pages).unwrap().collect();
    assert_eq!(left.len(), 1, "a refused run wrote pages");
    assert_eq!(
        std::fs::read_to_string(pages.join("dicesim-batch.1")).unwrap(),
        "mine"
    );

    dicesim_ok(dir.path(), &["man", "--out-dir", "man1", "--force"]);
    let batch = std::fs::read_to_string(pages.join("dicesim-batch.1")).unwrap();
    assert!(batch.contains(".TH dicesim-batch 1"), "{batch}");

    let e = dicesim_refused(dir.path(), &["man", "--out-dir", "missing"]);
    assert!(e.contains("the folder missing does not exist"), "{e}");
    assert!(!dir.path().join("missing").exists());
}

#[test]
fn a_page_of_no_such_command_is_refused_with_the_commands_there_are() {
    let dir = tempfile::tempdir().unwrap();
    let e = dicesim_refused(dir.path(), &["man", "bogus"]);
    assert!(
        e.contains("`dicesim` has no command `bogus`; its commands are roll, trace"),
        "{e}"
    );
    let e = dicesim_refused(dir.path(), &["man", "presets", "bogus"]);
    assert!(e.contains("its commands are list, show, save, path"), "{e}");
    let e = dicesim_refused(dir.path(), &["man", "roll", "x"]);
    assert!(e.contains("`dicesim roll` has no commands under it"), "{e}");
    assert!(
        dicesim_in(dir.path(), &["man", "batch", "--out-dir", "."])
            .status
            .code()
            == Some(2)
    );
}
