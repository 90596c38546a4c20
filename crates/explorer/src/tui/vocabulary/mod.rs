//! The explorer's vocabulary: what every other part names and none of it names back. The
//! one key table, the parameter rows, numbers as text, fitting text to a width, the themes,
//! the die's solid, and where each part of a screen goes.

pub(crate) mod big_type;
pub(crate) mod fit;
pub(crate) mod format;
pub(crate) mod key_table;
pub(crate) mod layout;
pub(crate) mod param;
pub(crate) mod solid;
pub(crate) mod theme;
