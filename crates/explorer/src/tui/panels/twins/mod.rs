//! The panels a twin puts in the outcome table's and the plot's places while it rolls.

pub(crate) mod predictability_curve;
pub(crate) mod separation;
pub(crate) mod versus_table;
