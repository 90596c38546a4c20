//! A batch's counts in a form that adds up exactly: the summary of the whole batch is the
//! same whether its rolls were tallied in one pass or in shards merged afterwards.
//!
//! Integer counts add exactly by nature; the simulated seconds are floats, whose sums
//! depend on the order of addition. [`ExactSum`] keeps them as one wide fixed-point integer
//! and rounds once at the end, so a merged batch reports the very bits a single run does.

use crate::record::RollRecord;
use crate::stats::FaceTally;
use crate::summary::{BatchSummary, StartFaceCounts, StatusCounts};
use dicesim_physics::Status;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::time::Duration;

/// 64-bit words of an [`ExactSum`]: bit `k` of the integer weighs 2^(k − 1074), so the
/// smallest subnormal (2^−1074) up to the largest double (below 2^1024) fit in 2098 bits,
/// with 78 bits of room for carries (2^78 additions of the largest double).
const WORDS: usize = 34;

/// The exact sum of non-negative finite doubles, rounded to the nearest double (ties to
/// even) only when read: independent of the order and grouping of the additions.
#[derive(Clone, PartialEq, Eq)]
pub struct ExactSum {
    /// Little-endian words of the fixed-point integer.
    words: [u64; WORDS],
}

impl Default for ExactSum {
    fn default() -> Self {
        ExactSum { words: [0; WORDS] }
    }
}

impl std::fmt::Debug for ExactSum {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "ExactSum({})", self.value())
    }
}

impl ExactSum {
    /// Adds `x`; simulated times are never negative, and a negative or non-finite `x` (which
    /// no roll produces) is ignored rather than corrupting the sum.
    pub(crate) fn add(&mut self, x: f64) {
        if !(x.is_finite() && x > 0.0) {
            return;
        }
        let bits = x.to_bits();
        let exponent = ((bits >> 52) & 0x7ff) as usize;
        let fraction = bits & ((1 << 52) - 1);
        // x = mantissa · 2^(shift − 1074): subnormals have no hidden bit and the exponent of 1.
        let (mantissa, shift) = if exponent == 0 {
            (fraction, 0)
        } else {
            (fraction | 1 << 52, exponent - 1)
        };
        let wide = (mantissa as u128) << (shift % 64);
        self.add_at(shift / 64, wide as u64);
        self.add_at(shift / 64 + 1, (wide >> 64) as u64);
    }

    /// Adds every word of `other`.
    pub(crate) fn merge(&mut self, other: &ExactSum) {
        for (i, &w) in other.words.iter().enumerate() {
            self.add_at(i, w);
        }
    }

    fn add_at(&mut self, mut i: usize, mut w: u64) {
        while w != 0 && i < WORDS {
            let (sum, carry) = self.words[i].overflowing_add(w);
            self.words[i] = sum;
            w = u64::from(carry);
            i += 1;
        }
    }

    /// The sum rounded to the nearest double, ties to even (infinity past the largest).
    pub(crate) fn value(&self) -> f64 {
        let Some(top_word) = self.words.iter().rposition(|&w| w != 0) else {
            return 0.0;
        };
        let top = top_word * 64 + 63 - self.words[top_word].leading_zeros() as usize;
        if top < 53 {
            // Below 2^53 · 2^−1074 every value is a double exactly (subnormal or not).
            return self.words[0] as f64 * f64::from_bits(1);
        }
        let bit = |k: usize| (self.words[k / 64] >> (k % 64)) & 1;
        let low = top - 52;
        let mut mantissa = (low..=top).rev().fold(0u64, |m, k| m << 1 | bit(k));
        let round = bit(low - 1) == 1;
        let sticky = (0..low - 1).any(|k| bit(k) == 1);
        let mut exponent = top as i64 - 1074;
        if round && (sticky || mantissa & 1 == 1) {
            mantissa += 1;
            if mantissa == 1 << 53 {
                mantissa >>= 1;
                exponent += 1;
            }
        }
        if exponent > 1023 {
            return f64::INFINITY;
        }
        f64::from_bits(((exponent + 1023) as u64) << 52 | (mantissa & ((1 << 52) - 1)))
    }

    /// The integer as hexadecimal digits, most significant first, without leading zeros and
    /// with trailing zero words written as `p` and their bit count: `1p128` is 2^128.
    fn to_hex(&self) -> String {
        let Some(top) = self.words.iter().rposition(|&w| w != 0) else {
            return "0".to_string();
        };
        let low = self.words.iter().position(|&w| w != 0).unwrap_or(0);
        let mut s = format!("{:x}", self.words[top]);
        for w in self.words[low..top].iter().rev() {
            s.push_str(&format!("{w:016x}"));
        }
        if low > 0 {
            s.push_str(&format!("p{}", 64 * low));
        }
        s
    }

    fn from_hex(s: &str) -> Option<ExactSum> {
        let (digits, shift) = match s.split_once('p') {
            Some((d, p)) => (d, p.parse::<usize>().ok().filter(|p| p % 64 == 0)? / 64),
            None => (s, 0),
        };
        if digits.is_empty()
            || digits.len() > (WORDS - shift.min(WORDS)) * 16
            || !digits.bytes().all(|b| b.is_ascii_hexdigit())
        {
            return None;
        }
        let mut sum = ExactSum::default();
        for (i, chunk) in digits.as_bytes().rchunks(16).enumerate() {
            let chunk = std::str::from_utf8(chunk).ok()?;
            sum.words[shift + i] = u64::from_str_radix(chunk, 16).ok()?;
        }
        Some(sum)
    }
}

impl Serialize for ExactSum {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.to_hex())
    }
}

impl<'de> Deserialize<'de> for ExactSum {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        ExactSum::from_hex(&s).ok_or_else(|| {
            serde::de::Error::custom(format!(
                "`{s}` is not an exact sum (hexadecimal digits, then p and a multiple of 64)"
            ))
        })
    }
}

/// Everything a batch summary is computed from, as sums that merge exactly.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tally {
    pub rolls: u64,
    /// Settled rolls per number the die shows.
    pub faces: FaceTally,
    pub start_face: StartFaceCounts,
    pub status: StatusCounts,
    /// Steps over all rolls.
    pub steps: u64,
    /// s of simulated time over all rolls, as the exact sum of every roll's time.
    pub simulated_s: ExactSum,
}

impl Tally {
    /// No rolls yet of a die that shows `numbers` ([`Die::face_numbers`](dicesim_physics::Die::face_numbers)).
    pub fn new(numbers: &'static [u8]) -> Tally {
        Tally {
            rolls: 0,
            faces: FaceTally::new(numbers),
            start_face: StartFaceCounts::default(),
            status: StatusCounts::default(),
            steps: 0,
            simulated_s: ExactSum::default(),
        }
    }

    /// Counts read from a file, as those of a die that shows `numbers`
    /// ([`FaceTally::of_die`]).
    pub fn of_die(self, numbers: &'static [u8]) -> Result<Tally, String> {
        Ok(Tally {
            faces: self.faces.of_die(numbers)?,
            ..self
        })
    }

    /// Counts one roll.
    pub fn add(&mut self, r: &RollRecord) {
        self.rolls += 1;
        self.steps += r.outcome.steps;
        self.simulated_s.add(r.outcome.time_s);
        match (r.outcome.status, r.outcome.face) {
            (Status::Settled, Some(face)) => {
                self.status.settled += 1;
                self.faces.add(face);
                self.start_face.add(self.faces.numbers(), r.start_face, face);
            }
            (Status::Settled, None) => self.status.settled_without_face += 1,
            (Status::Timeout, _) => self.status.timeout += 1,
            (Status::Unstable, _) => self.status.unstable += 1,
        }
    }

    /// Checks that the counts agree with each other and with `max_steps` per roll: every
    /// roll has one status, every settled roll with a face one face and one start-face
    /// relation. Sums are taken wide, so no count can wrap into agreement.
    pub fn check(&self, max_steps: u64) -> Result<(), String> {
        let sum = |xs: &[u64]| xs.iter().map(|&x| u128::from(x)).sum::<u128>();
        let st = &self.status;
        let statuses = sum(&[st.settled, st.settled_without_face, st.timeout, st.unstable]);
        if statuses != u128::from(self.rolls) {
            return Err(format!(
                "its status counts add up to {statuses}, but it counts {} rolls",
                self.rolls
            ));
        }
        let faces = sum(&self.faces.counts);
        if faces != u128::from(st.settled) {
            return Err(format!(
                "its face counts add up to {faces}, but it counts {} settled rolls",
                st.settled
            ));
        }
        let sf = &self.start_face;
        let relations = sum(&[sf.same, sf.adjacent, sf.opposite]);
        if relations != u128::from(st.settled) {
            return Err(format!(
                "its start-face counts add up to {relations}, but it counts {} settled rolls",
                st.settled
            ));
        }
        if u128::from(self.steps) > u128::from(self.rolls) * u128::from(max_steps) {
            return Err(format!(
                "it counts {} steps, more than {} rolls of at most {max_steps} steps take",
                self.steps, self.rolls
            ));
        }
        Ok(())
    }

    /// Adds another tally's rolls (of disjoint rolls: a shard's).
    pub fn merge(&mut self, other: &Tally) {
        self.rolls += other.rolls;
        self.faces.merge(&other.faces);
        self.start_face.same += other.start_face.same;
        self.start_face.adjacent += other.start_face.adjacent;
        self.start_face.opposite += other.start_face.opposite;
        let (s, o) = (&mut self.status, &other.status);
        s.settled += o.settled;
        s.settled_without_face += o.settled_without_face;
        s.timeout += o.timeout;
        s.unstable += o.unstable;
        self.steps += other.steps;
        self.simulated_s.merge(&other.simulated_s);
    }

    /// The summary of these rolls, which took `elapsed` of wall-clock time.
    pub fn summary(&self, elapsed: Duration) -> BatchSummary {
        let elapsed_s = elapsed.as_secs_f64();
        let rate = |n: f64| if elapsed_s > 0.0 { n / elapsed_s } else { 0.0 };
        BatchSummary {
            rolls: self.rolls,
            faces: self.faces.clone(),
            face_shares: self.faces.shares(),
            face_intervals: self.faces.share_intervals(),
            chi_square: self.faces.chi_square(),
            p_value: self.faces.p_value(),
            rolls_to_detect: self.faces.rolls_to_detect(),
            start_face: self.start_face,
            start_face_shares: self.start_face.shares(),
            status: self.status,
            steps: self.steps,
            simulated_s: self.simulated_s.value(),
            elapsed_s,
            rolls_per_s: rate(self.rolls as f64),
            steps_per_s: rate(self.steps as f64),
        }
    }
}

impl Tally {
    /// The tally of `records` of a die that shows `numbers`.
    pub fn of_records<'a>(
        numbers: &'static [u8],
        records: impl IntoIterator<Item = &'a RollRecord>,
    ) -> Tally {
        let mut t = Tally::new(numbers);
        records.into_iter().for_each(|r| t.add(r));
        t
    }
}

impl BatchSummary {
    /// Tallies `records` of a die that shows `numbers`, which took `elapsed` of wall-clock
    /// time.
    pub fn new(numbers: &'static [u8], records: &[RollRecord], elapsed: Duration) -> BatchSummary {
        Tally::of_records(numbers, records).summary(elapsed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn sum_of(xs: &[f64]) -> ExactSum {
        let mut s = ExactSum::default();
        for &x in xs {
            s.add(x);
        }
        s
    }

    #[test]
    fn exact_where_floats_round() {
        // 0.1 + 0.2 rounds to 0.30000000000000004 in floats; the exact sum of the two
        // doubles 0.1 and 0.2 is 0.3000000000000000166…, whose nearest double is that too.
        assert_eq!(sum_of(&[0.1, 0.2]).value(), 0.1 + 0.2);
        // 1 + 2^−53 + 2^−53: sequential float addition loses both halves; the exact sum
        // 1 + 2^−52 is a double.
        let half_ulp = f64::EPSILON / 2.0;
        assert_eq!((1.0 + half_ulp) + half_ulp, 1.0);
        assert_eq!(sum_of(&[1.0, half_ulp, half_ulp]).value(), 1.0 + f64::EPSILON);
        // A tie rounds to even: 1 + 2^−53 is halfway between 1 and 1 + 2^−52.
        assert_eq!(sum_of(&[1.0, half_ulp]).value(), 1.0);
        assert_eq!(
            sum_of(&[1.0 + f64::EPSILON, half_ulp]).value(),
            1.0 + 2.0 * f64::EPSILON
        );
        // Subnormals, the largest double and overflow.
        assert_eq!(sum_of(&[f64::from_bits(1); 3]).value(), f64::from_bits(3));
        assert_eq!(sum_of(&[f64::MAX]).value(), f64::MAX);
        assert_eq!(sum_of(&[f64::MAX, f64::MAX]).value(), f64::INFINITY);
        assert_eq!(ExactSum::default().value(), 0.0);
        assert_eq!(sum_of(&[-1.0, f64::NAN, 2.5]).value(), 2.5);
    }

    #[test]
    fn hex_round_trip_and_refusal() {
        let s = sum_of(&[1e300, 3.25, 1e-310]);
        assert_eq!(ExactSum::from_hex(&s.to_hex()), Some(s));
        assert_eq!(ExactSum::default().to_hex(), "0");
        // 1.0 is 2^1074 in units of 2^−1074: bit 50 of word 16.
        assert_eq!(sum_of(&[1.0]).to_hex(), "4000000000000p1024");
        assert_eq!(ExactSum::from_hex("4000000000000p1024").unwrap().value(), 1.0);
        assert_eq!(ExactSum::from_hex("1p100"), None);
        assert_eq!(ExactSum::from_hex("1p2176"), None);
        assert_eq!(ExactSum::from_hex("1g"), None);
        assert_eq!(ExactSum::from_hex(""), None);
        assert!(
            serde_json::from_str::<ExactSum>("\"zz\"")
                .unwrap_err()
                .to_string()
                .contains("`zz`")
        );
    }

    #[test]
    fn merged_tallies_count_the_rolls_of_both() {
        use dicesim_physics::{InitialCondition, Outcome};
        let roll = |status, face, time_s| RollRecord {
            id: 0,
            initial: InitialCondition::default(),
            outcome: Outcome {
                status,
                face,
                steps: 10,
                time_s,
                impacts: 0,
                first_impact: None,
            },
            start_face: 1,
        };
        let d6 = &[1, 2, 3, 4, 5, 6];
        let first = Tally::of_records(
            d6,
            &[
                roll(Status::Settled, Some(1), 0.1),
                roll(Status::Timeout, None, 0.2),
            ],
        );
        let second = Tally::of_records(d6, &[roll(Status::Settled, Some(6), 0.3)]);
        let mut merged = first.clone();
        merged.merge(&second);
        assert_eq!((merged.rolls, merged.steps), (3, 30));
        assert_eq!(merged.faces.counts, [1, 0, 0, 0, 0, 1]);
        assert_eq!((merged.status.settled, merged.status.timeout), (2, 1));
        // Face 1 from start face 1 is the same face, 6 the opposite one.
        assert_eq!((merged.start_face.same, merged.start_face.opposite), (1, 1));
        // The exact sum: 0.1 + 0.2 + 0.3 as the nearest double to the true sum of the
        // three doubles (0.6000000000000001 in floats added left to right).
        assert_eq!(merged.summary(Duration::ZERO).simulated_s, 0.6);
        assert_eq!(merged.check(10), Ok(()));
        assert!(
            merged
                .check(9)
                .unwrap_err()
                .contains("more than 3 rolls of at most 9 steps")
        );
    }

    #[test]
    fn a_d20s_tally_counts_its_twenty_numbers_and_refuses_any_other() {
        let d20: &[u8] = &[
            1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20,
        ];
        let settled = |id, face| RollRecord::ended(id, Status::Settled, Some(face));
        let records = [settled(0, 20), settled(1, 7), settled(2, 20)];
        let t = Tally::of_records(d20, &records);
        let mut expected = vec![0; 20];
        (expected[19], expected[6]) = (2, 1);
        assert_eq!(t.faces.counts, expected);
        assert_eq!(t.check(1), Ok(()));
        let s = t.summary(Duration::ZERO);
        // Three rolls on 20 faces, 0.15 expected each: χ² = (1.85²·1 + 0.85²·1 + 0.15²·18)/0.15
        // = (3.4225 + 0.7225 + 0.405)/0.15 = 30.333…, on 19 dof.
        assert!((s.chi_square.unwrap() - 30.333_333_333_333).abs() < 1e-9);
        assert_eq!((s.face_shares.len(), s.face_intervals.len()), (20, 20));
        assert_eq!(s.face_shares[19], 2.0 / 3.0);
        // A 21 is no face of it: counted settled, not counted as a face, which the check sees.
        let bad = Tally::of_records(d20, &[settled(0, 21)]);
        assert_eq!(
            bad.check(1).unwrap_err(),
            "its face counts add up to 0, but it counts 1 settled rolls"
        );
        // Counts read back of another die are refused.
        let read: Tally = serde_json::from_str(&serde_json::to_string(&t).unwrap()).unwrap();
        assert_eq!(read.clone().of_die(d20), Ok(t));
        assert!(read.of_die(&[1, 2, 3, 4]).is_err());
    }

    proptest! {
        /// Any split of any list sums to the same bits, and small sums of integers are exact.
        #[test]
        fn order_and_grouping_do_not_matter(
            xs in prop::collection::vec(0.0f64..1e6, 0..200),
            cut in 0usize..200,
        ) {
            let cut = cut.min(xs.len());
            let whole = sum_of(&xs);
            let mut merged = sum_of(&xs[cut..]);
            merged.merge(&sum_of(&xs[..cut]));
            prop_assert_eq!(merged.value().to_bits(), whole.value().to_bits());
            let mut reversed: Vec<f64> = xs.clone();
            reversed.reverse();
            prop_assert_eq!(sum_of(&reversed).value().to_bits(), whole.value().to_bits());
            let ints: Vec<f64> = xs.iter().map(|x| x.floor()).collect();
            prop_assert_eq!(sum_of(&ints).value(), ints.iter().sum::<f64>());
        }
    }
}
