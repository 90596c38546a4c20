//! The preset dialogs' state: what the picker offers and what the save dialog holds.

use dicesim_setup::preset::Preset;

/// The picker's groups, in the order it lists them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Group {
    /// The shipped presets the lesson opens ([`dicesim_setup::preset::LESSON`]).
    Lesson,
    /// The other shipped presets.
    Shipped,
    /// The user's own.
    Yours,
}

impl Group {
    /// The heading the picker writes over the group.
    pub(crate) fn heading(self) -> &'static str {
        match self {
            Group::Lesson => "for the lesson",
            Group::Shipped => "more shipped presets",
            Group::Yours => "yours ★",
        }
    }
}

/// One preset the picker offers.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Choice {
    pub(crate) name: String,
    /// The user's own (saved from here or by hand), rather than shipped.
    pub(crate) user: bool,
    /// The group it is listed in.
    pub(crate) group: Group,
    /// The preset, or why its file does not load.
    pub(crate) preset: Result<Box<Preset>, String>,
}

#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Dialog {
    Picker {
        choices: Vec<Choice>,
        selected: usize,
        error: Option<String>,
    },
    Save {
        name: String,
        /// Empty: the automatic description
        /// ([`UserSetup::automatic_description`](super::user_setup::UserSetup::automatic_description))
        /// is saved.
        description: String,
        /// Which field the keys type into (Tab switches).
        field: SaveField,
        error: Option<String>,
        /// The name exists and Enter was pressed once: the next Enter replaces it.
        confirm_replace: bool,
    },
}

/// The save dialog's fields.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum SaveField {
    Name,
    Description,
}
