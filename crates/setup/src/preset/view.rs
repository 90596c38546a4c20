//! A preset's optional `[view]`: how the explorer shows the setup when the preset opens
//! (docs/presets.md, "The view"). Every key is optional; a missing key leaves the
//! explorer's own default. The CLI ignores the view.

use super::speed::Speed;
use dicesim_physics::{Limits, ParamError};
use serde::{Deserialize, Serialize};

/// °, the camera's turn about the vertical.
pub(crate) const YAW: Limits = Limits {
    key: "view.camera.yaw",
    unit: "°",
    min: -360.0,
    max: 360.0,
};
/// °, the camera's elevation: 0 looks level, 89 almost straight down.
pub const PITCH: Limits = Limits {
    key: "view.camera.pitch",
    unit: "°",
    min: -10.0,
    max: 89.0,
};
/// Zoom steps, each 1.25 times closer.
pub const ZOOM: Limits = Limits {
    key: "view.camera.zoom",
    unit: "",
    min: -8.0,
    max: 8.0,
};

#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct View {
    /// Playback speed, as the header shows it: `"1/100×"` … `"100×"`, or `"instant"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed: Option<Speed>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera: Option<CameraView>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub theme: Option<ThemeName>,
    /// Arrows for ω, L, v and the contact forces.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub arrows: Option<bool>,
    /// A chaos twin rolls beside the die, its start perturbed by this relative ε.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub twin: Option<f64>,
    /// The screen the explorer opens on.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub screen: Option<Screen>,
    /// The readouts on the die panel and in the presentation view: the signed spin, the
    /// lean from the vertical, the distance slid.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub readouts: Option<Readouts>,
}

/// One readout a class can see beside the die (docs/explorer.md, "Readouts").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Readout {
    /// rad/s, ω's components with their signs.
    Spin,
    /// °, the die's lean from the vertical.
    Lean,
    /// cm, slid along the table since the contact began.
    Slid,
}

/// The readouts chosen, written as a list: `readouts = ["spin", "lean"]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(from = "Vec<Readout>", into = "Vec<Readout>")]
pub struct Readouts {
    pub spin: bool,
    pub lean: bool,
    pub slid: bool,
}

impl From<Vec<Readout>> for Readouts {
    fn from(list: Vec<Readout>) -> Readouts {
        Readouts {
            spin: list.contains(&Readout::Spin),
            lean: list.contains(&Readout::Lean),
            slid: list.contains(&Readout::Slid),
        }
    }
}

impl From<Readouts> for Vec<Readout> {
    fn from(r: Readouts) -> Vec<Readout> {
        [
            (r.spin, Readout::Spin),
            (r.lean, Readout::Lean),
            (r.slid, Readout::Slid),
        ]
        .into_iter()
        .filter_map(|(on, which)| on.then_some(which))
        .collect()
    }
}

impl Readout {
    /// The name a preset writes.
    pub fn name(self) -> &'static str {
        match self {
            Readout::Spin => "spin",
            Readout::Lean => "lean",
            Readout::Slid => "slid",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraView {
    /// °, turn about the vertical.
    pub yaw: f64,
    /// °, elevation.
    pub pitch: f64,
    /// Zoom steps.
    #[serde(default)]
    pub zoom: i32,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ThemeName {
    Dark,
    Light,
    Projector,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Screen {
    /// The die, its energy and the outcome table.
    Die,
    /// The basin map of the setup.
    Map,
}

impl View {
    /// Whether nothing is set (no `[view]` is written then).
    pub(crate) fn is_empty(&self) -> bool {
        *self == View::default()
    }

    /// Every value in its range; errors name the key as the file has it.
    pub(crate) fn validate(&self) -> Result<(), ParamError> {
        if let Some(c) = &self.camera {
            YAW.check(c.yaw)?;
            PITCH.check(c.pitch)?;
            ZOOM.check(f64::from(c.zoom))?;
        }
        if let Some(epsilon) = self.twin {
            Limits {
                key: "view.twin",
                ..crate::chaos::EPSILON
            }
            .check(epsilon)?;
        }
        Ok(())
    }

    /// The `[view]` table's lines, with their comments (empty when nothing is set).
    pub(crate) fn lines(&self) -> Vec<(String, String, &'static str)> {
        let mut out = Vec::new();
        let string = |s: &str| toml::Value::String(s.to_string()).to_string();
        if let Some(s) = self.speed {
            out.push((
                "speed".to_string(),
                string(s.label()),
                "playback: 1/100× … 100×, or instant",
            ));
        }
        if let Some(c) = self.camera {
            out.push((
                "camera".to_string(),
                format!(
                    "{{ yaw = {}, pitch = {}, zoom = {} }}",
                    toml::Value::Float(c.yaw),
                    toml::Value::Float(c.pitch),
                    c.zoom
                ),
                "°, °, zoom steps (each 1.25× closer)",
            ));
        }
        if let Some(t) = self.theme {
            let name = match t {
                ThemeName::Dark => "dark",
                ThemeName::Light => "light",
                ThemeName::Projector => "projector",
            };
            out.push(("theme".to_string(), string(name), "dark, light or projector"));
        }
        if let Some(a) = self.arrows {
            out.push(("arrows".to_string(), a.to_string(), "ω, L, v and F on the die"));
        }
        if let Some(e) = self.twin {
            out.push((
                "twin".to_string(),
                // `1e-9` reads better than `0.000000001`, and TOML takes both.
                format!("{e:e}"),
                "a chaos twin at this relative ε",
            ));
        }
        if let Some(s) = self.screen {
            let name = match s {
                Screen::Die => "die",
                Screen::Map => "map",
            };
            out.push(("screen".to_string(), string(name), "die or map"));
        }
        if let Some(r) = self.readouts {
            let names: Vec<String> = Vec::<Readout>::from(r).iter().map(|n| string(n.name())).collect();
            out.push((
                "readouts".to_string(),
                format!("[{}]", names.join(", ")),
                "beside the die: spin (ω, signed), lean (°), slid (cm)",
            ));
        }
        out
    }
}
