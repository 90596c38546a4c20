//! Drawing: `render(&App, &mut Frame)` is a pure function of the app state. It never steps
//! the physics and never reads a clock.

use super::app::{App, Drawing};
use super::camera::{EDGES, FACE_CORNERS, face_centre, face_normal};
use super::footer::{render_footer, render_help};
use super::format::{fmt_num, fmt_range};
use super::layout::{MIN_HEIGHT, MIN_WIDTH, param_window, screen_layout};
use super::param::all;
use crate::physics::stopping::why_it_cannot_settle;
use crate::physics::{Stability, Status, UnstableReason};
use crate::worker::{EnergySample, Phase, RollKind};
use nalgebra::Vector3;
use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::canvas::{Canvas, Context, Line as CanvasLine};
use ratatui::widgets::{Axis, Block, Chart, Clear, Dataset, GraphType, LineGauge, Paragraph, Wrap};

/// Share of the tightest stability limit from which the step is worth watching; past the
/// limit itself (1) a roll is predicted unstable (docs/model.md, "Stability").
pub(crate) const STABILITY_CAUTION: f64 = 0.8;
pub(crate) const STABILITY_DANGER: f64 = 1.0;

/// Draws the whole screen.
pub fn render(app: &App, frame: &mut Frame) {
    if app.view == super::map::View::Map {
        super::map::render_map_screen(app, frame);
        return;
    }
    let area = frame.area();
    let Some(areas) = screen_layout(area) else {
        render_too_small(area, frame);
        app.theme.paint(frame.buffer_mut());
        return;
    };
    render_header(app, areas.header, frame);
    render_params(app, areas.params, frame);
    render_outcomes(app, areas.outcomes, frame);
    render_die(app, areas.die, frame);
    super::timeline::render(app, areas.timeline, frame);
    if app.live.twin.is_some() {
        super::twin::render_separation(app, areas.energy, frame);
    } else {
        render_energy(app, areas.energy, frame);
    }
    super::ledger::render_ledger(app, areas.ledger, frame);
    render_footer(app, areas.footer, frame);
    if app.help {
        render_help(app, area, frame);
    }
    super::dialogs::render(app, area, frame);
    app.theme.paint(frame.buffer_mut());
}

pub(crate) fn render_too_small(area: Rect, frame: &mut Frame) {
    let text = vec![
        Line::styled(
            format!("Enlarge the terminal to at least {MIN_WIDTH}×{MIN_HEIGHT}"),
            Style::new().add_modifier(Modifier::BOLD),
        ),
        Line::from(format!("(it is {}×{} now) · q quits", area.width, area.height)),
    ];
    let top = area.height.saturating_sub(2) / 2;
    let [_, middle] = area.layout(&Layout::vertical([Constraint::Length(top), Constraint::Min(0)]));
    frame.render_widget(Paragraph::new(text).centered().wrap(Wrap { trim: true }), middle);
}

fn phase_style(app: &App, phase: &Phase) -> Style {
    let t = &app.theme;
    match phase {
        Phase::InContact => t.contact(),
        Phase::Ended(o) if o.status == Status::Settled => t.good(),
        Phase::Ended(o) if o.status == Status::Unstable => t.danger(),
        Phase::Ended(_) => t.caution(),
        _ => t.heading(),
    }
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

/// `text` broken at spaces into lines of at most `width` characters (a longer word gets a
/// line of its own).
fn wrap_words(text: &str, width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        let needed = line.chars().count() + usize::from(!line.is_empty()) + word.chars().count();
        if !line.is_empty() && needed > width {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// Why the roll on screen ended unstable, or could not settle on its table, when it did.
fn end_reason(app: &App) -> Option<(String, Style)> {
    match app.live.phase {
        Phase::Ended(o) if o.status == Status::Unstable => Some((
            format!(
                "unstable: {}",
                UnstableReason::new(&app.live.params, &app.live.initial)
            ),
            app.theme.danger(),
        )),
        Phase::Ended(o) if o.status == Status::Timeout => why_it_cannot_settle(&app.live.params)
            .map(|why| (format!("did not settle: {why}"), app.theme.caution())),
        _ => None,
    }
}

pub(crate) fn render_header(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let live = &app.live;
    let sep = Span::raw(" │ ");
    let roll = match live.roll {
        RollKind::Preset => "preset roll".to_string(),
        RollKind::Random(n) => format!("random roll #{n}"),
        RollKind::Edited => "edited roll".to_string(),
    };
    let state = if live.playing { "▶ playing" } else { "⏸ paused" };
    let fps = app.fps.map_or("– fps".to_string(), |f| format!("{f:.0} fps"));
    let phase = Span::styled(live.phase.label(), phase_style(app, &live.phase));
    // The setup differs from the preset it came from: saving (s) would keep it.
    let changed = super::dialogs::modified(app);
    let modified = Span::styled(if changed { "*" } else { "" }, t.caution());
    let full = Line::from(vec![
        Span::styled(" dicesim ", t.selected().add_modifier(Modifier::BOLD)),
        Span::raw(" "),
        Span::styled(app.preset.name.clone(), t.heading()),
        Span::styled(if changed { " (changed)" } else { "" }, t.caution()),
        Span::raw(format!(" · {roll}")),
        sep.clone(),
        Span::raw(format!("t = {:.3} s", live.time_s)),
        sep.clone(),
        Span::raw(format!("step {}", live.step)),
        sep.clone(),
        Span::raw(format!("speed {}", app.speed.label())),
        sep.clone(),
        Span::raw(state),
        sep.clone(),
        phase.clone(),
        sep,
        Span::raw(fps.clone()),
    ]);
    // Narrow terminals get the same facts in fewer words, the phase never cut off.
    let line = if full.width() <= area.width as usize {
        full
    } else {
        let sep = Span::raw("│");
        Line::from(vec![
            Span::styled(app.preset.name.clone(), t.heading()),
            modified,
            Span::raw(" "),
            sep.clone(),
            Span::raw(format!("t {:.3} s", live.time_s)),
            sep.clone(),
            Span::raw(format!("step {}", live.step)),
            sep.clone(),
            Span::raw(app.speed.label()),
            sep.clone(),
            Span::raw(if live.playing { "▶" } else { "⏸" }),
            sep.clone(),
            phase,
            sep,
            Span::raw(fps),
        ])
    };
    frame.render_widget(Paragraph::new(line), area);
}

pub(crate) fn render_params(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let block = Block::bordered()
        .title(Line::styled(" parameters ", t.heading()))
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
    let (first, visible) = param_window(app, area);
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
    let detail = match &app.editing {
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
    let block = Block::bordered().title(Line::from(title));
    let body = block.inner(area);
    frame.render_widget(block, area);
    if body.height == 0 || body.width < 20 {
        return;
    }
    let bar_width = (body.width as usize).saturating_sub(21).max(2);
    let fair_at = bar_width / 2;
    let mut lines = Vec::new();
    // The bar spans 0 to 1/3, so a fair face reaches the dotted mark in the middle.
    let mark = format!("{}┆ 1/6 fair", " ".repeat(fair_at));
    lines.push(Line::from(vec![
        Span::styled(" face  count  share", t.heading()),
        Span::raw(mark),
    ]));
    let n = table.tally.total();
    for face in 1..=6u8 {
        let count = table.tally.counts[face as usize - 1];
        let share = table.tally.share(face);
        let filled = (share * 3.0 * bar_width as f64 * 8.0).round() as usize;
        let mut bar = String::new();
        for j in 0..bar_width {
            let eighths = filled.saturating_sub(j * 8).min(8);
            bar.push(match eighths {
                0 if j == fair_at => '┆',
                0 => ' ',
                e => [' ', '▏', '▎', '▍', '▌', '▋', '▊', '▉', '█'][e],
            });
        }
        let over = if filled > bar_width * 8 { "▸" } else { "" };
        let share_text = if n > 0 {
            format!("{:5.1}%", 100.0 * share)
        } else {
            "     –".to_string()
        };
        let newest = table.last.front().and_then(|r| r.outcome.face) == Some(face);
        let face_style = if newest { t.selected() } else { Style::new() };
        lines.push(Line::from(vec![
            Span::styled(format!("  {face}  "), face_style),
            Span::raw(format!("{count:>6} {share_text} ")),
            Span::styled(bar, t.bar()),
            Span::styled(over, t.bar()),
        ]));
    }
    let mut summary = vec![Span::raw(format!(" n {n}"))];
    match (table.tally.chi_square(), table.tally.p_value()) {
        (Some(chi2), Some(p)) => {
            summary.push(Span::raw(format!("  χ² {chi2:.2}  p ")));
            let style = if p < 0.01 { t.caution() } else { Style::new() };
            summary.push(Span::styled(fmt_num(p), style));
        }
        _ => summary.push(Span::raw("  χ² –  p –")),
    }
    if table.did_not_settle > 0 {
        summary.push(Span::raw(format!("  no face {}", table.did_not_settle)));
    }
    if table.unstable > 0 {
        summary.push(Span::styled(format!("  unstable {}", table.unstable), t.danger()));
    }
    lines.push(Line::from(summary));
    let mut rest = body.height.saturating_sub(lines.len() as u16);
    let text_area = Rect {
        height: body.height.min(lines.len() as u16),
        ..body
    };
    frame.render_widget(Paragraph::new(lines), text_area);
    let mut y = text_area.bottom();
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
    if rest > 0 && !table.last.is_empty() {
        let mut last = vec![Line::styled(
            " last rolls: spin ω (rad/s) → face, steps",
            t.heading(),
        )];
        for r in table.last.iter().take(rest as usize - 1) {
            let w = r.initial.angular_velocity;
            let end = match (r.outcome.status, r.outcome.face) {
                (Status::Settled, Some(f)) => format!("→ {f}"),
                (Status::Unstable, _) => "→ unstable".to_string(),
                _ => "→ no face".to_string(),
            };
            last.push(Line::from(format!(
                " #{:<5} ({:>4.0},{:>4.0},{:>4.0}) {end} {:>6}",
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

pub(crate) fn render_die(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let die = &app.live.die;
    let half = app.live.params.die.half_size;
    let lowest = die.corners.iter().map(|c| c.z).fold(f64::INFINITY, f64::min);
    let mut title = vec![
        Span::styled(" die ", t.heading()),
        Span::raw(format!(
            "· face up {} · lowest corner {:.2} cm ",
            die.face_up, lowest
        )),
    ];
    if let Some(twin) = &app.live.twin {
        title.push(Span::styled(
            format!("· twin face up {} ", twin.die.face_up),
            Style::new().fg(t.ghost()),
        ));
    }
    let title = Line::from(title);
    let block = Block::bordered().title(title);
    let body = block.inner(area);
    frame.render_widget(block, area);
    if body.width < 2 || body.height < 2 {
        return;
    }
    let cam = app.camera;
    let width = cam.width_cm(half);
    let height = width * 2.0 * body.height as f64 / body.width as f64;
    let focus = Vector3::new(die.centre.x, die.centre.y, 0.0);
    let centre_y = cam.project(&die.centre, &focus).y.max(0.35 * height);
    let (x_lo, x_hi) = (-width / 2.0, width / 2.0);
    let (y_lo, y_hi) = (centre_y - height / 2.0, centre_y + height / 2.0);
    let marker = match app.drawing {
        Drawing::Braille => Marker::Braille,
        Drawing::Ascii => Marker::Custom('*'),
    };
    let contact: [bool; 8] = std::array::from_fn(|k| die.forces[k].depth > 0.0);
    let canvas = Canvas::default()
        .marker(marker)
        .x_bounds([x_lo, x_hi])
        .y_bounds([y_lo, y_hi])
        .paint(|ctx| {
            draw_ground(ctx, app, &focus, width, half);
            if let Some(twin) = &app.live.twin {
                super::twin::draw_ghost(ctx, app, &cam, &focus, &twin.die);
            }
            ctx.layer();
            let foot = |p: &Vector3<f64>| Vector3::new(p.x, p.y, 0.0);
            for (a, b) in EDGES {
                line3(
                    ctx,
                    &cam,
                    &focus,
                    &foot(&die.corners[a]),
                    &foot(&die.corners[b]),
                    t.shadow(),
                );
            }
            if lowest > 0.02 * half {
                let low = die
                    .corners
                    .iter()
                    .min_by(|p, q| p.z.total_cmp(&q.z))
                    .copied()
                    .unwrap_or(die.centre);
                line3(ctx, &cam, &focus, &low, &foot(&low), t.shadow());
            }
            ctx.layer();
            let visible: [bool; 6] =
                std::array::from_fn(|f| cam.facing(&face_normal(&die.corners, &die.centre, f)) > 0.0);
            for (a, b) in EDGES {
                let seen = (0..6)
                    .any(|f| visible[f] && FACE_CORNERS[f].contains(&a) && FACE_CORNERS[f].contains(&b));
                let touching = contact[a] || contact[b];
                if seen || touching {
                    let colour = if touching { t.contact_colour() } else { t.die() };
                    line3(ctx, &cam, &focus, &die.corners[a], &die.corners[b], colour);
                }
            }
            for f in 0..6 {
                let facing = cam.facing(&face_normal(&die.corners, &die.centre, f));
                if facing > 0.3 {
                    let c = cam.project(&face_centre(&die.corners, f), &focus);
                    let style = if f as u8 + 1 == die.face_up {
                        t.heading().add_modifier(Modifier::REVERSED)
                    } else {
                        t.heading()
                    };
                    ctx.print(c.x, c.y, Span::styled(format!("{}", f + 1), style));
                }
            }
            let dot = if app.drawing == Drawing::Ascii { "@" } else { "●" };
            for k in (0..8).filter(|&k| contact[k]) {
                let c = cam.project(&die.corners[k], &focus);
                ctx.print(c.x, c.y, Span::styled(dot, t.contact()));
            }
            if app.vectors {
                super::vectors::draw(ctx, app, &cam, &focus, die);
            }
            ctx.print(x_lo, y_hi, Span::raw(format!("centre {:.2} cm up", die.centre.z)));
        });
    frame.render_widget(canvas, body);
    if let Some((reason, style)) = end_reason(app) {
        let lines: Vec<Line> = wrap_words(&reason, body.width as usize)
            .into_iter()
            .map(|l| Line::styled(l, style))
            .collect();
        let top = Rect {
            height: (lines.len() as u16).min(body.height),
            ..body
        };
        frame.render_widget(Clear, top);
        frame.render_widget(Paragraph::new(lines), top);
    }
    if app.vectors && body.height >= 6 {
        let legend = Rect {
            y: body.bottom() - 2,
            height: 2,
            ..body
        };
        frame.render_widget(Paragraph::new(super::vectors::legend(app, body.width)), legend);
    }
}

pub(crate) fn line3(
    ctx: &mut Context,
    cam: &super::camera::Camera,
    focus: &Vector3<f64>,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
    colour: ratatui::style::Color,
) {
    let (p, q) = (cam.project(a, focus), cam.project(b, focus));
    if [p.x, p.y, q.x, q.y].iter().all(|v| v.is_finite()) {
        ctx.draw(&CanvasLine::new(p.x, p.y, q.x, q.y, colour));
    }
}

/// A patch of floor tiles around the die, fixed to the world so the die's travel shows
/// against it; small enough that the die stays the thing to look at.
fn draw_ground(ctx: &mut Context, app: &App, focus: &Vector3<f64>, view_width: f64, half: f64) {
    let side = 2.0 * half;
    let spacing = 2.0 * side * (view_width / (6.0 * side)).round().max(1.0);
    let reach = 0.45 * view_width;
    let colour = app.theme.ground();
    let cells = |c: f64| {
        (
            ((c - reach) / spacing).ceil() as i64,
            ((c + reach) / spacing).floor() as i64,
        )
    };
    let ((x0, x1), (y0, y1)) = (cells(focus.x), cells(focus.y));
    let (xa, xb) = (focus.x - reach, focus.x + reach);
    let (ya, yb) = (focus.y - reach, focus.y + reach);
    let cam = app.camera;
    for i in x0..=x1 {
        let x = i as f64 * spacing;
        line3(
            ctx,
            &cam,
            focus,
            &Vector3::new(x, ya, 0.0),
            &Vector3::new(x, yb, 0.0),
            colour,
        );
    }
    for j in y0..=y1 {
        let y = j as f64 * spacing;
        line3(
            ctx,
            &cam,
            focus,
            &Vector3::new(xa, y, 0.0),
            &Vector3::new(xb, y, 0.0),
            colour,
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
/// (the order of [`super::theme::Theme::energy_series`]).
const LEGEND: [&str; 5] = ["total", "transl", "rot", "grav", "elastic"];

/// One energy term of a sample, erg.
type Term = fn(&EnergySample) -> f64;

/// erg: the floor of the log plot (energies below, including negative gravity, sit on it).
const LOG_FLOOR: f64 = 1.0;

pub(crate) fn render_energy(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let scale = if app.log_scale { "log" } else { "linear" };
    let colours = t.energy_series();
    // The legend rides in the title, so it never hides an impact spike.
    let mut title = vec![
        Span::styled(" energy ", t.heading()),
        Span::raw(format!("erg · {scale} (y) ")),
    ];
    for (name, colour) in LEGEND.iter().zip(colours) {
        title.push(Span::styled(format!("━{name} "), Style::new().fg(colour)));
    }
    title.push(Span::raw("••stop "));
    let block = Block::bordered().title(Line::from(title));
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
    let stop_line = [(0.0, y_of(threshold)), (x_hi, y_of(threshold))];
    let (mut lo, mut hi) = (y_of(threshold), y_of(threshold));
    for s in &series {
        for &(_, v) in s {
            if v.is_finite() {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
    }
    let (y_lo, y_hi) = if log {
        (y_of(LOG_FLOOR), hi.max(y_of(LOG_FLOOR) + 1.0).ceil())
    } else {
        let floor = if lo < 0.0 { -nice_ceiling(-lo) } else { 0.0 };
        (floor, nice_ceiling(hi.max(1.0) * 1.05))
    };
    let marker = app.drawing.line_marker();
    let mut datasets: Vec<Dataset> = series
        .iter()
        .zip(LEGEND)
        .zip(colours)
        .map(|((data, name), colour)| {
            Dataset::default()
                .name(name)
                .marker(marker)
                .graph_type(GraphType::Line)
                .style(Style::new().fg(colour))
                .data(data)
        })
        .collect();
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
    let label = |v: f64| if log { fmt_num(10f64.powf(v)) } else { fmt_num(v) };
    let chart = Chart::new(datasets)
        .block(block)
        .x_axis(
            Axis::default()
                .bounds([0.0, x_hi])
                .labels(["0 s".to_string(), format!("{} s", fmt_num(x_hi))]),
        )
        .y_axis(Axis::default().bounds([y_lo, y_hi]).labels([
            label(y_lo),
            label((y_lo + y_hi) / 2.0),
            label(y_hi),
        ]))
        .legend_position(None);
    frame.render_widget(chart, area);
}

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
