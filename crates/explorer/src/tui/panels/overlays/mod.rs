//! The panels drawn over a screen: the help and the dialogs.

pub(crate) mod dialogs;
pub(crate) mod help;
pub(crate) mod popup;
