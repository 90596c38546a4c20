//! Whole frames: the screens in the states a roll goes through, in every theme and at any size.

use crate::tui::render::screen::render;
use crate::tui::state::app::App;
use crate::tui::tests::fixtures::{
    Harness, boundary_sizes, draw, editing, filled_table, full, help, lines_of, mid_impact, mid_impact_with,
    screen, settled, spun_preset, start, twin_after, unstable,
};
use crate::tui::vocabulary::param::{Param, all};
use crate::tui::vocabulary::theme::Theme;
use crate::worker::{Command, Phase};
use dicesim_physics::Status;
use dicesim_setup::preset::Preset;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::crossterm::event::KeyCode;
use ratatui::layout::Rect;
use ratatui::style::Color;

#[test]
fn start_screen() {
    let s = start();
    assert_eq!(s.app.roll.live.step, 0);
    insta::assert_snapshot!("start_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("start_80x24", screen(&s.app, 80, 24));
}

/// The 120×36 screen is also the README's picture of the explorer (`tests/cli/docs.rs` holds
/// the README to this snapshot).
#[test]
fn mid_impact_screen() {
    let s = mid_impact();
    assert_eq!(s.app.roll.live.phase, Phase::InContact);
    insta::assert_snapshot!("mid_impact_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("mid_impact_80x24", screen(&s.app, 80, 24));
}

#[test]
fn settled_screen() {
    let s = settled();
    assert!(matches!(s.app.roll.live.phase, Phase::Ended(o) if o.status == Status::Settled));
    insta::assert_snapshot!("settled_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("settled_80x24", screen(&s.app, 80, 24));
}

#[test]
fn unstable_screen() {
    let s = unstable();
    assert!(matches!(s.app.roll.live.phase, Phase::Ended(o) if o.status == Status::Unstable));
    assert_eq!(s.app.setup.params.ground.stiffness, 2e7);
    insta::assert_snapshot!("unstable_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("unstable_80x24", screen(&s.app, 80, 24));
}

#[test]
fn editing_a_value() {
    let mut s = editing();
    insta::assert_snapshot!("editing_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("editing_80x24", screen(&s.app, 80, 24));
    for _ in 0..3 {
        s.key(KeyCode::Backspace);
    }
    s.key(KeyCode::Char('9'));
    s.key(KeyCode::Enter);
    assert!(
        s.app.value_editor().is_some_and(|e| e.error.is_some()),
        "9 is outside 0…5"
    );
    assert_eq!(
        s.app.setup.params.ground.friction,
        spun_preset().ground.friction,
        "a refused value changes nothing"
    );
    insta::assert_snapshot!("editing_refused_120x36", screen(&s.app, 120, 36));
}

#[test]
fn no_color_sends_no_colour_at_all() {
    for mut s in [mid_impact_with(Theme::monochrome()), {
        let mut s = Harness::new(&spun_preset(), Theme::monochrome());
        s.command(Command::SetParam(
            Param::named("ground.stiffness").scan_key(),
            4e6,
        ));
        s
    }] {
        s.key(KeyCode::Char('?'));
        s.key(KeyCode::Char('?'));
        let t = draw(&s.app, 120, 36);
        let buffer = t.backend().buffer();
        for y in 0..36 {
            for x in 0..120 {
                let c = &buffer[(x, y)];
                assert_eq!(
                    (c.fg, c.bg),
                    (Color::Reset, Color::Reset),
                    "cell {x},{y} `{}`",
                    c.symbol()
                );
            }
        }
    }
}

/// Rendering never panics, whatever the size and the state.
mod sizes {
    use super::*;
    use proptest::prelude::*;
    use std::sync::OnceLock;

    /// A spread of states, built once: each render below is cheap, the physics is not.
    fn states() -> &'static Vec<App> {
        static STATES: OnceLock<Vec<App>> = OnceLock::new();
        STATES.get_or_init(|| {
            let mut help_scrolled = help();
            for _ in 0..40 {
                help_scrolled.key(KeyCode::Down);
            }
            let mut refused = editing();
            refused.key(KeyCode::Char('9'));
            refused.key(KeyCode::Enter);
            vec![
                start().app,
                mid_impact().app,
                settled().app,
                unstable().app,
                help_scrolled.app,
                refused.app,
                filled_table().app,
                mid_impact_with(Theme::monochrome()).app,
            ]
        })
    }

    fn draw_into(app: &App, width: u16, height: u16) {
        let mut t = Terminal::new(TestBackend::new(width, height)).expect("test backend");
        t.draw(|f| render(app, f)).expect("draw");
    }

    #[test]
    fn every_boundary_size_draws() {
        for app in states() {
            for (width, height) in boundary_sizes() {
                draw_into(app, width, height);
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        #[test]
        fn random_states_at_random_sizes_draw(
            which in 0usize..8,
            width in 1u16..=200,
            height in 1u16..=60,
            yaw in -720.0f64..720.0,
            pitch in -90.0f64..90.0,
            zoom in -20i32..20,
            selected in 0usize..all().len(),
            log in any::<bool>(),
            ascii in any::<bool>(),
            help_scroll in 0u16..200,
        ) {
            let mut app = states()[which].clone();
            app.die_screen.camera.orbit(yaw, pitch);
            app.die_screen.camera.zoom_by(zoom);
            app.die_screen.selected = selected;
            app.die_screen.log_scale = log;
            if app.help_scroll().is_some() {
                app.overlay = Some(crate::tui::state::app::Overlay::Help { scroll: help_scroll });
            }
            app.die_screen.drawing = if ascii { crate::tui::state::die_screen::Drawing::Ascii } else { crate::tui::state::die_screen::Drawing::Braille };
            app.screen = Rect::new(0, 0, width, height);
            draw_into(&app, width, height);
        }
    }
}

/// Text that came from a file (a preset's name, an error quoting it) never sends a control
/// character to the terminal: the footer's notices show it escaped, and no cell holds one.
#[test]
fn control_characters_from_files_never_reach_the_terminal() {
    let title = "\u{1b}]0;owned\u{7}";
    let preset = Preset {
        name: format!("x{title}"),
        ..Preset::default()
    };
    let mut s = Harness::new(&preset, Theme::default());
    s.app.notice = Some(format!("cannot open {title}.toml"));
    let t = draw(&s.app, 120, 36);
    let buffer = t.backend().buffer();
    for line in lines_of(buffer) {
        assert!(!line.contains(char::is_control), "{line:?}");
    }
    let footer = &lines_of(buffer)[35];
    assert!(
        footer.contains(r"cannot open \u{1b}]0;owned\u{7}.toml"),
        "{footer}"
    );
}

mod themes {
    use super::*;
    use crate::tui::Theme;
    use crate::tui::input::update::update;
    use crate::tui::state::messages::Msg;
    use crate::tui::tests::fixtures::mid_impact_with;
    use crate::tui::vocabulary::theme::Palette;
    use ratatui::buffer::Buffer;
    use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
    use ratatui::style::Modifier;

    fn press(app: &mut App, code: KeyCode) {
        let sent = update(
            app,
            Msg::Input(Event::Key(KeyEvent::new(code, KeyModifiers::NONE))),
        );
        assert!(sent.is_empty(), "a theme asks nothing of the worker");
    }

    fn buffer(app: &App) -> Buffer {
        let mut t = Terminal::new(TestBackend::new(120, 36)).expect("test backend");
        t.draw(|f| render(app, f)).expect("draw");
        t.backend().buffer().clone()
    }

    /// Cells of `area` showing `symbol`.
    fn cells_with(b: &Buffer, area: Rect, symbol: &str) -> Vec<(u16, u16)> {
        (area.top()..area.bottom())
            .flat_map(|y| (area.left()..area.right()).map(move |x| (x, y)))
            .filter(|&p| b[p].symbol() == symbol)
            .collect()
    }

    #[test]
    fn t_cycles_dark_light_projector() {
        let mut a = start().app;
        assert_eq!(a.theme.palette, Palette::Dark);
        press(&mut a, KeyCode::Char('t'));
        assert_eq!(a.theme.palette, Palette::Light);
        assert_eq!(
            a.notice.as_deref(),
            Some("theme: light (t cycles dark, light, projector)")
        );
        press(&mut a, KeyCode::Char('t'));
        assert_eq!(a.theme.palette, Palette::Projector);
        press(&mut a, KeyCode::Char('t'));
        assert_eq!(a.theme.palette, Palette::Dark);
    }

    #[test]
    fn dark_keeps_the_terminal_background() {
        let b = buffer(&mid_impact().app);
        let areas = full();
        let (x, y) = (areas.params.x + 3, areas.params.y + 2);
        assert_eq!((b[(x, y)].fg, b[(x, y)].bg), (Color::Reset, Color::Reset));
    }

    #[test]
    fn light_paints_white_with_dark_inks() {
        let mut s = mid_impact_with(Theme::default().next());
        s.app.die_screen.arrows = true;
        let b = buffer(&s.app);
        let areas = full();
        // Plain text: black on white, not bold.
        let (x, y) = (areas.params.x + 3, areas.params.y + 2);
        assert_eq!(
            (b[(x, y)].fg, b[(x, y)].bg),
            (Color::Rgb(0, 0, 0), Color::Rgb(255, 255, 255))
        );
        assert!(!b[(x, y)].modifier.contains(Modifier::BOLD));
        // Every cell has a painted background (warnings keep their own).
        for y in 0..36 {
            for x in 0..120 {
                assert_ne!(b[(x, y)].bg, Color::Reset, "cell {x},{y}");
            }
        }
        // A touching corner in the light red (drawn without the arrows' legend over it);
        // at the impact the die is low, so the bar's bottom is rotational, light magenta.
        s.app.die_screen.arrows = false;
        let plain = buffer(&s.app);
        let dots = cells_with(&plain, areas.die, "●");
        assert!(!dots.is_empty());
        for p in dots {
            assert_eq!(plain[p].fg, Color::Rgb(160, 0, 0));
        }
        let bar = (areas.ledger.x + 1, areas.ledger.bottom() - 2);
        assert_eq!(b[bar].symbol(), "█");
        assert_eq!(b[bar].fg, Color::Rgb(130, 0, 140));
        // ω's arrow in the darkened cyan.
        let omega = cells_with(&b, areas.die, "ω");
        assert!(omega.iter().any(|&p| b[p].fg == Color::Rgb(0, 80, 120)));
    }

    #[test]
    fn projector_is_bold_black_on_white_with_strong_inks() {
        let s = mid_impact_with(Theme::default().next().next());
        assert_eq!(s.app.theme.palette, Palette::Projector);
        let b = buffer(&s.app);
        for y in 0..36 {
            for x in 0..120 {
                assert!(b[(x, y)].modifier.contains(Modifier::BOLD), "cell {x},{y}");
            }
        }
        let areas = full();
        let (x, y) = (areas.params.x + 3, areas.params.y + 2);
        assert_eq!(
            (b[(x, y)].fg, b[(x, y)].bg),
            (Color::Rgb(0, 0, 0), Color::Rgb(255, 255, 255))
        );
        let dots = cells_with(&b, areas.die, "●");
        assert!(!dots.is_empty());
        for p in dots {
            assert_eq!(b[p].fg, Color::Rgb(170, 0, 0));
        }
    }

    #[test]
    fn no_color_stays_colourless_in_every_theme() {
        let mut s = mid_impact_with(Theme::monochrome());
        s.app.die_screen.arrows = true;
        for _ in 0..3 {
            press(&mut s.app, KeyCode::Char('t'));
            assert!(s.app.notice.as_deref().is_some_and(|n| n.contains("NO_COLOR")));
            let b = buffer(&s.app);
            for y in 0..36 {
                for x in 0..120 {
                    assert_eq!(
                        (b[(x, y)].fg, b[(x, y)].bg),
                        (Color::Reset, Color::Reset),
                        "cell {x},{y}"
                    );
                }
            }
        }
    }
}

/// The classroom views draw at any terminal size without panicking.
mod every_size {
    use super::*;
    use crate::tui::Theme;
    use crate::tui::input::update::update;
    use crate::tui::state::messages::Msg;
    use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};

    fn with_keys(mut app: App, keys: &[KeyCode]) -> App {
        for &k in keys {
            update(
                &mut app,
                Msg::Input(Event::Key(KeyEvent::new(k, KeyModifiers::NONE))),
            );
        }
        app
    }

    fn classroom_views() -> [App; 6] {
        let twin = twin_after(500).app;
        let mut editing = with_keys(twin.clone(), &[KeyCode::Char('E'), KeyCode::Char('1')]);
        editing.die_screen.arrows = true;
        [
            with_keys(mid_impact().app, &[KeyCode::Char('v'), KeyCode::Char('t')]),
            twin,
            editing,
            with_keys(start().app, &[KeyCode::Char('o'), KeyCode::Down]),
            with_keys(
                start().app,
                &[KeyCode::Char('s'), KeyCode::Char('!'), KeyCode::Enter],
            ),
            {
                let mut a = settled().app;
                a.theme = Theme::default().next().next();
                a.die_screen.arrows = true;
                a
            },
        ]
    }

    fn draw_at(app: &App, width: u16, height: u16) {
        let mut t = Terminal::new(TestBackend::new(width, height)).expect("test backend");
        t.draw(|f| render(app, f)).expect("draw");
    }

    #[test]
    fn every_classroom_view_draws_at_every_boundary_size() {
        for app in &classroom_views() {
            for (width, height) in boundary_sizes() {
                draw_at(app, width, height);
            }
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]

        #[test]
        fn classroom_views_draw_at_random_sizes(which in 0usize..6, width in 1u16..=200, height in 1u16..=60) {
            static VIEWS: std::sync::OnceLock<[App; 6]> = std::sync::OnceLock::new();
            draw_at(&VIEWS.get_or_init(classroom_views)[which], width, height);
        }
    }
}
