//! A roll as an animation for a slide: an animated GIF or PNG (APNG) of the die, or of the
//! die and its chaos twin, from the drop to the face it ends on.
//!
//! The roll is rolled first, keeping the dice's state at every frame's time (`1/fps` s
//! apart, then the end), so the view can hold the whole path and the frame count is known;
//! then each frame is drawn ([`render::Scene::render`], a pure function of the state) and
//! encoded as it comes. Frames after the first carry only the rectangle that changed, its
//! unchanged pixels transparent, so a few seconds at 640×480 stay well under a megabyte or
//! two. The file says how it was made: the setup and the outcome as GIF comments or PNG
//! text chunks, the same keys the plots' PNGs carry. Nothing in it depends on the clock or
//! the machine: the same setup gives the same bytes.

pub mod render;
mod solid;
pub mod terminal;

use crate::figure::resolved;
use crate::plot::Record;
use dicesim_experiment::Error;
use dicesim_physics::{InitialCondition, Outcome, Params, Roll, Status, face_most_nearly_up};
use dicesim_setup::number::die_number;
use dicesim_setup::output::{Output, OutputError};
use render::{Body, CLEAR, Camera, DieShot, Frame, PALETTE, Scene, Shot, View};
use solid::Polyhedral;
use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};

/// Frames per second an animation may have: GIF delays are whole hundredths of a second
/// and viewers slow anything under two of them down, so 50 is the most that plays true.
pub const FPS: std::ops::RangeInclusive<u32> = 1..=50;
/// Pixels across and down an animation may have.
pub const WIDTH: std::ops::RangeInclusive<u32> = 64..=3840;
pub const HEIGHT: std::ops::RangeInclusive<u32> = 64..=2160;
/// s the last frame stays before the animation starts again, to read the face.
pub(crate) const HOLD_S: f64 = 2.0;
/// Simulated seconds per played second, as the explorer's speed ladder has them.
pub(crate) const SPEED: std::ops::RangeInclusive<f64> = 0.01..=100.0;
/// The most frames one animation has (a 30 s roll that never settles at 1/100× would be
/// 75 000): past it a lower rate or a faster speed is asked for, before anything is drawn.
use dicesim_experiment::limits::FRAMES;

/// The file formats: by the extension, `.gif` or `.png` (an animated PNG).
pub const EXTENSIONS: [&str; 2] = ["gif", "png"];

/// How to film a roll.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnimationSpec {
    /// Frames per played second.
    pub fps: u32,
    /// Simulated seconds per played second: 1 plays in real time, 0.1 ten times slower.
    pub speed: f64,
    /// Pixels, width × height.
    pub size: (u32, u32),
    /// The chaos twin's ε ([`dicesim_setup::chaos::perturbed`]), if it rolls beside.
    pub twin: Option<f64>,
    pub camera: Camera,
    /// The camera follows the die and frames it: its side about a third of the frame's
    /// height, the table moving under it (else the view holds the whole path).
    pub zoom: bool,
    /// A number of the die whose face and its opposite face to mark (on the box 1 to 6,
    /// its opposite 7 minus it; on a polyhedral die the face printed with it and the one
    /// opposite, [`dicesim_physics::Solid::opposite_number`]): both coloured and their body
    /// axis drawn, on the die. [`AnimationSpec::face_pair_on`] checks it against the die.
    pub face_pair: Option<u8>,
}

impl AnimationSpec {
    /// A spec of `fps` frames per second and `size` pixels, no twin, the explorer's camera.
    pub fn new(fps: u32, size: (u32, u32)) -> AnimationSpec {
        AnimationSpec {
            fps,
            speed: 1.0,
            size,
            twin: None,
            camera: Camera::DEFAULT,
            zoom: false,
            face_pair: None,
        }
    }

    /// Every value in its range, else what is wrong.
    pub fn validate(&self) -> Result<(), Error> {
        let bad = |what: String| Err(Error::Animation(what));
        if !FPS.contains(&self.fps) {
            return bad(format!(
                "{} frames/s: from {} to {}",
                self.fps,
                FPS.start(),
                FPS.end()
            ));
        }
        if !SPEED.contains(&self.speed) {
            return bad(format!(
                "speed {}×: from {}× to {}×",
                self.speed,
                SPEED.start(),
                SPEED.end()
            ));
        }
        let (w, h) = self.size;
        if !WIDTH.contains(&w) || !HEIGHT.contains(&h) {
            return bad(format!(
                "{w}×{h} pixels: from {}×{} to {}×{}",
                WIDTH.start(),
                HEIGHT.start(),
                WIDTH.end(),
                HEIGHT.end()
            ));
        }
        if let Some(e) = self.twin {
            dicesim_setup::chaos::EPSILON.check(e)?;
        }
        Ok(())
    }

    /// The face pair to mark on `params`' die: [`AnimationSpec::face_pair`] and its
    /// opposite number, the lower first; refused, saying why, for a number the die does not
    /// show, and on the d4, whose faces each lie opposite a vertex.
    pub fn face_pair_on(&self, params: &Params) -> Result<Option<(u8, u8)>, String> {
        let Some(face) = self.face_pair else {
            return Ok(None);
        };
        let kind = params.die.kind;
        let numbers = kind.face_numbers();
        let die = match kind {
            dicesim_physics::Solid::Box => "the box".to_string(),
            k => format!("a {}", k.name()),
        };
        if !numbers.contains(&face) {
            let words = |n: u8| die_number(kind, n);
            let (first, last) = (numbers[0], numbers[numbers.len() - 1]);
            let step = numbers[1] - numbers[0];
            let every = if step == 1 {
                String::new()
            } else {
                format!(" in steps of {step}")
            };
            return Err(format!(
                "{die}'s faces are {} to {}{every}",
                words(first),
                words(last)
            ));
        }
        let opposite = kind.opposite_number(face).ok_or_else(|| {
            format!("{die} has no opposite faces (each face lies opposite a vertex), so there is no pair of faces to mark")
        })?;
        Ok(Some((face.min(opposite), face.max(opposite))))
    }
}

/// How far an animation has got.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AnimationProgress {
    /// False while the roll is rolled, true once frames are drawn.
    pub drawing: bool,
    /// Steps rolled (of the cap `integrator.max_time / dt`), or frames drawn.
    pub done: u64,
    pub total: u64,
}

/// What [`write_animation`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Animated {
    pub frames: usize,
    /// s of simulated time, the drop to the end of the later die.
    pub duration_s: f64,
    pub outcome: Outcome,
    pub twin: Option<Outcome>,
}

/// A filmed roll: each frame's time and picture state, and how the dice ended.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Film {
    pub(crate) times: Vec<f64>,
    pub(crate) shots: Vec<Shot>,
    pub(crate) outcome: Outcome,
    pub(crate) twin: Option<Outcome>,
}

/// Steps between looks at the cancel flag while rolling.
const REPORT_EVERY: u64 = 4096;

/// The die as a frame draws it: the box's corners, a polyhedral die's hull vertices (its
/// solid's, `solid`, turned and placed as the roll has it). The face drawn up: the one the
/// roll ended on once it has, else the one most nearly up.
fn die_shot(roll: &Roll, solid: Option<&Polyhedral>) -> DieShot {
    let up = match roll.outcome() {
        Some(o) => o.face,
        None => Some(face_up(roll)),
    };
    if let Some(sim) = roll.simulation() {
        let s = sim.state();
        return DieShot {
            corners: sim.corner_positions().to_vec(),
            centre: s.position,
            up,
        };
    }
    let (centre, turn) = (roll.position(), roll.orientation());
    DieShot {
        corners: solid
            .map(|d| d.offsets.iter().map(|p| centre + turn * p).collect())
            .unwrap_or_else(|| roll.point_positions()),
        centre,
        up,
    }
}

/// The number of the face most nearly up: the box's by its corners (as it always was), a
/// die's as a player reads it.
fn face_up(roll: &Roll) -> u8 {
    match roll.simulation() {
        Some(sim) => face_most_nearly_up(&sim.state().corner_offsets),
        None => roll.face_up(),
    }
}

/// A playback speed as the explorer's ladder writes it: `1/10×`, `1×`, `5×`.
pub fn speed_words(speed: f64) -> String {
    if speed < 1.0 {
        format!("1/{}×", crate::figure::setup_value(1.0 / speed))
    } else {
        format!("{}×", crate::figure::setup_value(speed))
    }
}

/// How an ended roll reads in a headline.
fn ending_words(o: &Outcome, params: &Params) -> String {
    match (o.status, o.face) {
        (Status::Settled, Some(f)) => format!("ended on face {}", die_number(params.die.kind, f)),
        (Status::Settled, None) if params.die.is_polyhedral() => {
            "settled on no face (on an edge or a vertex)".to_string()
        }
        (Status::Settled, None) => "settled on no face (the 4 highest corners form none)".to_string(),
        (Status::Timeout, _) => format!(
            "did not settle within {} s",
            crate::figure::setup_value(params.integrator.max_time)
        ),
        (Status::Unstable, _) => "unstable (the time step is too long for this table)".to_string(),
    }
}

/// The times (simulated s) of the frames of a roll that ends at `end_s`, stepped `dt` s:
/// every `speed / fps` s from the drop while more than half a step before the end, then
/// the end; more than the frames' limit is refused before anything is drawn.
pub fn frame_times(spec: &AnimationSpec, end_s: f64, dt: f64) -> Result<Vec<f64>, Error> {
    let frame_s = spec.speed / f64::from(spec.fps);
    let before_end = ((end_s - 0.5 * dt) / frame_s).ceil().max(0.0);
    if before_end + 1.0 > FRAMES.max as f64 {
        return Err(too_many_frames(spec));
    }
    let mut times: Vec<f64> = (0..before_end as u64).map(|k| k as f64 * frame_s).collect();
    times.push(end_s);
    Ok(times)
}

/// Why an animation of `spec` is refused for its length.
fn too_many_frames(spec: &AnimationSpec) -> Error {
    Error::Limit(format!(
        "more than {} frames at {} frames/s and {}: {}; {}",
        FRAMES.max,
        spec.fps,
        speed_words(spec.speed),
        FRAMES.stated(),
        FRAMES.why
    ))
}

/// Rolls `initial` (and its twin) to the end, keeping the state at `k / fps` s for every
/// frame before the end and at the end itself.
pub(crate) fn film(
    name: &str,
    params: &Params,
    initial: &InitialCondition,
    spec: &AnimationSpec,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(AnimationProgress),
) -> Result<Film, Error> {
    let mut die = Roll::new_unchecked(params, initial);
    let mut twin = spec
        .twin
        .map(|e| Roll::new_unchecked(params, &dicesim_setup::chaos::perturbed(initial, e)));
    let solid = Polyhedral::of(params);
    let solid = solid.as_ref();
    let dt = params.integrator.dt;
    // Simulated seconds between frames.
    let frame_s = spec.speed / f64::from(spec.fps);
    let pace = if spec.speed == 1.0 {
        String::new()
    } else {
        format!(" ({})", speed_words(spec.speed))
    };
    let time_words = |t: f64| format!("t = {} s{pace}", resolved(t, frame_s));
    let headline = |die: &Roll, twin: Option<&Roll>, t: f64| {
        let face = |s: &Roll| match s.outcome() {
            Some(o) => ending_words(&o, params),
            None => format!("face {} up", die_number(params.die.kind, face_up(s))),
        };
        let mut line = format!("{name} · {} · {}", time_words(t), face(die));
        if let (Some(b), Some(e)) = (twin, spec.twin) {
            let apart = (die.position() - b.position()).norm();
            line += &format!(
                "\ntwin (ε {}): {}, {} cm apart",
                crate::figure::setup_value(e),
                face(b),
                resolved(apart, 0.01)
            );
        }
        line
    };
    let mut times = Vec::new();
    let mut shots = Vec::new();
    let mut status = AnimationProgress {
        drawing: false,
        done: 0,
        total: params.max_steps(),
    };
    loop {
        // The later die's clock: one that has ended stays where it stopped.
        let t = die.time_s().max(twin.as_ref().map_or(0.0, Roll::time_s));
        // Every frame time this step reaches (its state is the nearest at or after it).
        while (times.len() as f64) * frame_s <= t + 0.5 * dt {
            let at = times.len() as f64 * frame_s;
            times.push(at);
            shots.push(Shot {
                die: die_shot(&die, solid),
                twin: twin.as_ref().map(|b| die_shot(b, solid)),
                headline: headline(&die, twin.as_ref(), at),
                played_s: at / spec.speed,
            });
        }
        if times.len() as u64 > FRAMES.max {
            return Err(too_many_frames(spec));
        }
        let ended = die.outcome().is_some() && twin.as_ref().is_none_or(|b| b.outcome().is_some());
        if ended {
            break;
        }
        for s in std::iter::once(&mut die).chain(twin.as_mut()) {
            if s.outcome().is_none() {
                s.advance();
            }
        }
        let step = die.steps().max(twin.as_ref().map_or(0, Roll::steps));
        if step.is_multiple_of(REPORT_EVERY) {
            if cancel.load(Ordering::Relaxed) {
                return Err(Error::Cancelled);
            }
            status.done = step;
            progress(status);
        }
    }
    // The end, as the last frame: a sampled frame within half a step of it is the end.
    let end = die.time_s().max(twin.as_ref().map_or(0.0, Roll::time_s));
    while times.last().is_some_and(|&t| t >= end - 0.5 * dt) {
        times.pop();
        shots.pop();
    }
    times.push(end);
    shots.push(Shot {
        die: die_shot(&die, solid),
        twin: twin.as_ref().map(|b| die_shot(b, solid)),
        headline: headline(&die, twin.as_ref(), end),
        played_s: end / spec.speed,
    });
    Ok(Film {
        times,
        shots,
        outcome: die.outcome().expect("the loop ends when the die has"),
        twin: twin.as_ref().and_then(Roll::outcome),
    })
}

/// How a roll ended, as the files' `dicesim-outcome` records it.
pub(crate) fn outcome_json(o: &Outcome) -> serde_json::Value {
    serde_json::json!({
        "status": o.status.name(),
        "face": o.face,
        "steps": o.steps,
        "time_s": o.time_s,
    })
}

/// The record of an animation: the setup's caption and text (as the plots' PNGs have
/// them), the twin's ε, and the outcome as JSON in `dicesim-outcome`.
fn animation_record(
    name: &str,
    (params, initial): (&Params, &InitialCondition),
    (spec, pair): (&AnimationSpec, Option<(u8, u8)>),
    film: &Film,
) -> Record {
    let title = match spec.twin {
        Some(_) => format!("{name}: a roll and its chaos twin"),
        None => format!("{name}: a roll"),
    };
    let mut record = Record::of_setup(&title, name, params, initial);
    if let Some(e) = spec.twin {
        record.caption.push(format!(
            "twin: height, velocity and spin × (1 + ε), ε = {}",
            crate::figure::setup_value(e)
        ));
    }
    if let Some((low, high)) = pair {
        let words = |n: u8| die_number(params.die.kind, n);
        record.caption.push(format!(
            "faces {} (vermilion) and {} (purple) coloured, their body axis drawn through them",
            words(low),
            words(high)
        ));
    }
    let outcome = outcome_json;
    let mut json = serde_json::json!({
        "frames": film.shots.len(),
        "fps": spec.fps,
        "speed": spec.speed,
        "width": spec.size.0,
        "height": spec.size.1,
        "camera": { "yaw": spec.camera.yaw_deg, "pitch": spec.camera.pitch_deg },
        "zoom": spec.zoom,
        "face_pair": pair.map(|(low, _)| low),
        "die": outcome(&film.outcome),
    });
    if let (Some(e), Some(t)) = (spec.twin, &film.twin) {
        json["twin"] = outcome(t);
        json["twin"]["epsilon"] = serde_json::json!(e);
    }
    record
        .text
        .push(("dicesim-outcome".to_string(), json.to_string()));
    record
}

/// Rolls `initial` under `params` (and the twin, if `spec` asks) and writes it to `out` as
/// an animated GIF or PNG, by the extension; the setup and outcome travel in the file.
/// `cancel` stops it (nothing is written), `progress` hears of the rolling and drawing.
pub fn write_animation(
    name: &str,
    params: &Params,
    initial: &InitialCondition,
    spec: &AnimationSpec,
    out: &Output,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(AnimationProgress),
) -> Result<Animated, Error> {
    spec.validate()?;
    let pair = spec.face_pair_on(params).map_err(|why| {
        Error::Animation(format!("face pair {}: {why}", spec.face_pair.unwrap_or_default()))
    })?;
    let gif = Encoding::is_gif(out)?;
    let film = film(name, params, initial, spec, cancel, progress)?;
    let record = animation_record(name, (params, initial), (spec, pair), &film);
    let view = View {
        camera: spec.camera,
        zoom: spec.zoom,
        face_pair: pair,
    };
    let body = match Polyhedral::of(params) {
        Some(die) => Body::Polyhedron(std::sync::Arc::new(die)),
        None => Body::Box,
    };
    let scene = Scene::new(
        spec.size.0,
        spec.size.1,
        (view, body),
        &film.shots,
        &record.caption,
    );
    let mut frames = film.shots.iter().map(|s| scene.render(s));
    let encoding = Encoding {
        gif,
        size: spec.size,
        palette: &flat_palette(&PALETTE),
        record: &record,
    };
    encoding.write(out, &film.times, spec.speed, &mut frames, cancel, progress)?;
    Ok(Animated {
        frames: film.shots.len(),
        duration_s: film.times.last().copied().unwrap_or(0.0),
        outcome: film.outcome,
        twin: film.twin,
    })
}

/// How frames become a file: GIF or APNG, their size, their palette (RGB, 256 entries, the
/// first never drawn: [`CLEAR`]) and the record the file carries.
pub(crate) struct Encoding<'a> {
    pub(crate) gif: bool,
    pub(crate) size: (u32, u32),
    pub(crate) palette: &'a [u8],
    pub(crate) record: &'a Record,
}

impl Encoding<'_> {
    /// The format `out`'s extension names: GIF, else APNG; else what is wrong.
    pub(crate) fn is_gif(out: &Output) -> Result<bool, Error> {
        match out.extension() {
            "gif" => Ok(true),
            "png" => Ok(false),
            other => Err(Error::Animation(format!(
                "a .{other} file: expected a .gif or .png file"
            ))),
        }
    }

    /// Writes `frames`, shown at `times` (simulated s, played at `speed`), to `out`; the
    /// last stays [`HOLD_S`]. `cancel` stops it with nothing written.
    pub(crate) fn write(
        &self,
        out: &Output,
        times: &[f64],
        speed: f64,
        frames: &mut dyn Iterator<Item = Frame>,
        cancel: &AtomicBool,
        progress: &mut dyn FnMut(AnimationProgress),
    ) -> Result<(), Error> {
        // Played seconds: simulated ones over the speed.
        let played: Vec<f64> = times.iter().map(|t| t / speed).collect();
        let until = display_times(&played);
        let mut status = AnimationProgress {
            drawing: true,
            done: 0,
            total: times.len() as u64,
        };
        progress(status);
        let mut each = |k: usize| {
            if cancel.load(Ordering::Relaxed) {
                return Err(std::io::Error::other(CANCELLED));
            }
            status.done = k as u64 + 1;
            progress(status);
            Ok(())
        };
        let (size, palette, record) = (self.size, self.palette, self.record);
        out.write(|w| {
            if self.gif {
                let delays = delays(&played, &until, 0.01);
                encode_gif(w, size, palette, record, &delays, frames, &mut each)
            } else {
                let delays = delays(&played, &until, 0.001);
                encode_apng(w, size, palette, record, &delays, frames, &mut each)
            }
        })
        .map_err(|e| match e {
            OutputError::Write { message, .. } if message == CANCELLED => Error::Cancelled,
            e => Error::Output(e),
        })
    }
}

/// The reason a cancelled write stops with (it never reaches a person).
const CANCELLED: &str = "animation cancelled";

/// s from the start each frame is shown until: the next frame's time, and the last
/// [`HOLD_S`] past the end.
fn display_times(times: &[f64]) -> Vec<f64> {
    let end = times.last().copied().unwrap_or(0.0);
    times
        .iter()
        .skip(1)
        .copied()
        .chain(std::iter::once(end + HOLD_S))
        .collect()
}

/// Whole units of `unit_s` from one frame's start to the next: rounded on the running
/// total, so the clock never drifts however the frames divide.
fn delays(times: &[f64], until: &[f64], unit_s: f64) -> Vec<u16> {
    times
        .iter()
        .zip(until)
        .map(|(&t, &u)| {
            let ticks = (u / unit_s).round() - (t / unit_s).round();
            ticks.clamp(1.0, f64::from(u16::MAX)) as u16
        })
        .collect()
}

/// The rectangle of `frame` that differs from `previous` (x, y, width, height), or a
/// single pixel where nothing does (a frame must still be there to keep the time).
fn changed(previous: &Frame, frame: &Frame) -> (u32, u32, u32, u32) {
    let w = frame.width as usize;
    let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
    for (y, (a, b)) in previous.pixels.chunks(w).zip(frame.pixels.chunks(w)).enumerate() {
        if a == b {
            continue;
        }
        let first = a.iter().zip(b).position(|(p, q)| p != q).unwrap_or(0);
        let last = w
            - 1
            - a.iter()
                .rev()
                .zip(b.iter().rev())
                .position(|(p, q)| p != q)
                .unwrap_or(0);
        x0 = x0.min(first);
        x1 = x1.max(last);
        y0 = y0.min(y);
        y1 = y;
    }
    if x0 == usize::MAX {
        return (0, 0, 1, 1);
    }
    (x0 as u32, y0 as u32, (x1 - x0 + 1) as u32, (y1 - y0 + 1) as u32)
}

/// The pixels of `frame` in `rect`, those equal to `previous` [`CLEAR`] (drawn over the
/// old frame, they leave it as it was, and long runs of one index pack tightly).
fn delta(previous: Option<&Frame>, frame: &Frame, rect: (u32, u32, u32, u32)) -> Vec<u8> {
    let (x, y, w, h) = rect;
    let stride = frame.width as usize;
    let mut out = Vec::with_capacity(w as usize * h as usize);
    for row in y as usize..(y + h) as usize {
        let span = row * stride + x as usize..row * stride + (x + w) as usize;
        match previous {
            Some(p) => out.extend(
                frame.pixels[span.clone()]
                    .iter()
                    .zip(&p.pixels[span])
                    .map(|(&q, &o)| if q == o { CLEAR } else { q }),
            ),
            None => out.extend_from_slice(&frame.pixels[span]),
        }
    }
    out
}

/// Each frame's rectangle and pixels: the first whole, the others as [`delta`]s.
fn frame_parts<'a>(
    frames: &'a mut dyn Iterator<Item = Frame>,
) -> impl Iterator<Item = ((u32, u32, u32, u32), Vec<u8>)> + 'a {
    let mut previous: Option<Frame> = None;
    frames.map(move |frame| {
        let rect = match &previous {
            None => (0, 0, frame.width, frame.height),
            Some(p) => changed(p, &frame),
        };
        let pixels = delta(previous.as_ref(), &frame, rect);
        previous = Some(frame);
        (rect, pixels)
    })
}

/// A palette as the encoders take it: its colours' bytes, red, green, blue.
pub(crate) fn flat_palette(palette: &[[u8; 3]]) -> Vec<u8> {
    palette.iter().flatten().copied().collect()
}

fn io(e: impl std::fmt::Display) -> std::io::Error {
    std::io::Error::other(e.to_string())
}

/// The frames as an animated GIF (looping; the record as comment extensions).
fn encode_gif(
    w: &mut (dyn Write + Send),
    size: (u32, u32),
    palette: &[u8],
    record: &Record,
    delays: &[u16],
    frames: &mut dyn Iterator<Item = Frame>,
    each: &mut dyn FnMut(usize) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut encoder = gif::Encoder::new(w, size.0 as u16, size.1 as u16, palette).map_err(io)?;
    encoder.set_repeat(gif::Repeat::Infinite).map_err(io)?;
    for (keyword, text) in &record.text {
        let comment = format!("{keyword}: {text}");
        encoder
            .write_raw_extension(gif::Extension::Comment.into(), &[comment.as_bytes()])
            .map_err(io)?;
    }
    for (k, ((x, y, fw, fh), pixels)) in frame_parts(frames).enumerate() {
        each(k)?;
        let frame = gif::Frame {
            delay: delays[k],
            dispose: gif::DisposalMethod::Keep,
            transparent: (k > 0).then_some(CLEAR),
            left: x as u16,
            top: y as u16,
            width: fw as u16,
            height: fh as u16,
            buffer: std::borrow::Cow::Owned(pixels),
            ..gif::Frame::default()
        };
        encoder.write_frame(&frame).map_err(io)?;
    }
    encoder.into_inner().map_err(io)?;
    Ok(())
}

/// The frames as an animated PNG (looping; the record as iTXt chunks, UTF-8 for μ and Δt).
fn encode_apng(
    w: &mut (dyn Write + Send),
    size: (u32, u32),
    palette: &[u8],
    record: &Record,
    delays: &[u16],
    frames: &mut dyn Iterator<Item = Frame>,
    each: &mut dyn FnMut(usize) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut encoder = png::Encoder::new(w, size.0, size.1);
    encoder.set_color(png::ColorType::Indexed);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_palette(palette.to_vec());
    // Only the unchanged pixels of a delta frame are see-through.
    encoder.set_trns(vec![0u8]);
    encoder.set_filter(png::Filter::NoFilter);
    // zlib's level 9, what the smallest of the simple presets gave before png 0.18.
    encoder.set_deflate_compression(png::DeflateCompression::Level(9));
    encoder.set_animated(delays.len() as u32, 0).map_err(io)?;
    for (keyword, text) in &record.text {
        encoder
            .add_itxt_chunk(keyword.clone(), text.clone())
            .map_err(io)?;
    }
    let mut writer = encoder.write_header().map_err(io)?;
    for (k, ((x, y, fw, fh), pixels)) in frame_parts(frames).enumerate() {
        each(k)?;
        writer.reset_frame_position().map_err(io)?;
        writer.set_frame_dimension(fw, fh).map_err(io)?;
        writer.set_frame_position(x, y).map_err(io)?;
        writer.set_frame_delay(delays[k], 1000).map_err(io)?;
        writer.set_dispose_op(png::DisposeOp::None).map_err(io)?;
        writer
            .set_blend_op(if k == 0 {
                png::BlendOp::Source
            } else {
                png::BlendOp::Over
            })
            .map_err(io)?;
        writer.write_image_data(&pixels).map_err(io)?;
    }
    writer.finish().map_err(io)?;
    Ok(())
}

/// The comment extensions of a GIF this module wrote (its provenance), read block by block
/// as a viewer does; a file cut short gives the comments before the cut.
pub fn gif_comments(bytes: &[u8]) -> Vec<String> {
    let Some(flags) = bytes.get(10) else {
        return Vec::new();
    };
    let palette = 3 << ((flags & 7) + 1);
    let mut at = 13 + palette;
    let mut comments = Vec::new();
    while bytes.get(at) == Some(&0x21) {
        let Some(&label) = bytes.get(at + 1) else { break };
        at += 2;
        let mut data = Vec::new();
        while let Some(&n) = bytes.get(at).filter(|&&n| n != 0) {
            let Some(block) = bytes.get(at + 1..at + 1 + n as usize) else {
                return comments;
            };
            data.extend_from_slice(block);
            at += 1 + n as usize;
        }
        at += 1;
        if label == 0xFE {
            comments.push(String::from_utf8_lossy(&data).into_owned());
        }
    }
    comments
}

#[cfg(test)]
mod tests {
    use super::*;
    use dicesim_physics::roll;

    /// The paper's roll: thrown sideways with a lopsided spin from 15 cm.
    fn paper() -> (Params, InitialCondition) {
        let initial = InitialCondition {
            velocity: [30.0, 0.0, 0.0],
            angular_velocity: [12.0, -20.0, 6.0],
            ..InitialCondition::default()
        };
        (Params::default(), initial)
    }

    /// Writes the animation of `params`/`initial` into a fresh folder; its bytes.
    fn animate(
        params: &Params,
        initial: &InitialCondition,
        spec: &AnimationSpec,
        ext: &str,
    ) -> (Vec<u8>, Animated) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(format!("roll.{ext}"));
        let out = Output::check(&path, &EXTENSIONS, false).unwrap();
        let animated = write_animation(
            "paper",
            params,
            initial,
            spec,
            &out,
            &AtomicBool::new(false),
            &mut |_| {},
        )
        .unwrap();
        (std::fs::read(&path).unwrap(), animated)
    }

    /// The GIF's frames as the viewer shows them: each drawn over the last, its transparent
    /// pixels leaving what was there.
    fn gif_frames(bytes: &[u8]) -> Vec<Vec<u8>> {
        let mut options = gif::DecodeOptions::new();
        options.set_color_output(gif::ColorOutput::Indexed);
        let mut decoder = options.read_info(bytes).unwrap();
        let (w, h) = (decoder.width() as usize, decoder.height() as usize);
        let mut canvas = vec![0u8; w * h];
        let mut frames = Vec::new();
        while let Some(f) = decoder.read_next_frame().unwrap() {
            for row in 0..f.height as usize {
                for col in 0..f.width as usize {
                    let i = f.buffer[row * f.width as usize + col];
                    if Some(i) != f.transparent {
                        canvas[(f.top as usize + row) * w + f.left as usize + col] = i;
                    }
                }
            }
            frames.push(canvas.clone());
        }
        frames
    }

    #[test]
    fn frames_are_one_per_frame_time_of_the_roll() {
        let (params, initial) = paper();
        // The roll's length, from the physics alone.
        let (outcome, _) = roll(&params, &initial).unwrap();
        for fps in [7, 25, 50] {
            let spec = AnimationSpec::new(fps, (160, 120));
            let (bytes, animated) = animate(&params, &initial, &spec, "gif");
            let n = gif_frames(&bytes).len() as f64;
            let expected = (outcome.time_s * f64::from(fps)).ceil();
            assert!(
                (n - expected).abs() <= 1.0,
                "{fps} fps: {n} frames for {} s",
                outcome.time_s
            );
            assert_eq!(animated.frames as f64, n);
            assert_eq!(animated.outcome, outcome);
        }
        // Slowed down ten times: ten times the frames, and the delays add up to the played
        // time (hundredths of a second) and the hold at the end.
        let mut spec = AnimationSpec::new(10, (120, 90));
        spec.speed = 0.1;
        let (bytes, _) = animate(&params, &initial, &spec, "gif");
        let n = gif_frames(&bytes).len() as f64;
        assert!(
            (n - (outcome.time_s * 100.0).ceil()).abs() <= 1.0,
            "{n} frames at 1/10×"
        );
        let mut decoder = gif::DecodeOptions::new().read_info(&bytes[..]).unwrap();
        let mut played_cs = 0u32;
        while let Some(f) = decoder.read_next_frame().unwrap() {
            played_cs += u32::from(f.delay);
        }
        let expected_cs = (outcome.time_s / 0.1 + HOLD_S) * 100.0;
        assert!(
            (f64::from(played_cs) - expected_cs).abs() <= 1.0,
            "{played_cs} cs, {expected_cs} expected"
        );
        // The twin's roll may be the longer one: the film lasts until both have ended.
        let mut spec = AnimationSpec::new(25, (160, 120));
        spec.twin = Some(1e-3);
        let twin = dicesim_setup::chaos::perturbed(&initial, 1e-3);
        let (twin_outcome, _) = roll(&params, &twin).unwrap();
        let (bytes, _) = animate(&params, &initial, &spec, "gif");
        let n = gif_frames(&bytes).len() as f64;
        let end = outcome.time_s.max(twin_outcome.time_s);
        assert!((n - (end * 25.0).ceil()).abs() <= 1.0, "{n} frames for {end} s");
    }

    #[test]
    fn the_same_setup_gives_the_same_bytes() {
        let (params, initial) = paper();
        let mut spec = AnimationSpec::new(20, (200, 150));
        spec.twin = Some(1e-6);
        for ext in EXTENSIONS {
            let (a, _) = animate(&params, &initial, &spec, ext);
            let (b, _) = animate(&params, &initial, &spec, ext);
            assert!(a == b, "{ext}: two runs differ");
        }
    }

    /// Pip discs on the face drawn up in `frame`: connected pip-coloured regions with a
    /// face-up pixel right beside them.
    fn pips_on_the_up_face(frame: &[u8], width: usize) -> usize {
        let is_pip = |i: u8| (render::PIP..render::PIP + render::PIP_STEPS).contains(&i);
        let is_up = |i: u8| {
            let up = render::RAMP + render::RAMP_STEPS;
            (up..up + render::RAMP_STEPS).contains(&i)
        };
        let mut seen = vec![false; frame.len()];
        let mut count = 0;
        for start in 0..frame.len() {
            if seen[start] || !is_pip(frame[start]) {
                continue;
            }
            let (mut stack, mut beside_up) = (vec![start], false);
            seen[start] = true;
            while let Some(i) = stack.pop() {
                let (x, y) = (i % width, i / width);
                let around = [
                    (x > 0).then(|| i - 1),
                    (x + 1 < width).then(|| i + 1),
                    (y > 0).then(|| i - width),
                    (i + width < frame.len()).then(|| i + width),
                ];
                for j in around.into_iter().flatten() {
                    if is_up(frame[j]) {
                        beside_up = true;
                    }
                    if !seen[j] && is_pip(frame[j]) {
                        seen[j] = true;
                        stack.push(j);
                    }
                }
            }
            count += usize::from(beside_up);
        }
        count
    }

    /// Rows from the top of the die's pixels to their bottom in `frame` (the die's own ramps
    /// and the pair's, its pips), below the caption band.
    fn die_rows(frame: &[u8], width: usize) -> usize {
        let die = |i: u8| {
            let ramp =
                |r: u8| render::RAMP + r * render::RAMP_STEPS..render::RAMP + (r + 1) * render::RAMP_STEPS;
            ramp(0).contains(&i)
                || ramp(1).contains(&i)
                || ramp(render::PAIR_RAMP).contains(&i)
                || ramp(render::PAIR_RAMP + 1).contains(&i)
        };
        let rows: Vec<usize> = (0..frame.len() / width)
            .filter(|&y| frame[y * width..(y + 1) * width].iter().any(|&i| die(i)))
            .collect();
        rows.last().map_or(0, |last| last + 1 - rows[0])
    }

    /// Is palette index `i` part of a die (its shades, the pair's, a pip, an edge or a
    /// corner's contact mark)?
    fn on_a_die(i: u8) -> bool {
        i == render::EDGE
            || i == render::CONTACT
            || (render::PIP..render::PIP + render::PIP_STEPS).contains(&i)
            || (render::RAMP..=u8::MAX).contains(&i)
    }

    /// Is palette index `i` the table (a tile, in light or in the shadow)?
    fn on_the_table(i: u8) -> bool {
        (render::TILE_LIGHT..=render::SHADOW_DARK).contains(&i)
    }

    /// Rows of the caption band at the top of `frame` (its left column is the band's white).
    fn band_rows(frame: &[u8], width: usize) -> usize {
        frame
            .chunks(width)
            .take_while(|row| row[0] == render::BAND)
            .count()
    }

    /// The box round the pixels of `frame` that `pick` picks: left, top, right, bottom.
    fn pixel_box(
        frame: &[u8],
        width: usize,
        pick: impl Fn(u8) -> bool,
    ) -> Option<(usize, usize, usize, usize)> {
        let mut b: Option<(usize, usize, usize, usize)> = None;
        for (k, _) in frame.iter().enumerate().filter(|(_, i)| pick(**i)) {
            let (x, y) = (k % width, k / width);
            b = Some(b.map_or((x, y, x, y), |(l, t, r, d)| {
                (l.min(x), t.min(y), r.max(x), d.max(y))
            }));
        }
        b
    }

    /// `--zoom` frames the whole drop: in every frame the die is whole inside the picture
    /// (no pixel of it on the frame's edge or in the caption band) with the table visible
    /// below it, so the first frame shows the die high above the table (and its shadow on
    /// it); the camera closes in as it falls, to the die at a third of the frame's height
    /// at the end, where the whole-path view leaves it far smaller. `--face-pair 2`
    /// colours faces 2 and 5.
    #[test]
    fn a_zoomed_animation_frames_the_whole_drop_and_colours_its_face_pair() {
        let (params, initial) = paper();
        let (w, h) = (480usize, 360usize);
        let spec = AnimationSpec {
            zoom: true,
            face_pair: Some(5),
            ..AnimationSpec::new(10, (w as u32, h as u32))
        };
        let (bytes, _) = animate(&params, &initial, &spec, "gif");
        let frames = gif_frames(&bytes);
        let mut heights = Vec::new();
        for (k, f) in frames.iter().enumerate() {
            let band = band_rows(f, w);
            let (left, top, right, bottom) = pixel_box(f, w, on_a_die).expect("the die is drawn");
            assert!(
                left > 0 && right < w - 1 && top > band && bottom < h - 1,
                "frame {k}: the die at x {left}..{right}, y {top}..{bottom}, the picture x 1..{}, y {}..{}",
                w - 2,
                band + 1,
                h - 2
            );
            let table_below = (bottom + 1..h).any(|y| (left..=right).any(|x| on_the_table(f[y * w + x])));
            assert!(table_below, "frame {k}: no table below the die");
            heights.push(bottom + 1 - top);
        }
        // The drop: in the first frame the die is 15 cm up, its shadow on the table far below.
        let first = &frames[0];
        let die = pixel_box(first, w, on_a_die).unwrap();
        let shadow = pixel_box(first, w, |i| {
            i == render::SHADOW_LIGHT || i == render::SHADOW_DARK
        })
        .expect("the shadow in the first frame");
        assert!(
            shadow.3 < h - 1,
            "the whole shadow in the picture, rows {}..{}",
            shadow.1,
            shadow.3
        );
        assert!(
            shadow.1 > die.3 + 2 * heights[0],
            "the shadow (rows {}..{}) two dice below the die (rows {}..{})",
            shadow.1,
            shadow.3,
            die.1,
            die.3
        );
        // Closing in: the die grows as it comes down, to a third of the frame's height.
        let last = *heights.last().unwrap();
        assert!(heights[0] * 3 < last, "{heights:?}");
        assert!(last * 3 >= h, "the die {last} of {h} rows at the end");
        let whole = gif_frames(
            &animate(
                &params,
                &initial,
                &AnimationSpec::new(10, (w as u32, h as u32)),
                "gif",
            )
            .0,
        );
        assert!(
            die_rows(whole.last().unwrap(), w) * 3 < h,
            "the whole path's view is wider"
        );
        for r in [render::PAIR_RAMP, render::PAIR_RAMP + 1] {
            let ramp = render::RAMP + r * render::RAMP_STEPS..render::RAMP + (r + 1) * render::RAMP_STEPS;
            assert!(
                frames.iter().any(|f| f.iter().any(|i| ramp.contains(i))),
                "ramp {r} of the pair in some frame"
            );
        }
        let comments = gif_comments(&bytes).join("\n");
        assert!(
            comments.contains("\"face_pair\":2") && comments.contains("\"zoom\":true"),
            "{comments}"
        );
        let bad = AnimationSpec {
            face_pair: Some(7),
            ..spec
        };
        assert_eq!(
            bad.face_pair_on(&params).unwrap_err(),
            "the box's faces are 1 to 6"
        );
    }

    /// A drop of many die sides (4 m) starts as wide (the die and the table below it in
    /// the first frame) and closes in: from [`render::CLOSE_IN_S`] of playback on, the die
    /// is at least its side ([`render::DIE_AT_LEAST`] of the picture for its bounding
    /// sphere, √3 sides across) high, and whole inside the picture in every frame.
    #[test]
    fn a_tall_zoomed_drop_closes_in_on_the_die() {
        // (The fall takes 0.9 s, 9 s played, the die 3 m up when the camera has closed in.)
        let (params, mut initial) = paper();
        initial.height = 400.0;
        let (w, h) = (320usize, 240usize);
        // At 1/10×, so the die is still high when the camera has closed in.
        let spec = AnimationSpec {
            zoom: true,
            speed: 0.1,
            ..AnimationSpec::new(2, (w as u32, h as u32))
        };
        let (bytes, _) = animate(&params, &initial, &spec, "gif");
        let frames = gif_frames(&bytes);
        let margin = (render::caption_sizes(w as u32, h as u32).0 * 0.6).round() as usize;
        let film = film(
            "paper",
            &params,
            &initial,
            &spec,
            &AtomicBool::new(false),
            &mut |_| {},
        )
        .unwrap();
        for (k, f) in frames.iter().enumerate() {
            let band = band_rows(f, w);
            let (left, top, right, bottom) = pixel_box(f, w, on_a_die).expect("the die is drawn");
            assert!(
                left > 0 && right < w - 1 && top > band && bottom < h - 1,
                "frame {k}: the die at x {left}..{right}, y {top}..{bottom}"
            );
            let picture = (h - band - 2 * margin) as f64;
            let least = render::DIE_AT_LEAST * picture / 3f64.sqrt();
            let rows = (bottom + 1 - top) as f64;
            if film.times[k] / spec.speed >= render::CLOSE_IN_S {
                assert!(
                    rows >= least - 1.0,
                    "frame {k}: the die {rows} rows, {least} at least"
                );
            }
            if k == 0 {
                assert!(rows * 4.0 < least, "the first frame is wide: the die {rows} rows");
                let table_below = (bottom + 1..h).any(|y| (0..w).any(|x| on_the_table(f[y * w + x])));
                assert!(table_below, "the first frame shows the table");
            }
        }
    }

    /// The rows of the first text line in `frame`'s band that hold ink (text pixels at
    /// least half covered): from its capitals' tops to its descenders.
    fn first_line_ink_rows(frame: &[u8], width: usize) -> usize {
        let inked = |row: &[u8]| {
            row.iter().any(|&i| {
                (render::TEXT + render::TEXT_STEPS / 2..render::TEXT + render::TEXT_STEPS).contains(&i)
            })
        };
        let rows: Vec<&[u8]> = frame.chunks(width).take(band_rows(frame, width)).collect();
        let start = rows.iter().position(|r| inked(r)).expect("a headline");
        rows[start..].iter().take_while(|r| inked(r)).count()
    }

    /// The captions grow with the frame: the headline's ink is as many times taller as the
    /// frame is, and at least the em of 24-point type on a 7.5-inch slide, 1/22.5 of the
    /// frame's height (DejaVu Sans Bold's `f` and `t` reach 0.76 em up and `p` 0.24 em down:
    /// an em, less a pixel at either end where the ink covers under half a pixel), at every
    /// size from 400×300 to a 1600×1200 projector's frame.
    #[test]
    fn captions_grow_with_the_frame_and_read_from_the_back_row() {
        let (params, initial) = paper();
        let mut ink = Vec::new();
        for (w, h) in [(400usize, 300usize), (800, 600), (1600, 1200)] {
            let spec = AnimationSpec::new(1, (w as u32, h as u32));
            let (bytes, _) = animate(&params, &initial, &spec, "gif");
            let first = &gif_frames(&bytes)[0];
            let rows = first_line_ink_rows(first, w);
            assert!(
                rows as f64 + 2.0 >= h as f64 / 22.5,
                "{w}×{h}: the headline {rows} rows high"
            );
            ink.push(rows as f64);
        }
        for pair in ink.windows(2) {
            let ratio = pair[1] / pair[0];
            assert!(
                (1.8..=2.2).contains(&ratio),
                "twice the frame, the headline {ratio}× as tall: {ink:?}"
            );
        }
    }

    #[test]
    fn the_last_frame_shows_the_face_the_roll_ends_on() {
        // Seen from nearly straight above, so each pip of the face up is a disc of its own.
        let (params, paper) = paper();
        let spun = InitialCondition {
            angular_velocity: [30.0, 5.0, -10.0],
            ..paper
        };
        for (name, initial) in [("paper", paper), ("spun", spun)] {
            let (outcome, _) = roll(&params, &initial).unwrap();
            let face = outcome.face.expect("these rolls settle on a face");
            let mut spec = AnimationSpec::new(10, (480, 360));
            spec.camera = Camera {
                yaw_deg: 0.0,
                pitch_deg: 85.0,
            };
            let (bytes, _) = animate(&params, &initial, &spec, "gif");
            let frames = gif_frames(&bytes);
            let last = frames.last().unwrap();
            assert_eq!(
                pips_on_the_up_face(last, 480),
                usize::from(face),
                "{name}: face {face}"
            );
            // And the outcome the file records is the physics' own.
            let comments = gif_comments(&bytes);
            let recorded = comments
                .iter()
                .find_map(|c| c.strip_prefix("dicesim-outcome: "))
                .unwrap();
            let v: serde_json::Value = serde_json::from_str(recorded).unwrap();
            assert_eq!(v["die"]["face"], serde_json::json!(face), "{name}");
            assert_eq!(v["frames"], serde_json::json!(frames.len()));
        }
    }

    /// A d20 (the shipped preset's die and step) thrown as the paper's throw.
    fn d20() -> (Params, InitialCondition) {
        let (mut params, initial) = paper();
        params.die.kind = dicesim_physics::Solid::D20;
        params.integrator.dt = 0.00025;
        (params, initial)
    }

    /// A d20 seen from nearly straight above at the end of its roll: the face up is tinted and
    /// its number inked inside it, centred on it (the ink's centroid within a tenth of the
    /// tinted triangle's width of its centroid), and the faces round it carry their numbers
    /// too (more ink outside the face up than in it); the file records the roll's own end.
    #[test]
    fn a_d20_shows_the_number_of_its_face_up_on_that_face() {
        let (params, initial) = d20();
        let mut roll = Roll::new(&params, &initial).unwrap();
        let outcome = roll.run_to_end();
        assert!(outcome.face.is_some(), "{outcome:?}");
        let (w, h) = (480usize, 360usize);
        let spec = AnimationSpec {
            zoom: true,
            camera: Camera {
                yaw_deg: 0.0,
                pitch_deg: 85.0,
            },
            ..AnimationSpec::new(10, (w as u32, h as u32))
        };
        let (bytes, animated) = animate(&params, &initial, &spec, "gif");
        assert_eq!(animated.outcome.face, outcome.face);
        assert_eq!(animated.outcome.steps, outcome.steps);
        let last = gif_frames(&bytes).pop().unwrap();
        let up = render::RAMP + render::RAMP_STEPS..render::RAMP + 2 * render::RAMP_STEPS;
        let ink = |i: u8| (render::PIP..render::PIP + render::PIP_STEPS).contains(&i);
        let pixels = |pick: &dyn Fn(usize, usize) -> bool| -> Vec<(f64, f64)> {
            (0..w * h)
                .map(|k| (k % w, k / w))
                .filter(|&(x, y)| pick(x, y))
                .map(|(x, y)| (x as f64, y as f64))
                .collect()
        };
        let tinted = pixels(&|x, y| up.contains(&last[y * w + x]));
        assert!(tinted.len() > 500, "the face up: {} pixels", tinted.len());
        let (left, right) = tinted
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, r), p| {
                (l.min(p.0), r.max(p.0))
            });
        // Ink inside the face up: ink pixels with tinted pixels on either side along the row.
        let inside = |x: usize, y: usize| {
            let row = &last[y * w..(y + 1) * w];
            row[..x].iter().any(|i| up.contains(i)) && row[x..].iter().any(|i| up.contains(i))
        };
        let number = pixels(&|x, y| ink(last[y * w + x]) && inside(x, y));
        let others = pixels(&|x, y| ink(last[y * w + x]) && !inside(x, y));
        assert!(
            number.len() > 30,
            "the number on the face up: {} pixels",
            number.len()
        );
        let mean = |p: &[(f64, f64)]| {
            let n = p.len() as f64;
            (
                p.iter().map(|q| q.0).sum::<f64>() / n,
                p.iter().map(|q| q.1).sum::<f64>() / n,
            )
        };
        let (face, text) = (mean(&tinted), mean(&number));
        let off = ((face.0 - text.0).powi(2) + (face.1 - text.1).powi(2)).sqrt();
        assert!(
            off < 0.1 * (right - left),
            "the number {off} px off the face's centre"
        );
        assert!(
            others.len() > number.len(),
            "{} inked pixels off the face up",
            others.len()
        );
    }

    /// `--face-pair 3` on a d20 colours the face printed 3 and the one printed 18 (3 + 18 =
    /// 21) in the pair's two colours; the d4 has no pair to mark.
    #[test]
    fn a_d20_colours_its_face_pair_and_a_d4_has_none() {
        let (params, initial) = d20();
        // Every 20 ms, so the tumbling shows each face of the pair.
        let spec = AnimationSpec {
            face_pair: Some(18),
            zoom: true,
            ..AnimationSpec::new(50, (200, 150))
        };
        assert_eq!(spec.face_pair_on(&params), Ok(Some((3, 18))));
        let (bytes, _) = animate(&params, &initial, &spec, "gif");
        let frames = gif_frames(&bytes);
        for r in [render::PAIR_RAMP, render::PAIR_RAMP + 1] {
            let ramp = render::RAMP + r * render::RAMP_STEPS..render::RAMP + (r + 1) * render::RAMP_STEPS;
            assert!(
                frames.iter().any(|f| f.iter().any(|i| ramp.contains(i))),
                "ramp {r} of the pair in some frame"
            );
        }
        let comments = gif_comments(&bytes).join("\n");
        assert!(comments.contains("\"face_pair\":3"), "{comments}");
        let mut d4 = params;
        d4.die.kind = dicesim_physics::Solid::D4;
        let two = AnimationSpec {
            face_pair: Some(2),
            ..spec
        };
        assert!(two.face_pair_on(&d4).unwrap_err().contains("no opposite faces"));
        assert_eq!(spec.face_pair_on(&d4).unwrap_err(), "a d4's faces are 1 to 4");
    }

    #[test]
    fn gif_and_apng_show_the_same_frames_and_carry_the_setup() {
        let (params, initial) = paper();
        let spec = AnimationSpec::new(12, (200, 150));
        let (gif_bytes, _) = animate(&params, &initial, &spec, "gif");
        let (png_bytes, _) = animate(&params, &initial, &spec, "png");
        let gif = gif_frames(&gif_bytes);
        // The APNG's frames composited the same way (palette indices, index 0 see-through).
        let mut decoder = png::Decoder::new(std::io::Cursor::new(&png_bytes));
        decoder.set_transformations(png::Transformations::IDENTITY);
        let mut reader = decoder.read_info().unwrap();
        let info = reader.info().clone();
        assert_eq!(info.animation_control.unwrap().num_frames as usize, gif.len());
        let texts: Vec<(String, String)> = info
            .utf8_text
            .iter()
            .map(|t| (t.keyword.clone(), t.get_text().unwrap()))
            .collect();
        let setup = &texts.iter().find(|(k, _)| k == "dicesim-setup").unwrap().1;
        assert!(setup.contains("ground.stiffness = 500000"), "{setup}");
        assert!(
            gif_comments(&gif_bytes)
                .iter()
                .any(|c| c.starts_with("dicesim-setup: preset = \"paper\""))
        );
        let (w, _) = (200usize, 150usize);
        let mut canvas = vec![0u8; 200 * 150];
        let mut buffer = vec![0u8; reader.output_buffer_size().expect("a frame that fits in memory")];
        for (k, expected) in gif.iter().enumerate() {
            let frame = reader.next_frame(&mut buffer).unwrap();
            let fc = reader.info().frame_control.unwrap();
            for row in 0..frame.height as usize {
                for col in 0..frame.width as usize {
                    let i = buffer[row * frame.line_size + col];
                    if i != CLEAR {
                        canvas[(fc.y_offset as usize + row) * w + fc.x_offset as usize + col] = i;
                    }
                }
            }
            assert!(canvas == *expected, "frame {k} differs");
        }
    }

    #[test]
    fn three_seconds_at_640_by_480_stay_under_five_megabytes() {
        // A softly damped table and a higher drop: the die rolls for 3.4 s.
        let (mut params, mut initial) = paper();
        params.ground.damping = 0.0003;
        initial.height = 30.0;
        let mut spec = AnimationSpec::new(25, (640, 480));
        spec.twin = Some(1e-6);
        for ext in EXTENSIONS {
            let (bytes, animated) = animate(&params, &initial, &spec, ext);
            assert!(animated.duration_s >= 3.0, "{} s", animated.duration_s);
            assert!(bytes.len() < 5_000_000, "{ext}: {} bytes", bytes.len());
        }
    }

    #[test]
    fn a_cancelled_animation_writes_nothing() {
        let (params, initial) = paper();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("roll.gif");
        let out = Output::check(&path, &EXTENSIONS, false).unwrap();
        let cancel = AtomicBool::new(false);
        // Cancelled once the frames are being drawn: the write has begun.
        let e = write_animation(
            "paper",
            &params,
            &initial,
            &AnimationSpec::new(25, (160, 120)),
            &out,
            &cancel,
            &mut |p| {
                if p.drawing && p.done >= 3 {
                    cancel.store(true, Ordering::Relaxed);
                }
            },
        )
        .unwrap_err();
        assert_eq!(e, Error::Cancelled);
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }

    #[test]
    fn out_of_range_specs_are_refused_with_their_range() {
        let e = AnimationSpec::new(0, (640, 480)).validate().unwrap_err();
        assert!(e.to_string().contains("0 frames/s: from 1 to 50"), "{e}");
        let mut slow = AnimationSpec::new(25, (640, 480));
        slow.speed = 0.001;
        assert!(
            slow.validate()
                .unwrap_err()
                .to_string()
                .contains("from 0.01× to 100×")
        );
        let e = AnimationSpec::new(25, (10, 480)).validate().unwrap_err();
        assert!(e.to_string().contains("10×480 pixels"), "{e}");
        let mut spec = AnimationSpec::new(25, (640, 480));
        spec.twin = Some(0.5);
        assert!(spec.validate().unwrap_err().to_string().contains("twin.epsilon"));
    }
}
