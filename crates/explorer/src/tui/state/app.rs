//! The explorer's state and what changes it (a worker snapshot absorbed, a value set, a
//! question asked). Keys and the mouse reach it through the input routing above it; the
//! panels read it. Nothing here draws, sleeps or reads a clock, and nothing here imports
//! a panel: what `App` holds lives beside it in the state module.

use super::camera::OrbitCamera;
use super::dialog::Dialog;
use super::die_screen::DieScreen;
use super::editor::Editor;
use super::lesson_run::LessonRun;
use super::map_view::MapView;
use super::messages::{Effect, Outbox};
use super::roll_view::RollView;
use super::twins::TwinView;
use super::user_setup::UserSetup;
use crate::tui::vocabulary::key_table::{self, Action, Input, Scope, label};
use crate::tui::vocabulary::layout::{Areas, screen_layout};
use crate::tui::vocabulary::param::Param;
use crate::tui::vocabulary::theme::{Palette, Theme};
use crate::worker::{Command, Notice, Snapshot};
use dicesim_setup::preset::{
    CameraView, Preset, Readouts, Screen as PresetScreen, Store, ThemeName, View as PresetView,
};
use ratatui::layout::Rect;

/// Which page is on screen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Page {
    /// The main screen: the die, its energy and the outcome table.
    #[default]
    Die,
    /// The basin-map screen (`Tab`).
    Map,
    /// The presentation view (`P`): the die large, for a projector.
    Presentation,
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
    /// Throw mode on the die screen: the aiming keys and a drag on the die throw it.
    Throw,
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
                key_table::named(Scope::Die, Action::SavePreset)
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
                key_table::named(Scope::Prompt, Action::Confirm),
                key_table::named(Scope::Prompt, asking)
            ),
            key_table::words(Scope::Prompt, asking),
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

/// The explorer's state: parts with their own rules (the roll as the worker reports it,
/// the user's setup, the twins, the die and map screens, whatever is on top) and the few
/// facts of the terminal itself.
#[derive(Debug, Clone)]
pub struct App {
    /// The live roll, its table, batch and export, as the worker's snapshots tell them.
    pub(crate) roll: RollView,
    /// The setup as the user last set it (ahead of the worker's until it catches up).
    pub(crate) setup: UserSetup,
    /// The chaos twin (`T`) and the parameter twin (`D`): ε, drift, die B, the curve.
    pub(crate) twin: TwinView,
    /// The die screen's selection, plot, arrows, drawing, camera and readout.
    pub(crate) die_screen: DieScreen,
    pub(crate) map: MapView,
    /// The lesson the step keys walk (the shipped one, or `--lesson FILE`'s), if given.
    pub(crate) lesson: Option<LessonRun>,
    /// The page on screen: the die, the basin map or the presentation view.
    pub(crate) page: Page,
    /// What is on top of the screen, if anything: it takes every key.
    pub(crate) overlay: Option<Overlay>,
    /// One line for the user, in the footer, until the next key.
    pub(crate) notice: Option<String>,
    /// Where presets are listed from and saved to.
    pub(crate) store: Store,
    pub(crate) theme: Theme,
    /// Frames drawn per second, measured by the event loop.
    pub(crate) fps: Option<f64>,
    /// The terminal's size, for mouse hit tests.
    pub(crate) screen: Rect,
    pub(crate) quit: bool,
    /// What the current `update` sends out: worker commands and file work, in order.
    pub(crate) outbox: Outbox,
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
            die_screen: DieScreen::default(),
            lesson: None,
            page: Page::Die,
            notice,
            overlay: None,
            store: Store::new(None),
            theme,
            fps: None,
            screen: Rect::new(0, 0, 120, 36),
            quit: false,
            outbox: Outbox::default(),
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
        self.die_screen.camera = view.camera.map_or_else(OrbitCamera::default, |c| OrbitCamera {
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
        self.die_screen.arrows = view.arrows.unwrap_or(false);
        self.die_screen.readouts = view.readouts.unwrap_or_default();
        if view.twin.is_some() {
            self.twin.apply(view.twin);
        }
        self.map.open_asked = view.screen == Some(PresetScreen::Map);
    }

    /// The view on screen, as `s` saves it.
    pub(crate) fn current_view(&self) -> PresetView {
        let camera = &self.die_screen.camera;
        PresetView {
            speed: Some(self.setup.speed),
            camera: Some(CameraView {
                yaw: camera.yaw_deg,
                pitch: camera.pitch_deg,
                zoom: camera.zoom,
            }),
            theme: Some(match self.theme.palette {
                Palette::Dark => ThemeName::Dark,
                Palette::Light => ThemeName::Light,
                Palette::Projector => ThemeName::Projector,
            }),
            arrows: Some(self.die_screen.arrows),
            twin: self.twin.on.then_some(self.twin.epsilon),
            screen: Some(match self.page {
                Page::Die | Page::Presentation => PresetScreen::Die,
                Page::Map => PresetScreen::Map,
            }),
            readouts: Some(self.die_screen.readouts).filter(|r| *r != Readouts::default()),
        }
    }

    /// The setup and the view on screen as a preset named `name`: the loaded preset's random
    /// ranges, the current model values, start and view, and `description` (empty: the
    /// automatic one, [`UserSetup::automatic_description`]).
    pub(crate) fn as_preset(&self, name: &str, description: &str) -> Preset {
        let p = &self.setup.params;
        let description = match description.trim() {
            "" => self.setup.automatic_description(),
            typed => typed.to_string(),
        };
        Preset {
            name: name.to_string(),
            description,
            die: p.die,
            ground: p.ground,
            world: p.world,
            integrator: p.integrator,
            initial: self.setup.initial,
            view: self.current_view(),
            ..self.setup.preset.clone()
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
            None if self.page == Page::Die && self.die_screen.throw.is_some() => Mode::Throw,
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

    /// Where the rows of the key table that apply now come from.
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
            Mode::Throw => Scope::Throw,
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

    /// Queues a command for the worker.
    pub(crate) fn send(&mut self, c: Command) {
        self.outbox.command(c);
    }

    /// Asks the event loop for an effect outside the worker (files, folders).
    pub(crate) fn ask(&mut self, effect: Effect) {
        self.outbox.ask(effect);
    }

    /// Whether frames should keep coming without input (a moving roll or a running batch).
    pub(crate) fn animating(&self) -> bool {
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
        self.setup.adopt(&s, self.outbox.commands_sent());
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
    pub(crate) fn quit(&mut self) {
        self.quit = true;
        self.send(Command::Quit);
    }

    /// Quits, or asks first when the setup has unsaved changes.
    pub(crate) fn quit_asking(&mut self) {
        if self.setup.modified() {
            self.overlay = Some(Overlay::Prompt {
                prompt: Prompt::Quit,
                under: None,
            });
        } else {
            self.quit();
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

    /// Loads `preset`'s setup (the worker sends the preset itself back with its roll).
    pub(crate) fn load(&mut self, preset: Box<Preset>) {
        let c = self.setup.load(preset);
        self.send(c);
    }

    /// The parameter list shown: the values the setup's contact law reads.
    pub(crate) fn params_listed(&self) -> &'static [Param] {
        crate::tui::vocabulary::param::listed(&self.setup.params)
    }

    /// The parameter selected on the list shown.
    pub(crate) fn selected_param(&self) -> Param {
        self.die_screen.selected_param(self.params_listed())
    }

    /// The selected parameter a step up or down (`coarse`: a big step).
    pub(crate) fn nudge(&mut self, steps: i32, coarse: bool) {
        let p = self.selected_param();
        let before = (self.setup.params, self.setup.initial);
        // In differ mode a value die B already differs by steps on from B's value (the
        // change then goes to B and A's value comes back: see the twins' keys, `divert`).
        let b = self
            .twin
            .differ
            .then(|| self.twin.differs_by.iter().find(|(k, _)| *k == p.scan_key()));
        if let Some(Some(&(_, value))) = b {
            let _ = p.set(&mut self.setup.params, &mut self.setup.initial, value);
        }
        match self.setup.nudge(p, steps, coarse) {
            Some(c) => self.send(c),
            None => (self.setup.params, self.setup.initial) = before,
        }
    }

    /// `B`: the next batch size, or the editor to type one; from that editor, the first
    /// size again with the editor closed.
    pub(crate) fn next_batch_size(&mut self) {
        let typing = matches!(self.overlay, Some(Overlay::BatchSize(_)));
        match self.roll.next_batch_size(typing) {
            Some(notice) => {
                if typing {
                    self.overlay = None;
                }
                self.notice = Some(notice);
            }
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
