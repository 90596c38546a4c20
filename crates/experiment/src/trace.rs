//! A roll's trajectory and every quantity of [`dicesim_setup::quantity`] as CSV rows
//! (`dicesim trace`, and the explorer's export).

use dicesim_physics::Simulation;
use dicesim_setup::quantity::{QUANTITIES, read_all};

/// The CSV columns, each with its unit: the state (centre of mass, its velocity, angular
/// momentum, angular velocity), every quantity of [`QUANTITIES`], then the corners in
/// docs/model.md's corner order.
pub fn header() -> Vec<String> {
    let mut h: Vec<String> = vec!["step".to_string(), "t_s".to_string()];
    for (names, unit) in [
        (["x", "y", "z"], "cm"),
        (["vx", "vy", "vz"], "cm_per_s"),
        (["Lx", "Ly", "Lz"], "g_cm2_per_s"),
        (["wx", "wy", "wz"], "rad_per_s"),
    ] {
        h.extend(names.map(|n| format!("{n}_{unit}")));
    }
    h.extend(QUANTITIES.iter().map(|q| q.column.to_string()));
    for k in 1..=8 {
        h.extend(["x", "y", "z"].map(|a| format!("c{k}{a}_cm")));
    }
    h
}

/// One CSV record for the simulation's current state; numbers in Rust's shortest
/// round-trip form, so reading them back gives the same bits.
pub fn row(sim: &Simulation) -> Vec<String> {
    let s = sim.state();
    let w = sim.angular_velocity();
    let mut record = vec![s.step.to_string(), s.time_s.to_string()];
    let values = s
        .position
        .iter()
        .chain(s.velocity.iter())
        .chain(s.angular_momentum.iter())
        .chain(w.iter())
        .copied()
        .chain(read_all(sim));
    record.extend(values.map(|v| v.to_string()));
    for p in sim.corner_positions() {
        record.extend([p.x, p.y, p.z].map(|v| v.to_string()));
    }
    record
}

/// Bytes a record takes in the CSV: its fields, each followed by a comma or the newline
/// (numbers are never quoted).
pub fn record_len(record: &[String]) -> u64 {
    record.iter().map(|f| f.len() as u64 + 1).sum()
}

/// A trace as CSV: the header, then one record per [`TraceWriter::write`].
pub struct TraceWriter<W: std::io::Write> {
    csv: csv::Writer<W>,
}

impl<W: std::io::Write> TraceWriter<W> {
    /// Writes the header into `out`.
    pub fn new(out: W) -> std::io::Result<Self> {
        let mut csv = csv::Writer::from_writer(out);
        csv.write_record(header()).map_err(crate::csv_io)?;
        Ok(TraceWriter { csv })
    }

    /// One record for the simulation's current state; returns its length in bytes.
    pub fn write(&mut self, sim: &Simulation) -> std::io::Result<u64> {
        let record = row(sim);
        self.csv.write_record(&record).map_err(crate::csv_io)?;
        Ok(record_len(&record))
    }

    pub fn flush(&mut self) -> std::io::Result<()> {
        self.csv.flush()
    }
}
