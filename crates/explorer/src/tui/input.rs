//! Key and mouse routing: `update(&mut App, Msg)` reads a key through the key table
//! ([`super::keys::read`]) and hands it to whatever is on top, or to the screen under it.
//! It sits above the state ([`App`]) and the panels; nothing below imports it. Nothing here
//! draws, sleeps or reads a clock: the commands for the worker and the file work are
//! returned.

use super::app::{App, Drawing, Editor, Effect, Mode, Msg, Overlay, Prompt, Typed, VALUE_CHARS};
use super::camera::OrbitCamera;
use super::keys::{Action, Input, Scope, label, read};
use super::layout::param_row_at;
use super::map_keys as map;
use super::map_view::Page;
use super::param::all;
use crate::worker::Command;
use ratatui::crossterm::event::{Event, KeyEvent, KeyEventKind, MouseButton, MouseEventKind};
use ratatui::layout::{Position, Rect};

/// Applies one message; returns what the event loop is to do, in order: the worker's
/// commands, then any file work.
pub fn update(app: &mut App, msg: Msg) -> Vec<Effect> {
    let mut out = Vec::new();
    // In differ mode the value changes a key or the mouse makes go to die B.
    let before = (app.setup.params, app.setup.initial);
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
    super::versus::divert(app, before, &mut out);
    if std::mem::take(&mut app.map.open_asked) {
        map::open(app, &mut out);
    }
    let mut effects: Vec<Effect> = out.into_iter().map(Effect::Worker).collect();
    effects.append(&mut app.effects);
    effects
}

fn on_key(app: &mut App, key: KeyEvent, out: &mut Vec<Command>) {
    let input = read(app.key_scope(), key);
    if input == Input::Interrupt {
        app.quit(out);
        return;
    }
    app.notice = None;
    match app.mode() {
        Mode::Prompt => on_prompt_key(app, &input, out),
        Mode::EditingValue => on_edit_key(app, &input, out),
        Mode::Dialog => super::dialogs::on_key(app, &input, out),
        Mode::EditingEpsilon => super::twin::on_editor_key(app, &input, out),
        Mode::EditingRange => map::on_range_key(app, &input, out),
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
            Input::Act { action, coarse } => act(app, action, coarse, out),
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
fn on_prompt_key(app: &mut App, input: &Input, out: &mut Vec<Command>) {
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
        Prompt::Quit => app.quit(out),
        Prompt::Reset => {
            let preset = Box::new(app.setup.preset.clone());
            app.setup.load(out, preset);
        }
        Prompt::Load(preset) => {
            app.setup.load(out, preset);
        }
    }
}

/// Does what a key of the table stands for.
fn act(app: &mut App, action: Action, coarse: bool, out: &mut Vec<Command>) {
    match action {
        Action::TogglePlay => app.setup.send(out, Command::TogglePlay),
        Action::StepForward => app.setup.send(out, Command::Step(1)),
        Action::StepBack => app.setup.send(out, Command::StepBack(1)),
        Action::ToStart => app.setup.send(out, Command::Seek(0)),
        Action::ToEnd => app.setup.send(out, Command::Seek(u64::MAX)),
        Action::Replay => app.setup.send(out, Command::Replay),
        Action::RandomRoll => app.setup.send(out, Command::RandomRoll),
        Action::Batch => {
            let c = app.roll.batch_command();
            app.setup.send(out, c);
        }
        Action::BatchSize => app.next_batch_size(),
        Action::ClearTable => app.setup.send(out, Command::ClearTable),
        Action::Slower => app.setup.set_speed(out, app.setup.speed.slower()),
        Action::Faster => app.setup.set_speed(out, app.setup.speed.faster()),
        Action::SelectPrevious => app.select(-1),
        Action::SelectNext => app.select(1),
        Action::SelectFirst => app.selected = 0,
        Action::SelectLast => app.selected = all().len() - 1,
        Action::Decrease => app.nudge(out, -1, coarse),
        Action::Increase => app.nudge(out, 1, coarse),
        Action::DecreaseBig => app.nudge(out, -1, true),
        Action::IncreaseBig => app.nudge(out, 1, true),
        // The value editor and the parameter list are the main screen's: typing a value
        // blind is no help to a class.
        Action::TypeValue if app.page == Page::Presentation => {
            app.notice = Some(format!(
                "{} first: values are typed on the main screen",
                label(Scope::Show, Action::Presentation)
            ))
        }
        Action::TypeValue => app.overlay = Some(Overlay::Value(Editor::default())),
        Action::LogScale => app.log_scale = !app.log_scale,
        Action::PlotQuantity => app.plot.next(),
        Action::PhasePlot => app.plot.toggle_phase(),
        Action::Export => {
            let c = app.roll.export_command(app.log_scale);
            app.setup.send(out, c);
        }
        Action::ExportAnimation => {
            let c = app.roll.animation_command(&app.camera);
            app.setup.send(out, c);
        }
        Action::Arrows => app.vectors = !app.vectors,
        Action::Twin | Action::TwinEpsilonDown | Action::TwinEpsilonUp | Action::TwinEpsilonType => {
            if !super::twin::on_key(app, action, out) {
                app.notice = Some(format!(
                    "{} first: these keys set the twin's ε",
                    label(Scope::Die, Action::Twin)
                ));
            }
        }
        Action::Differ => super::versus::on_key(app, out),
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
            app.drawing = match app.drawing {
                Drawing::Braille => Drawing::Ascii,
                Drawing::Ascii => Drawing::Braille,
            }
        }
        Action::OrbitLeft => app.camera.orbit(-15.0, 0.0),
        Action::OrbitRight => app.camera.orbit(15.0, 0.0),
        Action::TiltUp => app.camera.orbit(0.0, 10.0),
        Action::TiltDown => app.camera.orbit(0.0, -10.0),
        Action::ZoomIn => app.camera.zoom_by(1),
        Action::ZoomOut => app.camera.zoom_by(-1),
        Action::ResetCamera => app.camera = OrbitCamera::default(),
        Action::OpenPreset => app.ask(Effect::ListPresets),
        Action::SavePreset => super::dialogs::open_save(app),
        Action::ResetSetup => app.reset_asking(),
        Action::OpenMap => map::open(app, out),
        Action::Presentation => {
            app.page = match app.page {
                Page::Presentation => Page::Die,
                _ => Page::Presentation,
            }
        }
        Action::NextReadout => app.readout = app.readout.next(),
        Action::Help => {
            app.overlay = Some(Overlay::Help { scroll: 0 });
        }
        Action::Close => match app.page {
            Page::Map => {
                map::close(app, out);
            }
            Page::Presentation => app.page = Page::Die,
            Page::Die => {
                app.notice = Some(format!(
                    "nothing to close ({} quits)",
                    label(Scope::Die, Action::Quit)
                ))
            }
        },
        Action::Quit => app.quit_asking(out),
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
        | Action::MapExportSize => map::act(app, action, coarse, out),
        // Rows of the overlays only: `read` never gives them on a screen.
        Action::Confirm | Action::Delete | Action::NextField => {}
    }
}

fn on_edit_key(app: &mut App, input: &Input, out: &mut Vec<Command>) {
    if let Some(Overlay::BatchSize(editor)) = app.overlay.as_mut() {
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
            match number.and_then(|v| app.setup.set_param(out, p, v)) {
                Ok(()) => app.overlay = None,
                Err(e) => {
                    if let Some(Overlay::Value(editor)) = app.overlay.as_mut() {
                        editor.error = Some(e);
                    }
                }
            }
        }
    }
}

fn on_mouse(app: &mut App, kind: MouseEventKind, column: u16, row: u16, out: &mut Vec<Command>) {
    if app.mode() != Mode::Normal {
        return;
    }
    if app.page == Page::Presentation {
        // The die fills the view: a drag anywhere orbits, a scroll zooms.
        match kind {
            MouseEventKind::Down(MouseButton::Left) => app.drag = Some((column, row)),
            MouseEventKind::ScrollUp => app.camera.zoom_by(1),
            MouseEventKind::ScrollDown => app.camera.zoom_by(-1),
            _ => {}
        }
    }
    let Some(areas) = app.areas() else { return };
    let at = Position::new(column, row);
    match kind {
        MouseEventKind::Down(_) | MouseEventKind::ScrollUp | MouseEventKind::ScrollDown
            if app.page == Page::Presentation => {}
        MouseEventKind::Down(MouseButton::Left) => {
            if let Some(i) = param_row_at(app.selected, &areas, at) {
                app.selected = i;
            } else if let Some(bar) = super::timeline::bar(areas.timeline).filter(|b| b.contains(at)) {
                let step = super::timeline::step_at(app, bar, column);
                app.setup.send(out, Command::Seek(step));
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
                if let Some(i) = param_row_at(app.selected, &areas, at) {
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
