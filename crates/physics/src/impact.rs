//! Impacts, by the one definition every reader of a roll uses (docs/model.md, "Impacts"): an
//! impact begins at a state in contact with the table that follows at least one state with
//! the whole body clear of it. Contact is the step's own reading, [`Simulation::in_contact`]
//! (some corner, or a rounded body's corner sphere, below the table), so a die that rocks
//! from corner to corner without ever lifting clear is in one impact, and one that leaves the
//! table for a single step and comes back starts another.
//!
//! [`Simulation::in_contact`]: crate::Simulation::in_contact

/// Follows a roll's contact state by state and says where each impact begins.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Impacts {
    /// Whether the last state seen had the whole body clear of the table.
    clear: bool,
    /// Impacts begun so far.
    count: u64,
}

impl Impacts {
    /// A roll whose first state is in contact (`in_contact`) or clear of the table: a die
    /// placed on the table starts no impact until it has left it.
    pub fn new(in_contact: bool) -> Impacts {
        Impacts {
            clear: !in_contact,
            count: 0,
        }
    }

    /// The next state's contact; whether an impact begins at it.
    pub fn observe(&mut self, in_contact: bool) -> bool {
        let begins = in_contact && self.clear;
        self.clear = !in_contact;
        self.count += u64::from(begins);
        begins
    }

    /// Impacts begun in the states seen so far.
    pub fn count(&self) -> u64 {
        self.count
    }
}

/// The indices at which impacts begin in a roll's contact readings, one per state from the
/// first (index 0, the start, never begins one: nothing came before it).
pub fn impact_starts(contact: impl IntoIterator<Item = bool>) -> Vec<u64> {
    let mut states = contact.into_iter();
    let Some(first) = states.next() else {
        return Vec::new();
    };
    let mut impacts = Impacts::new(first);
    (1..)
        .zip(states)
        .filter_map(|(i, c)| impacts.observe(c).then_some(i))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_impact_begins_only_after_the_body_was_clear() {
        // Falling, a contact of three states, one state clear, a contact, resting on.
        let contact = [false, false, true, true, true, false, true, true, true];
        assert_eq!(impact_starts(contact), [2, 6]);
        let mut counted = Impacts::new(false);
        for c in contact {
            counted.observe(c);
        }
        assert_eq!(counted.count(), 2);
        // A die placed on the table: its first contact is no impact, its next bounce is.
        assert_eq!(impact_starts([true, true, false, true]), [3]);
        assert!(impact_starts([]).is_empty());
        assert!(impact_starts([false; 5]).is_empty());
    }
}
