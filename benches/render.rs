//! Drawing speed: one full 120×36 frame of the explorer into a `TestBackend`.
//!
//! `cargo bench --bench render`; the target is at most 1 ms per frame.

use criterion::{Criterion, criterion_group, criterion_main};
use dicesim_explorer::tui::{App, Theme, render};
use dicesim_explorer::worker::Simulator;
use dicesim_setup::preset::Preset;
use ratatui::Terminal;
use ratatui::backend::TestBackend;

/// A tumbling roll 600 steps in: the die in contact, an energy history with impacts.
fn mid_roll() -> App {
    let preset = Preset::default()
        .with_overrides(&["initial.angular_velocity=[12,-20,6]", "initial.velocity=[30,0,0]"])
        .expect("valid overrides");
    let mut simulator = Simulator::new(&preset).expect("valid preset");
    simulator.advance_steps(600);
    App::new(simulator.snapshot(), Theme::default())
}

fn bench_render(c: &mut Criterion) {
    let app = mid_roll();
    let mut terminal = Terminal::new(TestBackend::new(120, 36)).expect("test backend");
    c.bench_function("render/120x36/mid-roll", |b| {
        b.iter(|| {
            terminal.draw(|f| render(&app, f)).expect("draw");
        })
    });
}

criterion_group!(benches, bench_render);
criterion_main!(benches);
