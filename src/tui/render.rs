//! Drawing: `render(&App, &mut Frame)` is a pure function of the app state. It never steps
//! the physics and never reads a clock.

use super::app::{App, Drawing};
use super::die::render_die;
use super::footer::{render_footer, render_help};
use super::format::{fmt_num, fmt_range, group, wrap_words};
use super::header::{render_header, render_too_small};
use super::layout::{param_window, screen_layout};
use super::param::all;
use crate::physics::Stability;
use crate::worker::EnergySample;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, LineGauge, Paragraph};

/// Share of the tightest stability limit from which the step is worth watching; past the
/// limit itself (1) a roll is predicted unstable (docs/model.md, "Stability").
pub(crate) const STABILITY_CAUTION: f64 = 0.8;
pub(crate) const STABILITY_DANGER: f64 = 1.0;

/// Draws the whole screen, then paints the theme over every cell of it, whichever screen.
pub fn render(app: &App, frame: &mut Frame) {
    if app.view == super::map::View::Map {
        super::map::render_map_screen(app, frame);
    } else {
        render_die_screen(app, frame);
    }
    app.theme.paint(frame.buffer_mut());
}

fn render_die_screen(app: &App, frame: &mut Frame) {
    let area = frame.area();
    let Some(areas) = screen_layout(area) else {
        render_too_small(area, frame);
        return;
    };
    render_header(app, areas.header, frame);
    render_params(app, areas.params, frame);
    render_die(app, areas.die, frame);
    super::timeline::render(app, areas.timeline, frame);
    // While a twin rolls, its predictability curve takes the outcome table's place and
    // the separation of the two dice the energy plot's.
    if app.live.twin.is_some() {
        super::curve::render_curve(app, areas.outcomes, frame);
        super::twin::render_separation(app, areas.energy, frame);
    } else {
        render_outcomes(app, areas.outcomes, frame);
        render_energy(app, areas.energy, frame);
    }
    super::ledger::render_ledger(app, areas.ledger, frame);
    render_footer(app, areas.footer, frame);
    if app.help_scroll().is_some() {
        render_help(app, area, frame);
    }
    super::dialogs::render(app, area, frame);
}

fn stability_style(app: &App, load: f64) -> Style {
    if load > STABILITY_DANGER || load.is_nan() {
        app.theme.danger()
    } else if load >= STABILITY_CAUTION {
        app.theme.caution()
    } else {
        Style::new()
    }
}

/// The one stability readout: the tightest of the predictor's limits for the setup on the
/// list, as a share of that limit, e.g. "Δt stability: table stiffness at 44 % of limit".
pub(crate) fn stability_readout(app: &App, width: u16) -> Line<'static> {
    let reading = Stability::predict(&app.params, &app.initial).verdict();
    let load = reading.load();
    let percent = if load.is_finite() {
        format!("{:.0} %", 100.0 * load)
    } else {
        "∞".to_string()
    };
    let name = reading.limit.name();
    let text = [
        format!(" Δt stability: {name} at {percent} of limit "),
        format!(" Δt: {name} at {percent} of limit "),
        format!(" Δt: {name} {percent} of limit "),
    ]
    .into_iter()
    .find(|t| t.chars().count() <= width as usize)
    .unwrap_or_else(|| format!(" Δt: {name} {percent} "));
    Line::styled(text, stability_style(app, load))
}

pub(crate) fn render_params(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let (first, visible) = param_window(app.selected, area);
    // Rows scrolled out of view, above and below: ↑↓ (or a click and the wheel) reach them.
    let below = all().len().saturating_sub(first + visible);
    let mut title = vec![Span::styled(" parameters ", t.heading())];
    if first > 0 {
        title.push(Span::raw(format!("↑{first} ")));
    }
    if below > 0 {
        title.push(Span::raw(format!("↓{below} more ")));
    }
    let block = Block::bordered()
        .title(Line::from(title))
        .title_bottom(stability_readout(app, area.width.saturating_sub(2)));
    let body = block.inner(area);
    frame.render_widget(block, area);
    if body.height == 0 {
        return;
    }
    let wide = body.width >= 49;
    let mut lines = Vec::with_capacity(body.height as usize);
    let mut head = format!(" {:<13} {:>8} {:<6}", "parameter", "value", "unit");
    if wide {
        head.push_str(&format!(" {:<11}", "range"));
    }
    lines.push(Line::styled(head, t.heading()));
    for (i, &p) in all().iter().enumerate().skip(first).take(visible) {
        let value = fmt_num(p.get(&app.params, &app.initial));
        let mut spans = vec![Span::raw(format!(
            "{}{:<13} {:>8} {:<6}",
            if i == app.selected { "▶" } else { " " },
            p.label(),
            value,
            p.limits().unit
        ))];
        if wide {
            spans.push(Span::raw(format!(" {:<11}", fmt_range(p))));
        }
        let mut line = Line::from(spans);
        if i == app.selected {
            line = line.style(t.selected());
        }
        lines.push(line);
    }
    let p = app.selected_param();
    let detail = match app.value_editor() {
        Some(editor) => match &editor.error {
            Some(e) => Line::styled(format!(" {e}"), t.danger()),
            None => Line::from(vec![
                Span::styled(format!(" {} = ", p.label()), t.heading()),
                Span::styled(format!("{}▏", editor.text), t.selected()),
                Span::raw(format!("  {} {}", fmt_range(p), p.limits().unit)),
            ]),
        },
        None => {
            let when = if p.acts_mid_roll() {
                "acts now"
            } else {
                "restarts the roll"
            };
            let mut s = vec![Span::raw(format!(" {} ", p.key()))];
            if !wide {
                s.push(Span::raw(format!("{} ", fmt_range(p))));
            }
            s.push(Span::raw(format!("· {when}")));
            Line::from(s)
        }
    };
    let rows_area = Rect {
        height: body.height.saturating_sub(1),
        ..body
    };
    frame.render_widget(Paragraph::new(lines), rows_area);
    if body.height >= 2 {
        let detail_area = Rect {
            y: body.bottom() - 1,
            height: 1,
            ..body
        };
        frame.render_widget(Paragraph::new(detail), detail_area);
    }
}

/// Rolls below which some face's expected count n/6 is under 5, where the χ² test's
/// p-value is not to be trusted.
pub(crate) const RELIABLE_ROLLS: u64 = 30;

/// " n 601  χ² 7.86  p 0.164": the face count and the fairness test, its p-value marked
/// while too few rolls back it and while a batch is still adding rolls.
fn fairness(app: &App) -> Vec<Span<'static>> {
    let t = &app.theme;
    let tally = &app.table.tally;
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
            if app.batch.is_some() {
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
    let tally = &app.table.tally;
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
    let table = &app.table;
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
    let table = &app.table;
    let mut title = vec![Span::styled(" outcomes of random rolls ", t.heading())];
    if let Some(b) = app.batch {
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
    if let Some(b) = app.batch
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

/// Each series thinned to at most two points (its low and its high) per bucket, so a frame
/// costs the same for any roll length and impact spikes stay visible.
fn thinned(
    history: &[EnergySample],
    buckets: usize,
    value: impl Fn(&EnergySample) -> f64,
) -> Vec<(f64, f64)> {
    let n = history.len();
    if n <= 2 * buckets.max(1) {
        return history.iter().map(|s| (s.time_s, value(s))).collect();
    }
    let mut out = Vec::with_capacity(2 * buckets);
    for b in 0..buckets {
        let slice = &history[b * n / buckets..((b + 1) * n / buckets).max(b * n / buckets + 1).min(n)];
        let (mut lo, mut hi) = (slice[0], slice[0]);
        for s in slice {
            if value(s) < value(&lo) {
                lo = *s;
            }
            if value(s) > value(&hi) {
                hi = *s;
            }
        }
        let (first, second) = if lo.time_s <= hi.time_s {
            (lo, hi)
        } else {
            (hi, lo)
        };
        out.push((first.time_s, value(&first)));
        out.push((second.time_s, value(&second)));
    }
    out
}

/// Short names of the energy terms: total, translational, rotational, gravitational, elastic
/// (the order of [`super::theme::Theme::energy_series`], and the ledger's words).
const LEGEND: [&str; 5] = ["total", "transl", "rot", "grav", "elastic"];

/// Without colour each line is drawn with its own character, so the five stay apart.
const PATTERNS: [char; 5] = ['#', '+', 'x', 'o', '*'];

/// One energy term of a sample, erg.
type Term = fn(&EnergySample) -> f64;

/// erg: the floor of the log plot (energies below, including negative gravity, sit on it).
const LOG_FLOOR: f64 = 1.0;

/// The energy plot's legend: each term's line sample and name, then the stop threshold's.
fn energy_legend(app: &App) -> Vec<Span<'static>> {
    let colours = app.theme.energy_series();
    let mut items: Vec<Span<'static>> = LEGEND
        .iter()
        .zip(colours)
        .zip(PATTERNS)
        .map(|((name, colour), pattern)| {
            let sample = if app.theme.colour { '━' } else { pattern };
            Span::styled(format!("{sample}{name}"), Style::new().fg(colour))
        })
        .collect();
    let dots = if app.drawing == Drawing::Ascii {
        "--"
    } else {
        "••"
    };
    items.push(Span::raw(format!("{dots}stop")));
    items
}

/// The legend's items packed into lines of at most `width` characters, one space apart.
fn pack(items: Vec<Span<'static>>, width: usize) -> Vec<Line<'static>> {
    let mut lines: Vec<Vec<Span<'static>>> = vec![Vec::new()];
    let mut used = 0;
    for item in items {
        let w = item.width();
        let line = lines.last_mut().expect("one line at least");
        if !line.is_empty() && used + 1 + w > width {
            lines.push(vec![item]);
            used = w;
        } else {
            if !line.is_empty() {
                line.push(Span::raw(" "));
                used += 1;
            }
            used += w;
            line.push(item);
        }
    }
    lines.into_iter().map(Line::from).collect()
}

/// Axis ticks that read well: bounds and every tick a multiple of one step of 1, 2 or 5 × 10ⁿ,
/// at most `most` labels, and the top at least `top`.
pub(crate) fn nice_ticks(bottom: f64, top: f64, most: usize) -> (f64, f64, Vec<f64>) {
    let most = most.max(2);
    let span = (top - bottom).max(f64::MIN_POSITIVE);
    let mut step = 10f64.powf((span / (most - 1) as f64).log10().floor());
    loop {
        for m in [1.0, 2.0, 5.0] {
            let s = step * m;
            let (lo, hi) = ((bottom / s).floor() * s, (top / s - 1e-9).ceil() * s);
            let n = ((hi - lo) / s).round() as usize + 1;
            if n <= most {
                let ticks = (0..n)
                    .map(|k| lo + k as f64 * s)
                    .map(|v| if v.abs() < s * 1e-9 { 0.0 } else { v })
                    .collect();
                return (lo, hi, ticks);
            }
        }
        step *= 10.0;
    }
}

pub(crate) fn render_energy(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let scale = if app.log_scale { "log" } else { "linear" };
    let colours = t.energy_series();
    let border = area.width.saturating_sub(2) as usize;
    // "(y)": the axis the scale applies to, where the title has room for it.
    let axis = if 25 <= border { " (y)" } else { "" };
    let heading = vec![
        Span::styled(" energy ", t.heading()),
        Span::raw(format!("erg · {scale}{axis} ")),
    ];
    let legend = energy_legend(app);
    let legend_width: usize = legend.iter().map(Span::width).sum::<usize>() + legend.len() - 1;
    let heading_width: usize = heading.iter().map(Span::width).sum();
    // The legend rides in the title or the bottom border when it fits there whole; else it
    // takes the plot's top rows, and the y range grows so that no line runs under it.
    let mut block = Block::bordered();
    let mut inside: Vec<Line<'static>> = Vec::new();
    if heading_width + legend_width < border {
        let mut title = heading;
        title.extend(pack(legend, border).into_iter().flat_map(|l| l.spans));
        block = block.title(Line::from(title));
    } else if legend_width <= border {
        block = block
            .title(Line::from(heading))
            .title_bottom(Line::from(pack(legend, border).remove(0).spans).right_aligned());
    } else {
        block = block.title(Line::from(heading));
        // Over the whole width, the y labels under it left out; the threshold's item only
        // if it needs no line of its own (it is no energy term).
        inside = pack(legend.clone(), border);
        if inside.len() > pack(legend[..legend.len() - 1].to_vec(), border).len() {
            inside = pack(legend[..legend.len() - 1].to_vec(), border);
        }
    }
    let body = block.inner(area);
    if body.width < 12 || body.height < 4 {
        frame.render_widget(block, area);
        return;
    }
    let log = app.log_scale;
    let y_of = |v: f64| if log { v.max(LOG_FLOOR).log10() } else { v };
    let buckets = (body.width as usize).saturating_mul(2);
    let terms: [Term; 5] = [
        |s| s.total,
        |s| s.energy.translational,
        |s| s.energy.rotational,
        |s| s.energy.gravitational,
        |s| s.energy.elastic,
    ];
    let series: Vec<Vec<(f64, f64)>> = terms
        .iter()
        .map(|f| thinned(&app.history, buckets, |s| y_of(f(s))))
        .collect();
    let t_end = app.history.last().map_or(0.0, |s| s.time_s).max(app.live.time_s);
    let x_hi = nice_ceiling(t_end.max(0.1));
    let threshold = app.live.stop_threshold;
    let (mut lo, mut hi) = if threshold.is_finite() {
        (y_of(threshold), y_of(threshold))
    } else {
        (y_of(LOG_FLOOR), y_of(LOG_FLOOR))
    };
    for s in &series {
        for &(_, v) in s {
            if v.is_finite() {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
    }
    // Rows of the plot itself (the x axis and its labels take two), and how many of the
    // top ones the legend covers.
    let rows = body.height.saturating_sub(2).max(1) as f64;
    let covered = (inside.len() as f64).min(rows - 1.0);
    let most_labels = (rows as usize).div_ceil(2).clamp(2, 5);
    let (y_lo, y_hi, ticks) = if log {
        let bottom = y_of(LOG_FLOOR);
        let top = bottom + (hi.max(bottom + 1.0) - bottom) * rows / (rows - covered);
        // Whole decades, every one labelled or every second, third, …
        let decades = (top - bottom).ceil().max(1.0) as usize;
        let every = (1..=decades)
            .find(|d| decades.div_ceil(*d) < most_labels)
            .unwrap_or(decades);
        let n = decades.div_ceil(every);
        let top = bottom + (n * every) as f64;
        (
            bottom,
            top,
            (0..=n).map(|k| bottom + (k * every) as f64).collect::<Vec<_>>(),
        )
    } else {
        // A die pressed into the table has a slightly negative potential energy: a floor
        // below zero only when that is a visible share of the plot.
        let floor = if lo < -0.05 * hi.max(1.0) { lo } else { 0.0 };
        let top = floor + (hi.max(1.0) * 1.05 - floor) * rows / (rows - covered);
        nice_ticks(floor, top, most_labels)
    };
    let stop_line = [(0.0, y_of(threshold)), (x_hi, y_of(threshold))];
    let mut datasets: Vec<Dataset> = series
        .iter()
        .zip(LEGEND)
        .zip(colours)
        .zip(PATTERNS)
        .map(|(((data, name), colour), pattern)| {
            let marker = if t.colour {
                app.drawing.line_marker()
            } else {
                Marker::Custom(pattern)
            };
            Dataset::default()
                .name(name)
                .marker(marker)
                .graph_type(GraphType::Line)
                .style(Style::new().fg(colour))
                .data(data)
        })
        .collect();
    if threshold.is_finite() {
        datasets.push(
            Dataset::default()
                .name("stop")
                .marker(if app.drawing == Drawing::Ascii {
                    Marker::Custom('-')
                } else {
                    Marker::Dot
                })
                .graph_type(GraphType::Line)
                .style(Style::new().fg(t.threshold()))
                .data(&stop_line),
        );
    }
    let label = |v: f64| {
        let s = if log { fmt_num(10f64.powf(v)) } else { fmt_num(v) };
        format!("{s:>width$}", width = Y_LABEL_WIDTH as usize - 1)
    };
    // Labels sit evenly from the bottom row (first) to the top (last); those under the
    // legend are left blank.
    let plot_rows = rows as usize;
    let n = ticks.len();
    let labels: Vec<String> = ticks
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            let from_top = (plot_rows - 1) as f64 * (1.0 - i as f64 / (n - 1).max(1) as f64);
            if (from_top.round() as usize) < inside.len() {
                String::new()
            } else {
                label(v)
            }
        })
        .collect();
    let chart = Chart::new(datasets)
        .block(block)
        .x_axis(
            Axis::default()
                .bounds([0.0, x_hi])
                .labels(["0 s".to_string(), format!("{} s", fmt_num(x_hi))]),
        )
        .y_axis(Axis::default().bounds([y_lo, y_hi]).labels(labels))
        .legend_position(None);
    frame.render_widget(chart, area);
    if !inside.is_empty() {
        let legend_area = Rect {
            height: (inside.len() as u16).min(body.height),
            ..body
        };
        frame.render_widget(Paragraph::new(inside), legend_area);
    }
}

/// Characters the y axis's labels take ("200000" and a space).
const Y_LABEL_WIDTH: u16 = 7;

/// The next of 1, 2, 5 × 10ⁿ at or above `v` (axis ends that read well).
fn nice_ceiling(v: f64) -> f64 {
    if v <= 0.0 || !v.is_finite() {
        return 1.0;
    }
    let p = 10f64.powf(v.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * p)
        .find(|&c| c >= v * (1.0 - 1e-12))
        .unwrap_or(10.0 * p)
}
