//! The literature's statements about predictability (Nagler & Richter 2008; Kapitaniak et
//! al. 2012), reproduced with this model on seeded experiments: a start beside its ε-twins.

use dicesim_experiment::predict::{PredictSpec, Prediction, run_prediction};
use dicesim_experiment::{RandomRanges, RunOptions, ScanKey};
use dicesim_physics::{InitialCondition, Params};
use std::sync::atomic::AtomicBool;

/// A gentle throw from any orientation: ±20 cm/s, ±10 rad/s.
fn ranges() -> RandomRanges {
    RandomRanges {
        seed: 1,
        velocity: [-20.0, 20.0],
        angular_velocity: [-10.0, 10.0],
        random_orientation: true,
        ..RandomRanges::default()
    }
}

fn predict(key: &str, values: &[f64]) -> Prediction {
    let spec = PredictSpec {
        epsilons: vec![1e-11, 1e-9, 1e-7, 1e-5, 1e-3, 1e-1],
        count: 200,
        seed: 1,
        sweep: Some((ScanKey::named(key).unwrap().clone(), values.to_vec())),
    };
    let p = run_prediction(
        &Params::default(),
        &ranges(),
        &InitialCondition::default(),
        &spec,
        &RunOptions::default(),
        &AtomicBool::new(false),
        &mut |_| {},
    )
    .unwrap();
    assert!(!p.cancelled);
    p
}

/// ε½ of each curve (a bound counts as its value: "above 0.1" is at least 0.1).
fn thresholds(p: &Prediction) -> Vec<f64> {
    p.curves.iter().map(|c| c.threshold.unwrap().value()).collect()
}

#[test]
fn a_lower_drop_is_predictable_with_a_coarser_knowledge_of_the_throw() {
    let p = predict("initial.height", &[15.0, 5.0, 2.0]);
    let t = thresholds(&p);
    // Orders of magnitude: at least 10× between 15 cm and 2 cm, and growing as it falls.
    assert!(t[2] >= 10.0 * t[0] && t[1] > t[0] && t[2] > t[1], "ε½ {t:?}");
    for c in &p.curves {
        // At the smallest ε the twins agree far more often than chance.
        assert!(c.points[0].interval[0] > c.half, "{:?}", c.points[0]);
    }
}

#[test]
fn a_softer_or_more_damped_table_is_more_predictable() {
    let soft = thresholds(&predict("ground.stiffness", &[500_000.0, 50_000.0]));
    assert!(soft[1] >= 10.0 * soft[0], "ε½ {soft:?}");
    let damped = thresholds(&predict("ground.damping", &[0.005, 0.02]));
    assert!(damped[1] >= 10.0 * damped[0], "ε½ {damped:?}");
}

#[test]
fn the_start_face_is_favoured_at_low_drops_and_not_at_fifteen_centimetres() {
    let p = predict("initial.height", &[2.0, 15.0]);
    let (low, high) = (&p.curves[0], &p.curves[1]);
    // The 95 % interval of the share that kept its start face, against chance (1/6).
    assert!(
        low.start_face_interval[0] > 0.4,
        "2 cm: {:?}",
        low.start_face_interval
    );
    let [a, b] = high.start_face_interval;
    assert!(a < 1.0 / 6.0 && 1.0 / 6.0 < b, "15 cm: {a}–{b}");
}
