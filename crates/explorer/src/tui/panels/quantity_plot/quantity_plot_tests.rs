//! The plot panel: the energy plot and every other quantity, their axes, readout and marks.

use crate::tui::panels::chart::nice_ticks;
use crate::tui::panels::quantity_plot;
use crate::tui::tests::fixtures::{
    Harness, full, mid_impact, mid_impact_with, panel, panel_at, screen, settled, start, text,
};
use crate::tui::vocabulary::format::fmt_num;
use crate::tui::vocabulary::theme::Theme;
use crate::worker::Command;
use dicesim_physics::Simulation;
use dicesim_setup::preset::{Preset, Store};
use ratatui::crossterm::event::KeyCode;

/// The spun roll computed to its end, the screen back at `step`, `w` pressed `presses`
/// times (and `V` after, for a phase plot).
fn plot_at(step: u64, presses: usize, phase: bool) -> Harness {
    let mut s = settled();
    s.command(Command::Seek(step));
    for _ in 0..presses {
        s.key(KeyCode::Char('w'));
    }
    if phase {
        s.key(KeyCode::Char('V'));
    }
    s
}

/// The plot panel's rows of a screen: those between its title row and the next panel's.
fn panel_rows(text: &str, title: &str) -> Vec<String> {
    let lines: Vec<String> = text.lines().map(str::to_string).collect();
    let top = lines
        .iter()
        .position(|l| l.contains(title))
        .unwrap_or_else(|| panic!("no {title:?} in\n{text}"));
    lines[top..].to_vec()
}

/// Where the roll of the scene ends, s, worked out by a simulation of its own.
fn roll_end(s: &Harness) -> f64 {
    let mut sim = Simulation::new(&s.app.roll.live.params, &s.app.roll.live.initial).unwrap();
    sim.run_to_end().time_s
}

#[test]
fn the_height_plot_marks_the_time_on_screen_on_an_axis_fitted_to_the_roll() {
    let s = plot_at(300, 1, false);
    let text = screen(&s.app, 120, 36);
    insta::assert_snapshot!("plot_height_120x36", text);
    insta::assert_snapshot!("plot_height_80x24", screen(&s.app, 80, 24));
    let rows = panel_rows(&text, "height of the centre · cm");
    // The axis's end label: a round number of seconds past the roll's end, not a fixed 1 s.
    let end = roll_end(&s);
    let label = rows
        .iter()
        .find_map(|l| {
            let at = l.find(" s")?;
            let number = l[..at].split_whitespace().last()?;
            number.parse::<f64>().ok()
        })
        .expect("a time label");
    assert!(
        label >= end && label < end + 0.5 * end.max(0.2),
        "axis to {label} s for a {end} s roll"
    );
    // The marker: one column of │ in the plot, at 0.3 s of the axis's span.
    let columns: Vec<usize> = rows
        .iter()
        .filter_map(|l| l.chars().position(|c| c == '│').filter(|&x| x > 0))
        .collect();
    assert!(columns.len() >= 3, "the time marker spans rows: {rows:#?}");
    // The y-axis line is the left border of the plot (the first column of ─ in the x axis).
    let axis_row = rows.iter().find(|l| l.contains("└")).expect("the x axis");
    let left = axis_row.chars().position(|c| c == '└').unwrap();
    let right = left + axis_row.chars().skip(left + 1).take_while(|&c| c == '─').count();
    let want = left as f64 + 0.3 / label * (right - left) as f64;
    assert!(
        columns.iter().any(|&c| (c as f64 - want).abs() <= 1.5),
        "marker columns {columns:?}, want about {want:.1}"
    );
}

#[test]
fn the_contact_force_plot_is_flat_in_flight_and_spikes_at_the_impacts() {
    let s = plot_at(300, 5, false);
    let text = screen(&s.app, 120, 36);
    insta::assert_snapshot!("plot_contact_force_120x36", text);
    insta::assert_snapshot!("plot_contact_force_80x24", screen(&s.app, 80, 24));
    assert!(text.contains("contact force · dyn"), "{text}");
    // The table pushes only on a die pressed into it: no force while the lowest corner is
    // above the table, and the largest force of the roll while it is below.
    let history = &s.app.roll.history;
    let (lowest, force) = (
        |h: &crate::worker::EnergySample| h.quantities[1],
        |h: &crate::worker::EnergySample| h.quantities[4],
    );
    assert!(
        history
            .iter()
            .filter(|h| lowest(h) > 0.0)
            .all(|h| force(h) == 0.0)
    );
    let peak = history
        .iter()
        .max_by(|a, b| force(a).total_cmp(&force(b)))
        .unwrap();
    assert!(lowest(peak) < 0.0 && force(peak) > 0.0, "{peak:?}");
    assert!(
        history.iter().any(|h| lowest(h) > 0.0),
        "the roll starts in the air"
    );
}

#[test]
fn the_phase_plot_draws_the_speed_against_the_height_and_marks_the_state_on_screen() {
    let s = plot_at(300, 1, true);
    let text = screen(&s.app, 120, 36);
    insta::assert_snapshot!("plot_phase_120x36", text);
    insta::assert_snapshot!("plot_phase_80x24", screen(&s.app, 80, 24));
    assert!(text.contains("speed (cm/s) vs height (cm)"), "{text}");
    // One ● more than the same screen without the phase plot (the die marks its contacts
    // with ● too).
    let mut plain = plot_at(300, 1, false);
    plain.sync();
    let before = screen(&plain.app, 120, 36).matches('●').count();
    assert_eq!(
        text.matches('●').count(),
        before + 1,
        "one state on screen:\n{text}"
    );
    let narrow = screen(&s.app, 80, 24);
    assert!(narrow.contains("speed vs height"), "{narrow}");
}

#[test]
fn a_mid_roll_edit_is_marked_on_the_timeline_and_the_plot_and_the_old_run_stays_faded() {
    let mut s = plot_at(300, 0, false);
    let before = s.app.roll.history.clone();
    // The stiffness (the first row) one step up, at 0.3 s: the table acts at once.
    assert_eq!(s.app.die_screen.selected, 0);
    s.key(KeyCode::Right);
    assert_eq!(s.app.roll.edits, vec![300], "the worker's record of the edit");
    assert_eq!(s.app.roll.previous, before, "the run before the edit, kept whole");
    s.run_to_end();
    // The new run shares the old one's samples up to the edit and parts from it after.
    let shared = s.app.roll.history.iter().take_while(|h| h.time_s <= 0.3).count();
    assert_eq!(s.app.roll.history[..shared], before[..shared]);
    assert_ne!(s.app.roll.history[shared..], before[shared..shared + 1]);
    let text = screen(&s.app, 120, 36);
    insta::assert_snapshot!("plot_edit_120x36", text);
    insta::assert_snapshot!("plot_edit_80x24", screen(&s.app, 80, 24));
    assert_eq!(text.matches('▼').count(), 1, "the edit on the timeline:\n{text}");
    assert!(text.contains('┊'), "the edit on the plot:\n{text}");
    // A replay is a new run: no edit in it, the edited run now the faded one.
    let edited = s.app.roll.history.clone();
    s.key(KeyCode::Char('r'));
    s.sync();
    assert!(s.app.roll.edits.is_empty());
    assert_eq!(s.app.roll.previous, edited);
    assert!(!screen(&s.app, 120, 36).contains('▼'));
}

/// The largest value label of the energy plot's y axis on a 100×30 screen, erg.
fn energy_axis_top(s: &Harness) -> f64 {
    let rows = panel_rows(&screen(&s.app, 100, 30), "┌ energy ");
    let left = rows[0].split("┌ energy ").next().map_or(0, |l| l.chars().count());
    rows.iter()
        .skip(1)
        .filter_map(|row| {
            let inside: String = row.chars().skip(left + 1).collect();
            inside.split('│').next()?.trim().parse::<f64>().ok()
        })
        .fold(0.0, f64::max)
}

#[test]
fn a_previous_rolls_ghost_does_not_set_the_energy_axis() {
    let mut s = Harness::new(&Preset::default(), Theme::default());
    s.run_to_end();
    let paper_top = energy_axis_top(&s);
    let gentle = Store::new(None).load("gentle-drop").expect("shipped").0;
    s.command(Command::LoadPreset(Box::new(gentle)));
    s.run_to_end();
    assert!(!s.app.roll.previous.is_empty(), "paper's roll is the faded one");
    let start = s.app.roll.history[0].total;
    let top = energy_axis_top(&s);
    assert!(
        start / 2.0 <= top && top < 2.0 * start,
        "axis to {top} erg for a {start} erg roll (paper's to {paper_top})"
    );
    // A map cell replayed after paper's roll: the axis follows the replay, not the run before.
    let (params, initial) = (s.app.setup.params, s.app.setup.initial);
    s.command(Command::LoadPreset(Box::default()));
    s.run_to_end();
    s.command(Command::PlaySetup(Box::new(params), initial));
    s.run_to_end();
    assert!(
        s.app.roll.previous[0].total > 10.0 * start,
        "paper's roll is the faded one"
    );
    let top = energy_axis_top(&s);
    assert!(
        start / 2.0 <= top && top < 2.0 * start,
        "axis to {top} erg for a {start} erg replay"
    );
}

#[test]
fn the_energy_legend_names_every_term_at_both_sizes() {
    for theme in [Theme::default(), Theme::monochrome()] {
        let s = mid_impact_with(theme);
        for (w, h) in [(80, 24), (120, 36)] {
            let b = panel_at(&s.app, w, h, |a| a.energy, quantity_plot::render);
            let t = text(&b);
            for name in ["total", "transl", "rot", "grav", "elastic"] {
                assert!(t.contains(name), "{name} missing at {w}×{h}:\n{t}");
            }
            if !theme.colour {
                // Without colour every line has its own character, which the legend shows.
                for item in ["#total", "+transl", "xrot", "ograv", "*elastic"] {
                    assert!(t.contains(item), "`{item}` at {w}×{h}:\n{t}");
                }
            }
            // No tick reads like 99750: each is a multiple of a round step.
            let ticks: Vec<f64> = t
                .lines()
                .filter_map(|l| l.split('│').nth(1))
                .filter_map(|cell| cell.trim().parse::<f64>().ok())
                .collect();
            assert!(ticks.len() >= 2, "{t}");
            let step = (ticks[0] - ticks[1]).abs();
            let mantissa = step / 10f64.powf(step.log10().floor());
            assert!(
                [1.0, 2.0, 5.0].iter().any(|m| (m - mantissa).abs() < 1e-9),
                "{ticks:?}\n{t}"
            );
            let name = format!(
                "energy_{}_{w}x{h}",
                if theme.colour { "colour" } else { "no_colour" }
            );
            insta::assert_snapshot!(name, t);
        }
    }
}

#[test]
fn ticks_are_round_numbers() {
    assert_eq!(nice_ticks(0.0, 199_500.0, 3).2, vec![0.0, 100_000.0, 200_000.0]);
    let (lo, hi, ticks) = nice_ticks(-480.0, 120_000.0, 4);
    assert!(lo <= -480.0 && hi >= 120_000.0);
    let step = ticks[1] - ticks[0];
    let mantissa = step / 10f64.powf(step.log10().floor());
    assert!(
        [1.0, 2.0, 5.0].iter().any(|m| (m - mantissa).abs() < 1e-9),
        "step {step}"
    );
    assert!(ticks.len() <= 4);
    assert!(ticks.iter().all(|t| (t / step).fract().abs() < 1e-9), "{ticks:?}");
}

/// The plot's readout at the time marker: each plotted quantity's value at the state on
/// screen with its unit, in the plot's bottom border; the energy plot's terms in the
/// ledger beside it, titled with theirs.
#[test]
fn the_readout_shows_each_plotted_value_with_its_unit() {
    let mut s = start();
    s.simulator.advance_steps(120);
    s.sync();
    let die = s.app.roll.live.die.clone();
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

/// The plot panel (the energy plot) alone, in its place on a 120×36 screen.
#[test]
fn panel_energy_alone() {
    let app = mid_impact().app;
    insta::assert_snapshot!(
        "panel_energy",
        panel(&app, full().energy, super::render).backend()
    );
}
