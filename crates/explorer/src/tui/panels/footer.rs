//! The footer's key hints and the help overlay's frame.

use crate::tui::state::app::{App, Mode};
use crate::tui::vocabulary::format::group;
use crate::tui::vocabulary::key_table::{Action, INTERRUPT, Scope, labels, rows};
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

/// A footer hint: keys, what they do, and priority (on a narrow terminal the highest
/// numbers go first, so the keys that matter most, help and quit among them, stay in view).
pub(crate) type KeyHint = (String, String, u8);

/// The priority from which a hint too many for the footer goes altogether (below it, only
/// its words go).
const DROPPED_FROM: u8 = 3;

fn hint(keys: &str, words: &str, priority: u8) -> KeyHint {
    (keys.to_string(), words.to_string(), priority)
}

/// The footer of either screen: the hints of whatever is topmost.
pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
    let keys = match app.mode() {
        Mode::Prompt => {
            let prompt = app.prompt().expect("the mode says so");
            let (keys, words) = prompt.answers();
            let question = prompt.question(&app.setup.preset.name);
            let hints = vec![
                hint(&keys, words, 0),
                // Its separator goes with it when a narrow footer drops it.
                hint("· any other key", "stays", DROPPED_FROM),
            ];
            return render_line(app, Some(question), hints, area, frame);
        }
        Mode::EditingValue if app.batch_editor().is_some() => {
            let editor = app.batch_editor().expect("checked");
            let line = match &editor.error {
                Some(e) => e.clone(),
                None => format!("batch size: {}▏ rolls", editor.text),
            };
            return render_line(app, Some(line), typing_hints(None), area, frame);
        }
        Mode::EditingValue if app.value_editor().is_some() => {
            let refusal = crate::tui::panels::params_panel::refusal_for_status_line(app, area.width);
            return render_line(app, refusal, typing_hints(None), area, frame);
        }
        Mode::EditingValue | Mode::EditingEpsilon => typing_hints(None),
        Mode::EditingRange => typing_hints(Some("MIN MAX")),
        Mode::Dialog | Mode::Help => table_hints(app, app.key_scope()),
        Mode::Map => table_hints(app, Scope::Map),
        Mode::Throw => {
            // What the throw as aimed would give, until a notice says more; in as many words
            // as leave the keys that throw and go back in view.
            let hints = table_hints(app, Scope::Throw);
            let needed: usize = hints
                .iter()
                .filter(|h| h.2 == 0)
                .map(|(k, w, _)| 2 + k.chars().count() + w.chars().count())
                .sum();
            let aim = app.die_screen.throw.map(|t| {
                let thrown = t.thrown(&app.die_screen.camera, &app.setup.params);
                let [vectors, sizes] = thrown.short_words();
                let forms = [format!("aim: {}", thrown.words()), vectors, sizes];
                let room = crate::tui::vocabulary::fit::room(area.width as usize).saturating_sub(needed + 2);
                forms
                    .iter()
                    .find(|f| f.chars().count() <= room)
                    .unwrap_or(&forms[2])
                    .clone()
            });
            let notice = app.roll.export_status().or_else(|| app.notice.clone()).or(aim);
            return render_line(app, notice, hints, area, frame);
        }
        Mode::Normal => table_hints(app, Scope::Die),
    };
    render_key_hints(app, keys, area, frame);
}

/// The hints of one screen's rows of the key table, in words that follow the state.
fn table_hints(app: &App, screen: Scope) -> Vec<KeyHint> {
    // The lesson's keys while one is walked (the help lists them always).
    let walking = app.lesson.as_ref().is_some_and(|l| l.at.is_some());
    rows(screen)
        .filter_map(|b| b.hint.map(|h| (b.action, h)))
        .filter(|(action, _)| walking || *action != Action::NextStep)
        .map(|(action, h)| match action {
            Action::NextStep => {
                let run = app.lesson.as_ref().expect("walking");
                let step = run.at.map_or(0, |i| i + 1);
                hint(h.keys, &format!("step {step}/{}", run.len()), h.priority)
            }
            Action::TogglePlay if app.roll.live.playing => hint(h.keys, "pause", h.priority),
            Action::Batch if app.roll.batch.is_some() => hint(h.keys, "cancel batch", h.priority),
            Action::Batch => hint(
                h.keys,
                &format!("batch {}", group(app.roll.batch_size)),
                h.priority,
            ),
            Action::Twin if app.twin.on => hint(
                &labels(
                    screen,
                    &[
                        Action::Twin,
                        Action::TwinEpsilonDown,
                        Action::TwinEpsilonUp,
                        Action::TwinEpsilonType,
                    ],
                ),
                "twin, ε",
                // While the twin rolls its ε keys matter more than when it is off.
                h.priority.min(2),
            ),
            Action::Confirm if screen == Scope::Save => hint(h.keys, "save", h.priority),
            Action::ExportMap => {
                let ((w, h_px), _) = app.map.png_size();
                let keys = labels(screen, &[Action::ExportMap, Action::MapExportSize]);
                hint(&keys, &format!("PNG {w}×{h_px}"), h.priority)
            }
            _ => hint(h.keys, h.words, h.priority),
        })
        .collect()
}

/// The footer while text is typed: the text mode's rows of the key table, and that every
/// other key is typed (`form`, when given, says what the text should look like).
pub(crate) fn typing_hints(form: Option<&str>) -> Vec<KeyHint> {
    let mut hints: Vec<KeyHint> = form.map(|f| hint(f, "type", 0)).into_iter().collect();
    hints.extend(rows(Scope::Text).filter_map(|b| b.hint.map(|h| hint(h.keys, h.words, h.priority))));
    // Ctrl-C is no row: it quits in every mode, text entry included.
    hints.push(hint(INTERRUPT, "quit", 0));
    if form.is_none() {
        hints.push(hint("other keys", "type", 9));
    }
    hints
}

/// A footer line of hints after any notice (an export's progress first).
pub(crate) fn render_key_hints(app: &App, keys: Vec<KeyHint>, area: Rect, frame: &mut Frame) {
    let notice = app.roll.export_status().or_else(|| app.notice.clone());
    render_line(app, notice, keys, area, frame);
}

/// `notice` in the caution style, then as many hints as fit: on a narrow terminal the
/// highest priority numbers are dropped first, down to [`DROPPED_FROM`], then the words of
/// the rest; priority 0 always stays whole.
fn render_line(app: &App, notice: Option<String>, keys: Vec<KeyHint>, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    // Notices and questions quote names and errors from files: an escape sequence in one
    // is shown, not obeyed (ratatui alone would drop the control character and show the rest).
    let notice = notice.map(|n| format!(" {} ", dicesim_setup::output::printable(&n)));
    let width = |ks: &[KeyHint]| -> usize {
        ks.iter()
            .map(|(k, w, _)| 1 + k.chars().count() + if w.is_empty() { 0 } else { 1 + w.chars().count() })
            .sum::<usize>()
            + notice.as_ref().map_or(0, |n| n.chars().count())
    };
    // Too wide: the hints of priority 3 and up go, least important first; then those of 1
    // and 2 give up their words, least important first, their keys staying in view (a
    // lesson's keys are among them); beside a long notice their keys go too. Priority 0
    // always stays whole.
    let room = crate::tui::vocabulary::fit::room(area.width as usize);
    let mut shown = keys;
    while width(&shown) > room {
        let droppable = shown.iter().enumerate().filter(|(_, e)| e.2 >= DROPPED_FROM);
        if let Some((i, _)) = droppable.max_by_key(|(i, e)| (e.2, *i)) {
            shown.remove(i);
            continue;
        }
        let wordy = shown
            .iter_mut()
            .enumerate()
            .filter(|(_, e)| e.2 > 0 && !e.1.is_empty());
        if let Some((_, e)) = wordy.max_by_key(|(i, e)| (e.2, *i)) {
            e.1.clear();
            continue;
        }
        // A long notice: the keys go too, all but priority 0.
        let Some((i, _)) = shown
            .iter()
            .enumerate()
            .filter(|(_, e)| e.2 > 0)
            .max_by_key(|(i, e)| (e.2, *i))
        else {
            break;
        };
        shown.remove(i);
    }
    let mut spans = Vec::new();
    if let Some(n) = notice {
        spans.push(Span::styled(n, t.caution()));
    }
    for (k, what, _) in shown {
        spans.push(Span::raw(" "));
        spans.push(Span::styled(k, t.key()));
        if !what.is_empty() {
            spans.push(Span::raw(format!(" {what}")));
        }
    }
    let line = crate::tui::vocabulary::fit::abbreviate(Line::from(spans), area.width as usize);
    frame.render_widget(Paragraph::new(line), area);
}

#[cfg(test)]
mod footer_tests;
