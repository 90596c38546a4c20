//! Input: `update` turns a message (a key, a click, a snapshot) into changes of the state and
//! effects for the outbox, with one file of keys per mode that needs more than the key table.

pub(crate) mod dialog_keys;
pub(crate) mod lesson_keys;
pub(crate) mod map_keys;
pub(crate) mod throw_keys;
pub(crate) mod twin_keys;
pub(crate) mod update;

#[cfg(test)]
mod map_keys_tests;
#[cfg(test)]
mod throw_keys_tests;
#[cfg(test)]
mod update_tests;
