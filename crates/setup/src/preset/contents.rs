//! What one preset holds: [`Preset`], every section of the file, and the format version.

use super::view::View;
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

    /// Every value of this setup, as the registry's rows read them.
    pub fn values(&self) -> crate::registry::Setup {
        crate::registry::Setup {
            params: self.params(),
            initial: self.initial,
            random: self.random,
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
        crate::random::check_seed(self.random.seed)?;
        self.random.validate()?;
        self.view.validate()
    }
}
