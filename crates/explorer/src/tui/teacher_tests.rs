//! The explorer in a teacher's hands: the event keys against the roll's trace, a throw by
//! hand through `update` and back from a saved preset, the plots' readout and fitted axis,
//! the marked face pair, and the screens a class reads at a projector's sizes.

use super::state::camera::OrbitCamera;
use super::state::messages::Msg;
use super::state::projection::die_view;
use super::state::throw::THROW_TIME_S;
use super::tests::{Harness, screen, start};
use crate::tui::input::update::update;
use crate::tui::vocabulary::format::fmt_num;
use crate::tui::vocabulary::layout::screen_layout;
use crate::tui::vocabulary::param::Param;
use crate::tui::vocabulary::theme::{Palette, Theme};
use dicesim_experiment::trace::TraceWriter;
use dicesim_physics::{Simulation, impact_starts};
use dicesim_setup::preset::{Preset, Store, shipped_text};
use ratatui::crossterm::event::{Event, KeyCode, KeyModifiers, MouseButton, MouseEvent, MouseEventKind};

fn projector() -> Theme {
    Theme {
        colour: true,
        palette: Palette::Projector,
    }
}

fn shipped(name: &str) -> Harness {
    let preset = Preset::from_toml_str(shipped_text(name).expect("shipped"), name).expect("valid");
    let mut s = Harness::new(&preset, projector());
    s.app.store = Store::new(None);
    s
}

/// The roll as `dicesim trace` writes it (a row at t = 0, then one per step to the roll's
/// end): the steps of its rows and the contact its `lowest_corner_cm` column reads.
fn traced(preset: &Preset) -> (Vec<u64>, Vec<bool>) {
    let mut sim = Simulation::new(&preset.params(), &preset.initial).expect("valid");
    let mut csv = Vec::new();
    {
        // `dicesim trace`'s loop: the start, then each step until the one the roll ends at.
        let mut out = TraceWriter::new(&mut csv, preset.params().integrator.dt).expect("header");
        out.write(&sim).expect("row");
        loop {
            let ended = sim.advance().is_some();
            out.write(&sim).expect("row");
            if ended {
                break;
            }
        }
        out.flush().expect("flushed");
    }
    let text = String::from_utf8(csv).expect("text");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).expect("a column");
    let (step, lowest) = (col("step"), col("lowest_corner_cm"));
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let z: f64 = f[lowest].parse().expect("a number");
            (f[step].parse::<u64>().expect("a step"), z < 0.0)
        })
        .unzip()
}

fn position(s: &Harness) -> u64 {
    s.app.roll.live.timeline.position
}

/// `i`, `I` and `F` land where the trace says: on each step where contact begins after the
/// die was clear of the table, read from `dicesim trace`'s columns by the physics' one
/// definition of an impact, and on the step the face was decided, the trace's last.
#[test]
fn the_impact_keys_land_on_the_steps_the_trace_starts_its_contacts() {
    let name = "slow-motion-classroom";
    let preset = Preset::from_toml_str(shipped_text(name).expect("shipped"), name).expect("valid");
    let (steps, contact) = traced(&preset);
    assert!(
        steps.iter().enumerate().all(|(i, &n)| n == i as u64),
        "a row a step"
    );
    let expected = impact_starts(contact.iter().copied());
    let decided = *steps.last().expect("rows");
    assert!(expected.len() >= 3, "the roll bounces: {expected:?}");

    let mut s = shipped(name);
    s.key(KeyCode::Home);
    let mut landed = Vec::new();
    loop {
        s.key(KeyCode::Char('i'));
        let at = position(&s);
        if landed.last() == Some(&at) || at > decided {
            break;
        }
        landed.push(at);
    }
    assert_eq!(landed, expected, "next impact, from the start");
    // The status line says which impact and where; the timeline marks it under ◆.
    s.key(KeyCode::Home);
    s.key(KeyCode::Char('i'));
    let text = screen(&s.app, 100, 30);
    let seconds = format!("{:.3} s", expected[0] as f64 * preset.params().integrator.dt);
    assert!(
        text.contains(&format!("impact 1 begins at {seconds} (step {})", expected[0])),
        "{text}"
    );
    // Back from the last: every impact in turn, then none before the first.
    s.command(crate::worker::Command::Seek(decided));
    let mut back = Vec::new();
    for _ in 0..expected.len() + 1 {
        s.key(KeyCode::Char('I'));
        back.push(position(&s));
    }
    let mut reversed = expected.clone();
    reversed.reverse();
    reversed.push(expected[0]);
    assert_eq!(back, reversed, "previous impact, from the decided step");
    assert!(screen(&s.app, 100, 30).contains("no impact before"));
    s.key(KeyCode::Home);
    s.key(KeyCode::Char('F'));
    assert_eq!(position(&s), decided, "face decided");
    assert_eq!(s.app.roll.live.timeline.decided, Some(decided));
    s.key(KeyCode::Home);
    let text = screen(&s.app, 80, 24);
    assert!(text.contains('✓'), "the decided mark on the timeline:\n{text}");
}

fn mouse(s: &mut Harness, kind: MouseEventKind, column: u16, row: u16, modifiers: KeyModifiers) {
    let m = MouseEvent {
        kind,
        column,
        row,
        modifiers,
    };
    for effect in update(&mut s.app, Msg::Input(Event::Mouse(m))) {
        if let Some(c) = crate::tui::event_loop::effects::perform(&mut s.app, effect) {
            s.simulator.handle(c);
        }
    }
    s.sync();
}

/// The paper's die seen level, from the front: across the panel is the world's x, up is z.
/// A plain left-button drag along `path`: pressed at its first cell, dragged through the
/// others, released at the last.
fn drag(s: &mut Harness, path: &[(u16, u16)]) {
    let (first, rest) = path.split_first().expect("a path");
    mouse(
        s,
        MouseEventKind::Down(MouseButton::Left),
        first.0,
        first.1,
        KeyModifiers::NONE,
    );
    for &(column, row) in rest {
        mouse(
            s,
            MouseEventKind::Drag(MouseButton::Left),
            column,
            row,
            KeyModifiers::NONE,
        );
    }
    let last = path.last().expect("a path");
    mouse(
        s,
        MouseEventKind::Up(MouseButton::Left),
        last.0,
        last.1,
        KeyModifiers::NONE,
    );
}

fn level(s: &mut Harness) {
    s.app.die_screen.camera = OrbitCamera {
        yaw_deg: 0.0,
        pitch_deg: 0.0,
        zoom: 0,
    };
}

/// cm of the view one column of the die panel spans, by the camera's rule: nine half sizes
/// across the panel's inside at zoom 0 (docs/explorer.md); a row is twice as tall.
fn column_cm(s: &Harness) -> f64 {
    let areas = screen_layout(s.app.screen).expect("a screen");
    9.0 * s.app.roll.live.params.die.largest_half_size() / (areas.die.width - 2) as f64
}

/// The die's centre on screen, to press on.
fn die_centre_cell(s: &Harness) -> (u16, u16) {
    let areas = screen_layout(s.app.screen).expect("a screen");
    let view = die_view(&s.app, areas.die);
    let (c, r) = view
        .cell(view.flat(&s.app.roll.live.die.centre))
        .expect("in view");
    (view.area.x + c, view.area.y + r)
}

/// A drag on the die in throw mode throws it: the drag's length and direction over the
/// throw time are the velocity, and where it was grabbed the spin, `M·(r × v)/I` (the
/// paper's cube: M = 8 g, I = 16/3 g·cm²); both go into the setup, and the saved throw rolls
/// the same bits.
#[test]
fn a_drag_on_the_die_throws_it_and_the_saved_throw_rolls_the_same_bits() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = Harness::new(&Preset::default(), Theme::default());
    s.app.store = Store::new(Some(dir.path().to_path_buf()));
    level(&mut s);
    let w = column_cm(&s);
    let h = 2.0 * w;
    let (c, r) = die_centre_cell(&s);
    let (m, i) = (8.0, 16.0 / 3.0);
    // A plain drag orbits the camera and throws nothing.
    let before = s.app.setup.initial;
    drag(&mut s, &[(c, r), (c + 2, r)]);
    assert_eq!(s.app.setup.initial, before);
    assert_ne!(s.app.die_screen.camera.yaw_deg, 0.0, "orbited");
    level(&mut s);
    // Thrown twice, 6 columns right and 2 rows up, grabbed a row above and a row below.
    let mut spin_y = Vec::new();
    for grab_row in [r - 1, r + 1] {
        s.key(KeyCode::Char('f'));
        assert!(
            screen(&s.app, 120, 36).contains("Enter throw"),
            "throw mode's keys in the footer"
        );
        drag(
            &mut s,
            &[(c, grab_row), (c + 3, grab_row - 1), (c + 6, grab_row - 2)],
        );
        let v = s.app.setup.initial.velocity;
        let (vx, vz) = (6.0 * w / THROW_TIME_S, 2.0 * h / THROW_TIME_S);
        assert!(
            (v[0] - vx).abs() <= 0.05 && v[1] == 0.0 && (v[2] - vz).abs() <= 0.05,
            "{v:?}"
        );
        let spin = s.app.setup.initial.angular_velocity;
        assert!(
            spin[0] == 0.0 && spin[2] == 0.0,
            "about the line of sight only: {spin:?}"
        );
        spin_y.push(spin[1]);
        assert!(s.app.roll.live.playing, "thrown from its start");
        s.key(KeyCode::Esc);
    }
    // Two rows apart: Δω_y = M·Δr_z·v_x/I, up to the setup's 0.01 rad/s.
    let vx = 6.0 * w / THROW_TIME_S;
    let expected = m * 2.0 * h * vx / i;
    assert!(
        (spin_y[0] - spin_y[1] - expected).abs() <= 0.011,
        "{spin_y:?} vs {expected}"
    );
    assert!(
        spin_y[0] > 0.0,
        "grabbed high and pulled right, the top goes right: +y"
    );

    // The keyboard: grabbed a row above the centre, aimed 6 right and 2 up.
    s.key(KeyCode::Char('f'));
    s.key(KeyCode::Char('w'));
    for _ in 0..6 {
        s.key(KeyCode::Right);
    }
    s.key(KeyCode::Up);
    s.key(KeyCode::Up);
    s.key(KeyCode::Enter);
    let v = s.app.setup.initial.velocity;
    assert!((v[0] - vx).abs() <= 0.05 && (v[2] - 2.0 * h / THROW_TIME_S).abs() <= 0.05);
    let spin = s.app.setup.initial.angular_velocity;
    assert!((spin[1] - m * h * vx / i).abs() <= 0.005, "{spin:?}");
    s.key(KeyCode::Esc);

    // Saved, and rolled from the saved file: the same roll, bit for bit.
    s.key(KeyCode::Char('s'));
    for ch in "thrown".chars() {
        s.key(KeyCode::Char(ch));
    }
    s.key(KeyCode::Enter);
    let saved = Store::new(Some(dir.path().to_path_buf()))
        .load("thrown")
        .expect("saved")
        .0;
    assert_eq!(saved.initial, s.app.setup.initial);
    let bits = |p: &dicesim_physics::Params, ic: &dicesim_physics::InitialCondition| {
        let mut sim = Simulation::new(p, ic).expect("valid");
        let o = sim.run_to_end();
        format!("{o:?} {:?}", sim.state())
    };
    let from_file = bits(&saved.params(), &saved.initial);
    assert_eq!(from_file, bits(&s.app.setup.params, &s.app.setup.initial));
    // And the explorer's own roll of the throw ends on those bits where the face is decided.
    s.key(KeyCode::Char('F'));
    let sim_at_decided = format!("{:?}", s.simulator.simulation().state());
    assert!(
        from_file.ends_with(&sim_at_decided),
        "{from_file}\n{sim_at_decided}"
    );
}

/// A Ctrl-drag throws without throw mode and leaves it off; Alt works the same.
#[test]
fn a_ctrl_drag_on_the_die_throws_and_plain_keys_stay_the_die_screens() {
    let mut s = Harness::new(&Preset::default(), Theme::default());
    level(&mut s);
    let (c, r) = die_centre_cell(&s);
    mouse(
        &mut s,
        MouseEventKind::Down(MouseButton::Left),
        c,
        r,
        KeyModifiers::CONTROL,
    );
    mouse(
        &mut s,
        MouseEventKind::Drag(MouseButton::Left),
        c + 4,
        r,
        KeyModifiers::CONTROL,
    );
    mouse(
        &mut s,
        MouseEventKind::Up(MouseButton::Left),
        c + 4,
        r,
        KeyModifiers::CONTROL,
    );
    let vx = 4.0 * column_cm(&s) / THROW_TIME_S;
    assert!((s.app.setup.initial.velocity[0] - vx).abs() <= 0.05);
    assert!(s.app.die_screen.throw.is_none(), "throw mode is off again");
    assert_eq!(s.app.die_screen.camera.yaw_deg, 0.0, "no orbit");
}

/// The plot's readout at the time marker: each plotted quantity's value at the state on
/// screen with its unit, in the plot's bottom border; the energy plot's terms in the
/// ledger beside it, titled with theirs.
#[test]
fn the_readout_shows_each_plotted_value_with_its_unit() {
    let mut s = start();
    s.simulator.advance_steps(120);
    s.sync();
    let die = s.app.roll.live.die;
    let height = die.centre.z;
    let lowest = die.corners.iter().map(|c| c.z).fold(f64::INFINITY, f64::min);
    s.key(KeyCode::Char('w'));
    s.key(KeyCode::Char('Y'));
    for (w, h) in [(100, 30), (120, 36)] {
        let text = screen(&s.app, w, h);
        assert!(text.contains(&format!("height {} cm", fmt_num(height))), "{text}");
        assert!(text.contains(&format!("lowest {} cm", fmt_num(lowest))), "{text}");
    }
    // Two curves on the one axis of their unit, named in the title.
    assert!(screen(&s.app, 120, 36).contains("━height ━lowest · cm"));
    // Back to the energy plot: its terms now in the ledger, in erg.
    for _ in 0..dicesim_setup::quantity::QUANTITY_COUNT {
        s.key(KeyCode::Char('w'));
    }
    assert_eq!(s.app.die_screen.plot.quantity, None);
    let text = screen(&s.app, 80, 24);
    assert!(text.contains("energy now, erg"), "{text}");
    assert!(text.contains(&fmt_num(s.app.roll.live.energy.total())), "{text}");
}

/// The value axis's labels of the plot panel on a 120×36 screen, bottom first.
fn value_labels(text: &str) -> Vec<f64> {
    let rows: Vec<&str> = text.lines().collect();
    let top = rows
        .iter()
        .position(|l| l.contains("┌ height"))
        .expect("the height plot");
    let left = rows[top]
        .split("┌ height")
        .next()
        .map_or(0, |l| l.chars().count());
    rows[top + 1..]
        .iter()
        .take_while(|l| l.chars().nth(left).is_none_or(|c| c != '└'))
        .filter_map(|row| {
            let inside: String = row.chars().skip(left + 1).collect();
            inside.split('│').next()?.trim().parse::<f64>().ok()
        })
        .collect()
}

/// `y` fits the value axis to the curves around the time on screen: at rest on the table,
/// the height plot's axis closes in on the die's half size instead of spanning the drop.
#[test]
fn y_fits_the_value_axis_to_the_curves_around_the_time_on_screen() {
    let mut s = start();
    s.run_to_end();
    s.key(KeyCode::Char('w'));
    let whole = value_labels(&screen(&s.app, 120, 36));
    assert!(
        whole.iter().cloned().fold(0.0, f64::max) >= 15.0,
        "the drop: {whole:?}"
    );
    s.key(KeyCode::Char('y'));
    let fitted = value_labels(&screen(&s.app, 120, 36));
    let top = fitted.iter().cloned().fold(0.0, f64::max);
    assert!(top < 3.0 && top > 0.5, "near the resting height: {fitted:?}");
    s.key(KeyCode::Char('y'));
    assert_eq!(value_labels(&screen(&s.app, 120, 36)), whole);
}

/// `M` marks a face pair: its faces take their own tints and its axis is drawn through them
/// with both numbers at its tips; 2 and 5 first, the pair the tennis racket flips.
#[test]
fn m_marks_the_face_pair_two_and_five_first() {
    let mut s = shipped("tennis-racket");
    s.simulator.advance_steps(60);
    s.sync();
    s.key(KeyCode::Char('M'));
    assert_eq!(s.app.die_screen.face_pair, Some(2));
    let areas = screen_layout(s.app.screen).expect("a screen");
    let view = die_view(&s.app, areas.die);
    let pic = crate::tui::panels::die::picture(&s.app, &view);
    for face in ["2", "5"] {
        assert!(pic.labels.iter().any(|l| l.text == face), "the axis's tip {face}");
    }
    let mut t = ratatui::Terminal::new(ratatui::backend::TestBackend::new(120, 36)).expect("backend");
    t.draw(|f| super::render(&s.app, f)).expect("draw");
    let b = t.backend().buffer();
    let die = areas.die;
    // The pair's tints on the projector's white: warm (red full) and cool (green full).
    let tinted = (die.y..die.bottom())
        .flat_map(|y| (die.x..die.right()).map(move |x| (x, y)))
        .filter(|&p| match b[p].bg {
            ratatui::style::Color::Rgb(r, g, bl) => (r == 255 && bl < g) || (g == 255 && r < g),
            _ => false,
        })
        .count();
    assert!(tinted > 4, "{tinted} cells of the pair's tints");
    for _ in 0..3 {
        s.key(KeyCode::Char('M'));
    }
    assert_eq!(s.app.die_screen.face_pair, None, "2·5 → 1·6 → 3·4 → none");
}

/// Defect: at 80×24 on `gentle-drop`, the map's colour key stayed under the cursor's text.
#[test]
fn the_maps_colour_key_stays_at_80_by_24() {
    let mut s = shipped("gentle-drop");
    s.key(KeyCode::Tab);
    let m = super::map_tests::computed(&s.app);
    update(&mut s.app, Msg::from(m));
    // The cursor on a cell filled in from its block's corners: the longest cursor text.
    let map = s.app.map.map().expect("computed");
    let inferred = (0..map.width())
        .flat_map(|i| (0..map.height()).map(move |j| (i, j)))
        .find(|&(i, j)| map.cell(i, j).is_some_and(|c| !c.sampled))
        .expect("an inferred cell");
    s.app.map.cursor = inferred;
    for (w, h) in [(80, 24), (100, 30)] {
        let text = screen(&s.app, w, h);
        assert!(
            text.contains("like its block's"),
            "the inferred cell's words at {w}×{h}:\n{text}"
        );
        assert!(
            text.contains("██1 ██2 ██3 ██4 ██5 ██6"),
            "the colour key at {w}×{h}:\n{text}"
        );
        assert!(text.contains("legend: face up"), "{text}");
    }
}

/// Defect: `slow-motion-classroom`, `Home`, `.` ×133: the ledger cut `friction` mid-word.
#[test]
fn the_ledger_never_cuts_a_word() {
    let mut s = shipped("slow-motion-classroom");
    s.key(KeyCode::Home);
    for _ in 0..133 {
        s.key(KeyCode::Char('.'));
    }
    for (w, h) in [(80, 24), (100, 30), (120, 36)] {
        let text = screen(&s.app, w, h);
        let areas = screen_layout(ratatui::layout::Rect::new(0, 0, w, h)).expect("a screen");
        let ledger: Vec<String> = text
            .lines()
            .skip(areas.ledger.y as usize + 1)
            .take(areas.ledger.height as usize - 1)
            .map(|l| {
                l.trim_matches('"')
                    .chars()
                    .skip(areas.ledger.x as usize)
                    .collect()
            })
            .collect();
        for row in &ledger {
            assert!(!row.contains('…'), "a word cut at {w}×{h}: {row:?}");
        }
        assert!(ledger.iter().any(|r| r.contains("fric")), "{ledger:?}");
    }
}

/// Defect: with the parameter twin, die B came to rest off the top of the die panel.
#[test]
fn the_parameter_twins_die_b_stays_in_the_picture() {
    let mut s = start();
    s.key(KeyCode::Char('D'));
    s.select(Param::named("ground.friction"));
    s.key(KeyCode::Enter);
    for c in "0.3".chars() {
        s.key(KeyCode::Char(c));
    }
    s.key(KeyCode::Enter);
    s.run_to_end();
    for (w, h) in [(80, 24), (100, 30), (120, 36)] {
        s.app.screen = ratatui::layout::Rect::new(0, 0, w, h);
        let areas = screen_layout(s.app.screen).expect("a screen");
        let view = die_view(&s.app, areas.die);
        let twin = s.app.roll.live.twin.as_ref().expect("die B");
        for body in [&s.app.roll.live.die, &twin.die] {
            for c in &body.corners {
                assert!(
                    view.cell(view.flat(c)).is_some(),
                    "{w}×{h}: a corner off the picture"
                );
            }
        }
        let mut t = ratatui::Terminal::new(ratatui::backend::TestBackend::new(w, h)).expect("backend");
        t.draw(|f| super::render(&s.app, f)).expect("draw");
        let b = t.backend().buffer();
        let ghost = s.app.theme.ghost();
        let drawn = (areas.die.y + 1..areas.die.bottom() - 1)
            .flat_map(|y| (areas.die.x + 1..areas.die.right() - 1).map(move |x| (x, y)))
            .filter(|&p| b[p].fg == ghost && b[p].symbol() != " ")
            .count();
        assert!(drawn > 8, "{w}×{h}: die B drawn in {drawn} cells");
    }
}
