//! The twins' keys. The chaos twin (`T`): a ghost die rolled from a start a relative ε
//! away, ε stepped by decades (`<` `>`) or typed (`E`). The parameter twin (`D`, "differ"):
//! while differ mode is on, a value changed on the parameter list goes to a second die B
//! only, rolled from the same start beside the die A, which keeps its values; the worker
//! rolls both, and this turns the edits into B's difference.

use crate::tui::state::app::{App, Overlay};
use crate::tui::state::editor::{Editor, Typed, VALUE_CHARS};
use crate::tui::state::twins::{DEFINITION, differs_text};
use crate::tui::vocabulary::format::fmt_num;
use crate::tui::vocabulary::key_table::{Action, Input, Scope, label};
use crate::worker::Command;
use dicesim_physics::{InitialCondition, Params};
use dicesim_setup::registry::Role;

/// The chaos twin's keys; returns whether `action` did anything (the ε keys need the twin on).
pub(crate) fn on_twin_key(app: &mut App, action: Action) -> bool {
    let twin = &mut app.twin;
    match action {
        Action::Twin => {
            let c = twin.toggle();
            if twin.on {
                app.notice = Some(format!("{DEFINITION}, ε = {}", fmt_num(twin.epsilon)));
            }
            app.send(c);
        }
        Action::TwinEpsilonDown | Action::TwinEpsilonUp if twin.on => {
            let factor = if action == Action::TwinEpsilonUp {
                10.0
            } else {
                0.1
            };
            if let Some(c) = twin.step(factor) {
                app.send(c);
            }
        }
        Action::TwinEpsilonType if twin.on => app.overlay = Some(Overlay::Epsilon(Editor::default())),
        _ => return false,
    }
    true
}

/// Typing ε (after `E`): digits, `e`, `-`, `.`; Enter applies, Esc cancels.
pub(crate) fn on_epsilon_key(app: &mut App, input: &Input) {
    let Some(Overlay::Epsilon(editor)) = app.overlay.as_mut() else {
        return;
    };
    match editor.input(input, VALUE_CHARS) {
        Typed::Cancelled => app.overlay = None,
        Typed::Editing => {}
        Typed::Submitted(number) => match number.and_then(|v| app.twin.set(v)) {
            Ok(c) => {
                app.overlay = None;
                app.send(c);
            }
            Err(e) => editor.error = Some(e),
        },
    }
}

/// `D`: differ mode on or off, with a notice saying what it does.
pub(crate) fn on_differ_key(app: &mut App) {
    let command = app.twin.toggle_differ();
    let key = label(Scope::Die, Action::Differ);
    app.notice = Some(if app.twin.differ {
        format!("differ: the next value changes go to die B only; {key} again ends it")
    } else {
        "differ off: die B is gone".to_string()
    });
    if let Some(c) = command {
        app.send(c);
    }
}

/// While differ mode is on, the value changes queued in this `update` become B's
/// difference: the setup as the user sees it goes back to `before` (A keeps its values)
/// and each change is sent as B's new list. A start value changes both dice (they share
/// the start), and Δt cannot differ (the dice step in lock-step): both are left to A, Δt
/// with a notice.
pub(crate) fn divert(app: &mut App, before: (Params, InitialCondition)) {
    if !app.twin.differ {
        return;
    }
    for c in app.outbox.commands_mut() {
        let Command::SetParam(key, value) = *c else {
            continue;
        };
        if key.spec.role == Role::Initial {
            continue;
        }
        (app.setup.params, app.setup.initial) = before;
        if key.key == "integrator.dt" {
            // Resent as A's own value: nothing changes, and the count of commands sent stays true.
            *c = Command::SetParam(key, key.get(&before.0, &before.1));
            app.notice = Some("Δt cannot differ: the two dice step in lock-step".to_string());
            continue;
        }
        *c = app.twin.differ_by(key, value);
        app.notice = Some(format!("die B: {}", differs_text(&app.twin.differs_by)));
    }
}
