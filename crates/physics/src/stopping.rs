//! When a roll has settled: the stopping rule over the whole allowed range (docs/model.md,
//! "Stopping rule").
//!
//! The paper ends a roll once its energy is below `f·E_edge`, with the potential measured
//! from a die lying flat on a rigid table. On a table of finite stiffness the die rests
//! `δ = M·g/(4k)` deep, so its resting energy `V_rest` is below zero and an edge-balanced
//! die sits lower too (`V_edge`). The rule below keeps the paper's test and adds what only
//! binds on soft tables: the energy must stay clear of `V_edge`, and the kinetic and the
//! potential energy must each be within what the energy test allows above rest.

use super::params::Params;
use super::shape::Shape;

/// The two thresholds of the stopping rule, erg, derived once from the parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StopRule {
    /// The stop energy must be at or below this.
    pub energy_threshold: f64,
    /// The kinetic part of the stop energy must be at or below this.
    pub kinetic_threshold: f64,
}

impl StopRule {
    /// The widest of several faces' rules: the largest of each threshold, which every one of
    /// them passes within (the step's cheap screen before the face down is looked up).
    pub(crate) fn widest(rules: &[StopRule; 6]) -> StopRule {
        let widest =
            |threshold: fn(&StopRule) -> f64| rules.iter().map(threshold).fold(f64::NEG_INFINITY, f64::max);
        StopRule {
            energy_threshold: widest(|r| r.energy_threshold),
            kinetic_threshold: widest(|r| r.kinetic_threshold),
        }
    }

    /// `energy_threshold = min(f·E_edge, V_edge − ½·(1 − f)·E_edge)` and
    /// `kinetic_threshold = energy_threshold − V_rest`; both are −∞ (the roll can only end
    /// as a timeout) when the table cannot hold the die on a face: its resting centre would
    /// be below the table top, or the threshold would not lie above the resting energy.
    ///
    /// A body other than the paper's cube has a rule per face down
    /// ([`super::shape::Shape`]); this is the widest of them.
    pub(crate) fn new(p: &Params) -> StopRule {
        if !p.die.is_cube() {
            return Shape::new(p).widest_stop_rule();
        }
        let paper = p.stop_threshold();
        let rest = resting_energy(p);
        let margin = 0.5 * (1.0 - p.integrator.stop_energy_fraction) * p.edge_energy();
        let energy_threshold = paper.min(edge_balanced_energy(p) - margin);
        let rest_centre = p.die.half_size() - resting_depth_on_face(p);
        if energy_threshold > rest && rest_centre > 0.0 {
            StopRule {
                energy_threshold,
                kinetic_threshold: energy_threshold - rest,
            }
        } else {
            StopRule {
                energy_threshold: f64::NEG_INFINITY,
                kinetic_threshold: f64::NEG_INFINITY,
            }
        }
    }

    /// Whether any state can meet this rule (false on a table too soft to hold a face).
    pub fn can_settle(&self) -> bool {
        self.energy_threshold.is_finite()
    }
}

/// Why no roll can settle on this table, in words; `None` when one can.
pub fn why_it_cannot_settle(p: &Params) -> Option<String> {
    if StopRule::new(p).can_settle() {
        return None;
    }
    let depth = resting_depth_on_face(p);
    let a = p.die.half_size();
    Some(if depth >= a {
        format!(
            "the table is too soft to hold the die: at rest it would sink {depth:.3} cm, its centre \
             {:.3} cm below the table top",
            depth - a
        )
    } else {
        format!(
            "the table is too soft to keep a face: at rest the die sinks {depth:.3} cm, and tipping \
             it over an edge takes only {:.1} erg, too little to tell a settled die from a rocking one",
            edge_balanced_energy(p) - resting_energy(p)
        )
    })
}

/// Whether a state has settled:
///
/// `stop_energy ≤ energy_threshold && kinetic ≤ kinetic_threshold && potential ≤
/// energy_threshold`, evaluated in that order, every comparison inclusive.
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
pub fn settles(stop_energy: f64, kinetic: f64, potential: f64, rule: &StopRule) -> bool {
    stop_energy <= rule.energy_threshold
        && kinetic <= rule.kinetic_threshold
        && potential <= rule.energy_threshold
}

/// cm, how deep the lower corners sink when the die rests on a face, with as many corners
/// touching as the depth implies (4, or all 8 on a table too soft to carry it); for a body
/// other than the paper's cube, the deepest over its faces.
pub fn resting_depth_on_face(p: &Params) -> f64 {
    if !p.die.is_cube() {
        let faces = Shape::faces(p);
        return faces.iter().map(|f| f.rest_depth).fold(0.0, f64::max);
    }
    let a = p.die.half_size();
    let (centre, _) = lowest_potential(p, &[-a, -a, -a, -a, a, a, a, a]);
    a - centre
}

/// erg, the potential energy of the die at rest on a face (`−½·M·g·δ` while only the four
/// lower corners touch), measured like the rigid-body energy from the flat height `z = a`.
pub(crate) fn resting_energy(p: &Params) -> f64 {
    let a = p.die.half_size();
    lowest_potential(p, &[-a, -a, -a, -a, a, a, a, a]).1
}

/// erg, the potential energy of the die at rest balanced on an edge (`E_edge − M·g·δ` while
/// only the edge's two corners touch): the lowest pass between two faces.
pub(crate) fn edge_balanced_energy(p: &Params) -> f64 {
    let e = p.die.half_size() * std::f64::consts::SQRT_2;
    lowest_potential(p, &[-e, -e, 0.0, 0.0, 0.0, 0.0, e, e]).1
}

/// The centre height (cm) that minimises the potential `M·g·(z − a) + Σ ½·k·max(0, −z − o)²`
/// of a die whose corners sit `offsets` (cm, ascending) above or below its centre, and that
/// lowest potential (erg).
///
/// The potential is convex in `z`, so the minimum is where the weight balances the springs
/// of the corners in contact: with the `j` lowest corners touching, `z = −(M·g/k + Σ o)/j`.
fn lowest_potential(p: &Params, offsets: &[f64; 8]) -> (f64, f64) {
    lowest_potential_at(
        p.total_mass() * p.world.gravity,
        p.ground.stiffness,
        p.die.half_size(),
        offsets,
    )
}

/// [`lowest_potential`] for a body of weight `weight` (dyn) on a table of stiffness `k`
/// (dyn/cm), the potential measured from the centre at height `reference` (cm).
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

    fn with_stiffness(k: f64) -> Params {
        let mut p = Params::default();
        p.ground.stiffness = k;
        p
    }

    #[test]
    fn shallow_table_matches_the_closed_forms() {
        let p = Params::default();
        let (m, g, delta) = (p.total_mass(), p.world.gravity, p.resting_depth());
        assert!((resting_depth_on_face(&p) - delta).abs() < 1e-12);
        assert!((resting_energy(&p) + 0.5 * m * g * delta).abs() < 1e-9);
        assert!((edge_balanced_energy(&p) - (p.edge_energy() - m * g * delta)).abs() < 1e-9);
    }

    #[test]
    fn the_papers_threshold_stands_at_the_defaults() {
        let p = Params::default();
        let rule = StopRule::new(&p);
        assert_eq!(rule.energy_threshold, p.stop_threshold());
        assert_eq!(rule.kinetic_threshold, p.stop_threshold() - resting_energy(&p));
    }

    #[test]
    fn a_table_softer_than_the_die_cannot_hold_a_face() {
        // k = 100: δ = 19.6 cm, all 8 corners sink and the die rests 9.8 cm under the top.
        let p = with_stiffness(100.0);
        assert!((resting_depth_on_face(&p) - (1.0 + 9.8)).abs() < 1e-9);
        // Buried whole, every orientation has the same energy: there is no pass to climb.
        assert!((edge_balanced_energy(&p) - resting_energy(&p)).abs() < 1e-6);
        assert!(!StopRule::new(&p).can_settle());
    }

    #[test]
    fn a_soft_table_lowers_the_threshold_below_the_edge() {
        // k = 5000: δ = 0.392 cm, the paper's 2598 erg would lie above the edge (174 erg).
        let p = with_stiffness(5000.0);
        let rule = StopRule::new(&p);
        let edge = edge_balanced_energy(&p);
        assert!(edge < p.stop_threshold());
        assert!(rule.energy_threshold < edge);
        assert!(rule.energy_threshold > resting_energy(&p));
        assert!(rule.kinetic_threshold < p.stop_threshold());
    }

    #[test]
    fn settles_needs_all_three_energies_and_refuses_nan() {
        let rule = StopRule {
            energy_threshold: 10.0,
            kinetic_threshold: 20.0,
        };
        assert!(settles(10.0, 20.0, -10.0, &rule));
        assert!(settles(10.0, 20.0, 10.0, &rule));
        assert!(!settles(10.5, 0.0, 0.0, &rule));
        assert!(!settles(-100.0, 21.0, 0.0, &rule));
        assert!(!settles(-100.0, 0.0, 11.0, &rule));
        assert!(!settles(f64::NAN, 0.0, 0.0, &rule));
        assert!(!settles(0.0, f64::NAN, 0.0, &rule));
        assert!(!settles(0.0, 0.0, f64::NAN, &rule));
    }
}
