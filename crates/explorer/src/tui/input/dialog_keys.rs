//! The preset dialogs' keys. The picker (open once the event loop has listed the presets
//! `o` asked for) chooses one to load, asking first over unsaved changes; `s` opens the save
//! dialog, whose Enter asks the event loop to write the preset. No key here touches the disk.

use crate::tui::state::app::{App, Overlay, Prompt};
use crate::tui::state::dialog::{Choice, Dialog, SaveField};
use crate::tui::state::messages::Effect;
use crate::tui::vocabulary::key_table::{Action, Input};
use dicesim_setup::preset::check_name;

/// Characters a preset name may have in the dialog (the name check decides the rest).
const NAME_CHARS: usize = 64;
/// Characters of a description typed in the dialog.
const DESCRIPTION_CHARS: usize = 600;

/// `s`: the save dialog, both fields empty.
pub(crate) fn open_save(app: &mut App) {
    app.overlay = Some(Overlay::Dialog(Dialog::Save {
        name: String::new(),
        description: String::new(),
        field: SaveField::Name,
        error: None,
        confirm_replace: false,
    }));
}

/// Keys while a dialog is open.
pub(crate) fn on_key(app: &mut App, input: &Input) {
    let Some(Overlay::Dialog(dialog)) = app.overlay.take() else {
        return;
    };
    let next = match dialog {
        Dialog::Picker {
            choices,
            selected,
            error,
        } => picker_key(app, input, choices, selected, error),
        Dialog::Save {
            name,
            description,
            field,
            error,
            confirm_replace,
        } => save_key(
            app,
            input,
            SaveForm {
                name,
                description,
                field,
            },
            error,
            confirm_replace,
        ),
    };
    // A question asked from the picker has taken the top, the picker kept under it.
    if app.overlay.is_none() {
        app.overlay = next.map(Overlay::Dialog);
    }
}

fn picker_key(
    app: &mut App,
    input: &Input,
    choices: Vec<Choice>,
    selected: usize,
    error: Option<String>,
) -> Option<Dialog> {
    let last = choices.len().saturating_sub(1);
    let action = match input {
        Input::Act { action, .. } => *action,
        other => {
            app.nothing_here(other);
            return Some(Dialog::Picker {
                choices,
                selected,
                error,
            });
        }
    };
    let selected = match action {
        Action::Close => return None,
        Action::SelectPrevious => selected.saturating_sub(1),
        Action::SelectNext => (selected + 1).min(last),
        Action::SelectFirst => 0,
        Action::SelectLast => last,
        Action::Confirm => match choices.get(selected).map(|c| c.preset.clone()) {
            Some(Ok(preset)) if app.setup.modified() => {
                // The picker stays under the question: anything but yes goes back to it.
                app.overlay = Some(Overlay::Prompt {
                    prompt: Prompt::Load(preset),
                    under: Some(Dialog::Picker {
                        choices,
                        selected,
                        error,
                    }),
                });
                return None;
            }
            Some(Ok(preset)) => {
                app.load(preset);
                return None;
            }
            Some(Err(e)) => {
                return Some(Dialog::Picker {
                    choices,
                    selected,
                    error: Some(e),
                });
            }
            None => return None,
        },
        _ => selected,
    };
    // Moving on clears the error of the file that did not load.
    let error = if action == Action::Confirm { error } else { None };
    Some(Dialog::Picker {
        choices,
        selected,
        error,
    })
}

/// What the save dialog holds as it is typed.
struct SaveForm {
    name: String,
    description: String,
    field: SaveField,
}

fn save_key(
    app: &mut App,
    input: &Input,
    mut form: SaveForm,
    error: Option<String>,
    confirm_replace: bool,
) -> Option<Dialog> {
    let dialog = |form: SaveForm, error: Option<String>, confirm_replace: bool| {
        Some(Dialog::Save {
            name: form.name,
            description: form.description,
            field: form.field,
            error,
            confirm_replace,
        })
    };
    let typing = match form.field {
        SaveField::Name => &mut form.name,
        SaveField::Description => &mut form.description,
    };
    let limit = match form.field {
        SaveField::Name => NAME_CHARS,
        SaveField::Description => DESCRIPTION_CHARS,
    };
    let action = |a: Action| matches!(input, Input::Act { action, .. } if *action == a);
    match input {
        _ if action(Action::Close) => None,
        _ if action(Action::NextField) => {
            form.field = match form.field {
                SaveField::Name => SaveField::Description,
                SaveField::Description => SaveField::Name,
            };
            dialog(form, error, confirm_replace)
        }
        _ if action(Action::Delete) => {
            typing.pop();
            // Another name is another question.
            let keep = form.field == SaveField::Description;
            dialog(form, error.filter(|_| keep), confirm_replace && keep)
        }
        Input::Type(c) => {
            if typing.chars().count() < limit {
                typing.push(*c);
            }
            let keep = form.field == SaveField::Description;
            dialog(form, error.filter(|_| keep), confirm_replace && keep)
        }
        _ if action(Action::Confirm) => {
            if let Err(e) = check_name(&form.name) {
                return dialog(form, Some(e.to_string()), false);
            }
            app.ask(Effect::SavePreset {
                preset: Box::new(app.as_preset(&form.name, &form.description)),
                replace: confirm_replace,
            });
            dialog(form, None, confirm_replace)
        }
        other => {
            app.nothing_here(other);
            dialog(form, error, confirm_replace)
        }
    }
}
