//! Presets: named TOML files that capture a whole setup (docs/presets.md).
//!
//! - [`Preset`] is one setup; [`Preset::from_toml_str`] and [`Preset::to_toml`] read and write
//!   the file format, [`Preset::with_overrides`] applies `--set KEY=VALUE`.
//! - [`View`] is a preset's optional `[view]`: how the explorer opens it.
//! - [`Store`] finds presets (a path, the user's folder, the shipped set), lists them and saves
//!   into the user's folder atomically.
//! - [`Preset::default`] is the shipped `paper` preset: what runs when no preset is named.

mod error;
mod file;
mod overrides;
mod shipped;
mod speed;
mod store;
mod view;

pub use error::{Location, PresetError};
pub use shipped::{DEFAULT_NAME, SHIPPED, shipped_text};
pub use speed::Speed;
pub use store::read_regular_file;
pub use store::{Entry, PRESETS_ENV, Source, Store, check_name, load_file};
pub use view::{CameraView, Screen, ThemeName, View};
pub use view::{PITCH, ZOOM};

use dicesim_physics::RandomRanges;
use dicesim_physics::{Die, Ground, InitialCondition, Integrator, Limits, ParamError, Params, World};
use serde::{Deserialize, Serialize};

/// The newest preset file format this program reads and writes.
pub const FORMAT: u32 = 1;

/// The `format` key's allowed values: a file from a newer program is refused.
pub(crate) const FORMAT_LIMITS: Limits = Limits {
    key: "format",
    unit: "",
    min: 1.0,
    max: FORMAT as f64,
};

/// One experiment's complete setup. Every key is optional in a file; missing keys take the
/// paper's defaults (the model's, not the `paper` preset's initial spin).
///
/// The defaults are per field rather than `#[serde(default)]` on the struct, because the
/// struct's `Default` is itself loaded from a file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Preset {
    #[serde(default = "current_format")]
    pub format: u32,
    /// Shown in the TUI header; a saved preset's file stem.
    #[serde(default)]
    pub name: String,
    /// Read aloud by a teacher, shown in the TUI and by `presets list`.
    #[serde(default)]
    pub description: String,
    #[serde(default)]
    pub die: Die,
    #[serde(default)]
    pub ground: Ground,
    #[serde(default)]
    pub world: World,
    #[serde(default)]
    pub integrator: Integrator,
    #[serde(default)]
    pub initial: InitialCondition,
    #[serde(default)]
    pub random: RandomRanges,
    /// How the explorer shows it (speed, camera, theme, …); all optional.
    #[serde(default, skip_serializing_if = "View::is_empty")]
    pub view: View,
}

fn current_format() -> u32 {
    FORMAT
}

impl Default for Preset {
    /// The shipped `paper` preset (the paper's constants and a lively first roll).
    fn default() -> Self {
        shipped::default_preset().clone()
    }
}

impl Preset {
    /// The model parameters of this setup.
    pub fn params(&self) -> Params {
        Params {
            die: self.die,
            ground: self.ground,
            world: self.world,
            integrator: self.integrator,
        }
    }

    /// Takes the model parameters of `params` into this setup.
    pub(crate) fn set_params(&mut self, params: Params) {
        let Params {
            die,
            ground,
            world,
            integrator,
        } = params;
        (self.die, self.ground, self.world, self.integrator) = (die, ground, world, integrator);
    }

    /// Checks every value against its allowed range.
    pub fn validate(&self) -> Result<(), ParamError> {
        FORMAT_LIMITS.check(f64::from(self.format))?;
        self.params().validate()?;
        self.initial.validate()?;
        self.initial.check_clear_of_table(&self.params())?;
        self.random.validate()?;
        self.view.validate()
    }
}
