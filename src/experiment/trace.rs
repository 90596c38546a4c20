//! A roll's trajectory and energies as CSV rows (`dicesim trace`, and the explorer's export),
//! and the export of one roll: its trace and its energy plot, written side by side.

use super::Error;
use super::energy_plot::write_energy_plot;
use crate::physics::{InitialCondition, Params, Simulation};
use std::path::{Path, PathBuf};

/// The CSV columns; the corner columns follow docs/model.md's corner order.
pub(crate) fn header() -> Vec<String> {
    let mut h: Vec<String> = "step,t,x,y,z,vx,vy,vz,Lx,Ly,Lz,wx,wy,wz,e_trans,e_rot,e_grav,e_elastic,e_total"
        .split(',')
        .map(str::to_string)
        .collect();
    for k in 1..=8 {
        h.extend(["x", "y", "z"].map(|a| format!("c{k}{a}")));
    }
    h
}

/// One CSV record for the simulation's current state; numbers in Rust's shortest
/// round-trip form, so reading them back gives the same bits.
pub(crate) fn row(sim: &Simulation) -> Vec<String> {
    let s = sim.state();
    let e = sim.energy();
    let w = sim.angular_velocity();
    let mut record = vec![s.step.to_string(), s.time_s.to_string()];
    let values = s
        .position
        .iter()
        .chain(s.velocity.iter())
        .chain(s.angular_momentum.iter())
        .chain(w.iter());
    record.extend(
        values
            .copied()
            .chain([
                e.translational,
                e.rotational,
                e.gravitational,
                e.elastic,
                e.total(),
            ])
            .map(|v| v.to_string()),
    );
    for p in sim.corner_positions() {
        record.extend([p.x, p.y, p.z].map(|v| v.to_string()));
    }
    record
}

/// A trace as CSV: the header, then one record per [`TraceWriter::write`].
pub(crate) struct TraceWriter<W: std::io::Write> {
    csv: csv::Writer<W>,
}

impl<W: std::io::Write> TraceWriter<W> {
    /// Writes the header into `out`.
    pub(crate) fn new(out: W) -> std::io::Result<Self> {
        let mut csv = csv::Writer::from_writer(out);
        csv.write_record(header()).map_err(super::csv_io)?;
        Ok(TraceWriter { csv })
    }

    /// One record for the simulation's current state.
    pub(crate) fn write(&mut self, sim: &Simulation) -> std::io::Result<()> {
        self.csv.write_record(row(sim)).map_err(super::csv_io)
    }

    pub(crate) fn flush(&mut self) -> std::io::Result<()> {
        self.csv.flush()
    }
}

/// What [`export_roll`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Exported {
    pub(crate) trace: PathBuf,
    pub(crate) plot: PathBuf,
}

/// The first stem for files `<stem>.<ext>` (one per extension) in `dir` that replaces no
/// file: `stem`, then `stem-2`, `stem-3`, …
pub(crate) fn free_stem(dir: &Path, stem: &str, extensions: &[&str]) -> String {
    (1..)
        .map(|n| {
            if n == 1 {
                stem.to_string()
            } else {
                format!("{stem}-{n}")
            }
        })
        .find(|s| {
            extensions
                .iter()
                .all(|ext| !dir.join(format!("{s}.{ext}")).exists())
        })
        .unwrap_or_else(|| stem.to_string())
}

/// Rolls `initial` again from t = 0 to its end, writing every step's row to
/// `<dir>/<stem>.csv` and the energy against time to `<dir>/<stem>.png`.
pub(crate) fn export_roll(
    params: &Params,
    initial: &InitialCondition,
    title: &str,
    dir: &Path,
    stem: &str,
) -> Result<Exported, Error> {
    let io = |path: &Path, e: std::io::Error| Error::Export(format!("{}: {e}", path.display()));
    let trace = dir.join(format!("{stem}.csv"));
    let plot = dir.join(format!("{stem}.png"));
    let mut sim = Simulation::new_unchecked(params, initial);
    let file = std::fs::File::create(&trace).map_err(|e| io(&trace, e))?;
    let mut out = TraceWriter::new(file).map_err(|e| io(&trace, e))?;
    let mut samples = Vec::new();
    loop {
        out.write(&sim).map_err(|e| io(&trace, e))?;
        samples.push((sim.state().time_s, sim.energy()));
        if sim.outcome().is_some() {
            break;
        }
        sim.advance();
    }
    out.flush().map_err(|e| io(&trace, e))?;
    write_energy_plot(&samples, sim.stop_threshold(), title, &plot).map_err(|e| match e {
        Error::Plot(m) => Error::Export(format!("{}: {m}", plot.display())),
        e => e,
    })?;
    Ok(Exported { trace, plot })
}
