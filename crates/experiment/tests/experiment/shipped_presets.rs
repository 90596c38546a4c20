//! The shipped presets do what their descriptions say: each loads, rolls and settles; the
//! paper's die tumbles through every face; the slow-motion wheel stays in its plane; the soft,
//! icy and sticky tables and the edge of stability behave as described; the loaded corner
//! shows the bias it states; the sleeping top, the superball and the incline show what the
//! spring-friction table does that the paper's cannot; the bubble in `d20-bubble` brings its
//! face up, and `thick-coin` lands on its faces alike and on its edge a fair share.

use dicesim_experiment::roll_record;
use dicesim_physics::lanes::roll_one;
use dicesim_physics::{ContactLaw, InitialCondition, Outcome, Params, Simulation, StabilityCheck, Status};
use dicesim_setup::preset::{FORMAT, Preset, SHIPPED, Source, Store};
use dicesim_setup::random::RandomDraws;

fn shipped(name: &str) -> Preset {
    let (preset, source) = Store::new(None)
        .load(name)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(source, Source::Shipped);
    preset
}

/// A roll followed step by step.
struct Watched {
    outcome: Outcome,
    sim: Simulation,
    /// The face most nearly up, each time it changes (starting with the first).
    faces: Vec<u8>,
    /// Steps the first contact with the table lasted.
    first_contact_steps: u64,
    /// cm/s, the vertical velocity as the first contact ends.
    first_rebound_speed: f64,
    /// cm, the largest sideways (y) excursion of the centre.
    max_abs_y: f64,
}

fn watch(params: &Params, initial: &InitialCondition) -> Watched {
    let mut sim = Simulation::new(params, initial).unwrap();
    let mut faces = vec![sim.face_up()];
    let (mut contact_start, mut first_contact_steps, mut first_rebound_speed) = (None, 0, f64::NAN);
    let mut max_abs_y: f64 = 0.0;
    let outcome = loop {
        let end = sim.advance();
        let s = sim.state();
        max_abs_y = max_abs_y.max(s.position.y.abs());
        if faces.last() != Some(&sim.face_up()) {
            faces.push(sim.face_up());
        }
        match (contact_start, sim.in_contact()) {
            (None, true) => contact_start = Some(s.step),
            (Some(start), false) if first_contact_steps == 0 => {
                first_contact_steps = s.step - start;
                first_rebound_speed = s.velocity.z;
            }
            _ => {}
        }
        if let Some(o) = end {
            break o;
        }
    };
    Watched {
        outcome,
        sim,
        faces,
        first_contact_steps,
        first_rebound_speed,
        max_abs_y,
    }
}

/// A die dropped flat, without spin or sideways motion, from the preset's height.
fn flat_drop(p: &Preset) -> InitialCondition {
    InitialCondition {
        height: p.initial.height,
        ..InitialCondition::default()
    }
}

/// The preset's `[random]` rolls number 0..n.
fn random_rolls(p: &Preset, n: u64) -> Vec<InitialCondition> {
    (0..n)
        .map(|i| p.random.draw(&p.initial, p.random.seed, i))
        .collect()
}

fn mean(xs: impl IntoIterator<Item = f64>) -> f64 {
    let (sum, n) = xs.into_iter().fold((0.0, 0.0), |(s, n), x| (s + x, n + 1.0));
    sum / n
}

// ---------------------------------------------------------------------------------------------
// The shipped set

/// Presets that show what the paper's model cannot, and end still moving, as their
/// descriptions say: the sleeping top spins until its time is up, the superball rolls away.
const STILL_MOVING_AT_THE_END: [&str; 2] = ["sleeping-top", "superball"];

/// The stability check (docs/model.md, "Stability") passes every shipped preset's throw and
/// its first 2 000 random throws, but for the one preset that is past the limit on purpose,
/// whose own throw it flags. A check that flagged a shipped preset would tell its user the
/// preset's endings are the step's, not the model's.
#[test]
fn the_stability_check_passes_every_shipped_preset_but_the_one_past_its_limit() {
    for (name, _) in SHIPPED {
        let p = shipped(name);
        let check = StabilityCheck::new(&p.params());
        let flagged = std::iter::once(p.initial)
            .chain(random_rolls(&p, 2000))
            .filter(|ic| !check.predict(ic).is_stable())
            .count();
        if *name == "on-the-edge-of-stability" {
            assert!(!check.predict(&p.initial).is_stable(), "{name}");
        } else {
            assert_eq!(flagged, 0, "{name}: {}", check.predict(&p.initial).verdict());
        }
    }
}

#[test]
fn every_shipped_preset_loads_rolls_and_settles() {
    for (name, _) in SHIPPED {
        let p = shipped(name);
        assert_eq!(p.name, *name);
        assert_eq!(p.format, FORMAT);
        assert!(
            p.description.split_whitespace().count() >= 30,
            "{name}: a teacher reads this aloud"
        );
        p.validate().unwrap();
        let params = p.params();
        assert!(params.stability_number() < 2.0, "{name}");
        let outcome = if params.die.is_polyhedral() {
            // The single roll refuses a polyhedral die, naming its key; the engines roll it.
            let refused = Simulation::new(&params, &p.initial).unwrap_err();
            assert_eq!(refused.key, "die.kind", "{name}");
            roll_one(&params, &p.initial, &|| false).expect("never stopped").0
        } else {
            Simulation::new(&params, &p.initial).unwrap().run_to_end()
        };
        if STILL_MOVING_AT_THE_END.contains(name) {
            assert_eq!(outcome.status, Status::Timeout, "{name}: {outcome:?}");
            continue;
        }
        assert_eq!(outcome.status, Status::Settled, "{name}: {outcome:?}");
        assert!(
            params.die.face_numbers().contains(&outcome.face.unwrap()),
            "{name}: {outcome:?}"
        );
        // The die at least fell to the table (the box's corners reach √3 cm below the centre,
        // a polyhedral die's vertices their circumradius).
        let reach = params.polyhedral_die().map_or(3f64.sqrt(), |die| {
            die.contact_points()
                .iter()
                .map(|c| c.offset.norm())
                .fold(0.0, f64::max)
        });
        let fall = (p.initial.height - reach).max(0.0);
        assert!(
            outcome.time_s >= (2.0 * fall / params.world.gravity).sqrt(),
            "{name}"
        );
    }
}

#[test]
fn paper_has_the_papers_constants_and_a_lively_first_roll() {
    let p = shipped("paper");
    assert_eq!(p.params(), Params::default());
    let w = watch(&p.params(), &p.initial);
    let mut seen = w.faces.clone();
    seen.sort();
    seen.dedup();
    assert_eq!(
        seen,
        [1, 2, 3, 4, 5, 6],
        "it tumbles through every face: {:?}",
        w.faces
    );
    assert_ne!(
        w.outcome.face,
        Some(w.faces[0]),
        "it ends on another face than it started"
    );
}

#[test]
fn slow_motion_classroom_rolls_like_a_wheel_and_never_shows_2_or_5() {
    let p = shipped("slow-motion-classroom");
    // A spin about y alone, a push along x: the motion stays in the x–z plane.
    assert_eq!(
        [p.initial.angular_velocity[0], p.initial.angular_velocity[2]],
        [0.0, 0.0]
    );
    assert_eq!(p.initial.velocity[1], 0.0);
    let w = watch(&p.params(), &p.initial);
    assert!(w.max_abs_y < 1e-9, "it left its plane by {} cm", w.max_abs_y);
    assert!(w.faces.iter().all(|f| [1, 3, 4, 6].contains(f)), "{:?}", w.faces);
    assert!([1, 3, 4, 6].contains(&w.outcome.face.unwrap()));
    for f in [1, 3, 4, 6] {
        assert!(w.faces.contains(&f), "it rolls over fully: {:?}", w.faces);
    }
}

#[test]
fn gentle_drop_keeps_the_start_face_and_height_is_what_randomises() {
    let p = shipped("gentle-drop");
    let params = p.params();
    let first = roll_record(&params, &p.initial, 0);
    assert_ne!(p.initial.orientation, [0.0; 3], "it starts tilted");
    assert_eq!(first.outcome.face, Some(first.start_face));

    assert!(p.random.random_orientation);
    let rolls = random_rolls(&p, 40);
    let starts: Vec<u8> = rolls
        .iter()
        .map(|ic| roll_record(&params, ic, 0).start_face)
        .collect();
    assert!(
        starts.iter().any(|&f| f != starts[0]),
        "the random tilts start on different faces"
    );
    for (i, ic) in rolls.iter().enumerate() {
        let r = roll_record(&params, ic, i as u64);
        assert_eq!(r.outcome.status, Status::Settled);
        assert_eq!(r.outcome.face, Some(r.start_face), "roll {i}: {ic:?}");
    }
    // The same throws from the paper's 15 cm mostly end elsewhere.
    let kept_from_high = rolls
        .iter()
        .map(|ic| roll_record(&params, &InitialCondition { height: 15.0, ..*ic }, 0))
        .filter(|r| r.outcome.face == Some(r.start_face))
        .count();
    assert!(
        kept_from_high < rolls.len() / 2,
        "{kept_from_high} of {} kept",
        rolls.len()
    );
}

#[test]
fn soft_table_sinks_ten_times_deeper_and_impacts_last_longer() {
    let p = shipped("soft-table");
    let params = p.params();
    let paper = Params::default();
    assert_eq!(params.ground.stiffness * 10.0, paper.ground.stiffness);
    assert_eq!(params.ground.damping, paper.ground.damping);

    // At rest (stepped on well past the end of the roll) each corner sinks M·g/(4k).
    let mut w = watch(&params, &p.initial);
    for _ in 0..3000 {
        w.sim.step();
    }
    let mut depths = w.sim.state().corner_depths;
    depths.sort_by(|a, b| b.total_cmp(a));
    let depth = mean(depths[..4].iter().copied());
    assert!(
        (depth / params.resting_depth() - 1.0).abs() < 0.05,
        "{depth} cm vs {} cm",
        params.resting_depth()
    );
    assert!((params.resting_depth() / paper.resting_depth() - 10.0).abs() < 1e-9);

    // A flat drop: contact lasts about √10 ≈ 3.2 times longer, the rebound is about as fast.
    let soft = watch(&params, &flat_drop(&p));
    let hard = watch(&paper, &flat_drop(&p));
    let ratio = soft.first_contact_steps as f64 / hard.first_contact_steps as f64;
    assert!((2.5..4.0).contains(&ratio), "contact {ratio} times longer");
    let rebound = soft.first_rebound_speed / hard.first_rebound_speed;
    assert!((0.8..1.25).contains(&rebound), "rebound ratio {rebound}");
}

#[test]
fn icy_table_slides_like_a_curling_stone_where_the_paper_table_trips_it() {
    let p = shipped("icy-table");
    let icy = p.params();
    assert!((icy.ground.friction * 12.0 - Params::default().ground.friction).abs() < 1e-12);
    assert_eq!(p.initial.angular_velocity, [0.0; 3]);

    let w = watch(&icy, &p.initial);
    assert_eq!(w.faces, [4], "the same face stays up all the way");
    assert_eq!(w.outcome.face, Some(4));
    // Sliding flat it decelerates at μ·g: the distance is (v₀² − v²)/(2μg).
    let s = w.sim.state();
    let (v0, v) = (p.initial.velocity[0], s.velocity.xy().norm());
    assert!(v > 10.0, "still gliding at the end: {v} cm/s");
    let expected = (v0 * v0 - v * v) / (2.0 * icy.ground.friction * icy.world.gravity);
    let travelled = s.position.xy().norm();
    assert!(
        (travelled / expected - 1.0).abs() < 0.03,
        "{travelled} cm vs {expected} cm"
    );

    let mut grippy = icy;
    grippy.ground.friction = Params::default().ground.friction;
    let tripped = watch(&grippy, &p.initial);
    assert!(
        tripped.faces.len() >= 3,
        "the paper's friction trips it: {:?}",
        tripped.faces
    );
}

#[test]
fn sticky_table_bounces_lower_tumbles_less_and_settles_sooner() {
    let p = shipped("sticky-table");
    let sticky = p.params();
    assert_eq!(sticky.ground.damping, 4.0 * Params::default().ground.damping);
    let mut lively = sticky;
    lively.ground.damping = Params::default().ground.damping;

    let drop = flat_drop(&p);
    let (a, b) = (watch(&sticky, &drop), watch(&lively, &drop));
    assert!(a.first_rebound_speed > 0.0 && a.first_rebound_speed < 0.8 * b.first_rebound_speed);

    let throws: Vec<InitialCondition> = std::iter::once(p.initial).chain(random_rolls(&p, 11)).collect();
    let (s, l): (Vec<Watched>, Vec<Watched>) = throws
        .iter()
        .map(|ic| (watch(&sticky, ic), watch(&lively, ic)))
        .unzip();
    let steps = |ws: &[Watched]| mean(ws.iter().map(|w| w.outcome.steps as f64));
    let turns = |ws: &[Watched]| mean(ws.iter().map(|w| (w.faces.len() - 1) as f64));
    assert!(steps(&s) < steps(&l), "{} vs {} steps", steps(&s), steps(&l));
    assert!(
        turns(&s) < turns(&l),
        "{} vs {} face changes",
        turns(&s),
        turns(&l)
    );
}

#[test]
fn on_the_edge_of_stability_settles_though_many_throws_do_not() {
    let p = shipped("on-the-edge-of-stability");
    let params = p.params();
    let number = params.stability_number();
    assert!((1.4..1.6).contains(&number), "ω_rock·Δt = {number}");
    // "each step shorter than about a third of one rock": 2/ω_rock of the period 2π/ω_rock.
    assert!((params.integrator.dt / Params::default().integrator.dt - 2.4).abs() < 1e-12);
    let paper = shipped("paper");
    assert_eq!(p.initial, paper.initial, "the paper's throw");
    let mut same_but_dt = params;
    same_but_dt.integrator.dt = paper.params().integrator.dt;
    assert_eq!(same_but_dt, paper.params());

    let (o, _) = dicesim_physics::roll(&params, &p.initial).unwrap();
    assert_eq!(o.status, Status::Settled);

    let unstable: Vec<InitialCondition> = random_rolls(&p, 30)
        .into_iter()
        .filter(|ic| roll_record(&params, ic, 0).outcome.status == Status::Unstable)
        .collect();
    assert!(unstable.len() >= 2, "only {} of 30 unstable", unstable.len());
    for ic in &unstable {
        let r = roll_record(&same_but_dt, ic, 0);
        assert_eq!(r.outcome.status, Status::Settled, "{ic:?}");
    }
}

/// The number just before `marker` in `text` (`"44 % of the time"` → 44).
fn number_before(text: &str, marker: &str) -> f64 {
    let at = text
        .find(marker)
        .unwrap_or_else(|| panic!("`{marker}` in {text:?}"));
    let digits: String = text[..at]
        .trim_end()
        .chars()
        .rev()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
        .collect();
    digits
        .parse()
        .unwrap_or_else(|_| panic!("a number before `{marker}`"))
}

#[test]
fn loaded_corner_shows_the_bias_and_the_rolls_a_class_needs_that_it_states() {
    use dicesim_experiment::{Rolls, RunOptions, stream_batch};
    let p = shipped("loaded-corner");
    let params = p.params();
    assert!(params.die.is_loaded());
    let stated_share = number_before(&p.description, "% of the time together") / 100.0;
    let stated_rolls = number_before(&p.description, "rolls before");
    let rolls = Rolls::Random {
        ranges: &p.random,
        base: &p.initial,
        seed: p.random.seed,
        first: 0,
        count: 4000,
    };
    let run = stream_batch(
        &params,
        &rolls,
        &RunOptions::default(),
        &std::sync::atomic::AtomicBool::new(false),
        &mut |_| Ok(()),
    )
    .unwrap();
    let s = run.summary;
    assert_eq!(s.status.settled, 4000);
    let c = &s.faces.counts;
    let heavy = (c[3] + c[4] + c[5]) as f64 / s.faces.total() as f64;
    // 4000 rolls measure a share to ±0.8 points (one standard error).
    assert!(
        (heavy - stated_share).abs() < 0.025,
        "faces 4–6 came up {heavy}, the description says {stated_share}"
    );
    // And the rolls the test needs to ±20 % (the measured bias's own error at 4000 rolls).
    let needed = s.rolls_to_detect.expect("a bias is measured") as f64;
    assert!(
        (0.7..1.4).contains(&(needed / stated_rolls)),
        "{needed} rolls needed, the description says {stated_rolls}"
    );
}

// ---------------------------------------------------------------------------------------------
// The spring-friction table (docs/model.md, "The spring-friction contact")

/// Degrees between the cube's long diagonal (corner 1 to corner 8) and the vertical.
fn diagonal_lean(sim: &Simulation) -> f64 {
    let r = &sim.state().corner_offsets;
    (r[7] - r[0]).normalize().z.acos().to_degrees()
}

/// Steps `sim` for `seconds`; the largest lean and when a second corner first touched.
fn spin_on_its_tip(sim: &mut Simulation, seconds: f64) -> (f64, Option<f64>) {
    let steps = (seconds / sim.params().integrator.dt).round() as u64;
    let (mut widest, mut second): (f64, Option<f64>) = (0.0, None);
    for _ in 0..steps {
        sim.step();
        widest = widest.max(diagonal_lean(sim));
        let s = sim.state();
        if second.is_none() && (1..8).any(|k| s.corner_depths[k] > 0.0) {
            second = Some(s.time_s);
        }
    }
    (widest, second)
}

#[test]
fn sleeping_top_spins_upright_above_the_critical_rate_and_topples_below_it() {
    let p = shipped("sleeping-top");
    let params = p.params();
    assert_eq!(params.ground.contact, ContactLaw::SpringFriction);
    // ω_c = 2·√(M·g·l·I₁)/I₃ about the tip, l = a·√3, I₁ = I + M·l², I₃ = I.
    let (mass, a, g, i3) = (
        params.total_mass(),
        params.die.half_size(),
        params.world.gravity,
        params.inertia(),
    );
    let l = a * 3f64.sqrt();
    let critical = 2.0 * (mass * g * l * (i3 + mass * l * l)).sqrt() / i3;
    let spin = nalgebra::Vector3::from(p.initial.angular_velocity);
    assert!((spin.norm() / critical - 1.2).abs() < 1e-6, "it spins at 1.2 ω_c");
    let mut sim = Simulation::new(&params, &p.initial).unwrap();
    assert!(
        (diagonal_lean(&sim) - 1.0).abs() < 1e-6,
        "the diagonal starts 1° off"
    );
    assert!(
        spin.normalize()
            .dot(&(sim.state().corner_offsets[7] - sim.state().corner_offsets[0]).normalize())
            > 1.0 - 1e-12
    );
    // Upright for the whole roll, which ends with the time as it spins.
    let (widest, second) = spin_on_its_tip(&mut sim, params.integrator.max_time);
    assert!(widest < 5.0, "it leaned {widest}°");
    assert_eq!(second, None);
    // The spin about z lowered to 200, as the description says: it topples within a second.
    let slower = InitialCondition {
        angular_velocity: [p.initial.angular_velocity[0], 0.0, 200.0],
        ..p.initial
    };
    let (_, second) = spin_on_its_tip(&mut Simulation::new(&params, &slower).unwrap(), 1.0);
    assert!(second.is_some(), "at 200 rad/s it topples");
    // On the paper's table the tip is held almost as well, as the description admits.
    let mut paper = params;
    paper.ground.contact = ContactLaw::Paper;
    let (widest, second) = spin_on_its_tip(&mut Simulation::new(&paper, &p.initial).unwrap(), 2.0);
    assert!(
        widest < 5.0 && second.is_none(),
        "paper table: leaned {widest}°, {second:?}"
    );
}

/// The ball's horizontal velocity and spin about y as each contact ends (cm/s, rad/s).
fn bounces(params: &Params, initial: &InitialCondition, count: usize) -> Vec<(f64, f64)> {
    let mut sim = Simulation::new(params, initial).unwrap();
    let (mut out, mut touching) = (Vec::new(), false);
    while out.len() < count {
        sim.step();
        if touching && !sim.in_contact() {
            out.push((sim.state().velocity.x, sim.angular_velocity().y));
        }
        touching = sim.in_contact();
    }
    out
}

#[test]
fn superball_bounces_back_with_its_spin_reversed_where_the_paper_table_cannot() {
    let p = shipped("superball");
    let params = p.params();
    let [vx, _, _] = p.initial.velocity;
    let wy = p.initial.angular_velocity[1];
    assert!(vx > 0.0 && wy < 0.0, "thrown forward with backspin");
    let hops = bounces(&params, &p.initial, 4);
    // Each bounce reverses both: backwards and spinning forwards, then forwards and back.
    for (i, &(v, w)) in hops.iter().enumerate() {
        let sign = if i % 2 == 0 { -1.0 } else { 1.0 };
        assert!(v * sign > 0.0 && w * sign < 0.0, "bounce {}: v {v}, ω {w}", i + 1);
    }
    let mut sim = Simulation::new(&params, &p.initial).unwrap();
    let outcome = sim.run_to_end();
    assert_eq!(outcome.status, Status::Timeout);
    let rolling = sim.state().velocity.x - params.die.half_size() * sim.angular_velocity().y;
    assert!(
        rolling.abs() < 0.5,
        "it rolls away at the end: slip {rolling} cm/s"
    );
    // The paper's table only slows the slip: the ball goes on forwards, spinning forwards.
    let mut paper = params;
    paper.ground = dicesim_physics::Ground {
        contact: ContactLaw::Paper,
        restitution: Params::default().ground.restitution,
        ..paper.ground
    };
    let (v, w) = bounces(&paper, &p.initial, 1)[0];
    assert!(v > 0.0 && w > 0.0, "paper table: v {v}, ω {w}");
}

#[test]
fn incline_holds_the_die_below_the_friction_angle_and_slides_it_above() {
    let p = shipped("incline");
    let params = p.params();
    let g = &params.ground;
    assert!(
        g.tilt.to_radians().tan() < g.friction,
        "25° is below both coefficients"
    );
    assert!(
        (g.static_friction.atan().to_degrees() - 31.0).abs() < 0.1,
        "the friction angle, 31°"
    );
    let mut sim = Simulation::new(&params, &p.initial).unwrap();
    let outcome = sim.run_to_end();
    assert_eq!((outcome.status, outcome.face), (Status::Settled, Some(4)));
    // It slides a few centimetres, stops and holds.
    let steps = (2.0 / params.integrator.dt) as u64;
    for _ in 0..steps {
        sim.step();
    }
    let stopped = sim.state().position.x;
    assert!((1.0..10.0).contains(&stopped), "it stopped {stopped} cm downhill");
    for _ in 0..steps {
        sim.step();
    }
    assert!((sim.state().position.x - stopped).abs() < 0.01, "it holds");
    // Tilted to 35°, as the description says: it slides away at g·(sin θ − μk·cos θ).
    let mut steep = params;
    steep.ground.tilt = 35.0;
    assert!(dicesim_physics::why_it_cannot_settle(&steep).is_some());
    let mut sim = Simulation::new(&steep, &p.initial).unwrap();
    let (mut v1, mut t1) = (0.0, 0.0);
    for n in 0..steps {
        sim.step();
        if n == steps / 4 {
            (v1, t1) = (sim.state().velocity.x, sim.state().time_s);
        }
    }
    let s = sim.state();
    let a = (s.velocity.x - v1) / (s.time_s - t1);
    let theta = 35f64.to_radians();
    let expected = params.world.gravity * (theta.sin() - g.friction * theta.cos());
    assert!((expected - 161.0).abs() < 0.5, "the description's 161 cm/s²");
    assert!((a / expected - 1.0).abs() < 0.01, "a = {a}, expected {expected}");
    assert_eq!(sim.run_to_end().status, Status::Timeout);
}

/// `calibrated-table` (and `calibrated-table-budden`, the table it replaced) is the paper's die
/// and throw on another table: every key but the table's (`ground.*`) and the step that table
/// needs (`integrator.dt`) is the paper's; its description names what it was fitted to and
/// the fit's command; and at that step every body it is meant for steps stably at the worst
/// throw of its ranges — each of Budden's cuboids thrown by hand, the paper's die, and the
/// shaved die cut by 3 % and dropped as Murray's group dropped it.
#[test]
fn calibrated_table_is_the_papers_setup_on_a_fitted_table_that_holds_every_body() {
    use dicesim_experiment::compare_budden::{cuboid, hand_throw};
    use dicesim_experiment::compare_shaved::{cut_die, drop_throw};
    use dicesim_experiment::real_data::budden;
    use dicesim_setup::random::worst_throw_reading;
    let tables: [(&str, &[&str]); 2] = [
        (
            "calibrated-table",
            &[
                "Budden",
                "0.63, 1.16, 1.87",
                "shaved die",
                "seed 1",
                "compare joint",
                "--fit ground.restitution",
            ],
        ),
        (
            "calibrated-table-budden",
            &[
                "Budden",
                "0.63, 1.16, 1.87",
                "seed 1",
                "compare budden --fit ground.restitution",
            ],
        ),
    ];
    let paper = shipped("paper");
    let p = paper.params();
    for (name, words) in tables {
        let table = shipped(name);
        let t = table.params();
        assert_eq!(t.die, p.die, "{name}");
        assert_eq!(t.world, p.world, "{name}");
        assert_eq!(
            dicesim_physics::Integrator {
                dt: p.integrator.dt,
                ..t.integrator
            },
            p.integrator,
            "{name}"
        );
        assert_eq!(
            (table.initial, table.random),
            (paper.initial, paper.random),
            "{name}"
        );
        assert_eq!(t.ground.contact, ContactLaw::SpringFriction, "{name}");
        for w in words {
            assert!(
                table.description.contains(w),
                "{name}: no `{w}` in the description"
            );
        }
        let hand = hand_throw(&table.random);
        for row in budden().0 {
            let body = Params {
                die: cuboid(row.ratio),
                ..t
            };
            let reading = worst_throw_reading(&body, &hand, &table.initial);
            assert!(!reading.exceeded(), "{name}, ratio {}: {reading}", row.ratio);
        }
        let reading = worst_throw_reading(&t, &table.random, &table.initial);
        assert!(!reading.exceeded(), "{name}, the paper's die: {reading}");
        let shaved = Params {
            die: cut_die(&t.die, 0.03),
            ..t
        };
        let reading = worst_throw_reading(&shaved, &drop_throw(1), &table.initial);
        assert!(!reading.exceeded(), "{name}, the shaved die: {reading}");
    }
}

/// The dice presets are the standard 16 mm resin dice of docs/dice.md on the dice' table (the
/// paper's at Δt = 0.25 ms), thrown from any orientation, and a batch of each rolls its own
/// die: every record ends settled on one of its numbers, the counts summing to the rolls.
#[test]
fn the_dice_presets_roll_their_die_on_the_dice_table() {
    use dicesim_experiment::{Rolls, RunOptions, stream_batch};
    use dicesim_physics::Solid;
    for (name, kind) in [
        ("d4", Solid::D4),
        ("d8", Solid::D8),
        ("d10", Solid::D10),
        ("d100", Solid::Percentile),
        ("d12", Solid::D12),
        ("d20", Solid::D20),
    ] {
        let p = shipped(name);
        let params = p.params();
        assert_eq!(params.die.kind, kind, "{name}");
        assert_eq!((params.die.height, params.die.density), (1.6, 1.18), "{name}");
        let paper = Params::default();
        assert_eq!(
            (params.ground, params.world),
            (paper.ground, paper.world),
            "{name}"
        );
        assert_eq!(params.integrator.dt, 0.00025, "{name}");
        assert!(p.random.random_orientation, "{name}");
        const ROLLS: u64 = 40;
        let rolls = Rolls::Random {
            ranges: &p.random,
            base: &p.initial,
            seed: 3,
            first: 0,
            count: ROLLS,
        };
        let mut records = Vec::new();
        stream_batch(
            &params,
            &rolls,
            &RunOptions::default(),
            &std::sync::atomic::AtomicBool::new(false),
            &mut |chunk| {
                records.extend_from_slice(chunk);
                Ok(())
            },
        )
        .unwrap();
        assert_eq!(records.len() as u64, ROLLS, "{name}");
        let numbers = params.die.face_numbers();
        for r in &records {
            assert_eq!(r.outcome.status, Status::Settled, "{name}: {r:?}");
            assert!(numbers.contains(&r.outcome.face.unwrap()), "{name}: {r:?}");
            assert!(numbers.contains(&r.start_face), "{name}: {r:?}");
            assert!(r.outcome.impacts >= 1, "{name}: {r:?}");
        }
        // Rolled by the engines alike: the same records as one roll at a time.
        for r in records.iter().take(4) {
            let (outcome, start_face) = roll_one(&params, &r.initial, &|| false).unwrap();
            assert_eq!(
                (outcome.face, outcome.steps, start_face),
                (r.outcome.face, r.outcome.steps, r.start_face)
            );
        }
    }
}

/// `rolls` random rolls of `p` (its `[random]`, seed 3) by a batch: each record's number.
fn batch_faces(p: &Preset, rolls: u64) -> Vec<u8> {
    use dicesim_experiment::{Rolls, RunOptions, stream_batch};
    let params = p.params();
    let spec = Rolls::Random {
        ranges: &p.random,
        base: &p.initial,
        seed: 3,
        first: 0,
        count: rolls,
    };
    let mut faces = Vec::new();
    stream_batch(
        &params,
        &spec,
        &RunOptions::default(),
        &std::sync::atomic::AtomicBool::new(false),
        &mut |chunk| {
            for r in chunk {
                assert_eq!(r.outcome.status, Status::Settled, "{}: {r:?}", p.name);
                faces.push(r.outcome.face.expect("a settled die shows a face"));
            }
            Ok(())
        },
    )
    .unwrap();
    assert_eq!(faces.len() as u64, rolls, "{}", p.name);
    faces
}

/// `T̂ ± SE`: the mean over `faces` of the face up's outward normal along face `toward`'s
/// (docs/model.md, "The bias, rolled"; 0 for a fair die).
fn lean_toward(p: &Preset, faces: &[u8], toward: u32) -> (f64, f64) {
    let die = p.params().polyhedral_die().expect("a polyhedral die");
    let numbers = &die.numbering().numbers;
    let normal = |number: u32| {
        let f = numbers
            .iter()
            .position(|&n| n == number)
            .expect("a face of that number");
        die.shape().faces()[f].normal
    };
    let u = normal(toward);
    let along: Vec<f64> = faces.iter().map(|&n| normal(u32::from(n)).dot(&u)).collect();
    let n = along.len() as f64;
    let t = mean(along.iter().copied());
    let variance = along.iter().map(|x| (x - t) * (x - t)).sum::<f64>() / (n - 1.0);
    (t, (variance / n).sqrt())
}

/// `d20-bubble`: a bubble toward face 20 makes that side light, so the die rests with it up
/// more often (docs/model.md, "Which way a bubble biases the die"): the face up leans toward
/// face 20 by more than two standard errors in 3 000 rolls (the bias is about 0.03, derived
/// `T ≈ 5·s/cm` with the centre's shift `s = 0.0066` cm, docs/dice.md "Flaws").
#[test]
fn d20_bubble_brings_the_face_toward_its_bubble_up() {
    let p = shipped("d20-bubble");
    let f = &p.params().die.flaws;
    assert_eq!(
        (f.bubble_toward, f.bubble_radius, f.bubble_offset),
        (Some(20), 0.2, 0.5)
    );
    let faces = batch_faces(&p, 3000);
    let (t, error) = lean_toward(&p, &faces, 20);
    assert!(t > 2.0 * error, "T = {t} ± {error}");
}

/// `thick-coin`: a convex die of 16 corners, its flat faces 1 and 10 opposite, its eight
/// sides 2 to 9: by its symmetry heads and tails come up alike, each more often than any one
/// side, and it lands on its edge a fair share of the time.
#[test]
fn thick_coin_lands_on_its_faces_alike_and_on_its_edge_a_fair_share() {
    let p = shipped("thick-coin");
    let params = p.params();
    assert_eq!(params.die.kind, dicesim_physics::Solid::Convex);
    assert_eq!(params.die.vertices.points().len(), 16);
    assert_eq!(params.die.face_numbers(), (1..=10).collect::<Vec<u8>>());
    const ROLLS: u64 = 1000;
    let faces = batch_faces(&p, ROLLS);
    let count = |n: u8| faces.iter().filter(|&&f| f == n).count() as f64;
    let (heads, tails) = (count(1), count(10));
    // Equal shares p: their difference has the error √(2·p·ROLLS).
    let share = (heads + tails) / (2.0 * ROLLS as f64);
    assert!(
        (heads - tails).abs() < 3.0 * (2.0 * share * ROLLS as f64).sqrt(),
        "{heads} {tails}"
    );
    for side in 2..=9 {
        assert!(count(side) < heads.min(tails), "side {side}: {}", count(side));
    }
    let edge = 1.0 - (heads + tails) / ROLLS as f64;
    assert!((0.1..0.5).contains(&edge), "on its edge in {edge} of the rolls");
}
