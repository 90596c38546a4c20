//! The outcome table: each face's share of the random rolls with its 95 % interval, the
//! fairness test and how many rolls a bias as large as the one measured needs.

use super::app::App;
use super::format::{fmt_num, group, wrap_words};
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, LineGauge, Paragraph};

/// Rolls below which some face's expected count n/6 is under 5, where the χ² test's
/// p-value is not to be trusted.
pub(crate) const RELIABLE_ROLLS: u64 = 30;

/// " n 601  χ² 7.86  p 0.164": the face count and the fairness test, its p-value marked
/// while too few rolls back it and while a batch is still adding rolls.
fn fairness(app: &App) -> Vec<Span<'static>> {
    let t = &app.theme;
    let tally = &app.roll.table.tally;
    let n = tally.total();
    let mut spans = vec![Span::raw(format!(" n {n}"))];
    let end = Span::raw(" ");
    match (tally.chi_square(), tally.p_value()) {
        (Some(_), Some(_)) if n < RELIABLE_ROLLS => {
            spans.push(Span::raw("  p "));
            spans.push(Span::styled(
                format!("unreliable below n {RELIABLE_ROLLS}"),
                t.caution(),
            ));
        }
        (Some(chi2), Some(p)) => {
            spans.push(Span::raw(format!("  χ² {chi2:.2}  p ")));
            if app.roll.batch.is_some() {
                spans.push(Span::raw(format!("{} so far", fmt_num(p))));
            } else {
                let style = if p < 0.01 { t.caution() } else { Style::new() };
                spans.push(Span::styled(fmt_num(p), style));
            }
        }
        _ => spans.push(Span::raw("  χ² –  p –")),
    }
    spans.push(end);
    spans
}

/// Characters of the interval column: " 15.9–17.6".
const INTERVAL_COLUMN: usize = 10;

/// A face's bar over shares 0 to 1/3 in `width` cells: solid (in eighths) up to the low end
/// of its 95 % interval and shaded from there to the high end, so the bar says where the
/// share lies. The fair share's dotted mark stays in view: `┼` inside the shading, `┃`
/// inside the solid part (the whole interval lies above 1/6), `┆` past the bar (below it).
pub(crate) fn share_bar(share: f64, interval: Option<[f64; 2]>, width: usize) -> String {
    let eighths_of = |x: f64| (x * 3.0 * width as f64 * 8.0).round().max(0.0) as usize;
    let [low, high] = interval.map_or([eighths_of(share); 2], |[l, h]| [eighths_of(l), eighths_of(h)]);
    let fair_at = width / 2;
    (0..width)
        .map(|j| {
            let from = j * 8;
            let eighths = low.saturating_sub(from).min(8);
            // A cell the interval reaches at least half way into, that the solid part leaves open.
            let shaded = high >= from + 4 && eighths < 4;
            match eighths {
                _ if shaded && j == fair_at => '┼',
                _ if shaded => '░',
                0 if j == fair_at => '┆',
                0 => ' ',
                _ if j == fair_at => '┃',
                e => [' ', '▏', '▎', '▍', '▌', '▋', '▊', '▉', '█'][e],
            }
        })
        .collect()
}

/// How many rolls a class needs to see the bias the table measures (the χ² test at 5 %
/// with 80 % power), once the table has rolls enough for its p-value to mean something.
fn detection_line(app: &App) -> Option<Line<'static>> {
    let tally = &app.roll.table.tally;
    if tally.total() < RELIABLE_ROLLS {
        return None;
    }
    let text = match tally.rolls_to_detect() {
        Some(n) => format!(" bias this large shows in {} rolls", group(n)),
        None => " no bias beyond chance so far".to_string(),
    };
    Some(Line::styled(text, app.theme.heading()))
}

/// The rolls that ended without a face, as "words count" items (only those that occurred).
fn faceless_items(app: &App) -> Vec<(String, Style)> {
    use crate::experiment::ending::Ending;
    let table = &app.roll.table;
    let mut items = Vec::new();
    let counts = [
        (Ending::WithoutFace, table.without_face, app.theme.caution()),
        (Ending::DidNotSettle, table.did_not_settle, app.theme.caution()),
        (Ending::Unstable, table.unstable, app.theme.danger()),
    ];
    for (ending, n, style) in counts {
        if n > 0 {
            items.push((format!("{} {n}", ending.name()), style));
        }
    }
    items
}

/// The items broken into lines of `width` at spaces, every item whole (a long one wraps
/// onto lines of its own, never cut at the panel's edge).
fn item_lines(items: &[(String, Style)], width: usize) -> Vec<Line<'static>> {
    let mut lines: Vec<Line<'static>> = Vec::new();
    let mut used = usize::MAX;
    for (text, style) in items {
        let len = text.chars().count() + 1;
        if used != usize::MAX && used + 2 + len <= width {
            let line = lines.last_mut().expect("a line");
            line.spans.push(Span::raw(" ·"));
            line.spans.push(Span::styled(format!(" {text}"), *style));
            used += 2 + len;
            continue;
        }
        for part in wrap_words(text, width.saturating_sub(1).max(1)) {
            used = part.chars().count() + 1;
            lines.push(Line::from(Span::styled(format!(" {part}"), *style)));
        }
    }
    lines
}

pub(crate) fn render_outcomes(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let table = &app.roll.table;
    let mut title = vec![Span::styled(" outcomes of random rolls ", t.heading())];
    if let Some(b) = app.roll.batch {
        title.push(Span::styled(
            format!("batch {}/{} ", b.done, b.total),
            t.caution(),
        ));
    }
    let mut block = Block::bordered().title(Line::from(title));
    let body = block.inner(area);
    if body.height == 0 || body.width < 20 {
        frame.render_widget(block, area);
        return;
    }
    let width = body.width as usize;
    let faceless = item_lines(&faceless_items(app), width);
    // The six faces and every other ending always show; the heading row gives way first,
    // then the fairness line moves into the bottom border.
    let needed = 6 + faceless.len() as u16;
    let header = needed + 2 <= body.height;
    let fairness_inside = needed < body.height;
    if !fairness_inside {
        block = block.title_bottom(Line::from(fairness(app)));
    }
    frame.render_widget(block, area);
    let n = table.tally.total();
    let intervals = table.tally.share_intervals();
    // The interval's figures take a column of their own where the bar keeps room enough;
    // the bar always shows it, shaded.
    let numbers = width >= 21 + INTERVAL_COLUMN + 16;
    let bar_width = width
        .saturating_sub(21 + if numbers { INTERVAL_COLUMN } else { 0 })
        .max(2);
    let fair_at = bar_width / 2;
    let mut lines = Vec::new();
    if header {
        // The bar spans 0 to 1/3, so a fair face reaches the dotted mark in the middle.
        let column = if numbers { " 95 % int." } else { "" };
        let mark = format!("{}┆ 1/6 fair", " ".repeat(fair_at));
        lines.push(Line::from(vec![
            Span::styled(format!(" face  count  share{column}"), t.heading()),
            Span::raw(mark),
        ]));
    }
    for face in 1..=6u8 {
        let count = table.tally.counts[face as usize - 1];
        let share = table.tally.share(face);
        let interval = (n > 0).then_some(intervals[face as usize - 1]);
        let bar = share_bar(share, interval, bar_width);
        let over = if share * 3.0 > 1.0 { "▸" } else { "" };
        let share_text = if n > 0 {
            format!("{:5.1}%", 100.0 * share)
        } else {
            "     –".to_string()
        };
        let interval_text = match interval {
            _ if !numbers => String::new(),
            Some([low, high]) => format!(" {:>4.1}–{:<4.1}", 100.0 * low, 100.0 * high),
            None => " ".repeat(INTERVAL_COLUMN),
        };
        let newest = table.last.front().and_then(|r| r.outcome.face) == Some(face);
        let face_style = if newest { t.selected() } else { Style::new() };
        lines.push(Line::from(vec![
            Span::styled(format!("  {face}  "), face_style),
            Span::raw(format!("{count:>6} {share_text}{interval_text} ")),
            Span::styled(bar, t.bar()),
            Span::styled(over, t.bar()),
        ]));
    }
    if fairness_inside {
        lines.push(Line::from(fairness(app)));
    }
    lines.extend(faceless);
    let mut rest = body.height.saturating_sub(lines.len() as u16);
    let text_area = Rect {
        height: body.height.min(lines.len() as u16),
        ..body
    };
    frame.render_widget(Paragraph::new(lines), text_area);
    let mut y = text_area.bottom();
    if rest > 0
        && let Some(line) = detection_line(app)
    {
        frame.render_widget(Paragraph::new(line), Rect { y, height: 1, ..body });
        y += 1;
        rest -= 1;
    }
    if let Some(b) = app.roll.batch
        && rest > 0
    {
        let ratio = if b.total > 0 {
            b.done as f64 / b.total as f64
        } else {
            0.0
        };
        let gauge = LineGauge::default()
            .ratio(ratio.clamp(0.0, 1.0))
            .label(format!(" batch {:>3.0}% ", 100.0 * ratio))
            .filled_style(t.bar().add_modifier(Modifier::BOLD));
        frame.render_widget(gauge, Rect { y, height: 1, ..body });
        y += 1;
        rest -= 1;
    }
    if rest > 1 && !table.last.is_empty() {
        let mut last = vec![Line::styled(
            " last rolls: spin ω (rad/s) → ending, steps",
            t.heading(),
        )];
        for r in table.last.iter().take(rest as usize - 1) {
            let w = r.initial.angular_velocity;
            let end = crate::experiment::ending::Ending::of(&r.outcome).words();
            last.push(Line::from(format!(
                " #{:<5} ({:>4.0},{:>4.0},{:>4.0}) → {end} {:>6}",
                r.id, w[0], w[1], w[2], r.outcome.steps
            )));
        }
        frame.render_widget(
            Paragraph::new(last),
            Rect {
                y,
                height: rest,
                ..body
            },
        );
    }
}
