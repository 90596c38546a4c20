//! `dicesim bench`: both engines on the same rolls in one process, as ratios (timed by the
//! experiment crate's `bench`, each comparison the median of rounds in alternating order).

use super::args::SetupArgs;
use super::error::CliError;
use clap::Args;
use dicesim_experiment::{Engine, Method, Rolls, bench};
use dicesim_physics::{InitialCondition, Params};
use std::io::Write;

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
    let steps = std::cell::Cell::new(0u64);
    let batch = |jobs: usize, engine: Engine| steps.set(bench::batch_steps(&params, &rolls, jobs, engine));
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
    let engines = bench::compare(args.rounds, &mut || batch(1, Engine::Scalar), &mut || {
        batch(1, Engine::Lanes)
    });
    let (scalar, lanes) = (engines.a_s, engines.b_s);
    let rate = |s: f64| steps.get() as f64 / s / 1e6;
    writeln!(
        out,
        "one core     scalar {scalar:.3} s ({:.1} M steps/s), lanes {lanes:.3} s ({:.1} M steps/s): lanes {:.2}× scalar",
        rate(scalar),
        rate(lanes),
        1.0 / engines.ratio
    )?;
    out.flush()?;
    let jobs = bench::compare(args.rounds, &mut || batch(1, Engine::Lanes), &mut || {
        batch(2, Engine::Lanes)
    });
    writeln!(
        out,
        "lanes, jobs  1 job {:.3} s, 2 jobs {:.3} s: 2 jobs {:.2}× one job",
        jobs.a_s,
        jobs.b_s,
        1.0 / jobs.ratio
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
    let map = |method, engine| drop(bench::paper_map(params, base, method, engine));
    let engines = bench::compare(rounds, &mut || map(Method::Uniform, Engine::Scalar), &mut || {
        map(Method::Uniform, Engine::Lanes)
    });
    writeln!(
        out,
        "200×100 map  {} cm, uniform, 2 jobs: scalar {:.3} s, lanes {:.3} s ({:.2}×)",
        base.height,
        engines.a_s,
        engines.b_s,
        1.0 / engines.ratio
    )?;
    let chosen = bench::paper_map(params, base, Method::Adaptive, Engine::Lanes);
    let methods = bench::compare(rounds, &mut || map(Method::Uniform, Engine::Lanes), &mut || {
        map(Method::Adaptive, Engine::Lanes)
    });
    writeln!(
        out,
        "             adaptive, lanes: {:.3} s against uniform {:.3} s; {chosen}",
        methods.b_s, methods.a_s
    )?;
    Ok(())
}
