//! The preset dialogs: `o` picks a preset to load (shipped and the user's, with their
//! descriptions), `s` saves the current setup under a name, asking before it replaces one.
//!
//! Their keys never touch the disk themselves: listing the preset folder ([`open_picker`])
//! and writing a file ([`save`]) are effects the event loop runs after `update`.

use super::app::{App, Effect, Overlay, Prompt};
pub(crate) use super::dialog::{Choice, Dialog, SaveField};
use super::fit;
use super::format::fmt_num;
use super::keys::{Action, Input, Scope, named};
use super::param::all;
use crate::worker::Command;
use dicesim_setup::output::printable;
use dicesim_setup::preset::{Preset, Source, check_name};
use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph, Wrap};

/// Characters of a preset's description the picker shows: more than any screen holds.
const DESCRIPTION_SHOWN: usize = 4000;

/// Characters a preset name may have in the dialog (the name check decides the rest).
const NAME_CHARS: usize = 64;
/// Characters of a description typed in the dialog.
const DESCRIPTION_CHARS: usize = 600;

/// Whether the setup on screen differs from the preset it was loaded from.
pub(crate) fn modified(app: &App) -> bool {
    app.setup.modified()
}

/// Opens the picker on every preset the store lists, the loaded one selected.
pub(crate) fn open_picker(app: &mut App) {
    let choices: Vec<Choice> = app
        .store
        .list()
        .into_iter()
        .map(|e| Choice {
            user: matches!(e.source, Source::User(_)),
            preset: e.preset.map(Box::new).map_err(|err| err.to_string()),
            name: e.name,
        })
        .collect();
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

pub(crate) fn open_save(app: &mut App) {
    app.overlay = Some(Overlay::Dialog(Dialog::Save {
        name: String::new(),
        description: String::new(),
        field: SaveField::Name,
        error: None,
        confirm_replace: false,
    }));
}

/// What a saved setup says about itself when no description is typed: its base and the
/// values changed from it, as `presets save --set` words it.
pub(crate) fn automatic_description(app: &App) -> String {
    let base = (app.setup.preset.params(), app.setup.preset.initial);
    let changed: Vec<String> = all()
        .iter()
        .filter_map(|p| {
            let (now, was) = (
                p.get(&app.setup.params, &app.setup.initial),
                p.get(&base.0, &base.1),
            );
            (now != was).then(|| format!("{}={}", p.key(), fmt_num(now)))
        })
        .collect();
    if changed.is_empty() {
        format!("The `{}` preset, saved from the explorer.", app.setup.preset.name)
    } else {
        format!(
            "The `{}` preset with {}.",
            app.setup.preset.name,
            changed.join(", ")
        )
    }
}

/// The setup and the view on screen as a preset named `name`: the loaded preset's random
/// ranges, the current model values, start and view.
pub(crate) fn current_setup(app: &App, name: &str, description: &str) -> Preset {
    let p = &app.setup.params;
    let description = match description.trim() {
        "" => automatic_description(app),
        typed => typed.to_string(),
    };
    Preset {
        name: name.to_string(),
        description,
        die: p.die,
        ground: p.ground,
        world: p.world,
        integrator: p.integrator,
        initial: app.setup.initial,
        view: app.current_view(),
        ..app.setup.preset.clone()
    }
}

/// Keys while a dialog is open.
pub(crate) fn on_key(app: &mut App, input: &Input, out: &mut Vec<Command>) {
    let Some(Overlay::Dialog(dialog)) = app.overlay.take() else {
        return;
    };
    let next = match dialog {
        Dialog::Picker {
            choices,
            selected,
            error,
        } => picker_key(app, input, out, choices, selected, error),
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
    out: &mut Vec<Command>,
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
            Some(Ok(preset)) if modified(app) => {
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
                app.setup.load(out, preset);
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
                preset: Box::new(current_setup(app, &form.name, &form.description)),
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

/// Writes `preset` into the user's folder (the effect [`Effect::SavePreset`]): a name that
/// exists is replaced only with `replace`, else the dialog asks for a second Enter.
pub(crate) fn save(app: &mut App, preset: &Preset, replace: bool) {
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

/// Draws the open dialog, centred over the screen, and over it any question being asked.
pub fn render(app: &App, area: Rect, frame: &mut Frame) {
    render_dialog(app, area, frame);
    if let Some(prompt) = app.prompt() {
        let t = &app.theme;
        let (keys, words) = prompt.answers();
        let popup = area.centered(Constraint::Max(64), Constraint::Length(4));
        clear_around(popup, area, frame);
        let lines = vec![
            Line::styled(printable(&prompt.question(&app.setup.preset.name)), t.caution()),
            Line::from(vec![
                Span::styled(keys, t.key()),
                Span::raw(format!(" {words} · any other key stays")),
            ]),
        ];
        let block = Block::bordered().title(Line::styled(" are you sure? ", t.heading()));
        let body = text_area(block.inner(popup));
        frame.render_widget(block, popup);
        frame.render_widget(Paragraph::new(lines).wrap(Wrap { trim: true }), body);
    }
}

/// Clears a popup and a column either side of it, so the text it covers ends in a blank
/// column instead of running into its border as if cut.
pub(crate) fn clear_around(popup: Rect, screen: Rect, frame: &mut Frame) {
    let x = popup.x.saturating_sub(1).max(screen.x);
    let right = (popup.right() + 1).min(screen.right());
    frame.render_widget(
        Clear,
        Rect {
            x,
            width: right - x,
            ..popup
        },
    );
}

/// The part of a popup's inside its text wraps in: the last column stays free (`fit`).
pub(crate) fn text_area(inside: Rect) -> Rect {
    Rect {
        width: fit::room(inside.width as usize) as u16,
        ..inside
    }
}

/// The picker's list of `total` entries in `height` rows, the selection in view: the first
/// entry shown, how many are shown, and whether a row above and below marks more entries.
pub(crate) fn picker_window(total: usize, selected: usize, height: usize) -> (usize, usize, bool) {
    if total <= height || height < 3 {
        let shown = total.min(height);
        let first = selected.saturating_sub(shown.saturating_sub(1));
        return (first.min(total - shown), shown, false);
    }
    let shown = height - 2;
    let first = selected.saturating_sub(shown - 1).min(total - shown);
    (first, shown, true)
}

fn render_dialog(app: &App, area: Rect, frame: &mut Frame) {
    let Some(dialog) = app.dialog() else { return };
    let t = &app.theme;
    match dialog {
        Dialog::Picker {
            choices,
            selected,
            error,
        } => {
            let popup = area.centered(Constraint::Max(90), Constraint::Percentage(80));
            clear_around(popup, area, frame);
            let block = Block::bordered()
                .title(Line::styled(" open a preset ", t.heading()))
                .title_bottom(
                    fit::abbreviate(
                        Line::from(format!(
                            " {} choose · {} loads · {} closes · ★ yours ",
                            named(Scope::Picker, Action::SelectPrevious),
                            named(Scope::Picker, Action::Confirm),
                            named(Scope::Picker, Action::Close)
                        )),
                        popup.width.saturating_sub(2) as usize,
                    )
                    .right_aligned(),
                );
            let body = block.inner(popup);
            frame.render_widget(block, popup);
            let mut lines = Vec::new();
            let room = fit::room(body.width as usize);
            for (i, c) in choices.iter().enumerate() {
                let mark = if c.user { "★" } else { " " };
                let pointer = if i == *selected { "▶" } else { " " };
                let name = fit::cut_text(&printable(&c.name), room.saturating_sub(3));
                let mut line = Line::from(format!("{pointer}{mark} {name}"));
                if i == *selected {
                    line = line.style(t.selected());
                }
                lines.push(line);
            }
            let about = match (error, choices.get(*selected).map(|c| &c.preset)) {
                (Some(e), _) => Line::styled(printable(e), t.danger()),
                // Only what the box can show is wrapped: a long description stays cheap.
                (None, Some(Ok(p))) => Line::raw(printable(
                    &p.description.chars().take(DESCRIPTION_SHOWN).collect::<String>(),
                )),
                (None, Some(Err(_))) => Line::styled(
                    format!(
                        "this file does not load: {} shows why",
                        named(Scope::Picker, Action::Confirm)
                    ),
                    t.caution(),
                ),
                (None, None) => Line::raw("no presets found"),
            };
            // The list on top (scrolled to keep the selection in view), the description below.
            let list_height = (lines.len() as u16).min(body.height.saturating_sub(3) / 2).max(1);
            let [list, _, description] = body.layout(&Layout::vertical([
                Constraint::Length(list_height),
                Constraint::Length(1),
                Constraint::Min(0),
            ]));
            // Entries past the list's ends are counted on a row of their own.
            let total = lines.len();
            let (first, shown, marked) = picker_window(total, *selected, list_height as usize);
            let mut rows: Vec<Line> = lines.into_iter().skip(first).take(shown).collect();
            if marked {
                let more = |arrow: &str, n: usize| {
                    if n > 0 {
                        Line::styled(format!(" {arrow} {n} more"), t.heading())
                    } else {
                        Line::raw("")
                    }
                };
                rows.insert(0, more("▲", first));
                rows.push(more("▼", total - first - shown));
            }
            frame.render_widget(Paragraph::new(rows), list);
            frame.render_widget(
                Paragraph::new(about).wrap(Wrap { trim: true }),
                text_area(description),
            );
        }
        Dialog::Save {
            name,
            description,
            field,
            error,
            confirm_replace,
        } => {
            let popup = area.centered(Constraint::Max(76), Constraint::Length(11));
            clear_around(popup, area, frame);
            let block = Block::bordered()
                .title(Line::styled(" save the setup and view as a preset ", t.heading()))
                .title_bottom(
                    fit::abbreviate(
                        Line::from(format!(
                            " {}: name / description · {} saves · {} cancels ",
                            named(Scope::Save, Action::NextField),
                            named(Scope::Save, Action::Confirm),
                            named(Scope::Save, Action::Close)
                        )),
                        popup.width.saturating_sub(2) as usize,
                    )
                    .right_aligned(),
                );
            let folder = match app.store.user_dir() {
                Ok(dir) => format!("into {}", dir.display()),
                Err(e) => e.to_string(),
            };
            let cursor = |on: bool| if on { "▏" } else { "" };
            let description_line = if description.is_empty() && *field != SaveField::Description {
                Span::raw(printable(&automatic_description(app)))
            } else {
                Span::styled(
                    format!("{description}{}", cursor(*field == SaveField::Description)),
                    t.selected(),
                )
            };
            let mut lines = vec![
                Line::from(vec![
                    Span::styled("name: ", t.heading()),
                    Span::styled(
                        format!("{name}{}", cursor(*field == SaveField::Name)),
                        t.selected(),
                    ),
                ]),
                Line::from(vec![Span::styled("description: ", t.heading()), description_line]),
            ];
            if description.is_empty() {
                lines.push(Line::raw(format!(
                    "(left empty, the text above is saved; {} to type your own)",
                    named(Scope::Save, Action::NextField)
                )));
            }
            lines.push(Line::raw(folder));
            if let Some(e) = error {
                let style = if *confirm_replace { t.caution() } else { t.danger() };
                lines.push(Line::styled(e.clone(), style));
            }
            let body = text_area(block.inner(popup));
            frame.render_widget(block, popup);
            frame.render_widget(Paragraph::new(lines).wrap(Wrap { trim: true }), body);
        }
    }
}

#[cfg(test)]
mod picker_tests {
    use super::picker_window;

    #[test]
    fn the_picker_keeps_the_selection_in_view_between_its_markers() {
        // Fifteen presets in seven rows: five entries between the two marker rows.
        assert_eq!(picker_window(15, 0, 7), (0, 5, true));
        assert_eq!(picker_window(15, 4, 7), (0, 5, true));
        assert_eq!(picker_window(15, 5, 7), (1, 5, true));
        assert_eq!(picker_window(15, 14, 7), (10, 5, true));
        // Everything fits: no markers.
        assert_eq!(picker_window(5, 4, 7), (0, 5, false));
    }
}
