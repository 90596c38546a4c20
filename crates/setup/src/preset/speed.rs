//! Playback speed: how much simulated time passes per second of wall time. A preset's
//! `[view]` names one by its label (`speed = "1/20×"`), so the ladder lives with presets.

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// Simulated seconds per wall-clock second, from 1/100× to 100×; the step Δt never changes.
const FACTORS: [f64; 13] = [
    0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0,
];
const LABELS: [&str; 13] = [
    "1/100×", "1/50×", "1/20×", "1/10×", "1/5×", "1/2×", "1×", "2×", "5×", "10×", "20×", "50×", "100×",
];
const INSTANT: u8 = FACTORS.len() as u8;
const REAL_TIME: u8 = 6;

/// A playback speed on the ladder 1/100× … 100×, then "instant" (compute to the end, then show).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Speed(u8);

impl Default for Speed {
    fn default() -> Self {
        Speed(REAL_TIME)
    }
}

impl Speed {
    pub const SLOWEST: Speed = Speed(0);
    #[cfg(test)]
    pub(crate) const FASTEST: Speed = Speed(FACTORS.len() as u8 - 1);
    pub const INSTANT: Speed = Speed(INSTANT);

    /// Simulated seconds per wall second; `None` for instant.
    pub fn factor(self) -> Option<f64> {
        FACTORS.get(self.0 as usize).copied()
    }

    pub fn slower(self) -> Speed {
        Speed(self.0.saturating_sub(1))
    }

    pub fn faster(self) -> Speed {
        Speed((self.0 + 1).min(INSTANT))
    }

    pub fn label(self) -> &'static str {
        LABELS.get(self.0 as usize).copied().unwrap_or("instant")
    }

    /// The speed a label names (`1/20×`, `1/20`, `5×`, `5`, `instant`), if it is on the ladder.
    pub fn from_label(label: &str) -> Option<Speed> {
        let bare = label.trim().trim_end_matches(['×', 'x']);
        if bare == "instant" {
            return Some(Speed::INSTANT);
        }
        LABELS
            .iter()
            .position(|l| l.trim_end_matches('×') == bare)
            .map(|i| Speed(i as u8))
    }

    /// Every label, slowest first, for messages that list them.
    pub fn labels() -> impl Iterator<Item = &'static str> {
        LABELS.iter().copied().chain(["instant"])
    }
}

impl Serialize for Speed {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.label())
    }
}

impl<'de> Deserialize<'de> for Speed {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Speed, D::Error> {
        let label = String::deserialize(d)?;
        Speed::from_label(&label).ok_or_else(|| {
            serde::de::Error::custom(format!(
                "`{label}` is not a playback speed; one of {}",
                Speed::labels().collect::<Vec<_>>().join(", ")
            ))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ladder_runs_from_a_hundredth_to_instant_and_stops_at_the_ends() {
        assert_eq!(Speed::default().factor(), Some(1.0));
        assert_eq!(Speed::SLOWEST.slower(), Speed::SLOWEST);
        assert_eq!(Speed::SLOWEST.factor(), Some(0.01));
        assert_eq!(Speed::FASTEST.factor(), Some(100.0));
        assert_eq!(Speed::FASTEST.faster(), Speed::INSTANT);
        assert_eq!(Speed::INSTANT.faster(), Speed::INSTANT);
        assert_eq!(Speed::INSTANT.factor(), None);
        assert_eq!(Speed::INSTANT.slower(), Speed::FASTEST);
        assert_eq!(Speed::default().slower().label(), "1/2×");
        for label in Speed::labels() {
            let s = Speed::from_label(label).expect("its own label");
            assert_eq!(s.label(), label);
        }
        assert_eq!(Speed::from_label("1/20"), Some(Speed(2)));
        assert_eq!(Speed::from_label("1/3×"), None);
    }
}
