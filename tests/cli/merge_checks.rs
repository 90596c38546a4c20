//! What `merge` must never do: merge records that are damaged, mixed up or inconsistent
//! with their summaries. Each test reproduces one way a cluster job goes wrong (a file cut
//! short, another sweep's records, an edited cell, counts that disagree) and checks that
//! the merge is refused with a message naming the file and the problem, and writes nothing.
//!
//! A damaged file is first caught by its size and content hash; to reach the checks behind
//! them, most tests also rewrite the part's hash (as a careless copy or a forger would), so
//! the records themselves must be read and refused.

use crate::common::{dicesim_in, dicesim_ok as ok, dicesim_refused, rehash_part as rehash};
use std::path::Path;

/// Runs a merge that must be refused (exit 2) without writing `m.csv`; returns stderr.
fn refused(dir: &Path, args: &[&str]) -> String {
    let stderr = dicesim_refused(dir, args);
    assert!(!dir.join("m.csv").exists(), "a refused merge writes nothing");
    stderr
}

/// The p4 of the issue: the CSV parts of `batch --rolls 400 --shard K/4`, and the
/// one-machine file.
fn p4(d: &Path) {
    ok(d, &["batch", "--rolls", "400", "--out", "one.csv"]);
    std::fs::create_dir(d.join("p4")).unwrap();
    for k in 0..4 {
        ok(
            d,
            &[
                "batch",
                "--rolls",
                "400",
                "--shard",
                &format!("{k}/4"),
                "--out",
                &format!("p4/part-{k}.csv"),
            ],
        );
    }
}

/// Edits the part summary's JSON.
fn edit_part(part: &Path, edit: impl FnOnce(&mut serde_json::Value)) {
    let mut v: serde_json::Value = serde_json::from_slice(&std::fs::read(part).unwrap()).unwrap();
    edit(&mut v);
    std::fs::write(part, serde_json::to_vec_pretty(&v).unwrap()).unwrap();
}

/// Replaces row `row` (1-based among the records, after the header) of a CSV records file
/// with what `edit` makes of its cells.
fn edit_row(path: &Path, row: usize, edit: impl FnOnce(&mut Vec<String>)) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let mut cells: Vec<String> = lines[row].split(',').map(String::from).collect();
    edit(&mut cells);
    lines[row] = cells.join(",");
    std::fs::write(path, lines.join("\n") + "\n").unwrap();
}

/// The columns of a batch of random rolls: the spin as an angular velocity, each with its unit.
const HEADER: [&str; 20] = [
    "id",
    "height_cm",
    "velocity_x_cm_per_s",
    "velocity_y_cm_per_s",
    "velocity_z_cm_per_s",
    "angular_velocity_x_rad_per_s",
    "angular_velocity_y_rad_per_s",
    "angular_velocity_z_rad_per_s",
    "yaw_deg",
    "pitch_deg",
    "roll_deg",
    "start_face",
    "face",
    "status",
    "steps",
    "time_s",
    "impacts",
    "first_impact_steps",
    "first_impact_time_s",
    "first_impact_face_down",
];

fn col(name: &str) -> usize {
    HEADER.iter().position(|c| *c == name).unwrap()
}

fn merge_p4(d: &Path) -> String {
    refused(d, &["merge", "p4", "--out", "m.csv"])
}

#[test]
fn an_intact_sweep_still_merges_into_the_one_machine_bytes_and_verifies() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    p4(d);
    let text = ok(d, &["merge", "p4", "--out", "m.csv", "--verify", "40"]);
    assert_eq!(
        std::fs::read(d.join("m.csv")).unwrap(),
        std::fs::read(d.join("one.csv")).unwrap()
    );
    assert!(
        text.contains(
            "verified               40 records chosen at random, rolled again: identical bit for bit"
        ),
        "{text}"
    );
}

/// A spreadsheet that saves a part puts an invisible UTF-8 byte-order mark in front of it;
/// the mark is not part of the first line, so the part merges as it was.
#[test]
fn a_byte_order_mark_in_front_of_a_part_is_not_part_of_its_first_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    p4(d);
    let path = d.join("p4/part-2.csv");
    let mut bytes = "\u{feff}".as_bytes().to_vec();
    bytes.extend(std::fs::read(&path).unwrap());
    std::fs::write(&path, bytes).unwrap();
    rehash(&d.join("p4/part-2.part.json"));
    ok(d, &["merge", "p4", "--out", "m.csv"]);
    assert_eq!(
        std::fs::read(d.join("m.csv")).unwrap(),
        std::fs::read(d.join("one.csv")).unwrap()
    );
}

#[test]
fn a_cut_records_file_is_refused_by_its_size_and_by_its_last_row() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    p4(d);
    let path = d.join("p4/part-3.csv");
    let full = std::fs::read(&path).unwrap();
    std::fs::write(&path, &full[..full.len() - 30]).unwrap();
    let e = merge_p4(d);
    assert!(
        e.contains("p4/part-3.csv (records of p4/part-3.part.json): "),
        "{e}"
    );
    assert!(e.contains("the file was cut, extended or replaced"), "{e}");
    rehash(&d.join("p4/part-3.part.json"));
    let e = merge_p4(d);
    assert!(
        e.starts_with("dicesim: p4/part-3.csv: row ") && e.contains("the last line is cut short"),
        "{e}"
    );
}

#[test]
fn records_of_another_sweep_under_this_sweeps_part_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    p4(d);
    std::fs::create_dir(d.join("g1")).unwrap();
    ok(
        d,
        &[
            "batch",
            "--rolls",
            "400",
            "--seed",
            "7",
            "--shard",
            "1/4",
            "--out",
            "g1/part-1.csv",
        ],
    );
    std::fs::copy(d.join("g1/part-1.csv"), d.join("p4/part-1.csv")).unwrap();
    let e = merge_p4(d);
    assert!(
        e.contains("p4/part-1.csv (records of p4/part-1.part.json): ") && e.contains("the file was"),
        "{e}"
    );
    rehash(&d.join("p4/part-1.part.json"));
    // Under this sweep's sidecar, its first row's start is not seed 1's draw.
    let e = merge_p4(d);
    assert_eq!(
        e,
        "dicesim: p4/part-1.csv: row 2: roll 100: its start is not the one the sweep's seed draws for it (a record of another sweep, or an edited one)\n"
    );
    // Copied with its own sidecar, the provenance names seed 7: refused before any row.
    let ours = std::fs::read(d.join("p4/part-1.csv.meta.json")).unwrap();
    std::fs::copy(
        d.join("g1/part-1.csv.meta.json"),
        d.join("p4/part-1.csv.meta.json"),
    )
    .unwrap();
    let e = merge_p4(d);
    assert_eq!(
        e,
        "dicesim: p4/part-1.csv.meta.json: its provenance is not this sweep's: `preset.random.seed` is 7, expected 1 (records of another sweep or build)\n"
    );
    // Without its sidecar, a CSV part says so.
    std::fs::remove_file(d.join("p4/part-1.csv.meta.json")).unwrap();
    let e = merge_p4(d);
    assert!(
        e.starts_with("dicesim: p4/part-1.csv: its sidecar p4/part-1.csv.meta.json is missing: "),
        "{e}"
    );
    std::fs::write(d.join("p4/part-1.csv.meta.json"), ours).unwrap();
}

/// Parts rolled by builds of two commits are refused, both named, unless the user accepts
/// them; the merged file then names both builds.
#[test]
fn parts_of_two_builds_merge_only_when_accepted() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    p4(d);
    let part = d.join("p4/part-2.part.json");
    let this: String =
        serde_json::from_slice::<serde_json::Value>(&std::fs::read(&part).unwrap()).unwrap()["commit"]
            .as_str()
            .unwrap()
            .to_string();
    // As another build would have written the part and its records' sidecar.
    let other = "0123456789ab";
    edit_part(&part, |v| v["commit"] = other.into());
    let sidecar = d.join("p4/part-2.csv.meta.json");
    let mut meta: serde_json::Value = serde_json::from_slice(&std::fs::read(&sidecar).unwrap()).unwrap();
    meta["provenance"]["commit"] = other.into();
    std::fs::write(&sidecar, serde_json::to_string_pretty(&meta).unwrap() + "\n").unwrap();
    let e = merge_p4(d);
    assert!(
        e.contains(&format!(
            "p4/part-2.part.json was rolled by the build of commit {other}, p4/part-0.part.json by commit {this}"
        )) && e.contains("--accept-mixed-builds"),
        "{e}"
    );
    ok(
        d,
        &[
            "merge",
            "p4",
            "--out",
            "m.csv",
            "--accept-mixed-builds",
            "--verify",
            "20",
        ],
    );
    assert_eq!(
        std::fs::read(d.join("m.csv")).unwrap(),
        std::fs::read(d.join("one.csv")).unwrap()
    );
    let merged: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("m.csv.meta.json")).unwrap()).unwrap();
    assert_eq!(
        merged["provenance"]["commit"],
        format!("mixed builds: {this}, {other}")
    );
}

#[test]
fn edited_cells_are_refused_with_their_row_and_field() {
    type Edit = fn(&mut Vec<String>);
    let cases: [(&str, Edit, &str); 7] = [
        (
            "face 9",
            |c| c[col("face")] = "9".into(),
            "face 9 is not a face of this die (its faces read 1–6)",
        ),
        (
            "timeout where it settled",
            |c| {
                c[col("status")] = "timeout".into();
                c[col("face")] = String::new();
            },
            "with status `timeout`, but a roll times out at exactly",
        ),
        (
            "a mangled height",
            |c| c[col("height_cm")] = "-1x.73".into(),
            "`height_cm` = `-1x.73` is not valid",
        ),
        (
            "a row two columns short",
            |c| {
                c.truncate(14);
            },
            "14 cells, expected 20",
        ),
        (
            "a face the start does not put up",
            |c| {
                let f: u8 = c[col("start_face")].parse().unwrap();
                c[col("start_face")] = (f % 6 + 1).to_string();
            },
            "is not the face its start puts up",
        ),
        (
            "a time that is not its steps",
            |c| c[col("time_s")] = "12345.5".into(),
            "time_s 12345.5 is not",
        ),
        (
            // The largest count a cell holds: checking it must not overflow.
            "more impacts than a u64 can double",
            |c| c[col("impacts")] = u64::MAX.to_string(),
            "18446744073709551615 impacts in",
        ),
    ];
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    p4(d);
    let path = d.join("p4/part-2.csv");
    let intact = std::fs::read(&path).unwrap();
    for (what, edit, expected) in cases {
        std::fs::write(&path, &intact).unwrap();
        // Row 5 of shard 2 is roll 204, line 6 after the header; every row of the default
        // preset settles.
        edit_row(&path, 5, edit);
        rehash(&d.join("p4/part-2.part.json"));
        let e = merge_p4(d);
        assert!(
            e.starts_with("dicesim: p4/part-2.csv: row 6: ") && e.contains(expected),
            "{what}: {e}"
        );
    }
}

#[test]
fn a_flipped_bit_in_a_parquet_part_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for k in 0..2 {
        ok(
            d,
            &[
                "batch",
                "--rolls",
                "400",
                "--shard",
                &format!("{k}/2"),
                "--out",
                &format!("q{k}.parquet"),
            ],
        );
    }
    let path = d.join("q1.parquet");
    let intact = std::fs::read(&path).unwrap();
    // Every byte of the data pages (the first quarter of the file and more): a flip is
    // refused by the hash, and with the hash rewritten by the reader or the field checks,
    // or else changes nothing the merged file holds.
    ok(
        d,
        &["merge", "q0.part.json", "q1.part.json", "--out", "whole.csv"],
    );
    let whole = std::fs::read(d.join("whole.csv")).unwrap();
    let mut refusals = 0;
    for at in (8..intact.len() / 2).step_by(97) {
        let mut bytes = intact.clone();
        bytes[at] ^= 0x10;
        std::fs::write(&path, &bytes).unwrap();
        let e = refused(d, &["merge", "q0.part.json", "q1.part.json", "--out", "m.csv"]);
        assert!(e.contains("its content hash is"), "{e}");
        rehash(&d.join("q1.part.json"));
        let o = dicesim_in(d, &["merge", "q0.part.json", "q1.part.json", "--out", "m.csv"]);
        match o.status.code() {
            Some(0) => {
                assert_eq!(std::fs::read(d.join("m.csv")).unwrap(), whole, "byte {at}");
                std::fs::remove_file(d.join("m.csv")).unwrap();
            }
            Some(2) => {
                let e = String::from_utf8_lossy(&o.stderr);
                assert!(
                    e.starts_with("dicesim: q1.parquet: ") || e.starts_with("dicesim: q1.part.json: "),
                    "{e}"
                );
                refusals += 1;
            }
            c => panic!("byte {at}: exit {c:?}: {}", String::from_utf8_lossy(&o.stderr)),
        }
        std::fs::write(&path, &intact).unwrap();
        rehash(&d.join("q1.part.json"));
    }
    assert!(refusals > 0, "some flips change records");
}

#[test]
fn counts_that_disagree_with_each_other_or_the_records_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::create_dir(d.join("c")).unwrap();
    for k in 0..2 {
        ok(
            d,
            &[
                "batch",
                "--rolls",
                "200",
                "--shard",
                &format!("{k}/2"),
                "--part",
                &format!("c/s{k}.part.json"),
            ],
        );
    }
    let part = d.join("c/s1.part.json");
    let intact = std::fs::read(&part).unwrap();
    let m = |d: &Path| refused(d, &["merge", "c"]);
    edit_part(&part, |v| v["tally"]["status"]["settled"] = 50.into());
    assert_eq!(
        m(d),
        "dicesim: c/s1.part.json: its status counts add up to 50, but it counts 100 rolls\n"
    );
    std::fs::write(&part, &intact).unwrap();
    edit_part(&part, |v| {
        v["tally"]["faces"]["counts"][0] = u64::MAX.into();
    });
    let e = m(d);
    assert!(
        e.starts_with("dicesim: c/s1.part.json: its face counts add up to 1844674407370955"),
        "{e}"
    );
    std::fs::write(&part, &intact).unwrap();
    // Counts of another die (twenty, the six counted and fourteen zeros) for the cube's
    // setup: not one count per number it shows, however they add up.
    edit_part(&part, |v| {
        let faces = &mut v["tally"]["faces"]["counts"];
        let mut twenty = faces.as_array().unwrap().clone();
        twenty.resize(20, 0.into());
        *faces = twenty.into();
    });
    assert_eq!(
        m(d),
        "dicesim: c/s1.part.json: `tally`: 20 face counts, but its die shows 6 numbers (1–6)\n"
    );
    std::fs::write(&part, &intact).unwrap();
    for bad in [-1.0, 1e308] {
        edit_part(&part, |v| v["elapsed_s"] = bad.into());
        let e = m(d);
        assert!(
            e.contains("`elapsed_s` = ") && e.contains("is not a shard's duration"),
            "{e}"
        );
        std::fs::write(&part, &intact).unwrap();
    }
    edit_part(&part, |v| v["part_format"] = 0.into());
    assert!(m(d).contains("part format 0, which this program no longer reads"));

    // With records: a summary that agrees with itself but not with its records.
    p4(d);
    let part = d.join("p4/part-0.part.json");
    edit_part(&part, |v| {
        let faces = &mut v["tally"]["faces"]["counts"];
        let (a, b) = (faces[0].as_u64().unwrap(), faces[1].as_u64().unwrap());
        faces[0] = (a + 1).into();
        faces[1] = (b - 1).into();
    });
    let e = merge_p4(d);
    assert!(
        e.starts_with("dicesim: p4/part-0.part.json: its counts are not those of its records in p4/part-0.csv (faces: the summary says ["),
        "{e}"
    );
}

#[test]
fn a_consistent_forgery_is_caught_only_by_rolling_again() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    p4(d);
    // Swap the outcomes of two settled rolls with the same start face: every count stays.
    let path = d.join("p4/part-0.csv");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut rows: Vec<Vec<String>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    let outcome = col("face")..HEADER.len();
    let (a, b) = (0..rows.len())
        .flat_map(|a| (a + 1..rows.len()).map(move |b| (a, b)))
        .find(|&(a, b)| {
            let (ra, rb) = (&rows[a], &rows[b]);
            ra[col("start_face")] == rb[col("start_face")] && ra[col("face")] != rb[col("face")]
        })
        .expect("two rolls from one face ending on different faces");
    let (oa, ob) = (
        rows[a][outcome.clone()].to_vec(),
        rows[b][outcome.clone()].to_vec(),
    );
    rows[a].splice(outcome.clone(), ob);
    rows[b].splice(outcome, oa);
    let head: Vec<&str> = text.lines().take(1).collect();
    let body: Vec<String> = rows.iter().map(|r| r.join(",")).collect();
    std::fs::write(&path, format!("{}\n{}\n", head.join("\n"), body.join("\n"))).unwrap();
    rehash(&d.join("p4/part-0.part.json"));
    // Every check of form and counts passes ...
    ok(d, &["merge", "p4", "--out", "forged.csv"]);
    assert_ne!(
        std::fs::read(d.join("forged.csv")).unwrap(),
        std::fs::read(d.join("one.csv")).unwrap()
    );
    // ... and rolling every record again finds it.
    let e = refused(d, &["merge", "p4", "--out", "m.csv", "--verify", "400"]);
    // The first column that differs is the face the two rolls traded (their starts are
    // their own; row a now holds b's ending), in the file that holds the roll.
    assert_eq!(
        e,
        format!(
            "dicesim: p4/part-0.csv: --verify: roll {a} rolled again gives face = {}, but its record says {}: the records are not what this setup rolls\n",
            rows[b][col("face")],
            rows[a][col("face")]
        ),
    );
}

/// A map's cells are rolled again from their nodes' starts, as a batch's records are: two
/// cells' outcomes swapped pass every other check, and only rolling again finds them.
#[test]
fn merge_verify_rolls_map_cells_again() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let map = [
        "basin",
        "--x",
        "initial.angular_velocity.x:-60:60",
        "--y",
        "initial.height:5:20",
        "--res",
        "6x4",
    ];
    for k in 0..2 {
        let mut args = map.to_vec();
        let shard = format!("{k}/2");
        let out = format!("r{k}.csv");
        args.extend(["--shard", &shard, "--out", &out]);
        ok(d, &args);
    }
    let mut one = map.to_vec();
    one.extend(["--uniform", "--out", "one.csv"]);
    ok(d, &one);
    let parts = ["merge", "r0.part.json", "r1.part.json"];
    let text = ok(d, &[&parts[..], &["--out", "v.csv", "--verify", "24"]].concat());
    assert!(
        text.contains("verified            24 cells chosen at random, rolled again: identical bit for bit"),
        "{text}"
    );
    assert_eq!(
        std::fs::read(d.join("v.csv")).unwrap(),
        std::fs::read(d.join("one.csv")).unwrap()
    );
    // --verify without --out reads and rolls the cells all the same.
    let text = ok(d, &[&parts[..], &["--verify", "3"]].concat());
    assert!(text.contains("verified            3 cells"), "{text}");

    // Swap the outcomes (start_face..time_s) of two cells of r1 that start on the same face
    // and end on different ones: the face counts, the coordinates and the times all stay.
    let path = d.join("r1.csv");
    let intact = std::fs::read_to_string(&path).unwrap();
    let mut rows: Vec<Vec<String>> = intact
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    let (a, b) = (0..rows.len())
        .flat_map(|a| (a + 1..rows.len()).map(move |b| (a, b)))
        .find(|&(a, b)| rows[a][4] == rows[b][4] && rows[a][5] != rows[b][5])
        .expect("two cells from one face ending on different faces");
    let (oa, ob) = (rows[a][5..9].to_vec(), rows[b][5..9].to_vec());
    rows[a].splice(5..9, ob);
    rows[b].splice(5..9, oa);
    let head: Vec<&str> = intact.lines().take(1).collect();
    let body: Vec<String> = rows.iter().map(|r| r.join(",")).collect();
    std::fs::write(&path, format!("{}\n{}\n", head.join("\n"), body.join("\n"))).unwrap();
    rehash(&d.join("r1.part.json"));
    ok(d, &[&parts[..], &["--out", "forged.csv"]].concat());
    let e = refused(d, &[&parts[..], &["--out", "m.csv", "--verify", "24"]].concat());
    let (i, j) = (a % 6, 2 + a / 6);
    assert!(
        e.starts_with(&format!(
            "dicesim: --verify: cell ({i}, {j}) (initial.angular_velocity.x = "
        )) && e.ends_with("the cells are not what this setup rolls\n"),
        "{e}"
    );
}

#[test]
fn a_map_cell_moved_or_timed_impossibly_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let map = [
        "basin",
        "--x",
        "initial.angular_velocity.x:-60:60",
        "--y",
        "initial.height:5:20",
        "--res",
        "6x4",
    ];
    for k in 0..2 {
        let mut args = map.to_vec();
        let shard = format!("{k}/2");
        let out = format!("r{k}.csv");
        args.extend(["--shard", &shard, "--out", &out]);
        ok(d, &args);
    }
    let path = d.join("r1.csv");
    let intact = std::fs::read_to_string(&path).unwrap();
    let m = |d: &Path| refused(d, &["merge", "r0.part.json", "r1.part.json", "--out", "m.csv"]);
    for (column, value, expected) in [
        (2, "-59.0", "but the map's axes put it at (-60.0, "),
        (8, "1e308", "time_s 1e308 is not"),
        (8, "12345.5", "time_s 12345.5 is not"),
    ] {
        let mut lines: Vec<String> = intact.lines().map(String::from).collect();
        // Line 2: the first cell, after the header.
        let mut cells: Vec<String> = lines[1].split(',').map(String::from).collect();
        cells[column] = value.to_string();
        lines[1] = cells.join(",");
        std::fs::write(&path, lines.join("\n") + "\n").unwrap();
        let e = m(d);
        assert!(
            e.contains("r1.csv (records of r1.part.json): ") && e.contains("the file was"),
            "{e}"
        );
        rehash(&d.join("r1.part.json"));
        let e = m(d);
        assert!(
            e.starts_with("dicesim: r1.csv: line 2: ") && e.contains(expected),
            "{e}"
        );
    }
}

#[cfg(unix)]
#[test]
fn fifos_and_endless_files_are_refused_without_waiting() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    p4(d);
    nix::unistd::mkfifo(&d.join("x.part.json"), nix::sys::stat::Mode::S_IRWXU).unwrap();
    let e = refused(d, &["merge", "p4/part-0.part.json", "x.part.json"]);
    assert!(e.contains("x.part.json: not a regular file"), "{e}");
    std::fs::remove_file(d.join("p4/part-1.csv")).unwrap();
    nix::unistd::mkfifo(&d.join("p4/part-1.csv"), nix::sys::stat::Mode::S_IRWXU).unwrap();
    let e = merge_p4(d);
    assert!(
        e.contains("p4/part-1.csv (records of p4/part-1.part.json): not a regular file"),
        "{e}"
    );
    // A file of NUL bytes as records: one endless line, refused at its bound.
    std::fs::remove_file(d.join("p4/part-1.csv")).unwrap();
    std::fs::write(d.join("p4/part-1.csv"), vec![0u8; 200_000]).unwrap();
    rehash(&d.join("p4/part-1.part.json"));
    let e = merge_p4(d);
    assert!(
        e.starts_with("dicesim: p4/part-1.csv: row 1: a line longer than 65536 bytes"),
        "{e}"
    );
}

#[test]
fn outputs_that_clash_with_each_other_or_the_inputs_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    p4(d);
    let e = refused(d, &["merge", "p4", "--out", "m.csv", "--out", "./m.csv"]);
    assert_eq!(
        e,
        "dicesim: --out ./m.csv: named twice as an output (it would be written and then refused)\n"
    );
    let shard = std::fs::read(d.join("p4/part-1.csv")).unwrap();
    let e = refused(d, &["merge", "p4", "--out", "p4/part-1.csv", "--force"]);
    assert_eq!(
        e,
        "dicesim: --out p4/part-1.csv: this command reads it (the records of p4/part-1.part.json); write the result elsewhere\n"
    );
    assert_eq!(std::fs::read(d.join("p4/part-1.csv")).unwrap(), shard);
    let o = dicesim_in(
        d,
        &["predict", "--rolls", "2", "--out", "c.csv", "--out", "c.csv"],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("c.csv: named twice as an output"));
    assert!(!d.join("c.csv").exists());
}
