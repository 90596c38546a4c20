//! How a roll ended, in the words every output uses for it: the batch summary, the
//! explorer's outcome table and its basin map's legend, and the map images.

use dicesim_physics::{Outcome, Status};

/// The endings a roll can have.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ending {
    /// Settled with this face up.
    Face(u8),
    /// Settled, but the 4 highest corners form no face (balanced on an edge or a corner).
    WithoutFace,
    /// Still moving when `integrator.max_time` ran out.
    DidNotSettle,
    /// The integrator gained energy until the state ran away.
    Unstable,
}

impl Ending {
    pub fn of(outcome: &Outcome) -> Ending {
        match (outcome.status, outcome.face) {
            (Status::Settled, Some(f)) => Ending::Face(f),
            (Status::Settled, None) => Ending::WithoutFace,
            (Status::Timeout, _) => Ending::DidNotSettle,
            (Status::Unstable, _) => Ending::Unstable,
        }
    }

    /// The ending in words: "face 3", "settled without a face", "did not settle", "unstable".
    pub fn words(self) -> String {
        match self {
            Ending::Face(f) => format!("face {f}"),
            other => other.name().to_string(),
        }
    }

    /// The words of an ending without a face; "face" for the faces.
    pub fn name(self) -> &'static str {
        match self {
            Ending::Face(_) => "face",
            Ending::WithoutFace => "settled without a face",
            Ending::DidNotSettle => "did not settle",
            Ending::Unstable => "unstable",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_status_has_its_words() {
        let o = |status, face| Outcome {
            status,
            face,
            steps: 0,
            time_s: 0.0,
            impacts: 0,
            first_impact: None,
        };
        assert_eq!(Ending::of(&o(Status::Settled, Some(3))).words(), "face 3");
        assert_eq!(
            Ending::of(&o(Status::Settled, None)).words(),
            "settled without a face"
        );
        assert_eq!(Ending::of(&o(Status::Timeout, None)).words(), "did not settle");
        assert_eq!(Ending::of(&o(Status::Unstable, None)).words(), "unstable");
    }
}
