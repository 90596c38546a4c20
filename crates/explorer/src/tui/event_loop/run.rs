//! The terminal's lifecycle and the event loop: report hooks first, then the terminal,
//! restored on every way out.
//!
//! - `update` does no I/O: the effects it returns (worker commands, listing and saving
//!   presets) are run here, through [`perform`].
//! - Quitting (`q`, Ctrl-C as a key) leaves the loop and restores it.
//! - SIGTERM, SIGHUP, SIGINT and SIGQUIT reach a thread of their own (signal-hook), which
//!   asks the loop to stop, so the terminal is restored and the process exits with 128 +
//!   the signal; should the loop not answer within half a second, that thread restores the
//!   terminal and exits itself.
//! - A panic on any thread restores the terminal first, then prints its message once, then
//!   ends the whole process (exit status 101): a half-alive explorer drawing over the
//!   message helps nobody.
//!
//! Drawing holds [`SCREEN`], and whoever restores takes it first and never gives it back,
//! so no frame lands after the terminal was given back to the shell.

use crate::lesson::Lesson;
use crate::tui::event_loop::effects::perform;
use crate::tui::input::lesson_keys::open_step;
use crate::tui::input::update::update;
use crate::tui::render::screen::render;
use crate::tui::state::app::App;
use crate::tui::state::lesson_run::LessonRun;
use crate::tui::state::messages::Msg;
use crate::tui::vocabulary::theme::Theme;
use crate::worker::{Simulator, Worker};
use dicesim_physics::ParamError;
use dicesim_setup::preset::Preset;
use ratatui::DefaultTerminal;
use ratatui::crossterm::cursor::Show;
use ratatui::crossterm::event::{DisableMouseCapture, EnableMouseCapture};
use ratatui::crossterm::execute;
use ratatui::layout::Rect;
use signal_hook::consts::{SIGHUP, SIGINT, SIGQUIT, SIGTERM};
use signal_hook::iterator::Signals;
use std::collections::VecDeque;
use std::io::stdout;
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, channel};
use std::sync::{Mutex, TryLockError};
use std::time::{Duration, Instant};

/// Longest wait between frames while something moves (the worker's ticks usually come first).
const FRAME: Duration = Duration::from_millis(33);

/// Held while a frame is drawn, and for good once the terminal has been restored.
static SCREEN: Mutex<()> = Mutex::new(());

/// Mouse reporting off, the cursor shown, raw mode off, the normal screen back. Waits
/// (briefly: a panic mid-frame holds it on this very thread) for any frame being drawn.
fn restore_for_good() {
    let deadline = Instant::now() + Duration::from_millis(200);
    let guard = loop {
        match SCREEN.try_lock() {
            Ok(g) => break Some(g),
            Err(TryLockError::Poisoned(p)) => break Some(p.into_inner()),
            Err(TryLockError::WouldBlock) if Instant::now() < deadline => {
                std::thread::sleep(Duration::from_millis(5))
            }
            Err(TryLockError::WouldBlock) => break None,
        }
    };
    // ratatui's restore turns neither mouse reporting off nor the cursor back on.
    let _ = execute!(stdout(), DisableMouseCapture, Show);
    ratatui::restore();
    std::mem::forget(guard);
}

/// Why the explorer could not open, or stopped: each names what it was doing and keeps the
/// cause it failed on.
#[derive(Debug, thiserror::Error)]
pub enum ExplorerError {
    /// The preset's setup is outside what the physics accepts.
    #[error("the preset cannot be simulated: {0}")]
    Setup(#[source] ParamError),
    /// The signal thread could not be set up.
    #[error("cannot catch signals: {0}")]
    Signals(#[source] std::io::Error),
    /// Neither standard input nor `/dev/tty` could be read.
    #[error("cannot read the terminal: {0}")]
    Input(#[source] std::io::Error),
    /// Drawing on, or asking the size of, the terminal failed.
    #[error("the terminal failed: {0}")]
    Terminal(#[source] std::io::Error),
}

/// The signals that end the explorer: a terminal closing, `kill`, Ctrl-C or Ctrl-\ sent
/// from outside (inside, raw mode turns those keys into key presses).
const ENDING_SIGNALS: [i32; 4] = [SIGTERM, SIGHUP, SIGINT, SIGQUIT];

/// Opens the explorer on `preset` and runs it until the user quits; a signal ends the
/// process from here with 128 + the signal, after restoring the terminal.
/// `lesson` is what the lesson keys walk; with `walk` its first step opens at once
/// (`dicesim tui --lesson`).
pub fn run(preset: &Preset, theme: Theme, lesson: Lesson, walk: bool) -> Result<(), ExplorerError> {
    let simulator = Simulator::new(preset).map_err(ExplorerError::Setup)?;
    let mut signals = Signals::new(ENDING_SIGNALS).map_err(ExplorerError::Signals)?;
    let signal_handle = signals.handle();
    let mut terminal = ratatui::init();
    let _ = execute!(stdout(), EnableMouseCapture);
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        restore_for_good();
        previous(info);
        std::process::exit(101);
    }));
    let (tx, rx) = channel::<Msg>();
    let to_loop = tx.clone();
    std::thread::Builder::new()
        .name("dicesim-signals".to_string())
        .spawn(move || {
            if let Some(signal) = signals.forever().next() {
                let _ = to_loop.send(Msg::Signal(signal));
                std::thread::sleep(Duration::from_millis(500));
                restore_for_good();
                std::process::exit(128 + signal);
            }
        })
        .map_err(ExplorerError::Signals)?;
    let result = event_loop(&mut terminal, simulator, theme, (lesson, walk), tx, rx);
    restore_for_good();
    signal_handle.close();
    match result {
        Ok(Some(signal)) => std::process::exit(128 + signal),
        Ok(None) => Ok(()),
        Err(e) => Err(e),
    }
}

/// Runs until the user quits (`None`) or a signal arrives (`Some(signal)`).
fn event_loop(
    terminal: &mut DefaultTerminal,
    mut simulator: Simulator,
    theme: Theme,
    (lesson, walk): (Lesson, bool),
    tx: Sender<Msg>,
    rx: Receiver<Msg>,
) -> Result<Option<i32>, ExplorerError> {
    let mut app = App::new(simulator.snapshot(), theme);
    app.store = dicesim_setup::preset::Store::from_env();
    app.lesson = Some(LessonRun::new(lesson));
    let size = terminal.size().map_err(ExplorerError::Terminal)?;
    app.screen = Rect::new(0, 0, size.width, size.height);
    let maps = tx.clone();
    let worker = Worker::spawn_with_maps(simulator, tx.clone(), move |m| maps.send(Msg::from(m)).is_ok());
    if walk {
        open_step(&mut app, 0);
        for effect in app.outbox.take() {
            if let Some(command) = perform(&mut app, effect) {
                worker.send(command);
            }
        }
    }
    // The input threads block reading the terminal for the life of the process.
    crate::tui::event_loop::tty::spawn(move |ev| tx.send(Msg::Input(ev)).is_ok())
        .map_err(ExplorerError::Input)?;
    let mut drawn: VecDeque<Instant> = VecDeque::new();
    'frames: loop {
        {
            let _drawing = SCREEN.lock().unwrap_or_else(|p| p.into_inner());
            terminal
                .draw(|f| render(&app, f))
                .map_err(ExplorerError::Terminal)?;
        }
        crate::fault::inject("ui");
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
            if let Msg::Signal(signal) = msg {
                worker.shutdown();
                return Ok(Some(signal));
            }
            for effect in update(&mut app, msg) {
                if let Some(command) = perform(&mut app, effect) {
                    worker.send(command);
                }
            }
            if app.quit {
                break 'frames;
            }
        }
        app.fps = app.animating().then_some(drawn.len() as f64);
    }
    worker.shutdown();
    Ok(None)
}
