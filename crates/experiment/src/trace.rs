//! A roll's trajectory and every quantity of [`dicesim_setup::quantity`] as CSV rows
//! (`dicesim trace`, and the explorer's export).

use crate::data_file::Column;
use dicesim_physics::RollingDie;
use dicesim_physics::{Params, Roll};
use dicesim_setup::number::{Real, StepClock};
use dicesim_setup::quantity::{QUANTITIES, read_all};

/// How a trace names the die's contact points and how many it has: the box's 8 corners
/// `c1`…`c8` (docs/model.md's corner order), a polyhedral die's `N` points `p1`…`pN`
/// (its vertices in its solid's order, docs/dice.md).
fn points_of(params: &Params) -> (char, usize) {
    match params.polyhedral_die() {
        Some(die) => ('p', die.shape().vertices().len()),
        None => ('c', 8),
    }
}

/// The CSV columns of a trace of `params`' die, each with its unit: the step and its time,
/// the state (centre of mass, its velocity, angular momentum, angular velocity), every
/// quantity of [`QUANTITIES`], then each contact point's world position (the box's corners
/// `c1x_cm`…`c8z_cm`, a die's points `p1x_cm`…`pNz_cm`).
pub fn columns_for(params: &Params) -> Vec<Column> {
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
    let (prefix, points) = points_of(params);
    for k in 1..=points {
        c.extend(["x", "y", "z"].map(|a| Column::real(format!("{prefix}{k}{a}_cm"))));
    }
    c
}

/// The columns of a trace of the box (any box: its 8 corners), [`columns_for`] the paper's.
pub fn columns() -> Vec<Column> {
    columns_for(&Params::default())
}

/// The names of [`columns_for`] `params`.
pub fn header_for(params: &Params) -> Vec<String> {
    columns_for(params).into_iter().map(|c| c.name).collect()
}

/// The names of [`columns`], the box's.
pub fn header() -> Vec<String> {
    header_for(&Params::default())
}

/// One CSV record for the roll's current state (a box's `Simulation` or any die's `Roll`):
/// its time the steps × Δt that `clock` prints, the numbers in shortest round-trip form
/// with their point, so reading them back gives the same bits.
pub fn row(roll: &dyn RollingDie, clock: &StepClock) -> Vec<String> {
    let mut record = vec![roll.steps().to_string()];
    record.extend(values(roll, clock).into_iter().map(|v| Real(v).to_string()));
    record
}

/// The numbers of [`row`] after its step: every column of [`columns_for`] but the first,
/// in their units (what the Python module's arrays hold, bit for bit the CSV's cells).
pub fn values(roll: &dyn RollingDie, clock: &StepClock) -> Vec<f64> {
    let mut values = vec![clock.time_s(roll.steps())];
    values.extend(
        roll.position()
            .iter()
            .chain(roll.velocity().iter())
            .chain(roll.angular_momentum().iter())
            .chain(roll.angular_velocity().iter())
            .copied()
            .chain(read_all(roll)),
    );
    for p in roll.point_positions() {
        values.extend([p.x, p.y, p.z]);
    }
    values
}

/// Steps `roll` as `dicesim trace` does and hands `row` its state at the start and after
/// every `every`-th step: exactly `steps` steps (`Some(0)`: the start alone), or until
/// the roll ends; the last state is always handed over.
pub fn follow<E>(
    roll: &mut Roll,
    steps: Option<u64>,
    every: u64,
    row: &mut dyn FnMut(&Roll) -> Result<(), E>,
) -> Result<(), E> {
    let every = every.max(1);
    let done = |roll: &Roll| match steps {
        Some(n) => roll.steps() >= n,
        None => roll.outcome().is_some(),
    };
    row(roll)?;
    while !done(roll) {
        roll.advance();
        if roll.steps().is_multiple_of(every) || done(roll) {
            row(roll)?;
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
    /// Writes the box's header into `out`, for a roll with steps of `dt` s.
    pub fn new(out: W, dt: f64) -> std::io::Result<Self> {
        TraceWriter::headed(out, &header(), dt)
    }

    /// Writes the header of a trace of `params`' die into `out`.
    pub fn of(out: W, params: &Params) -> std::io::Result<Self> {
        TraceWriter::headed(out, &header_for(params), params.integrator.dt)
    }

    fn headed(mut out: W, header: &[String], dt: f64) -> std::io::Result<Self> {
        writeln!(out, "{}", header.join(","))?;
        Ok(TraceWriter {
            out,
            clock: StepClock::new(dt),
        })
    }

    /// One record for the roll's current state; returns its length in bytes.
    pub fn write(&mut self, roll: &dyn RollingDie) -> std::io::Result<u64> {
        let record = row(roll, &self.clock);
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
    use dicesim_physics::{InitialCondition, Params, Simulation};

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
