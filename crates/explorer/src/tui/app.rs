//! The explorer's state and what changes it (a worker snapshot absorbed, a value set);
//! keys and the mouse reach it through [`super::input`]. Nothing here draws, sleeps or reads a clock.

use super::camera::OrbitCamera;
use super::dialog::Dialog;
pub(crate) use super::editor::{Editor, Typed, VALUE_CHARS};
use super::keys::{self, Action, Input, Scope, label};
use super::layout::{Areas, screen_layout};
use super::map_view::{MapView, Page};
use super::param::{Param, all};
use super::plot::PlotChoice;
use super::roll_view::RollView;
use super::setup::UserSetup;
use super::theme::{Palette, Theme};
use super::twin_view::TwinView;
use crate::worker::{Command, MapUpdate, Notice, Snapshot};
use dicesim_setup::preset::{
    CameraView, Preset, Screen as PresetScreen, Store, ThemeName, View as PresetView,
};
use ratatui::crossterm::event::Event;
use ratatui::layout::Rect;
use ratatui::symbols::Marker;

/// What the explorer asks of the world outside `update`: the event loop runs these (in
/// order: worker commands as they come, then the rest), so `update` itself never touches
/// the disk or a thread.
#[derive(Debug, Clone, PartialEq)]
// A worker command carries a whole setup (a loaded die's eight corner masses among it); an
// effect lives only from `update` to the event loop, so boxing it would buy nothing.
#[allow(clippy::large_enum_variant)]
pub enum Effect {
    /// A command for the simulation thread.
    Worker(Command),
    /// List the presets (shipped and the user's folder) and open the picker on them.
    ListPresets,
    /// Write this preset into the user's folder; an existing file of its name is replaced
    /// only with `replace` (else the save dialog asks).
    SavePreset { preset: Box<Preset>, replace: bool },
}

impl Effect {
    /// The worker command, if this is one.
    pub fn command(self) -> Option<Command> {
        match self {
            Effect::Worker(c) => Some(c),
            _ => None,
        }
    }
}

/// Tests compare the effects of a key with the worker commands they expect.
impl PartialEq<Command> for Effect {
    fn eq(&self, other: &Command) -> bool {
        matches!(self, Effect::Worker(c) if c == other)
    }
}

/// What is topmost, and so gets the keys. [`App::mode`] is the one place that decides it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Mode {
    /// A question that must be answered first (quit, reset or load over unsaved changes).
    Prompt,
    /// A parameter's value being typed.
    EditingValue,
    /// The preset picker or the save dialog.
    Dialog,
    /// The twin's ε being typed.
    EditingEpsilon,
    /// A map axis range being typed.
    EditingRange,
    Help,
    /// The basin-map screen.
    Map,
    /// The die screen, nothing over it.
    Normal,
}

/// What is on top of the screens. One thing at a time: opening one replaces another,
/// except a question asked over the preset picker, which keeps the picker under it.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Overlay {
    /// The help (`?`), scrolled down by `scroll` lines.
    Help { scroll: u16 },
    /// A value of the parameter list being typed.
    Value(Editor),
    /// The batch size being typed (after `B` has walked past the largest preset size).
    BatchSize(Editor),
    /// The twin's ε being typed.
    Epsilon(Editor),
    /// The preset picker or the save dialog.
    Dialog(Dialog),
    /// A question; `under` (the picker it was asked from) comes back after a no.
    Prompt { prompt: Prompt, under: Option<Dialog> },
}

/// A question asked before something that would lose the user's changes.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Prompt {
    /// `q` with unsaved changes: `y` or `q` again quits.
    Quit,
    /// `Backspace` with changes: `y` or `Backspace` again resets to the open preset.
    Reset,
    /// A preset chosen in the picker over unsaved changes: `y` or `Enter` loads it.
    Load(Box<Preset>),
}

impl Prompt {
    /// The question, as the footer asks it.
    pub(crate) fn question(&self, preset: &str) -> String {
        match self {
            Prompt::Quit => format!(
                "Quit? The setup has unsaved changes ({} saves them).",
                keys::named(Scope::Die, Action::SavePreset)
            ),
            Prompt::Reset => format!("Reset the setup to {preset}? Your changes are lost."),
            Prompt::Load(p) => format!("Open {}? Your changes to {preset} are lost.", p.name),
        }
    }

    /// The footer's answers.
    pub(crate) fn answers(&self) -> (String, &'static str) {
        let asking = self.asked_by();
        (
            format!(
                "{}/{}",
                keys::named(Scope::Prompt, Action::Confirm),
                keys::named(Scope::Prompt, asking)
            ),
            keys::words(Scope::Prompt, asking),
        )
    }

    /// The action whose key asked the question (and answers yes to it).
    fn asked_by(&self) -> Action {
        match self {
            Prompt::Quit => Action::Quit,
            Prompt::Reset => Action::ResetSetup,
            Prompt::Load(_) => Action::OpenPreset,
        }
    }

    /// Whether `action` answers yes: `y`, or the key that asked the question.
    pub(crate) fn confirmed_by(&self, action: Action) -> bool {
        action == Action::Confirm || action == self.asked_by()
    }
}

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

/// The explorer's state: parts with their own rules (the roll as the worker reports it,
/// the user's setup, the twin, the map screen, whatever is on top) and the few facts of
/// the screen itself.
#[derive(Debug, Clone)]
pub struct App {
    /// The live roll, its table, batch and export, as the worker's snapshots tell them.
    pub(crate) roll: RollView,
    /// The setup as the user last set it (ahead of the worker's until it catches up).
    pub(crate) setup: UserSetup,
    /// The chaos twin (`T`): its ε, its drift and the predictability curve.
    pub(crate) twin: TwinView,
    /// What is on top of the screen, if anything: it takes every key.
    pub(crate) overlay: Option<Overlay>,
    pub(crate) notice: Option<String>,
    /// Index into [`all`](super::param::all).
    pub(crate) selected: usize,
    pub(crate) log_scale: bool,
    /// What the plot panel draws (`w`, `V`).
    pub(crate) plot: PlotChoice,
    /// Arrows for ω, L, v and the contact forces on the die (`v`).
    pub(crate) vectors: bool,
    /// Where presets are listed from and saved to.
    pub(crate) store: Store,
    pub(crate) drawing: Drawing,
    pub(crate) camera: OrbitCamera,
    pub(crate) theme: Theme,
    /// Frames drawn per second, measured by the event loop.
    pub(crate) fps: Option<f64>,
    /// The terminal's size, for mouse hit tests.
    pub(crate) screen: Rect,
    pub(crate) quit: bool,
    /// The page on screen: the die, the basin map or the presentation view.
    pub(crate) page: Page,
    /// The number the presentation view shows beside the face.
    pub(crate) readout: super::presentation::Readout,
    pub(crate) map: MapView,
    /// Effects other than worker commands asked for during the current `update`.
    pub(crate) effects: Vec<Effect>,
    /// Last mouse position while dragging the die.
    pub(crate) drag: Option<(u16, u16)>,
}

impl App {
    /// The explorer showing `first`, typically the simulator's snapshot before the worker starts.
    pub fn new(mut first: Snapshot, theme: Theme) -> App {
        let preset = first.preset.take().map_or_else(Preset::default, |p| *p);
        let notice = first.notice.take().map(|n| worded(&n));
        let twin = TwinView {
            curve: first.curve.take(),
            ..TwinView::default()
        };
        App {
            map: MapView::new(&first.params, &first.initial),
            setup: UserSetup::new(&first, preset),
            roll: RollView::new(first),
            twin,
            notice,
            overlay: None,
            selected: 0,
            log_scale: false,
            plot: PlotChoice::default(),
            vectors: false,
            store: Store::new(None),
            drawing: Drawing::default(),
            camera: OrbitCamera::default(),
            theme,
            fps: None,
            screen: Rect::new(0, 0, 120, 36),
            quit: false,
            page: Page::Die,
            readout: Default::default(),
            effects: Vec::new(),
            drag: None,
        }
        .with_view()
    }

    /// The app with its preset's `[view]` applied.
    fn with_view(mut self) -> App {
        let view = self.setup.preset.view;
        self.apply_view(&view);
        self
    }

    /// A preset's view: what the UI owns of it (the worker sets the speed and rolls the
    /// twin itself). A preset opens the same way every time, so a key the view leaves out
    /// means the default (the camera's, no arrows, the die screen); the theme stays as it
    /// is, since it suits the room rather than the preset, and so does a twin that rolls
    /// (a lesson turns it on, then opens presets to compare them with it).
    pub(crate) fn apply_view(&mut self, view: &PresetView) {
        self.camera = view.camera.map_or_else(OrbitCamera::default, |c| OrbitCamera {
            yaw_deg: c.yaw,
            pitch_deg: c.pitch,
            zoom: c.zoom,
        });
        if let Some(name) = view.theme {
            self.theme.palette = match name {
                ThemeName::Dark => Palette::Dark,
                ThemeName::Light => Palette::Light,
                ThemeName::Projector => Palette::Projector,
            };
        }
        self.vectors = view.arrows.unwrap_or(false);
        if view.twin.is_some() {
            self.twin.apply(view.twin);
        }
        self.map.open_asked = view.screen == Some(PresetScreen::Map);
    }

    /// The view on screen, as `s` saves it.
    pub(crate) fn current_view(&self) -> PresetView {
        PresetView {
            speed: Some(self.setup.speed),
            camera: Some(CameraView {
                yaw: self.camera.yaw_deg,
                pitch: self.camera.pitch_deg,
                zoom: self.camera.zoom,
            }),
            theme: Some(match self.theme.palette {
                Palette::Dark => ThemeName::Dark,
                Palette::Light => ThemeName::Light,
                Palette::Projector => ThemeName::Projector,
            }),
            arrows: Some(self.vectors),
            twin: self.twin.on.then_some(self.twin.epsilon),
            screen: Some(match self.page {
                Page::Die | Page::Presentation => PresetScreen::Die,
                Page::Map => PresetScreen::Map,
            }),
        }
    }

    /// What is topmost now.
    pub(crate) fn mode(&self) -> Mode {
        match &self.overlay {
            Some(Overlay::Prompt { .. }) => Mode::Prompt,
            Some(Overlay::Value(_) | Overlay::BatchSize(_)) => Mode::EditingValue,
            Some(Overlay::Dialog(_)) => Mode::Dialog,
            Some(Overlay::Epsilon(_)) => Mode::EditingEpsilon,
            // The map's range editor is the map screen's own, under any overlay.
            _ if self.page == Page::Map && self.map.editing.is_some() => Mode::EditingRange,
            Some(Overlay::Help { .. }) => Mode::Help,
            None if self.page == Page::Map => Mode::Map,
            None => Mode::Normal,
        }
    }

    /// The question being asked, if any.
    pub(crate) fn prompt(&self) -> Option<&Prompt> {
        match &self.overlay {
            Some(Overlay::Prompt { prompt, .. }) => Some(prompt),
            _ => None,
        }
    }

    /// The dialog open, on top or under a question.
    pub(crate) fn dialog(&self) -> Option<&Dialog> {
        match &self.overlay {
            Some(Overlay::Dialog(d)) | Some(Overlay::Prompt { under: Some(d), .. }) => Some(d),
            _ => None,
        }
    }

    /// The parameter value being typed, if any.
    pub(crate) fn value_editor(&self) -> Option<&Editor> {
        match &self.overlay {
            Some(Overlay::Value(e)) => Some(e),
            _ => None,
        }
    }

    /// The batch size being typed, if any.
    pub(crate) fn batch_editor(&self) -> Option<&Editor> {
        match &self.overlay {
            Some(Overlay::BatchSize(e)) => Some(e),
            _ => None,
        }
    }

    /// The twin's ε being typed, if any.
    pub(crate) fn epsilon_editor(&self) -> Option<&Editor> {
        match &self.overlay {
            Some(Overlay::Epsilon(e)) => Some(e),
            _ => None,
        }
    }

    /// How far the help is scrolled, while it is open.
    pub(crate) fn help_scroll(&self) -> Option<u16> {
        match &self.overlay {
            Some(Overlay::Help { scroll }) => Some(*scroll),
            _ => None,
        }
    }

    /// The mode whose rows of the key table apply now.
    pub(crate) fn key_scope(&self) -> Scope {
        match self.mode() {
            Mode::Prompt => Scope::Prompt,
            Mode::EditingValue | Mode::EditingEpsilon | Mode::EditingRange => Scope::Text,
            Mode::Dialog => match self.dialog() {
                Some(Dialog::Save { .. }) => Scope::Save,
                _ => Scope::Picker,
            },
            Mode::Help => Scope::Help,
            Mode::Map => Scope::Map,
            Mode::Normal if self.page == Page::Presentation => Scope::Show,
            Mode::Normal => Scope::Die,
        }
    }

    /// A key that means nothing here: it does nothing, and the footer says so.
    pub(crate) fn nothing_here(&mut self, input: &Input) {
        if let Input::Nothing(key) = input {
            self.notice = Some(format!(
                "{key}: nothing here ({} lists the keys)",
                label(Scope::Die, Action::Help)
            ));
        }
    }

    /// Asks the event loop for an effect outside the worker (files, folders).
    pub(crate) fn ask(&mut self, effect: Effect) {
        self.effects.push(effect);
    }

    pub(crate) fn selected_param(&self) -> Param {
        all()[self.selected.min(all().len() - 1)]
    }

    /// Whether frames should keep coming without input (a moving roll or a running batch).
    pub fn animating(&self) -> bool {
        self.roll.animating()
    }

    /// A worker snapshot: its roll, its twin, its notice in words, a newly loaded preset
    /// (and its view), and its setup once the worker has caught up with the user's edits.
    pub(crate) fn absorb(&mut self, mut s: Snapshot) {
        self.twin.absorb(&mut s);
        if let Some(n) = s.notice.take() {
            self.notice = Some(worded(&n));
        }
        if let Some(p) = s.preset.take() {
            self.map.reopen(&p.params(), &p.initial);
            let view = p.view;
            self.setup.preset = *p;
            self.apply_view(&view);
        }
        self.setup.adopt(&s);
        let (was, now) = (self.roll.live.timeline.position, s.timeline.position);
        if let Some(d) = s
            .timeline
            .decided
            .filter(|&d| was < d && d <= now && !s.history_reset)
        {
            self.notice = Some(format!(
                "face decided at {:.3} s: the roll's data end there",
                d as f64 * s.params.integrator.dt
            ));
        }
        self.roll.absorb(s);
    }

    /// Quits, telling the worker.
    pub(crate) fn quit(&mut self, out: &mut Vec<Command>) {
        self.quit = true;
        self.setup.send(out, Command::Quit);
    }

    /// Quits, or asks first when the setup has unsaved changes.
    pub(crate) fn quit_asking(&mut self, out: &mut Vec<Command>) {
        if self.setup.modified() {
            self.overlay = Some(Overlay::Prompt {
                prompt: Prompt::Quit,
                under: None,
            });
        } else {
            self.quit(out);
        }
    }

    /// The setup back to the open preset's (its roll from the start, a fresh table); asks
    /// first when there are changes.
    pub(crate) fn reset_asking(&mut self) {
        if self.setup.modified() {
            self.overlay = Some(Overlay::Prompt {
                prompt: Prompt::Reset,
                under: None,
            });
        } else {
            self.notice = Some(format!(
                "nothing to reset: the setup is {}'s",
                self.setup.preset.name
            ));
        }
    }

    /// Moves the parameter list's selection by `delta` rows, inside the list.
    pub(crate) fn select(&mut self, delta: isize) {
        self.selected = (self.selected as isize + delta).clamp(0, all().len() as isize - 1) as usize;
    }

    /// The selected parameter a step up or down (`coarse`: a big step).
    pub(crate) fn nudge(&mut self, out: &mut Vec<Command>, steps: i32, coarse: bool) {
        let p = self.selected_param();
        let before = (self.setup.params, self.setup.initial);
        // In differ mode a value die B already differs by steps on from B's value (the
        // change then goes to B and A's value comes back: see `versus::divert`).
        let b = self
            .twin
            .differ
            .then(|| self.twin.differs_by.iter().find(|(k, _)| *k == p.scan_key()));
        if let Some(Some(&(_, value))) = b {
            let _ = p.set(&mut self.setup.params, &mut self.setup.initial, value);
        }
        let sent = out.len();
        self.setup.nudge(out, p, steps, coarse);
        if out.len() == sent {
            (self.setup.params, self.setup.initial) = before;
        }
    }

    /// `B`: the next batch size, or the editor to type one.
    pub(crate) fn next_batch_size(&mut self) {
        match self.roll.next_batch_size() {
            Some(notice) => self.notice = Some(notice),
            None => self.overlay = Some(Overlay::BatchSize(Editor::default())),
        }
    }

    pub(crate) fn areas(&self) -> Option<Areas> {
        screen_layout(self.screen)
    }
}

/// A worker's notice in words, naming the keys it points at from the key table.
pub(crate) fn worded(notice: &Notice) -> String {
    match notice {
        Notice::RollEnded => format!(
            "the roll has ended: {} replays it",
            label(Scope::Die, Action::Replay)
        ),
        Notice::ExportRunning => format!(
            "an export is running: {} cancels it",
            label(Scope::Die, Action::Export)
        ),
        Notice::Said(words) => words.clone(),
    }
}
