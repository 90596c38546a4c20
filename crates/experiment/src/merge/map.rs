//! A basin map's parts merged: every row checked against its node and the part's face
//! counts, the merged rows written as the one-machine CSV as they are read, and every cell
//! kept for the images the caller draws.

use super::parts::{
    MergeError, Parts, checked_records_path, chosen_at_random, out_kind, outcome_words, row_error,
};
use super::rows::{copy_rows, parse_map_row};
use crate::basin::{Axis, BasinMap, Cell, Layer, Method, node_setup};
use crate::columns::RecordCheck;
use crate::provenance;
use crate::record::roll_record;
use crate::shard::{Part, Sweep};
use crate::stats::FaceTally;
use dicesim_physics::{InitialCondition, Params};
use dicesim_setup::number::Real;
use dicesim_setup::output::{Output, Staged, sidecar_path};
use dicesim_setup::preset::{Preset, read_regular_file};
use rayon::prelude::*;
use std::io::{BufReader, Write};

/// A merged map: its cells (every one, once a merged file or `--verify` read them) and
/// what `merge` prints and draws of it.
#[derive(Debug, Clone)]
pub struct MapMerge {
    pub map: BasinMap,
    /// The layer the sweep's images show.
    pub layer: Layer,
    /// The faces the parts count, added up.
    pub faces: FaceTally,
    /// The setup the parts record.
    pub preset: Preset,
    /// The map's provenance, as its images record it.
    pub provenance: serde_json::Value,
    pub shards: usize,
    /// s of wall-clock time of all shards added up, and of the longest.
    pub shard_s: f64,
    pub longest_s: f64,
    /// Cells rolled again by `--verify`.
    pub verified: usize,
}

impl MapMerge {
    /// The cells the merged map knows: all of them, as its parts are complete, whether or
    /// not this merge read them.
    pub fn known_cells(&self) -> u64 {
        (self.map.width() * self.map.height()) as u64
    }
}

impl Parts {
    /// Merges a map's parts: the merged CSV for the .csv among `outputs`, staged (the .png
    /// and .svg are the caller's to draw from the cells returned, and to commit with it, so
    /// all are written or none), after checking every row against its node and every
    /// part's face counts; `verify` cells chosen at random are rolled again and must end
    /// bit for bit as their rows say.
    pub fn merge_map(
        &self,
        outputs: &[Output],
        verify: u64,
    ) -> Result<(MapMerge, Option<Staged>), MergeError> {
        let Sweep::Map {
            x,
            y,
            width,
            height,
            layer,
            ..
        } = &self.first().sweep
        else {
            unreachable!("merge_map is called for maps")
        };
        let preset = self.setup()?;
        let params = preset.params();
        params.validate()?;
        let bad_sweep = |e: String| MergeError::Parts(format!("{}: {e}", self.parts[0].0.display()));
        let x = Axis::parse(x, *width).map_err(|e| bad_sweep(e.to_string()))?;
        let y = Axis::parse(y, *height).map_err(|e| bad_sweep(e.to_string()))?;
        let layer = [Layer::Face, Layer::SettleTime]
            .into_iter()
            .find(|l| l.name() == layer)
            .ok_or_else(|| bad_sweep(format!("unknown layer `{layer}`")))?;
        let numbers = params.die.face_numbers();
        let faces = self.faces(numbers)?;
        let mut map = BasinMap {
            x,
            y,
            method: Method::Uniform,
            cells: vec![None; width * height],
            numbers,
            sampled: 0,
            complete: true,
            switched_to_uniform: None,
        };
        for output in outputs {
            out_kind(output.path(), &["csv", "png", "svg"])?;
        }
        let chosen = chosen_at_random(width * height, verify);
        let sweep = provenance::map(&preset, &map);
        let provenance = provenance::built_by(sweep.clone(), &self.builds());
        let mut staged = None;
        if !outputs.is_empty() || !chosen.is_empty() {
            let setup = (&params, &preset.initial);
            match outputs.iter().find(|o| o.extension() == "csv") {
                Some(csv) => {
                    let meta = crate::data_file::sidecar(&provenance, &map.csv_columns());
                    let mut sink = csv.stage(Some(&meta)).map_err(MergeError::unwritten)?;
                    let failed = |e: std::io::Error| MergeError::unwritten(csv.failed(&e));
                    self.read_cells(&mut map, setup, &sweep, (&mut sink, &failed), &chosen)?;
                    staged = Some(sink);
                }
                None => {
                    let sink = &mut std::io::sink();
                    self.read_cells(&mut map, setup, &sweep, (sink, &MergeError::Io), &chosen)?;
                }
            }
            map.sampled = map.cells.iter().flatten().filter(|c| c.sampled).count();
        } else {
            // Read no cell: the parts are complete (checked), and a sharded map rolls them all.
            map.sampled = width * height;
        }
        let (shard_s, longest_s) = self.shard_times();
        let merged = MapMerge {
            map,
            layer,
            faces,
            preset,
            provenance,
            shards: self.parts.len(),
            shard_s,
            longest_s,
            verified: chosen.len(),
        };
        Ok((merged, staged))
    }

    /// The face counts every part claims, added up: each one count per number the setup's
    /// die shows (`numbers`).
    fn faces(&self, numbers: &'static [u8]) -> Result<FaceTally, MergeError> {
        let mut faces = FaceTally::new(numbers);
        for (path, p) in self.iter() {
            faces.merge(&part_faces(path, p, numbers)?);
        }
        Ok(faces)
    }

    /// One pass over the parts: their rows copied to `sink` (the merged CSV) after the
    /// header, every cell checked and kept in `map`, each part's sidecar checked against
    /// `sweep` (the map's provenance) as its build wrote it; then each part's face counts
    /// and the cells `chosen` rolled again are checked, before the merged CSV is kept, so a
    /// refused merge writes nothing.
    ///
    /// `failed` words a failure to write to `sink`; the rows' own are named by their file.
    fn read_cells(
        &self,
        map: &mut BasinMap,
        (params, base): (&Params, &InitialCondition),
        sweep: &serde_json::Value,
        (sink, failed): (&mut (dyn Write + Send), &dyn Fn(std::io::Error) -> MergeError),
        chosen: &[usize],
    ) -> Result<(), MergeError> {
        let header = crate::data_file::header(&map.csv_columns());
        writeln!(sink, "{header}").map_err(failed)?;
        let leading = [header.as_str()];
        let w = map.width();
        let check = RecordCheck::new(params);
        for (path, p) in self.iter() {
            let records = checked_records_path(path, p)?;
            check_map_sidecar(&records, sweep, p, map)?;
            let reader = std::fs::File::open(&records)
                .map(|f| BufReader::with_capacity(1 << 20, f))
                .map_err(|e| MergeError::Parts(format!("{}: {e}", records.display())))?;
            let first_cell = p.range[0] as usize * w;
            let (x, y, cells) = (&map.x, &map.y, &mut map.cells);
            copy_rows(reader, &mut *sink, &leading, p.len() * w as u64, &mut |n, row| {
                let index = first_cell + n as usize;
                let (i, j) = (index % w, index / w);
                let (nx, ny) = (Real(x.value(i)).to_string(), Real(y.value(j)).to_string());
                cells[index] = Some(parse_map_row(row, i, j, &check, Some((&nx, &ny)))?);
                Ok(())
            })
            .map_err(|e| row_error(&records, e))?;
        }
        self.check_faces(map)?;
        verify_cells(params, base, (&map.x, &map.y), &map.cells, chosen)
    }

    /// Refuses a part whose face counts are not those of its own cells.
    fn check_faces(&self, map: &BasinMap) -> Result<(), MergeError> {
        let w = map.width();
        for (path, p) in self.iter() {
            let rows = p.range[0] as usize * w..p.range[1] as usize * w;
            let found = map.face_tally_of(&map.cells[rows]);
            let claimed = part_faces(path, p, map.numbers)?;
            if found != claimed {
                return Err(MergeError::Parts(format!(
                    "{}: its face counts {:?} are not those of its cells {:?}",
                    path.display(),
                    claimed.counts,
                    found.counts
                )));
            }
        }
        Ok(())
    }
}

/// The face counts map part `p` (from the file at `path`) claims, as counts of a die that
/// shows `numbers`.
fn part_faces(path: &std::path::Path, p: &Part, numbers: &'static [u8]) -> Result<FaceTally, MergeError> {
    let refused = |e: String| MergeError::Parts(format!("{}: {e}", path.display()));
    let faces = p
        .map_faces
        .clone()
        .ok_or_else(|| refused("a map part without its face counts (`map_faces`)".to_string()))?;
    faces
        .of_die(numbers)
        .map_err(|e| refused(format!("`map_faces`: {e}")))
}

/// Checks that the sidecar of a map part's CSV says its cells are this sweep's (`sweep`,
/// as the part's build wrote it), with the map's columns.
fn check_map_sidecar(
    records: &std::path::Path,
    sweep: &serde_json::Value,
    part: &Part,
    map: &BasinMap,
) -> Result<(), MergeError> {
    let sidecar = sidecar_path(records);
    if std::fs::symlink_metadata(&sidecar).is_err() {
        return Err(MergeError::Parts(format!(
            "{}: its sidecar {} is missing: a CSV's provenance is in it, which merge checks (copy it with the cells)",
            records.display(),
            sidecar.display()
        )));
    }
    let want = crate::data_file::sidecar(
        &provenance::built_by(sweep.clone(), &part.commit),
        &map.csv_columns(),
    );
    let found = read_regular_file(&sidecar, 1 << 20)
        .map_err(|e| MergeError::Parts(format!("{}: {e}", sidecar.display())))?;
    let same = found.as_bytes() == want
        || serde_json::from_str::<serde_json::Value>(&found).ok()
            == serde_json::from_slice::<serde_json::Value>(&want).ok();
    if !same {
        return Err(MergeError::Parts(format!(
            "{}: its provenance or columns are not this map's (cells of another sweep or build)",
            sidecar.display()
        )));
    }
    Ok(())
}

/// Rolls the cells `chosen` (indices in row order) of a map with axes `(x, y)` again from
/// their nodes' starts (`base` with the two axis values set, as the shard rolled them) and
/// refuses the merge if any ends differently in any bit, its start face included.
fn verify_cells(
    params: &Params,
    base: &InitialCondition,
    (x, y): (&Axis, &Axis),
    cells: &[Option<Cell>],
    chosen: &[usize],
) -> Result<(), MergeError> {
    let w = x.cells;
    let again = |index: usize| {
        let (p, ic) = node_setup(params, base, x, y, index % w, index / w);
        roll_record(&p, &ic, index as u64)
    };
    let differs = |index: usize| {
        let r = again(index);
        match &cells[index] {
            Some(c) => {
                let (a, b) = (&c.outcome, &r.outcome);
                c.start_face != r.start_face
                    || (a.status, a.face, a.steps) != (b.status, b.face, b.steps)
                    || a.time_s.to_bits() != b.time_s.to_bits()
            }
            None => true,
        }
    };
    let Some(index) = chosen.par_iter().copied().find_first(|&k| differs(k)) else {
        return Ok(());
    };
    let r = again(index);
    let (i, j) = (index % w, index / w);
    let recorded = match &cells[index] {
        Some(c) => format!(
            "{} after {} steps (start face {})",
            outcome_words(&c.outcome),
            c.outcome.steps,
            c.start_face
        ),
        None => "nothing".to_string(),
    };
    Err(MergeError::Parts(format!(
        "--verify: cell ({i}, {j}) ({} = {}, {} = {}) rolled again ends {} after {} steps (start face {}), but its row says {recorded}: the cells are not what this setup rolls",
        x.key.key,
        x.value(i),
        y.key.key,
        y.value(j),
        outcome_words(&r.outcome),
        r.outcome.steps,
        r.start_face,
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn verify_refuses_a_cell_that_does_not_roll_as_its_row_says() {
        let paper = Preset::default();
        let params = paper.params();
        let x = Axis::parse("initial.height:5:15", 2).unwrap();
        let y = Axis::parse("ground.friction:0.4:1.2", 1).unwrap();
        let cell = |i: usize| {
            let (p, ic) = node_setup(&params, &paper.initial, &x, &y, i, 0);
            let r = roll_record(&p, &ic, i as u64);
            Some(Cell {
                outcome: r.outcome,
                start_face: r.start_face,
                sampled: true,
            })
        };
        let mut cells = vec![cell(0), cell(1)];
        assert!(verify_cells(&params, &paper.initial, (&x, &y), &cells, &[0, 1]).is_ok());
        cells[1].as_mut().unwrap().start_face = 7 - cells[1].unwrap().start_face;
        // Only the cells chosen are rolled again.
        assert!(verify_cells(&params, &paper.initial, (&x, &y), &cells, &[0]).is_ok());
        let e = verify_cells(&params, &paper.initial, (&x, &y), &cells, &[0, 1])
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with(
                "--verify: cell (1, 0) (initial.height = 15, ground.friction = 0.8) rolled again ends"
            ),
            "{e}"
        );
        cells[0] = None;
        let e = verify_cells(&params, &paper.initial, (&x, &y), &cells, &[0])
            .unwrap_err()
            .to_string();
        assert!(e.contains("but its row says nothing"), "{e}");
    }
}
