//! Basin maps: the outcome over a grid of two setup values (the authors' 1-D and 2-D scans).
//!
//! Grid nodes sit on both ends of each range, so a coarse grid's nodes are nodes of the fine
//! one. The adaptive method samples a coarse grid, then splits only blocks whose corners
//! differ (in face or status) and fills agreeing blocks from their corners; like the
//! authors' refinement it can miss an island smaller than a coarse block, which the uniform
//! method (every node rolled) cannot. Where the basins are finely interleaved (a 15 cm drop)
//! nearly every block splits down to single cells, and refining level by level costs more
//! than rolling every cell at once. A smooth boundary line leaves about half of a split
//! block's four parts differing; so once more than [`UNIFORM_SWITCH_SHARE`] of the parts of
//! the blocks split at a refinement still differ, the adaptive method rolls every remaining
//! cell, and the map says so ([`BasinMap::switched_to_uniform`]).

use crate::Error;
use crate::batch::{RunOptions, thread_pool};
use crate::data_file::Column;
use crate::engine::roll_setups;
use crate::hashing::{Hashing, Written};
use crate::record::RollRecord;
use crate::stats::FaceTally;
use dicesim_physics::{InitialCondition, Outcome, Params, Status, check_setup};
use dicesim_setup::keys::ScanKey;
use dicesim_setup::number::{Real, fmt_exact};
use dicesim_setup::output::{Output, OutputError};
use rayon::prelude::*;
use std::io::Write;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};

/// The adaptive method rolls every remaining cell once more than this share of the parts
/// of the blocks split at a refinement still differ: the map is nearly all boundary, its
/// cells would be rolled nearly all anyway, and one pass keeps every thread and lane busy
/// where level after level would not.
pub const UNIFORM_SWITCH_SHARE: f64 = 0.75;

/// Nodes per task: enough to keep four lanes full most of the time, few enough that two
/// threads share a block of rows evenly.
const NODES_PER_TASK: usize = 128;

/// One axis of a map: a key scanned from `min` to `max` (both included) over `cells` nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    pub key: ScanKey,
    /// In the key's unit.
    pub min: f64,
    /// In the key's unit.
    pub max: f64,
    /// Grid nodes along this axis (≥ 1); one node sits at the middle of the range.
    pub cells: usize,
}

impl Axis {
    /// An axis from `KEY:MIN:MAX`, e.g. `initial.angular_velocity.x:-60:60`.
    pub fn parse(spec: &str, cells: usize) -> Result<Axis, Error> {
        let parts: Vec<&str> = spec.split(':').collect();
        let bad = |message: String| Error::Axis {
            spec: spec.to_string(),
            message,
        };
        let [key, min, max] = parts[..] else {
            return Err(bad("expected KEY:MIN:MAX".to_string()));
        };
        let key = ScanKey::parse(key.trim())?;
        let number = |s: &str| {
            s.trim()
                .parse::<f64>()
                .map_err(|_| bad(format!("`{s}` is not a number")))
        };
        Axis::new(key, number(min)?, number(max)?, cells).map_err(|e| match e {
            Error::Axis { message, .. } => bad(message),
            e => e,
        })
    }

    /// Checks both ends against the key's allowed range and that `min < max` (or `min <= max`
    /// for a single node).
    pub fn new(key: ScanKey, min: f64, max: f64, cells: usize) -> Result<Axis, Error> {
        // The ends as typed (1e-200, not a 202-character decimal).
        let (low, high) = (fmt_exact(min), fmt_exact(max));
        let bad = |message: String| Error::Axis {
            spec: format!("{}:{low}:{high}", key.key),
            message,
        };
        if cells == 0 {
            return Err(bad("an axis needs at least 1 cell".to_string()));
        }
        key.check(min)?;
        key.check(max)?;
        if min > max || (min == max && cells > 1) {
            return Err(bad(format!("MIN ({low}) must be below MAX ({high})")));
        }
        Ok(Axis { key, min, max, cells })
    }

    /// The value at node `i` (0-based), exact at both ends.
    pub fn value(&self, i: usize) -> f64 {
        let n = self.cells;
        if n == 1 {
            0.5 * (self.min + self.max)
        } else if i == 0 {
            self.min
        } else if i + 1 == n {
            self.max
        } else {
            self.min + (self.max - self.min) * (i as f64 / (n - 1) as f64)
        }
    }

    /// The distance between neighbouring nodes (the whole range for a single node).
    pub fn spacing(&self) -> f64 {
        (self.max - self.min) / (self.cells.max(2) - 1) as f64
    }
}

/// What to map: two axes and how to sample them.
#[derive(Debug, Clone, PartialEq)]
pub struct MapSpec {
    pub x: Axis,
    pub y: Axis,
    pub method: Method,
}

/// How a map was computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Coarse grid, then splitting only blocks whose corners differ.
    Adaptive,
    /// Every node rolled.
    Uniform,
}

impl Method {
    pub fn name(self) -> &'static str {
        match self {
            Method::Adaptive => "adaptive",
            Method::Uniform => "uniform",
        }
    }
}

/// What a map shows per cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layer {
    /// The face up at the end.
    Face,
    /// s of simulated time until the roll ended.
    SettleTime,
}

impl Layer {
    pub fn name(self) -> &'static str {
        match self {
            Layer::Face => "face",
            Layer::SettleTime => "settle-time",
        }
    }
}

/// One node of a map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cell {
    pub outcome: Outcome,
    /// The face most nearly up at t = 0.
    pub start_face: u8,
    /// Rolled (true), or filled from the agreeing corners of its block (false).
    pub sampled: bool,
}

impl Cell {
    /// What the adaptive method compares: two cells agree when they end alike.
    fn class(&self) -> (Status, Option<u8>) {
        (self.outcome.status, self.outcome.face)
    }
}

/// A basin map, complete or partial. Cell `(i, j)` is x node `i`, y node `j`; rows run
/// from `y.min` (j = 0) up.
#[derive(Debug, Clone, PartialEq)]
pub struct BasinMap {
    pub x: Axis,
    pub y: Axis,
    pub method: Method,
    /// Row-major, `j * width + i`; `None` where nothing is known yet (a partial map).
    pub cells: Vec<Option<Cell>>,
    /// The numbers the map's die shows ([`Die::face_numbers`](dicesim_physics::Die::face_numbers)),
    /// in the order its key and colours list them.
    pub numbers: &'static [u8],
    /// How many cells were rolled.
    pub sampled: usize,
    /// False for a partial map (delivered while running, or after a cancel).
    pub complete: bool,
    /// For an adaptive map that rolled every remaining cell: after how many refinement
    /// passes, and the share of the parts of the blocks split at the last one that still
    /// differed.
    pub switched_to_uniform: Option<(usize, f64)>,
}

impl BasinMap {
    pub fn width(&self) -> usize {
        self.x.cells
    }

    pub fn height(&self) -> usize {
        self.y.cells
    }

    pub fn cell(&self, i: usize, j: usize) -> Option<&Cell> {
        self.cells[j * self.width() + i].as_ref()
    }

    /// The faces of the cells rolled or filled so far.
    pub fn face_tally(&self) -> FaceTally {
        self.face_tally_of(&self.cells)
    }

    /// The faces of `cells`, some of this map's.
    pub(crate) fn face_tally_of(&self, cells: &[Option<Cell>]) -> FaceTally {
        let mut tally = FaceTally::new(self.numbers);
        (cells.iter().flatten().filter_map(|c| c.outcome.face)).for_each(|f| tally.add(f));
        tally
    }

    /// How the map was computed, in words.
    pub fn method_report(&self) -> String {
        let total = self.cells.len();
        let rolled = format!(
            "{} of {} cells rolled ({:.1}%)",
            self.sampled,
            total,
            100.0 * self.sampled as f64 / total.max(1) as f64
        );
        match (self.method, self.switched_to_uniform) {
            (Method::Uniform, _) => "uniform grid: every cell rolled".to_string(),
            (Method::Adaptive, None) => {
                format!("adaptive: {rolled}, the rest filled from agreeing neighbours")
            }
            (Method::Adaptive, Some((passes, share))) => format!(
                "adaptive: {rolled}; after {passes} refinement{} {:.0}% of the split blocks' parts still differed, so every remaining cell was rolled",
                if passes == 1 { "" } else { "s" },
                100.0 * share
            ),
        }
    }
}

impl BasinMap {
    /// The map's CSV columns: the node (`i`, `j`), both keys' values named with their units
    /// ([`ScanKey::column`]), the cell's ending and whether it was rolled.
    pub fn csv_columns(&self) -> Vec<Column> {
        vec![
            Column::integer("i"),
            Column::integer("j"),
            Column::real(self.x.key.column()),
            Column::real(self.y.key.column()),
            Column::integer("start_face"),
            Column::integer("face"),
            Column::text("status"),
            Column::integer("steps"),
            Column::real("time_s"),
            Column::integer("sampled"),
        ]
    }

    /// The map as CSV: the header ([`BasinMap::csv_columns`]), then one row per cell in row
    /// order, with `sampled` = 1 for rolled cells and 0 for cells filled by the adaptive
    /// method. Unknown cells of a partial map are left out.
    pub fn write_csv(&self, w: &mut (impl Write + ?Sized)) -> std::io::Result<()> {
        writeln!(w, "{}", crate::data_file::header(&self.csv_columns()))?;
        let mut line = String::with_capacity(96);
        for j in 0..self.height() {
            for i in 0..self.width() {
                let Some(c) = self.cell(i, j) else { continue };
                line.clear();
                self.write_row(&mut line, i, j, c);
                line.push('\n');
                w.write_all(line.as_bytes())?;
            }
        }
        Ok(())
    }

    /// Appends cell `(i, j)`'s row (without its line end): its cells are numbers and status
    /// names, which CSV never quotes; reals with their point.
    pub(crate) fn write_row(&self, line: &mut String, i: usize, j: usize, c: &Cell) {
        use std::fmt::Write as _;
        let o = &c.outcome;
        let face = o.face.map(|f| f.to_string()).unwrap_or_default();
        // Writing into a String cannot fail.
        let _ = write!(
            line,
            "{i},{j},{},{},{},{face},{},{},{},{}",
            Real(self.x.value(i)),
            Real(self.y.value(j)),
            c.start_face,
            o.status.name(),
            o.steps,
            Real(o.time_s),
            u8::from(c.sampled)
        );
    }

    /// Writes the map's CSV file and its sidecar (atomically, both or neither): the map's
    /// rows ([`BasinMap::write_csv`]) and `provenance`; returns the CSV's size and content
    /// hash, which a shard's part records.
    pub fn write_csv_file(
        &self,
        provenance: &serde_json::Value,
        output: &Output,
    ) -> Result<Written, OutputError> {
        let mut written = None;
        let meta = crate::data_file::sidecar(provenance, &self.csv_columns());
        output.write_table(Some(&meta), |w| {
            let mut hashing = Hashing::new(w);
            self.write_csv(&mut hashing)?;
            written = Some(hashing.seal());
            Ok(())
        })?;
        Ok(written.expect("the file was written"))
    }
}

/// The most cells a map takes (e.g. 2048×2048): the map and its partial copy stay in memory.
pub const MAX_CELLS: usize = crate::limits::MAP_CELLS.max as usize;

/// Why a map with axes `x` and `y` would not apply a change of `key` to its preset (a
/// `--set`), as [`dicesim_setup::preset::refuse_unapplied`] asks: an axis sets it in every
/// cell, and a map rolls the preset's one start, drawing nothing from `random.*`.
pub fn unapplied_by_map(key: &str, x: &Axis, y: &Axis) -> Option<String> {
    [x, y]
        .into_iter()
        .find(|axis| axis.key.overlaps(key))
        .map(|axis| format!("the map sets it in every cell (its axis `{}`)", axis.key.key))
        .or_else(|| dicesim_setup::random::unapplied_when_fixed(key, "basin"))
}

/// The check `roll` makes of its setup ([`check_setup`]), made of every node of a map with
/// axes `x` and `y` before any is rolled: the first node refused (a body that cannot exist,
/// a start inside the table) is the error, with its axis values and the setup's own words.
/// A map is refused whole rather than drawn with cells that are no outcome.
pub fn check_nodes(params: &Params, base: &InitialCondition, x: &Axis, y: &Axis) -> Result<(), Error> {
    for j in 0..y.cells {
        for i in 0..x.cells {
            let (p, ic) = node_setup(params, base, x, y, i, j);
            check_setup(&p, &ic).map_err(|error| Error::Node {
                error: Box::new(error),
                node: format!(
                    "{} = {}, {} = {}",
                    x.key.key,
                    fmt_exact(x.value(i)),
                    y.key.key,
                    fmt_exact(y.value(j))
                ),
            })?;
        }
    }
    Ok(())
}

/// The setup of node `(i, j)`: `base` with the two keys set to the nodes' values.
pub fn node_setup(
    params: &Params,
    base: &InitialCondition,
    x: &Axis,
    y: &Axis,
    i: usize,
    j: usize,
) -> (Params, InitialCondition) {
    let (mut p, mut ic) = (*params, *base);
    x.key.set(&mut p, &mut ic, x.value(i));
    y.key.set(&mut p, &mut ic, y.value(j));
    (p, ic)
}

/// Computes the map `spec` around `params` and `base` on `jobs` threads (0: one per core),
/// with the engine of [`RunOptions::default`] (the lane engine where the CPU has AVX2).
///
/// `on_partial` is called on the calling thread with the map so far: after each block of
/// rows (uniform) or each refinement level (adaptive, every cell then filled from the
/// nearest rolled corner of its block). The result is the same for any `jobs` and engine.
pub fn run_map(
    params: &Params,
    base: &InitialCondition,
    spec: &MapSpec,
    jobs: usize,
    cancel: &AtomicBool,
    on_partial: &mut dyn FnMut(&BasinMap),
) -> Result<BasinMap, Error> {
    let options = RunOptions {
        jobs,
        ..RunOptions::default()
    };
    run_map_with(params, base, spec, &options, cancel, on_partial)
}

/// [`run_map`] with a choice of threads and engine.
///
/// Setting `cancel` stops the running rolls within a few thousand steps and returns the map
/// as far as it got (`complete == false`): for a uniform map an exact prefix of its cells in
/// row order, for an adaptive one the last whole level.
pub fn run_map_with(
    params: &Params,
    base: &InitialCondition,
    spec: &MapSpec,
    options: &RunOptions,
    cancel: &AtomicBool,
    on_partial: &mut dyn FnMut(&BasinMap),
) -> Result<BasinMap, Error> {
    run_map_rows(params, base, spec, 0..spec.y.cells, options, cancel, on_partial)
}

/// [`run_map_with`] over the rows `rows` of the map only (a shard of it): the other rows
/// stay unknown, and the map is complete when these are. Only the uniform method can split
/// rows, since adaptive refinement compares cells across row boundaries.
pub fn run_map_rows(
    params: &Params,
    base: &InitialCondition,
    spec: &MapSpec,
    rows: Range<usize>,
    options: &RunOptions,
    cancel: &AtomicBool,
    on_partial: &mut dyn FnMut(&BasinMap),
) -> Result<BasinMap, Error> {
    params.validate()?;
    base.validate()?;
    check_nodes(params, base, &spec.x, &spec.y)?;
    if rows.end > spec.y.cells || (spec.method == Method::Adaptive && rows != (0..spec.y.cells)) {
        return Err(Error::Shard(format!(
            "rows {}..{} of a {}-row {} map: only a uniform map splits into rows",
            rows.start,
            rows.end,
            spec.y.cells,
            spec.method.name()
        )));
    }
    let pool = thread_pool(options.jobs)?;
    let engine = options.engine.resolve();
    let MapSpec { x, y, method } = spec;
    let method = *method;
    let mut map = BasinMap {
        x: x.clone(),
        y: y.clone(),
        method,
        cells: vec![None; x.cells * y.cells],
        numbers: params.die.face_numbers(),
        sampled: 0,
        complete: false,
        switched_to_uniform: None,
    };
    let stopped = || cancel.load(Ordering::Relaxed);
    // Rolls `nodes`; false if a cancel cut it short (then some of them are left unknown).
    let roll = |map: &mut BasinMap, nodes: &[(usize, usize)]| -> bool {
        let done: Vec<(usize, Vec<RollRecord>)> = pool.install(|| {
            nodes
                .par_chunks(NODES_PER_TASK)
                .map(|chunk| {
                    // A chunk started after a cancel would step its rolls until their first
                    // stop check: thousands of chunks of a big map's level took seconds.
                    if stopped() {
                        return (chunk.len(), Vec::new());
                    }
                    let setups: Vec<_> = chunk
                        .iter()
                        .map(|&(i, j)| {
                            let (p, ic) = node_setup(params, base, x, y, i, j);
                            ((j * x.cells + i) as u64, p, ic)
                        })
                        .collect();
                    (chunk.len(), roll_setups(engine, &setups, &stopped))
                })
                .collect()
        });
        let mut whole = true;
        for (asked, records) in done {
            whole &= records.len() == asked;
            map.sampled += records.len();
            for r in records {
                map.cells[r.id as usize] = Some(Cell {
                    outcome: r.outcome,
                    start_face: r.start_face,
                    sampled: true,
                });
            }
        }
        whole
    };
    match method {
        Method::Uniform => {
            let rows_per_block = (pool.current_num_threads() * 4 * NODES_PER_TASK / x.cells).max(1);
            let mut j0 = rows.start;
            map.complete = rows.is_empty();
            while j0 < rows.end {
                let j1 = (j0 + rows_per_block).min(rows.end);
                let nodes: Vec<_> = (j0..j1).flat_map(|j| (0..x.cells).map(move |i| (i, j))).collect();
                if !roll(&mut map, &nodes) || stopped() {
                    // Keep only the exact prefix of the rows' cells in row order, so that
                    // what a cancelled map shows or writes is what a longer run agrees with.
                    let first = rows.start * x.cells;
                    let known = map.cells[first..].iter().take_while(|c| c.is_some()).count();
                    map.cells[first + known..].iter_mut().for_each(|c| *c = None);
                    map.sampled = known;
                    map.complete = false;
                    on_partial(&map);
                    return Ok(map);
                }
                j0 = j1;
                map.complete = j0 == rows.end;
                on_partial(&map);
            }
            Ok(map)
        }
        Method::Adaptive => {
            let xs = coarse_nodes(x.cells);
            let ys = coarse_nodes(y.cells);
            let nodes: Vec<_> = ys.iter().flat_map(|&j| xs.iter().map(move |&i| (i, j))).collect();
            if !roll(&mut map, &nodes) {
                on_partial(&map);
                return Ok(map);
            }
            let mut pending: Vec<Block> = Vec::new();
            for w in ys.windows(2.min(ys.len())) {
                for v in xs.windows(2.min(xs.len())) {
                    pending.push(Block {
                        x0: v[0],
                        x1: v[v.len() - 1],
                        y0: w[0],
                        y1: w[w.len() - 1],
                    });
                }
            }
            let mut settled: Vec<Block> = Vec::new();
            let mut split = 0;
            for passes in 0.. {
                let (done, refine): (Vec<Block>, Vec<Block>) = pending
                    .drain(..)
                    .partition(|b| b.is_single() || b.corners_agree(&map));
                settled.extend(done);
                // Of the blocks the last pass split, the share whose parts still differ.
                let still_differ = refine.len() as f64 / (4 * split).max(1) as f64;
                if passes > 0 && still_differ > UNIFORM_SWITCH_SHARE {
                    map.switched_to_uniform = Some((passes, still_differ));
                    let rest: Vec<_> = (0..map.cells.len())
                        .filter(|&n| map.cells[n].is_none())
                        .map(|n| (n % x.cells, n / x.cells))
                        .collect();
                    let mut shown = map.clone();
                    fill(&mut shown, settled.iter().chain(&refine));
                    if !roll(&mut map, &rest) {
                        // Half the remaining cells would mix rolled and filled ones unmarked.
                        on_partial(&shown);
                        return Ok(shown);
                    }
                    map.complete = true;
                    on_partial(&map);
                    return Ok(map);
                }
                let mut shown = map.clone();
                fill(&mut shown, settled.iter().chain(&refine));
                shown.complete = refine.is_empty();
                on_partial(&shown);
                if refine.is_empty() || stopped() {
                    return Ok(shown);
                }
                split = refine.len();
                let next: Vec<Block> = refine.into_iter().flat_map(Block::split).collect();
                let mut nodes: Vec<_> = next.iter().flat_map(Block::corners).collect();
                nodes.sort_unstable_by_key(|&(i, j)| (j, i));
                nodes.dedup();
                nodes.retain(|&(i, j)| map.cell(i, j).is_none());
                if !roll(&mut map, &nodes) {
                    // Half a level would show blocks filled from corners not yet rolled.
                    return Ok(shown);
                }
                pending = next;
            }
            unreachable!("the refinement loop returns")
        }
    }
}

/// Coarse nodes along an axis of `n`: every `s`-th node and the last, with `s` a power of
/// two about 1/16 of the axis, so the coarse grid holds about 1/256 of a 2-D map.
fn coarse_nodes(n: usize) -> Vec<usize> {
    let target = ((n.max(1) - 1) / 16).max(1);
    let step = 1 << target.ilog2();
    let mut nodes: Vec<usize> = (0..n).step_by(step).collect();
    if nodes.last() != Some(&(n - 1)) {
        nodes.push(n - 1);
    }
    nodes
}

/// A block of the adaptive grid between rolled corner nodes (inclusive bounds).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Block {
    x0: usize,
    x1: usize,
    y0: usize,
    y1: usize,
}

impl Block {
    /// No nodes between the corners: nothing left to split.
    fn is_single(&self) -> bool {
        self.x1 - self.x0 <= 1 && self.y1 - self.y0 <= 1
    }

    fn corners(&self) -> [(usize, usize); 4] {
        [
            (self.x0, self.y0),
            (self.x1, self.y0),
            (self.x0, self.y1),
            (self.x1, self.y1),
        ]
    }

    fn corners_agree(&self, map: &BasinMap) -> bool {
        let class = |(i, j)| map.cell(i, j).map(Cell::class);
        let first = class((self.x0, self.y0));
        self.corners().into_iter().all(|c| class(c) == first)
    }

    /// Halves the block along each axis that has nodes between its corners.
    fn split(self) -> Vec<Block> {
        let halves = |a: usize, b: usize| {
            if b - a > 1 {
                let m = a + (b - a) / 2;
                vec![(a, m), (m, b)]
            } else {
                vec![(a, b)]
            }
        };
        let mut out = Vec::with_capacity(4);
        for (y0, y1) in halves(self.y0, self.y1) {
            for (x0, x1) in halves(self.x0, self.x1) {
                out.push(Block { x0, x1, y0, y1 });
            }
        }
        out
    }
}

/// Fills every unknown cell of each block from the nearest of its corners (all equal for a
/// block whose corners agree), marked as not sampled.
fn fill<'a>(map: &mut BasinMap, blocks: impl Iterator<Item = &'a Block>) {
    let w = map.width();
    for b in blocks {
        for j in b.y0..=b.y1 {
            for i in b.x0..=b.x1 {
                if map.cells[j * w + i].is_some() {
                    continue;
                }
                let ci = if i - b.x0 <= b.x1 - i { b.x0 } else { b.x1 };
                let cj = if j - b.y0 <= b.y1 - j { b.y0 } else { b.y1 };
                map.cells[j * w + i] = map.cells[cj * w + ci].map(|c| Cell { sampled: false, ..c });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis(spec: &str, cells: usize) -> Axis {
        Axis::parse(spec, cells).unwrap()
    }

    #[test]
    fn nodes_include_both_ends() {
        let a = axis("initial.height:0.1:0.3", 7);
        assert_eq!(a.value(0), 0.1);
        assert_eq!(a.value(6), 0.3);
        assert!((a.value(3) - 0.2).abs() < 1e-15);
        assert_eq!(axis("ground.friction:0.5:1.5", 1).value(0), 1.0);
        assert_eq!(axis("ground.friction:0.5:0.5", 1).value(0), 0.5);
    }

    #[test]
    fn the_first_node_starting_in_the_table_is_named() {
        let (params, base) = (Params::default(), InitialCondition::default());
        let y = axis("ground.friction:0.2:0.8", 2);
        assert_eq!(
            check_nodes(&params, &base, &axis("initial.height:5:15", 3), &y),
            Ok(())
        );
        // A cube of half size 1 cm level on the table needs its centre 1 cm up: the nodes of
        // the first row, at 0.5 cm, start with corners inside, and the first of them is named.
        let x = axis("ground.friction:0.2:0.8", 2);
        let e = check_nodes(&params, &base, &x, &axis("initial.height:0.5:5", 2))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("the node ground.friction = 0.2, initial.height = 0.5: "),
            "{e}"
        );
    }

    #[test]
    fn a_node_whose_body_cannot_exist_is_refused_in_the_words_roll_uses() {
        // The red team's maps: corner radii up to 2 on a half size 1, pips deeper than their
        // radius, and a half size below the corner radius; each node that is no body is named
        // with roll's own refusal, before anything is rolled.
        let base = InitialCondition::default();
        let cases = [
            ("die.corner_radius:0:2", Params::default()),
            ("die.pip_depth:0:0.3", {
                let mut p = Params::default();
                p.die.pip_diameter = 0.3;
                p
            }),
            ("die.half_sizes.x:0.1:1", {
                let mut p = Params::default();
                p.die.corner_radius = 0.5;
                p
            }),
        ];
        for (x, params) in cases {
            let (x, y) = (axis(x, 5), axis("ground.friction:0.2:0.8", 2));
            let e = check_nodes(&params, &base, &x, &y).unwrap_err();
            let Error::Node { node, error } = &e else {
                panic!("{e}")
            };
            let (i, j) = (0..x.cells)
                .flat_map(|i| [(i, 0)])
                .find(|&(i, j)| {
                    let (p, ic) = node_setup(&params, &base, &x, &y, i, j);
                    check_setup(&p, &ic).is_err()
                })
                .unwrap();
            let (p, ic) = node_setup(&params, &base, &x, &y, i, j);
            assert_eq!(**error, check_setup(&p, &ic).unwrap_err(), "{e}");
            assert!(
                node.starts_with(&format!("{} = {}", x.key.key, x.value(i))),
                "{e}"
            );
            let spec = MapSpec {
                x,
                y,
                method: Method::Uniform,
            };
            let ran = run_map(&params, &base, &spec, 1, &AtomicBool::new(false), &mut |_| {
                panic!("a map of a body that cannot exist was rolled")
            });
            assert_eq!(ran.unwrap_err(), e);
        }
    }

    #[test]
    fn coarse_nodes_nest_in_the_grid() {
        assert_eq!(coarse_nodes(1), vec![0]);
        assert_eq!(coarse_nodes(2), vec![0, 1]);
        assert_eq!(coarse_nodes(20), (0..20).collect::<Vec<_>>());
        let n = coarse_nodes(200);
        assert_eq!(n.len(), 26);
        assert_eq!((n[1], n[24], n[25]), (8, 192, 199));
    }

    #[test]
    fn bad_axes_name_the_problem() {
        let e = |s: &str| Axis::parse(s, 10).unwrap_err().to_string();
        assert_eq!(
            e("initial.height:5:1"),
            "`initial.height:5:1`: MIN (5) must be below MAX (1)"
        );
        assert_eq!(e("initial.height:5"), "`initial.height:5`: expected KEY:MIN:MAX");
        assert_eq!(
            e("initial.height:a:1"),
            "`initial.height:a:1`: `a` is not a number"
        );
        assert_eq!(
            e("ground.friction:0:9"),
            "`ground.friction` = 9 is outside the allowed range 0 to 5"
        );
        assert!(e("initial.hight:0:1").starts_with("`initial.hight` is not a numeric setup key"));
    }

    #[test]
    fn splitting_covers_the_block() {
        let b = Block {
            x0: 0,
            x1: 5,
            y0: 3,
            y1: 4,
        };
        assert_eq!(
            b.split(),
            vec![
                Block {
                    x0: 0,
                    x1: 2,
                    y0: 3,
                    y1: 4
                },
                Block {
                    x0: 2,
                    x1: 5,
                    y0: 3,
                    y1: 4
                }
            ]
        );
    }
}
