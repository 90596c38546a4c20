//! The timeline strip: where the roll is, its impacts, seeking on it.

use crate::tui::tests::fixtures::{Harness, line_with, screen, shipped, stepped_back};
use crate::tui::vocabulary::layout::screen_layout;
use crate::worker::Command;
use dicesim_experiment::trace::TraceWriter;
use dicesim_physics::{Simulation, impact_starts};
use dicesim_setup::preset::{Preset, shipped_text};
use ratatui::crossterm::event::{Event, KeyCode, MouseButton, MouseEvent, MouseEventKind};

#[test]
fn the_timeline_shows_where_the_roll_is_and_its_impacts() {
    let s = stepped_back();
    assert_eq!(s.app.roll.live.timeline.position, 170);
    assert!(s.app.roll.live.timeline.ended);
    assert!(!s.app.roll.impacts.is_empty());
    let text = screen(&s.app, 120, 36);
    let strip = line_with(&text, "t 0.170 s");
    let end = s.app.roll.live.timeline.furthest as f64 * 1e-3;
    assert!(strip.contains(&format!("end {end:.3} s")), "{strip}");
    assert!(strip.contains('◆') && strip.contains('┃'), "{strip}");
    insta::assert_snapshot!("timeline_stepped_back_120x36", text);
    insta::assert_snapshot!("timeline_stepped_back_80x24", screen(&s.app, 80, 24));
}

#[test]
fn a_click_on_the_timeline_seeks_there() {
    let mut s = stepped_back();
    s.app.screen = ratatui::layout::Rect::new(0, 0, 120, 36);
    let areas = screen_layout(s.app.screen).expect("fits");
    let bar = crate::tui::vocabulary::layout::timeline_bar(
        areas.timeline,
        crate::tui::input::update::strip_margins(&s.app),
    )
    .expect("wide enough");
    let furthest = s.app.roll.live.timeline.furthest;
    for (column, expected) in [(bar.x, 0), (bar.right() - 1, furthest)] {
        let click = MouseEvent {
            kind: MouseEventKind::Down(MouseButton::Left),
            column,
            row: bar.y,
            modifiers: ratatui::crossterm::event::KeyModifiers::NONE,
        };
        let sent = crate::tui::input::update::update(
            &mut s.app,
            crate::tui::state::messages::Msg::Input(Event::Mouse(click)),
        );
        assert_eq!(sent, [Command::Seek(expected)]);
        s.command(Command::Seek(expected));
        assert_eq!(s.app.roll.live.timeline.position, expected);
    }
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
    s.command(Command::Seek(decided));
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

/// A roll of Δt = 50 µs (the sleeping top's) writes its times to five decimals: both
/// labels keep their unit at 80 columns, `t 10.00000 s` and `end 10.00000 s`.
#[test]
fn a_fine_step_keeps_the_timelines_unit_at_80_columns() {
    let mut s = shipped("sleeping-top");
    s.run_to_end();
    let text = screen(&s.app, 80, 24);
    let strip = line_with(&text, "end 10.00000");
    assert!(
        strip.contains("t 10.00000 s ") && strip.contains("end 10.00000 s"),
        "{strip}"
    );
}

/// A click on the timeline is an answer as a key is: the notice about what came before (no
/// impact after the end of the roll) goes.
#[test]
fn a_click_on_the_timeline_clears_the_last_notice() {
    let mut s = stepped_back();
    s.app.screen = ratatui::layout::Rect::new(0, 0, 120, 36);
    s.key(KeyCode::End);
    s.key(KeyCode::Char('i'));
    assert!(
        s.app
            .notice
            .as_deref()
            .is_some_and(|n| n.contains("no impact after")),
        "{:?}",
        s.app.notice
    );
    let areas = screen_layout(s.app.screen).expect("fits");
    let bar = crate::tui::vocabulary::layout::timeline_bar(
        areas.timeline,
        crate::tui::input::update::strip_margins(&s.app),
    )
    .expect("wide enough");
    let click = MouseEvent {
        kind: MouseEventKind::Down(MouseButton::Left),
        column: bar.x + 1,
        row: bar.y,
        modifiers: ratatui::crossterm::event::KeyModifiers::NONE,
    };
    crate::tui::input::update::update(
        &mut s.app,
        crate::tui::state::messages::Msg::Input(Event::Mouse(click)),
    );
    assert_eq!(s.app.notice, None);
    assert!(!screen(&s.app, 120, 36).contains("no impact after"));
}
