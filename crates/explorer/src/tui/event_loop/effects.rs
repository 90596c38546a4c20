//! The effects `update` asks for, run by the event loop: a worker command is handed back
//! to be sent, the file work is done here (listing the presets for the picker, writing
//! one), on the loop's thread, so `update` itself never touches the disk.

use crate::tui::state::app::{App, Overlay};
use crate::tui::state::dialog::{Choice, Dialog, Group};
use crate::tui::state::messages::Effect;
use crate::tui::vocabulary::key_table::{Action, Scope, named};
use crate::worker::Command;
use dicesim_setup::preset::{LESSON, Preset, Source};

/// Runs one effect of `update`: the file work here, on the loop's thread; a worker command
/// is handed back for the caller to send.
pub(crate) fn perform(app: &mut App, effect: Effect) -> Option<Command> {
    match effect {
        Effect::Worker(command) => return Some(command),
        Effect::ListPresets => open_picker(app),
        Effect::SavePreset { preset, replace } => save(app, &preset, replace),
    }
    None
}

/// Opens the picker on every preset the store lists, the loaded one selected.
fn open_picker(app: &mut App) {
    let mut choices: Vec<Choice> = app
        .store
        .list()
        .into_iter()
        .map(|e| {
            let user = matches!(e.source, Source::User(_));
            let group = match LESSON.iter().position(|n| *n == e.name) {
                _ if user => Group::Yours,
                Some(_) => Group::Lesson,
                None => Group::Shipped,
            };
            Choice {
                user,
                group,
                preset: e.preset.map(Box::new).map_err(|err| err.to_string()),
                name: e.name,
            }
        })
        .collect();
    // The lesson's presets first, in its order; the rest keep the store's.
    let order = |c: &Choice| (c.group, LESSON.iter().position(|n| *n == c.name));
    choices.sort_by_key(order);
    let selected = choices
        .iter()
        .position(|c| c.name == app.setup.preset.name)
        .unwrap_or(0);
    app.overlay = Some(Overlay::Dialog(Dialog::Picker {
        choices,
        selected,
        error: None,
    }));
}

/// Writes `preset` into the user's folder ([`Effect::SavePreset`]): a name that
/// exists is replaced only with `replace`, else the dialog asks for a second Enter.
fn save(app: &mut App, preset: &Preset, replace: bool) {
    let name = preset.name.clone();
    let refuse = |app: &mut App, error: String, confirm_replace: bool| {
        if let Some(Overlay::Dialog(Dialog::Save {
            error: e,
            confirm_replace: c,
            ..
        })) = &mut app.overlay
        {
            (*e, *c) = (Some(error), confirm_replace);
        }
    };
    if !replace && app.store.exists(&name) {
        return refuse(
            app,
            format!(
                "`{name}` exists: {} again replaces it, {} keeps it",
                named(Scope::Save, Action::Confirm),
                named(Scope::Save, Action::Close)
            ),
            true,
        );
    }
    match app.store.save(preset, replace) {
        Ok(path) => {
            app.notice = Some(format!("saved {}", path.display()));
            // The saved file is now what the setup is compared with.
            app.setup.preset = preset.clone();
            app.overlay = None;
        }
        Err(e) => refuse(app, e.to_string(), false),
    }
}
