//! The chaos twin's predictability curve, beside its separation plot.

use crate::tui::panels::twins::predictability_curve::at_epsilon;
use crate::tui::state::app::App;
use crate::tui::state::die_screen::Drawing;
use crate::tui::tests::fixtures::{THROWS, complete, curves, failed, partial, twin_scene, with_curve};
use crate::tui::vocabulary::layout::screen_layout;
use crate::tui::vocabulary::theme::{Palette, Theme};
use crate::worker::CurveState;
use dicesim_experiment::predict::PredictCurve;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::crossterm::event::KeyCode;
use ratatui::style::{Color, Modifier};

fn draw(app: &App, width: u16, height: u16) -> Buffer {
    let mut t = Terminal::new(TestBackend::new(width, height)).expect("test backend");
    t.draw(|f| crate::tui::render(app, f)).expect("draw");
    t.backend().buffer().clone()
}

fn screen(app: &App, width: u16, height: u16) -> String {
    let b = draw(app, width, height);
    let area = b.area;
    (area.top()..area.bottom())
        .map(|y| {
            (area.left()..area.right())
                .map(|x| b[(x, y)].symbol())
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The cells of the curve panel on a full screen of this size.
fn panel_cells(b: &Buffer) -> Vec<(u16, u16)> {
    let area = screen_layout(b.area).expect("full size").outcomes;
    (area.top()..area.bottom())
        .flat_map(|y| (area.left()..area.right()).map(move |x| (x, y)))
        .collect()
}

fn panel_text(b: &Buffer) -> String {
    panel_cells(b).iter().map(|&p| b[p].symbol()).collect()
}

/// The curve panel with each character's ink as a letter: the points and their intervals
/// (b), chance (r), halfway (g), our ε (m), the text's ink (.), and a blank for a blank.
fn inks(b: &Buffer, theme: Theme) -> String {
    let area = screen_layout(b.area).expect("full size").outcomes;
    let letter = |fg: Color| {
        [
            (Color::Blue, 'b'),
            (Color::Red, 'r'),
            (Color::DarkGray, 'g'),
            (Color::Magenta, 'm'),
            (Color::Reset, '.'),
        ]
        .iter()
        .find(|(c, _)| theme.ink(*c) == fg)
        .map_or('?', |(_, l)| *l)
    };
    (area.top()..area.bottom())
        .map(|y| {
            (area.left()..area.right())
                .map(|x| {
                    let cell = &b[(x, y)];
                    if cell.symbol() == " " {
                        ' '
                    } else {
                        letter(cell.fg)
                    }
                })
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// "83 %": the share the panel should state for ε = 1e-9, read off the curve's own point.
fn share_at_1e9(c: &PredictCurve) -> String {
    let p = c
        .points
        .iter()
        .find(|p| p.epsilon == 1e-9)
        .expect("1e-9 is listed");
    format!("{:.0} %", 100.0 * p.same_share)
}

#[test]
fn a_complete_curve_beside_the_separation_plot() {
    let s = complete(Theme::default());
    let curve = &curves().1;
    for (w, h) in [(120, 36), (80, 24)] {
        let text = screen(&s.app, w, h);
        // The separation plot keeps its axes and title.
        assert!(text.contains("twin ε = 1e-9") && text.contains("1e-16"), "{text}");
        assert!(
            text.contains(&format!("P(same face) · {THROWS} throws")),
            "{text}"
        );
        assert!(text.contains(&share_at_1e9(curve)), "{text}");
        // Our ε's mark, the points, their intervals and both levels are drawn.
        for glyph in ['◆', '●', '│', '┄', '·', '┆'] {
            assert!(
                panel_text(&draw(&s.app, w, h)).contains(glyph),
                "{glyph} at {w}×{h}"
            );
        }
        assert!(
            !text.contains("outcomes of random rolls"),
            "the curve takes the table's place"
        );
    }
    let wide = screen(&s.app, 120, 36);
    let threshold = curve.threshold.expect("pairs were rolled").text();
    assert!(wide.contains(&format!("ε½ {threshold}")), "{wide}");
    assert!(wide.contains("the faces agree in"), "{wide}");
    insta::assert_snapshot!("twin_curve_complete_120x36", wide);
    insta::assert_snapshot!("twin_curve_complete_80x24", screen(&s.app, 80, 24));
}

#[test]
fn a_partial_curve_says_it_is_computing_and_how_far() {
    let s = partial();
    let (part, _) = curves();
    let n = part.starts;
    for (w, h, progress) in [
        (120, 36, format!("computing {n} of {THROWS} throws")),
        (80, 24, format!("computing {n}/{THROWS}")),
    ] {
        let text = screen(&s.app, w, h);
        assert!(text.contains(&progress), "{text}");
        assert!(
            text.contains("computing: the intervals narrow") || h < 30,
            "{text}"
        );
    }
    insta::assert_snapshot!("twin_curve_partial_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("twin_curve_partial_80x24", screen(&s.app, 80, 24));
}

#[test]
fn a_setup_that_cannot_settle_says_why() {
    let s = failed();
    let Some(CurveState::Failed(why)) = s.app.twin.curve.as_ref().map(|c| &c.state) else {
        panic!("{:?}", s.app.twin.curve);
    };
    assert!(why.contains("time cap of 0.01 s"), "{why}");
    for (w, h) in [(120, 36), (80, 24)] {
        let text = screen(&s.app, w, h);
        assert!(text.contains("The curve cannot be computed"), "{text}");
        assert!(text.contains("none of the"), "{text}");
    }
    insta::assert_snapshot!("twin_curve_failed_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("twin_curve_failed_80x24", screen(&s.app, 80, 24));
}

#[test]
fn the_projector_theme_paints_the_curve_bold_on_white() {
    let theme = Theme {
        palette: Palette::Projector,
        ..Theme::default()
    };
    let s = complete(theme);
    let b = draw(&s.app, 120, 36);
    let cells = panel_cells(&b);
    assert!(cells.iter().all(|&p| b[p].modifier.contains(Modifier::BOLD)));
    assert!(cells.iter().all(|&p| b[p].bg == Color::Rgb(255, 255, 255)));
    let of = |glyph: &str| cells.iter().find(|&&p| b[p].symbol() == glyph).map(|&p| b[p].fg);
    assert_eq!(of("┄"), Some(theme.ink(Color::Red)), "chance");
    assert_eq!(of("●"), Some(theme.ink(Color::Blue)), "points");
    assert_eq!(of("◆"), Some(theme.ink(Color::Magenta)), "our ε");
    // The text is the dark theme's; what the projector changes is the ink.
    assert_eq!(
        screen(&s.app, 120, 36),
        screen(&complete(Theme::default()).app, 120, 36)
    );
    insta::assert_snapshot!("twin_curve_projector_inks_120x36", inks(&b, theme));
    insta::assert_snapshot!(
        "twin_curve_projector_inks_80x24",
        inks(&draw(&s.app, 80, 24), theme)
    );
}

#[test]
fn without_colour_or_braille_the_lines_keep_their_own_characters() {
    let mono = complete(Theme::monochrome());
    let b = draw(&mono.app, 80, 24);
    let cells = panel_cells(&b);
    assert!(cells.iter().all(|&p| b[p].fg == Color::Reset), "no colour at all");
    let text = panel_text(&b);
    for glyph in ['◆', '●', '│', '┄', '·'] {
        assert!(text.contains(glyph), "{glyph}: {text}");
    }
    let mut ascii = complete(Theme::monochrome());
    ascii.app.die_screen.drawing = Drawing::Ascii;
    let text = panel_text(&draw(&ascii.app, 80, 24));
    for glyph in ['#', 'o', '|', '=', '-'] {
        assert!(text.contains(glyph), "{glyph}: {text}");
    }
    assert!(
        !text
            .chars()
            .any(|c| ('\u{2800}'..='\u{28ff}').contains(&c) || "●◆┄┆".contains(c)),
        "{text}"
    );
    insta::assert_snapshot!("twin_curve_ascii_80x24", screen(&ascii.app, 80, 24));
}

#[test]
fn the_app_keeps_the_newest_curve_and_drops_it_with_the_twin() {
    let (part, whole) = curves();
    let s = with_curve(
        twin_scene(Theme::default()),
        5,
        CurveState::Complete(whole.clone()),
    );
    // A late update of an older generation changes nothing.
    let mut s = with_curve(s, 4, CurveState::Computing(Some(part.clone())));
    assert_eq!(s.app.twin.curve.as_ref().map(|c| c.generation), Some(5));
    s.key(KeyCode::Char('T'));
    assert!(s.app.roll.live.twin.is_none());
    assert!(s.app.twin.curve.is_none(), "no twin, no curve");
    let text = screen(&s.app, 120, 36);
    assert!(text.contains("outcomes of random rolls"), "the table is back");
}

#[test]
fn our_epsilon_reads_the_listed_point_or_interpolates_in_log_epsilon() {
    let c = &curves().1;
    let listed = c.points.iter().find(|p| p.epsilon == 1e-9).expect("listed");
    assert_eq!(
        at_epsilon(c, 1e-9),
        Some((listed.same_share, Some(listed.interval)))
    );
    let next = c.points.iter().find(|p| p.epsilon == 1e-8).expect("listed");
    // √10 · 1e-9 lies halfway between 1e-9 and 1e-8 in log ε.
    let (share, interval) = at_epsilon(c, 10f64.powf(-8.5)).expect("between two points");
    assert!((share - 0.5 * (listed.same_share + next.same_share)).abs() < 1e-9);
    assert_eq!(interval, None);
}

#[test]
fn a_narrow_separation_panel_keeps_the_whole_epsilon_and_moves_its_legend_down() {
    let mut s = twin_scene(Theme::default());
    s.key(KeyCode::Char('<'));
    s.key(KeyCode::Char('<'));
    assert_eq!(s.app.roll.live.twin.as_ref().map(|t| t.epsilon), Some(1e-11));
    let narrow = screen(&s.app, 80, 24);
    assert!(narrow.contains("┌ twin ε = 1e-11 ─"), "{narrow}");
    assert!(narrow.contains("└━cm ━rad ─"), "{narrow}");
    assert!(screen(&s.app, 120, 36).contains("ε = 1e-11"));
    // Where it fits with the gap column before the corner, the legend stays in the title.
    let wide = screen(&twin_scene(Theme::default()).app, 130, 36);
    assert!(
        wide.contains("chaos twin ε = 1e-9 ━centre cm ━angle rad"),
        "{wide}"
    );
}
