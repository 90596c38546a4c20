//! Faults on purpose, for the tests that check the terminal survives a panic on any thread.
//!
//! In a debug build (tests included), `DICESIM_FAULT=<place>` makes [`inject`] panic at that
//! place: `ui` (the event loop, after the first frame), `worker` (the simulation thread,
//! after its first snapshot), `map` (a basin map's thread, as it starts) or `curve` (the
//! thread of the twin's predictability curve, as it starts). Release builds compile it away.

/// Panics here if `DICESIM_FAULT` names `place` (debug builds only).
pub(crate) fn inject(place: &str) {
    #[cfg(debug_assertions)]
    if std::env::var("DICESIM_FAULT").is_ok_and(|v| v == place) {
        panic!("a fault injected in the {place} thread (DICESIM_FAULT={place})");
    }
    #[cfg(not(debug_assertions))]
    let _ = place;
}
