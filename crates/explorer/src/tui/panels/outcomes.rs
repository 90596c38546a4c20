//! The outcome table: each face's share of the random rolls with its 95 % interval, the
//! fairness test and how many rolls a bias as large as the one measured needs.

use crate::tui::state::app::App;
use crate::tui::vocabulary::fit;
use crate::tui::vocabulary::format::{face_text, fmt_num, group};
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, LineGauge, Paragraph};

/// Rolls below which some face's expected count n/6 is under 5, where the χ² test's
/// p-value is not to be trusted.
pub(crate) const RELIABLE_ROLLS: u64 = 30;

/// " n 601  χ² 7.86  p 0.164": the face count and the fairness test, its p-value marked
/// while too few rolls back it and while a batch is still adding rolls; the parts ranked
/// for a narrow panel (the χ² value goes before the count and the p-value).
fn fairness(app: &App, width: usize) -> Line<'static> {
    let t = &app.theme;
    let tally = &app.roll.table.tally;
    let n = tally.total();
    let mut parts = vec![(0, vec![Span::raw(format!(" n {n}"))])];
    match (tally.chi_square(), tally.p_value()) {
        (Some(_), Some(_)) if n < RELIABLE_ROLLS => {
            parts.push((
                0,
                vec![
                    Span::raw("  p "),
                    Span::styled(format!("unreliable below n {RELIABLE_ROLLS}"), t.caution()),
                ],
            ));
        }
        (Some(chi2), Some(p)) => {
            parts.push((1, vec![Span::raw(format!("  χ² {chi2:.2}"))]));
            let style = if p < 0.01 && app.roll.batch.is_none() {
                t.caution()
            } else {
                Style::new()
            };
            parts.push((0, vec![Span::raw("  p "), Span::styled(fmt_num(p), style)]));
            if app.roll.batch.is_some() {
                parts.push((0, vec![Span::raw(" so far")]));
            }
        }
        _ => parts.push((1, vec![Span::raw("  χ² –  p –")])),
    }
    parts.push((0, vec![Span::raw(" ")]));
    fit::line(parts, width)
}

/// Characters of the interval column: " 15.9–17.6".
const INTERVAL_COLUMN: usize = 10;

/// The shares the bars of a six-faced die may start at, largest first: round percentages,
/// so the heading can name where the bar begins. A bar always ends as far above the fair
/// share as it begins below it; a die of `N` faces starts its bars at these times 6/N.
const BAR_STARTS: [f64; 6] = [0.15, 0.14, 0.12, 0.10, 0.05, 0.0];

/// The share the bars start at, `fair` the fair share 1/N: the largest of [`BAR_STARTS`]
/// (times 6/N) whose bar, from there to as far above the fair share, holds every face's 95 %
/// interval. Once a batch has narrowed the intervals the bars spread out around the fair
/// share, so a bias of a few percent is cells long, not one; with few rolls (or none) they
/// span 0 to twice the fair share.
pub(crate) fn bar_start(intervals: Option<Vec<[f64; 2]>>, fair: f64) -> f64 {
    let Some(intervals) = intervals else { return 0.0 };
    // 6/N from the fair share as 1/N was computed: exactly 1 for the six-faced die.
    let scale = 6.0 * fair;
    let scale = if (scale - 1.0).abs() < 1e-12 { 1.0 } else { scale };
    BAR_STARTS
        .into_iter()
        .map(|from| from * scale)
        .find(|&from| {
            intervals
                .iter()
                .all(|&[l, h]| l >= from && h <= 2.0 * fair - from)
        })
        .unwrap_or(0.0)
}

/// The fair share of a die showing `faces` numbers: 1/N.
pub(crate) fn fair_share(faces: usize) -> f64 {
    1.0 / faces.max(1) as f64
}

/// A face's bar over shares `from` to `2·fair − from` in `width` cells, the fair share in the middle:
/// solid (in eighths) up to the low end of its 95 % interval and shaded from there to the
/// high end, so the bar says where the share lies. The fair share's dotted mark stays in
/// view where the bar leaves it open: `┼` inside the shading, `┆` past the bar (the whole
/// interval lies below 1/6); where the whole interval lies above 1/6 the solid bar runs
/// through the mark, so above and below read apart from the back of a room. The mark is
/// read from the interval itself, not from the cells: on a narrow bar a tight interval
/// around 1/6 may fill too little of a cell to shade it, and must still read fair.
pub(crate) fn share_bar(
    share: f64,
    interval: Option<[f64; 2]>,
    width: usize,
    from: f64,
    fair: f64,
) -> String {
    let span = 2.0 * fair - 2.0 * from;
    let eighths_of = |x: f64| ((x - from) / span * width as f64 * 8.0).round().max(0.0) as usize;
    let [low, high] = interval.map_or([eighths_of(share); 2], |[l, h]| [eighths_of(l), eighths_of(h)]);
    let fair_at = width / 2;
    let fair_mark = interval.map(|[l, h]| match () {
        _ if h < fair => '┆',
        _ if l > fair => '█',
        _ => '┼',
    });
    (0..width)
        .map(|j| {
            let from = j * 8;
            let eighths = low.saturating_sub(from).min(8);
            // A cell the interval reaches at least half way into, that the solid part leaves open.
            let shaded = high >= from + 4 && eighths < 4;
            if j == fair_at
                && let Some(mark) = fair_mark
            {
                return mark;
            }
            match eighths {
                _ if shaded && j == fair_at => '┼',
                _ if shaded => '░',
                0 if j == fair_at => '┆',
                0 => ' ',
                _ if j == fair_at => '█',
                e => [' ', '▏', '▎', '▍', '▌', '▋', '▊', '▉', '█'][e],
            }
        })
        .collect()
}

/// The significance below which the table calls a bias shown (the χ² test's level).
const SIGNIFICANT: f64 = 0.05;

/// How many rolls a class needs to see the bias the table measures (the χ² test at 5 %
/// with 80 % power), once the table has rolls enough for its p-value to mean something
/// and only while the bias is significant: a fair die's chance wobble has no such number.
fn detection_lines(app: &App, width: usize) -> Vec<Line<'static>> {
    let tally = &app.roll.table.tally;
    if tally.total() < RELIABLE_ROLLS {
        return Vec::new();
    }
    let significant = tally.p_value().is_some_and(|p| p < SIGNIFICANT);
    let text = match tally.rolls_to_detect() {
        Some(n) if significant => format!("bias this large shows in {} rolls", group(n)),
        _ => "no bias beyond chance so far".to_string(),
    };
    fit::wrap(&text, width.saturating_sub(1))
        .into_iter()
        .map(|l| Line::styled(format!(" {l}"), app.theme.heading()))
        .collect()
}

/// The rolls that ended without a face, as "words count" items (only those that occurred).
fn faceless_items(app: &App) -> Vec<(String, Style)> {
    use dicesim_experiment::ending::Ending;
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
        for part in fit::wrap(text, width.saturating_sub(1).max(2)) {
            used = part.chars().count() + 1;
            lines.push(Line::from(Span::styled(format!(" {part}"), *style)));
        }
    }
    lines
}

/// A row of the table's body: text, or the batch's progress gauge.
#[derive(Clone)]
enum TableRow {
    Text(Line<'static>),
    Fairness,
    Gauge(f64),
}

/// Characters of the columns before the bar: the face, the count, the share.
const FACE_COLUMN: usize = 5;
const COUNT_COLUMN: usize = 7;
const SHARE_COLUMN: usize = 6;
/// The fewest cells a face's bar is drawn in.
const MIN_BAR: usize = 8;

/// The columns of a table `room` wide: by importance the interval's figures, then the count
/// (n is in the fairness line), then the bar takes what is left.
#[derive(Debug, Clone, Copy)]
struct Columns {
    numbers: bool,
    count_shown: bool,
    bar_width: usize,
    /// The share the bars start at ([`bar_start`]).
    from: f64,
    /// Too narrow for the face and share columns with a bar (a d20's faces three abreast
    /// at 80×24): the face in two characters, the share in percent without its sign (the
    /// heading carries it), then the bar.
    compact: bool,
}

/// Characters of a compact row before its bar: `20 5.1 `.
const COMPACT_FIXED: usize = 8;

impl Columns {
    fn fitting(room: usize, from: f64) -> Columns {
        let fixed = FACE_COLUMN + SHARE_COLUMN + 2;
        if room < fixed + 3 {
            return Columns {
                numbers: false,
                count_shown: false,
                bar_width: room.saturating_sub(COMPACT_FIXED).max(2),
                from,
                compact: true,
            };
        }
        let numbers = room >= fixed + INTERVAL_COLUMN + MIN_BAR;
        let count_shown = room >= fixed + COUNT_COLUMN + INTERVAL_COLUMN * usize::from(numbers) + MIN_BAR;
        let bar_width = room
            .saturating_sub(fixed)
            .saturating_sub(if numbers { INTERVAL_COLUMN } else { 0 })
            .saturating_sub(if count_shown { COUNT_COLUMN } else { 0 })
            .max(2);
        Columns {
            numbers,
            count_shown,
            bar_width,
            from,
            compact: false,
        }
    }
}

/// The panel's title, with the batch's progress while one runs.
fn title(app: &App, inside: usize) -> Line<'static> {
    let t = &app.theme;
    // The batch's progress matters more than the panel's name while it runs.
    match app.roll.batch {
        Some(b) => {
            let progress = format!("batch {}/{} ", b.done, b.total);
            let name = [" outcomes of random rolls ", " outcomes · ", " "]
                .into_iter()
                .find(|n| n.chars().count() + progress.chars().count() <= fit::room(inside))
                .unwrap_or(" ");
            Line::from(vec![
                Span::styled(name, t.heading()),
                Span::styled(progress, t.caution()),
            ])
        }
        None => Line::styled(" outcomes of random rolls ", t.heading()),
    }
}

/// The heading row over the columns, with the fair share's mark over the bars.
fn heading(app: &App, room: usize, c: Columns) -> TableRow {
    let t = &app.theme;
    let Columns {
        numbers,
        count_shown,
        bar_width,
        from,
        compact,
    } = c;
    let fair_at = bar_width / 2;
    let faces = app.roll.table.tally.numbers().len();
    if compact {
        // The share's unit over its figures, the fair mark over the bars' middle.
        let pad = " ".repeat(fair_at);
        return TableRow::Text(Line::from(vec![
            Span::styled("      %", t.heading()),
            Span::raw(format!(" {pad}┆")),
        ]));
    }
    // The bar spans `from` to 2/N − `from`, so a fair face reaches the dotted mark in the middle.
    let mut head = " face".to_string();
    if count_shown {
        head.push_str("  count");
    }
    // "share" takes the bar's leading space, so each heading ends over its figures' column.
    head.push_str("  share");
    if numbers {
        head.push_str(" 95 % int.");
    }
    // Where the bars start, over their first cell, once they no longer start at 0.
    let percent = 100.0 * from;
    let percent = if (percent - percent.round()).abs() < 1e-9 {
        format!("{percent:.0}")
    } else {
        format!("{percent:.1}")
    };
    let start = [format!(" {percent} %"), format!(" {percent}%")]
        .into_iter()
        .find(|l| from > 0.0 && l.chars().count() < fair_at)
        .unwrap_or_default();
    let mark_room = room.saturating_sub(head.chars().count() + fair_at);
    let mark = [
        format!("┆ 1/{faces} fair"),
        format!("┆ 1/{faces}"),
        "┆".to_string(),
    ]
    .into_iter()
    .find(|m| m.chars().count() <= mark_room)
    .unwrap_or_default();
    // The heading names the interval column; the fairness line can move to the border.
    TableRow::Text(Line::from(vec![
        Span::styled(head, t.heading()),
        Span::raw(format!("{start:<fair_at$}{mark}")),
    ]))
}

/// The row of `face`, the `k`th number of the die's list: its count, share, interval and bar.
fn face_row(app: &App, (k, face): (usize, u8), c: Columns) -> TableRow {
    let t = &app.theme;
    let table = &app.roll.table;
    let n = table.tally.total();
    let intervals = table.tally.share_intervals();
    let Columns {
        numbers,
        count_shown,
        bar_width,
        from,
        compact,
    } = c;
    let count = table.tally.counts[k];
    let share = table.tally.share(face);
    let interval = (n > 0).then_some(intervals[k]);
    let fair = fair_share(table.tally.numbers().len());
    let bar = share_bar(share, interval, bar_width, from, fair);
    let over = if share > 2.0 * fair - from { "▸" } else { "" };
    let share_text = if n > 0 {
        format!("{:5.1}%", 100.0 * share)
    } else {
        "     –".to_string()
    };
    let count_text = if count_shown {
        format!("{count:>6} ")
    } else {
        String::new()
    };
    let interval_text = match interval {
        _ if !numbers => String::new(),
        Some([low, high]) => format!(" {:>4.1}–{:<4.1}", 100.0 * low, 100.0 * high),
        None => " ".repeat(INTERVAL_COLUMN),
    };
    let face_text = face_text(app.roll.live.params.die.kind, face.into());
    let newest = table.last.front().and_then(|r| r.outcome.face) == Some(face);
    let face_style = if newest { t.selected() } else { Style::new() };
    if compact {
        let share_text = if n > 0 {
            format!("{:4.1}", 100.0 * share)
        } else {
            "   –".to_string()
        };
        return TableRow::Text(Line::from(vec![
            Span::styled(format!("{face_text:>2}"), face_style),
            Span::raw(format!(" {share_text} ")),
            Span::styled(bar, t.bar()),
            Span::styled(over, t.bar()),
        ]));
    }
    TableRow::Text(Line::from(vec![
        Span::styled(format!(" {face_text:>2}  "), face_style),
        Span::raw(format!("{count_text}{share_text}{interval_text} ")),
        Span::styled(bar, t.bar()),
        Span::styled(over, t.bar()),
    ]))
}

/// The last rolls, under their heading.
fn last_rows(app: &App, width: usize) -> Vec<(u8, TableRow)> {
    let t = &app.theme;
    let table = &app.roll.table;
    let mut out = Vec::new();
    if !table.last.is_empty() {
        out.push((
            3,
            TableRow::Text(fit::abbreviate(
                Line::styled(" last: spin ω (rad/s) → ending, steps, impacts", t.heading()),
                width,
            )),
        ));
        for r in &table.last {
            let w = r.initial.angular_velocity;
            let end = dicesim_experiment::ending::Ending::of(&r.outcome).words();
            let line = Line::from(format!(
                " #{:<5} ({:>4.0},{:>4.0},{:>4.0}) → {end} {:>6} {:>3}×",
                r.id, w[0], w[1], w[2], r.outcome.steps, r.outcome.impacts
            ));
            out.push((4, TableRow::Text(fit::abbreviate(line, width))));
        }
    }
    out
}

/// Draws the rows that fit, one per line of `body`.
fn draw_rows(app: &App, rows: Vec<TableRow>, body: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let width = body.width as usize;
    let room = fit::room(width);
    for (row, y) in rows.into_iter().zip(body.y..) {
        let at = Rect { y, height: 1, ..body };
        match row {
            TableRow::Text(line) => frame.render_widget(Paragraph::new(line), at),
            TableRow::Fairness => frame.render_widget(Paragraph::new(fairness(app, width)), at),
            TableRow::Gauge(ratio) => {
                let gauge = LineGauge::default()
                    .ratio(ratio)
                    .label(format!(" batch {:>3.0}% ", 100.0 * ratio))
                    .filled_style(t.bar().add_modifier(Modifier::BOLD));
                let at = Rect {
                    width: room as u16,
                    ..at
                };
                frame.render_widget(gauge, at);
            }
        }
    }
}

/// The least room a column of faces takes beside another: a compact row with a bar of two.
const MIN_FACE_CELL: usize = COMPACT_FIXED + 2;

/// How many columns the faces of a die of `faces` numbers take in a table of `rows` rows
/// and `room` characters: one while they fit under the heading (the six-faced die always
/// at 80×24); else the fewest that fit under the heading with room for a bar in each, or
/// failing that the fewest that fit without it (a d20 at 80×24: two of ten, the heading and
/// the fairness line giving way to the faces, the fairness line into the border).
fn face_columns(faces: usize, rows: usize, room: usize) -> usize {
    let fits = |across: usize, heading: usize| {
        faces.div_ceil(across) + heading <= rows && (across == 1 || room / across > MIN_FACE_CELL)
    };
    (1..=4)
        .find(|&across| fits(across, 1))
        .or_else(|| (2..=4).find(|&across| fits(across, 0)))
        .unwrap_or(4)
}

/// Rows of the table set side by side, each padded to `width` characters but the last.
fn side_by_side(cells: impl Iterator<Item = TableRow>, width: usize) -> TableRow {
    let mut spans: Vec<Span<'static>> = Vec::new();
    let mut used = 0;
    for (i, cell) in cells.enumerate() {
        let TableRow::Text(line) = cell else { continue };
        if i > 0 {
            spans.push(Span::raw(" ".repeat((i * width).saturating_sub(used))));
            used = i * width;
        }
        used += line.width();
        spans.extend(line.spans);
    }
    TableRow::Text(Line::from(spans))
}

/// The outcome table: each face's count, share, 95 % interval and bar, the fairness test,
/// the rolls without a face, a batch's progress and the last rolls.
pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
    let inside = area.width.saturating_sub(2) as usize;
    let mut block = Block::bordered().title(fit::abbreviate(title(app, inside), inside));
    let body = block.inner(area);
    if body.height == 0 || body.width < 20 {
        frame.render_widget(block, area);
        return;
    }
    let width = body.width as usize;
    let tally = &app.roll.table.tally;
    let faces = tally.numbers();
    let from = bar_start(
        (tally.total() > 0).then(|| tally.share_intervals()),
        fair_share(faces.len()),
    );
    let room = fit::room(width);
    let across = face_columns(faces.len(), body.height as usize, room);
    let column_room = if across == 1 { room } else { room / across - 1 };
    let columns = Columns::fitting(column_room, from);
    let mut rows: Vec<(u8, TableRow)> = Vec::new();
    // The heading names the interval column; the fairness line can move to the border.
    let heading_row = heading(app, column_room, columns);
    let faces_down = faces.len().div_ceil(across);
    let rows_of_faces: Vec<TableRow> = (0..faces_down)
        .map(|row| {
            // Faces run down the first column, then the next: 1 to 10 beside 11 to 20.
            let cells = (0..across)
                .map(|column| column * faces_down + row)
                .filter(|&k| k < faces.len())
                .map(|k| face_row(app, (k, faces[k]), columns));
            side_by_side(cells, column_room + 1)
        })
        .collect();
    rows.push((
        1,
        side_by_side(std::iter::repeat_n(heading_row, across), column_room + 1),
    ));
    rows.extend(rows_of_faces.into_iter().map(|r| (0, r)));
    rows.push((2, TableRow::Fairness));
    for line in item_lines(&faceless_items(app), width) {
        rows.push((0, TableRow::Text(line)));
    }
    for line in detection_lines(app, width) {
        rows.push((0, TableRow::Text(line)));
    }
    if let Some(b) = app.roll.batch {
        let ratio = if b.total > 0 {
            b.done as f64 / b.total as f64
        } else {
            0.0
        };
        rows.push((1, TableRow::Gauge(ratio.clamp(0.0, 1.0))));
    }
    rows.extend(last_rows(app, width));
    let rows = fit::rows(rows, body.height as usize);
    // The fairness line that has no row of its own goes into the bottom border.
    if !rows.iter().any(|r| matches!(r, TableRow::Fairness)) {
        block = block.title_bottom(fairness(app, inside));
    }
    frame.render_widget(block, area);
    draw_rows(app, rows, body, frame);
}

#[cfg(test)]
mod outcomes_tests;
