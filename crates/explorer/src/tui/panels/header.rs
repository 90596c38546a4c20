//! The top line every screen shares: the preset, the roll, time, speed, phase.

use crate::tui::state::app::App;
use crate::worker::{Phase, RollKind};
use dicesim_physics::Status;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

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

pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let live = &app.roll.live;
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
    let changed = app.setup.modified();
    let modified = Span::styled(if changed { "*" } else { "" }, t.caution());
    let full = Line::from(vec![
        Span::styled(" dicesim ", t.selected().add_modifier(Modifier::BOLD)),
        Span::raw(" "),
        Span::styled(app.setup.preset.name.clone(), t.heading()),
        Span::styled(if changed { " (changed)" } else { "" }, t.caution()),
        Span::raw(format!(" · {roll}")),
        sep.clone(),
        Span::raw(format!("t = {:.3} s", live.time_s)),
        sep.clone(),
        Span::raw(format!("step {}", live.step)),
        sep.clone(),
        Span::raw(format!("speed {}", app.setup.speed.label())),
        sep.clone(),
        Span::raw(state),
        sep.clone(),
        phase.clone(),
        sep,
        Span::raw(fps.clone()),
    ]);
    // Narrow terminals get the same facts in fewer words, the phase never cut off.
    let line = if full.width() <= crate::tui::vocabulary::fit::room(area.width as usize) {
        full
    } else {
        let sep = || Span::raw("│");
        let part = |rank: u8, spans: Vec<Span<'static>>| (rank, spans);
        crate::tui::vocabulary::fit::line(
            vec![
                part(
                    0,
                    vec![
                        Span::styled(app.setup.preset.name.clone(), t.heading()),
                        modified,
                        Span::raw(" "),
                    ],
                ),
                part(0, vec![sep(), Span::raw(format!("t {:.3} s", live.time_s))]),
                part(2, vec![sep(), Span::raw(format!("step {}", live.step))]),
                part(1, vec![sep(), Span::raw(app.setup.speed.label())]),
                part(1, vec![sep(), Span::raw(if live.playing { "▶" } else { "⏸" })]),
                part(0, vec![sep(), phase]),
                part(3, vec![sep(), Span::raw(fps)]),
            ],
            area.width as usize,
        )
    };
    frame.render_widget(Paragraph::new(line), area);
}

#[cfg(test)]
mod header_tests;
