//! When a roll has settled (docs/model.md, "Stopping rule"): the two thresholds a body's
//! rule sets, the test a state must pass, and the lowest potential of a body resting on
//! its springs, from which every body works out its thresholds (cube.rs for the paper's
//! cube, mass.rs for a loaded one, shape.rs for a general body).

use super::lane::Lane;

/// The two thresholds of the stopping rule, erg, derived once from the parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StopRule {
    /// The stop energy must be at or below this.
    pub energy_threshold: f64,
    /// The kinetic part of the stop energy must be at or below this.
    pub kinetic_threshold: f64,
}

impl StopRule {
    /// The rule of a table that cannot hold the die on a face: no state meets it, and the
    /// roll can only end as a timeout.
    pub(crate) const NEVER: StopRule = StopRule {
        energy_threshold: f64::NEG_INFINITY,
        kinetic_threshold: f64::NEG_INFINITY,
    };

    /// The widest of several faces' rules: the largest of each threshold, which every one of
    /// them passes within (the step's cheap screen before the face down is looked up).
    pub(crate) fn widest(rules: &[StopRule]) -> StopRule {
        let widest =
            |threshold: fn(&StopRule) -> f64| rules.iter().map(threshold).fold(f64::NEG_INFINITY, f64::max);
        StopRule {
            energy_threshold: widest(|r| r.energy_threshold),
            kinetic_threshold: widest(|r| r.kinetic_threshold),
        }
    }

    /// Whether any state can meet this rule (false on a table too soft to hold a face).
    pub fn can_settle(&self) -> bool {
        self.energy_threshold.is_finite()
    }
}

/// Whether a state has settled, per lane:
///
/// `stop_energy ≤ energy_threshold && kinetic ≤ kinetic_threshold && potential ≤
/// energy_threshold`, every comparison inclusive, the thresholds those of a [`StopRule`].
///
/// - `stop_energy`: the energy named by `integrator.stop_energy`. Rigid body:
///   `((½·M·|v|² + ½·ω·L) + M·g·(z − a)) + Σ ½·k·d_k²`; point masses: the authors' sum
///   `((½·m·Σ|u_k|² + m·g·Σ(z + r_k,z)) + ½·Σ d_k·P_k) − M·g·a`.
/// - `kinetic`: its kinetic part, `½·M·|v|² + ½·ω·L` or `½·m·Σ|u_k|²`.
/// - `potential`: the rigid-body potential `M·g·(z − a) + Σ ½·k·d_k²`, whatever the stop
///   energy. The point-mass sum counts the damped press force `P_k`, which can make a die
///   buried deep and rising look low in energy; the real potential cannot. (With the
///   rigid-body stop energy this test follows from the first two.)
///
/// All three are the energies the step's end-of-roll check has already computed; NaN in
/// any of them never settles.
#[inline(always)]
pub(crate) fn settles<L: Lane>(
    stop_energy: L,
    kinetic: L,
    potential: L,
    energy_threshold: L,
    kinetic_threshold: L,
) -> L::Mask {
    stop_energy.le(energy_threshold) & kinetic.le(kinetic_threshold) & potential.le(energy_threshold)
}

/// The centre height `z` (cm) that minimises the potential
/// `weight·(z − reference) + Σ ½·k·max(0, −z − o)²` of a body of weight `weight` (`M·g`,
/// dyn) on a table of stiffness `k` (dyn/cm), whose contact points sit `offsets` (cm,
/// ascending) above or below its centre of mass, and that lowest potential (erg).
///
/// The potential is convex in `z`, so the minimum is where the weight balances the springs
/// of the points in contact: with the `j` lowest touching, `z = −(M·g/k + Σ o)/j`.
pub(crate) fn lowest_potential_at(weight: f64, k: f64, reference: f64, offsets: &[f64; 8]) -> (f64, f64) {
    let mut sum = 0.0;
    let mut centre = f64::NAN;
    for j in 0..8 {
        sum += offsets[j];
        let z = -(weight / k + sum) / (j + 1) as f64;
        let touches = z + offsets[j] <= 0.0;
        let next_clear = j == 7 || z + offsets[j + 1] >= 0.0;
        if touches && next_clear {
            centre = z;
            break;
        }
    }
    let elastic: f64 = offsets
        .iter()
        .map(|o| {
            let depth = (-(centre + o)).max(0.0);
            0.5 * k * depth * depth
        })
        .sum();
    (centre, weight * (centre - reference) + elastic)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settles_needs_all_three_energies_and_refuses_nan() {
        let rule = StopRule {
            energy_threshold: 10.0,
            kinetic_threshold: 20.0,
        };
        let settles = |stop: f64, kinetic: f64, potential: f64| {
            settles(
                stop,
                kinetic,
                potential,
                rule.energy_threshold,
                rule.kinetic_threshold,
            )
        };
        assert!(settles(10.0, 20.0, -10.0));
        assert!(settles(10.0, 20.0, 10.0));
        assert!(!settles(10.5, 0.0, 0.0));
        assert!(!settles(-100.0, 21.0, 0.0));
        assert!(!settles(-100.0, 0.0, 11.0));
        assert!(!settles(f64::NAN, 0.0, 0.0));
        assert!(!settles(0.0, f64::NAN, 0.0));
        assert!(!settles(0.0, 0.0, f64::NAN));
    }

    #[test]
    fn the_widest_rule_takes_each_threshold_from_any_face() {
        let mut rules = [StopRule::NEVER; 6];
        rules[1].energy_threshold = 5.0;
        rules[4].kinetic_threshold = 7.0;
        let widest = StopRule::widest(&rules);
        assert_eq!((widest.energy_threshold, widest.kinetic_threshold), (5.0, 7.0));
        assert!(!StopRule::NEVER.can_settle() && widest.can_settle());
    }
}
