//! The `?` overlay: every key, and the model explained for a classroom.

use crate::tui::state::app::App;
use crate::tui::state::app::Page;
use crate::tui::vocabulary::format::group;
use crate::tui::vocabulary::key_table::{Action, Scope, label, named, section};
use ratatui::Frame;
use ratatui::layout::{Constraint, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph};

const MODEL: &[&str] = &[
    "The die is a cube of 8 point masses, its corners, moving as one rigid body (Chin & Li, 2019). \
     Gravity pulls every corner down.",
    "The table is a stiff trampoline. A corner that sinks a depth d into it is pushed up by a spring, k·d, \
     minus damping, k·d·γ·u (u: how fast the corner moves down), which takes energy out. Friction drags the \
     corner sideways against its sliding with μ times that push.",
    "One step of Δt: the forces change the velocity, the new velocity moves the die (semi-implicit Euler); \
     the torques change the spin, and the cube turns by |ω|·Δt. Then the forces are worked out again.",
    "Energy: translational (moving), rotational (turning), gravitational (height) and elastic (the squashed \
     spring). At an impact a corner sinks a fraction of a millimetre into a very stiff spring: for a \
     millisecond the elastic term spikes above all the others, then is handed back as motion, less what \
     damping and friction took. The log scale ({LogScale}) shows the spikes and the small terms together.",
    "The energy panel: a bar of the energy now, stacked by form and scaled to the energy at the start \
     (◀ marks the total), and the ledger of where the rest went: work done by the ground's damping and by \
     friction, measured step by step, and the remainder, the integrator's own error (semi-implicit Euler \
     loses ½·M·g²·Δt² per step even in free flight). Damping + friction + integrator + now = start.",
    "A roll ends once the energy drops below 80% of what it takes to tip the die over an edge (the dotted \
     stop line): from then on the face up cannot change.",
    "Same start, same face: the model is deterministic (r). A die looks random because a tiny change in the \
     start changes the face (R, b). The chaos twin (T) shows it: two dice a relative ε = 1e-9 apart drift \
     apart, the gap growing by orders of magnitude at the impacts, until it is as big as the die; from a \
     gentle drop they land the same way.",
    "While the twin rolls, the predictability curve of the setup takes the outcome table's place, \
     computed in the background: random throws (the ones {RandomRoll} draws), each rolled beside a twin at every ε \
     from 1e-15 to 0.1, and P(same face), the share of pairs that land alike, against ε (● with its 95 % \
     interval │). It falls from 1 towards chance, Σp² (┄), what two unrelated throws share; ε½ is where \
     it crosses halfway (·). ◆ marks the twin's own ε on it. {Twin} again brings the table back.",
    "The step is stable only while ω_rock·Δt < 2, where ω_rock = √(6k/M) is how fast a die lying flat rocks \
     on its face; spin, impact speed, damping and friction set limits of their own. The readout under the \
     parameters names the tightest, \"Δt stability: … at N % of limit\", amber from 80 % and red past \
     100 %: raise k or Δt and watch the energy grow instead of fall.",
    "The outcome table: each face's share of the random rolls, its bar shaded (░) over the 95 % interval in \
     which the die's true share lies; a fair die's 1/6 is the dotted line, ┼ where it falls inside the \
     shading. χ² and p test the faces against a fair die, and the line below says how many rolls a test at \
     5 % needs to see a bias as large as the one measured, 4 times in 5. A loaded die shows it: give a \
     corner extra mass (extra mass 1…8, the last rows of the parameters; ◆ marks it on the die), or open \
     loaded-corner, and batch.",
];

/// `text` with each `{Action}` replaced by that action's keys on the die screen.
fn keyed(text: &str) -> String {
    [
        ("{Replay}", Action::Replay),
        ("{RandomRoll}", Action::RandomRoll),
        ("{Batch}", Action::Batch),
        ("{Twin}", Action::Twin),
        ("{LogScale}", Action::LogScale),
    ]
    .iter()
    .fold(text.to_string(), |t, (name, action)| {
        t.replace(name, label(Scope::Die, *action))
    })
}

/// Columns of a key line's keys, its help text starting after them.
const KEY_COLUMNS: usize = 16;

/// `text` after `first` (a key, or the indent of a paragraph, `lead` columns wide), wrapped at
/// spaces to fit a help `width` columns wide (its gap column kept free): every line after the
/// first starts at `lead`, under the text it goes on, never at the left edge where it would
/// read as an item of its own.
fn hanging(first: Span<'static>, lead: usize, text: &str, width: usize) -> Vec<Line<'static>> {
    let mut lines = Vec::new();
    let mut first = Some(first);
    for words in crate::tui::vocabulary::fit::wrap(text, width.saturating_sub(lead).max(10)) {
        let start = first.take().unwrap_or_else(|| Span::raw(" ".repeat(lead)));
        lines.push(Line::from(vec![start, Span::raw(words)]));
    }
    lines.extend(first.map(|f| Line::from(vec![f])));
    lines
}

/// The help's lines for an overlay `width` columns wide inside its border.
pub(crate) fn help_lines(app: &App, width: usize) -> Vec<Line<'static>> {
    let t = &app.theme;
    let key_lines = |screen: Scope| {
        let mut rows: Vec<_> = section(screen).collect();
        // The keys of every screen first: the help and how to leave it, quitting, before
        // the first page ends.
        rows.sort_by_key(|b| b.screen != Scope::Both);
        rows.into_iter().flat_map(move |b| {
            let what = b.help.replace(
                "a batch of",
                &format!("a batch of {}", group(app.roll.batch_size)),
            );
            let keys = Span::styled(format!("  {:<14}", b.label), t.key());
            hanging(keys, KEY_COLUMNS, &what, width)
        })
    };
    let mut die = vec![Line::styled("Keys", t.heading())];
    die.extend(key_lines(Scope::Die));
    die.extend(hanging(
        Span::styled(format!("  {:<14}", "mouse"), t.key()),
        KEY_COLUMNS,
        &format!(
            "click a value to select it, scroll to change it; drag the die to orbit, scroll on it to zoom; \
             click the timeline to jump there; in throw mode ({}) a drag on the die throws it, and so does a \
             Ctrl- or Alt-drag on it without",
            label(Scope::Die, Action::ThrowMode)
        ),
        width,
    ));
    die.push(Line::raw(""));
    let mut map = vec![Line::styled(
        format!("Basin-map screen ({})", label(Scope::Die, Action::OpenMap)),
        t.heading(),
    )];
    map.extend(key_lines(Scope::Map));
    map.push(Line::raw(""));
    // The keys of the screen the help was opened on come first.
    let mut lines = if app.page == Page::Map {
        [map, die].concat()
    } else {
        [die, map].concat()
    };
    // What is on top of the screens keeps its own keys.
    for mode in Scope::MODES
        .into_iter()
        .filter(|m| !matches!(m, Scope::Die | Scope::Map))
    {
        lines.push(Line::styled(mode.title(), t.heading()));
        lines.extend(key_lines(mode));
        lines.push(Line::raw(""));
    }
    lines.push(Line::styled("The model", t.heading()));
    for paragraph in MODEL {
        lines.extend(hanging(Span::raw("  "), 2, &keyed(paragraph), width));
        lines.push(Line::raw(""));
    }
    lines
}

/// The help, over the screen `area`.
pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let popup = area.centered(Constraint::Max(100), Constraint::Percentage(90));
    crate::tui::panels::overlays::popup::clear_around(popup, area, frame);
    let block = Block::bordered()
        .title(Line::styled(" help · the model in a nutshell ", t.heading()))
        .title_bottom(
            Line::from(format!(
                " {} scroll · {} closes ",
                named(Scope::Help, Action::SelectPrevious),
                named(Scope::Help, Action::Close)
            ))
            .right_aligned(),
        );
    let body = block.inner(popup);
    frame.render_widget(block, popup);
    let para =
        Paragraph::new(help_lines(app, body.width as usize)).scroll((app.help_scroll().unwrap_or(0), 0));
    frame.render_widget(para, body);
}

#[cfg(test)]
mod help_tests;
