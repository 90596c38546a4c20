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

/// The box's A ending against B's over shared throws, faces 1–6 and no face: the shape the
/// explorer's parameter twin panel reads. [`VersusCounts`] is any die's (`batch --versus`);
/// this table goes when the explorer reads that.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct VersusTable {
    /// `counts[a][b]`: throws that ended on A's face `a + 1` and B's face `b + 1`
    /// ([`NO_FACE`] for no face).
    pub counts: [[u64; ENDINGS]; ENDINGS],
}

impl VersusTable {
    /// Counts one throw, rolled in A and in B.
    pub fn add(&mut self, a: &RollRecord, b: &RollRecord) {
        let faces = dicesim_physics::Solid::Box.face_numbers();
        self.counts[ending(a, faces)][ending(b, faces)] += 1;
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
        agreement(self.agreeing(), self.faced())
    }
}

/// A's ending against B's over shared throws. The rows are A's die's numbers in the order
/// its tables list them (1–6 on the box, 1–20 on a d20, 0–9 on a d10), then the throws that
/// ended on no face (did not settle, went unstable, or settled with no face up); the columns
/// B's the same way. Two setups roll the same die unless B changes `die.kind`, so the two
/// lists are the same but for that.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VersusCounts {
    /// The numbers A's die shows: row `i` is `a_faces[i]`, row `a_faces.len()` no face.
    pub a_faces: &'static [u8],
    /// The numbers B's die shows: the columns, as the rows.
    pub b_faces: &'static [u8],
    /// `counts[a][b]`: throws that ended on A's row `a` and B's column `b`.
    pub counts: Vec<Vec<u64>>,
}

/// `agreeing` of `faced` as a share with its 95 % Wilson interval; `None` when `faced` is 0.
fn agreement(agreeing: u64, faced: u64) -> Option<(f64, [f64; 2])> {
    (faced > 0).then(|| (agreeing as f64 / faced as f64, wilson_interval(agreeing, faced)))
}

/// The row (or column) of a roll's ending among `faces`: its number's place, else
/// `faces.len()` (no face).
fn ending(r: &RollRecord, faces: &[u8]) -> usize {
    let settled = r.outcome.status == dicesim_physics::Status::Settled;
    r.outcome
        .face
        .filter(|_| settled)
        .and_then(|f| faces.iter().position(|&n| n == f))
        .unwrap_or(faces.len())
}

impl VersusCounts {
    /// An empty table of A's die's numbers against B's.
    pub fn new(a_faces: &'static [u8], b_faces: &'static [u8]) -> VersusCounts {
        VersusCounts {
            a_faces,
            b_faces,
            counts: vec![vec![0; b_faces.len() + 1]; a_faces.len() + 1],
        }
    }

    /// The empty table of `a`'s die against `b`'s.
    pub fn of(a: &Params, b: &Params) -> VersusCounts {
        VersusCounts::new(a.die.face_numbers(), b.die.face_numbers())
    }

    /// The row of the throws A ended on no face (its numbers' count); the column of B's is
    /// `b_faces.len()`.
    pub fn no_face_row(&self) -> usize {
        self.a_faces.len()
    }

    /// Counts one throw, rolled in A and in B.
    pub fn add(&mut self, a: &RollRecord, b: &RollRecord) {
        self.counts[ending(a, self.a_faces)][ending(b, self.b_faces)] += 1;
    }

    /// Every throw counted.
    pub fn throws(&self) -> u64 {
        self.counts.iter().flatten().sum()
    }

    /// Throws that ended on a face in both setups: the share's denominator.
    pub fn faced(&self) -> u64 {
        let (rows, columns) = (self.a_faces.len(), self.b_faces.len());
        self.counts[..rows]
            .iter()
            .map(|row| row[..columns].iter().sum::<u64>())
            .sum()
    }

    /// Throws that ended on the same number in both setups.
    pub fn agreeing(&self) -> u64 {
        self.a_faces
            .iter()
            .enumerate()
            .filter_map(|(a, n)| {
                let b = self.b_faces.iter().position(|m| m == n)?;
                Some(self.counts[a][b])
            })
            .sum()
    }

    /// The share of throws ending on a face in both setups that end on the same one, and
    /// its 95 % Wilson interval; `None` before any such throw.
    pub fn agreement(&self) -> Option<(f64, [f64; 2])> {
        agreement(self.agreeing(), self.faced())
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
    /// The numbers A's die shows, the table's rows but the last (no face).
    pub faces_a: Vec<u8>,
    /// The numbers B's die shows, its columns but the last.
    pub faces_b: Vec<u8>,
    /// Rows: A's faces in the order of `faces_a`, then no face; columns: B's the same way.
    pub table: Vec<Vec<u64>>,
}

impl VersusCounts {
    pub fn summary(&self) -> VersusSummary {
        let agreement = self.agreement();
        VersusSummary {
            throws: self.throws(),
            faced: self.faced(),
            agreeing: self.agreeing(),
            agreement: agreement.map(|a| a.0),
            interval: agreement.map(|a| a.1),
            faces_a: self.a_faces.to_vec(),
            faces_b: self.b_faces.to_vec(),
            table: self.counts.clone(),
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
    pub table: VersusCounts,
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
    let mut table = VersusCounts::of(a, b);
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
    use dicesim_physics::{Solid, Status};

    fn record(status: Status, face: Option<u8>) -> RollRecord {
        RollRecord::ended(0, status, face)
    }

    #[test]
    fn faceless_endings_are_counted_apart_from_the_share() {
        let mut t = VersusCounts::of(&Params::default(), &Params::default());
        let face = |f| record(Status::Settled, Some(f));
        t.add(&face(3), &face(3));
        t.add(&face(3), &face(5));
        t.add(&face(1), &face(1));
        t.add(&record(Status::Timeout, None), &face(2));
        t.add(&record(Status::Settled, None), &record(Status::Unstable, None));
        assert_eq!(t.throws(), 5);
        assert_eq!((t.faced(), t.agreeing()), (3, 2));
        let none = t.no_face_row();
        assert_eq!(none, 6);
        assert_eq!(t.counts[none][1], 1);
        assert_eq!(t.counts[none][none], 1);
        let (share, [lo, hi]) = t.agreement().unwrap();
        assert_eq!(share, 2.0 / 3.0);
        assert!(lo < share && share < hi);
        assert_eq!(
            VersusCounts::of(&Params::default(), &Params::default()).agreement(),
            None
        );
    }

    /// A d20's table has a row and a column for each of its 20 numbers; a d10's first is its
    /// 0, which is a face like any other, and the d%'s rows are its tens.
    #[test]
    fn a_polyhedral_die_has_a_row_and_a_column_per_number() {
        let die = |kind| {
            let mut p = Params::default();
            p.die.kind = kind;
            p
        };
        let face = |f| record(Status::Settled, Some(f));
        let mut t = VersusCounts::of(&die(Solid::D20), &die(Solid::D20));
        assert_eq!((t.counts.len(), t.counts[0].len()), (21, 21));
        t.add(&face(20), &face(20));
        t.add(&face(20), &face(7));
        t.add(&face(13), &record(Status::Timeout, None));
        assert_eq!((t.counts[19][19], t.counts[19][6], t.counts[12][20]), (1, 1, 1));
        assert_eq!((t.throws(), t.faced(), t.agreeing()), (3, 2, 1));
        let mut t = VersusCounts::of(&die(Solid::D10), &die(Solid::D10));
        assert_eq!(t.counts.len(), 11);
        t.add(&face(0), &face(0));
        t.add(&face(9), &face(0));
        assert_eq!((t.counts[0][0], t.counts[9][0]), (1, 1));
        assert_eq!((t.faced(), t.agreeing()), (2, 1));
        let mut t = VersusCounts::of(&die(Solid::Percentile), &die(Solid::Percentile));
        t.add(&face(90), &face(90));
        assert_eq!(t.counts[9][9], 1);
        // A B that rolls another die: the columns are its numbers, and only a number both
        // show can agree.
        let mut t = VersusCounts::of(&Params::default(), &die(Solid::D8));
        assert_eq!((t.counts.len(), t.counts[0].len()), (7, 9));
        t.add(&face(6), &face(8));
        t.add(&face(2), &face(2));
        assert_eq!((t.counts[5][7], t.faced(), t.agreeing()), (1, 2, 1));
        assert_eq!(t.summary().faces_b, [1, 2, 3, 4, 5, 6, 7, 8]);
    }
}
