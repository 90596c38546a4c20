//! `dicesim bench`: both engines on the same rolls in one process, as ratios.
//!
//! Wall-clock figures on a shared machine drift with the other load, so every comparison
//! alternates its two sides round by round and reports the median of the per-round ratios.

use super::{CliError, SetupArgs};
use clap::Args;
use dicesim_experiment::{Axis, Engine, MapSpec, Method, Rolls, RunOptions, run_map_with, stream_batch};
use dicesim_physics::{InitialCondition, Params};
use std::io::Write;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

#[derive(Debug, Args)]
pub struct BenchArgs {
    #[command(flatten)]
    pub setup: SetupArgs,
    /// Rolls per timed batch (drawn from the preset's `[random]` ranges).
    #[arg(long, value_name = "N", default_value_t = 20_000)]
    pub rolls: u64,
    /// Rounds per comparison; each round times both sides once, in alternating order.
    #[arg(long, value_name = "R", default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..))]
    pub rounds: u64,
    /// Skip the basin-map timing.
    #[arg(long)]
    pub no_map: bool,
}

/// The median of `xs` (not empty).
fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    let n = xs.len();
    if n % 2 == 1 {
        xs[n / 2]
    } else {
        0.5 * (xs[n / 2 - 1] + xs[n / 2])
    }
}

/// Times `a` and `b` over `rounds` rounds, alternating which goes first; returns the
/// medians of their seconds and of the ratio `time(b) / time(a)` per round.
fn compare(rounds: u64, a: &mut dyn FnMut(), b: &mut dyn FnMut()) -> (f64, f64, f64) {
    let time = |f: &mut dyn FnMut()| {
        let t = Instant::now();
        f();
        t.elapsed().as_secs_f64()
    };
    let (mut ta, mut tb, mut ratio) = (Vec::new(), Vec::new(), Vec::new());
    for round in 0..rounds {
        let (x, y) = if round % 2 == 0 {
            let x = time(a);
            (x, time(b))
        } else {
            let y = time(b);
            (time(a), y)
        };
        ta.push(x);
        tb.push(y);
        ratio.push(y / x);
    }
    (median(ta), median(tb), median(ratio))
}

pub fn run(args: &BenchArgs) -> Result<(), CliError> {
    let preset = args.setup.resolve()?;
    let params = preset.params();
    params.validate()?;
    let rolls = Rolls::Random {
        ranges: &preset.random,
        base: &preset.initial,
        seed: preset.random.seed,
        first: 0,
        count: args.rolls,
    };
    let never = AtomicBool::new(false);
    let steps = std::cell::Cell::new(0u64);
    let batch = |jobs: usize, engine: Engine| {
        let options = RunOptions { jobs, engine };
        let run = stream_batch(&params, &rolls, &options, &never, &mut |_| Ok(()))
            .expect("validated parameters and ranges");
        steps.set(run.summary.steps);
    };
    let mut out = std::io::stdout().lock();
    writeln!(
        out,
        "{} rolls of the `{}` preset, {} rounds per comparison (medians; ratios per round)",
        args.rolls, preset.name, args.rounds
    )?;
    if Engine::Lanes.resolve() != Engine::Lanes {
        writeln!(
            out,
            "this CPU has no AVX2: the lane engine runs as the scalar one"
        )?;
    }
    let (scalar, lanes, ratio) = compare(args.rounds, &mut || batch(1, Engine::Scalar), &mut || {
        batch(1, Engine::Lanes)
    });
    let rate = |s: f64| steps.get() as f64 / s / 1e6;
    writeln!(
        out,
        "one core     scalar {scalar:.3} s ({:.1} M steps/s), lanes {lanes:.3} s ({:.1} M steps/s): lanes {:.2}× scalar",
        rate(scalar),
        rate(lanes),
        1.0 / ratio
    )?;
    out.flush()?;
    let (one, two, ratio) = compare(args.rounds, &mut || batch(1, Engine::Lanes), &mut || {
        batch(2, Engine::Lanes)
    });
    writeln!(
        out,
        "lanes, jobs  1 job {one:.3} s, 2 jobs {two:.3} s: 2 jobs {:.2}× one job",
        1.0 / ratio
    )?;
    out.flush()?;
    if !args.no_map {
        bench_map(&mut out, &params, &preset.initial, args.rounds)?;
    }
    Ok(())
}

/// The paper's 200×100 face map at the preset's height, spin x and y over ±60 rad/s, on
/// 2 threads: lanes against scalar, and the method the adaptive map chose.
fn bench_map(
    out: &mut impl Write,
    params: &Params,
    base: &InitialCondition,
    rounds: u64,
) -> Result<(), CliError> {
    let spec = |method| MapSpec {
        x: Axis::parse("initial.angular_velocity.x:-60:60", 200).expect("a valid axis"),
        y: Axis::parse("initial.angular_velocity.y:-60:60", 100).expect("a valid axis"),
        method,
    };
    let never = AtomicBool::new(false);
    let map = |method, engine| {
        let options = RunOptions { jobs: 2, engine };
        run_map_with(params, base, &spec(method), &options, &never, &mut |_| {}).expect("a valid map")
    };
    let (scalar, lanes, ratio) = compare(
        rounds,
        &mut || drop(map(Method::Uniform, Engine::Scalar)),
        &mut || drop(map(Method::Uniform, Engine::Lanes)),
    );
    writeln!(
        out,
        "200×100 map  {} cm, uniform, 2 jobs: scalar {scalar:.3} s, lanes {lanes:.3} s ({:.2}×)",
        base.height,
        1.0 / ratio
    )?;
    let adaptive = map(Method::Adaptive, Engine::Lanes);
    let (uniform, chosen, _) = compare(
        rounds,
        &mut || drop(map(Method::Uniform, Engine::Lanes)),
        &mut || drop(map(Method::Adaptive, Engine::Lanes)),
    );
    writeln!(
        out,
        "             adaptive, lanes: {chosen:.3} s against uniform {uniform:.3} s; {}",
        adaptive.method_report()
    )?;
    Ok(())
}
