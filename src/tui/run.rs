//! The terminal's lifecycle and the event loop: report hooks first, then
//! the terminal, mouse capture undone on every exit path, panic included.

use super::app::{App, Msg, update};
use super::render::render;
use super::theme::Theme;
use crate::preset::Preset;
use crate::worker::{Engine, Worker};
use color_eyre::eyre::{Result, WrapErr};
use ratatui::DefaultTerminal;
use ratatui::crossterm::event::{self, DisableMouseCapture, EnableMouseCapture};
use ratatui::crossterm::execute;
use ratatui::layout::Rect;
use std::collections::VecDeque;
use std::io::stdout;
use std::sync::mpsc::{RecvTimeoutError, channel};
use std::time::{Duration, Instant};

/// Longest wait between frames while something moves (the worker's ticks usually come first).
const FRAME: Duration = Duration::from_millis(33);

/// Opens the explorer on `preset` and runs it until the user quits.
pub(crate) fn run(preset: &Preset, theme: Theme) -> Result<()> {
    let engine = Engine::new(preset).wrap_err("the preset cannot be simulated")?;
    // A second install (a caller already did) is harmless: keep the first.
    let _ = color_eyre::install();
    let mut terminal = ratatui::init();
    let _ = execute!(stdout(), EnableMouseCapture);
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        // ratatui's restore does not turn mouse reporting off.
        let _ = execute!(stdout(), DisableMouseCapture);
        previous(info);
    }));
    let result = event_loop(&mut terminal, engine, theme);
    let _ = execute!(stdout(), DisableMouseCapture);
    ratatui::restore();
    result
}

fn event_loop(terminal: &mut DefaultTerminal, mut engine: Engine, theme: Theme) -> Result<()> {
    let (tx, rx) = channel::<Msg>();
    let mut app = App::new(engine.snapshot(), theme);
    app.store = crate::preset::Store::from_env();
    let size = terminal.size()?;
    app.screen = Rect::new(0, 0, size.width, size.height);
    let maps = tx.clone();
    let worker = Worker::spawn_with_maps(engine, tx.clone(), move |m| maps.send(Msg::from(m)).is_ok());
    // The input thread blocks in `event::read` for the life of the process; it ends with it.
    std::thread::Builder::new()
        .name("dicesim-input".to_string())
        .spawn(move || {
            while let Ok(ev) = event::read() {
                if tx.send(Msg::Input(ev)).is_err() {
                    break;
                }
            }
        })?;
    let mut drawn: VecDeque<Instant> = VecDeque::new();
    'frames: loop {
        terminal.draw(|f| render(&app, f))?;
        let now = Instant::now();
        drawn.push_back(now);
        while drawn
            .front()
            .is_some_and(|t| now.duration_since(*t) > Duration::from_secs(1))
        {
            drawn.pop_front();
        }
        // Idle: block until input or a worker message, so a paused explorer uses no CPU.
        let first = if app.animating() {
            match rx.recv_timeout(FRAME) {
                Ok(m) => Some(m),
                Err(RecvTimeoutError::Timeout) => None,
                Err(RecvTimeoutError::Disconnected) => break,
            }
        } else {
            match rx.recv() {
                Ok(m) => Some(m),
                Err(_) => break,
            }
        };
        for msg in first.into_iter().chain(std::iter::from_fn(|| rx.try_recv().ok())) {
            for command in update(&mut app, msg) {
                worker.send(command);
            }
            if app.quit {
                break 'frames;
            }
        }
        if let Ok(dir) = std::env::current_dir() {
            super::map::export_if_asked(&mut app, &dir);
        }
        app.fps = app.animating().then_some(drawn.len() as f64);
    }
    worker.shutdown();
    Ok(())
}
