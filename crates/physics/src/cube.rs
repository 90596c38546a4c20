//! The paper's body (docs/model.md): a sharp cube of side `2a` whose mass sits at its 8
//! corners, with its edge energy, its fastest contact mode and its stopping rule over the
//! whole allowed range ("Stopping rule"). A loaded cube is this cube with extra corner
//! masses (mass.rs), and keeps this rule as the one its faces' rules are scaled from.
//!
//! The paper ends a roll once its energy is below `f·E_edge`, with the potential measured
//! from a die lying flat on a rigid table. On a table of finite stiffness the die rests
//! `δ = M·g/(4k)` deep, so its resting energy `V_rest` is below zero and an edge-balanced
//! die sits lower too (`V_edge`). The rule below keeps the paper's test and adds what only
//! binds on soft tables: the energy must stay clear of `V_edge`, and the kinetic and the
//! potential energy must each be within what the energy test allows above rest.

use super::params::Params;
use super::stopping::{StopRule, lowest_potential_at};
use std::f64::consts::SQRT_2;

/// The paper's cube on its table: what its closed forms read from the parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Cube {
    /// cm, `a`.
    half_size: f64,
    /// g, the 8 corners of `die.corner_mass`, without the extra masses.
    uniform_mass: f64,
    /// g, the whole die `M`.
    mass: f64,
    /// cm/s².
    gravity: f64,
    /// dyn/cm per corner.
    stiffness: f64,
    /// A roll ends below this share of the edge energy.
    stop_energy_fraction: f64,
}

impl Cube {
    /// `p`'s die as the paper's cube: `8·m` plus its extra corner masses (adding a fair
    /// die's zeros leaves `8·m` bit for bit).
    pub(crate) fn new(p: &Params) -> Cube {
        let uniform_mass = 8.0 * p.die.corner_mass;
        Cube::weighing(p, uniform_mass + p.die.extra_corner_mass.iter().sum::<f64>())
    }

    /// A cube of `p`'s first half size that weighs `mass` (g).
    pub(crate) fn weighing(p: &Params, mass: f64) -> Cube {
        Cube {
            half_size: p.die.half_size(),
            uniform_mass: 8.0 * p.die.corner_mass,
            mass,
            gravity: p.world.gravity,
            stiffness: p.ground.stiffness,
            stop_energy_fraction: p.integrator.stop_energy_fraction,
        }
    }

    /// cm, `a`.
    pub(crate) fn half_size(&self) -> f64 {
        self.half_size
    }

    /// g, `M`.
    pub(crate) fn mass(&self) -> f64 {
        self.mass
    }

    /// g, `8·m`: the cube without its extra corner masses.
    pub(crate) fn uniform_mass(&self) -> f64 {
        self.uniform_mass
    }

    /// g·cm², the uniform cube's isotropic `(2a)²/6·8m` (a loaded cube's extra masses are
    /// not in it: they turn with the body, mass.rs). Written in the authors' order of
    /// operations, so the default is bitwise 16/3.
    pub(crate) fn inertia(&self) -> f64 {
        let side = 2.0 * self.half_size;
        side * side / 6.0 * self.uniform_mass
    }

    /// erg, the energy to tip over an edge from lying flat on a rigid table, `M·g·a·(√2 − 1)`.
    pub(crate) fn edge_energy(&self) -> f64 {
        self.mass * self.gravity * self.half_size * (SQRT_2 - 1.0)
    }

    /// erg, the paper's stopping threshold `f·E_edge`, grouped as the authors grouped it:
    /// bitwise 2597.9474632040528 at the defaults.
    fn paper_threshold(&self) -> f64 {
        self.stop_energy_fraction * (self.mass * self.gravity * self.half_size) * (SQRT_2 - 1.0)
    }

    /// rad/s, the fastest contact mode: the cube lying flat rocking on its face, `√(6k/M)`.
    pub(crate) fn rocking_frequency(&self) -> f64 {
        (6.0 * self.stiffness / self.mass).sqrt()
    }

    /// `energy_threshold = min(f·E_edge, V_edge − ½·(1 − f)·E_edge)` and
    /// `kinetic_threshold = energy_threshold − V_rest`; both are −∞ (the roll can only end
    /// as a timeout) when the table cannot hold the die on a face: its resting centre would
    /// be below the table top, or the threshold would not lie above the resting energy.
    pub(crate) fn stop_rule(&self) -> StopRule {
        let rest = self.resting_energy();
        let margin = 0.5 * (1.0 - self.stop_energy_fraction) * self.edge_energy();
        let energy_threshold = self.paper_threshold().min(self.edge_balanced_energy() - margin);
        let rest_centre = self.half_size - self.resting_depth_on_face();
        if energy_threshold > rest && rest_centre > 0.0 {
            StopRule {
                energy_threshold,
                kinetic_threshold: energy_threshold - rest,
            }
        } else {
            StopRule::NEVER
        }
    }

    /// cm, how deep the lower corners sink when the die rests on a face, with as many
    /// corners touching as the depth implies (4, or all 8 on a table too soft to carry it).
    pub(crate) fn resting_depth_on_face(&self) -> f64 {
        let a = self.half_size;
        let (centre, _) = self.lowest_potential(&[-a, -a, -a, -a, a, a, a, a]);
        a - centre
    }

    /// erg, the potential energy of the die at rest on a face (`−½·M·g·δ` while only the
    /// four lower corners touch), measured like the rigid-body energy from the flat height
    /// `z = a`.
    pub(crate) fn resting_energy(&self) -> f64 {
        let a = self.half_size;
        self.lowest_potential(&[-a, -a, -a, -a, a, a, a, a]).1
    }

    /// erg, the potential energy of the die at rest balanced on an edge (`E_edge − M·g·δ`
    /// while only the edge's two corners touch): the lowest pass between two faces.
    pub(crate) fn edge_balanced_energy(&self) -> f64 {
        let e = self.half_size * SQRT_2;
        self.lowest_potential(&[-e, -e, 0.0, 0.0, 0.0, 0.0, e, e]).1
    }

    /// [`lowest_potential_at`] for this cube, its corners `offsets` (cm, ascending) above
    /// or below its centre.
    fn lowest_potential(&self, offsets: &[f64; 8]) -> (f64, f64) {
        lowest_potential_at(self.mass * self.gravity, self.stiffness, self.half_size, offsets)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn on_stiffness(k: f64) -> Cube {
        let mut p = Params::default();
        p.ground.stiffness = k;
        Cube::new(&p)
    }

    #[test]
    #[allow(clippy::excessive_precision)] // the reference's threshold, digit for digit
    fn the_paper_cube_has_the_papers_numbers() {
        let cube = Cube::new(&Params::default());
        assert_eq!(cube.mass(), 8.0);
        assert_eq!(cube.inertia(), 16.0 / 3.0);
        assert_eq!(cube.paper_threshold(), 2597.9474632040528);
        // M·g·a·(√2 − 1) = 8·980·(√2 − 1) = 3247.4 erg; √(6k/M) = √375000.
        assert!((cube.edge_energy() - 3247.4).abs() < 0.05);
        assert!((cube.rocking_frequency() - 612.37).abs() < 0.01);
        // The rule stands at the paper's threshold on the paper's stiff table.
        let rule = cube.stop_rule();
        assert_eq!(rule.energy_threshold, cube.paper_threshold());
        assert_eq!(
            rule.kinetic_threshold,
            cube.paper_threshold() - cube.resting_energy()
        );
    }

    #[test]
    fn shallow_table_matches_the_closed_forms() {
        let cube = Cube::new(&Params::default());
        let (m, g) = (8.0, 980.0);
        let delta = m * g / (4.0 * 500_000.0);
        assert!((cube.resting_depth_on_face() - delta).abs() < 1e-12);
        assert!((cube.resting_energy() + 0.5 * m * g * delta).abs() < 1e-9);
        assert!((cube.edge_balanced_energy() - (cube.edge_energy() - m * g * delta)).abs() < 1e-9);
    }

    #[test]
    fn a_table_softer_than_the_die_cannot_hold_a_face() {
        // k = 100: δ = 19.6 cm, all 8 corners sink and the die rests 9.8 cm under the top.
        let cube = on_stiffness(100.0);
        assert!((cube.resting_depth_on_face() - (1.0 + 9.8)).abs() < 1e-9);
        // Buried whole, every orientation has the same energy: there is no pass to climb.
        assert!((cube.edge_balanced_energy() - cube.resting_energy()).abs() < 1e-6);
        assert!(!cube.stop_rule().can_settle());
    }

    #[test]
    fn a_soft_table_lowers_the_threshold_below_the_edge() {
        // k = 5000: δ = 0.392 cm, the paper's 2598 erg would lie above the edge (174 erg).
        let cube = on_stiffness(5000.0);
        let rule = cube.stop_rule();
        let edge = cube.edge_balanced_energy();
        assert!(edge < cube.paper_threshold());
        assert!(rule.energy_threshold < edge);
        assert!(rule.energy_threshold > cube.resting_energy());
        assert!(rule.kinetic_threshold < cube.paper_threshold());
    }

    #[test]
    fn a_cube_weighed_anew_keeps_its_size_and_table() {
        let p = Params::default();
        let heavier = Cube::weighing(&p, 16.0);
        assert_eq!(heavier.edge_energy(), 2.0 * Cube::new(&p).edge_energy());
        assert_eq!(heavier.inertia(), Cube::new(&p).inertia());
    }
}
