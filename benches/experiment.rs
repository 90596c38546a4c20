//! Experiment speed: batch throughput per job count, and a 200×100 basin map.
//!
//! `cargo bench --bench experiment`; the README quotes the figures. Throughput is in steps
//! per second (one element = one integrator step), so dividing by the job count gives the
//! per-core speed.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use dicesim_experiment::{Axis, MapSpec, Method, RandomRanges, Rolls, run_batch, run_map};
use dicesim_physics::{InitialCondition, Params};
use std::hint::black_box;
use std::sync::atomic::AtomicBool;
use std::time::Duration;

/// Rolls per batch: long enough that the chunk barriers and the pool start are a small share.
const ROLLS: u64 = 8192;

fn bench_batch(c: &mut Criterion) {
    let params = Params::default();
    let ranges = RandomRanges::default();
    let base = InitialCondition::default();
    let rolls = Rolls::Random {
        ranges: &ranges,
        base: &base,
        seed: 1,
        first: 0,
        count: ROLLS,
    };
    let never = AtomicBool::new(false);
    let steps = run_batch(&params, &rolls, 1, &never, &mut |_| {})
        .unwrap()
        .summary()
        .steps;
    let mut g = c.benchmark_group("batch");
    g.sample_size(10).measurement_time(Duration::from_secs(4));
    g.throughput(Throughput::Elements(steps));
    for jobs in [1, 2] {
        g.bench_function(format!("steps/jobs-{jobs}"), |b| {
            b.iter(|| run_batch(black_box(&params), &rolls, jobs, &never, &mut |_| {}).unwrap())
        });
    }
    g.finish();
}

fn bench_map(c: &mut Criterion) {
    // The paper's defaults (15 cm, no throw) with the spin's x and y components scanned.
    let params = Params::default();
    let base = InitialCondition::default();
    let never = AtomicBool::new(false);
    let mut g = c.benchmark_group("basin-map-200x100");
    g.sample_size(10).measurement_time(Duration::from_secs(8));
    g.throughput(Throughput::Elements(200 * 100));
    for method in [Method::Uniform, Method::Adaptive] {
        let spec = MapSpec {
            x: Axis::parse("initial.angular_velocity.x:-60:60", 200).unwrap(),
            y: Axis::parse("initial.angular_velocity.y:-60:60", 100).unwrap(),
            method,
        };
        g.bench_function(format!("face/{}/jobs-2", method.name()), |b| {
            b.iter(|| run_map(black_box(&params), &base, &spec, 2, &never, &mut |_| {}).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, bench_batch, bench_map);
criterion_main!(benches);
