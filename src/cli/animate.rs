//! `dicesim animate`: a roll (or a roll and its chaos twin) as an animated GIF or PNG, or
//! with `--present` the explorer's presentation view of it.

use super::args::SetupArgs;
use super::error::CliError;
use super::running::{self, cancel_on_ctrl_c};
use super::tui::ThemeArg;
use crate::tables;
use clap::Args;
use dicesim_explorer::tui::{TERMINAL_COLUMNS, TERMINAL_ROWS, Theme, write_presentation};
use dicesim_figures::animation::render::Camera;
use dicesim_figures::animation::terminal::Grid;
use dicesim_figures::animation::{self, AnimationProgress, AnimationSpec, write_animation};
use dicesim_setup::chaos::DEFAULT_EPSILON;
use dicesim_setup::output::Output;
use dicesim_setup::preset::{Preset, Speed, ThemeName, refuse_unapplied};
use dicesim_setup::random::unapplied_when_fixed;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub(crate) struct AnimateArgs {
    #[command(flatten)]
    pub(crate) setup: SetupArgs,
    /// Frames per second of playback, 1 to 50 (at most 10⁴ frames in all: a lower rate or a
    /// faster --speed for a long roll).
    #[arg(long, value_name = "N", default_value_t = 25,
          value_parser = clap::value_parser!(u32).range(*animation::FPS.start() as i64..=*animation::FPS.end() as i64))]
    pub(crate) fps: u32,
    /// Playback speed, as the explorer's ladder: `1/10` plays ten times slower, `2` twice as
    /// fast (default: the preset's `view.speed`, else 1, real time).
    #[arg(long, value_name = "1/100…100")]
    pub(crate) speed: Option<String>,
    /// Width × height in pixels, from 64x64 to 3840x2160.
    #[arg(long, value_name = "WxH", default_value = "640x480", value_parser = parse_size)]
    pub(crate) size: (u32, u32),
    /// Roll a chaos twin beside the die, its height, velocity and spin × (1 + ε) (default:
    /// the preset's `view.twin`, else 1e-9).
    #[arg(long, value_name = "EPSILON", num_args = 0..=1, default_missing_value = "default")]
    pub(crate) twin: Option<String>,
    /// Follow the die with a camera that frames it and the table under it: wide while it
    /// drops, closing in to its side about a third of the frame's height as it lands
    /// (default: the whole path in view, the die small in it).
    #[arg(long)]
    pub(crate) zoom: bool,
    /// Colour the face numbered N and the one opposite it (7 − N on the box, N + 1 less it
    /// on a d8, d12 or d20, 9 less it on a d10) and draw their body axis, e.g. 2 for the
    /// tennis racket's flip of faces 2 and 5 (not on a d4, which has no opposite faces).
    #[arg(long, value_name = "N")]
    pub(crate) face_pair: Option<u8>,
    /// Draw the explorer's presentation view (`P`) instead: the die large over its height
    /// scale, the face up in block digits, the time and a readout, as the terminal shows
    /// them, rasterised at --size pixels.
    #[arg(long, conflicts_with_all = ["zoom", "twin", "face_pair"])]
    pub(crate) present: bool,
    /// With --present: the terminal's columns × rows, from 80x24 to 400x200 (default 80x24,
    /// the projector's).
    #[arg(long, value_name = "COLSxROWS", requires = "present", value_parser = parse_terminal)]
    pub(crate) terminal: Option<(u16, u16)>,
    /// With --present: the theme (default: the preset's, else projector).
    #[arg(long, value_enum, requires = "present")]
    pub(crate) theme: Option<ThemeArg>,
    /// Write the animation to a .gif or an (animated) .png file.
    #[arg(long, value_name = "FILE.gif|FILE.png")]
    pub(crate) out: PathBuf,
    /// Replace an existing file.
    #[arg(long)]
    pub(crate) force: bool,
}

/// `s` as two numbers `AxB` (or `A×B`), each in its range, else what `AxB` should be.
fn parse_pair<T>(
    s: &str,
    what: &str,
    example: &str,
    ranges: (std::ops::RangeInclusive<T>, std::ops::RangeInclusive<T>),
) -> Result<(T, T), String>
where
    T: std::str::FromStr + PartialOrd + std::fmt::Display,
{
    let (a, b) = ranges;
    let bad = || {
        format!(
            "`{s}`: expected {what}, from {}x{} to {}x{}, e.g. {example}",
            a.start(),
            b.start(),
            a.end(),
            b.end()
        )
    };
    let (x, y) = s.split_once(['x', 'X', '×']).ok_or_else(bad)?;
    let x: T = x.trim().parse().map_err(|_| bad())?;
    let y: T = y.trim().parse().map_err(|_| bad())?;
    if !a.contains(&x) || !b.contains(&y) {
        return Err(bad());
    }
    Ok((x, y))
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    parse_pair(
        s,
        "WxH in pixels",
        "640x480",
        (animation::WIDTH, animation::HEIGHT),
    )
}

/// A terminal's size, `COLSxROWS`, in the presentation view's range.
fn parse_terminal(s: &str) -> Result<(u16, u16), String> {
    parse_pair(s, "COLSxROWS", "80x24", (TERMINAL_COLUMNS, TERMINAL_ROWS))
}

/// The animation the arguments ask for, over `preset`'s view; a `--speed` given becomes
/// the view's too (the presentation view's title states the speed it plays at).
fn spec_of(args: &AnimateArgs, preset: &mut Preset) -> Result<AnimationSpec, CliError> {
    let params = preset.params();
    let twin = match args.twin.as_deref() {
        None => None,
        Some("default") => Some(preset.view.twin.unwrap_or(DEFAULT_EPSILON)),
        Some(text) => Some(
            text.trim()
                .parse::<f64>()
                .map_err(|_| CliError::Usage(format!("--twin `{text}`: expected a number, e.g. 1e-9")))?,
        ),
    };
    let speed = match args.speed.as_deref() {
        None => preset.view.speed.and_then(Speed::factor).unwrap_or(1.0),
        Some(label) => {
            let chosen = Speed::from_label(label).filter(|s| s.factor().is_some());
            let chosen = chosen.ok_or_else(|| {
                let ladder: Vec<&str> = Speed::labels().filter(|l| *l != "instant").collect();
                CliError::Usage(format!("--speed `{label}`: one of {}", ladder.join(", ")))
            })?;
            preset.view.speed = Some(chosen);
            chosen.factor().unwrap_or(1.0)
        }
    };
    let camera = preset.view.camera.map_or(Camera::DEFAULT, |c| Camera {
        yaw_deg: c.yaw,
        pitch_deg: c.pitch,
    });
    let spec = AnimationSpec {
        twin,
        camera,
        speed,
        zoom: args.zoom,
        face_pair: args.face_pair,
        ..AnimationSpec::new(args.fps, args.size)
    };
    spec.validate().map_err(CliError::experiment("--twin "))?;
    if let Some(face) = spec.face_pair {
        spec.face_pair_on(&params)
            .map_err(|why| CliError::Usage(format!("--face-pair {face}: {why}")))?;
    }
    Ok(spec)
}

pub(crate) fn run(args: &AnimateArgs) -> Result<(), CliError> {
    let mut preset = args.setup.resolve()?;
    refuse_unapplied(&args.setup.set, |key| unapplied_when_fixed(key, "animate"))?;
    let params = preset.params();
    if args.present {
        // The presentation view is the explorer's, which draws the box only for now.
        dicesim_physics::refuse_polyhedral_die(&params, "`dicesim animate --present` (the explorer's view)")?;
    }
    // The checks `roll` makes: every value in range, no point starting inside the table.
    dicesim_physics::Roll::new(&params, &preset.initial)?;
    let spec = spec_of(args, &mut preset)?;
    let terminal = args.terminal.unwrap_or((80, 24));
    if args.present {
        Grid::legible(args.size, terminal.0, terminal.1)
            .map_err(|e| CliError::Usage(format!("--size {e}")))?;
    }
    let output =
        Output::check(&args.out, &animation::EXTENSIONS, args.force).map_err(CliError::output("--out "))?;

    let bar = running::progress_bar(params.max_steps(), "{msg:14} {bar:40} {pos}/{len}, {elapsed}");
    bar.set_message(if args.present {
        "screens drawn"
    } else {
        "steps rolled"
    });
    let stop = cancel_on_ctrl_c()?;
    let mut progress = |p: AnimationProgress| {
        if bar.length() != Some(p.total) {
            bar.set_length(p.total);
        }
        if p.drawing {
            bar.set_message("frames drawn");
        }
        bar.set_position(p.done);
    };
    let animated = if args.present {
        let theme = args.theme.map(ThemeName::from).or(preset.view.theme);
        preset.view.theme = Some(theme.unwrap_or(ThemeName::Projector));
        write_presentation(
            &preset,
            &spec,
            terminal,
            Theme::default(),
            &output,
            &stop,
            &mut progress,
        )
    } else {
        write_animation(
            &preset.name,
            &params,
            &preset.initial,
            &spec,
            &output,
            &stop,
            &mut progress,
        )
    }
    .map_err(|e| match e {
        dicesim_experiment::Error::Output(e) => CliError::output("")(e),
        dicesim_experiment::Error::Cancelled => {
            CliError::Stopped(format!("{}: nothing was written", args.out.display()))
        }
        e => CliError::experiment("")(e),
    })?;
    bar.finish_and_clear();
    let frames = (args.fps, args.size);
    tables::animation(
        &mut std::io::stdout().lock(),
        &animated,
        spec.twin,
        spec.speed,
        frames,
        &args.out,
    )?;
    Ok(())
}
