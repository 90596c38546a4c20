//! What a batch's rolls came to: the counts of faces and endings and the statistics drawn
//! from them, as a summary prints them and `--json` carries them.

use crate::stats::FaceTally;
use dicesim_physics::Solid;
use serde::{Deserialize, Serialize};

/// How a roll's final face relates to the face that started up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StartFaceCounts {
    /// Ended on the face that started up.
    pub(crate) same: u64,
    /// Ended on another face: on the box, one of the 4 next to it (the name files keep).
    pub(crate) adjacent: u64,
    /// Ended on the opposite face.
    pub(crate) opposite: u64,
}

impl StartFaceCounts {
    /// Counts a roll of a die that shows `numbers` from `start_face` up to `face`.
    pub(crate) fn add(&mut self, numbers: &[u8], start_face: u8, face: u8) {
        let opposite = Solid::showing(numbers).and_then(|s| s.opposite_number(start_face));
        if face == start_face {
            self.same += 1;
        } else if Some(face) == opposite {
            self.opposite += 1;
        } else {
            self.adjacent += 1;
        }
    }

    pub(crate) fn total(&self) -> u64 {
        self.same + self.adjacent + self.opposite
    }

    /// Shares of (same, adjacent, opposite); zeros with no rolls.
    pub(crate) fn shares(&self) -> [f64; 3] {
        let n = self.total().max(1) as f64;
        [self.same, self.adjacent, self.opposite].map(|c| c as f64 / n)
    }
}

/// How the rolls of a batch ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StatusCounts {
    /// Settled with a face up.
    pub settled: u64,
    /// Settled, but the 4 highest corners formed no face.
    pub settled_without_face: u64,
    /// Did not settle within `integrator.max_time`.
    pub timeout: u64,
    /// The integrator gained energy.
    pub unstable: u64,
}

/// The statistics of a batch: what a summary prints and `--json` carries.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BatchSummary {
    pub rolls: u64,
    /// Settled rolls per number the die shows, in its order ([`FaceTally::numbers`]).
    pub faces: FaceTally,
    /// Share of each number among rolls that ended with a face, in the die's order.
    pub face_shares: Vec<f64>,
    /// The 95 % (Wilson) interval of each number's share, in the die's order.
    pub face_intervals: Vec<[f64; 2]>,
    /// Pearson's χ² of the face counts against a fair die (`None` without faces).
    pub chi_square: Option<f64>,
    /// Probability of at least this χ² from a fair die (one degree of freedom fewer than the
    /// die has numbers).
    pub p_value: Option<f64>,
    /// Rolls at which the χ² test at 5 % would detect the bias these faces measure with 80 %
    /// power (`None`: no bias stands out of the noise).
    pub rolls_to_detect: Option<u64>,
    pub start_face: StartFaceCounts,
    /// Shares of `start_face` (same, adjacent, opposite) among rolls that ended with a face.
    pub start_face_shares: [f64; 3],
    pub status: StatusCounts,
    /// Steps over all rolls.
    pub steps: u64,
    /// s of simulated time over all rolls.
    pub simulated_s: f64,
    /// s of wall-clock time.
    pub elapsed_s: f64,
    pub rolls_per_s: f64,
    pub steps_per_s: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Opposite faces of real dice sum to the lowest and highest number together
    /// (docs/dice.md): 21 on a d20, 9 on a d10, 90 on a d%; a d4's faces have none.
    #[test]
    fn the_start_faces_opposite_is_the_dies_own() {
        let mut d20 = StartFaceCounts::default();
        let twenty: Vec<u8> = (1..=20).collect();
        let numbers = Solid::D20.face_numbers();
        assert_eq!(numbers, &twenty[..]);
        for (start, face) in [(3, 3), (3, 18), (3, 4), (20, 1), (7, 14)] {
            d20.add(numbers, start, face);
        }
        assert_eq!((d20.same, d20.adjacent, d20.opposite), (1, 1, 3));
        let mut d10 = StartFaceCounts::default();
        for (start, face) in [(0, 9), (2, 7), (2, 5)] {
            d10.add(Solid::D10.face_numbers(), start, face);
        }
        assert_eq!((d10.same, d10.adjacent, d10.opposite), (0, 1, 2));
        let mut percentile = StartFaceCounts::default();
        percentile.add(Solid::Percentile.face_numbers(), 30, 60);
        assert_eq!(percentile.opposite, 1);
        let mut d4 = StartFaceCounts::default();
        for (start, face) in [(1, 4), (2, 3), (4, 4)] {
            d4.add(Solid::D4.face_numbers(), start, face);
        }
        assert_eq!((d4.same, d4.adjacent, d4.opposite), (1, 2, 0));
        let mut cube = StartFaceCounts::default();
        for (start, face) in [(1, 6), (2, 5), (2, 3)] {
            cube.add(Solid::Box.face_numbers(), start, face);
        }
        assert_eq!((cube.same, cube.adjacent, cube.opposite), (0, 1, 2));
    }
}
