//! Fair dice come out fair (docs/model.md, "Fair dice come out fair"): each regular die thrown
//! from orientations uniform over all rotations ends on every face equally often, so its
//! counts pass Pearson's χ² against uniform at p > 0.001, every throw rolled by both engines
//! to the same bits and settled, the counts summing to the throws.
//!
//! The default run throws each die as often as fits in about 20 s on one core of a loaded
//! two-core machine (both engines, at the dice' table's Δt = 0.25 ms: from about 230 throws a
//! second for the d10 to 4 000 for the d4); the full 200 000 throws a die are `#[ignore]`d,
//! about 40 minutes on one core of a loaded machine:
//!
//! ```text
//! cargo test -p dicesim-physics --test physics -- --ignored --nocapture dice::fairness
//! ```

use super::rolled::roll_both_engines;
use super::throw;
use dicesim_physics::polyhedron::DieKind;
use statrs::distribution::{ChiSquared, ContinuousCDF};
use std::collections::BTreeMap;

/// The seed of every die's throws: throw `i` is the `i`-th stream of it.
const SEED: u64 = 2026;

/// Throws are rolled this many at a time, so the finished rolls held at once stay small.
const CHUNK: u64 = 512;

/// The full test's throws a die.
const FULL: u64 = 200_000;

/// `throws` throws of `kind` (of `N` vertices): every number the die carries shows, the
/// counts sum to the throws, and Pearson's χ² against equal shares has `p > 0.001` on
/// `F − 1` degrees of freedom. Prints the counts, χ² and p.
fn comes_out_fair<const N: usize>(kind: DieKind, throws: u64) {
    let die = kind.standard();
    let faces = die.shape().faces().len();
    let mut counts: BTreeMap<u8, u64> = (0..faces)
        .map(|f| {
            let number = u8::try_from(die.numbering().read_with_down(f)).expect("a small number");
            (number, 0)
        })
        .collect();
    assert_eq!(
        counts.len(),
        faces,
        "{}: every face a number of its own",
        kind.name()
    );
    for first in (0..throws).step_by(CHUNK as usize) {
        let starts: Vec<_> = (first..throws.min(first + CHUNK))
            .map(|i| throw(SEED, i))
            .collect();
        for number in roll_both_engines::<N>(&die, &starts) {
            *counts
                .get_mut(&number)
                .unwrap_or_else(|| panic!("{}: {number} is on no face", kind.name())) += 1;
        }
    }
    assert_eq!(
        counts.values().sum::<u64>(),
        throws,
        "{}: the counts sum to the throws",
        kind.name()
    );
    let expected = throws as f64 / faces as f64;
    let chi_square: f64 = counts
        .values()
        .map(|&c| (c as f64 - expected).powi(2) / expected)
        .sum();
    let dof = (faces - 1) as f64;
    let p = ChiSquared::new(dof).expect("a χ² law").sf(chi_square);
    println!(
        "{} × {throws}: χ² = {chi_square:.3} on {dof} degrees of freedom, p = {p:.4}; counts {counts:?}",
        kind.name()
    );
    assert!(
        p > 0.001,
        "{}: χ² = {chi_square} on {dof} degrees of freedom, p = {p}: {counts:?}",
        kind.name()
    );
}

/// Each die's test in the default run (`$throws` throws) and its full one ([`FULL`] throws).
macro_rules! fair {
    ($die:ident, $points:literal, $throws:literal, $default:ident, $full:ident) => {
        #[test]
        fn $default() {
            comes_out_fair::<$points>(DieKind::$die, $throws);
        }

        #[test]
        #[ignore = "200 000 throws: see the module's doc for the command"]
        fn $full() {
            comes_out_fair::<$points>(DieKind::$die, FULL);
        }
    };
}

fair!(
    D4,
    4,
    100_000,
    a_d4_comes_out_fair,
    a_d4_comes_out_fair_in_200_000_throws
);
fair!(
    D6,
    8,
    28_000,
    a_d6_comes_out_fair,
    a_d6_comes_out_fair_in_200_000_throws
);
fair!(
    D8,
    6,
    34_000,
    a_d8_comes_out_fair,
    a_d8_comes_out_fair_in_200_000_throws
);
fair!(
    D10,
    12,
    4_600,
    a_d10_comes_out_fair,
    a_d10_comes_out_fair_in_200_000_throws
);
fair!(
    D12,
    20,
    7_700,
    a_d12_comes_out_fair,
    a_d12_comes_out_fair_in_200_000_throws
);
fair!(
    D20,
    12,
    10_800,
    a_d20_comes_out_fair,
    a_d20_comes_out_fair_in_200_000_throws
);
