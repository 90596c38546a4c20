//! The explorer's simulation thread through its public protocol: commands in, snapshots out,
//! basin maps and the twin's predictability curve equal to what the experiment layer
//! computes.

mod worker_curve;
mod worker_map;
mod worker_protocol;
