//! Fuzzing `merge`: a sweep's shard records and part summaries are mutated at random (cut
//! short, a bit flipped, a byte replaced, a span deleted or doubled, a number edited), with
//! and without the part's content hash rewritten to match (as a careless copy or a forger
//! would), and `merge` must either refuse (exit 2, a message naming a file, no output) or
//! write exactly the one-machine file. Never anything else: no other exit, no other bytes.
//!
//! A forger who rewrites the hash can edit a record into another that is just as consistent
//! (an impact count 9 made 7): no check of the files alone can see that, which is what
//! `--verify` is for. So a part whose hash was rewritten is merged with `--verify` on every
//! record, as a careful user merging parts from an untrusted place would.
//!
//! PROPTEST_CASES sets the number of cases (default 96, a few seconds).

use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};

use crate::common::{dicesim_in, dicesim_ok as ok, rehash_part as rehash};

/// How a file is damaged; positions are fractions of its length.
#[derive(Debug, Clone)]
enum Mutation {
    Cut(f64),
    FlipBit(f64, u8),
    SetByte(f64, u8),
    Delete(f64, usize),
    Double(f64, usize),
    /// Replaces the `n`th number in the text by `value`.
    EditNumber(usize, String),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let at = 0.0..1.0f64;
    prop_oneof![
        at.clone().prop_map(Mutation::Cut),
        (at.clone(), 0u8..8).prop_map(|(a, b)| Mutation::FlipBit(a, b)),
        (at.clone(), any::<u8>()).prop_map(|(a, b)| Mutation::SetByte(a, b)),
        (at.clone(), 1usize..200).prop_map(|(a, n)| Mutation::Delete(a, n)),
        (at, 1usize..200).prop_map(|(a, n)| Mutation::Double(a, n)),
        (
            0usize..400,
            prop_oneof![
                Just("0".to_string()),
                Just("-1".to_string()),
                Just("7".to_string()),
                Just("1e308".to_string()),
                Just("18446744073709551615".to_string()),
                Just("NaN".to_string()),
                (-100.0..100.0f64).prop_map(|x| x.to_string()),
            ]
        )
            .prop_map(|(n, v)| Mutation::EditNumber(n, v)),
    ]
}

fn apply(bytes: &[u8], m: &Mutation) -> Vec<u8> {
    let at = |f: f64| ((bytes.len() as f64 * f) as usize).min(bytes.len().saturating_sub(1));
    let mut b = bytes.to_vec();
    match m {
        Mutation::Cut(f) => b.truncate(at(*f)),
        Mutation::FlipBit(f, bit) => {
            let i = at(*f);
            b[i] ^= 1 << bit;
        }
        Mutation::SetByte(f, v) => {
            let i = at(*f);
            b[i] = *v;
        }
        Mutation::Delete(f, n) => {
            let i = at(*f);
            b.drain(i..(i + n).min(b.len()));
        }
        Mutation::Double(f, n) => {
            let i = at(*f);
            let span: Vec<u8> = b[i..(i + n).min(b.len())].to_vec();
            b.splice(i..i, span);
        }
        Mutation::EditNumber(n, value) => {
            let text = String::from_utf8_lossy(bytes);
            let mut spans = Vec::new();
            let mut start = None;
            for (i, c) in text.char_indices() {
                let numeric = c.is_ascii_digit() || c == '.' || c == '-' || c == 'e';
                match (numeric, start) {
                    (true, None) => start = Some(i),
                    (false, Some(s)) => {
                        spans.push(s..i);
                        start = None;
                    }
                    _ => {}
                }
            }
            if !spans.is_empty() {
                let span = spans[n % spans.len()].clone();
                let mut t = text.into_owned();
                t.replace_range(span, value);
                b = t.into_bytes();
            }
        }
    }
    b
}

/// The sweep's rolls: every one of them is rolled again when a part's hash was rewritten.
const ROLLS: &str = "60";

#[test]
fn merge_refuses_or_reproduces_the_one_machine_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A small sweep, as CSV and as Parquet, and its one-machine files.
    let sweep = ["batch", "--rolls", ROLLS];
    for ext in ["csv", "parquet"] {
        let one = format!("one.{ext}");
        ok(d, &[&sweep[..], &["--out", &one]].concat());
        for k in 0..3 {
            let shard = format!("{k}/3");
            let out = format!("{ext}/part-{k}.{ext}");
            std::fs::create_dir_all(d.join(ext)).unwrap();
            ok(d, &[&sweep[..], &["--shard", &shard, "--out", &out]].concat());
        }
    }
    let pristine: Vec<(String, Vec<u8>)> = ["csv", "parquet"]
        .iter()
        .flat_map(|ext| {
            (0..3).flat_map(move |k| {
                [
                    format!("{ext}/part-{k}.{ext}"),
                    format!("{ext}/part-{k}.part.json"),
                ]
            })
        })
        .map(|name| {
            let bytes = std::fs::read(d.join(&name)).unwrap();
            (name, bytes)
        })
        .collect();
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(96);
    let mut runner = TestRunner::new(Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    });
    let (refused, identical) = (std::cell::Cell::new(0u32), std::cell::Cell::new(0u32));
    let strategy = (0..pristine.len(), mutation(), any::<bool>());
    runner
        .run(&strategy, |(file, m, fix_hash)| {
            for (name, bytes) in &pristine {
                std::fs::write(d.join(name), bytes).unwrap();
            }
            let (name, bytes) = &pristine[file];
            std::fs::write(d.join(name), apply(bytes, &m)).unwrap();
            let ext = name.split('/').next().unwrap();
            if fix_hash && !name.ends_with(".part.json") {
                rehash(&d.join(name.replace(&format!(".{ext}"), ".part.json")));
            }
            let out = d.join(format!("m.{ext}"));
            let _ = std::fs::remove_file(&out);
            let merged = format!("m.{ext}");
            let mut args = vec!["merge", ext, "--out", &merged];
            if fix_hash {
                args.extend(["--verify", ROLLS]);
            }
            let o = dicesim_in(d, &args);
            let err = String::from_utf8_lossy(&o.stderr);
            match o.status.code() {
                Some(0) => {
                    let one = std::fs::read(d.join(format!("one.{ext}"))).unwrap();
                    prop_assert!(
                        std::fs::read(&out).unwrap() == one,
                        "{name} {m:?}: merged other bytes"
                    );
                    identical.set(identical.get() + 1);
                }
                Some(2) => {
                    prop_assert!(err.starts_with("dicesim: "), "{err}");
                    prop_assert!(err.contains(ext), "names the file: {err}");
                    prop_assert!(!out.exists(), "a refusal writes nothing");
                    refused.set(refused.get() + 1);
                }
                c => prop_assert!(false, "{name} {m:?} (hash fixed: {fix_hash}): exit {c:?}: {err}"),
            }
            Ok(())
        })
        .unwrap();
    let (refused, identical) = (refused.get(), identical.get());
    eprintln!("merge fuzz: {cases} cases, {refused} refused, {identical} merged identically");
    assert_eq!(refused + identical, cases);
    assert!(refused > 0);
}
