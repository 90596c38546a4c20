//! Presets: named TOML files that capture a whole setup (docs/presets.md).
//!
//! - [`Preset`] is one setup; [`Preset::from_toml_str`] and [`Preset::to_toml`] read and write
//!   the file format, [`Preset::with_overrides`] applies `--set KEY=VALUE`.
//! - [`View`] is a preset's optional `[view]`: how the explorer opens it.
//! - [`Store`] finds presets (a path, the user's folder, the shipped set), lists them and saves
//!   into the user's folder atomically.
//! - [`Preset::default`] is the shipped `paper` preset: what runs when no preset is named.

mod contents;
mod error;
mod file;
mod overrides;
mod shipped;
mod speed;
mod store;
mod view;

pub use contents::{FORMAT, Preset};
pub use error::{Location, PresetError};
pub use overrides::refuse_unapplied;
pub use shipped::{DEFAULT_NAME, LESSON, SHIPPED, shipped_text};
pub use speed::Speed;
pub use store::read_regular_file;
pub use store::{Entry, PRESETS_ENV, Source, Store, check_name, load_file};
pub use view::{CameraView, Readout, Readouts, Screen, ThemeName, View};
pub use view::{PITCH, ZOOM};
