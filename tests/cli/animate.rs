//! `dicesim animate` as a user runs it: the face its file records and shows agrees with
//! `dicesim roll --json`, two runs write the same bytes, and bad input writes nothing.

use crate::common::{dicesim_ok as ok, dicesim_refused as refused, png_text};

#[test]
fn the_recorded_outcome_is_the_rolls_own() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for preset in ["paper", "loaded-corner", "icy-table"] {
        let roll: serde_json::Value =
            serde_json::from_str(&ok(d, &["roll", "--preset", preset, "--json"])).unwrap();
        let out = format!("{preset}.png");
        ok(
            d,
            &[
                "animate", "--preset", preset, "--size", "160x120", "--fps", "20", "--out", &out,
            ],
        );
        let text = png_text(&d.join(&out));
        let outcome: serde_json::Value = serde_json::from_str(&text["dicesim-outcome"]).unwrap();
        assert_eq!(outcome["die"]["face"], roll["face"], "{preset}");
        assert_eq!(outcome["die"]["status"], roll["status"], "{preset}");
        assert_eq!(outcome["die"]["steps"], roll["steps"], "{preset}");
        // ⌈T·fps⌉ ± 1 frames, and the file holds as many as it says.
        let frames = outcome["frames"].as_u64().unwrap() as f64;
        let expected = (roll["time_s"].as_f64().unwrap() * 20.0).ceil();
        assert!(
            (frames - expected).abs() <= 1.0,
            "{preset}: {frames} frames, {expected} expected"
        );
        let reader = png::Decoder::new(std::io::BufReader::new(
            std::fs::File::open(d.join(&out)).unwrap(),
        ))
        .read_info()
        .unwrap();
        let actl = reader.info().animation_control.expect("an animated PNG");
        assert_eq!(f64::from(actl.num_frames), frames, "{preset}");
        assert!(
            text["dicesim-setup"].starts_with(&format!("preset = \"{preset}\"")),
            "{preset}"
        );
    }
}

/// The printed summary lines its values up by characters (`ε` is two bytes), and `--zoom`
/// with `--face-pair` is recorded in the file.
#[test]
fn the_summary_lines_up_by_characters_and_the_view_is_recorded() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let text = ok(
        d,
        &[
            "animate",
            "--twin",
            "--size",
            "160x120",
            "--fps",
            "10",
            "--zoom",
            "--face-pair",
            "5",
            "--out",
            "z.png",
        ],
    );
    let column = |name: &str| {
        // The column, in characters, where the value after the name's padding begins.
        let line = text.lines().find(|l| l.starts_with(name)).expect(name);
        let padding = line.find("  ").expect("padded");
        line.chars().count() - line[padding..].trim_start().chars().count()
    };
    assert_eq!(column("twin (ε"), column("die"), "{text}");
    assert_eq!(column("wrote"), column("die"), "{text}");
    let outcome: serde_json::Value =
        serde_json::from_str(&png_text(&d.join("z.png"))["dicesim-outcome"]).unwrap();
    assert_eq!(outcome["zoom"], true);
    assert_eq!(outcome["face_pair"], 2);
    let e = refused(d, &["animate", "--face-pair", "7", "--out", "y.gif"]);
    assert!(e.contains("7"), "{e}");
    assert!(!d.join("y.gif").exists());
}

#[test]
fn two_runs_write_the_same_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for name in ["a.gif", "b.gif"] {
        ok(
            d,
            &["animate", "--twin", "1e-6", "--size", "200x150", "--out", name],
        );
    }
    assert!(std::fs::read(d.join("a.gif")).unwrap() == std::fs::read(d.join("b.gif")).unwrap());
}

#[test]
fn bad_input_is_refused_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("old.gif"), "old").unwrap();
    let e = refused(d, &["animate", "--out", "old.gif"]);
    assert!(
        e.contains("old.gif: the file exists (--force replaces it)"),
        "{e}"
    );
    assert_eq!(std::fs::read_to_string(d.join("old.gif")).unwrap(), "old");
    for (args, words) in [
        (vec!["--out", "roll.mp4"], "expected a .gif or .png file"),
        (
            vec!["--size", "20x20", "--out", "x.gif"],
            "from 64x64 to 3840x2160",
        ),
        (vec!["--fps", "0", "--out", "x.gif"], "0 is not in 1..=50"),
        (vec!["--twin", "0.5", "--out", "x.gif"], "twin.epsilon"),
        (vec!["--twin", "much", "--out", "x.gif"], "expected a number"),
        (
            vec!["--set", "ground.friction=-1", "--out", "x.gif"],
            "ground.friction",
        ),
    ] {
        let mut all = vec!["animate"];
        all.extend(&args);
        let e = refused(d, &all);
        assert!(e.contains(words), "{args:?}: {e}");
    }
    let left: Vec<_> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, ["old.gif"], "nothing else written");
}

/// The frames of an animated PNG as a viewer shows them, each as RGB pixels.
fn apng_frames(path: &std::path::Path) -> (u32, u32, Vec<Vec<[u8; 3]>>) {
    let mut decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    decoder.set_transformations(png::Transformations::IDENTITY);
    let mut reader = decoder.read_info().unwrap();
    let info = reader.info().clone();
    let palette: Vec<[u8; 3]> = info
        .palette
        .as_ref()
        .expect("an indexed PNG")
        .chunks(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    let (w, h) = (info.width, info.height);
    let frames = info.animation_control.expect("an animated PNG").num_frames;
    let mut canvas = vec![0u8; (w * h) as usize];
    let mut buffer = vec![0u8; reader.output_buffer_size().expect("a frame that fits in memory")];
    let mut out = Vec::new();
    for _ in 0..frames {
        let frame = reader.next_frame(&mut buffer).unwrap();
        let fc = reader.info().frame_control.unwrap();
        for row in 0..frame.height as usize {
            for col in 0..frame.width as usize {
                let i = buffer[row * frame.line_size + col];
                // Index 0 is see-through: the pixel the frame leaves as it was.
                if i != 0 {
                    canvas[(fc.y_offset as usize + row) * w as usize + fc.x_offset as usize + col] = i;
                }
            }
        }
        out.push(canvas.iter().map(|&i| palette[usize::from(i)]).collect());
    }
    (w, h, out)
}

/// `--present` writes the explorer's presentation view: an 80×24 screen in 16 × 30-pixel
/// cells filling 1280×720 (DejaVu Sans Mono's cell, 0.602 by 1.164 em, at the most the
/// width allows), the projector's black on white, the panels' borders continuous lines
/// across their cells, the die's picture changing as it falls while the borders stay, and
/// the file recording the view, the terminal and the roll's own outcome.
#[test]
fn the_presentation_view_is_written_as_the_class_sees_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let roll: serde_json::Value = serde_json::from_str(&ok(d, &["roll", "--json"])).unwrap();
    ok(
        d,
        &[
            "animate",
            "--present",
            "--size",
            "1280x720",
            "--fps",
            "5",
            "--out",
            "p.png",
        ],
    );
    let text = png_text(&d.join("p.png"));
    let outcome: serde_json::Value = serde_json::from_str(&text["dicesim-outcome"]).unwrap();
    assert_eq!(outcome["view"], "the presentation view");
    assert_eq!(outcome["terminal"]["columns"], 80);
    assert_eq!(outcome["terminal"]["rows"], 24);
    assert_eq!(outcome["terminal"]["cell"], serde_json::json!([16, 30]));
    assert_eq!(outcome["die"]["face"], roll["face"]);
    assert!(text["Title"].contains("the presentation view"), "{text:?}");
    let (w, h, frames) = apng_frames(&d.join("p.png"));
    assert_eq!((w, h), (1280, 720));
    assert_eq!(frames.len() as u64, outcome["frames"].as_u64().unwrap());
    const INK: [u8; 3] = [0, 0, 0];
    const PAPER: [u8; 3] = [255, 255, 255];
    let at = |f: &Vec<[u8; 3]>, x: u32, y: u32| f[(y * w + x) as usize];
    for f in [&frames[0], frames.last().unwrap()] {
        let paper = f.iter().filter(|&&p| p == PAPER).count();
        assert!(paper * 2 > f.len(), "mostly the white page");
        assert!(f.contains(&INK), "black ink");
        // The die's panel (rows 1 to 22, columns 0 to 55): its top border a line through
        // the row's cells, its left border (column 0) one down the middle of its cells.
        let (cell_w, cell_h) = (16, 30);
        let mid_row = cell_h + cell_h / 2;
        let mid_column = cell_w / 2;
        let corner_row = (0..cell_h)
            .find(|&y| at(f, mid_column, cell_h + y) == INK)
            .expect("a corner");
        // Right of the title (columns 28 on) to the panel's corner (column 55), and the
        // corner itself: whole lines of ink.
        let ink_from = |x0: u32, x1: u32| (x0..x1).all(|x| at(f, x, cell_h + corner_row) == INK);
        assert!(ink_from(mid_column, cell_w), "the corner joins the line");
        assert!(ink_from(28 * cell_w, 55 * cell_w), "the top border is one line");
        // Down to its bottom corner, in the middle of row 22.
        let left: Vec<bool> = (mid_row..22 * cell_h + cell_h / 2)
            .map(|y| at(f, mid_column, y) == INK)
            .collect();
        assert!(
            left.iter().all(|&i| i),
            "the left border is one line down the screen"
        );
    }
    // The die falls: its picture changes, the borders do not.
    let changed = frames[0]
        .iter()
        .zip(frames.last().unwrap())
        .filter(|(a, b)| a != b)
        .count();
    assert!(changed > 1000, "{changed} pixels changed");
}

#[test]
fn the_presentation_view_refuses_what_it_cannot_draw() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (args, words) in [
        (vec!["--present", "--zoom"], "--zoom"),
        (vec!["--present", "--twin"], "--twin"),
        (vec!["--terminal", "100x30"], "--present"),
        (vec!["--present", "--terminal", "20x10"], "from 80x24 to 400x200"),
        (
            vec!["--present", "--size", "320x240"],
            "--size 320×240 pixels: 80×24 terminal cells need at least 560×288",
        ),
    ] {
        let mut all = vec!["animate"];
        all.extend(&args);
        all.extend(["--out", "x.gif"]);
        let e = refused(d, &all);
        assert!(e.contains(words), "{args:?}: {e}");
        assert!(!d.join("x.gif").exists());
    }
}
