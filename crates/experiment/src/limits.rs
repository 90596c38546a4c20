//! The largest value of every size a user types: how many rolls, candidates, steps, cells
//! or frames one command may be asked for. Each limit is one row here, stated in its
//! option's `--help` and in docs/troubleshooting.md ("Limits, stated up front"), and a
//! request past it is refused before any work, naming the option and the limit (exit 2):
//! past these a request is years of core time or more memory than a machine has, a typo
//! more likely than a plan.

use crate::Error;

/// One size a user types and the most it may be.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SizeLimit {
    /// The commands whose option it is, as typed (`compare`, `trace`).
    pub commands: &'static [&'static str],
    /// The option, as its refusal names it (`--candidates`, `--res`), or what is counted
    /// where the size is a product of several options (`rolls`).
    pub option: &'static str,
    /// The most it may be, in `unit`s.
    pub max: u64,
    /// What is counted (`rolls`, `candidates`).
    pub unit: &'static str,
    /// Why the limit is where it is, and the way round it.
    pub why: &'static str,
}

impl SizeLimit {
    /// The limit in words, as `--help` and the docs state it: `at most 1000 candidates`.
    pub fn stated(&self) -> String {
        format!("at most {} {}", count(self.max), self.unit)
    }

    /// Refuses `value` past the limit: `--candidates 5000: at most 1000 candidates; …`, or
    /// for a product of options `2000000000 rolls: at most 10⁹ rolls in one experiment; …`.
    pub fn check(&self, value: u64) -> Result<(), Error> {
        if value <= self.max {
            return Ok(());
        }
        Err(self.refuse(if self.option.starts_with("--") {
            format!("{} {value}", self.option)
        } else {
            format!("{value} {}", self.option)
        }))
    }

    /// The refusal of a request past the limit, `what` saying the request
    /// (`--res 5000x5000: 25000000 cells would need about 1.2 GB of memory`).
    pub fn refuse(&self, what: String) -> Error {
        Error::Limit(format!("{what}: {}; {}", self.stated(), self.why))
    }
}

/// A count as the limits state it: a power of ten from 10⁴ up as `10ⁿ`, else its digits.
pub fn count(n: u64) -> String {
    const SUPERSCRIPTS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let digits = n.to_string();
    if n >= 10_000 && digits[1..].bytes().all(|b| b == b'0') && digits.starts_with('1') {
        let mut power = "10".to_string();
        for d in (digits.len() - 1).to_string().bytes() {
            power.push(SUPERSCRIPTS[usize::from(d - b'0')]);
        }
        return power;
    }
    digits
}

/// `batch --rolls`: records stream to `--out` as they complete, so memory does not grow with
/// the batch; past this a batch is years of core time, and a sweep that size belongs on
/// many machines.
pub const BATCH_ROLLS: SizeLimit = SizeLimit {
    commands: &["batch"],
    option: "--rolls",
    max: 100_000_000_000,
    unit: "rolls per batch",
    why: "split a sweep this large over machines with --shard K/N",
};

/// The rolls of one comparison or prediction (throws × dice × candidates; starts × (1 + the
/// ε count) × values): each keeps its counts per candidate or curve in memory, and past this
/// it is days of core time on one machine.
pub const EXPERIMENT_ROLLS: SizeLimit = SizeLimit {
    commands: &["compare", "predict"],
    option: "rolls",
    max: 1_000_000_000,
    unit: "rolls in one experiment",
    why: "fewer --throws or --rolls, candidates, ε or values",
};

/// `compare --candidates`: each candidate keeps its throws' counts, and more than this many
/// values over one range resolve nothing the deviance's own noise does not blur.
pub const CANDIDATES: SizeLimit = SizeLimit {
    commands: &["compare"],
    option: "--candidates",
    max: 1000,
    unit: "candidates",
    why: "a fit's deviances scatter by a few units from one candidate to the next, so more \
          candidates over the same range do not narrow its interval; fit a narrower range",
};

/// `trace --steps`: the most steps any roll may take (120 s at Δt = 10⁻⁵ s), a trace of about
/// 6 GB at `--every 1`.
pub const TRACE_STEPS: SizeLimit = SizeLimit {
    commands: &["trace"],
    option: "--steps",
    max: dicesim_physics::params::MAX_STEPS_CAP,
    unit: "steps",
    why: "the longest roll the model runs (integrator.max_time 120 s at Δt 1e-5 s)",
};

/// `basin --res`: the map, the copy shown while refining and the picture drawn from it.
pub const MAP_CELLS: SizeLimit = SizeLimit {
    commands: &["basin"],
    option: "--res",
    max: 2048 * 2048,
    unit: "cells (2048x2048)",
    why: "a bigger map needs more memory than its picture can show; split it over machines \
          with --shard or map a smaller range",
};

/// `animate`: every frame is kept until the file is written.
pub const FRAMES: SizeLimit = SizeLimit {
    commands: &["animate"],
    option: "frames",
    max: 10_000,
    unit: "frames",
    why: "a lower --fps or a faster --speed",
};

/// Every limit, for the help and docs that state them.
pub const ALL: [&SizeLimit; 6] = [
    &BATCH_ROLLS,
    &EXPERIMENT_ROLLS,
    &CANDIDATES,
    &TRACE_STEPS,
    &MAP_CELLS,
    &FRAMES,
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_read_as_people_write_them() {
        assert_eq!(count(100_000_000_000), "10¹¹");
        assert_eq!(count(1_000_000_000), "10⁹");
        assert_eq!(count(10_000), "10⁴");
        assert_eq!(count(1000), "1000");
        assert_eq!(count(12_000_000), "12000000");
        assert_eq!(CANDIDATES.stated(), "at most 1000 candidates");
        assert!(CANDIDATES.check(1000).is_ok());
        let e = CANDIDATES.check(1_000_000_000).unwrap_err().to_string();
        assert!(
            e.starts_with("--candidates 1000000000: at most 1000 candidates; "),
            "{e}"
        );
    }
}
