//! The twin screen's predictability curve: `experiment::predict::run_prediction` for the
//! worker's current setup on a thread of its own, its partial curves passed on as they grow.
//!
//! The curve follows the simulator rather than commands: on every tick the worker hands over
//! the setup the curve should show (none while no twin rolls), and a setup other than the
//! one computing stops the old computation and starts a new one under a new generation.
//! Stopping waits for the thread, which takes milliseconds since every roll looks at the
//! cancel flag every few thousand steps: at most one curve computes at a time, and nothing
//! of an older generation is ever passed on.

use super::job::{Report, Runner};
use dicesim_experiment::predict::{PredictCurve, PredictSpec, default_epsilons, run_prediction};
use dicesim_experiment::{RandomRanges, RunOptions};
use dicesim_physics::{InitialCondition, Params};
use std::sync::atomic::{AtomicBool, Ordering};

/// Random throws per curve, each rolled beside 15 twins (one per decade of ε): 16 000 rolls,
/// about a second for the paper's setup and at most five for the shipped presets (the
/// loaded die, on the scalar engine, is the slowest), and 95 % intervals of about ±3
/// points where P(same face) is halfway.
pub const CURVE_STARTS: u64 = 1000;

/// Everything the curve depends on: the random throws `R` draws, rolled with these values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveSetup {
    pub params: Params,
    /// The preset's random ranges; their seed is the curve's, so a setup always gives the
    /// same curve.
    pub ranges: RandomRanges,
    /// The preset's start: random throws take their orientation from it.
    pub base: InitialCondition,
}

impl CurveSetup {
    /// The experiment: [`CURVE_STARTS`] throws, one twin per decade of ε, no sweep.
    pub fn spec(&self) -> PredictSpec {
        PredictSpec {
            epsilons: default_epsilons(),
            count: CURVE_STARTS,
            seed: self.ranges.seed,
            sweep: None,
        }
    }
}

/// How far a curve has got.
#[derive(Debug, Clone, PartialEq)]
pub enum CurveState {
    /// Rolling: the curve of the throws rolled whole so far (none before the first chunk).
    Computing(Option<PredictCurve>),
    Complete(PredictCurve),
    /// Why there is no curve, in words.
    Failed(String),
}

/// The curve, partial or complete, or why it could not be computed.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveUpdate {
    /// Newer curves have higher generations.
    pub generation: u64,
    /// Throws asked for.
    pub count: u64,
    pub state: CurveState,
}

/// Computes the curve of `setup` on this thread (one roll thread per core), handing each
/// partial curve to `partial`; stops early when `cancel` is set.
pub(crate) fn compute(
    setup: &CurveSetup,
    cancel: &AtomicBool,
    partial: &mut dyn FnMut(&PredictCurve),
) -> CurveState {
    crate::fault::inject("curve");
    let spec = setup.spec();
    let run = run_prediction(
        &setup.params,
        &setup.ranges,
        &setup.base,
        &spec,
        &RunOptions::default(),
        cancel,
        &mut |p| partial(p.curve),
    );
    match run {
        Err(e) => CurveState::Failed(e.to_string()),
        Ok(mut p) => match p.curves.pop() {
            Some(c) if c.faces.total() == 0 => CurveState::Failed(format!(
                "none of the {} throws ended on a face within the time cap of {} s \
                 (they did not settle, or went unstable): no curve",
                c.starts, setup.params.integrator.max_time
            )),
            Some(c) => CurveState::Complete(c),
            None => CurveState::Failed("no curve was rolled".to_string()),
        },
    }
}

/// The curve thread of one worker: at most one at a time, on the runner every job uses.
pub(super) struct CurveRunner {
    generation: u64,
    /// The setup of the curve computing or shown last.
    setup: Option<CurveSetup>,
    /// Whether the last tick wanted a curve (a twin was rolling).
    wanted: bool,
    /// The curve computing (under its generation): its newest partial curve, left for the
    /// worker's next tick.
    runner: Runner<Option<PredictCurve>, CurveState>,
    /// The complete curve of `setup`, shown again at once when the twin comes back on it.
    complete: Option<CurveState>,
}

impl Default for CurveRunner {
    fn default() -> CurveRunner {
        CurveRunner {
            generation: 0,
            setup: None,
            wanted: false,
            runner: Runner::new("dicesim-curve"),
            complete: None,
        }
    }
}

impl CurveRunner {
    /// Whether a curve is computing.
    pub(crate) fn running(&self) -> bool {
        self.runner.running()
    }

    /// Follows the setup the simulator wants a curve of (`None`: no twin, no curve), and
    /// returns what the UI has not seen yet: a new curve's start, a grown curve, the end.
    pub(crate) fn sync(&mut self, wanted: Option<CurveSetup>) -> Option<CurveUpdate> {
        let Some(setup) = wanted else {
            self.wanted = false;
            self.stop();
            return None;
        };
        if !self.wanted || self.setup != Some(setup) {
            self.wanted = true;
            self.stop();
            self.generation += 1;
            if self.setup == Some(setup)
                && let Some(done) = &self.complete
            {
                return Some(self.update(done.clone()));
            }
            self.setup = Some(setup);
            self.complete = None;
            return Some(self.start(setup));
        }
        match self.runner.poll()? {
            Report::Progress(_, partial) => partial.map(|c| self.update(CurveState::Computing(Some(c)))),
            Report::Finished(_, _, state) => {
                let state = state
                    .unwrap_or_else(|| CurveState::Failed("the curve's computation panicked".to_string()));
                if matches!(state, CurveState::Complete(_)) {
                    self.complete = Some(state.clone());
                }
                Some(self.update(state))
            }
        }
    }

    fn update(&self, state: CurveState) -> CurveUpdate {
        CurveUpdate {
            generation: self.generation,
            count: CURVE_STARTS,
            state,
        }
    }

    fn start(&mut self, setup: CurveSetup) -> CurveUpdate {
        let started = self.runner.start(self.generation, move |cancel, post| {
            compute(&setup, cancel, &mut |c| {
                // The last partial curve has every throw: it is the complete curve, which
                // comes as the job's result. Posted, a tick between it and the thread's end
                // would show it as still computing.
                if !cancel.load(Ordering::Relaxed) && c.starts < CURVE_STARTS {
                    post.post(|newest| *newest = Some(c.clone()));
                }
            })
        });
        match started {
            Ok(()) => self.update(CurveState::Computing(None)),
            Err(e) => self.update(CurveState::Failed(format!(
                "cannot start the curve's thread: {e}"
            ))),
        }
    }

    /// Cancels the curve computing, if any, and waits for its thread (milliseconds).
    pub(crate) fn stop(&mut self) {
        self.runner.stop();
    }
}
