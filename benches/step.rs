//! Physics speed: steps per second of one roll, rolls per second of random rolls.
//!
//! `cargo bench --bench step`; the README quotes the figures.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use dicesim_experiment::{RandomRanges, roll_record};
use dicesim_physics::{FrictionLaw, InitialCondition, Params, Simulation};
use dicesim_setup::random::RandomDraws;
use std::hint::black_box;

/// A paper-default roll with some spin (so contact, friction and rotation all take part).
fn spinning_roll() -> InitialCondition {
    InitialCondition {
        angular_velocity: [20.0, -35.0, 10.0],
        velocity: [30.0, -10.0, 0.0],
        ..Default::default()
    }
}

fn bench_steps(c: &mut Criterion) {
    let mut g = c.benchmark_group("physics");
    for (label, law) in [
        ("per-corner", FrictionLaw::PerCorner),
        ("whole-die-norm", FrictionLaw::WholeDieNorm),
    ] {
        let mut params = Params::default();
        params.ground.friction_law = law;
        let initial = spinning_roll();
        let steps = Simulation::new(&params, &initial).unwrap().run_to_end().steps;
        g.throughput(Throughput::Elements(steps));
        g.bench_function(format!("roll-steps/{label}"), |b| {
            b.iter(|| {
                Simulation::new(black_box(&params), black_box(&initial))
                    .unwrap()
                    .run_to_end()
            })
        });
    }
    // A loaded die (the `loaded-corner` preset's half gram at corner 8): its tensor and spin
    // are rebuilt every step, in flight too.
    let mut params = Params::default();
    params.die.extra_corner_mass[7] = 0.5;
    let initial = spinning_roll();
    let steps = Simulation::new(&params, &initial).unwrap().run_to_end().steps;
    g.throughput(Throughput::Elements(steps));
    g.bench_function("roll-steps/loaded", |b| {
        b.iter(|| {
            Simulation::new(black_box(&params), black_box(&initial))
                .unwrap()
                .run_to_end()
        })
    });
    // Random rolls from the default ranges: rolls per second on one core.
    let params = Params::default();
    let ranges = RandomRanges::default();
    let base = InitialCondition::default();
    const ROLLS: u64 = 64;
    g.throughput(Throughput::Elements(ROLLS));
    g.bench_function("random-rolls", |b| {
        b.iter(|| {
            (0..ROLLS)
                .map(|i| roll_record(&params, &ranges.draw(&base, 1, i), i).outcome.steps)
                .sum::<u64>()
        })
    });
    g.finish();
}

criterion_group!(benches, bench_steps);
criterion_main!(benches);
