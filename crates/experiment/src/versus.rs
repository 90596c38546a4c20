//! Two setups on the same throws (`dicesim batch --versus`): each random throw rolled in
//! setup A (as given) and in setup B (A with some values changed), the table of A's face
//! against B's, and the share of throws on which they agree.

use crate::Error;
use crate::batch::{Rolls, RunOptions, stream_setups};
use crate::engine::Engine;
use crate::record::RollRecord;
use crate::stats::wilson_interval;
use dicesim_physics::Params;
use serde::Serialize;
use std::sync::atomic::AtomicBool;

/// Rows and columns of the table: faces 1–6, then the throws that ended on no face (did not
/// settle, went unstable, or settled with no face up).
pub const ENDINGS: usize = 7;

/// The row and column of a throw that ended on no face.
pub const NO_FACE: usize = 6;

/// A's ending against B's over shared throws.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct VersusTable {
    /// `counts[a][b]`: throws that ended on A's face `a + 1` and B's face `b + 1`
    /// ([`NO_FACE`] for no face).
    pub counts: [[u64; ENDINGS]; ENDINGS],
}

/// The row or column of a roll's ending.
fn ending(r: &RollRecord) -> usize {
    match r.outcome.face {
        Some(f @ 1..=6) if r.outcome.status == dicesim_physics::Status::Settled => f as usize - 1,
        _ => NO_FACE,
    }
}

impl VersusTable {
    /// Counts one throw, rolled in A and in B.
    pub fn add(&mut self, a: &RollRecord, b: &RollRecord) {
        self.counts[ending(a)][ending(b)] += 1;
    }

    /// Every throw counted.
    pub fn throws(&self) -> u64 {
        self.counts.iter().flatten().sum()
    }

    /// Throws that ended on a face in both setups: the share's denominator.
    pub fn faced(&self) -> u64 {
        self.counts[..NO_FACE]
            .iter()
            .map(|row| row[..NO_FACE].iter().sum::<u64>())
            .sum()
    }

    /// Throws that ended on the same face in both setups.
    pub fn agreeing(&self) -> u64 {
        (0..NO_FACE).map(|f| self.counts[f][f]).sum()
    }

    /// The share of throws ending on a face in both setups that end on the same one, and
    /// its 95 % Wilson interval; `None` before any such throw.
    pub fn agreement(&self) -> Option<(f64, [f64; 2])> {
        let n = self.faced();
        (n > 0).then(|| {
            let k = self.agreeing();
            (k as f64 / n as f64, wilson_interval(k, n))
        })
    }
}

/// The figures a versus run reports (its JSON's `agreement`, `interval`, `table`, …).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct VersusSummary {
    /// Throws rolled in both setups.
    pub throws: u64,
    /// Of them, ending on a face in both.
    pub faced: u64,
    /// Of those, ending on the same face.
    pub agreeing: u64,
    /// `agreeing / faced` (null when `faced` is 0).
    pub agreement: Option<f64>,
    /// Its 95 % Wilson interval.
    pub interval: Option<[f64; 2]>,
    /// Rows: A's face 1–6 then no face; columns: B's the same way.
    pub table: [[u64; ENDINGS]; ENDINGS],
}

impl VersusTable {
    pub fn summary(&self) -> VersusSummary {
        let agreement = self.agreement();
        VersusSummary {
            throws: self.throws(),
            faced: self.faced(),
            agreeing: self.agreeing(),
            agreement: agreement.map(|a| a.0),
            interval: agreement.map(|a| a.1),
            table: self.counts,
        }
    }
}

/// A finished (or cancelled) versus run.
#[derive(Debug, Clone)]
pub struct VersusRun {
    pub requested: u64,
    /// Throws rolled in both setups: all, or an exact prefix if cancelled.
    pub completed: u64,
    pub cancelled: bool,
    pub jobs: usize,
    pub engine: Engine,
    pub table: VersusTable,
}

/// Rolls every throw of `rolls` in `a` and in `b` in parallel and tallies A's ending against
/// B's; `sink` gets each chunk's throws in order as pairs (A's record, B's record). The same
/// throws give the same table for any thread count and engine. Cancelling and sink errors
/// as in [`super::stream_batch`].
pub fn stream_versus(
    a: &Params,
    b: &Params,
    rolls: &Rolls,
    options: &RunOptions,
    cancel: &AtomicBool,
    sink: &mut dyn FnMut(&[RollRecord]) -> Result<(), String>,
) -> Result<VersusRun, Error> {
    let mut table = VersusTable::default();
    let run = stream_setups(&[*a, *b], rolls, options, cancel, &mut |chunk| {
        sink(chunk)?;
        for pair in chunk.chunks_exact(2) {
            table.add(&pair[0], &pair[1]);
        }
        Ok(())
    })?;
    Ok(VersusRun {
        requested: run.requested,
        completed: run.completed,
        cancelled: run.completed < run.requested,
        jobs: run.jobs,
        engine: run.engine,
        table,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use dicesim_physics::Status;

    fn record(status: Status, face: Option<u8>) -> RollRecord {
        RollRecord::ended(0, status, face)
    }

    #[test]
    fn faceless_endings_are_counted_apart_from_the_share() {
        let mut t = VersusTable::default();
        let face = |f| record(Status::Settled, Some(f));
        t.add(&face(3), &face(3));
        t.add(&face(3), &face(5));
        t.add(&face(1), &face(1));
        t.add(&record(Status::Timeout, None), &face(2));
        t.add(&record(Status::Settled, None), &record(Status::Unstable, None));
        assert_eq!(t.throws(), 5);
        assert_eq!((t.faced(), t.agreeing()), (3, 2));
        assert_eq!(t.counts[NO_FACE][1], 1);
        assert_eq!(t.counts[NO_FACE][NO_FACE], 1);
        let (share, [lo, hi]) = t.agreement().unwrap();
        assert_eq!(share, 2.0 / 3.0);
        assert!(lo < share && share < hi);
        assert_eq!(VersusTable::default().agreement(), None);
    }
}
