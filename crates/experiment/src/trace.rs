//! A roll's trajectory and every quantity of [`dicesim_setup::quantity`] as CSV rows
//! (`dicesim trace`, and the explorer's export).

use crate::data_file::Column;
use dicesim_physics::Simulation;
use dicesim_setup::number::{Real, StepClock};
use dicesim_setup::quantity::{QUANTITIES, read_all};

/// The CSV columns, each with its unit: the step and its time, the state (centre of mass,
/// its velocity, angular momentum, angular velocity), every quantity of [`QUANTITIES`], then
/// the corners in docs/model.md's corner order.
pub fn columns() -> Vec<Column> {
    let mut c = vec![Column::integer("step"), Column::real("time_s")];
    for (names, unit) in [
        (["x", "y", "z"], "cm"),
        (["vx", "vy", "vz"], "cm_per_s"),
        (["Lx", "Ly", "Lz"], "g_cm2_per_s"),
        (["wx", "wy", "wz"], "rad_per_s"),
    ] {
        c.extend(names.map(|n| Column::real(format!("{n}_{unit}"))));
    }
    c.extend(QUANTITIES.iter().map(|q| Column::real(q.column)));
    for k in 1..=8 {
        c.extend(["x", "y", "z"].map(|a| Column::real(format!("c{k}{a}_cm"))));
    }
    c
}

/// The names of [`columns`].
pub fn header() -> Vec<String> {
    columns().into_iter().map(|c| c.name).collect()
}

/// One CSV record for the simulation's current state: its time the steps × Δt that
/// `clock` prints, the numbers in shortest round-trip form with their point, so reading
/// them back gives the same bits.
pub fn row(sim: &Simulation, clock: &StepClock) -> Vec<String> {
    let mut record = vec![sim.state().step.to_string()];
    record.extend(values(sim, clock).into_iter().map(|v| Real(v).to_string()));
    record
}

/// The numbers of [`row`] after its step: every column of [`columns`] but the first, in
/// their units (what the Python module's arrays hold, bit for bit the CSV's cells).
pub fn values(sim: &Simulation, clock: &StepClock) -> Vec<f64> {
    let s = sim.state();
    let w = sim.angular_velocity();
    let mut values = vec![clock.time_s(s.step)];
    values.extend(
        s.position
            .iter()
            .chain(s.velocity.iter())
            .chain(s.angular_momentum.iter())
            .chain(w.iter())
            .copied()
            .chain(read_all(sim)),
    );
    for p in sim.corner_positions() {
        values.extend([p.x, p.y, p.z]);
    }
    values
}

/// Steps `sim` as `dicesim trace` does and hands `row` its state at the start and after
/// every `every`-th step: exactly `steps` steps (`Some(0)`: the start alone), or until
/// the roll ends; the last state is always handed over.
pub fn follow<E>(
    sim: &mut Simulation,
    steps: Option<u64>,
    every: u64,
    row: &mut dyn FnMut(&Simulation) -> Result<(), E>,
) -> Result<(), E> {
    let every = every.max(1);
    let done = |sim: &Simulation| match steps {
        Some(n) => sim.state().step >= n,
        None => sim.outcome().is_some(),
    };
    row(sim)?;
    while !done(sim) {
        sim.advance();
        if sim.state().step.is_multiple_of(every) || done(sim) {
            row(sim)?;
        }
    }
    Ok(())
}

/// Bytes a record takes in the CSV: its fields, each followed by a comma or the newline
/// (numbers are never quoted).
pub fn record_len(record: &[String]) -> u64 {
    record.iter().map(|f| f.len() as u64 + 1).sum()
}

/// A trace as CSV: the header, then one record per [`TraceWriter::write`].
pub struct TraceWriter<W: std::io::Write> {
    out: W,
    clock: StepClock,
}

impl<W: std::io::Write> TraceWriter<W> {
    /// Writes the header into `out`, for a roll with steps of `dt` s.
    pub fn new(mut out: W, dt: f64) -> std::io::Result<Self> {
        writeln!(out, "{}", header().join(","))?;
        Ok(TraceWriter {
            out,
            clock: StepClock::new(dt),
        })
    }

    /// One record for the simulation's current state; returns its length in bytes.
    pub fn write(&mut self, sim: &Simulation) -> std::io::Result<u64> {
        let record = row(sim, &self.clock);
        writeln!(self.out, "{}", record.join(","))?;
        Ok(record_len(&record))
    }

    pub fn flush(&mut self) -> std::io::Result<()> {
        self.out.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use dicesim_physics::{InitialCondition, Params};

    #[test]
    fn a_trace_row_has_a_cell_per_column_its_time_the_steps_of_dt_and_reals_as_reals() {
        let params = Params::default();
        let mut sim = Simulation::new(&params, &InitialCondition::default()).unwrap();
        for _ in 0..684 {
            sim.advance();
        }
        let row = row(&sim, &StepClock::new(params.integrator.dt));
        assert_eq!(row.len(), columns().len());
        assert_eq!(row[..2], ["684", "0.684"]);
        // Every other cell a real: with its point or exponent, never `15` for 15.0.
        assert!(row[2..].iter().all(|c| c.contains(['.', 'e'])), "{row:?}");
    }
}
