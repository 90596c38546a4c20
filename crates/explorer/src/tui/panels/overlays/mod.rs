//! The panels drawn over a screen: the help, the dialogs and a lesson step's card.

pub(crate) mod dialogs;
pub(crate) mod help;
pub(crate) mod lesson_card;
pub(crate) mod popup;
