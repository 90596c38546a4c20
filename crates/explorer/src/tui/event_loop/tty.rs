//! The terminal's bytes, read by the explorer itself and turned into events.
//!
//! crossterm's own reader waits for the end of any sequence it has begun, so `Alt+[` then
//! `?` (the bytes `ESC [ ?`) or a bracketed-paste opener (`ESC [ 2 0 0 ~`) swallowed every
//! later key until a byte it was waiting for arrived. Here a sequence that does not complete
//! within [`WAIT`] is delivered as the keys its bytes spell (`Alt+[`, `?`), and a complete
//! sequence the explorer never asked for (paste markers, focus reports, kitty keys) is
//! dropped, so nothing typed afterwards is lost.
//!
//! [`Decoder`] is pure (bytes in, events out); [`spawn`] owns the threads that feed it.

use ratatui::crossterm::event::{
    Event, KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use std::io::{IsTerminal, Read};
use std::sync::mpsc::{RecvTimeoutError, channel};
use std::time::Duration;

/// How long an unfinished sequence waits for its next byte. A terminal writes a whole
/// sequence at once, so its bytes arrive within microseconds; people type ~10× slower.
pub(crate) const WAIT: Duration = Duration::from_millis(50);

const ESC: u8 = 0x1b;

/// Bytes in, events out; an unfinished sequence is kept until more bytes or [`flush`].
///
/// [`flush`]: Decoder::flush
#[derive(Debug, Default)]
pub(crate) struct Decoder {
    pending: Vec<u8>,
}

/// What the bytes at the front of the buffer decode to.
enum Decoded {
    /// `len` bytes read: an event, or nothing (a sequence the explorer has no use for).
    Done(Option<Event>, usize),
    /// The bytes so far begin a sequence that is not finished yet.
    Unfinished,
}

impl Decoder {
    /// The events `bytes` complete; an unfinished sequence at the end waits for more.
    pub(crate) fn feed(&mut self, bytes: &[u8]) -> Vec<Event> {
        self.pending.extend_from_slice(bytes);
        self.drain(false)
    }

    /// Nothing more came within [`WAIT`]: what is pending is delivered as keys.
    pub(crate) fn flush(&mut self) -> Vec<Event> {
        self.drain(true)
    }

    /// Whether bytes are waiting for the rest of their sequence.
    pub(crate) fn waiting(&self) -> bool {
        !self.pending.is_empty()
    }

    fn drain(&mut self, last: bool) -> Vec<Event> {
        let mut events = Vec::new();
        let mut at = 0;
        while at < self.pending.len() {
            match step(&self.pending[at..], last) {
                Decoded::Done(event, len) => {
                    events.extend(event);
                    at += len;
                }
                Decoded::Unfinished => break,
            }
        }
        self.pending.drain(..at);
        events
    }
}

fn key(code: KeyCode, modifiers: KeyModifiers) -> Option<Event> {
    Some(Event::Key(KeyEvent::new(code, modifiers)))
}

/// Decodes the front of `b`; with `last`, nothing more is coming, so an unfinished
/// sequence becomes the keys its bytes spell.
fn step(b: &[u8], last: bool) -> Decoded {
    match b[0] {
        ESC => escape(b, last),
        _ => plain(b, last),
    }
}

/// A byte or UTF-8 character outside any sequence.
fn plain(b: &[u8], last: bool) -> Decoded {
    let none = KeyModifiers::NONE;
    let event = match b[0] {
        b'\r' | b'\n' => key(KeyCode::Enter, none),
        b'\t' => key(KeyCode::Tab, none),
        0x7f | 0x08 => key(KeyCode::Backspace, none),
        0 => key(KeyCode::Char(' '), KeyModifiers::CONTROL),
        c @ 0x01..=0x1a => key(KeyCode::Char((c - 1 + b'a') as char), KeyModifiers::CONTROL),
        c @ 0x1c..=0x1f => key(KeyCode::Char((c - 0x1c + b'4') as char), KeyModifiers::CONTROL),
        _ => return utf8(b, last),
    };
    Decoded::Done(event, 1)
}

fn utf8(b: &[u8], last: bool) -> Decoded {
    let len = match b[0] {
        0x00..=0x7f => 1,
        0xc0..=0xdf => 2,
        0xe0..=0xef => 3,
        0xf0..=0xf7 => 4,
        // A stray continuation byte or worse: nothing a key could be made of.
        _ => return Decoded::Done(None, 1),
    };
    if b.len() < len {
        return if last {
            Decoded::Done(None, b.len())
        } else {
            Decoded::Unfinished
        };
    }
    match std::str::from_utf8(&b[..len]).ok().and_then(|s| s.chars().next()) {
        Some(c) => {
            let shift = if c.is_uppercase() {
                KeyModifiers::SHIFT
            } else {
                KeyModifiers::NONE
            };
            Decoded::Done(key(KeyCode::Char(c), shift), len)
        }
        None => Decoded::Done(None, 1),
    }
}

/// `ESC` alone, `ESC` + a key (that key with Alt), `ESC O x` and `ESC [ …`.
fn escape(b: &[u8], last: bool) -> Decoded {
    let Some(&second) = b.get(1) else {
        return if last {
            Decoded::Done(key(KeyCode::Esc, KeyModifiers::NONE), 1)
        } else {
            Decoded::Unfinished
        };
    };
    match second {
        // Esc pressed twice: the first is a key of its own.
        ESC => Decoded::Done(key(KeyCode::Esc, KeyModifiers::NONE), 1),
        b'[' => match csi(b) {
            Decoded::Unfinished if last => alt(b, last),
            step => step,
        },
        b'O' => match b.get(2) {
            None if last => alt(b, last),
            None => Decoded::Unfinished,
            Some(&c) => Decoded::Done(ss3(c), 3),
        },
        _ => alt(b, last),
    }
}

/// `ESC` then a key: that key with Alt held.
fn alt(b: &[u8], last: bool) -> Decoded {
    match plain(&b[1..], last) {
        Decoded::Done(Some(Event::Key(mut k)), len) => {
            k.modifiers |= KeyModifiers::ALT;
            Decoded::Done(Some(Event::Key(k)), len + 1)
        }
        Decoded::Done(other, len) => Decoded::Done(other, len + 1),
        Decoded::Unfinished => Decoded::Unfinished,
    }
}

/// `ESC O x`: the cursor keys and F1–F4 in application mode.
fn ss3(c: u8) -> Option<Event> {
    let code = match c {
        b'A' => KeyCode::Up,
        b'B' => KeyCode::Down,
        b'C' => KeyCode::Right,
        b'D' => KeyCode::Left,
        b'H' => KeyCode::Home,
        b'F' => KeyCode::End,
        b'P'..=b'S' => KeyCode::F(1 + c - b'P'),
        _ => return None,
    };
    key(code, KeyModifiers::NONE)
}

/// `ESC [` parameters, intermediates, one final byte (ECMA-48), or the three raw bytes
/// of an X10 mouse report after `ESC [ M`.
fn csi(b: &[u8]) -> Decoded {
    if b.get(2) == Some(&b'M') {
        return match b.get(3..6) {
            Some(&[cb, cx, cy]) => {
                let (column, row) = (cx.saturating_sub(33), cy.saturating_sub(33));
                Decoded::Done(mouse(cb.wrapping_sub(32), column.into(), row.into(), false), 6)
            }
            _ => Decoded::Unfinished,
        };
    }
    for (i, &c) in b.iter().enumerate().skip(2) {
        match c {
            0x20..=0x3f => continue,
            0x40..=0x7e => return Decoded::Done(csi_event(&b[2..i], c), i + 1),
            // Not a sequence after all (Alt+[ then Esc or Enter): what came so far is keys.
            _ => return alt(&b[..2], true),
        }
    }
    Decoded::Unfinished
}

/// A complete `ESC [ params final`; `None` for those the explorer never asked for.
fn csi_event(params: &[u8], last: u8) -> Option<Event> {
    let text = std::str::from_utf8(params).ok()?;
    if let Some(sgr) = text.strip_prefix('<') {
        let mut n = sgr.split(';').map(|p| p.parse::<u16>().ok());
        let (Some(Some(cb)), Some(Some(cx)), Some(Some(cy))) = (n.next(), n.next(), n.next()) else {
            return None;
        };
        let cb = u8::try_from(cb).ok()?;
        return mouse(cb, cx.saturating_sub(1), cy.saturating_sub(1), last == b'm');
    }
    let numbers: Vec<u16> = if text.is_empty() {
        Vec::new()
    } else {
        text.split(';')
            .map(|p| p.split(':').next().unwrap_or("").parse().ok())
            .collect::<Option<_>>()?
    };
    if last == b'M' {
        // rxvt's mouse report: cb;cx;cy M.
        let [cb, cx, cy] = numbers[..] else {
            return None;
        };
        let cb = u8::try_from(cb.checked_sub(32)?).ok()?;
        return mouse(cb, cx.saturating_sub(1), cy.saturating_sub(1), false);
    }
    let modifiers = numbers.get(1).map_or(KeyModifiers::NONE, |&m| modifier_mask(m));
    let code = match last {
        b'A' => KeyCode::Up,
        b'B' => KeyCode::Down,
        b'C' => KeyCode::Right,
        b'D' => KeyCode::Left,
        b'H' => KeyCode::Home,
        b'F' => KeyCode::End,
        b'Z' => return key(KeyCode::BackTab, KeyModifiers::SHIFT | modifiers),
        b'P'..=b'S' => KeyCode::F(1 + last - b'P'),
        b'~' => match numbers.first()? {
            1 | 7 => KeyCode::Home,
            2 => KeyCode::Insert,
            3 => KeyCode::Delete,
            4 | 8 => KeyCode::End,
            5 => KeyCode::PageUp,
            6 => KeyCode::PageDown,
            n @ 11..=15 => KeyCode::F((n - 10) as u8),
            n @ 17..=21 => KeyCode::F((n - 11) as u8),
            n @ 23..=26 => KeyCode::F((n - 12) as u8),
            n @ 28..=29 => KeyCode::F((n - 13) as u8),
            n @ 31..=34 => KeyCode::F((n - 14) as u8),
            // 200~ and 201~ (paste markers, never enabled here) and the rest.
            _ => return None,
        },
        _ => return None,
    };
    // Private sequences (`ESC [ ? …`, `ESC [ > …`) are replies, not keys.
    if text.starts_with(['?', '>', '=']) {
        return None;
    }
    key(code, modifiers)
}

/// xterm's modifier parameter: 1 + a bit mask.
fn modifier_mask(m: u16) -> KeyModifiers {
    let bits = m.saturating_sub(1);
    let mut modifiers = KeyModifiers::NONE;
    for (bit, modifier) in [
        (1, KeyModifiers::SHIFT),
        (2, KeyModifiers::ALT),
        (4, KeyModifiers::CONTROL),
        (8, KeyModifiers::SUPER),
    ] {
        if bits & bit != 0 {
            modifiers |= modifier;
        }
    }
    modifiers
}

/// A mouse report's button byte: low bits the button, 32 a drag, 64 the wheel.
fn mouse(cb: u8, column: u16, row: u16, released: bool) -> Option<Event> {
    let button = match cb & 0b11 {
        0 => MouseButton::Left,
        1 => MouseButton::Middle,
        _ => MouseButton::Right,
    };
    let drag = cb & 32 != 0;
    let kind = match (cb & 64 != 0, cb & 0b11, drag) {
        (true, 0, _) => MouseEventKind::ScrollUp,
        (true, 1, _) => MouseEventKind::ScrollDown,
        (true, 2, _) => MouseEventKind::ScrollLeft,
        (true, _, _) => MouseEventKind::ScrollRight,
        (false, 3, true) => MouseEventKind::Moved,
        (false, 3, false) => MouseEventKind::Up(MouseButton::Left),
        (false, _, _) if released => MouseEventKind::Up(button),
        (false, _, true) => MouseEventKind::Drag(button),
        (false, _, false) => MouseEventKind::Down(button),
    };
    let mut modifiers = KeyModifiers::NONE;
    for (bit, modifier) in [
        (4, KeyModifiers::SHIFT),
        (8, KeyModifiers::ALT),
        (16, KeyModifiers::CONTROL),
    ] {
        if cb & bit != 0 {
            modifiers |= modifier;
        }
    }
    Some(Event::Mouse(MouseEvent {
        kind,
        column,
        row,
        modifiers,
    }))
}

/// Starts the threads that read the terminal and send its events to `send` until it
/// returns false: one blocks reading bytes, one decodes them (flushing after [`WAIT`]),
/// one turns SIGWINCH into a resize. They end with the process.
pub(crate) fn spawn(send: impl Fn(Event) -> bool + Send + Clone + 'static) -> std::io::Result<()> {
    let mut source: Box<dyn Read + Send> = if std::io::stdin().is_terminal() {
        Box::new(std::io::stdin())
    } else {
        Box::new(std::fs::File::open("/dev/tty")?)
    };
    let (bytes_tx, bytes_rx) = channel::<Vec<u8>>();
    std::thread::Builder::new()
        .name("dicesim-tty".to_string())
        .spawn(move || {
            let mut buf = [0u8; 1024];
            while let Ok(n) = source.read(&mut buf) {
                if n == 0 || bytes_tx.send(buf[..n].to_vec()).is_err() {
                    break;
                }
            }
        })?;
    let keys = send.clone();
    std::thread::Builder::new()
        .name("dicesim-input".to_string())
        .spawn(move || {
            let mut decoder = Decoder::default();
            loop {
                let events = if decoder.waiting() {
                    match bytes_rx.recv_timeout(WAIT) {
                        Ok(bytes) => decoder.feed(&bytes),
                        Err(RecvTimeoutError::Timeout) => decoder.flush(),
                        Err(RecvTimeoutError::Disconnected) => break,
                    }
                } else {
                    match bytes_rx.recv() {
                        Ok(bytes) => decoder.feed(&bytes),
                        Err(_) => break,
                    }
                };
                if !events.into_iter().all(&keys) {
                    break;
                }
            }
        })?;
    let mut winch = signal_hook::iterator::Signals::new([signal_hook::consts::SIGWINCH])?;
    std::thread::Builder::new()
        .name("dicesim-resize".to_string())
        .spawn(move || {
            for _ in winch.forever() {
                let Ok((w, h)) = ratatui::crossterm::terminal::size() else {
                    continue;
                };
                if !send(Event::Resize(w, h)) {
                    break;
                }
            }
        })?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn k(code: KeyCode, modifiers: KeyModifiers) -> Event {
        Event::Key(KeyEvent::new(code, modifiers))
    }
    fn c(ch: char) -> Event {
        k(KeyCode::Char(ch), KeyModifiers::NONE)
    }

    #[test]
    fn an_unfinished_csi_becomes_its_keys_after_the_wait_and_later_keys_pass() {
        let mut d = Decoder::default();
        assert_eq!(d.feed(b"\x1b["), vec![]);
        assert_eq!(d.feed(b"?"), vec![]);
        assert!(d.waiting());
        assert_eq!(d.flush(), vec![k(KeyCode::Char('['), KeyModifiers::ALT), c('?')]);
        assert_eq!(d.feed(b"q"), vec![c('q')]);
        assert!(!d.waiting());
    }

    #[test]
    fn a_paste_opener_is_dropped_and_what_follows_is_keys() {
        let mut d = Decoder::default();
        assert_eq!(d.feed(b"\x1b[200~q"), vec![c('q')]);
        assert_eq!(d.feed(b"\x1b[201~"), vec![]);
        // Focus reports and device replies, never asked for, are dropped as well.
        assert_eq!(d.feed(b"\x1b[I\x1b[?1;2c\x1b[?1u y"), vec![c(' '), c('y')]);
    }

    #[test]
    fn esc_alone_waits_then_is_esc_and_esc_then_a_key_is_alt() {
        let mut d = Decoder::default();
        assert_eq!(d.feed(b"\x1b"), vec![]);
        assert_eq!(d.flush(), vec![k(KeyCode::Esc, KeyModifiers::NONE)]);
        assert_eq!(d.feed(b"\x1bx"), vec![k(KeyCode::Char('x'), KeyModifiers::ALT)]);
        assert_eq!(d.feed(b"\x1b\x1b"), vec![k(KeyCode::Esc, KeyModifiers::NONE)]);
        assert_eq!(d.flush(), vec![k(KeyCode::Esc, KeyModifiers::NONE)]);
        // Alt+[ then Enter is not a sequence: both keys arrive at once.
        assert_eq!(
            d.feed(b"\x1b[\r"),
            vec![
                k(KeyCode::Char('['), KeyModifiers::ALT),
                k(KeyCode::Enter, KeyModifiers::NONE)
            ]
        );
    }

    #[test]
    fn keys_the_explorer_uses_decode_as_crossterm_names_them() {
        let mut d = Decoder::default();
        let none = KeyModifiers::NONE;
        assert_eq!(
            d.feed(b"\x1b[A\x1bOB\x1b[1;5C\x1b[D\x1b[Z\t\x7f\x1b[5~\x1b[6~\x1b[3~\x1b[15~\x03T\xc3\xa9"),
            vec![
                k(KeyCode::Up, none),
                k(KeyCode::Down, none),
                k(KeyCode::Right, KeyModifiers::CONTROL),
                k(KeyCode::Left, none),
                k(KeyCode::BackTab, KeyModifiers::SHIFT),
                k(KeyCode::Tab, none),
                k(KeyCode::Backspace, none),
                k(KeyCode::PageUp, none),
                k(KeyCode::PageDown, none),
                k(KeyCode::Delete, none),
                k(KeyCode::F(5), none),
                k(KeyCode::Char('c'), KeyModifiers::CONTROL),
                k(KeyCode::Char('T'), KeyModifiers::SHIFT),
                c('é'),
            ]
        );
    }

    #[test]
    fn a_character_split_across_reads_waits_for_its_rest() {
        let mut d = Decoder::default();
        assert_eq!(d.feed(b"\xc3"), vec![]);
        assert_eq!(d.feed(b"\xa9"), vec![c('é')]);
        assert_eq!(d.feed(b"\x1b[1;"), vec![]);
        assert_eq!(d.feed(b"2A"), vec![k(KeyCode::Up, KeyModifiers::SHIFT)]);
    }

    #[test]
    fn mouse_reports_decode_with_zero_based_cells() {
        let mut d = Decoder::default();
        let at = |kind, column, row| {
            Event::Mouse(MouseEvent {
                kind,
                column,
                row,
                modifiers: KeyModifiers::NONE,
            })
        };
        assert_eq!(
            d.feed(b"\x1b[<0;10;5M\x1b[<32;11;5M\x1b[<0;11;5m\x1b[<64;1;1M\x1b[<65;1;1M\x1b[M #!"),
            vec![
                at(MouseEventKind::Down(MouseButton::Left), 9, 4),
                at(MouseEventKind::Drag(MouseButton::Left), 10, 4),
                at(MouseEventKind::Up(MouseButton::Left), 10, 4),
                at(MouseEventKind::ScrollUp, 0, 0),
                at(MouseEventKind::ScrollDown, 0, 0),
                at(MouseEventKind::Down(MouseButton::Left), 2, 0),
            ]
        );
    }
}
