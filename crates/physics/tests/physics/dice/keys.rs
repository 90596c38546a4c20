//! A die as a preset's keys give it (docs/dice.md, "A convex die of its corners" and
//! "Flaws"): a convex die of its corners weighs and rolls as the solid they make, a die of a
//! vertex count the engines do not carry rolls as the next body up with points that never
//! touch, and each flaw key is refused by name when it makes an impossible body.

use super::{dice_table, throw};
use crate::common::state_bits;
use dicesim_physics::lanes::{LaneResult, roll_in_lanes, roll_one_by_one};
use dicesim_physics::params::{DieFlaws, Vertices};
use dicesim_physics::polyhedron::DieKind;
use dicesim_physics::{FrictionLaw, InitialCondition, Params, PointRoll, Solid, Status};
use nalgebra::Vector3;

/// The dice' table with a convex die of `points` (cm) in resin of `density`.
fn convex(points: &[[f64; 3]], density: f64) -> Params {
    let mut p = dice_table();
    p.die.kind = Solid::Convex;
    p.die.vertices = Vertices::new(points).expect("at most 20 corners");
    p.die.density = density;
    p
}

/// The cube of half side `a`, its 8 corners.
fn cube(a: f64) -> Vec<[f64; 3]> {
    let mut v = Vec::new();
    for x in [-a, a] {
        for y in [-a, a] {
            for z in [-a, a] {
                v.push([x, y, z]);
            }
        }
    }
    v
}

/// A right prism on a regular `sides`-gon of circumradius `r`, `h` thick (cm).
fn prism(sides: usize, r: f64, h: f64) -> Vec<[f64; 3]> {
    [0.5, -0.5]
        .into_iter()
        .flat_map(|z| {
            (0..sides).map(move |k| {
                let t = std::f64::consts::TAU * k as f64 / sides as f64;
                [r * t.cos(), r * t.sin(), z * h]
            })
        })
        .collect()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1.0)
}

/// docs/dice.md, "A convex die of its corners": the cube of side 2a in material of density ρ
/// has `M = 8ρa³` and `I = M(2a)²/6` about each axis through its centre; at a = 1 cm, ρ = 1
/// g/cm³ that is the paper's box, `M = 8` g and `I = 16/3` g·cm² (`Params::inertia` of the
/// default, bitwise 16/3).
#[test]
fn a_convex_cube_of_its_eight_corners_weighs_and_turns_as_the_box() {
    let p = convex(&cube(1.0), 1.0);
    p.validate().unwrap();
    let die = p.polyhedral_die().expect("a convex die");
    let props = die.mass_properties();
    assert!(close(props.mass, 8.0), "{}", props.mass);
    assert!(props.centre_of_mass.norm() < 1e-12);
    for i in 0..3 {
        for j in 0..3 {
            let expected = if i == j { 16.0 / 3.0 } else { 0.0 };
            assert!(
                close(props.inertia[(i, j)], expected),
                "I[{i}{j}] = {}",
                props.inertia[(i, j)]
            );
        }
    }
    assert!(close(p.total_mass(), Params::DEFAULT.total_mass()));
    assert!(close(p.inertia(), Params::DEFAULT.inertia()));
    // Six faces in three opposite pairs, each pair summing to 7 as the box's.
    assert_eq!(p.die.face_numbers(), &[1, 2, 3, 4, 5, 6]);
    let n = die.numbering();
    for (f, opposite) in n.opposite.iter().enumerate() {
        let g = opposite.expect("every face of a cube has an opposite");
        assert_eq!(n.numbers[f] + n.numbers[g], 7);
    }
    // Eight corners roll as a body of 12 points.
    assert_eq!(dicesim_physics::polyhedron::body_points(8), Some(12));
}

/// An engine: `roll_in_lanes` or `roll_one_by_one`.
type Engine = fn(
    usize,
    &mut dyn FnMut(usize) -> (Params, InitialCondition),
    &mut dyn FnMut(LaneResult<'_>),
    &dyn Fn() -> bool,
) -> bool;

/// A roll's face, status, steps, time (bits), impacts, start face and end state (bits).
type RollBits = (Option<u8>, Status, u64, u64, u64, u8, Vec<u64>);

/// Everything an engine's results carry, as bits, in the order of `setups`.
fn results(engine: Engine, setups: &[(Params, InitialCondition)]) -> Vec<RollBits> {
    let mut out = vec![None; setups.len()];
    assert!(engine(
        setups.len(),
        &mut |i| setups[i],
        &mut |r| {
            let o = r.outcome;
            out[r.index] = Some((
                o.face,
                o.status,
                o.steps,
                o.time_s.to_bits(),
                o.impacts,
                r.start_face,
                state_bits(r.state),
            ));
        },
        &|| false,
    ));
    out.into_iter().map(|r| r.expect("every roll reported")).collect()
}

/// The d20's corners listed as a convex die make the d20 itself: the same hull (the same
/// list in the same order), numbered the same way (opposite pairs summing to 21), so every
/// throw ends the same, bit for bit.
#[test]
fn a_convex_d20_of_its_corners_rolls_as_the_d20() {
    let corners: Vec<[f64; 3]> = DieKind::D20
        .vertices(1.6)
        .iter()
        .map(|v| [v.x, v.y, v.z])
        .collect();
    let as_convex = convex(&corners, 1.18);
    as_convex.validate().unwrap();
    let mut d20 = dice_table();
    d20.die.kind = Solid::D20;
    assert_eq!(as_convex.die.face_numbers(), d20.die.face_numbers());
    let throws = |p: Params| -> Vec<_> { (0..12).map(|i| (p, throw(51, i))).collect() };
    let convex_rolls = results(roll_in_lanes, &throws(as_convex));
    let d20_rolls = results(roll_in_lanes, &throws(d20));
    assert_eq!(convex_rolls, d20_rolls);
    assert!(convex_rolls.iter().all(|r| r.1 == Status::Settled));
}

/// A die the engines carry padded: a convex cube (8 corners, a body of 12), an octagonal
/// prism (16, a body of 20), a square pyramid (5, a body of 6) and a shaved d10 (14, a body
/// of 20). Each rolls bit for bit alike in both engines, and exactly as the body of its own
/// vertex count alone does (a `PointRoll` of 8, 16, 5 or 14 points): the padding points at
/// the centre of mass never touch, so they change nothing.
#[test]
fn a_padded_die_rolls_alike_in_both_engines_and_as_its_own_points() {
    let pyramid = vec![
        [1.0, 1.0, -0.5],
        [-1.0, 1.0, -0.5],
        [-1.0, -1.0, -0.5],
        [1.0, -1.0, -0.5],
        [0.0, 0.0, 1.0],
    ];
    let mut shaved_d10 = dice_table();
    shaved_d10.die.kind = Solid::D10;
    shaved_d10.die.flaws = DieFlaws {
        shave_face: Some(3),
        shave_depth: 0.05,
        ..DieFlaws::NONE
    };
    let dice = [
        ("cube", convex(&cube(0.8), 1.18), 8),
        ("octagonal prism", convex(&prism(8, 1.2, 0.85), 1.18), 16),
        ("square pyramid", convex(&pyramid, 1.18), 5),
        ("shaved d10", shaved_d10, 14),
    ];
    for (name, p, vertices) in dice {
        p.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
        let die = p.polyhedral_die().expect("a polyhedral die");
        assert_eq!(die.shape().vertices().len(), vertices, "{name}");
        let setups: Vec<_> = (0..8).map(|i| (p, throw(17, i))).collect();
        let scalar = results(roll_one_by_one, &setups);
        let lanes = results(roll_in_lanes, &setups);
        assert_eq!(scalar, lanes, "{name}: the engines differ");
        let numbers = p.die.face_numbers();
        for (i, r) in scalar.iter().enumerate() {
            assert_ne!(r.1, Status::Unstable, "{name} throw {i}");
            if let Some(face) = r.0 {
                assert!(numbers.contains(&face), "{name} throw {i}: face {face}");
            }
        }
        // The same throws of the body of its own points, unpadded.
        let own: Vec<(Option<u8>, Status, u64, u64)> = setups
            .iter()
            .map(|(p, initial)| match vertices {
                8 => own_points::<8>(p, initial),
                16 => own_points::<16>(p, initial),
                5 => own_points::<5>(p, initial),
                14 => own_points::<14>(p, initial),
                n => unreachable!("{n}"),
            })
            .collect();
        let padded: Vec<_> = scalar.iter().map(|r| (r.0, r.1, r.2, r.3)).collect();
        assert_eq!(padded, own, "{name}: padded against its own points");
    }
}

/// One throw of `p`'s die as a body of exactly its `N` vertices: face, status, steps, time.
fn own_points<const N: usize>(p: &Params, initial: &InitialCondition) -> (Option<u8>, Status, u64, u64) {
    let die = p.polyhedral_die().expect("a polyhedral die");
    let body = die.point_body::<N>(p).expect("its own vertex count");
    let mut roll = PointRoll::new(p, &body, initial).expect("a valid throw");
    let o = roll.run_to_end();
    (o.face, o.status, o.steps, o.time_s.to_bits())
}

/// The authors' whole-die friction norm sums over every point, the padding too: refused for a
/// padded die, kept for one the engines carry as it is.
#[test]
fn the_whole_die_norm_is_refused_for_a_padded_die_only() {
    let mut p = convex(&cube(0.8), 1.18);
    p.ground.friction_law = FrictionLaw::WholeDieNorm;
    let e = p.validate().unwrap_err();
    assert_eq!(e.key, "ground.friction_law");
    assert!(
        e.to_string().contains("8 vertices rolls as a body of 12 points"),
        "{e}"
    );
    let mut d20 = dice_table();
    d20.die.kind = Solid::D20;
    d20.ground.friction_law = FrictionLaw::WholeDieNorm;
    d20.validate().unwrap();
}

/// Each corner list that makes no die is refused at the corner at fault, or the list.
#[test]
fn a_list_of_corners_that_is_no_die_is_refused_by_the_corner_at_fault() {
    let refusal = |points: &[[f64; 3]]| convex(points, 1.18).validate().unwrap_err();
    // A point inside the hull of the others: the cube's centre.
    let mut inside = cube(1.0);
    inside.push([0.0, 0.0, 0.0]);
    let e = refusal(&inside);
    assert_eq!(e.key, "die.vertices.9");
    assert!(e.to_string().contains("not a corner of the die"), "{e}");
    // Repeated.
    let mut repeated = cube(1.0);
    repeated.push([1.0, 1.0, 1.0]);
    let e = refusal(&repeated);
    assert_eq!(e.key, "die.vertices.9");
    assert!(e.to_string().contains("same place as vertex 8"), "{e}");
    // Coplanar: a square and its centre's neighbours, all at z = 0.
    let flat = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    let e = refusal(&flat);
    assert_eq!(e.key, "die.vertices");
    assert!(e.to_string().contains("one line or in one plane"), "{e}");
    // None at all.
    let e = refusal(&[]);
    assert_eq!(e.key, "die.vertices");
    assert!(e.to_string().contains("at least 4"), "{e}");
    // Too thin: a slab 0.05 cm thick stands below the least height, 0.1 cm.
    let e = refusal(&prism(4, 1.0, 0.05));
    assert_eq!(e.key, "die.vertices");
    assert!(e.to_string().contains("0.05 cm tall"), "{e}");
    // A coordinate out of range names the corner.
    let mut far = cube(1.0);
    far[2][1] = 12.0;
    let e = refusal(&far);
    assert_eq!(e.key, "die.vertices.3");
    // More faces than a die numbers: a decagonal antiprism's 20 corners make 2 + 20 = 22.
    let antiprism: Vec<[f64; 3]> = (0..20)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / 20.0;
            let z = if k % 2 == 0 { 0.5 } else { -0.5 };
            [t.cos(), t.sin(), z]
        })
        .collect();
    let e = refusal(&antiprism);
    assert_eq!(e.key, "die.vertices");
    assert!(e.to_string().contains("22 faces"), "{e}");
    assert!(
        Vertices::new(&[[0.0; 3]; 21]).is_err(),
        "21 corners are more than a body carries"
    );
}

/// Each flaw key's refusal names it and why (docs/dice.md, "Flaws"), on the 16 mm d20: its
/// inradius is 0.8 cm, so a bubble reaches a face once its offset and radius pass 0.8 cm.
#[test]
fn each_flaw_key_is_refused_by_name_when_it_makes_no_body() {
    let d20 = |flaws: DieFlaws| {
        let mut p = dice_table();
        p.die.kind = Solid::D20;
        p.die.flaws = flaws;
        p.validate()
    };
    let f = DieFlaws::NONE;
    let refused = |flaws: DieFlaws, key: &str, words: &str| {
        let e = d20(flaws).expect_err(key);
        assert_eq!(e.key, key, "{e}");
        assert!(e.to_string().contains(words), "{key}: {e}");
    };
    // 0.5 + 0.35 > 0.8: the bubble breaks through face 20.
    let bubble = DieFlaws {
        bubble_radius: 0.35,
        bubble_toward: Some(20),
        ..f
    };
    d20(DieFlaws {
        bubble_offset: 0.44,
        ..bubble
    })
    .unwrap();
    refused(
        DieFlaws {
            bubble_offset: 0.5,
            ..bubble
        },
        "die.bubble_offset",
        "reaches face 20",
    );
    refused(
        DieFlaws {
            bubble_radius: 0.85,
            ..f
        },
        "die.bubble_radius",
        "reaches face",
    );
    refused(
        DieFlaws {
            bubble_radius: 0.2,
            bubble_offset: 0.3,
            ..f
        },
        "die.bubble_offset",
        "`die.bubble_toward`",
    );
    refused(
        DieFlaws {
            bubble_radius: 0.2,
            bubble_toward: Some(21),
            ..f
        },
        "die.bubble_toward",
        "faces show 1 to 20",
    );
    refused(
        DieFlaws {
            bubble_radius: 11.0,
            ..f
        },
        "die.bubble_radius",
        "outside the allowed range 0 to 10 cm",
    );
    // A point mass past the inradius (0.8 cm) along a face's normal lies beyond that face.
    refused(
        DieFlaws {
            point_mass: 1.0,
            point_mass_toward: Some(7),
            point_mass_offset: 0.9,
            ..f
        },
        "die.point_mass_offset",
        "outside the die, beyond face 7",
    );
    refused(
        DieFlaws {
            point_mass: 1001.0,
            ..f
        },
        "die.point_mass",
        "outside the allowed range 0 to 1000 g",
    );
    // A shave deeper than the die is thick takes whole faces.
    refused(
        DieFlaws {
            shave_face: Some(1),
            shave_depth: 1.0,
            ..f
        },
        "die.shave_depth",
        "removes the whole of face",
    );
    refused(
        DieFlaws {
            shave_depth: 0.1,
            ..f
        },
        "die.shave_depth",
        "`die.shave_face`",
    );
    refused(
        DieFlaws {
            shave_face: Some(0),
            ..f
        },
        "die.shave_face",
        "no face of this die shows 0",
    );
    // Rounding past a face.
    refused(
        DieFlaws { rounding: 2.0, ..f },
        "die.rounding",
        "reaches past face",
    );
    refused(
        DieFlaws {
            worn_face: Some(5),
            worn_rounding: 2.0,
            ..f
        },
        "die.worn_rounding",
        "reaches past face",
    );
    refused(
        DieFlaws {
            worn_rounding: 0.1,
            ..f
        },
        "die.worn_rounding",
        "`die.worn_face`",
    );
    let radii = dicesim_physics::params::PerVertex::new(&[0.01; 11], 0.0).expect("11 radii");
    refused(
        DieFlaws {
            vertex_rounding: radii,
            ..f
        },
        "die.vertex_rounding",
        "11 radii for a die of 12 vertices",
    );
    let mut one_too_round = [0.0; 12];
    one_too_round[4] = 3.0;
    refused(
        DieFlaws {
            vertex_rounding: dicesim_physics::params::PerVertex::new(&one_too_round, 0.0).expect("12"),
            ..f
        },
        "die.vertex_rounding.5",
        "vertex 5's rounding reaches past face",
    );
    refused(
        DieFlaws {
            vertex_rounding: dicesim_physics::params::PerVertex::new(&[0.01; 12], 0.0).expect("12"),
            shave_face: Some(2),
            shave_depth: 0.05,
            ..f
        },
        "die.vertex_rounding",
        "round it evenly",
    );
    // A flaw on the box is refused whatever its value: the box has its own.
    let mut p = Params::default();
    p.die.flaws.bubble_radius = 0.1;
    let e = p.validate().unwrap_err();
    assert_eq!(e.key, "die.bubble_radius");
    assert!(e.to_string().contains("`die.extra_corner_mass`"), "{e}");
    assert!(!Params::DEFAULT.die.reads("die.worn_face"));
    assert!(!Params::DEFAULT.die.reads("die.vertices"));
    let mut d20 = dice_table();
    d20.die.kind = Solid::D20;
    assert!(d20.die.reads("die.bubble_offset") && !d20.die.reads("die.vertices"));
    let coin = convex(&prism(8, 1.2, 0.85), 1.18);
    assert!(coin.die.reads("die.vertices") && !coin.die.reads("die.height"));
    assert!(coin.die.reads("die.shave_depth") && !coin.die.reads("die.corner_radius"));
}

/// The flaws move the die's mass as placed: a bubble `e` toward face 20 takes
/// `m_b = ρ·4/3·π·r³` from there, so the centre of mass moves `m_b·e/(M − m_b)` the other way
/// (docs/dice.md, "Flaws").
#[test]
fn a_bubble_placed_by_its_keys_moves_the_centre_of_mass_away_from_its_face() {
    let mut p = dice_table();
    p.die.kind = Solid::D20;
    let sharp = p.polyhedral_die().expect("a d20");
    let face = sharp
        .numbering()
        .numbers
        .iter()
        .position(|&n| n == 20)
        .expect("a 20");
    let normal: Vector3<f64> = sharp.shape().faces()[face].normal;
    p.die.flaws = DieFlaws {
        bubble_radius: 0.2,
        bubble_toward: Some(20),
        bubble_offset: 0.5,
        ..DieFlaws::NONE
    };
    p.validate().unwrap();
    let flawed = p.polyhedral_die().expect("a d20").mass_properties();
    let whole = sharp.mass_properties().mass;
    let bubble = 1.18 * 4.0 / 3.0 * std::f64::consts::PI * 0.2f64.powi(3);
    assert!(
        close(flawed.mass, whole - bubble),
        "{} {}",
        flawed.mass,
        whole - bubble
    );
    let expected = -normal * (bubble * 0.5 / (whole - bubble));
    assert!(
        (flawed.centre_of_mass - expected).norm() < 1e-14,
        "{:?}",
        flawed.centre_of_mass
    );
}

/// What padding costs: the same throws of a convex cube rolled as the body of its own 8
/// points and as the padded 12-point body the engines carry it as (scalar `PointRoll`, and
/// the lanes), rolls per second of each. Ignored: a measurement, not a check (run it on an
/// idle machine with `-- --ignored --nocapture dice::keys::padding`).
#[test]
#[ignore = "a measurement: see the doc comment for the command"]
fn padding_costs_its_share_of_the_loops_over_points() {
    use dicesim_physics::lanes::roll_points_in_lanes;
    use std::time::Instant;
    let p = convex(&cube(0.8), 1.18);
    let die = p.polyhedral_die().expect("a convex die");
    let throws: Vec<InitialCondition> = (0..2000).map(|i| throw(23, i)).collect();
    fn rate<const N: usize>(
        p: &Params,
        die: &dicesim_physics::polyhedron::Die,
        throws: &[InitialCondition],
    ) -> (f64, f64) {
        let body = die.point_body::<N>(p).expect("a body");
        let start = Instant::now();
        for initial in throws {
            PointRoll::new(p, &body, initial).expect("a throw").run_to_end();
        }
        let scalar = throws.len() as f64 / start.elapsed().as_secs_f64();
        let start = Instant::now();
        roll_points_in_lanes(p, &body, throws).expect("throws");
        let lanes = throws.len() as f64 / start.elapsed().as_secs_f64();
        (scalar, lanes)
    }
    let own = rate::<8>(&p, &die, &throws);
    let padded = rate::<12>(&p, &die, &throws);
    println!(
        "cube of 8 corners, 2 000 throws: rolls/s scalar {:.0} as 8 points, {:.0} as 12 ({:.2}×); lanes {:.0} and {:.0} ({:.2}×)",
        own.0,
        padded.0,
        own.0 / padded.0,
        own.1,
        padded.1,
        own.1 / padded.1
    );
}
