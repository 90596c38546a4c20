//! A polyhedral die as a preset's `[die]` keys describe it (docs/dice.md, "Flaws" and "A
//! convex die of its corners"): the regular solid of `die.height` or the hull of
//! `die.vertices`, with the flaws its keys size and place by a face's number. Every way the
//! keys can make an impossible body is refused here, naming the key and why, so that a die
//! the validation accepts always makes its body.

use super::die::Die;
use super::flaws::{Bubble, FlawError, Flaws, PointMass, Shave};
use super::hull::{HullError, convex_hull};
use crate::params::{
    self, ContactLaw, DieFlaws, FrictionLaw, Limits, MAX_DIE_VERTICES, MAX_FACES, ParamError, Params,
    PerVertex, Solid, Vertices, limits,
};
use nalgebra::Vector3;

/// The bodies the engines carry, by their points: a die of fewer vertices rolls as the next
/// one up, its extra points at its centre of mass (docs/dice.md, "A convex die of its corners").
pub const BODY_POINTS: [usize; 4] = [4, 6, 12, 20];

/// The points of the body a die of `vertices` vertices rolls as.
pub fn body_points(vertices: usize) -> Option<usize> {
    BODY_POINTS.into_iter().find(|&n| n >= vertices)
}

/// `params`' polyhedral die with its flaws, or the first key that makes it impossible; `None`
/// for the box.
pub(crate) fn made_die(params: &Params) -> Result<Option<Die>, ParamError> {
    let d = &params.die;
    let sharp = match d.kind {
        Solid::Box => return Ok(None),
        Solid::Convex => convex_die(params)?,
        kind => kind
            .regular()
            .expect("every solid but the box and a convex die is regular")
            .die(d.height, d.density),
    };
    let flaws = flaws(params, &sharp)?;
    if flaws == Flaws::default() {
        return Ok(Some(sharp));
    }
    let die = sharp
        .with_flaws(&flaws)
        .map_err(|e| flaw_refusal(&d.flaws, &sharp, e))?;
    let count = die.shape().vertices().len();
    if count > MAX_DIE_VERTICES {
        return Err(refused(
            limits::SHAVE_DEPTH,
            d.flaws.shave_depth,
            format!(
                "the shaved die has {count} vertices, and the engines carry bodies of at most \
                 {MAX_DIE_VERTICES} points: shave a face of fewer edges, or less deep"
            ),
        ));
    }
    Ok(Some(die))
}

impl Vertices {
    /// `points` (cm, die frame), their hull's faces counted (0 when they make no solid);
    /// refused past [`MAX_DIE_VERTICES`].
    pub fn new(points: &[[f64; 3]]) -> Result<Vertices, &'static str> {
        let points = PerVertex::new(points, [0.0; 3]).ok_or(params::TOO_MANY_VERTICES)?;
        let corners: Vec<Vector3<f64>> = points.as_slice().iter().map(|&p| p.into()).collect();
        let faces = convex_hull(&corners).map_or(0, |hull| hull.faces().len().min(255) as u8);
        Ok(Vertices { points, faces })
    }
}

impl Params {
    /// Refuses, naming the key and why, every polyhedral die the engines cannot roll: the
    /// keys [`made_die`] refuses, the authors' whole-die friction norm on a body carried with
    /// extra points (it sums over every point), and a body [`Die::point_body`] would refuse.
    pub(crate) fn check_polyhedral_die(&self) -> Result<(), ParamError> {
        check(self)
    }
}

/// [`Params::check_polyhedral_die`].
fn check(params: &Params) -> Result<(), ParamError> {
    let Some(die) = made_die(params)? else {
        return Ok(());
    };
    let count = die.shape().vertices().len();
    let points = body_points(count).expect("made_die keeps to 20 vertices");
    let g = &params.ground;
    if points != count && g.contact == ContactLaw::Paper && g.friction_law == FrictionLaw::WholeDieNorm {
        return Err(refused(
            params::FRICTION_LAW_KEY,
            f64::NAN,
            format!(
                "this die of {count} vertices rolls as a body of {points} points, its extra points at \
                 its centre of mass, and the authors' whole-die norm sums over every point: use \
                 \"per-corner\" (docs/dice.md, \"A convex die of its corners\")"
            ),
        ));
    }
    let built = match points {
        4 => die.point_body::<4>(params).map(drop),
        6 => die.point_body::<6>(params).map(drop),
        12 => die.point_body::<12>(params).map(drop),
        _ => die.point_body::<20>(params).map(drop),
    };
    built.map_err(|e| {
        refused(
            params::KIND_KEY,
            f64::NAN,
            format!("this die makes no body to roll: {}", e.0),
        )
    })
}

/// The refusal of `key` = `value` for `why`.
fn refused(limits: Limits, value: f64, why: String) -> ParamError {
    ParamError::refused(limits, value, why)
}

/// The sharp, uniform die of `die.vertices`, numbered in opposite pairs where its faces pair.
fn convex_die(params: &Params) -> Result<Die, ParamError> {
    let points = params.die.vertices.points();
    let corners: Vec<Vector3<f64>> = points.iter().map(|&p| p.into()).collect();
    let vertex_key = |vertex: usize| of_vertex(limits::VERTICES, vertex);
    let die = Die::from_vertices(&corners, params.die.density).map_err(|e| {
        let (at, why) = match e {
            HullError::TooFew { count: 0 } => (
                limits::VERTICES,
                "a convex die is given by its corners: `vertices = [[x, y, z], …]` (cm, at least 4)"
                    .to_string(),
            ),
            HullError::NotFinite { vertex }
            | HullError::Duplicate { vertex, .. }
            | HullError::NotConvex { vertex } => (vertex_key(vertex), e.to_string()),
            HullError::TooFew { .. } | HullError::TooMany { .. } | HullError::Flat => {
                (limits::VERTICES, e.to_string())
            }
        };
        refused(at, f64::NAN, why)
    })?;
    let faces = die.shape().faces().len();
    if faces > MAX_FACES {
        return Err(refused(
            limits::VERTICES,
            f64::NAN,
            format!("their hull has {faces} faces, and a die numbers at most {MAX_FACES}"),
        ));
    }
    // How tall it stands on its thinnest face: the sizes `die.height` allows.
    let shape = die.shape();
    let standing = shape
        .faces()
        .iter()
        .map(|f| {
            shape
                .vertices()
                .iter()
                .map(|v| -f.height_of(v))
                .fold(0.0, f64::max)
        })
        .fold(f64::INFINITY, f64::min);
    if standing < limits::HEIGHT.min {
        return Err(refused(
            limits::VERTICES,
            f64::NAN,
            format!(
                "the die stands only {} cm tall on its thinnest face, below the least size a die \
                 may have ({} cm, as `die.height`)",
                params::fmt_number((standing * 1e9).round() / 1e9),
                params::fmt_number(limits::HEIGHT.min)
            ),
        ));
    }
    Ok(die)
}

/// Twenty keys `$base.1` … `$base.20`: one per vertex, each naming its element's line.
macro_rules! per_vertex_keys {
    ($base:literal) => {
        [
            concat!($base, ".1"),
            concat!($base, ".2"),
            concat!($base, ".3"),
            concat!($base, ".4"),
            concat!($base, ".5"),
            concat!($base, ".6"),
            concat!($base, ".7"),
            concat!($base, ".8"),
            concat!($base, ".9"),
            concat!($base, ".10"),
            concat!($base, ".11"),
            concat!($base, ".12"),
            concat!($base, ".13"),
            concat!($base, ".14"),
            concat!($base, ".15"),
            concat!($base, ".16"),
            concat!($base, ".17"),
            concat!($base, ".18"),
            concat!($base, ".19"),
            concat!($base, ".20"),
        ]
    };
}

/// `limits` named for its `vertex`-th value (from 0), `die.vertices.K` with K from 1 as the
/// corners are numbered, so that a refusal points at the vertex's line.
fn of_vertex(limits: Limits, vertex: usize) -> Limits {
    const VERTICES: [&str; MAX_DIE_VERTICES] = per_vertex_keys!("die.vertices");
    const RADII: [&str; MAX_DIE_VERTICES] = per_vertex_keys!("die.vertex_rounding");
    let keys = if limits.key == VERTICES_KEY {
        &VERTICES
    } else {
        &RADII
    };
    Limits {
        key: keys.get(vertex).copied().unwrap_or(limits.key),
        ..limits
    }
}

const VERTICES_KEY: &str = limits::VERTICES.key;

/// The face of `die` that shows `number` (docs/dice.md: a face's number is the one printed
/// on it; the d4's, the one read while it lies down), or the refusal of `key`.
fn face_numbered(die: &Die, number: u8, key: Limits) -> Result<usize, ParamError> {
    let numbers = &die.numbering().numbers;
    numbers
        .iter()
        .position(|&n| n == u32::from(number))
        .ok_or_else(|| {
            let (first, last) = (numbers.iter().min(), numbers.iter().max());
            refused(
                key,
                f64::from(number),
                format!(
                    "no face of this die shows {number}: its faces show {} to {}",
                    first.copied().unwrap_or(0),
                    last.copied().unwrap_or(0)
                ),
            )
        })
}

/// cm, die frame: `offset` from the sharp die's centre of mass along the outward normal of
/// the face showing `toward`, refused when an offset has no face to lie toward.
fn placed(
    die: &Die,
    toward: Option<u8>,
    offset: f64,
    toward_key: Limits,
    offset_key: Limits,
) -> Result<Vector3<f64>, ParamError> {
    let centre = die.mass_properties().centre_of_mass;
    match toward {
        Some(number) => {
            let face = face_numbered(die, number, toward_key)?;
            Ok(centre + die.shape().faces()[face].normal * offset)
        }
        None if offset == 0.0 => Ok(centre),
        None => Err(refused(
            offset_key,
            offset,
            format!(
                "an offset needs the face it lies toward: give `{}` (a face's number)",
                toward_key.key
            ),
        )),
    }
}

/// The flaws `params`' keys give `die` (sharp and uniform), placed in its frame.
fn flaws(params: &Params, die: &Die) -> Result<Flaws, ParamError> {
    let f = &params.die.flaws;
    let mut flaws = Flaws::default();
    if f.bubble_radius > 0.0 {
        let centre = placed(
            die,
            f.bubble_toward,
            f.bubble_offset,
            limits::BUBBLE_TOWARD,
            limits::BUBBLE_OFFSET,
        )?;
        flaws.bubble = Some(Bubble {
            centre,
            radius: f.bubble_radius,
        });
    } else if let Some(number) = f.bubble_toward {
        face_numbered(die, number, limits::BUBBLE_TOWARD)?;
    }
    if f.point_mass > 0.0 {
        let position = placed(
            die,
            f.point_mass_toward,
            f.point_mass_offset,
            limits::POINT_MASS_TOWARD,
            limits::POINT_MASS_OFFSET,
        )?;
        flaws.point_mass = Some(PointMass {
            position,
            mass: f.point_mass,
        });
    } else if let Some(number) = f.point_mass_toward {
        face_numbered(die, number, limits::POINT_MASS_TOWARD)?;
    }
    let shave_face = f
        .shave_face
        .map(|number| face_numbered(die, number, limits::SHAVE_FACE))
        .transpose()?;
    if f.shave_depth > 0.0 {
        let Some(face) = shave_face else {
            return Err(refused(
                limits::SHAVE_DEPTH,
                f.shave_depth,
                "a shave needs the face it takes down: give `die.shave_face` (a face's number)".to_string(),
            ));
        };
        let plane = &die.shape().faces()[face];
        flaws.shave = Some(Shave {
            normal: plane.normal,
            offset: plane.offset - f.shave_depth,
        });
    }
    flaws.rounding = rounding(f, die, flaws.shave.is_some())?;
    Ok(flaws)
}

/// cm, the rounding radius of each vertex (`die.rounding`, plus its own in
/// `die.vertex_rounding`, plus `die.worn_rounding` on the worn face's vertices): empty when
/// all are sharp, one radius when all are alike.
fn rounding(f: &DieFlaws, die: &Die, shaved: bool) -> Result<Vec<f64>, ParamError> {
    let count = die.shape().vertices().len();
    let worn = f
        .worn_face
        .map(|number| face_numbered(die, number, limits::WORN_FACE))
        .transpose()?;
    if f.worn_rounding > 0.0 && worn.is_none() {
        return Err(refused(
            limits::WORN_ROUNDING,
            f.worn_rounding,
            "worn rounding needs the face whose corners it rounds: give `die.worn_face` (a face's number)"
                .to_string(),
        ));
    }
    let uneven = !f.vertex_rounding.is_empty() || f.worn_rounding > 0.0;
    if shaved && uneven {
        let (key, value) = if f.vertex_rounding.is_empty() {
            (limits::WORN_ROUNDING, f.worn_rounding)
        } else {
            (limits::VERTEX_ROUNDING, f64::NAN)
        };
        return Err(refused(
            key,
            value,
            "a shaved die's corners are not the ones it was made with: round it evenly \
             (`die.rounding`) or leave out the shave"
                .to_string(),
        ));
    }
    if !f.vertex_rounding.is_empty() && f.vertex_rounding.len() != count {
        return Err(refused(
            limits::VERTEX_ROUNDING,
            f64::NAN,
            format!(
                "{} radii for a die of {count} vertices: give one per vertex, in the order of its \
                 vertices (docs/dice.md)",
                f.vertex_rounding.len()
            ),
        ));
    }
    let on_worn: Vec<usize> = worn.map_or_else(Vec::new, |face| die.shape().faces()[face].vertices.clone());
    let radii: Vec<f64> = (0..count)
        .map(|k| {
            let own = f.vertex_rounding.as_slice().get(k).copied().unwrap_or(0.0);
            let extra = if on_worn.contains(&k) {
                f.worn_rounding
            } else {
                0.0
            };
            f.rounding + own + extra
        })
        .collect();
    Ok(if radii.iter().all(|&r| r == 0.0) {
        Vec::new()
    } else if radii.iter().all(|&r| r == radii[0]) {
        vec![radii[0]]
    } else {
        radii
    })
}

/// The key at fault for a flaw `sharp` cannot take, and why.
fn flaw_refusal(f: &DieFlaws, sharp: &Die, e: FlawError) -> ParamError {
    let why = e.to_string();
    match e {
        FlawError::BubbleRadius | FlawError::BubbleOutside { .. } => {
            if f.bubble_offset > 0.0 {
                refused(
                    limits::BUBBLE_OFFSET,
                    f.bubble_offset,
                    format!("{why} (radius {} cm)", f.bubble_radius),
                )
            } else {
                refused(limits::BUBBLE_RADIUS, f.bubble_radius, why)
            }
        }
        FlawError::PointMassValue | FlawError::PointMassOutside { .. } => {
            refused(limits::POINT_MASS_OFFSET, f.point_mass_offset, why)
        }
        FlawError::ShaveMisses
        | FlawError::ShaveLeavesFace { .. }
        | FlawError::ShaveRemovesFace { .. }
        | FlawError::ShaveTopples { .. }
        | FlawError::ShaveHull(HullError::Duplicate { .. } | HullError::NotConvex { .. }) => {
            refused(limits::SHAVE_DEPTH, f.shave_depth, why)
        }
        FlawError::ShaveHull(_) => refused(
            limits::SHAVE_DEPTH,
            f.shave_depth,
            "the cut is as deep as the die is thick across that face: nothing is left".to_string(),
        ),
        FlawError::RoundingCount { .. } => refused(limits::VERTEX_ROUNDING, f64::NAN, why),
        FlawError::RoundingValue { vertex } | FlawError::RoundingTooLarge { vertex, .. } => {
            // The key that rounds this vertex most.
            let k = vertex - 1;
            let own = f.vertex_rounding.as_slice().get(k).copied().unwrap_or(0.0);
            let worn = f
                .worn_face
                .and_then(|n| sharp.numbering().numbers.iter().position(|&m| m == u32::from(n)))
                .is_some_and(|face| sharp.shape().faces()[face].vertices.contains(&k));
            let worn = if worn { f.worn_rounding } else { 0.0 };
            if worn >= own && worn >= f.rounding && worn > 0.0 {
                refused(limits::WORN_ROUNDING, f.worn_rounding, why)
            } else if own >= f.rounding && own > 0.0 {
                refused(
                    of_vertex(limits::VERTEX_ROUNDING, k),
                    own,
                    format!("{why} (its own rounding is {} cm)", params::fmt_number(own)),
                )
            } else {
                refused(limits::ROUNDING, f.rounding, why)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_die_rolls_as_the_smallest_body_that_holds_its_vertices() {
        assert_eq!(body_points(4), Some(4));
        assert_eq!(body_points(5), Some(6));
        assert_eq!(body_points(8), Some(12));
        assert_eq!(body_points(12), Some(12));
        assert_eq!(body_points(13), Some(20));
        assert_eq!(body_points(20), Some(20));
        assert_eq!(body_points(21), None);
    }
}
