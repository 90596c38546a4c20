//! Throwing the die: a drag on it, or throw mode's keys.

use crate::tui::input::update::update;
use crate::tui::state::camera::OrbitCamera;
use crate::tui::state::messages::Msg;
use crate::tui::state::projection::die_view;
use crate::tui::state::throw::THROW_TIME_S;
use crate::tui::tests::fixtures::{Harness, screen};
use crate::tui::vocabulary::layout::screen_layout;
use crate::tui::vocabulary::theme::Theme;
use dicesim_physics::Simulation;
use dicesim_setup::preset::{Preset, Store};
use ratatui::crossterm::event::{Event, KeyCode, KeyModifiers, MouseButton, MouseEvent, MouseEventKind};

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

/// A drag on the die in throw mode throws it: the drag's length and direction laid on the
/// table, over the throw time, are the velocity, and where it was grabbed the spin, `M·(r × v)/I` (the
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
    let mut spin_y = Vec::new(); // ω of the throw grabbed high, then low
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
        // Across the table: right is +x, up the screen away from the viewer (+y), level.
        let v = s.app.setup.initial.velocity;
        let (vx, vy) = (6.0 * w / THROW_TIME_S, 2.0 * h / THROW_TIME_S);
        assert!(
            (v[0] - vx).abs() <= 0.05 && (v[1] - vy).abs() <= 0.05 && v[2] == 0.0,
            "{v:?}"
        );
        spin_y.push(s.app.setup.initial.angular_velocity);
        assert!(s.app.roll.live.playing, "thrown from its start");
        s.key(KeyCode::Esc);
    }
    // Two rows apart, Δr = (0, 0, 2h): Δω = M·(Δr × v)/I = M·2h·(−v_y, v_x, 0)/I, up to the
    // setup's 0.01 rad/s; the grab's offset across (the same both times) gives the same ω_z.
    let (vx, vy) = (6.0 * w / THROW_TIME_S, 2.0 * h / THROW_TIME_S);
    let [high, low] = [spin_y[0], spin_y[1]];
    let expected = [-m * 2.0 * h * vy / i, m * 2.0 * h * vx / i, 0.0];
    for k in 0..3 {
        assert!(
            (high[k] - low[k] - expected[k]).abs() <= 0.011,
            "{spin_y:?} vs {expected:?}"
        );
    }
    assert!(
        high[1] > 0.0 && high[0] < 0.0,
        "grabbed high and pulled right and away, the top goes right and away: +y, −x"
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
    // Grabbed at r = (0, 0, h): ω = M·(r × v)/I = M·h·(−v_y, v_x, 0)/I.
    let v = s.app.setup.initial.velocity;
    assert!((v[0] - vx).abs() <= 0.05 && (v[1] - vy).abs() <= 0.05 && v[2] == 0.0);
    let spin = s.app.setup.initial.angular_velocity;
    assert!(
        (spin[0] + m * h * vy / i).abs() <= 0.005
            && (spin[1] - m * h * vx / i).abs() <= 0.005
            && spin[2] == 0.0,
        "{spin:?}"
    );
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

/// The drag's end, a press on the die's centre and `path` of moves from it, left held.
fn hold_and_drag(s: &mut Harness, moves: &[(i32, i32)]) {
    let (c, r) = die_centre_cell(s);
    mouse(
        s,
        MouseEventKind::Down(MouseButton::Left),
        c,
        r,
        KeyModifiers::NONE,
    );
    for &(dc, dr) in moves {
        let (column, row) = ((c as i32 + dc) as u16, (r as i32 + dr) as u16);
        mouse(
            s,
            MouseEventKind::Drag(MouseButton::Left),
            column,
            row,
            KeyModifiers::NONE,
        );
    }
}

/// An upward drag throws the die across the table, away from the viewer, not up into the
/// air: seen from the default camera (from above, at an angle), the velocity is level and
/// points away, the way the camera looks.
#[test]
fn an_upward_drag_throws_the_die_across_the_table_not_up() {
    let mut s = Harness::new(&Preset::default(), Theme::default());
    s.key(KeyCode::Char('f'));
    hold_and_drag(&mut s, &[(0, -2), (0, -4)]);
    mouse(
        &mut s,
        MouseEventKind::Up(MouseButton::Left),
        0,
        0,
        KeyModifiers::NONE,
    );
    let v = s.app.setup.initial.velocity;
    let cam = s.app.die_screen.camera;
    assert!(cam.pitch_deg > 0.0, "the default camera looks down");
    let (sy, cy) = cam.yaw_deg.to_radians().sin_cos();
    let away = -sy * v[0] + cy * v[1];
    assert!(v[2] == 0.0 && away > 0.0, "level and away: {v:?}");
}

/// A throw by hand is a hand's throw across a table, 1 to 3 m/s, for a drag of a few
/// columns at 80×24: six columns right of the centre, in throw mode.
#[test]
fn a_six_column_drag_at_80x24_throws_at_a_hands_speed() {
    let mut s = Harness::new(&Preset::default(), Theme::default());
    s.app.screen = ratatui::layout::Rect::new(0, 0, 80, 24);
    level(&mut s);
    s.key(KeyCode::Char('f'));
    hold_and_drag(&mut s, &[(3, 0), (6, 0)]);
    mouse(
        &mut s,
        MouseEventKind::Up(MouseButton::Left),
        0,
        0,
        KeyModifiers::NONE,
    );
    let speed = nalgebra::Vector3::from(s.app.setup.initial.velocity).norm();
    assert!((100.0..=300.0).contains(&speed), "{speed} cm/s");
}

/// While the mouse drags, before it lets go, the footer reads the throw's velocity and spin
/// with their units at 80×24, and follows the drag.
#[test]
fn a_mouse_drag_reads_its_velocity_and_spin_live() {
    let mut s = Harness::new(&Preset::default(), Theme::default());
    s.app.screen = ratatui::layout::Rect::new(0, 0, 80, 24);
    level(&mut s);
    s.key(KeyCode::Char('f'));
    let footer = |s: &Harness| {
        screen(&s.app, 80, 24)
            .lines()
            .nth(23)
            .expect("a footer")
            .to_string()
    };
    hold_and_drag(&mut s, &[(2, 0)]);
    let short = footer(&s);
    hold_and_drag(&mut s, &[(6, -1)]);
    let long = footer(&s);
    assert!(
        s.app.die_screen.throw.is_some_and(|t| t.pressed.is_some()),
        "still held"
    );
    for f in [&short, &long] {
        assert!(f.contains("cm/s") && f.contains("rad/s"), "{f}");
    }
    assert_ne!(short, long, "the words follow the drag");
}
