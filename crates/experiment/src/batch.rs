//! Batches of rolls in parallel, streamed in roll order, reproducible for any thread count
//! and engine, and cancellable.
//!
//! Each roll depends on its own initial condition alone (random ones on (seed, roll index),
//! see [`RandomRanges::draw`]). Worker threads take chunks of consecutive rolls from a
//! queue; finished chunks are put back in roll order on the calling thread and handed on at
//! once, so records leave the engine in id order as they complete and memory stays flat in
//! the number of rolls (at most [`CHUNKS_IN_FLIGHT_PER_JOB`] chunks per thread wait). The
//! summary is accumulated record by record in roll order, so its float totals are the same
//! for any job count. A cancel is noticed inside rolls (every few thousand steps); the
//! records handed on are then an exact prefix of the full batch.

use crate::Error;
use crate::engine::{Engine, roll_setups};
use crate::record::RollRecord;
use crate::summary::BatchSummary;
use crate::tally::Tally;
use dicesim_physics::{InitialCondition, Params, StabilityCheck};
use dicesim_setup::random::RandomDraws;
use dicesim_setup::random::RandomRanges;
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Condvar, Mutex, mpsc};
use std::time::{Duration, Instant};

/// Rolls per chunk: long enough that a chunk's ragged end (lanes idle while its last rolls
/// finish) and the hand-over cost little, short enough that records flow steadily.
pub(crate) const CHUNK: u64 = 512;

/// Chunks a thread may run ahead of the oldest unfinished one.
pub(crate) const CHUNKS_IN_FLIGHT_PER_JOB: u64 = 4;

/// How often the calling thread looks at the cancel flag while it waits for chunks.
const POLL: Duration = Duration::from_millis(20);

/// Where a batch's initial conditions come from.
#[derive(Debug, Clone, Copy)]
pub enum Rolls<'a> {
    /// `count` rolls around `base` with ids from `first` on (0 unless a shard), roll `id`
    /// drawn by `ranges` from the stream (`seed`, `id`).
    Random {
        ranges: &'a RandomRanges,
        base: &'a InitialCondition,
        seed: u64,
        first: u64,
        count: u64,
    },
    /// Given initial conditions with their ids, e.g. from an `--ics` file.
    Given(&'a [(u64, InitialCondition)]),
}

impl Rolls<'_> {
    /// How many rolls the batch has.
    pub fn len(&self) -> u64 {
        match self {
            Rolls::Random { count, .. } => *count,
            Rolls::Given(ics) => ics.len() as u64,
        }
    }

    /// True for a batch of no rolls.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The id and initial condition of roll `index` (0-based, `< len()`).
    pub(crate) fn get(&self, index: u64) -> (u64, InitialCondition) {
        match self {
            Rolls::Random {
                ranges,
                base,
                seed,
                first,
                ..
            } => (first + index, ranges.draw(base, *seed, first + index)),
            Rolls::Given(ics) => ics[index as usize],
        }
    }
}

/// How to run a batch or a map.
#[derive(Debug, Clone, Copy, Default)]
pub struct RunOptions {
    /// Worker threads; 0: one per available core.
    pub jobs: usize,
    pub engine: Engine,
}

/// A finished (or cancelled) batch whose records were streamed.
#[derive(Debug, Clone)]
pub struct BatchRun {
    /// How many rolls were asked for.
    pub requested: u64,
    /// How many were handed on: all, or an exact prefix if cancelled.
    pub completed: u64,
    /// Whether the cancel flag stopped the batch before the end.
    pub cancelled: bool,
    /// Threads used.
    pub jobs: usize,
    /// The engine that ran (`Scalar` or `Lanes`).
    pub engine: Engine,
    /// The statistics of the completed rolls.
    pub summary: BatchSummary,
    /// Their counts in the exact form a merge of shards adds up.
    pub tally: Tally,
    /// Of the completed rolls, those whose start the stability check puts past its limit
    /// (docs/model.md, "Stability"): their endings are the step's, not the model's.
    pub past_stability_limit: u64,
}

/// A finished (or cancelled) batch with every record kept.
#[derive(Debug, Clone)]
pub struct Batch {
    /// The completed rolls in roll order: all of them, or an exact prefix if cancelled.
    pub records: Vec<RollRecord>,
    /// How many rolls were asked for.
    pub requested: u64,
    /// Whether the cancel flag stopped the batch before the end.
    pub cancelled: bool,
    /// Wall-clock time the rolls took.
    pub elapsed: Duration,
    /// Threads used.
    pub jobs: usize,
    /// The numbers its die shows ([`Die::face_numbers`](dicesim_physics::Die::face_numbers)).
    pub numbers: &'static [u8],
}

impl Batch {
    pub fn summary(&self) -> BatchSummary {
        BatchSummary::new(self.numbers, &self.records, self.elapsed)
    }
}

/// The most worker threads a run takes: 4 × the cores (more than a few per core only adds
/// switching).
pub fn max_jobs() -> usize {
    4 * thread_count(0)
}

/// The number of threads for `jobs` (0 means one per available core).
pub fn thread_count(jobs: usize) -> usize {
    if jobs > 0 {
        jobs
    } else {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    }
}

/// A local thread pool of `jobs` threads (0: one per core), so a map never competes
/// with, or depends on, rayon's global pool.
pub(crate) fn thread_pool(jobs: usize) -> Result<rayon::ThreadPool, Error> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(thread_count(jobs))
        .thread_name(|i| format!("dicesim-roll-{i}"))
        .build()
        .map_err(|e| Error::Threads(e.to_string()))
}

/// Runs every roll of `rolls` with `params` and keeps the records (the explorer's batches
/// and tests; [`stream_batch`] is the same without keeping them).
///
/// `progress` is called on the calling thread after each chunk with every record so far (in
/// roll order), so a UI can draw a gauge or a live tally. Setting `cancel` stops the batch
/// within a few thousand steps of every running roll; the records then are an exact prefix
/// of the full batch.
pub fn run_batch(
    params: &Params,
    rolls: &Rolls,
    jobs: usize,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(&[RollRecord]),
) -> Result<Batch, Error> {
    let mut records = Vec::with_capacity(rolls.len().min(1 << 24) as usize);
    let start = Instant::now();
    let options = RunOptions {
        jobs,
        engine: Engine::Auto,
    };
    let run = stream_batch(params, rolls, &options, cancel, &mut |chunk| {
        records.extend_from_slice(chunk);
        progress(&records);
        Ok(())
    })?;
    Ok(Batch {
        records,
        requested: run.requested,
        cancelled: run.cancelled,
        elapsed: start.elapsed(),
        jobs: run.jobs,
        numbers: params.die.face_numbers(),
    })
}

/// What a worker thread hands back: chunk number, its records (a prefix of the chunk's
/// rolls if the batch was cancelled), and whether it is whole.
type Finished = (u64, Vec<RollRecord>, bool);

/// Runs every roll of `rolls` with `params` and hands the records to `sink` on the calling
/// thread, in roll order, a chunk at a time, as they complete.
///
/// Setting `cancel` stops the batch within a few thousand steps of every running roll; the
/// records handed on are then an exact prefix of the full batch. A sink error stops the
/// batch and is returned as [`Error::Records`]. The parameters are validated first; initial
/// conditions are the caller's to check (an out-of-range one still ends in a status, never
/// a panic).
pub fn stream_batch(
    params: &Params,
    rolls: &Rolls,
    options: &RunOptions,
    cancel: &AtomicBool,
    sink: &mut dyn FnMut(&[RollRecord]) -> Result<(), String>,
) -> Result<BatchRun, Error> {
    let start = Instant::now();
    let mut tally = Tally::new(params.die.face_numbers());
    let check = StabilityCheck::new(params);
    let mut past_stability_limit = 0;
    let run = stream_setups(
        std::slice::from_ref(params),
        rolls,
        options,
        cancel,
        &mut |chunk| {
            sink(chunk)?;
            chunk.iter().for_each(|r| tally.add(r));
            past_stability_limit += chunk
                .iter()
                .filter(|r| !check.predict(&r.initial).is_stable())
                .count() as u64;
            Ok(())
        },
    )?;
    Ok(BatchRun {
        requested: run.requested,
        completed: run.completed,
        cancelled: run.completed < run.requested,
        jobs: run.jobs,
        engine: run.engine,
        summary: tally.summary(start.elapsed()),
        tally,
        past_stability_limit,
    })
}

/// How a run of [`stream_setups`] went.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SetupsRun {
    /// Throws asked for.
    pub(crate) requested: u64,
    /// Throws rolled in every setup and handed on: all, or a prefix if cancelled.
    pub(crate) completed: u64,
    pub(crate) jobs: usize,
    /// The engine that ran (`Scalar` or `Lanes`).
    pub(crate) engine: Engine,
}

/// Rolls every throw of `rolls` in each of `setups` (the same initial condition in each)
/// and hands the records to `sink` on the calling thread in throw order, a chunk at a time:
/// throw 0 in every setup in their order, then throw 1, … — `setups.len()` records a throw.
/// Cancelling and sink errors as in [`stream_batch`]; a throw is handed on only when it has
/// ended in every setup.
pub(crate) fn stream_setups(
    setups: &[Params],
    rolls: &Rolls,
    options: &RunOptions,
    cancel: &AtomicBool,
    sink: &mut dyn FnMut(&[RollRecord]) -> Result<(), String>,
) -> Result<SetupsRun, Error> {
    for params in setups {
        params.validate()?;
    }
    let per_throw = setups.len().max(1);
    if let Rolls::Random { ranges, .. } = rolls {
        ranges.validate()?;
    }
    let jobs = thread_count(options.jobs);
    let engine = options.engine.resolve();
    let requested = rolls.len();
    let chunks = requested.div_ceil(CHUNK);
    // Set when the calling thread stops the workers: a cancel, or a sink that failed.
    let halt = AtomicBool::new(false);
    let stopped = || cancel.load(Ordering::Relaxed) || halt.load(Ordering::Relaxed);
    let next_chunk = AtomicU64::new(0);
    // The oldest chunk not yet handed on; workers stay within the window after it.
    let oldest = (Mutex::new(0u64), Condvar::new());
    let window = CHUNKS_IN_FLIGHT_PER_JOB * jobs as u64;
    let (send, receive) = mpsc::channel::<Finished>();
    let mut completed = 0u64;
    let mut sink_error = None;
    std::thread::scope(|scope| -> Result<(), Error> {
        for j in 0..jobs {
            let send = send.clone();
            let (next_chunk, oldest, stopped) = (&next_chunk, &oldest, &stopped);
            std::thread::Builder::new()
                .name(format!("dicesim-roll-{j}"))
                .spawn_scoped(scope, move || {
                    loop {
                        let c = next_chunk.fetch_add(1, Ordering::Relaxed);
                        if c >= chunks {
                            return;
                        }
                        let (lock, wake) = oldest;
                        let mut first = lock.lock().expect("no worker panics holding it");
                        while c >= *first + window && !stopped() {
                            first = wake.wait_timeout(first, POLL).expect("no worker panics").0;
                        }
                        drop(first);
                        if stopped() {
                            return;
                        }
                        let chunk: Vec<_> = (c * CHUNK..((c + 1) * CHUNK).min(requested))
                            .flat_map(|i| {
                                let (id, ic) = rolls.get(i);
                                setups.iter().map(move |params| (id, *params, ic))
                            })
                            .collect();
                        let mut records = roll_setups(engine, &chunk, stopped);
                        let whole = records.len() == chunk.len();
                        // Only throws ended in every setup.
                        records.truncate(records.len() / per_throw * per_throw);
                        if send.send((c, records, whole)).is_err() || !whole {
                            return;
                        }
                    }
                })
                .map_err(|e| Error::Threads(e.to_string()))?;
        }
        drop(send);
        let mut waiting: BTreeMap<u64, (Vec<RollRecord>, bool)> = BTreeMap::new();
        let mut next_out = 0u64;
        let mut open = true;
        loop {
            match receive.recv_timeout(POLL) {
                Ok((c, records, whole)) => {
                    waiting.insert(c, (records, whole));
                }
                Err(mpsc::RecvTimeoutError::Timeout) => {}
                Err(mpsc::RecvTimeoutError::Disconnected) => break,
            }
            if cancel.load(Ordering::Relaxed) {
                halt.store(true, Ordering::Relaxed);
            }
            while open {
                let Some((records, whole)) = waiting.remove(&next_out) else {
                    break;
                };
                if let Err(e) = sink(&records) {
                    sink_error = Some(e);
                    halt.store(true, Ordering::Relaxed);
                    open = false;
                    break;
                }
                completed += (records.len() / per_throw) as u64;
                next_out += 1;
                open = whole;
                let (lock, wake) = &oldest;
                *lock.lock().expect("no worker panics holding it") = next_out;
                wake.notify_all();
            }
        }
        Ok(())
    })?;
    if let Some(e) = sink_error {
        return Err(Error::Records(e));
    }
    Ok(SetupsRun {
        requested,
        completed,
        jobs,
        engine,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::summary::{StartFaceCounts, StatusCounts};
    use dicesim_physics::{Outcome, Status};

    fn record(start_face: u8, status: Status, face: Option<u8>, steps: u64) -> RollRecord {
        RollRecord {
            id: 0,
            initial: InitialCondition::default(),
            outcome: Outcome {
                status,
                face,
                steps,
                time_s: steps as f64 * 1e-3,
                impacts: 0,
                first_impact: None,
            },
            start_face,
        }
    }

    #[test]
    fn summary_by_hand() {
        let mut rs = vec![
            record(1, Status::Settled, Some(1), 100), // same
            record(6, Status::Settled, Some(1), 100), // opposite
            record(5, Status::Settled, Some(2), 100), // opposite
            record(1, Status::Settled, Some(6), 100), // opposite
            record(3, Status::Settled, Some(4), 100), // opposite
            record(4, Status::Settled, Some(4), 100), // same
            record(2, Status::Settled, Some(3), 100), // adjacent
            record(2, Status::Settled, None, 100),
            record(2, Status::Timeout, None, 30_000),
            record(2, Status::Unstable, None, 5),
        ];
        rs.extend((0..2).map(|_| record(5, Status::Settled, Some(5), 200)));
        let s = BatchSummary::new(
            Params::DEFAULT.die.face_numbers(),
            &rs,
            Duration::from_millis(500),
        );
        assert_eq!(s.rolls, 12);
        assert_eq!(s.faces.counts, [2, 1, 1, 2, 2, 1]);
        // n = 9 faces, expected 1.5 each: χ² = 6·0.5²/1.5 = 1.
        assert!((s.chi_square.unwrap() - 1.0).abs() < 1e-12);
        // 5-dof closed form at x = 1: erfc(√0.5) + √(2/π)·e^(−0.5)·(1 + 1/3) = 0.9625657.
        assert!((s.p_value.unwrap() - 0.9625657).abs() < 1e-6);
        assert_eq!(
            s.start_face,
            StartFaceCounts {
                same: 4,
                adjacent: 1,
                opposite: 4
            }
        );
        assert_eq!(s.start_face_shares, [4.0 / 9.0, 1.0 / 9.0, 4.0 / 9.0]);
        assert_eq!(
            s.status,
            StatusCounts {
                settled: 9,
                settled_without_face: 1,
                timeout: 1,
                unstable: 1
            }
        );
        assert_eq!(s.steps, 8 * 100 + 30_000 + 5 + 2 * 200);
        assert_eq!(s.face_shares[0], 2.0 / 9.0);
        assert_eq!(s.rolls_per_s, 24.0);
        assert_eq!(s.steps_per_s, 2.0 * 31_205.0);
    }

    #[test]
    fn cancelled_batch_is_an_exact_prefix() {
        let params = Params::default();
        let ranges = RandomRanges::default();
        let base = InitialCondition::default();
        let rolls = Rolls::Random {
            ranges: &ranges,
            base: &base,
            seed: 3,
            first: 0,
            count: 3 * CHUNK,
        };
        let cancel = AtomicBool::new(false);
        let mut calls = 0;
        let part = run_batch(&params, &rolls, 1, &cancel, &mut |done| {
            calls += 1;
            if calls == 1 {
                assert_eq!(done.len() as u64, CHUNK);
            }
            cancel.store(true, Ordering::Relaxed);
        })
        .unwrap();
        assert!(part.cancelled);
        // The running chunk stops inside its rolls and gives its finished prefix.
        assert!(part.records.len() as u64 >= CHUNK && (part.records.len() as u64) < 3 * CHUNK);
        let full = run_batch(&params, &rolls, 2, &AtomicBool::new(false), &mut |_| {}).unwrap();
        assert!(!full.cancelled);
        assert_eq!(full.records.len() as u64, 3 * CHUNK);
        assert_eq!(part.records[..], full.records[..part.records.len()]);
        assert!(full.records.iter().enumerate().all(|(i, r)| r.id == i as u64));
    }
}
