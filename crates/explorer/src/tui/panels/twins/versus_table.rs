//! The parameter twin (`D`, "differ") on screen: both dice's outcomes and what die B
//! differs by, for the die panel's title, and the table of their shared throws in the
//! outcome table's place.

use crate::tui::state::app::App;
use crate::tui::state::twins::differs_text;
use crate::tui::vocabulary::fit::wrap;
use crate::tui::vocabulary::key_table::{Action, Scope, label};
use crate::worker::Phase;
use dicesim_experiment::versus::{ENDINGS, NO_FACE};
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph};

/// A die's outcome in words: `face 3` once decided (`no face` if it ended on none),
/// `face up 3` while it rolls; `compact`: the number alone (`—` for no face).
fn face_text(phase: &Phase, face_up: u8, compact: bool) -> String {
    match (phase, compact) {
        (Phase::Ended(o), false) => o.face.map_or("no face".to_string(), |f| format!("face {f}")),
        (Phase::Ended(o), true) => o.face.map_or("—".to_string(), |f| f.to_string()),
        (_, false) => format!("face up {face_up}"),
        (_, true) => face_up.to_string(),
    }
}

/// Both outcomes, `A face 3 · B face 5` (`compact`: `A 3 · B 5`), and what B differs by,
/// while a parameter twin rolls.
pub(crate) fn outcomes_text(app: &App, compact: bool) -> Option<(String, String)> {
    let twin = app.roll.live.twin.as_ref().filter(|t| !t.differs_by.is_empty())?;
    let live = &app.roll.live;
    Some((
        format!(
            "A {} · B {}",
            face_text(&live.phase, live.die.face_up, compact),
            face_text(&twin.phase, twin.die.face_up, compact)
        ),
        format!("B: {}", differs_text(&twin.differs_by)),
    ))
}

/// The parameter twin's shared throws in the outcome table's place: A's ending (rows)
/// against B's (columns), faces 1–6 then no face (`—`), and the share that agree with its
/// 95 % interval. The worker's batches (`b`) fill it, each throw rolled in both setups.
pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let mut title = vec![Span::styled(" A face ↓ against B face → ", t.heading())];
    if let Some(b) = app.roll.batch {
        title.push(Span::styled(
            format!("batch {}/{} ", b.done, b.total),
            t.caution(),
        ));
    }
    let mut block = Block::bordered().title(Line::from(title));
    let body = block.inner(area);
    let Some(table) = app.roll.live.versus else {
        frame.render_widget(block, area);
        let key = label(Scope::Die, Action::Batch);
        let words = format!("{key}: a batch of shared throws, each rolled in A and in B");
        let lines: Vec<Line> = wrap(&words, body.width as usize)
            .into_iter()
            .map(Line::raw)
            .collect();
        frame.render_widget(Paragraph::new(lines), body);
        return;
    };
    let column = ((body.width as usize).saturating_sub(3) / ENDINGS).clamp(3, 8);
    let name = |i: usize| {
        if i == NO_FACE {
            "—".to_string()
        } else {
            (i + 1).to_string()
        }
    };
    let mut lines = vec![Line::styled(
        format!(
            "   {}",
            (0..ENDINGS)
                .map(|b| format!("{:>column$}", name(b)))
                .collect::<String>()
        ),
        t.heading(),
    )];
    for (a, row) in table.counts.iter().enumerate() {
        let mut spans = vec![Span::styled(format!("{:>2} ", name(a)), t.heading())];
        for (b, n) in row.iter().enumerate() {
            let text = format!("{n:>column$}");
            spans.push(if a == b && a != NO_FACE {
                Span::styled(text, t.good())
            } else {
                Span::raw(text)
            });
        }
        lines.push(Line::from(spans));
    }
    let agreement = Line::raw(match table.agreement() {
        Some((share, [lo, hi])) => {
            let (k, n) = (table.agreeing(), table.faced());
            let (share, lo, hi) = (100.0 * share, 100.0 * lo, 100.0 * hi);
            crate::tui::vocabulary::fit::longest_fitting(
                &[
                    format!("agree {k}/{n} = {share:.1} % (95 % {lo:.1}–{hi:.1} %)"),
                    format!("agree {k}/{n} · {share:.1} % ({lo:.1}–{hi:.1} %)"),
                    format!("agree {share:.1} % ({lo:.1}–{hi:.1} %) of {n}"),
                ],
                body.width as usize,
            )
        }
        None => "agree: no throw ended on a face in both yet".to_string(),
    });
    // Short of a row, the share that agree moves into the bottom border.
    if lines.len() < body.height as usize {
        lines.push(agreement);
    } else {
        block = block.title_bottom(agreement);
    }
    frame.render_widget(block, area);
    frame.render_widget(Paragraph::new(lines), body);
}

#[cfg(test)]
mod versus_table_tests;
