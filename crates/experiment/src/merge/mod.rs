//! The shards of a sweep put back together, byte for byte the one-machine result, after
//! checking that they are all the shards of one sweep and that each file is what its shard
//! wrote; `--verify` rolls records chosen at random again, the one check a consistent
//! forgery cannot pass.
//!
//! [`Parts::read`] reads and checks the part summaries; [`Parts::merge_batch`] and
//! [`Parts::merge_map`] check every record or cell, write the merged files and return what
//! the command prints. A refused merge writes nothing.

mod batch;
mod map;
mod parts;
mod rows;

pub use batch::BatchMerge;
pub use map::MapMerge;
pub use parts::{MergeError, Parts};
