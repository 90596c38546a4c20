//! The energy terms a plot shows (docs/model.md, "Energy"), erg.

use serde::Serialize;

/// Rigid-body energy split into its forms, erg. Zero for a die at rest lying flat.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Energy {
    /// `½·M·|v|²`
    pub translational: f64,
    /// `½·ω·L`, with the cube's inertia.
    pub rotational: f64,
    /// `M·g·(z − a)`, zero when the cube lies flat.
    pub gravitational: f64,
    /// `Σ ½·k·d_k²` over corners below the ground.
    pub elastic: f64,
}

impl Energy {
    pub fn kinetic(&self) -> f64 {
        self.translational + self.rotational
    }

    pub fn total(&self) -> f64 {
        self.translational + self.rotational + self.gravitational + self.elastic
    }

    /// Each term's larger value of the two: what a thinned plot keeps over a stride, so
    /// impact spikes survive.
    pub fn max_each(&self, other: &Energy) -> Energy {
        Energy {
            translational: self.translational.max(other.translational),
            rotational: self.rotational.max(other.rotational),
            gravitational: self.gravitational.max(other.gravitational),
            elastic: self.elastic.max(other.elastic),
        }
    }
}
