//! The preset dialogs drawn: the picker (`o`: shipped presets and the user's, with their
//! descriptions), the save dialog (`s`), and over either the question asked before the
//! user's changes are lost.

use crate::tui::panels::overlays::popup::{clear_around, text_area};
use crate::tui::state::app::App;
use crate::tui::state::dialog::{Choice, Dialog, SaveField};
use crate::tui::vocabulary::fit;
use crate::tui::vocabulary::key_table::{Action, Scope, named};
use dicesim_setup::output::printable;
use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Wrap};

/// Characters of a preset's description the picker shows: more than any screen holds.
const DESCRIPTION_SHOWN: usize = 4000;

/// Columns of the picker's list beside the description: the longest shipped name with its
/// marks and the gap column.
const LIST_WIDTH: u16 = 29;

/// The picker's inside from which the description goes beside the list rather than under
/// it: the list and a description column of 40.
const PICKER_BESIDE: u16 = LIST_WIDTH + 1 + 40;

/// Draws the open dialog, centred over the screen, and over it any question being asked.
pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
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
    match app.dialog() {
        Some(Dialog::Picker {
            choices,
            selected,
            error,
        }) => render_picker(app, area, frame, choices, *selected, error.as_deref()),
        Some(Dialog::Save {
            name,
            description,
            field,
            error,
            confirm_replace,
        }) => render_save(
            app,
            area,
            frame,
            (name, description, *field),
            error.as_deref(),
            *confirm_replace,
        ),
        None => {}
    }
}

/// The preset picker: the list, and the selected preset's description beside or under it.
fn render_picker(
    app: &App,
    area: Rect,
    frame: &mut Frame,
    choices: &[Choice],
    selected: usize,
    error: Option<&str>,
) {
    let t = &app.theme;
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
    // Beside the list where the box is wide enough, under it where not.
    let beside = body.width >= PICKER_BESIDE;
    let list_width = if beside { LIST_WIDTH } else { body.width };
    let room = fit::room(list_width as usize);
    let (lines, row_of) = picker_lines(app, choices, selected, room);
    let about = picker_about(app, choices, selected, error);
    let (list, description) = if beside {
        let [list, _, description] = body.layout(&Layout::horizontal([
            Constraint::Length(list_width),
            Constraint::Length(1),
            Constraint::Min(0),
        ]));
        (list, description)
    } else {
        // The list on top, the description below.
        let list_height = (lines.len() as u16).min(body.height.saturating_sub(3) / 2).max(1);
        let [list, _, description] = body.layout(&Layout::vertical([
            Constraint::Length(list_height),
            Constraint::Length(1),
            Constraint::Min(0),
        ]));
        (list, description)
    };
    // Rows past the list's ends are counted on a row of their own; the selection
    // stays in view.
    let total = lines.len();
    let at = row_of.get(selected).copied().unwrap_or(0);
    let (first, shown, marked) = picker_window(total, at, list.height as usize);
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

/// The picker's list: each group under its heading, the selection marked; and the row of
/// each choice.
fn picker_lines(
    app: &App,
    choices: &[Choice],
    selected: usize,
    room: usize,
) -> (Vec<Line<'static>>, Vec<usize>) {
    let t = &app.theme;
    // Each group under its heading; `row_of[i]`: the row of choice i.
    let mut lines = Vec::new();
    let mut row_of = Vec::with_capacity(choices.len());
    for (i, c) in choices.iter().enumerate() {
        if i == 0 || choices[i - 1].group != c.group {
            lines.push(Line::styled(fit::cut_text(c.group.heading(), room), t.heading()));
        }
        row_of.push(lines.len());
        let mark = if c.user { "★" } else { " " };
        let pointer = if i == selected { "▶" } else { " " };
        let name = fit::cut_text(&printable(&c.name), room.saturating_sub(3));
        let mut line = Line::from(format!("{pointer}{mark} {name}"));
        if i == selected {
            line = line.style(t.selected());
        }
        lines.push(line);
    }
    (lines, row_of)
}

/// What the picker says about the selected choice: its description, or why it does not load.
fn picker_about(app: &App, choices: &[Choice], selected: usize, error: Option<&str>) -> Line<'static> {
    let t = &app.theme;
    match (error, choices.get(selected).map(|c| &c.preset)) {
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
    }
}

/// The save dialog: the name and description typed (`field` the one typing goes to), the
/// folder, and what went wrong or is asked.
fn render_save(
    app: &App,
    area: Rect,
    frame: &mut Frame,
    (name, description, field): (&str, &str, SaveField),
    error: Option<&str>,
    confirm_replace: bool,
) {
    let t = &app.theme;
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
    let description_line = if description.is_empty() && field != SaveField::Description {
        Span::raw(printable(&app.setup.automatic_description()))
    } else {
        Span::styled(
            format!("{description}{}", cursor(field == SaveField::Description)),
            t.selected(),
        )
    };
    let mut lines = vec![
        Line::from(vec![
            Span::styled("name: ", t.heading()),
            Span::styled(
                format!("{name}{}", cursor(field == SaveField::Name)),
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
        let style = if confirm_replace { t.caution() } else { t.danger() };
        lines.push(Line::styled(e.to_string(), style));
    }
    let body = text_area(block.inner(popup));
    frame.render_widget(block, popup);
    frame.render_widget(Paragraph::new(lines).wrap(Wrap { trim: true }), body);
}

#[cfg(test)]
mod dialogs_tests;
