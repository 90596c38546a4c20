//! The explorer's state and its pure key and mouse handling: `update(&mut App, Msg)`
//! returns the commands for the worker; nothing here draws, sleeps or reads a clock.

use super::camera::Camera;
use super::dialogs::Dialog;
use super::format::{fmt_num, fmt_range};
use super::layout::{Areas, param_row_at, screen_layout};
use super::map::{self, MapView, View};
use super::param::{Param, all};
use super::theme::Theme;
use crate::experiment::trace::{ExportProgress, human_bytes};
use crate::physics::{InitialCondition, Params};
use crate::preset::{Preset, Store};
use crate::worker::{
    BatchProgress, Command, EnergySample, MapUpdate, OutcomeTable, SeparationSample, Snapshot, Speed,
};
use ratatui::crossterm::event::{
    Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEventKind,
};
use ratatui::layout::{Position, Rect};
use ratatui::symbols::Marker;

/// Rolls in one batch (`b`).
pub(crate) const BATCH_ROLLS: u64 = 10_000;

/// What the event loop hands to [`update`]: terminal input or a worker snapshot.
#[derive(Debug, Clone)]
pub enum Msg {
    Input(Event),
    Worker(Box<Snapshot>),
    /// A basin map from the worker's map thread.
    Map(Box<MapUpdate>),
    /// A signal that ends the explorer (the event loop handles it before `update`).
    Signal(i32),
}

impl From<Snapshot> for Msg {
    fn from(s: Snapshot) -> Msg {
        Msg::Worker(Box::new(s))
    }
}

impl From<MapUpdate> for Msg {
    fn from(m: MapUpdate) -> Msg {
        Msg::Map(Box::new(m))
    }
}

/// A value being typed in (Enter on a parameter).
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Editor {
    pub(crate) text: String,
    /// Why the last Enter was refused.
    pub(crate) error: Option<String>,
}

/// What a key did to a number being typed.
pub(crate) enum Typed {
    Cancelled,
    /// Enter: the trimmed text, parsed (or why it is not a number).
    Submitted(Result<f64, String>),
    Editing,
}

impl Editor {
    /// Digits, `.`, `-`, `+` and exponents are typed; Backspace deletes; Enter submits the
    /// number; Esc cancels. Typing clears the last error.
    pub(crate) fn key(&mut self, code: KeyCode) -> Typed {
        match code {
            KeyCode::Esc => return Typed::Cancelled,
            KeyCode::Backspace => {
                self.text.pop();
            }
            KeyCode::Char(c) if c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E') => {
                if self.text.len() < 24 {
                    self.text.push(c);
                }
            }
            KeyCode::Enter => {
                let text = self.text.trim();
                return Typed::Submitted(match text.parse::<f64>() {
                    Ok(v) => Ok(v),
                    Err(_) if text.is_empty() => Err("type a number, or Esc to cancel".to_string()),
                    Err(_) => Err(format!("`{text}` is not a number")),
                });
            }
            _ => return Typed::Editing,
        }
        self.error = None;
        Typed::Editing
    }
}

/// How the die is drawn: Braille dots, or plain ASCII for fonts without Braille.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Drawing {
    #[default]
    Braille,
    Ascii,
}

impl Drawing {
    /// The marker that draws the plots' lines.
    pub(crate) fn line_marker(self) -> Marker {
        match self {
            Drawing::Braille => Marker::Braille,
            Drawing::Ascii => Marker::Custom('.'),
        }
    }
}

#[derive(Debug, Clone)]
pub struct App {
    /// The newest worker snapshot (its history already moved into `history`).
    pub(crate) live: Snapshot,
    /// The setup as the user last set it (ahead of `live` until the worker catches up).
    pub(crate) params: Params,
    pub(crate) initial: InitialCondition,
    pub(crate) speed: Speed,
    /// Energy samples of the roll on screen.
    pub(crate) history: Vec<EnergySample>,
    pub(crate) table: OutcomeTable,
    pub(crate) batch: Option<BatchProgress>,
    /// The roll's export, while it runs.
    pub(crate) export: Option<ExportProgress>,
    pub(crate) batch_rolls: u64,
    pub(crate) notice: Option<String>,
    /// Index into [`all`](super::param::all).
    pub(crate) selected: usize,
    pub(crate) editing: Option<Editor>,
    pub(crate) help: bool,
    pub(crate) help_scroll: u16,
    pub(crate) log_scale: bool,
    /// Arrows for ω, L, v and the contact forces on the die (`v`).
    pub(crate) vectors: bool,
    /// Whether a chaos twin rolls beside the die (`T`), and its ε.
    pub(crate) twin: bool,
    pub(crate) epsilon: f64,
    /// ε being typed in (`E`).
    pub(crate) epsilon_editor: Option<Editor>,
    /// The twin's separation samples of the roll on screen.
    pub(crate) twin_history: Vec<SeparationSample>,
    /// The preset the setup was loaded from (or last saved as).
    pub(crate) preset: Preset,
    /// Where presets are listed from and saved to.
    pub(crate) store: Store,
    /// The preset picker or the save dialog, when open.
    pub(crate) dialog: Option<Dialog>,
    pub(crate) drawing: Drawing,
    pub(crate) camera: Camera,
    pub(crate) theme: Theme,
    /// Frames drawn per second, measured by the event loop.
    pub(crate) fps: Option<f64>,
    /// The terminal's size, for mouse hit tests.
    pub(crate) screen: Rect,
    pub(crate) quit: bool,
    pub(crate) view: View,
    pub(crate) map: MapView,
    commands_sent: u64,
    /// Last mouse position while dragging the die.
    drag: Option<(u16, u16)>,
}

impl App {
    /// The explorer showing `first`, typically the engine's snapshot before the worker starts.
    pub fn new(mut first: Snapshot, theme: Theme) -> App {
        let history = std::mem::take(&mut first.history);
        let map = MapView::new(&first.params, &first.initial);
        let preset = first.preset.take().map_or_else(Preset::default, |p| *p);
        App {
            params: first.params,
            initial: first.initial,
            speed: first.speed,
            table: first.table.take().unwrap_or_default(),
            batch: first.batch,
            export: first.export,
            notice: first.notice.take(),
            live: first,
            history,
            batch_rolls: BATCH_ROLLS,
            selected: 0,
            editing: None,
            help: false,
            help_scroll: 0,
            log_scale: false,
            vectors: false,
            twin: false,
            epsilon: super::twin::DEFAULT_EPSILON,
            epsilon_editor: None,
            twin_history: Vec::new(),
            preset,
            store: Store::new(None),
            dialog: None,
            drawing: Drawing::default(),
            camera: Camera::default(),
            theme,
            fps: None,
            screen: Rect::new(0, 0, 120, 36),
            quit: false,
            view: View::Die,
            map,
            commands_sent: 0,
            drag: None,
        }
    }

    pub(crate) fn selected_param(&self) -> Param {
        all()[self.selected.min(all().len() - 1)]
    }

    /// Whether frames should keep coming without input (a moving roll or a running batch).
    pub fn animating(&self) -> bool {
        self.live.playing || self.batch.is_some() || self.export.is_some()
    }

    fn absorb(&mut self, mut s: Snapshot) {
        if s.history_reset {
            self.history.clear();
            self.twin_history.clear();
        }
        if let Some(twin) = &mut s.twin {
            self.twin_history.append(&mut twin.history);
        }
        self.history.append(&mut s.history);
        if let Some(t) = s.table.take() {
            self.table = t;
        }
        if let Some(n) = s.notice.take() {
            self.notice = Some(n);
        }
        if let Some(p) = s.preset.take() {
            self.preset = *p;
        }
        // Until the worker has seen every command, the user's own values are newer.
        if s.commands_handled >= self.commands_sent {
            self.params = s.params;
            self.initial = s.initial;
            self.speed = s.speed;
        }
        self.batch = s.batch;
        self.export = s.export;
        self.live = s;
    }

    /// What the status line says while the roll is exported: its size first, then how far.
    pub(crate) fn export_status(&self) -> Option<String> {
        let p = self.export?;
        let share = 100.0 * p.steps_done as f64 / p.steps_total.max(1) as f64;
        Some(if p.writing {
            format!(
                "exporting the roll: {share:.0}% of {} rows, {} · e cancels",
                p.steps_total + 1,
                human_bytes(p.bytes)
            )
        } else if p.bytes == 0 {
            "exporting the roll: measuring its length · e cancels".to_string()
        } else {
            format!(
                "exporting the roll: measuring its length, {share:.0}% of the time cap (at most {}) · e cancels",
                human_bytes(p.bytes)
            )
        })
    }

    pub(crate) fn send(&mut self, out: &mut Vec<Command>, c: Command) {
        self.commands_sent += 1;
        out.push(c);
    }

    fn set_param(&mut self, out: &mut Vec<Command>, p: Param, value: f64) -> Result<(), String> {
        p.set(&mut self.params, &mut self.initial, value).map_err(|e| {
            if e.limits == p.limits() {
                format!(
                    "{} is outside {} {}",
                    fmt_num(value),
                    fmt_range(p),
                    p.limits().unit
                )
            } else {
                // The value is in range, but the die would start inside the table.
                format!(
                    "{}: corner in the table; ≥ {} cm",
                    fmt_num(value),
                    fmt_num(e.limits.min)
                )
            }
        })?;
        self.send(out, Command::SetParam(p.scan_key(), value));
        Ok(())
    }

    fn nudge(&mut self, out: &mut Vec<Command>, steps: i32, coarse: bool) {
        let p = self.selected_param();
        let now = p.get(&self.params, &self.initial);
        let next = p.nudged(now, steps, coarse);
        if next != now {
            let _ = self.set_param(out, p, next);
        }
    }

    fn select(&mut self, delta: isize) {
        self.selected = (self.selected as isize + delta).clamp(0, all().len() as isize - 1) as usize;
    }

    fn set_speed(&mut self, out: &mut Vec<Command>, speed: Speed) {
        if speed != self.speed {
            self.speed = speed;
            self.send(out, Command::SetSpeed(speed));
        }
    }

    fn quit(&mut self, out: &mut Vec<Command>) {
        self.quit = true;
        self.send(out, Command::Quit);
    }

    fn areas(&self) -> Option<Areas> {
        screen_layout(self.screen)
    }
}

/// Applies one message; returns the commands to send to the worker, in order.
pub fn update(app: &mut App, msg: Msg) -> Vec<Command> {
    let mut out = Vec::new();
    match msg {
        Msg::Worker(s) => app.absorb(*s),
        Msg::Map(m) => map::absorb(app, *m),
        Msg::Input(Event::Resize(w, h)) => {
            app.screen = Rect::new(0, 0, w, h);
            map::resized(app, &mut out);
        }
        Msg::Input(Event::Key(key)) if key.kind != KeyEventKind::Release => on_key(app, key, &mut out),
        Msg::Input(Event::Mouse(m)) => on_mouse(app, m.kind, m.column, m.row, &mut out),
        Msg::Input(_) => {}
        Msg::Signal(_) => app.quit(&mut out),
    }
    out
}

fn on_key(app: &mut App, key: KeyEvent, out: &mut Vec<Command>) {
    let ctrl = key.modifiers.contains(KeyModifiers::CONTROL);
    if ctrl && matches!(key.code, KeyCode::Char('c') | KeyCode::Char('C')) {
        app.quit(out);
        return;
    }
    app.notice = None;
    if app.editing.is_some() {
        on_edit_key(app, key, out);
        return;
    }
    if app.dialog.is_some() {
        super::dialogs::on_key(app, key, out);
        return;
    }
    if app.epsilon_editor.is_some() {
        super::twin::on_editor_key(app, key, out);
        return;
    }
    if app.help {
        match key.code {
            KeyCode::Char('q') => app.quit(out),
            KeyCode::Up | KeyCode::Char('k') => app.help_scroll = app.help_scroll.saturating_sub(1),
            KeyCode::Down | KeyCode::Char('j') => app.help_scroll = app.help_scroll.saturating_add(1),
            KeyCode::Char('?') | KeyCode::Esc | KeyCode::Enter => app.help = false,
            _ => {}
        }
        return;
    }
    if app.view == View::Map && super::map_keys::on_key(app, key, out) {
        return;
    }
    if super::twin::on_key(app, key, out) {
        return;
    }
    let coarse = key
        .modifiers
        .intersects(KeyModifiers::SHIFT | KeyModifiers::CONTROL | KeyModifiers::ALT);
    match key.code {
        KeyCode::Char('q') | KeyCode::Esc => app.quit(out),
        KeyCode::Char(' ') => app.send(out, Command::TogglePlay),
        KeyCode::Char('n') => app.send(out, Command::Step(1)),
        KeyCode::Char('r') => app.send(out, Command::Replay),
        KeyCode::Char('R') => app.send(out, Command::RandomRoll),
        KeyCode::Char('b') => {
            let c = if app.batch.is_some() {
                Command::BatchCancel
            } else {
                Command::BatchStart(app.batch_rolls)
            };
            app.send(out, c);
        }
        KeyCode::Char('c') => app.send(out, Command::ClearTable),
        KeyCode::Char('[') | KeyCode::Char('-') => app.set_speed(out, app.speed.slower()),
        KeyCode::Char(']') | KeyCode::Char('+') | KeyCode::Char('=') => {
            app.set_speed(out, app.speed.faster())
        }
        KeyCode::Up | KeyCode::Char('k') => app.select(-1),
        KeyCode::Down | KeyCode::Char('j') => app.select(1),
        KeyCode::Home | KeyCode::Char('g') => app.selected = 0,
        KeyCode::End | KeyCode::Char('G') => app.selected = all().len() - 1,
        KeyCode::Left | KeyCode::Char('h') => app.nudge(out, -1, coarse),
        KeyCode::Right | KeyCode::Char('l') => app.nudge(out, 1, coarse),
        KeyCode::Char('H') => app.nudge(out, -1, true),
        KeyCode::Char('L') => app.nudge(out, 1, true),
        KeyCode::Enter => app.editing = Some(Editor::default()),
        KeyCode::Char('?') => {
            app.help = true;
            app.help_scroll = 0;
        }
        KeyCode::Char('y') => app.log_scale = !app.log_scale,
        KeyCode::Char('e') => {
            let c = if app.export.is_some() {
                Command::ExportCancel
            } else {
                Command::Export(".".into())
            };
            app.send(out, c);
        }
        KeyCode::Char('v') => app.vectors = !app.vectors,
        KeyCode::Char('t') => {
            app.theme = app.theme.next();
            app.notice = Some(format!(
                "theme: {}{} (t cycles dark, light, projector)",
                app.theme.palette.name(),
                if app.theme.colour {
                    ""
                } else {
                    ", but NO_COLOR is set"
                }
            ));
        }
        KeyCode::Char('m') => {
            app.drawing = match app.drawing {
                Drawing::Braille => Drawing::Ascii,
                Drawing::Ascii => Drawing::Braille,
            }
        }
        KeyCode::Char('a') => app.camera.orbit(-15.0, 0.0),
        KeyCode::Char('d') => app.camera.orbit(15.0, 0.0),
        KeyCode::Char('W') => app.camera.orbit(0.0, 10.0),
        KeyCode::Char('S') => app.camera.orbit(0.0, -10.0),
        KeyCode::Char('o') => super::dialogs::open_picker(app),
        KeyCode::Char('s') => super::dialogs::open_save(app),
        KeyCode::Char('z') => app.camera.zoom_by(1),
        KeyCode::Char('x') => app.camera.zoom_by(-1),
        KeyCode::Char('0') => app.camera = Camera::default(),
        KeyCode::Tab | KeyCode::BackTab | KeyCode::Char('2') => map::open(app, out),
        _ => {}
    }
}

fn on_edit_key(app: &mut App, key: KeyEvent, out: &mut Vec<Command>) {
    let Some(editor) = app.editing.as_mut() else {
        return;
    };
    match editor.key(key.code) {
        Typed::Cancelled => app.editing = None,
        Typed::Editing => {}
        Typed::Submitted(number) => {
            let p = app.selected_param();
            match number.and_then(|v| app.set_param(out, p, v)) {
                Ok(()) => app.editing = None,
                Err(e) => {
                    if let Some(editor) = app.editing.as_mut() {
                        editor.error = Some(e);
                    }
                }
            }
        }
    }
}

fn on_mouse(app: &mut App, kind: MouseEventKind, column: u16, row: u16, out: &mut Vec<Command>) {
    if app.help
        || app.editing.is_some()
        || app.epsilon_editor.is_some()
        || app.dialog.is_some()
        || app.view == View::Map
    {
        return;
    }
    let Some(areas) = app.areas() else { return };
    let at = Position::new(column, row);
    match kind {
        MouseEventKind::Down(MouseButton::Left) => {
            if let Some(i) = param_row_at(app, &areas, at) {
                app.selected = i;
            } else if areas.die.contains(at) {
                app.drag = Some((column, row));
            }
        }
        MouseEventKind::Drag(MouseButton::Left) => {
            if let Some((x, y)) = app.drag {
                app.camera
                    .orbit(5.0 * (column as f64 - x as f64), 5.0 * (row as f64 - y as f64));
                app.drag = Some((column, row));
            }
        }
        MouseEventKind::Up(_) => app.drag = None,
        MouseEventKind::ScrollUp | MouseEventKind::ScrollDown => {
            let up = kind == MouseEventKind::ScrollUp;
            if areas.params.contains(at) {
                if let Some(i) = param_row_at(app, &areas, at) {
                    app.selected = i;
                }
                app.nudge(out, if up { 1 } else { -1 }, false);
            } else if areas.die.contains(at) {
                app.camera.zoom_by(if up { 1 } else { -1 });
            }
        }
        _ => {}
    }
}
