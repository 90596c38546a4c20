//! The explorer's parameter list: the registry rows that carry labels, one entry per
//! component, in the rows' list order; how ←/→ step a value.

use dicesim_physics::{ContactLaw, InitialCondition, Limits, ParamError, Params, Solid};
use dicesim_setup::keys::ScanKey;
use dicesim_setup::registry::Nudge;
use std::sync::LazyLock;

/// One tunable value in the explorer's list (a vector's component for vector rows).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Param {
    key: &'static ScanKey,
}

/// Entries are equal when they name the same key.
impl PartialEq for Param {
    fn eq(&self, other: &Param) -> bool {
        std::ptr::eq(self.key, other.key)
    }
}

impl Eq for Param {}

/// Every tunable value, in the order the parameter list shows them.
pub(crate) fn all() -> &'static [Param] {
    static ALL: LazyLock<Vec<Param>> = LazyLock::new(|| {
        let mut list: Vec<Param> = ScanKey::all()
            .iter()
            .filter(|k| !k.spec.labels.is_empty())
            .map(|key| Param { key })
            .collect();
        list.sort_by_key(|p| (p.key.spec.list_position, p.key.component));
        list
    });
    &ALL
}

/// The entries `params`' table and die read, in list order: the list the explorer shows (a
/// key its contact law or its die does not read would show a value that acts on nothing,
/// and setting it is refused): a polyhedral die lists none of the box's sizes, masses and
/// pips ([`dicesim_physics::Die::reads`]).
pub(crate) fn listed(params: &Params) -> &'static [Param] {
    fn read_by(law: ContactLaw, polyhedral: bool) -> Vec<Param> {
        // Every polyhedral die reads the same keys (its kind, height and density).
        let mut die = Params::DEFAULT.die;
        if polyhedral {
            die.kind = Solid::D20;
        }
        all()
            .iter()
            .copied()
            .filter(|p| p.key.spec.law.is_none_or(|l| l == law) && die.reads(p.key.spec.key()))
            .collect()
    }
    static LISTS: LazyLock<[Vec<Param>; 4]> = LazyLock::new(|| {
        [
            read_by(ContactLaw::Paper, false),
            read_by(ContactLaw::SpringFriction, false),
            read_by(ContactLaw::Paper, true),
            read_by(ContactLaw::SpringFriction, true),
        ]
    });
    let law = match params.ground.contact {
        ContactLaw::Paper => 0,
        ContactLaw::SpringFriction => 1,
    };
    &LISTS[law + 2 * usize::from(params.die.is_polyhedral())]
}

/// How many entries of the list are the paper's own values: all but a real die's shape
/// beyond the paper's one half size (the other two half sizes, the corner radius and the
/// pips), a loaded die's extra corner masses and the keys only another contact law reads.
/// The layout gives the list this many rows when there is room; the rest scroll into view.
pub(crate) fn paper_rows() -> usize {
    use dicesim_setup::registry::{CORNER_RADIUS, EXTRA_CORNER_MASS, HALF_SIZES, PIP_DEPTH, PIP_DIAMETER};
    all()
        .iter()
        .filter(|p| {
            let spec = p.key.spec;
            !(spec.law.is_some_and(|law| law != ContactLaw::Paper)
                || spec == &EXTRA_CORNER_MASS
                || spec == &CORNER_RADIUS
                || spec == &PIP_DIAMETER
                || spec == &PIP_DEPTH
                || spec == &HALF_SIZES && p.key.component > 0)
        })
        .count()
}

impl Param {
    /// The listed value with this key (`initial.angular_velocity.x`).
    ///
    /// # Panics
    /// If the key is not in the explorer's list: callers name fixed keys.
    pub(crate) fn named(key: &str) -> Param {
        *all()
            .iter()
            .find(|p| p.key.key == key)
            .unwrap_or_else(|| panic!("`{key}` is not in the explorer's parameter list"))
    }

    /// The entry of a key from the list (a map axis names its value by scan key).
    pub(crate) fn of(key: &'static ScanKey) -> Param {
        Param { key }
    }

    /// Short label for the list, in the model's words (the words figures use too).
    pub(crate) fn label(self) -> &'static str {
        self.key.words()
    }

    /// The scan key that reads and writes this value.
    pub(crate) fn scan_key(self) -> &'static ScanKey {
        self.key
    }

    /// The preset key of this value, as `--set` takes it (`initial.velocity.x` names a component).
    pub(crate) fn key(self) -> &'static str {
        &self.key.key
    }

    pub(crate) fn limits(self) -> Limits {
        self.key.limits()
    }

    /// Ground values act on the running roll at once; every other value defines a new roll.
    pub(crate) fn acts_mid_roll(self) -> bool {
        self.key.spec.acts_mid_roll
    }

    pub(crate) fn get(self, params: &Params, initial: &InitialCondition) -> f64 {
        self.key.get(params, initial)
    }

    /// Sets the value after checking it against its range; on error nothing changes.
    pub(crate) fn set(
        self,
        params: &mut Params,
        initial: &mut InitialCondition,
        value: f64,
    ) -> Result<(), ParamError> {
        self.key.set_checked(params, initial, value)
    }

    /// The value one step up (`steps > 0`) or down from `value`, kept inside the range.
    ///
    /// Additive steps land on multiples of the step, so repeated presses give round numbers.
    pub(crate) fn nudged(self, value: f64, steps: i32, coarse: bool) -> f64 {
        let nudge = self.key.spec.nudge.expect("listed values have a step");
        let next = match nudge {
            Nudge::Add { fine, coarse: big } => {
                let step = if coarse { big } else { fine };
                let n = (value / step).round() + steps as f64;
                // Round away representation noise such as 0.30000000000000004.
                let v = n * step;
                (v * 1e9).round() / 1e9
            }
            Nudge::Times { fine, coarse: big } => {
                let factor: f64 = if coarse { big } else { fine };
                let v = value * factor.powi(steps);
                let digits = 10f64.powf(v.abs().log10().floor() - 2.0);
                (v / digits).round() * digits
            }
        };
        let limits = self.limits();
        if next.is_finite() {
            next.clamp(limits.min, limits.max)
        } else {
            value
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each law's list holds every value it reads and none it refuses: the paper's table
    /// has γ and no restitution, the spring-friction table the reverse; both share the die,
    /// the start and the step, in the one list order.
    #[test]
    fn the_list_shows_what_the_contact_law_reads() {
        for law in [ContactLaw::Paper, ContactLaw::SpringFriction] {
            let mut params = Params::default();
            params.ground.contact = law;
            let listed = listed(&params);
            for &p in all() {
                let shown = listed.contains(&p);
                assert_eq!(shown, params.ground.reads(p.key()), "{law:?}: {}", p.key());
                assert_eq!(
                    shown,
                    params.ground.refusal(p.key()).is_none(),
                    "{law:?}: {}",
                    p.key()
                );
            }
            let order: Vec<usize> = listed
                .iter()
                .map(|p| all().iter().position(|q| q == p).unwrap())
                .collect();
            assert!(order.is_sorted(), "{law:?}");
        }
        let named = |law, key| {
            let mut params = Params::default();
            params.ground.contact = law;
            listed(&params).contains(&Param::named(key))
        };
        assert!(
            named(ContactLaw::Paper, "ground.damping") && !named(ContactLaw::Paper, "ground.restitution")
        );
        assert!(!named(ContactLaw::SpringFriction, "ground.damping"));
        assert!(
            named(ContactLaw::SpringFriction, "ground.restitution")
                && named(ContactLaw::SpringFriction, "ground.tilt")
        );
        assert!(
            named(ContactLaw::SpringFriction, "die.half_sizes.x")
                && named(ContactLaw::SpringFriction, "integrator.dt")
        );
    }

    /// A polyhedral die's list holds none of the box's keys (half sizes, corner radius and
    /// mass, pips, extra masses), every other key the box's list holds, and whatever it
    /// lists its die reads (and is not refused).
    #[test]
    fn a_polyhedral_die_lists_only_the_keys_it_reads() {
        for kind in Solid::ALL.into_iter().filter(|&k| k != Solid::Box) {
            let mut params = Params::default();
            params.die.kind = kind;
            let shown = listed(&params);
            for &p in all() {
                let spec_key = p.key.spec.key();
                let reads = params.die.reads(spec_key) && params.ground.reads(p.key());
                assert_eq!(shown.contains(&p), reads, "{kind:?}: {}", p.key());
                assert_eq!(
                    reads,
                    params.die.refusal(spec_key).is_none() && params.ground.reads(p.key())
                );
            }
            for key in [
                "die.half_sizes.x",
                "die.corner_mass",
                "die.corner_radius",
                "die.pip_diameter",
            ] {
                assert!(!shown.contains(&Param::named(key)), "{kind:?} lists {key}");
            }
            let the_box = listed(&Params::default());
            assert!(the_box.contains(&Param::named("die.half_sizes.x")));
            assert_eq!(
                shown.len()
                    + the_box
                        .iter()
                        .filter(|p| !params.die.reads(p.key.spec.key()))
                        .count(),
                the_box.len(),
                "{kind:?}: the box's other rows all stay"
            );
        }
    }

    #[test]
    fn every_value_round_trips_through_set_and_get() {
        for &p in all() {
            let mut params = Params::default();
            // Drilled pips (the rounded die's, 3 mm wide and 1 mm deep), so that the pip depth
            // has room to move: on the paper's die, without pips, it must stay 0.
            params.die.pip_diameter = 0.3;
            params.die.pip_depth = 0.1;
            // A key is set under the contact law that reads it.
            params.ground.contact = p.key.spec.law.unwrap_or(params.ground.contact);
            let mut initial = InitialCondition::default();
            let l = p.limits();
            // A step from the default: in range, and a body the others allow (a quarter of
            // the corner radius's range is past the paper's half size).
            let start = p.get(&params, &initial);
            let mut v = p.nudged(start, 1, false);
            if v == start {
                v = p.nudged(start, -1, false);
            }
            assert_ne!(v, start, "{p:?} moves");
            p.set(&mut params, &mut initial, v).unwrap();
            assert_eq!(p.get(&params, &initial), v, "{p:?}");
            assert!(p.set(&mut params, &mut initial, l.max * 2.0 + 1.0).is_err());
            assert_eq!(
                p.get(&params, &initial),
                v,
                "a refused value leaves {p:?} unchanged"
            );
        }
    }

    #[test]
    fn the_list_keeps_its_order_and_labels() {
        let labels: Vec<&str> = all().iter().map(|p| p.label()).collect();
        assert_eq!(
            labels,
            [
                "stiffness k",
                "damping γ",
                "friction μ",
                "drop height",
                "spin ωx",
                "spin ωy",
                "spin ωz",
                "velocity vx",
                "velocity vy",
                "velocity vz",
                "yaw",
                "pitch",
                "roll",
                "time step Δt",
                "gravity g",
                "corner mass m",
                "half size x",
                "half size y",
                "half size z",
                "corner radius r",
                "pip diameter",
                "pip depth",
                "extra mass 1",
                "extra mass 2",
                "extra mass 3",
                "extra mass 4",
                "extra mass 5",
                "extra mass 6",
                "extra mass 7",
                "extra mass 8",
                "restitution e",
                "static friction μs",
                "tangential k_t/k",
                "table tilt",
                "tilt direction",
            ]
        );
        // The paper's values: the table's three, the drop height, spin, velocity and
        // orientation by three each, Δt, g, the half size and the corner mass.
        assert_eq!(paper_rows(), 3 + 1 + 3 * 3 + 2 + 2);
        assert_eq!(all()[6].key(), "initial.angular_velocity.z");
        assert_eq!(all()[11].key(), "initial.orientation.pitch");
        let mut params = Params::default();
        let mut initial = InitialCondition::default();
        let e = Param::named("initial.velocity.y")
            .set(&mut params, &mut initial, 1e9)
            .unwrap_err();
        assert_eq!(e.key, "initial.velocity.y");
    }

    #[test]
    fn spin_stated_as_momentum_is_shown_and_edited_as_velocity() {
        let params = Params::default();
        let mut initial = InitialCondition {
            angular_momentum: Some([16.0 / 3.0 * 2.0, 0.0, 0.0]),
            ..Default::default()
        };
        assert_eq!(
            Param::named("initial.angular_velocity.x").get(&params, &initial),
            2.0
        );
        Param::named("initial.angular_velocity.y")
            .set(&mut params.clone(), &mut initial, 5.0)
            .unwrap();
        assert_eq!(initial.angular_momentum, None);
        assert_eq!(initial.angular_velocity, [2.0, 5.0, 0.0]);
    }

    #[test]
    fn nudges_step_and_stay_in_range() {
        use dicesim_setup::registry::{DAMPING, DT, FRICTION};
        let friction = Param::named("ground.friction");
        let stiffness = Param::named("ground.stiffness");
        assert_eq!(friction.nudged(1.2, 1, false), 1.25);
        assert_eq!(friction.nudged(1.2, -1, true), 0.5);
        assert_eq!(friction.nudged(0.1, -1, true), 0.0);
        assert_eq!(friction.nudged(4.9, 3, true), FRICTION.limits.max);
        assert_eq!(stiffness.nudged(500_000.0, 1, true), 1_000_000.0);
        assert_eq!(stiffness.nudged(500_000.0, 1, false), 550_000.0);
        assert_eq!(
            Param::named("integrator.dt").nudged(DT.limits.max, 1, true),
            DT.limits.max
        );
        assert_eq!(
            Param::named("ground.damping").nudged(0.1, 1, false),
            DAMPING.limits.max
        );
    }
}
