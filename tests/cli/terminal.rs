//! The explorer under a real pseudo-terminal: whatever ends it (a key, a signal, a panic on
//! any thread), the terminal comes back cooked, on the normal screen, with its cursor shown
//! and mouse reporting off; and `q` answers at once even while rolls millions of steps long
//! are being computed.
#![cfg(unix)]
// Giving the child the pseudo-terminal as its controlling terminal takes a pre_exec hook.
#![allow(unsafe_code)]

use nix::pty::{Winsize, openpty};
use nix::sys::signal::{Signal, kill};
use nix::sys::termios::{LocalFlags, tcgetattr};
use nix::unistd::Pid;
use std::fs::File;
use std::io::{Read, Write};
use std::os::fd::OwnedFd;
use std::os::unix::process::CommandExt;
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Long enough for a loaded machine; a working explorer answers in milliseconds.
const PATIENCE: Duration = Duration::from_secs(20);

struct Explorer {
    child: Child,
    input: File,
    screen: Arc<Mutex<Vec<u8>>>,
    /// Kept open so the terminal's settings can be read after the explorer has gone.
    terminal: OwnedFd,
    _presets: tempfile::TempDir,
}

impl Explorer {
    fn start(args: &[&str], fault: Option<&str>) -> Explorer {
        let size = Winsize {
            ws_row: 36,
            ws_col: 120,
            ws_xpixel: 0,
            ws_ypixel: 0,
        };
        let pty = openpty(Some(&size), None).expect("a pseudo-terminal");
        let presets = tempfile::tempdir().unwrap();
        let mut command = Command::new(env!("CARGO_BIN_EXE_dicesim"));
        command
            .args(args)
            .env("TERM", "xterm-256color")
            .env("DICESIM_PRESETS", presets.path())
            .env_remove("DICESIM_FAULT")
            .current_dir(presets.path())
            .stdin(Stdio::from(pty.slave.try_clone().unwrap()))
            .stdout(Stdio::from(pty.slave.try_clone().unwrap()))
            .stderr(Stdio::from(pty.slave.try_clone().unwrap()));
        if let Some(place) = fault {
            command.env("DICESIM_FAULT", place);
        }
        // SAFETY: only async-signal-safe calls between fork and exec.
        unsafe {
            command.pre_exec(|| {
                nix::unistd::setsid().map_err(std::io::Error::from)?;
                if nix::libc::ioctl(0, nix::libc::TIOCSCTTY, 0) != 0 {
                    return Err(std::io::Error::last_os_error());
                }
                Ok(())
            });
        }
        let child = command.spawn().expect("the explorer starts");
        let master = File::from(pty.master);
        let input = master.try_clone().unwrap();
        let screen = Arc::new(Mutex::new(Vec::new()));
        let sink = screen.clone();
        std::thread::spawn(move || {
            let mut master = master;
            let mut buf = [0u8; 4096];
            while let Ok(n) = master.read(&mut buf) {
                if n == 0 {
                    break;
                }
                sink.lock().unwrap().extend_from_slice(&buf[..n]);
            }
        });
        let explorer = Explorer {
            child,
            input,
            screen,
            terminal: pty.slave,
            _presets: presets,
        };
        // A fault may end it before its first frame, but never before it took the terminal.
        let ready = if fault.is_some() {
            "\x1b[?1049h"
        } else {
            "outcomes of random rolls"
        };
        assert!(
            explorer.wait_for(ready),
            "the explorer never drew: {}",
            explorer.text()
        );
        explorer
    }

    fn text(&self) -> String {
        String::from_utf8_lossy(&self.screen.lock().unwrap()).into_owned()
    }

    fn wait_for(&self, needle: &str) -> bool {
        let end = Instant::now() + PATIENCE;
        while Instant::now() < end {
            if self.text().contains(needle) {
                return true;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        false
    }

    fn keys(&mut self, keys: &str) {
        self.input.write_all(keys.as_bytes()).unwrap();
        self.input.flush().unwrap();
    }

    fn signal(&self, signal: Signal) {
        kill(Pid::from_raw(self.child.id() as i32), signal).unwrap();
    }

    /// Its exit status, or a failed test (after killing it) if it does not end in time.
    fn ended(&mut self, what: &str) -> ExitStatus {
        let end = Instant::now() + PATIENCE;
        while Instant::now() < end {
            if let Some(status) = self.child.try_wait().unwrap() {
                // Let the reader catch the last bytes.
                std::thread::sleep(Duration::from_millis(100));
                return status;
            }
            std::thread::sleep(Duration::from_millis(10));
        }
        let _ = self.child.kill();
        panic!("{what}: the explorer was still running after {PATIENCE:?}");
    }

    /// How many of its threads have a name starting with `prefix` (Linux only; 0 elsewhere).
    fn threads_named(&self, prefix: &str) -> usize {
        let Ok(tasks) = std::fs::read_dir(format!("/proc/{}/task", self.child.id())) else {
            return 0;
        };
        tasks
            .filter_map(|t| std::fs::read_to_string(t.ok()?.path().join("comm")).ok())
            .filter(|name| name.starts_with(prefix))
            .count()
    }

    /// The terminal as the shell gets it back.
    fn assert_restored(&self, what: &str) {
        let modes = tcgetattr(&self.terminal).unwrap().local_flags;
        for flag in [LocalFlags::ICANON, LocalFlags::ECHO, LocalFlags::ISIG] {
            assert!(modes.contains(flag), "{what}: {flag:?} is off: {modes:?}");
        }
        let text = self.text();
        let last = |s: &str| text.rfind(s);
        // The cursor is hidden by the first frame, which a fault may come before; the
        // screen and mouse reporting are taken before anything else runs.
        for (on, off, name, always) in [
            ("\x1b[?1049h", "\x1b[?1049l", "the alternate screen", true),
            ("\x1b[?25l", "\x1b[?25h", "the hidden cursor", false),
            ("\x1b[?1000h", "\x1b[?1000l", "mouse reporting", true),
        ] {
            assert!(!always || last(on).is_some(), "{what}: {name} was never entered");
            assert!(
                last(off).is_some() && last(off) > last(on),
                "{what}: {name} was not undone"
            );
        }
    }
}

#[test]
fn every_ending_signal_restores_the_terminal_and_exits_128_plus_the_signal() {
    for signal in [Signal::SIGTERM, Signal::SIGHUP, Signal::SIGINT, Signal::SIGQUIT] {
        let mut e = Explorer::start(&["tui"], None);
        e.signal(signal);
        let status = e.ended(&format!("{signal}"));
        assert_eq!(status.code(), Some(128 + signal as i32), "{signal}");
        e.assert_restored(&format!("{signal}"));
    }
}

#[test]
fn a_panic_on_any_thread_restores_the_terminal_prints_once_and_ends_the_app() {
    for place in ["ui", "worker", "map", "curve"] {
        let mut e = Explorer::start(&["tui"], Some(place));
        match place {
            "map" => e.keys("\t"),
            // The twin starts its predictability curve.
            "curve" => e.keys("T"),
            _ => {}
        }
        let status = e.ended(place);
        assert_eq!(status.code(), Some(101), "{place}");
        e.assert_restored(place);
        let text = e.text();
        let message = format!("a fault injected in the {place} thread");
        assert_eq!(text.matches(&message).count(), 1, "{place}: {text}");
        assert!(
            text.rfind(&message) > text.rfind("\x1b[?1049l"),
            "{place}: the message was printed on the alternate screen"
        );
    }
}

/// One roll is millions of steps long here (no friction, Δt = 10 µs).
const SLOW: [&str; 5] = ["tui", "--set", "ground.friction=0", "--set", "integrator.dt=1e-5"];

#[test]
fn quit_answers_during_a_batch_of_slow_rolls() {
    let mut e = Explorer::start(&SLOW, None);
    e.keys("b");
    assert!(e.wait_for("batch 0/"), "the batch started");
    e.keys("b");
    assert!(e.wait_for("batch cancelled after 0 of"));
    e.keys(" b");
    std::thread::sleep(Duration::from_millis(300));
    e.keys("q");
    assert_eq!(e.ended("q during a batch").code(), Some(0));
    e.assert_restored("q during a batch");
}

#[test]
fn quit_answers_while_a_slow_map_computes() {
    let mut e = Explorer::start(&SLOW, None);
    e.keys("\t");
    std::thread::sleep(Duration::from_millis(300));
    // Each x asks for another map; each one stops the one before.
    e.keys("xxxxxxxxxx");
    std::thread::sleep(Duration::from_millis(500));
    let maps = e.threads_named("dicesim-map");
    assert!(maps <= 1, "{maps} map threads alive");
    let rolls = e.threads_named("dicesim-roll");
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    assert!(rolls <= cores, "{rolls} roll threads alive on {cores} cores");
    e.keys("\t\tq");
    assert_eq!(e.ended("q during a map").code(), Some(0));
    e.assert_restored("q during a map");
}

#[test]
fn quit_answers_while_the_twin_curve_computes() {
    let mut e = Explorer::start(&SLOW, None);
    // Each T turns the twin on or off: the curve starts, stops, starts again.
    e.keys("TTT");
    assert!(e.wait_for("computing"), "the curve started");
    std::thread::sleep(Duration::from_millis(300));
    let curves = e.threads_named("dicesim-curve");
    assert!(curves <= 1, "{curves} curve threads alive");
    e.keys("q");
    assert_eq!(e.ended("q while the curve computes").code(), Some(0));
    e.assert_restored("q while the curve computes");
}

/// crossterm's reader waited for the end of `ESC [ ?` (what Alt+[ then `?` sends) and of a
/// paste opener forever, swallowing every key after it; now the first becomes the keys it
/// spells once nothing follows, and the second is dropped.
#[test]
fn unfinished_and_unknown_escape_sequences_swallow_no_later_key() {
    let mut e = Explorer::start(&["tui"], None);
    // Alt+[ then `?`, typed as a person would: the `?` (help) arrives on its own.
    e.keys("\x1b[");
    std::thread::sleep(Duration::from_millis(20));
    e.keys("?");
    // The help's own word "scroll" (its bottom border): ratatui writes only the cells that
    // change, so a longer phrase can be split in the byte stream where a cell under it
    // already showed the same character.
    assert!(e.wait_for("scroll"), "the ? after Alt+[ opened the help");
    let before = e.text().len();
    e.keys("?");
    let closed = Instant::now() + PATIENCE;
    while e.text().len() == before && Instant::now() < closed {
        std::thread::sleep(Duration::from_millis(20));
    }
    e.keys("\x1b[200~");
    std::thread::sleep(Duration::from_millis(200));
    e.keys("q");
    assert_eq!(e.ended("q after the two sequences").code(), Some(0));
    e.assert_restored("q after the two sequences");
}

/// A polyhedral die's explorer (a d20 playing and tumbling, a d4 after a random roll) gives
/// the terminal back whole after `q` and after a signal, as the box's does.
#[test]
fn a_polyhedral_die_restores_the_terminal_after_q_and_after_a_signal() {
    for (preset, keys) in [("d20", " "), ("d4", "R")] {
        let mut e = Explorer::start(&["tui", "--preset", preset], None);
        e.keys(keys);
        std::thread::sleep(Duration::from_millis(300));
        e.keys("q");
        assert_eq!(e.ended(&format!("{preset}: q")).code(), Some(0));
        e.assert_restored(&format!("{preset}: q"));
        let mut e = Explorer::start(&["tui", "--preset", preset], None);
        e.keys(keys);
        e.signal(Signal::SIGTERM);
        let status = e.ended(&format!("{preset}: SIGTERM"));
        assert_eq!(status.code(), Some(128 + Signal::SIGTERM as i32), "{preset}");
        e.assert_restored(&format!("{preset}: SIGTERM"));
    }
}
