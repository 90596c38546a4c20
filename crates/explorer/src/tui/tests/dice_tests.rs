//! The polyhedral dice on screen: each drawn with the numbers printed on it, the number on
//! the face up the one a player reads, the d4's at its top vertex (docs/dice.md).

use crate::tui::panels::die::{body_of, polyhedral};
use crate::tui::state::projection::die_view;
use crate::tui::tests::fixtures::{Harness, draw, projector};
use crate::tui::tests::screen_tests::SIZES;
use crate::tui::vocabulary::layout::screen_layout;
use crate::tui::vocabulary::solid::{Body, Hull};
use crate::tui::vocabulary::theme::Theme;
use crate::worker::DieState;
use dicesim_physics::polyhedron::ReadAt;
use dicesim_physics::{ContactForce, Solid};
use dicesim_setup::preset::Preset;
use nalgebra::{Rotation3, Unit, Vector3};
use ratatui::layout::Rect;

/// A die of `kind` set on the table by hand, as a player leaves it: the face printed `up`
/// on top (the d4: the vertex printed `up` on top, the face numbered `up` down), turned
/// `yaw_deg` about the vertical, its lowest points on the table. The state is built from
/// the die's geometry alone, so what the panel draws is held to docs/dice.md, not to a roll.
pub(crate) fn at_rest(kind: Solid, up: u32, yaw_deg: f64, theme: Theme) -> Harness {
    let preset = Preset::default()
        .with_overrides(&["integrator.dt=0.00025", &format!("die.kind=\"{}\"", kind.name())])
        .expect("a regular die");
    let mut s = Harness::new(&preset, theme);
    let params = s.app.roll.live.params;
    let die = params.polyhedral_die().expect("a polyhedral die");
    let numbering = die.numbering().clone();
    let face = (0..numbering.numbers.len())
        .find(|&f| numbering.numbers[f] == up)
        .expect("the die carries the number");
    let normal = die.shape().faces()[face].normal;
    // Read at the top face, the face printed `up` points up; the d4's face numbered `up`
    // (the one its vertex `up` does not touch) lies on the table.
    let towards = match numbering.read_at {
        ReadAt::TopFace => Vector3::z(),
        _ => -Vector3::z(),
    };
    let turn = Rotation3::rotation_between(&normal, &towards).unwrap_or_else(|| {
        Rotation3::from_axis_angle(
            &Unit::new_normalize(normal.cross(&Vector3::x())),
            std::f64::consts::PI,
        )
    });
    let orientation = Rotation3::from_axis_angle(&Vector3::z_axis(), yaw_deg.to_radians()) * turn;
    let placed = Hull::new(die.clone(), Vector3::zeros(), &orientation);
    let centre = Vector3::new(0.0, 0.0, -placed.lowest().z);
    let hull = Hull::new(die, centre, &orientation);
    s.app.roll.live.die = DieState {
        corners: hull.vertices.clone(),
        forces: vec![ContactForce::default(); hull.vertices.len()],
        orientation,
        centre,
        velocity: Vector3::zeros(),
        angular_velocity: Vector3::zeros(),
        angular_momentum: Vector3::zeros(),
        face_up: u8::try_from(up).expect("a die's number"),
        start_face: u8::try_from(up).expect("a die's number"),
        slid_cm: None,
    };
    s
}

/// The die of `kind` resting on the face whose outward normal (the die's own frame) is
/// `down`, turned `yaw_deg` about the vertical.
fn resting_on(kind: Solid, down: Vector3<f64>, yaw_deg: f64, theme: Theme) -> Harness {
    let die = kind.regular().expect("a regular die").standard();
    let numbering = die.numbering();
    let face = (0..numbering.numbers.len())
        .min_by(|&a, &b| {
            let off = |f: usize| (die.shape().faces()[f].normal - down.normalize()).norm();
            off(a).total_cmp(&off(b))
        })
        .expect("faces");
    // The number docs/dice.md's table prints on that face (not what it reads).
    let printed = numbering.numbers[face];
    let up = match numbering.read_at {
        ReadAt::TopFace => numbering.read_with_down(face),
        _ => printed,
    };
    at_rest(kind, up, yaw_deg, theme)
}

/// The text drawn on the screen where the number read should be: at the centre of the
/// face most nearly up, or for the d4 by its top vertex on the face the camera sees most
/// squarely, at every classroom size.
fn number_read_on_screen(s: &Harness) -> Vec<String> {
    let app = &s.app;
    let Body::Hull(hull) = body_of(app, &app.roll.live.die) else {
        panic!("a polyhedral die")
    };
    SIZES
        .iter()
        .map(|&(w, h)| {
            let term = draw(app, w, h);
            let areas = screen_layout(Rect::new(0, 0, w, h)).expect("big enough");
            let view = die_view(app, areas.die);
            let facing = polyhedral::facing(&hull, &view.camera);
            let anchor = match hull.face_number(0) {
                Some(_) => hull.face_centre(hull.face_most_nearly_up()),
                None => {
                    let top = (0..hull.vertices.len())
                        .max_by(|&a, &b| hull.vertices[a].z.total_cmp(&hull.vertices[b].z))
                        .expect("vertices");
                    let faces = hull.die.shape().faces();
                    let seen = (0..faces.len())
                        .filter(|&f| faces[f].vertices.contains(&top))
                        .max_by(|&a, &b| facing[a].total_cmp(&facing[b]))
                        .expect("faces at the top vertex");
                    let centre = hull.face_centre(seen);
                    hull.vertices[top] + (centre - hull.vertices[top]) * 0.4
                }
            };
            let (col, row) = view.cell(view.flat(&anchor)).expect("in view");
            let buf = term.backend().buffer();
            let (x, y) = (view.area.x + col, view.area.y + row);
            // The number starts on the anchor's cell and runs right while it is digits.
            (x..view.area.right())
                .map(|x| buf[(x, y)].symbol().to_string())
                .take_while(|c| c.chars().all(|ch| ch.is_ascii_digit()) && !c.is_empty())
                .collect()
        })
        .collect()
}

/// A die at rest shows the number a player reads where a player reads it: for each die a
/// few of docs/dice.md's rows (a face's outward normal, and what is read with it down),
/// each at three turns about the vertical, in both themes, at every classroom size.
#[test]
fn the_number_drawn_up_is_the_number_read() {
    let rows: [(Solid, [f64; 3], &str); 10] = [
        (Solid::D4, [-0.5774, 0.5774, 0.5774], "2"),
        (Solid::D4, [-0.5774, -0.5774, -0.5774], "1"),
        (Solid::D8, [0.5774, 0.5774, 0.5774], "8"),
        (Solid::D10, [0.6, 0.4359, 0.6708], "9"),
        (Solid::D10, [0.2292, -0.7053, -0.6708], "8"),
        (Solid::Percentile, [0.6, 0.4359, 0.6708], "90"),
        (Solid::Percentile, [-0.6, -0.4359, -0.6708], "00"),
        (Solid::D12, [0.5257, 0.0, 0.8507], "12"),
        (Solid::D20, [0.3568, 0.0, 0.9342], "20"),
        (Solid::D20, [0.5774, 0.5774, -0.5774], "5"),
    ];
    for (kind, down, read) in rows {
        for yaw in [0.0, 35.0, 200.0] {
            for theme in [Theme::default(), projector()] {
                let s = resting_on(kind, Vector3::from(down), yaw, theme);
                for (drawn, size) in number_read_on_screen(&s).iter().zip(SIZES) {
                    assert_eq!(drawn, read, "{kind:?} on {down:?}, turned {yaw}°, at {size:?}");
                }
            }
        }
    }
}

/// A d20 at rest beside an outcome table filled by hand: face `n` counted `40 + (7·n mod
/// 13)` times (918 rolls), so the shares differ from face to face by a pattern a reader can check.
pub(crate) fn d20_table(theme: Theme) -> Harness {
    let mut s = at_rest(Solid::D20, 20, 20.0, theme);
    let mut table = crate::worker::OutcomeTable::new(Solid::D20.face_numbers());
    for n in 1..=20u8 {
        for _ in 0..40 + (7 * u64::from(n)) % 13 {
            table.tally.add(n);
        }
    }
    s.app.roll.table = table;
    s
}

/// All 20 faces of a d20 fit the outcome table at 80×24, each with its share in percent
/// (counted here: face n has 40 + (7·n mod 13) of 918 rolls), and the fairness test is χ²
/// against equal shares on 19 degrees of freedom: Σ (count − 45.9)² / 45.9 = 5.70.
#[test]
fn a_d20s_twenty_faces_fit_the_table_at_80x24() {
    let counts: Vec<u64> = (1..=20u64).map(|n| 40 + (7 * n) % 13).collect();
    let total: u64 = counts.iter().sum();
    assert_eq!(total, 918);
    let expected = total as f64 / 20.0;
    let chi2: f64 = counts
        .iter()
        .map(|&c| (c as f64 - expected).powi(2) / expected)
        .sum();
    for theme in [Theme::default(), projector()] {
        let s = d20_table(theme);
        let shown = crate::tui::tests::fixtures::screen(&s.app, 80, 24);
        for (n, &c) in (1..=20).zip(&counts) {
            let row = format!("{n:>2} {:4.1}", 100.0 * c as f64 / total as f64);
            assert!(shown.contains(&row), "face {n}: `{row}` in\n{shown}");
        }
        assert!(
            shown.contains(&format!("n 918  χ² {chi2:.2}")),
            "{chi2:.2} in\n{shown}"
        );
    }
}

/// The roll's exports (`e`, `A`) write the die rolled, never a box in its place: a d20's trace
/// has its 12 points' columns and is the roll `Roll` rolls from t = 0 to its end, step by step;
/// its animation is written.
#[test]
fn a_polyhedral_dies_exports_write_the_die() {
    use dicesim_experiment::trace::{header_for, row};
    use dicesim_physics::Roll;
    let preset = Preset::default()
        .with_overrides(&["integrator.dt=0.00025", "die.kind=\"d20\""])
        .expect("a d20");
    let written = |command: crate::worker::Command, dir: &std::path::Path, extension: &str| {
        let mut s = Harness::new(&preset, Theme::default());
        s.simulator.handle(command);
        s.simulator.run_export_here();
        let files: Vec<_> = std::fs::read_dir(dir)
            .expect("listed")
            .map(|e| e.expect("entry").path())
            .filter(|p| p.extension().is_some_and(|e| e == extension))
            .collect();
        assert_eq!(files.len(), 1, "{files:?}");
        files[0].clone()
    };
    let dir = tempfile::tempdir().expect("temp dir");
    let csv = written(
        crate::worker::Command::Export {
            dir: dir.path().to_path_buf(),
            log_scale: false,
        },
        dir.path(),
        "csv",
    );
    let params = preset.params();
    let text = std::fs::read_to_string(&csv).expect("csv written");
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], header_for(&params).join(","));
    assert!(lines[0].contains("p12z_cm") && !lines[0].contains("p13x_cm"));
    let mut roll = Roll::new(&params, &preset.initial).expect("valid");
    let clock = dicesim_setup::number::StepClock::new(params.integrator.dt);
    assert_eq!(lines[1], row(&roll, &clock).join(","));
    let outcome = roll.run_to_end();
    assert_eq!(lines.len() as u64, outcome.steps + 2);
    assert_eq!(*lines.last().expect("rows"), row(&roll, &clock).join(","));
    let dir = tempfile::tempdir().expect("temp dir");
    let gif = written(
        crate::worker::Command::ExportAnimation {
            dir: dir.path().to_path_buf(),
            yaw_deg: 0.0,
            pitch_deg: 20.0,
        },
        dir.path(),
        "gif",
    );
    assert!(std::fs::read(gif).expect("gif written").starts_with(b"GIF8"));
}

/// The presentation view writes the number read in big digits, both of a d20's 17 and a
/// d%'s 00 (the box's one digit is unchanged: its screens' snapshots).
#[test]
fn the_presentation_view_shows_a_two_digit_number_whole() {
    use crate::tui::panels::presentation::big_digit;
    for (kind, up, digits) in [(Solid::D20, 17, ['1', '7']), (Solid::Percentile, 0, ['0', '0'])] {
        let mut s = at_rest(kind, up, 20.0, projector());
        // The key alone, no snapshot after it: the worker's roll would replace the die set here.
        crate::tui::tests::fixtures::press(&mut s.app, ratatui::crossterm::event::KeyCode::Char('P'));
        for (w, h) in SIZES {
            let shown = crate::tui::tests::fixtures::screen(&s.app, w, h);
            // Some scale of the two glyphs side by side, a gap of as many columns as a dot.
            let found = (1..=6).any(|sx| {
                (1..=3).any(|sy| {
                    let (a, b) = (big_digit(digits[0], sx, sy), big_digit(digits[1], sx, sy));
                    let row = |r: usize| format!("{}{}{}", a[r], " ".repeat(sx), b[r]);
                    (0..a.len()).all(|r| shown.contains(row(r).trim_end()))
                })
            });
            assert!(found, "{kind:?} {up} at {w}x{h}:\n{shown}");
        }
    }
}
