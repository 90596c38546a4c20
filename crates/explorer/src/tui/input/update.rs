//! Key and mouse routing: `update(&mut App, Msg)` reads a key through the key table
//! ([`crate::tui::vocabulary::key_table::read`]) and hands it to whatever is on top, or to the screen under it.
//! It sits above the state ([`App`]) and below the panels, which never import it. Nothing
//! here draws, sleeps or reads a clock: the commands for the worker and the file work are
//! queued in the app's outbox and returned.

use crate::tui::input::dialog_keys;
use crate::tui::input::lesson_keys;
use crate::tui::input::map_keys as map;
use crate::tui::input::throw_keys;
use crate::tui::input::twin_keys;
use crate::tui::state::app::{App, Mode, Overlay, Page, Prompt};
use crate::tui::state::camera::OrbitCamera;
use crate::tui::state::die_screen::Drawing;
use crate::tui::state::editor::{Editor, Typed, VALUE_CHARS};
use crate::tui::state::messages::{Effect, Msg};
use crate::tui::vocabulary::key_table::{Action, Input, Scope, first_key, label, read};
use crate::tui::vocabulary::layout::{param_row_at, timeline_bar, timeline_margins, timeline_step_at};
use crate::worker::{Command, RollEvent};
use ratatui::crossterm::event::{
    Event, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use ratatui::layout::{Position, Rect};

/// Applies one message; returns what the event loop is to do, in the order asked: worker
/// commands and file work.
pub(crate) fn update(app: &mut App, msg: Msg) -> Vec<Effect> {
    // In differ mode the value changes a key or the mouse makes go to die B.
    let before = (app.setup.params, app.setup.initial);
    match msg {
        Msg::Worker(s) => app.absorb(*s),
        Msg::Map(m) => map::absorb(app, *m),
        Msg::Input(Event::Resize(w, h)) => {
            app.screen = Rect::new(0, 0, w, h);
            map::resized(app);
        }
        Msg::Input(Event::Key(key)) if key.kind != KeyEventKind::Release => on_key(app, key),
        Msg::Input(Event::Mouse(m)) => on_mouse(app, m),
        Msg::Input(_) => {}
        Msg::Signal(_) => app.quit(),
    }
    twin_keys::divert(app, before);
    if std::mem::take(&mut app.map.open_asked) {
        map::open(app);
    }
    app.outbox.take()
}

fn on_key(app: &mut App, key: KeyEvent) {
    let input = read(app.key_scope(), key);
    if input == Input::Interrupt {
        app.quit();
        return;
    }
    app.notice = None;
    lesson_keys::card_down(
        app,
        match input {
            Input::Act { action, .. } => Some(action),
            _ => None,
        },
    );
    match app.mode() {
        Mode::Prompt => on_prompt_key(app, &input),
        Mode::EditingValue => on_edit_key(app, &input),
        Mode::Dialog => dialog_keys::on_key(app, &input),
        Mode::EditingEpsilon => twin_keys::on_epsilon_key(app, &input),
        Mode::EditingRange => map::on_range_key(app, &input),
        Mode::Throw => throw_keys::on_key(app, &input),
        Mode::Help => {
            let Some(Overlay::Help { scroll }) = &mut app.overlay else {
                return;
            };
            match input {
                Input::Act {
                    action: Action::SelectPrevious,
                    ..
                } => *scroll = scroll.saturating_sub(1),
                Input::Act {
                    action: Action::SelectNext,
                    ..
                } => *scroll = scroll.saturating_add(1),
                Input::Act {
                    action: Action::Close,
                    ..
                } => app.overlay = None,
                other => app.nothing_here(&other),
            }
        }
        Mode::Map | Mode::Normal => match input {
            Input::Act { action, coarse } => act(app, action, coarse),
            // A digit on a parameter row starts the value editor with it typed.
            Input::Type(digit) => {
                app.overlay = Some(Overlay::Value(Editor {
                    text: digit.to_string(),
                    error: None,
                }))
            }
            other => app.nothing_here(&other),
        },
    }
}

/// A question's answer: its own key or `y` goes ahead, anything else keeps things as they are.
fn on_prompt_key(app: &mut App, input: &Input) {
    let Some(Overlay::Prompt { prompt, under }) = app.overlay.take() else {
        return;
    };
    let yes = match input {
        Input::Act { action, .. } => prompt.confirmed_by(*action),
        _ => false,
    };
    if !yes {
        app.overlay = under.map(Overlay::Dialog);
        app.notice = Some("nothing changed".to_string());
        return;
    }
    match prompt {
        Prompt::Quit => app.quit(),
        Prompt::Reset => {
            let preset = Box::new(app.setup.preset.clone());
            app.load(preset);
        }
        Prompt::Load(preset) => {
            app.load(preset);
        }
    }
}

/// Does what a key of the table stands for.
fn act(app: &mut App, action: Action, coarse: bool) {
    match action {
        Action::TogglePlay
        | Action::StepForward
        | Action::StepBack
        | Action::ToStart
        | Action::ToEnd
        | Action::NextImpact
        | Action::PreviousImpact
        | Action::ToDecided
        | Action::Replay
        | Action::RandomRoll
        | Action::Batch
        | Action::BatchSize
        | Action::ClearTable
        | Action::Slower
        | Action::Faster
        | Action::Export
        | Action::ExportAnimation => act_on_roll(app, action),
        Action::LogScale
        | Action::PlotQuantity
        | Action::PhasePlot
        | Action::FitAxis
        | Action::SecondQuantity
        | Action::FacePair
        | Action::Arrows
        | Action::Theme
        | Action::Drawing
        | Action::OrbitLeft
        | Action::OrbitRight
        | Action::TiltUp
        | Action::TiltDown
        | Action::ZoomIn
        | Action::ZoomOut
        | Action::ResetCamera
        | Action::NextReadout => act_on_view(app, action),
        Action::SelectPrevious => app.die_screen.select(-1, app.params_listed().len()),
        Action::SelectNext => app.die_screen.select(1, app.params_listed().len()),
        Action::SelectFirst => app.die_screen.selected = 0,
        Action::SelectLast => app.die_screen.selected = app.params_listed().len() - 1,
        Action::Decrease => app.nudge(-1, coarse),
        Action::Increase => app.nudge(1, coarse),
        Action::DecreaseBig => app.nudge(-1, true),
        Action::IncreaseBig => app.nudge(1, true),
        // The value editor and the parameter list are the main screen's: typing a value
        // blind is no help to a class.
        Action::TypeValue if app.page == Page::Presentation => {
            main_screen_first(app, "values are typed on the main screen")
        }
        Action::TypeValue => app.overlay = Some(Overlay::Value(Editor::default())),
        // Throwing is aimed on the die screen's die, not the presentation view's.
        Action::ThrowMode if app.page == Page::Presentation => {
            main_screen_first(app, "the throw is aimed on the main screen")
        }
        Action::ThrowMode => throw_keys::enter(app),
        Action::Twin | Action::TwinEpsilonDown | Action::TwinEpsilonUp | Action::TwinEpsilonType => {
            act_on_twin(app, action)
        }
        Action::Differ => twin_keys::on_differ_key(app),
        Action::NextStep | Action::PreviousStep => lesson_keys::on_step_key(app, action),
        Action::OpenPreset
        | Action::SavePreset
        | Action::ResetSetup
        | Action::OpenMap
        | Action::Presentation
        | Action::Help
        | Action::Close
        | Action::Quit => act_on_screens(app, action),
        Action::MapBack
        | Action::CursorLeft
        | Action::CursorRight
        | Action::CursorUp
        | Action::CursorDown
        | Action::CursorLeftBig
        | Action::CursorRightBig
        | Action::CursorUpBig
        | Action::CursorDownBig
        | Action::ReplayCell
        | Action::MapZoomIn
        | Action::MapZoomOut
        | Action::NextXAxis
        | Action::NextYAxis
        | Action::TypeXRange
        | Action::TypeYRange
        | Action::MapLayer
        | Action::ExportMap
        | Action::MapExportSize => map::act(app, action, coarse),
        // Rows of the overlays and of throw mode only: `read` never gives them on a screen.
        Action::Confirm
        | Action::Delete
        | Action::NextField
        | Action::GrabLeft
        | Action::GrabRight
        | Action::GrabUp
        | Action::GrabDown => {}
    }
}

/// The chaos twin's keys; its ε keys only once it rolls.
fn act_on_twin(app: &mut App, action: Action) {
    if !twin_keys::on_twin_key(app, action) {
        app.notice = Some(format!(
            "{} first: these keys set the twin's ε",
            label(Scope::Die, Action::Twin)
        ));
    }
}

/// Says that a key works on the main screen only, and why.
fn main_screen_first(app: &mut App, why: &str) {
    app.notice = Some(format!(
        "{} first: {why}",
        label(Scope::Show, Action::Presentation)
    ));
}

/// The keys that open, close and leave: presets, the map, the presentation view, the help.
fn act_on_screens(app: &mut App, action: Action) {
    match action {
        Action::OpenPreset => app.ask(Effect::ListPresets),
        Action::SavePreset => dialog_keys::open_save(app),
        Action::ResetSetup => app.reset_asking(),
        Action::OpenMap => map::open(app),
        Action::Presentation => {
            app.page = match app.page {
                Page::Presentation => Page::Die,
                _ => Page::Presentation,
            }
        }
        Action::Help => {
            app.overlay = Some(Overlay::Help { scroll: 0 });
        }
        Action::Close => match app.page {
            Page::Map => {
                map::close(app);
            }
            Page::Presentation => app.page = Page::Die,
            Page::Die => {
                app.notice = Some(format!(
                    "nothing to close ({} quits)",
                    label(Scope::Die, Action::Quit)
                ))
            }
        },
        Action::Quit => app.quit_asking(),
        // The others are `act`'s.
        _ => {}
    }
}

/// The roll's keys: playback, seeking, rolls, batches, speed and exports.
fn act_on_roll(app: &mut App, action: Action) {
    match action {
        Action::TogglePlay => app.send(Command::TogglePlay),
        Action::StepForward => app.send(Command::Step(1)),
        Action::StepBack => app.send(Command::StepBack(1)),
        Action::ToStart => app.send(Command::Seek(0)),
        Action::ToEnd => app.send(Command::Seek(u64::MAX)),
        Action::NextImpact => app.send(Command::SeekEvent(RollEvent::NextImpact)),
        Action::PreviousImpact => app.send(Command::SeekEvent(RollEvent::PreviousImpact)),
        Action::ToDecided => app.send(Command::SeekEvent(RollEvent::FaceDecided)),
        Action::Replay => app.send(Command::Replay),
        Action::RandomRoll => app.send(Command::RandomRoll),
        Action::Batch => {
            let c = app.roll.batch_command();
            app.send(c);
        }
        Action::BatchSize => app.next_batch_size(),
        Action::ClearTable => app.send(Command::ClearTable),
        Action::Slower => {
            if let Some(c) = app.setup.set_speed(app.setup.speed.slower()) {
                app.send(c)
            }
        }
        Action::Faster => {
            if let Some(c) = app.setup.set_speed(app.setup.speed.faster()) {
                app.send(c)
            }
        }
        Action::Export => {
            let c = app.roll.export_command(app.die_screen.log_scale);
            app.send(c);
        }
        Action::ExportAnimation => {
            let c = app.roll.animation_command(&app.die_screen.camera);
            app.send(c);
        }
        // The others are `act`'s.
        _ => {}
    }
}

/// The view's keys: the plot, the die's drawing and camera, the theme, the readout.
fn act_on_view(app: &mut App, action: Action) {
    match action {
        Action::LogScale => app.die_screen.log_scale = !app.die_screen.log_scale,
        Action::PlotQuantity => app.die_screen.plot.next(),
        Action::PhasePlot => app.die_screen.plot.toggle_phase(),
        Action::FitAxis => {
            let plot = &mut app.die_screen.plot;
            plot.fitted = !plot.fitted;
            app.notice = Some(
                if plot.fitted {
                    "the value axis fits the curves around the time on screen (y again: the whole roll)"
                } else {
                    "the value axis spans the whole roll"
                }
                .to_string(),
            );
        }
        Action::SecondQuantity => {
            if let Err(why) = app.die_screen.plot.next_second() {
                app.notice = Some(why);
            }
        }
        Action::FacePair => app.die_screen.next_face_pair(),
        Action::Arrows => app.die_screen.arrows = !app.die_screen.arrows,
        Action::Theme => {
            app.theme = app.theme.next();
            app.notice = Some(format!(
                "theme: {}{} ({} cycles dark, light, projector)",
                app.theme.palette.name(),
                if app.theme.colour {
                    ""
                } else {
                    ", but NO_COLOR is set"
                },
                label(Scope::Die, Action::Theme)
            ));
        }
        Action::Drawing => {
            app.die_screen.drawing = match app.die_screen.drawing {
                Drawing::Braille => Drawing::Ascii,
                Drawing::Ascii => Drawing::Braille,
            }
        }
        Action::OrbitLeft => app.die_screen.camera.orbit(-15.0, 0.0),
        Action::OrbitRight => app.die_screen.camera.orbit(15.0, 0.0),
        Action::TiltUp => app.die_screen.camera.orbit(0.0, 10.0),
        Action::TiltDown => app.die_screen.camera.orbit(0.0, -10.0),
        Action::ZoomIn => app.die_screen.camera.zoom_by(1),
        Action::ZoomOut => app.die_screen.camera.zoom_by(-1),
        Action::ResetCamera => app.die_screen.camera = OrbitCamera::default(),
        Action::NextReadout => app.die_screen.readout = app.die_screen.readout.next(),
        // The others are `act`'s.
        _ => {}
    }
}

fn on_edit_key(app: &mut App, input: &Input) {
    if let Some(Overlay::BatchSize(editor)) = app.overlay.as_mut() {
        // The size key again goes on round its ladder (no number has its letter) rather
        // than typing it.
        if let Input::Type(c) = input
            && first_key(Scope::Die, Action::BatchSize) == c.to_string()
        {
            app.next_batch_size();
            return;
        }
        // A count of rolls: digits (and an exponent, 1e6); a letter is refused as it is typed.
        if let Input::Type(c) = input
            && !(c.is_ascii_digit() || matches!(c, '.' | 'e' | 'E'))
        {
            editor.error = Some(format!(
                "`{c}`: a batch size is a whole number of rolls, typed in digits"
            ));
            return;
        }
        match editor.input(input, VALUE_CHARS) {
            Typed::Cancelled => app.overlay = None,
            Typed::Editing => {}
            Typed::Submitted(number) => match number.and_then(|n| app.roll.set_batch_size(n)) {
                Ok(notice) => {
                    app.overlay = None;
                    app.notice = Some(notice);
                }
                Err(e) => editor.error = Some(e),
            },
        }
        return;
    }
    let Some(Overlay::Value(editor)) = app.overlay.as_mut() else {
        return;
    };
    match editor.input(input, VALUE_CHARS) {
        Typed::Cancelled => app.overlay = None,
        Typed::Editing => {}
        Typed::Submitted(number) => {
            let p = app.selected_param();
            match number.and_then(|v| app.setup.set_param(p, v)) {
                Ok(c) => {
                    app.overlay = None;
                    app.send(c);
                }
                Err(e) => {
                    if let Some(Overlay::Value(editor)) = app.overlay.as_mut() {
                        editor.error = Some(e);
                    }
                }
            }
        }
    }
}

fn on_mouse(app: &mut App, m: MouseEvent) {
    let (kind, column, row) = (m.kind, m.column, m.row);
    if matches!(kind, MouseEventKind::Down(_)) {
        lesson_keys::card_down(app, None);
        // A click is an answer as a key is: the last notice was about what came before.
        app.notice = None;
    }
    // A drag on the die throws it in throw mode, and with Ctrl or Alt held outside it; a
    // plain drag orbits the camera.
    let flick = m.modifiers.intersects(KeyModifiers::CONTROL | KeyModifiers::ALT);
    match (app.mode(), kind) {
        (Mode::Throw, MouseEventKind::Down(MouseButton::Left)) => {
            if !throw_keys::press(app, column, row, false) {
                app.notice = Some("press on the die to grab it for a throw".to_string());
            }
            return;
        }
        (Mode::Normal, MouseEventKind::Down(MouseButton::Left))
            if flick && app.page == Page::Die && throw_keys::press(app, column, row, true) =>
        {
            return;
        }
        (Mode::Throw, MouseEventKind::Drag(MouseButton::Left)) => {
            throw_keys::drag(app, column, row);
            return;
        }
        (Mode::Throw, MouseEventKind::Up(_)) => {
            throw_keys::release(app);
            return;
        }
        (Mode::Throw, _) => return,
        _ => {}
    }
    if app.mode() != Mode::Normal {
        return;
    }
    if app.page == Page::Presentation {
        // The die fills the view: a drag anywhere orbits, a scroll zooms.
        match kind {
            MouseEventKind::Down(MouseButton::Left) => app.die_screen.drag = Some((column, row)),
            MouseEventKind::ScrollUp => app.die_screen.camera.zoom_by(1),
            MouseEventKind::ScrollDown => app.die_screen.camera.zoom_by(-1),
            _ => {}
        }
    }
    let Some(areas) = app.areas() else { return };
    let at = Position::new(column, row);
    match kind {
        MouseEventKind::Down(_) | MouseEventKind::ScrollUp | MouseEventKind::ScrollDown
            if app.page == Page::Presentation => {}
        MouseEventKind::Down(MouseButton::Left) => {
            if let Some(i) = param_row_at(app.die_screen.selected, app.params_listed().len(), &areas, at) {
                app.die_screen.selected = i;
            } else if let Some(bar) =
                timeline_bar(areas.timeline, strip_margins(app)).filter(|b| b.contains(at))
            {
                let step = timeline_step_at(&app.roll.live.timeline, bar, column);
                app.send(Command::Seek(step));
            } else if areas.die.contains(at) {
                app.die_screen.drag = Some((column, row));
            }
        }
        MouseEventKind::Drag(MouseButton::Left) => {
            if let Some((x, y)) = app.die_screen.drag {
                app.die_screen
                    .camera
                    .orbit(5.0 * (column as f64 - x as f64), 5.0 * (row as f64 - y as f64));
                app.die_screen.drag = Some((column, row));
            }
        }
        MouseEventKind::Up(_) => app.die_screen.drag = None,
        MouseEventKind::ScrollUp | MouseEventKind::ScrollDown => {
            let up = kind == MouseEventKind::ScrollUp;
            if areas.params.contains(at) {
                if let Some(i) = param_row_at(app.die_screen.selected, app.params_listed().len(), &areas, at)
                {
                    app.die_screen.selected = i;
                }
                app.nudge(if up { 1 } else { -1 }, false);
            } else if areas.die.contains(at) {
                app.die_screen.camera.zoom_by(if up { 1 } else { -1 });
            }
        }
        _ => {}
    }
}

/// The timeline strip's margins for the roll on screen.
pub(crate) fn strip_margins(app: &App) -> (u16, u16) {
    let integrator = &app.roll.live.params.integrator;
    timeline_margins(integrator.dt, integrator.max_time)
}
