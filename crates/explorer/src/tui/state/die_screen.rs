//! The die screen as the user set it up: which value of the parameter list is selected,
//! what the plot panel draws and on which scale, whether the arrows show, how the die is
//! drawn and seen, and the presentation view's number. The keys set these; the panels read
//! them.

use super::camera::OrbitCamera;
use super::throw::Throw;
use crate::tui::vocabulary::format::fmt_num;
use crate::tui::vocabulary::param::Param;
use crate::worker::{DieState, Snapshot};
use dicesim_setup::preset::Readouts;
use dicesim_setup::quantity::{QUANTITIES, QUANTITY_COUNT, TOTAL_ENERGY};
use ratatui::symbols::Marker;

/// The die screen's choices, each changed by its keys (or the mouse) and kept while the
/// map screen or an overlay is on top.
#[derive(Debug, Clone, Default)]
pub(crate) struct DieScreen {
    /// Index into [`all`].
    pub(crate) selected: usize,
    /// The energy plot on a logarithmic scale (`p`).
    pub(crate) log_scale: bool,
    /// What the plot panel draws (`w`, `V`).
    pub(crate) plot: PlotChoice,
    /// Arrows for ω, L, v and the contact forces on the die (`v`).
    pub(crate) arrows: bool,
    /// Braille dots or ASCII (`m`).
    pub(crate) drawing: Drawing,
    /// Orbited and zoomed by its keys, a drag and the wheel.
    pub(crate) camera: OrbitCamera,
    /// The number the presentation view shows beside the face.
    pub(crate) readout: Readout,
    /// Last mouse position while dragging the die.
    pub(crate) drag: Option<(u16, u16)>,
    /// The face pair marked (`M`), by its lower face (2, 1 or 3; the other is 7 minus it):
    /// its faces coloured, its body axis drawn through them.
    pub(crate) face_pair: Option<u8>,
    /// Throw mode's aim, while it is on (`f`, or a drag with Ctrl or Alt held).
    pub(crate) throw: Option<Throw>,
    /// The readouts beside the die, as the preset's `[view]` chose them.
    pub(crate) readouts: Readouts,
}

impl DieScreen {
    /// The parameter selected on `listed`, the list shown.
    pub(crate) fn selected_param(&self, listed: &[Param]) -> Param {
        listed[self.selected.min(listed.len() - 1)]
    }

    /// `M`: the next face pair marked, 2 and 5 first (the pair a tennis racket flips).
    pub(crate) fn next_face_pair(&mut self) {
        self.face_pair = match self.face_pair {
            None => Some(2),
            Some(2) => Some(1),
            Some(1) => Some(3),
            Some(_) => None,
        };
    }

    /// Moves the parameter list's selection by `delta` rows, inside a list of `rows`.
    pub(crate) fn select(&mut self, delta: isize, rows: usize) {
        self.selected = (self.selected as isize + delta).clamp(0, rows as isize - 1) as usize;
    }
}

/// How the die is drawn: Braille dots, or plain ASCII for fonts without Braille.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Drawing {
    #[default]
    Braille,
    Ascii,
}

impl Drawing {
    /// The marker that draws the plots' lines.
    pub(crate) fn line_marker(self) -> Marker {
        match self {
            Drawing::Braille => Marker::Braille,
            Drawing::Ascii => Marker::Custom('.'),
        }
    }
}

/// Index of the height of the centre and of the speed in [`QUANTITIES`](dicesim_setup::quantity::QUANTITIES).
const HEIGHT: usize = 0;
const SPEED: usize = 2;

/// What the plot panel draws, chosen with the plot keys.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct PlotChoice {
    /// `None`: the energy terms together; `Some(i)`: `QUANTITIES[i]` against time.
    pub(crate) quantity: Option<usize>,
    /// `Some(j)`: the phase plot, `QUANTITIES[j]` up against the first quantity across.
    pub(crate) phase: Option<usize>,
    /// `Some(j)`: `QUANTITIES[j]` against time beside the first, on its axis (the same unit).
    pub(crate) second: Option<usize>,
    /// The value axis fitted to the curves around the time on screen (`y`) rather than
    /// spanning the whole roll.
    pub(crate) fitted: bool,
}

impl PlotChoice {
    /// The quantity plotted against time, or across in the phase plot (the energy plot's
    /// is its total).
    pub(crate) fn first(&self) -> usize {
        self.quantity.unwrap_or(TOTAL_ENERGY)
    }

    /// The next quantity: against time, the energy terms, then each quantity in turn; in
    /// the phase plot, the next quantity up (never the one across).
    pub(crate) fn next(&mut self) {
        match self.phase {
            Some(j) => {
                let mut k = (j + 1) % QUANTITY_COUNT;
                if k == self.first() {
                    k = (k + 1) % QUANTITY_COUNT;
                }
                self.phase = Some(k);
            }
            None => {
                self.quantity = match self.quantity {
                    None => Some(0),
                    Some(i) if i + 1 < QUANTITY_COUNT => Some(i + 1),
                    Some(_) => None,
                };
                // A second curve shares the first's axis, which just changed.
                self.second = None;
            }
        }
    }

    /// `Y`: the next quantity after the second (or the first) in the plotted one's unit, or
    /// none after the last; why not, where the plot has no place for one.
    pub(crate) fn next_second(&mut self) -> Result<(), String> {
        let Some(i) = self.quantity.filter(|_| self.phase.is_none()) else {
            return Err(if self.phase.is_some() {
                "the phase plot draws one quantity against another already".to_string()
            } else {
                "the energy plot draws every energy term already".to_string()
            });
        };
        let unit = QUANTITIES[i].unit;
        let others: Vec<usize> = (0..QUANTITY_COUNT)
            .filter(|&j| j != i && QUANTITIES[j].unit == unit)
            .collect();
        if others.is_empty() {
            return Err(format!("no other quantity is in {unit}"));
        }
        self.second = match self.second.and_then(|s| others.iter().position(|&j| j == s)) {
            None => Some(others[0]),
            Some(k) => others.get(k + 1).copied(),
        };
        Ok(())
    }

    /// The phase plot on (up: the height, or the speed when the height is across) or off.
    pub(crate) fn toggle_phase(&mut self) {
        self.phase = match self.phase {
            Some(_) => None,
            None if self.first() == HEIGHT => Some(SPEED),
            None => Some(HEIGHT),
        };
    }
}

/// The one number the view shows beside the face (`N` picks the next).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Readout {
    /// cm, the centre of mass above the table.
    #[default]
    Height,
    /// cm/s, of the centre of mass.
    Speed,
    /// rad/s, |ω|.
    Spin,
    /// erg, translational and rotational.
    KineticEnergy,
}

impl Readout {
    pub(crate) fn next(self) -> Readout {
        match self {
            Readout::Height => Readout::Speed,
            Readout::Speed => Readout::Spin,
            Readout::Spin => Readout::KineticEnergy,
            Readout::KineticEnergy => Readout::Height,
        }
    }

    /// What it is, in the model's words.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Readout::Height => "height",
            Readout::Speed => "speed",
            Readout::Spin => "spin",
            Readout::KineticEnergy => "kinetic energy",
        }
    }

    /// Its value in the snapshot on screen, and the unit.
    pub(crate) fn value(self, live: &Snapshot) -> (f64, &'static str) {
        match self {
            Readout::Height => (live.die.centre.z, "cm"),
            Readout::Speed => (live.die.velocity.norm(), "cm/s"),
            Readout::Spin => (live.die.angular_velocity.norm(), "rad/s"),
            Readout::KineticEnergy => (live.energy.kinetic(), "erg"),
        }
    }

    /// The value as the view writes it: a fixed number of decimals for the lengths and
    /// rates, so the digits do not jump about while they change.
    pub(crate) fn text(self, live: &Snapshot) -> String {
        let (v, unit) = self.value(live);
        match self {
            Readout::Height => format!("{v:.2} {unit}"),
            Readout::Speed | Readout::Spin => format!("{v:.1} {unit}"),
            Readout::KineticEnergy => format!("{} {unit}", fmt_num(v)),
        }
    }
}

/// The readouts `chosen`, each as the die panel and the presentation view write it
/// (docs/explorer.md, "Readouts").
pub(crate) fn readout_texts(chosen: Readouts, live: &Snapshot) -> Vec<String> {
    let mut out = Vec::new();
    if chosen.spin {
        out.push(signed_spin(&live.die));
    }
    if chosen.lean {
        out.push(format!("lean {:.1}°", lean_deg(&live.die)));
    }
    if chosen.slid {
        out.push(match live.die.slid_cm {
            Some(d) => format!("slid {d:.2} cm"),
            None => "slid: clear of the table".to_string(),
        });
    }
    out
}

/// ω's world components with their signs, to a tenth of a rad/s (two spaces apart: the
/// presentation view puts each on a line of its own): a spin that turns round
/// shows its sign change (a value that rounds to zero is +0.0, never -0.0 or noise).
pub(crate) fn signed_spin(die: &DieState) -> String {
    let w = die.angular_velocity;
    let signed = |v: f64| {
        let v = if v.abs() < 0.05 { 0.0 } else { v };
        format!("{v:+.1}")
    };
    format!("ωx {}  ωy {}  ωz {} rad/s", signed(w.x), signed(w.y), signed(w.z))
}

/// °, the die's lean from the vertical: the angle between the vertical and the line from
/// its lowest corner up through its centre of mass. A die on a corner (a top) leans by its
/// long diagonal's tilt, 0° upright; flat on a face it reads 54.7° (a corner's diagonal).
pub(crate) fn lean_deg(die: &DieState) -> f64 {
    let lowest = die
        .corners
        .iter()
        .min_by(|a, b| a.z.total_cmp(&b.z))
        .copied()
        .unwrap_or(die.centre);
    let up = die.centre - lowest;
    let n = up.norm();
    if n <= 0.0 {
        return 0.0;
    }
    (up.z / n).clamp(-1.0, 1.0).acos().to_degrees()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plot_key_walks_every_quantity_and_back_to_the_energy_plot() {
        let mut p = PlotChoice::default();
        let mut seen = Vec::new();
        for _ in 0..=QUANTITY_COUNT {
            p.next();
            seen.push(p.quantity);
        }
        assert_eq!(seen.last(), Some(&None));
        assert_eq!(
            seen[..QUANTITY_COUNT],
            (0..QUANTITY_COUNT).map(Some).collect::<Vec<_>>()
        );
        // The phase plot: up is never the quantity across.
        p.quantity = Some(HEIGHT);
        p.toggle_phase();
        assert_eq!(p.phase, Some(SPEED));
        for _ in 0..2 * QUANTITY_COUNT {
            p.next();
            assert_ne!(p.phase, Some(HEIGHT));
            assert_eq!(p.quantity, Some(HEIGHT));
        }
        p.toggle_phase();
        assert_eq!(p.phase, None);
    }
}
