//! Screens and panels from deterministic states: a fixed preset, exact step counts, keys
//! fed through `update` into the worker's simulator, no thread and no clock.

use super::state::app::App;
use super::state::messages::Msg;
use crate::tui::input::update::update;
use crate::tui::panels::die;
use crate::tui::panels::footer;
use crate::tui::panels::header;
use crate::tui::panels::outcomes;
use crate::tui::panels::params_panel::{self, STABILITY_CAUTION, STABILITY_DANGER};
use crate::tui::panels::quantity_plot;
use crate::tui::render::screen::render;
use crate::tui::vocabulary::layout::screen_layout;
use crate::tui::vocabulary::param::{Param, all};
use crate::tui::vocabulary::theme::Theme;
use crate::worker::{Command, Phase, Simulator};
use dicesim_physics::Status;
use dicesim_physics::{Limit, Stability};
use dicesim_setup::preset::Preset;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier};

/// The paper's constants with a spin and a push, so the die tumbles and lands on an edge.
pub(crate) fn spun_preset() -> Preset {
    Preset::default()
        .with_overrides(&["initial.angular_velocity=[12,-20,6]", "initial.velocity=[30,0,0]"])
        .expect("valid overrides")
}

/// A panel's drawing function, as `render` calls it.
pub(crate) type Panel = fn(&App, Rect, &mut ratatui::Frame);

/// The simulator and the app wired together as the event loop wires them, minus the thread.
pub(crate) struct Harness {
    pub(crate) simulator: Simulator,
    pub(crate) app: App,
}

impl Harness {
    pub(crate) fn new(preset: &Preset, theme: Theme) -> Harness {
        let mut simulator = Simulator::new(preset).expect("valid preset");
        let app = App::new(simulator.snapshot(), theme);
        Harness { simulator, app }
    }

    pub(crate) fn sync(&mut self) {
        let s = self.simulator.snapshot();
        update(&mut self.app, Msg::from(s));
    }

    pub(crate) fn command(&mut self, c: Command) {
        self.simulator.handle(c);
        self.sync();
    }

    pub(crate) fn key_with(&mut self, code: KeyCode, modifiers: KeyModifiers) {
        for effect in update(
            &mut self.app,
            Msg::Input(Event::Key(KeyEvent::new(code, modifiers))),
        ) {
            if let Some(c) = crate::tui::event_loop::effects::perform(&mut self.app, effect) {
                self.simulator.handle(c);
            }
        }
        self.sync();
    }

    pub(crate) fn key(&mut self, code: KeyCode) {
        self.key_with(code, KeyModifiers::NONE);
    }

    pub(crate) fn select(&mut self, p: Param) {
        let target = self
            .app
            .params_listed()
            .iter()
            .position(|&q| q == p)
            .expect("listed");
        while self.app.die_screen.selected != target {
            self.key(if self.app.die_screen.selected < target {
                KeyCode::Down
            } else {
                KeyCode::Up
            });
        }
    }

    pub(crate) fn run_to_end(&mut self) {
        self.simulator.run_to_end();
        self.sync();
    }
}

pub(crate) fn start() -> Harness {
    Harness::new(&spun_preset(), Theme::default())
}

/// The first impact, at the step where the ground's spring is squeezed most.
pub(crate) fn mid_impact_with(theme: Theme) -> Harness {
    let mut s = Harness::new(&spun_preset(), theme);
    while s.simulator.phase() != Phase::InContact {
        assert!(s.simulator.advance_steps(1) == 1, "the die reaches the ground");
    }
    loop {
        let before = s.simulator.simulation().energy().elastic;
        s.simulator.advance_steps(1);
        if s.simulator.simulation().energy().elastic < before {
            break;
        }
    }
    s.sync();
    s
}

pub(crate) fn mid_impact() -> Harness {
    mid_impact_with(Theme::default())
}

pub(crate) fn settled() -> Harness {
    let mut s = start();
    s.run_to_end();
    s
}

pub(crate) fn unstable() -> Harness {
    let mut s = start();
    s.select(Param::named("ground.stiffness"));
    s.key(KeyCode::Enter);
    for c in "2e7".chars() {
        s.key(KeyCode::Char(c));
    }
    s.key(KeyCode::Enter);
    s.run_to_end();
    s
}

pub(crate) fn help() -> Harness {
    let mut s = mid_impact();
    s.key(KeyCode::Char('?'));
    s
}

pub(crate) fn editing() -> Harness {
    let mut s = start();
    s.select(Param::named("ground.friction"));
    s.key(KeyCode::Enter);
    for c in "0.8".chars() {
        s.key(KeyCode::Char(c));
    }
    s
}

pub(crate) fn filled_table() -> Harness {
    let mut s = start();
    s.key(KeyCode::Char('b'));
    // A smaller batch than `b` asks for keeps the test quick; the path is the same.
    s.simulator.handle(Command::BatchCancel);
    s.command(Command::BatchStart(600));
    s.simulator.run_batch_here();
    s.key(KeyCode::Char('R'));
    s.run_to_end();
    s
}

fn draw(app: &App, width: u16, height: u16) -> Terminal<TestBackend> {
    let mut t = Terminal::new(TestBackend::new(width, height)).expect("test backend");
    t.draw(|f| render(app, f)).expect("draw");
    t
}

pub(crate) fn screen(app: &App, width: u16, height: u16) -> String {
    draw(app, width, height).backend().to_string()
}

fn lines_of(buffer: &Buffer) -> Vec<String> {
    let area = buffer.area;
    (area.top()..area.bottom())
        .map(|y| {
            (area.left()..area.right())
                .map(|x| buffer[(x, y)].symbol())
                .collect()
        })
        .collect()
}

#[test]
fn start_screen() {
    let s = start();
    assert_eq!(s.app.roll.live.step, 0);
    insta::assert_snapshot!("start_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("start_80x24", screen(&s.app, 80, 24));
}

/// The 120×36 screen is also the README's picture of the explorer (`tests/cli/docs.rs` holds
/// the README to this snapshot).
#[test]
fn mid_impact_screen() {
    let s = mid_impact();
    assert_eq!(s.app.roll.live.phase, Phase::InContact);
    insta::assert_snapshot!("mid_impact_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("mid_impact_80x24", screen(&s.app, 80, 24));
}

#[test]
fn settled_screen() {
    let s = settled();
    assert!(matches!(s.app.roll.live.phase, Phase::Ended(o) if o.status == Status::Settled));
    insta::assert_snapshot!("settled_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("settled_80x24", screen(&s.app, 80, 24));
}

#[test]
fn unstable_screen() {
    let s = unstable();
    assert!(matches!(s.app.roll.live.phase, Phase::Ended(o) if o.status == Status::Unstable));
    assert_eq!(s.app.setup.params.ground.stiffness, 2e7);
    insta::assert_snapshot!("unstable_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("unstable_80x24", screen(&s.app, 80, 24));
}

#[test]
fn help_overlay() {
    let s = help();
    insta::assert_snapshot!("help_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("help_80x24", screen(&s.app, 80, 24));
}

#[test]
fn editing_a_value() {
    let mut s = editing();
    insta::assert_snapshot!("editing_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("editing_80x24", screen(&s.app, 80, 24));
    for _ in 0..3 {
        s.key(KeyCode::Backspace);
    }
    s.key(KeyCode::Char('9'));
    s.key(KeyCode::Enter);
    assert!(
        s.app.value_editor().is_some_and(|e| e.error.is_some()),
        "9 is outside 0…5"
    );
    assert_eq!(
        s.app.setup.params.ground.friction,
        spun_preset().ground.friction,
        "a refused value changes nothing"
    );
    insta::assert_snapshot!("editing_refused_120x36", screen(&s.app, 120, 36));
}

#[test]
fn filled_outcome_table() {
    let s = filled_table();
    assert_eq!(s.app.roll.table.rolls(), 601);
    insta::assert_snapshot!("table_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("table_80x24", screen(&s.app, 80, 24));
}

#[test]
fn too_small_says_how_large() {
    let s = start();
    let text = screen(&s.app, 70, 20);
    assert!(text.contains("at least 80×24"), "{text}");
    insta::assert_snapshot!("too_small_70x20", text);
}

#[test]
fn each_panel() {
    let table = filled_table();
    let impact = mid_impact();
    let areas = screen_layout(Rect::new(0, 0, 120, 36)).expect("full size");
    let panels: [(&str, &App, Rect, Panel); 6] = [
        ("panel_header", &impact.app, areas.header, header::render),
        ("panel_params", &impact.app, areas.params, params_panel::render),
        ("panel_outcomes", &table.app, areas.outcomes, outcomes::render),
        ("panel_die", &impact.app, areas.die, die::render),
        ("panel_energy", &impact.app, areas.energy, quantity_plot::render),
        ("panel_footer", &impact.app, areas.footer, footer::render),
    ];
    for (name, app, area, panel) in panels {
        let mut t = Terminal::new(TestBackend::new(area.width, area.height)).expect("test backend");
        t.draw(|f| panel(app, f.area(), f)).expect("draw");
        insta::assert_snapshot!(name, t.backend());
    }
}

#[test]
fn energy_log_scale_and_ascii_die() {
    let mut s = mid_impact();
    s.key(KeyCode::Char('p'));
    s.key(KeyCode::Char('m'));
    assert!(s.app.die_screen.log_scale);
    let areas = screen_layout(Rect::new(0, 0, 120, 36)).expect("full size");
    let t = draw(&s.app, 120, 36);
    let text = t.backend().to_string();
    assert!(text.contains("log (y)"));
    let die = lines_of(t.backend().buffer())[areas.die.y as usize..areas.die.bottom() as usize].join("\n");
    assert!(
        ['-', '|', '/', '\\'].iter().any(|&c| die.contains(c))
            && !die.contains('*')
            && !die.chars().any(|c| ('\u{2800}'..='\u{28ff}').contains(&c)),
        "ASCII only:\n{die}"
    );
    insta::assert_snapshot!("log_ascii_120x36", text);
}

/// Cells of the die panel that mark a touching corner.
fn contact_cells(buffer: &Buffer, area: Rect, mark: &str) -> Vec<(u16, u16)> {
    let mut cells = Vec::new();
    for y in area.top()..area.bottom() {
        for x in area.left()..area.right() {
            if buffer[(x, y)].symbol() == mark {
                cells.push((x, y));
            }
        }
    }
    cells
}

#[test]
fn touching_corners_are_red_and_bold_or_reversed_without_colour() {
    let areas = screen_layout(Rect::new(0, 0, 120, 36)).expect("full size");
    let s = mid_impact();
    let touching = s
        .app
        .roll
        .live
        .die
        .forces
        .iter()
        .filter(|f| f.depth > 0.0)
        .count();
    assert!(touching > 0);
    let t = draw(&s.app, 120, 36);
    let cells = contact_cells(t.backend().buffer(), areas.die, "●");
    assert!(!cells.is_empty() && cells.len() <= touching);
    for (x, y) in cells {
        let c = &t.backend().buffer()[(x, y)];
        assert_eq!(c.fg, Color::Red);
        assert!(c.modifier.contains(Modifier::BOLD));
    }
    // Edges at a touching corner are drawn in the contact colour too.
    let red_lines = (areas.die.top()..areas.die.bottom())
        .flat_map(|y| (areas.die.left()..areas.die.right()).map(move |x| (x, y)))
        .filter(|&p| t.backend().buffer()[p].fg == Color::Red && t.backend().buffer()[p].symbol() != "●")
        .count();
    assert!(red_lines > 0);

    let mono = mid_impact_with(Theme::monochrome());
    let t = draw(&mono.app, 120, 36);
    let cells = contact_cells(t.backend().buffer(), areas.die, "●");
    assert!(!cells.is_empty());
    for (x, y) in cells {
        assert!(
            t.backend().buffer()[(x, y)]
                .modifier
                .contains(Modifier::BOLD | Modifier::REVERSED)
        );
    }
}

#[test]
fn no_color_sends_no_colour_at_all() {
    for mut s in [mid_impact_with(Theme::monochrome()), {
        let mut s = Harness::new(&spun_preset(), Theme::monochrome());
        s.command(Command::SetParam(
            Param::named("ground.stiffness").scan_key(),
            4e6,
        ));
        s
    }] {
        s.key(KeyCode::Char('?'));
        s.key(KeyCode::Char('?'));
        let t = draw(&s.app, 120, 36);
        let buffer = t.backend().buffer();
        for y in 0..36 {
            for x in 0..120 {
                let c = &buffer[(x, y)];
                assert_eq!(
                    (c.fg, c.bg),
                    (Color::Reset, Color::Reset),
                    "cell {x},{y} `{}`",
                    c.symbol()
                );
            }
        }
    }
}

/// The stability readout on the parameters panel's bottom border: its text and the style
/// of its first letter.
fn stability_readout_cell(app: &App) -> (String, ratatui::buffer::Cell) {
    let t = draw(app, 120, 36);
    let buffer = t.backend().buffer().clone();
    let lines = lines_of(&buffer);
    let y = lines
        .iter()
        .position(|l| l.contains("└ Δt"))
        .expect("the readout is on screen");
    let x = lines[y].split("└ Δt").next().expect("row").chars().count() + 2;
    let text = lines[y].split('┘').next().expect("row").to_string();
    (text, buffer[(x as u16, y as u16)].clone())
}

#[test]
fn stability_readout_warns_as_the_tightest_limit_nears() {
    let mut s = start();
    let (text, calm) = stability_readout_cell(&s.app);
    assert!(text.contains("of limit"), "{text}");
    assert_eq!(calm.bg, Color::Reset);
    // The contact-mode reading is ω_rock·√(1 + γ·u)·Δt, with ω_rock ∝ √k and the striking
    // factor √(1 + γ·u) free of k (docs/model.md, "Stability"): a share of its limit is
    // reached at k₀·(share·limit / reading₀)².
    let k_for = |share: f64, app: &App| {
        let p = &app.setup.params;
        let r = Stability::predict(p, &app.setup.initial)
            .reading(Limit::ContactMode)
            .unwrap();
        p.ground.stiffness * (share * r.allowed / r.value).powi(2)
    };
    let k = k_for((STABILITY_CAUTION + STABILITY_DANGER) / 2.0, &s.app);
    s.command(Command::SetParam(Param::named("ground.stiffness").scan_key(), k));
    let (text, caution) = stability_readout_cell(&s.app);
    assert!(text.contains("table stiffness at 90 % of limit"), "{text}");
    assert_eq!(caution.bg, Color::Yellow);
    let k = k_for(STABILITY_DANGER + 0.3, &s.app);
    s.command(Command::SetParam(Param::named("ground.stiffness").scan_key(), k));
    let (text, danger) = stability_readout_cell(&s.app);
    assert!(text.contains("table stiffness at 130 % of limit"), "{text}");
    assert_eq!(danger.bg, Color::Red);
    assert!(danger.modifier.contains(Modifier::BOLD));
}

/// Spin of 10 000 rad/s: the readout and the roll's end both say a corner moves too far
/// per step, and by how much.
#[test]
fn fast_spin_is_called_unstable_with_its_reason() {
    let preset = Preset::default()
        .with_overrides(&["initial.angular_velocity=[10000,0,0]"])
        .expect("in range");
    let mut s = Harness::new(&preset, Theme::default());
    let (text, _) = stability_readout_cell(&s.app);
    // Both the corner's travel (17.5 cm a step, 1749 % of its limit) and the table's
    // contact mode, stiffened by the striking corner's speed, are past their limits; the
    // readout names the first past its limit, never a share within it.
    let percent: f64 = text
        .split(" at ")
        .nth(1)
        .and_then(|t| t.split(" %").next())
        .and_then(|t| t.trim().parse().ok())
        .expect("a share");
    assert!(percent > 100.0, "{text}");
    s.run_to_end();
    assert!(matches!(s.app.roll.live.phase, Phase::Ended(o) if o.status == Status::Unstable));
    let wide = screen(&s.app, 120, 36);
    // ω·a·√3 + the fall from 15 cm, times Δt: 17.3 + 0.17 cm.
    assert!(
        wide.contains("unstable: spin too fast for Δt: a corner moves 17.489 cm per step"),
        "{wide}"
    );
    insta::assert_snapshot!("fast_spin_unstable_120x36", wide);
    insta::assert_snapshot!("fast_spin_unstable_80x24", screen(&s.app, 80, 24));
}

/// k = 100: the table cannot hold the die, so the roll runs to its time limit instead of
/// "settling" with the die sinking through the table.
#[test]
fn a_table_too_soft_ends_as_did_not_settle() {
    let preset = Preset::default()
        .with_overrides(&["ground.stiffness=100"])
        .expect("in range");
    let mut s = Harness::new(&preset, Theme::default());
    s.run_to_end();
    assert!(matches!(s.app.roll.live.phase, Phase::Ended(o) if o.status == Status::Timeout));
    let text = screen(&s.app, 120, 36);
    assert!(
        text.contains("did not settle: the table is too soft to hold the die"),
        "{text}"
    );
    insta::assert_snapshot!("soft_table_120x36", text);
}

#[test]
fn a_start_inside_the_table_is_refused() {
    let mut s = start();
    s.select(Param::named("initial.height"));
    s.key(KeyCode::Enter);
    for _ in 0..4 {
        s.key(KeyCode::Backspace);
    }
    s.key(KeyCode::Char('0'));
    s.key(KeyCode::Enter);
    assert_eq!(s.app.setup.initial.height, 15.0);
    let text = screen(&s.app, 120, 36);
    assert!(text.contains("0: corner in the table; ≥ 0.9961 cm"), "{text}");
    insta::assert_snapshot!("start_inside_table_refused_80x24", screen(&s.app, 80, 24));
}

/// Pure key handling: an app, a key, the commands it sends; no worker involved.
mod keys {
    use super::*;
    use crate::worker::Speed;
    use ratatui::crossterm::event::{KeyEventKind, MouseButton, MouseEvent, MouseEventKind};

    fn app() -> App {
        start().app
    }

    fn press(app: &mut App, code: KeyCode) -> Vec<Command> {
        press_with(app, code, KeyModifiers::NONE)
    }

    fn press_with(app: &mut App, code: KeyCode, modifiers: KeyModifiers) -> Vec<Command> {
        update(app, Msg::Input(Event::Key(KeyEvent::new(code, modifiers))))
            .into_iter()
            .filter_map(|e| crate::tui::event_loop::effects::perform(app, e))
            .collect()
    }

    fn mouse(app: &mut App, kind: MouseEventKind, column: u16, row: u16) -> Vec<Command> {
        let m = MouseEvent {
            kind,
            column,
            row,
            modifiers: KeyModifiers::NONE,
        };
        update(app, Msg::Input(Event::Mouse(m)))
            .into_iter()
            .filter_map(|e| crate::tui::event_loop::effects::perform(app, e))
            .collect()
    }

    #[test]
    fn playback_keys_send_their_commands() {
        let mut a = app();
        assert_eq!(press(&mut a, KeyCode::Char(' ')), [Command::TogglePlay]);
        assert_eq!(press(&mut a, KeyCode::Char('n')), [Command::Step(1)]);
        assert_eq!(press(&mut a, KeyCode::Char('r')), [Command::Replay]);
        assert_eq!(press(&mut a, KeyCode::Char('R')), [Command::RandomRoll]);
        assert_eq!(press(&mut a, KeyCode::Char('c')), [Command::ClearTable]);
        assert_eq!(
            press(&mut a, KeyCode::Char('b')),
            [Command::BatchStart(super::super::state::roll_view::BATCH_ROLLS)]
        );
        assert!(!a.quit);
    }

    #[test]
    fn b_cancels_a_running_batch() {
        let mut s = start();
        s.key(KeyCode::Char('b'));
        assert!(s.app.roll.batch.is_some());
        assert_eq!(press(&mut s.app, KeyCode::Char('b')), [Command::BatchCancel]);
    }

    #[test]
    fn speed_walks_the_ladder_and_stops_at_its_ends() {
        let mut a = app();
        let start = a.setup.speed;
        assert_eq!(
            press(&mut a, KeyCode::Char('[')),
            [Command::SetSpeed(start.slower())]
        );
        assert_eq!(press(&mut a, KeyCode::Char(']')), [Command::SetSpeed(start)]);
        assert_eq!(
            press(&mut a, KeyCode::Char('+')),
            [Command::SetSpeed(start.faster())]
        );
        assert_eq!(press(&mut a, KeyCode::Char('-')), [Command::SetSpeed(start)]);
        for _ in 0..30 {
            press(&mut a, KeyCode::Char(']'));
        }
        assert_eq!(a.setup.speed, Speed::INSTANT);
        assert!(
            press(&mut a, KeyCode::Char(']')).is_empty(),
            "nothing faster than instant"
        );
        for _ in 0..30 {
            press(&mut a, KeyCode::Char('-'));
        }
        assert_eq!(a.setup.speed, Speed::SLOWEST);
    }

    #[test]
    fn arrows_and_vim_keys_select_and_change_values() {
        let mut a = app();
        assert_eq!(a.selected_param(), Param::named("ground.stiffness"));
        assert!(
            press(&mut a, KeyCode::Up).is_empty(),
            "the first row stays selected"
        );
        press(&mut a, KeyCode::Down);
        press(&mut a, KeyCode::Char('j'));
        assert_eq!(a.selected_param(), Param::named("ground.friction"));
        let mu = a.setup.params.ground.friction;
        let fine = Param::named("ground.friction").nudged(mu, 1, false);
        assert_eq!(
            press(&mut a, KeyCode::Right),
            [Command::SetParam(
                Param::named("ground.friction").scan_key(),
                fine
            )]
        );
        assert_eq!(
            a.setup.params.ground.friction, fine,
            "the list shows the new value at once"
        );
        let coarse = Param::named("ground.friction").nudged(fine, -1, true);
        assert_eq!(
            press_with(&mut a, KeyCode::Left, KeyModifiers::SHIFT),
            [Command::SetParam(
                Param::named("ground.friction").scan_key(),
                coarse
            )]
        );
        let back = Param::named("ground.friction").nudged(coarse, 1, true);
        assert_eq!(
            press(&mut a, KeyCode::Char('L')),
            [Command::SetParam(
                Param::named("ground.friction").scan_key(),
                back
            )]
        );
        let down = Param::named("ground.friction").nudged(back, -1, false);
        assert_eq!(
            press(&mut a, KeyCode::Char('h')),
            [Command::SetParam(
                Param::named("ground.friction").scan_key(),
                down
            )]
        );
        press(&mut a, KeyCode::Char('k'));
        assert_eq!(a.selected_param(), Param::named("ground.damping"));
        press(&mut a, KeyCode::Char('G'));
        assert_eq!(a.selected_param(), *a.params_listed().last().expect("rows"));
    }

    #[test]
    fn a_value_at_its_limit_sends_nothing() {
        let mut a = app();
        a.die_screen.selected = a
            .params_listed()
            .iter()
            .position(|&p| p == Param::named("ground.friction"))
            .expect("listed");
        assert_eq!(press(&mut a, KeyCode::Enter), []);
        for c in "0".chars() {
            press(&mut a, KeyCode::Char(c));
        }
        assert_eq!(
            press(&mut a, KeyCode::Enter),
            [Command::SetParam(Param::named("ground.friction").scan_key(), 0.0)]
        );
        assert!(press(&mut a, KeyCode::Left).is_empty());
    }

    #[test]
    fn typing_a_value_validates_it_and_esc_cancels() {
        let mut a = app();
        a.die_screen.selected = a
            .params_listed()
            .iter()
            .position(|&p| p == Param::named("initial.height"))
            .expect("listed");
        press(&mut a, KeyCode::Enter);
        assert!(a.value_editor().is_some());
        for c in "2x5q".chars() {
            // Every printable character is text here: q does not quit, x is typed.
            press(&mut a, KeyCode::Char(c));
        }
        assert!(!a.quit);
        assert_eq!(a.value_editor().map(|e| e.text.as_str()), Some("2x5q"));
        assert!(press(&mut a, KeyCode::Enter).is_empty());
        assert!(a.value_editor().is_some_and(|e| {
            e.error
                .as_deref()
                .is_some_and(|m| m.contains("`2x5q` is not a number"))
        }));
        for _ in 0..3 {
            press(&mut a, KeyCode::Backspace);
        }
        for c in "5e9".chars() {
            press(&mut a, KeyCode::Char(c));
        }
        assert!(
            press(&mut a, KeyCode::Enter).is_empty(),
            "25e9 cm is out of range"
        );
        assert!(a.value_editor().is_some_and(|e| {
            e.error
                .as_deref()
                .is_some_and(|m| m.contains("outside 0…1000 cm"))
        }));
        press(&mut a, KeyCode::Backspace);
        press(&mut a, KeyCode::Backspace);
        assert_eq!(
            press(&mut a, KeyCode::Enter),
            [Command::SetParam(Param::named("initial.height").scan_key(), 25.0)]
        );
        assert!(a.value_editor().is_none());
        press(&mut a, KeyCode::Enter);
        press(&mut a, KeyCode::Char('7'));
        assert!(press(&mut a, KeyCode::Esc).is_empty());
        assert!(
            a.value_editor().is_none() && !a.quit,
            "Esc leaves the editor, not the program"
        );
        assert_eq!(a.setup.initial.height, 25.0);
    }

    #[test]
    fn quitting_keys() {
        for (code, modifiers) in [
            (KeyCode::Char('q'), KeyModifiers::NONE),
            (KeyCode::Char('c'), KeyModifiers::CONTROL),
        ] {
            let mut a = app();
            assert_eq!(press_with(&mut a, code, modifiers), [Command::Quit]);
            assert!(a.quit);
        }
        let mut a = app();
        press(&mut a, KeyCode::Enter);
        assert_eq!(
            press_with(&mut a, KeyCode::Char('c'), KeyModifiers::CONTROL),
            [Command::Quit],
            "also while typing"
        );
    }

    #[test]
    fn help_opens_scrolls_and_closes_without_quitting() {
        let mut a = app();
        press(&mut a, KeyCode::Char('?'));
        assert!(a.help_scroll().is_some());
        assert!(
            press(&mut a, KeyCode::Char(' ')).is_empty(),
            "keys do not reach the die under the help"
        );
        press(&mut a, KeyCode::Down);
        assert_eq!(a.help_scroll(), Some(1));
        press(&mut a, KeyCode::Esc);
        assert!(a.help_scroll().is_none() && !a.quit);
        press(&mut a, KeyCode::Char('?'));
        assert_eq!(a.help_scroll(), Some(0));
        press(&mut a, KeyCode::Char('?'));
        assert!(a.help_scroll().is_none());
    }

    #[test]
    fn view_keys_change_only_the_view() {
        let mut a = app();
        let camera = a.die_screen.camera;
        for c in ['a', 'W', 'z', 'p', 'm'] {
            assert!(press(&mut a, KeyCode::Char(c)).is_empty());
        }
        assert!(
            a.die_screen.camera.yaw_deg != camera.yaw_deg && a.die_screen.camera.pitch_deg > camera.pitch_deg
        );
        assert!(a.die_screen.camera.zoom > camera.zoom && a.die_screen.log_scale);
        press(&mut a, KeyCode::Char('C'));
        assert_eq!(a.die_screen.camera, camera);
    }

    #[test]
    fn key_releases_are_ignored() {
        let mut a = app();
        let mut release = KeyEvent::new(KeyCode::Char('q'), KeyModifiers::NONE);
        release.kind = KeyEventKind::Release;
        assert!(update(&mut a, Msg::Input(Event::Key(release))).is_empty());
        assert!(!a.quit);
    }

    #[test]
    fn click_selects_a_parameter_and_scroll_changes_it() {
        let mut a = app();
        update(&mut a, Msg::Input(Event::Resize(120, 36)));
        let areas = screen_layout(a.screen).expect("full size");
        // Row 0 of the list is the heading; the rows follow in list order.
        let friction_row = areas.params.y
            + 2
            + a.params_listed()
                .iter()
                .position(|&p| p == Param::named("ground.friction"))
                .expect("listed") as u16;
        assert!(
            mouse(
                &mut a,
                MouseEventKind::Down(MouseButton::Left),
                areas.params.x + 3,
                friction_row
            )
            .is_empty()
        );
        assert_eq!(a.selected_param(), Param::named("ground.friction"));
        let up = Param::named("ground.friction").nudged(a.setup.params.ground.friction, 1, false);
        assert_eq!(
            mouse(&mut a, MouseEventKind::ScrollUp, areas.params.x + 3, friction_row),
            [Command::SetParam(Param::named("ground.friction").scan_key(), up)]
        );
        let zoom = a.die_screen.camera.zoom;
        mouse(&mut a, MouseEventKind::ScrollUp, areas.die.x + 5, areas.die.y + 5);
        assert_eq!(a.die_screen.camera.zoom, zoom + 1);
        let yaw = a.die_screen.camera.yaw_deg;
        mouse(
            &mut a,
            MouseEventKind::Down(MouseButton::Left),
            areas.die.x + 5,
            areas.die.y + 5,
        );
        mouse(
            &mut a,
            MouseEventKind::Drag(MouseButton::Left),
            areas.die.x + 8,
            areas.die.y + 5,
        );
        assert!(
            a.die_screen.camera.yaw_deg != yaw,
            "dragging the die orbits the camera"
        );
    }

    #[test]
    fn own_edits_win_until_the_worker_has_seen_them() {
        let mut s = start();
        let stale = s.simulator.snapshot();
        press(&mut s.app, KeyCode::Down);
        press(&mut s.app, KeyCode::Down);
        let cmds = press(&mut s.app, KeyCode::Right);
        let mine = s.app.setup.params.ground.friction;
        update(&mut s.app, Msg::from(stale));
        assert_eq!(
            s.app.setup.params.ground.friction, mine,
            "an older snapshot does not undo the edit"
        );
        for c in cmds {
            s.simulator.handle(c);
        }
        s.sync();
        assert_eq!(s.app.setup.params.ground.friction, mine);
        assert_eq!(s.app.roll.live.params.ground.friction, mine);
    }
}

/// The terminal sizes where a layout changes, and either side of each: the tiny sizes where
/// every panel collapses, the minimum screen (80×24), the wide layout (120 columns) and the
/// widest tested. Random sizes between them are left to the proptests.
pub(super) fn boundary_sizes() -> impl Iterator<Item = (u16, u16)> {
    const WIDTHS: [u16; 10] = [1, 2, 3, 79, 80, 81, 119, 120, 121, 200];
    const HEIGHTS: [u16; 9] = [1, 2, 3, 23, 24, 25, 35, 36, 60];
    WIDTHS
        .into_iter()
        .flat_map(|w| HEIGHTS.into_iter().map(move |h| (w, h)))
}

/// Rendering never panics, whatever the size and the state.
mod sizes {
    use super::*;
    use proptest::prelude::*;
    use std::sync::OnceLock;

    /// A spread of states, built once: each render below is cheap, the physics is not.
    fn states() -> &'static Vec<App> {
        static STATES: OnceLock<Vec<App>> = OnceLock::new();
        STATES.get_or_init(|| {
            let mut help_scrolled = help();
            for _ in 0..40 {
                help_scrolled.key(KeyCode::Down);
            }
            let mut refused = editing();
            refused.key(KeyCode::Char('9'));
            refused.key(KeyCode::Enter);
            vec![
                start().app,
                mid_impact().app,
                settled().app,
                unstable().app,
                help_scrolled.app,
                refused.app,
                filled_table().app,
                mid_impact_with(Theme::monochrome()).app,
            ]
        })
    }

    fn draw_into(app: &App, width: u16, height: u16) {
        let mut t = Terminal::new(TestBackend::new(width, height)).expect("test backend");
        t.draw(|f| render(app, f)).expect("draw");
    }

    #[test]
    fn every_boundary_size_draws() {
        for app in states() {
            for (width, height) in boundary_sizes() {
                draw_into(app, width, height);
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        #[test]
        fn random_states_at_random_sizes_draw(
            which in 0usize..8,
            width in 1u16..=200,
            height in 1u16..=60,
            yaw in -720.0f64..720.0,
            pitch in -90.0f64..90.0,
            zoom in -20i32..20,
            selected in 0usize..all().len(),
            log in any::<bool>(),
            ascii in any::<bool>(),
            help_scroll in 0u16..200,
        ) {
            let mut app = states()[which].clone();
            app.die_screen.camera.orbit(yaw, pitch);
            app.die_screen.camera.zoom_by(zoom);
            app.die_screen.selected = selected;
            app.die_screen.log_scale = log;
            if app.help_scroll().is_some() {
                app.overlay = Some(super::super::state::app::Overlay::Help { scroll: help_scroll });
            }
            app.die_screen.drawing = if ascii { super::super::state::die_screen::Drawing::Ascii } else { super::super::state::die_screen::Drawing::Braille };
            app.screen = Rect::new(0, 0, width, height);
            draw_into(&app, width, height);
        }
    }
}

/// Text that came from a file (a preset's name, an error quoting it) never sends a control
/// character to the terminal: the footer's notices show it escaped, and no cell holds one.
#[test]
fn control_characters_from_files_never_reach_the_terminal() {
    let title = "\u{1b}]0;owned\u{7}";
    let preset = Preset {
        name: format!("x{title}"),
        ..Preset::default()
    };
    let mut s = Harness::new(&preset, Theme::default());
    s.app.notice = Some(format!("cannot open {title}.toml"));
    let t = draw(&s.app, 120, 36);
    let buffer = t.backend().buffer();
    for line in lines_of(buffer) {
        assert!(!line.contains(char::is_control), "{line:?}");
    }
    let footer = &lines_of(buffer)[35];
    assert!(
        footer.contains(r"cannot open \u{1b}]0;owned\u{7}.toml"),
        "{footer}"
    );
}

/// A batch whose random drop heights reach below the die's lowest corner (the paper's
/// preset keeps the start's orientation, upright: a cm below the centre) is refused up
/// front, as `dicesim batch` refuses it: no roll is drawn, the table stays empty and the
/// footer names the key and the lowest allowed height.
#[test]
fn a_batch_whose_range_could_start_a_corner_in_the_table_is_refused() {
    let preset = Preset::default()
        .with_overrides(&["random.height=[0.5,2]"])
        .expect("in range");
    let mut s = Harness::new(&preset, Theme::default());
    s.command(Command::BatchStart(20));
    assert!(s.simulator.take_batch_request().is_none(), "a batch was started");
    s.simulator.run_batch_here();
    s.sync();
    let text = screen(&s.app, 120, 36);
    assert!(text.contains("batch not started"), "{text}");
    assert!(text.contains("random.height"), "{text}");
    // a = 1 cm less the resting depth M·g/(4k) = 8·980/(4·500 000) = 0.00392 cm.
    assert!(text.contains("0.99608"), "{text}");
    assert_eq!(s.app.roll.table.rolls(), 0);
}
