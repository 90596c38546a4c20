//! The explorer's test fixtures: a harness that runs the simulator beside the app, the
//! states every test starts from, and drawing them.

use crate::tui::input::update::update;
use crate::tui::render::screen::render;
use crate::tui::state::app::App;
use crate::tui::state::messages::{Effect, Msg};
use crate::tui::vocabulary::layout::screen_layout;
use crate::tui::vocabulary::param::Param;
use crate::tui::vocabulary::theme::{Palette, Theme};
use crate::worker::{Command, CurveSetup, CurveState, CurveUpdate, MapUpdate, Phase, Simulator};
use dicesim_experiment::predict::{PredictCurve, run_prediction};
use dicesim_experiment::{BasinMap, MapSpec, Method, RunOptions, run_map};
use dicesim_setup::preset::{Preset, Store, shipped_text};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::layout::Rect;
use std::sync::LazyLock;
use std::sync::atomic::AtomicBool;

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

    /// The worker's snapshot into the app, and what the app asks in answer (a preset's map
    /// screen starts its map) back to the worker, as the event loop does.
    pub(crate) fn sync(&mut self) {
        let s = self.simulator.snapshot();
        for effect in update(&mut self.app, Msg::from(s)) {
            if let Some(c) = crate::tui::event_loop::effects::perform(&mut self.app, effect) {
                self.simulator.handle(c);
            }
        }
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

pub(crate) fn draw(app: &App, width: u16, height: u16) -> Terminal<TestBackend> {
    let mut t = Terminal::new(TestBackend::new(width, height)).expect("test backend");
    t.draw(|f| render(app, f)).expect("draw");
    t
}

pub(crate) fn screen(app: &App, width: u16, height: u16) -> String {
    draw(app, width, height).backend().to_string()
}

pub(crate) fn lines_of(buffer: &Buffer) -> Vec<String> {
    let area = buffer.area;
    (area.top()..area.bottom())
        .map(|y| {
            (area.left()..area.right())
                .map(|x| buffer[(x, y)].symbol())
                .collect()
        })
        .collect()
}

/// The terminal sizes where a layout changes, and either side of each: the tiny sizes where
/// every panel collapses, the minimum screen (80×24), the wide layout (120 columns) and the
/// widest tested. Random sizes between them are left to the proptests.
pub(crate) fn boundary_sizes() -> impl Iterator<Item = (u16, u16)> {
    const WIDTHS: [u16; 10] = [1, 2, 3, 79, 80, 81, 119, 120, 121, 200];
    const HEIGHTS: [u16; 9] = [1, 2, 3, 23, 24, 25, 35, 36, 60];
    WIDTHS
        .into_iter()
        .flat_map(|w| HEIGHTS.into_iter().map(move |h| (w, h)))
}

/// Grid nodes of the test map: small enough to compute in a moment, odd in y so the last
/// character row holds a single cell.
pub(crate) const CELLS: (usize, usize) = (40, 27);

/// The map the app asked for last, at [`CELLS`], as the worker would compute it.
pub(crate) fn computed(app: &App) -> MapUpdate {
    let (request, params, initial) = app.map.requested.expect("a map was requested");
    let mut x = request.x;
    let mut y = request.y;
    (x.cells, y.cells) = CELLS;
    let spec = MapSpec {
        x: x.axis().expect("valid axis"),
        y: y.axis().expect("valid axis"),
        method: Method::Adaptive,
    };
    let never = AtomicBool::new(false);
    let map = run_map(&params, &initial, &spec, 0, &never, &mut |_| {}).expect("the map computes");
    assert!(map.complete);
    MapUpdate {
        generation: request.generation,
        params,
        initial,
        map: Ok(map),
    }
}

/// The die view's scene, switched to the map screen, with the map in and the cursor moved.
/// `e` on the map screen, and the export it orders run into `dir` as the worker's export
/// runner would run it (the key itself asks for the current folder).
pub(crate) fn export_into(s: &mut Harness, dir: &std::path::Path) {
    for c in press(&mut s.app, KeyCode::Char('e')) {
        let c = match c {
            Command::ExportMap(mut m) => {
                m.dir = dir.to_path_buf();
                Command::ExportMap(m)
            }
            other => other,
        };
        s.simulator.handle(c);
    }
    s.simulator.run_export_here();
    s.sync();
}

pub(crate) fn map_scene(theme: Theme) -> Harness {
    let mut s = Harness::new(&spun_preset(), theme);
    let sent = press(&mut s.app, KeyCode::Tab);
    assert!(matches!(sent[..], [Command::MapStart(_)]), "{sent:?}");
    let m = computed(&s.app);
    update(&mut s.app, Msg::from(m));
    // The terminal asked for a larger grid than the test computes: start from its middle.
    s.app.map.cursor = (CELLS.0 / 2, CELLS.1 / 2);
    for k in [KeyCode::Right, KeyCode::Right, KeyCode::Right, KeyCode::Up] {
        press(&mut s.app, k);
    }
    s
}

/// The paper's roll and its twin at ε = 1e-9, 700 steps in, paused.
pub(crate) fn twin_scene(theme: Theme) -> Harness {
    let mut s = start();
    s.app.theme = theme;
    s.key(KeyCode::Char('T'));
    s.command(Command::SetPlaying(false));
    s.simulator.advance_steps(700);
    s.sync();
    s
}

/// The setup's curve after its first chunk of rolls, and complete.
pub(crate) fn curves() -> &'static (PredictCurve, PredictCurve) {
    static CURVES: LazyLock<(PredictCurve, PredictCurve)> = LazyLock::new(|| {
        let setup = twin_scene(Theme::default())
            .simulator
            .curve_setup()
            .expect("a twin rolls");
        let spec = dicesim_experiment::predict::PredictSpec {
            count: THROWS,
            ..setup.spec()
        };
        let mut first = None;
        let p = run_prediction(
            &setup.params,
            &setup.ranges,
            &setup.base,
            &spec,
            &RunOptions::default(),
            &AtomicBool::new(false),
            &mut |p| {
                first.get_or_insert_with(|| p.curve.clone());
            },
        )
        .expect("the experiment runs");
        let partial = first.expect("a chunk came before the end");
        assert!(partial.starts < THROWS, "{} starts", partial.starts);
        (partial, p.curves[0].clone())
    });
    &CURVES
}

/// The scene with `state` delivered as the worker delivers it: in a snapshot.
pub(crate) fn with_curve(mut s: Harness, generation: u64, state: CurveState) -> Harness {
    let mut snapshot = s.simulator.snapshot();
    snapshot.curve = Some(CurveUpdate {
        generation,
        count: THROWS,
        state,
    });
    update(&mut s.app, Msg::from(snapshot));
    s
}

pub(crate) fn complete(theme: Theme) -> Harness {
    with_curve(twin_scene(theme), 1, CurveState::Complete(curves().1.clone()))
}

pub(crate) fn partial() -> Harness {
    with_curve(
        twin_scene(Theme::default()),
        1,
        CurveState::Computing(Some(curves().0.clone())),
    )
}

/// A setup whose throws cannot settle: the time cap ends every roll in mid-air.
pub(crate) fn failed() -> Harness {
    let s = twin_scene(Theme::default());
    let mut setup: CurveSetup = s.simulator.curve_setup().expect("a twin rolls");
    setup.params.integrator.max_time = 0.01;
    let state = crate::worker::curve::compute(&setup, &AtomicBool::new(false), &mut |_| {});
    with_curve(s, 1, state)
}

/// The paper's spun roll `steps` steps in: at 150 the die is still falling, tumbling.
pub(crate) fn after(steps: u64, theme: Theme) -> Harness {
    let mut s = Harness::new(&spun_preset(), theme);
    s.simulator.advance_steps(steps);
    s.sync();
    s
}

/// The shipped loaded die, `steps` steps into its own roll.
pub(crate) fn loaded_after(steps: u64, theme: Theme) -> Harness {
    use dicesim_setup::preset::{Preset, shipped_text};
    let text = shipped_text("loaded-corner").expect("shipped");
    let preset = Preset::from_toml_str(text, "loaded-corner").expect("valid");
    let mut s = Harness::new(&preset, theme);
    s.simulator.advance_steps(steps);
    s.sync();
    s
}

pub(crate) fn press(app: &mut App, code: KeyCode) -> Vec<Command> {
    update(
        app,
        Msg::Input(Event::Key(KeyEvent::new(code, KeyModifiers::NONE))),
    )
    .into_iter()
    .filter_map(Effect::command)
    .collect()
}

/// A key pressed, and the effects it asks for performed as the event loop would: the
/// worker's commands among them.
pub(crate) fn press_performing(app: &mut App, code: KeyCode) -> Vec<Command> {
    update(
        app,
        Msg::Input(Event::Key(KeyEvent::new(code, KeyModifiers::NONE))),
    )
    .into_iter()
    .filter_map(|e| crate::tui::event_loop::effects::perform(app, e))
    .collect()
}

pub(crate) fn map_of(app: &App) -> &BasinMap {
    app.map.map().expect("a map is shown")
}

/// Throws in the test curves: one chunk and a half of the batch machinery, so the first
/// chunk gives a partial curve.
pub(crate) const THROWS: u64 = 48;

/// One panel drawn where the layout of a `w`×`h` terminal puts it, painted as the screen is.
pub(crate) fn panel_at(
    app: &App,
    w: u16,
    h: u16,
    pick: fn(&crate::tui::vocabulary::layout::Areas) -> Rect,
    draw: Panel,
) -> Buffer {
    let area = pick(&screen_layout(Rect::new(0, 0, w, h)).expect("big enough"));
    let mut t = Terminal::new(TestBackend::new(area.width, area.height)).expect("test backend");
    t.draw(|f| {
        draw(app, f.area(), f);
        app.theme.paint(f.buffer_mut());
    })
    .expect("draw");
    t.backend().buffer().clone()
}

pub(crate) fn text(b: &Buffer) -> String {
    let a = b.area;
    (a.top()..a.bottom())
        .map(|y| {
            (a.left()..a.right())
                .map(|x| b[(x, y)].symbol())
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

pub(crate) fn at_rest(theme: Theme) -> Harness {
    let mut s = Harness::new(&spun_preset(), theme);
    s.run_to_end();
    s
}

/// One panel drawn on its own, as the full 120×36 screen places it.
pub(crate) fn panel(
    app: &App,
    area: Rect,
    draw: fn(&App, Rect, &mut ratatui::Frame),
) -> Terminal<TestBackend> {
    let mut t = Terminal::new(TestBackend::new(area.width, area.height)).expect("test backend");
    t.draw(|f| draw(app, f.area(), f)).expect("draw");
    t
}

pub(crate) fn full() -> crate::tui::vocabulary::layout::Areas {
    screen_layout(Rect::new(0, 0, 120, 36)).expect("full size")
}

/// The paper's roll computed to its end, then stepped back to step 170 (its first impact).
pub(crate) fn stepped_back() -> Harness {
    let mut s = start();
    s.run_to_end();
    s.key(KeyCode::Home);
    for _ in 0..170 {
        s.key(KeyCode::Char('.'));
    }
    s
}

/// The line of the screen that holds `needle`.
pub(crate) fn line_with(text: &str, needle: &str) -> String {
    text.lines()
        .find(|l| l.contains(needle))
        .unwrap_or_else(|| panic!("no `{needle}` in\n{text}"))
        .to_string()
}

pub(crate) fn shipped(name: &str) -> Harness {
    let preset = Preset::from_toml_str(shipped_text(name).expect("shipped"), name).expect("valid");
    let mut s = Harness::new(&preset, projector());
    s.app.store = Store::new(None);
    s
}

/// The paper's roll and its twin at ε = 1e-9, `steps` steps in.
pub(crate) fn twin_after(steps: u64) -> Harness {
    let mut s = start();
    s.key(KeyCode::Char('T'));
    s.command(Command::SetPlaying(false));
    s.simulator.advance_steps(steps);
    s.sync();
    s
}

/// The stability readout on the parameters panel's bottom border: its text and the style
/// of its first letter.
pub(crate) fn stability_readout_cell(app: &App) -> (String, ratatui::buffer::Cell) {
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

pub(crate) fn projector() -> Theme {
    Theme {
        colour: true,
        palette: Palette::Projector,
    }
}
