//! Basin maps as PNG or SVG images a teacher can put on a slide.
//!
//! Text is measured with the DejaVu Sans font embedded in the binary, so drawing needs no
//! system fonts (and the SVG names `sans-serif`, which viewers resolve themselves).

use crate::figure::{DEJAVU_SANS, Ticks, resolved, setup_value, wrap};
use dicesim_experiment::Error;
use dicesim_experiment::basin::{BasinMap, Cell, Layer};
use dicesim_experiment::ending::Ending;
use dicesim_physics::{InitialCondition, Params, Status};
use dicesim_setup::keys::ScanKey;
use dicesim_setup::output::Output;
use dicesim_setup::registry::{self, Role, Setup, Value};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::register_font;
use std::sync::OnceLock;

/// Image size in pixels (SVG user units).
pub const SIZE: (u32, u32) = (1200, 800);
/// Width of the legend strip on the right.
const LEGEND_WIDTH: u32 = 200;

/// The colours of a die's faces, by place in its list of numbers
/// ([`Die::face_numbers`](dicesim_physics::Die::face_numbers)): the first six Okabe–Ito's
/// (the cube's faces 1..6, distinguishable with the common colour-vision deficiencies), then
/// Paul Tol's muted and light schemes for a d8 to a d20, none of them a grey or pink the
/// endings without a face use. Past 20 faces [`face_colour`] turns the hue by the golden angle.
pub const FACE_COLOURS: [RGBColor; 20] = [
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 158, 115),
    RGBColor(240, 228, 66),
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(51, 34, 136),
    RGBColor(17, 119, 51),
    RGBColor(136, 34, 85),
    RGBColor(153, 153, 51),
    RGBColor(68, 170, 153),
    RGBColor(170, 68, 153),
    RGBColor(221, 204, 119),
    RGBColor(136, 204, 238),
    RGBColor(204, 102, 119),
    RGBColor(187, 204, 51),
    RGBColor(119, 170, 221),
    RGBColor(238, 136, 102),
    RGBColor(68, 187, 153),
    RGBColor(255, 170, 187),
];

/// The colour of the face at place `k` of its die's list of numbers: [`FACE_COLOURS`], then
/// hues a golden angle apart at fixed saturation and lightness.
pub fn face_colour_at(k: usize) -> RGBColor {
    match FACE_COLOURS.get(k) {
        Some(&c) => c,
        None => {
            let hue = ((k - FACE_COLOURS.len()) as f64 * 137.507_764) % 360.0;
            let c = HSLColor(hue / 360.0, 0.6, 0.5).to_rgba();
            RGBColor(c.0, c.1, c.2)
        }
    }
}

/// The colour of `face` on a die that shows `numbers` ([`face_colour_at`] its place); a
/// number it does not show (which no map of it holds) in the no-face grey.
pub fn face_colour(numbers: &[u8], face: u8) -> RGBColor {
    numbers
        .iter()
        .position(|&n| n == face)
        .map_or(NO_FACE, face_colour_at)
}
const NO_FACE: RGBColor = RGBColor(200, 200, 200);
const TIMEOUT: RGBColor = RGBColor(90, 90, 90);
const UNSTABLE: RGBColor = RGBColor(204, 121, 167);
const UNKNOWN: RGBColor = WHITE;
/// A settle-time cell the adaptive method filled in from its block instead of rolling: its
/// face is known, its time is not.
const INFERRED: RGBColor = RGBColor(215, 215, 215);
/// What the legend calls such a cell.
pub const INFERRED_WORDS: &str = "not rolled (filled in)";

/// Viridis at 0, ¼, ½, ¾, 1: a perceptually even scale for settle times.
const VIRIDIS: [RGBColor; 5] = [
    RGBColor(68, 1, 84),
    RGBColor(59, 82, 139),
    RGBColor(33, 145, 140),
    RGBColor(94, 201, 98),
    RGBColor(253, 231, 37),
];

pub(crate) fn viridis(t: f64) -> RGBColor {
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
    let x = t * (VIRIDIS.len() - 1) as f64;
    let k = (x.floor() as usize).min(VIRIDIS.len() - 2);
    let f = x - k as f64;
    let (a, b) = (VIRIDIS[k], VIRIDIS[k + 1]);
    let mix = |p: u8, q: u8| (p as f64 + (q as f64 - p as f64) * f).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

pub(crate) fn register_fonts() -> Result<(), Error> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            let [regular, bold] = DEJAVU_SANS;
            register_font("sans-serif", FontStyle::Normal, regular)
                .and_then(|_| register_font("sans-serif", FontStyle::Bold, bold))
                .map_err(|_| "the embedded DejaVu Sans font is not a valid font".to_string())
        })
        .clone()
        .map_err(Error::Plot)
}

pub(crate) fn plot_error(e: impl std::fmt::Display) -> Error {
    Error::Plot(e.to_string())
}

/// An image file format the plots are drawn in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    Png,
    Svg,
}

impl ImageFormat {
    /// The format for a file extension (`png` or `svg`, any case).
    pub(crate) fn from_extension(extension: &str) -> Option<ImageFormat> {
        match extension.to_ascii_lowercase().as_str() {
            "png" => Some(ImageFormat::Png),
            "svg" => Some(ImageFormat::Svg),
            _ => None,
        }
    }
}

/// What an image records of how it was made: caption lines drawn under the picture, and
/// text chunks (keyword, text) a PNG carries for any viewer or script to read.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Record {
    pub caption: Vec<String>,
    pub text: Vec<(String, String)>,
}

/// Pixels one caption line takes.
const CAPTION_LINE: u32 = 24;

/// How much larger than its design size an image is drawn: every length, font and margin
/// is multiplied by it, so a poster-sized map reads like the screen-sized one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Scale(pub(crate) f64);

impl Scale {
    /// Drawn at the size it was designed for.
    pub(crate) const ONE: Scale = Scale(1.0);

    /// The scale of an image `size` pixels large, designed at `design` (by height, the
    /// dimension the text stacks along; never below half size).
    pub(crate) fn of(size: (u32, u32), design: (u32, u32)) -> Scale {
        Scale((f64::from(size.1) / f64::from(design.1)).max(0.5))
    }

    /// `pixels` of the design size, at this scale.
    pub(crate) fn px(self, pixels: i32) -> i32 {
        (f64::from(pixels) * self.0).round() as i32
    }
}

impl Record {
    /// A figure's record: its title, its caption (drawn under the picture and, joined, the
    /// PNG's description) and the `software` that drew it.
    pub fn captioned(title: String, caption: Vec<String>, software: &str) -> Record {
        Record {
            text: vec![
                ("Title".to_string(), title),
                ("Description".to_string(), caption.join("\n")),
                ("Software".to_string(), software.to_string()),
            ],
            caption,
        }
    }

    /// The record of a setup: the caption names the values a reader looks for first, the
    /// `dicesim-setup` chunk holds every value, one `key = value` per line, as a preset
    /// file writes them.
    pub fn of_setup(title: &str, name: &str, params: &Params, initial: &InitialCondition) -> Record {
        Record::of_setup_varying(title, name, params, initial, &[])
    }

    /// [`Record::of_setup`] for a figure that varies the values `varied` (keys, a vector's
    /// components among them: a map's axes): its caption never states them, since the
    /// figure's axes or legend do (a varied component is written as its symbol, `(ωx, ωy,
    /// 6)`); the `dicesim-setup` chunk still holds the setup every figure starts from.
    pub fn of_setup_varying(
        title: &str,
        name: &str,
        params: &Params,
        initial: &InitialCondition,
        varied: &[&str],
    ) -> Record {
        let n = setup_value;
        let w = initial.angular_velocity_for(params.inertia());
        let mut values = Vec::new();
        if shown(varied, "initial.height") {
            values.push(format!("height {} cm", n(initial.height)));
        }
        for (what, key, v, unit) in [
            ("velocity", "initial.velocity", initial.velocity, " cm/s"),
            ("spin", "initial.angular_velocity", w.into(), " rad/s"),
            ("yaw pitch roll", "initial.orientation", initial.orientation, "°"),
        ] {
            values.push(format!("{what} {}{unit}", components(varied, key, v)));
        }
        let caption = vec![
            format!("{name}: {}", values.join(", ")),
            format!(
                "{} (every value in the file's dicesim-setup text)",
                body_line(params, varied)
            ),
        ];
        let mut record = Record::captioned(title.to_string(), caption, dicesim_experiment::BUILD);
        record
            .text
            .push(("dicesim-setup".to_string(), setup_text(name, params, initial)));
        record
    }
}

/// Whether the value `key` is stated: neither it nor a component of it is `varied`.
fn shown(varied: &[&str], key: &str) -> bool {
    !varied
        .iter()
        .any(|v| *v == key || v.strip_prefix(key).is_some_and(|rest| rest.starts_with('.')))
}

/// A vector value as a caption writes it, `(30, 0, 0)`, each varied component as the
/// symbol the explorer's words end in (`ωy` of `spin ωy`).
fn components(varied: &[&str], key: &str, v: [f64; 3]) -> String {
    let prefix = format!("{key}.");
    let keys: Vec<&ScanKey> = ScanKey::all()
        .iter()
        .filter(|k| k.key.starts_with(&prefix))
        .collect();
    let parts: Vec<String> = (0..3)
        .map(|i| match keys.iter().find(|k| k.component == i) {
            Some(k) if varied.contains(&k.key.as_str()) => {
                k.words().rsplit(' ').next().unwrap_or(&k.key).to_string()
            }
            _ => setup_value(v[i]),
        })
        .collect();
    format!("({})", parts.join(", "))
}

/// The table, die, gravity and time step as a caption names them, but for the `varied`
/// keys the figure shows; a loaded die says where its extra masses are ("loaded: +0.5 g
/// at corner 8").
fn body_line(params: &Params, varied: &[&str]) -> String {
    let n = setup_value;
    let extras: Vec<String> = (params.die.extra_corner_mass.iter().enumerate())
        .filter(|&(_, &m)| m > 0.0)
        .map(|(k, &m)| format!("+{} g at corner {}", n(m), k + 1))
        .collect();
    let loaded = if extras.is_empty() || !shown(varied, "die.extra_corner_mass") {
        String::new()
    } else {
        format!(", loaded: {}", extras.join(", "))
    };
    let stated = |parts: &[(&str, String)]| {
        parts
            .iter()
            .filter(|(key, _)| shown(varied, key))
            .map(|(_, text)| text.clone())
            .collect::<Vec<_>>()
            .join(", ")
    };
    let table = stated(&[
        (
            "ground.stiffness",
            format!("k {} dyn/cm", n(params.ground.stiffness)),
        ),
        ("ground.damping", format!("γ {} s/cm", n(params.ground.damping))),
        ("ground.friction", format!("μ {}", n(params.ground.friction))),
    ]);
    // A polyhedral die is its kind, height and material; the box's keys describe no part of it.
    let die = match params.die.is_polyhedral() {
        true => format!(
            "{} {}",
            params.die.kind.name(),
            stated(&[
                ("die.height", format!("{} cm across", n(params.die.height))),
                ("die.density", format!("{} g/cm³", n(params.die.density))),
            ])
        ),
        false => stated(&[
            ("die.half_sizes", format!("a {} cm", n(params.die.half_size()))),
            ("die.corner_mass", format!("m {} g", n(params.die.corner_mass))),
        ]),
    };
    let world = stated(&[
        ("world.gravity", format!("g {} cm/s²", n(params.world.gravity))),
        ("integrator.dt", format!("Δt {} s", n(params.integrator.dt))),
    ]);
    format!("table {table}; die {die}{loaded}; {world}")
}

impl Record {
    /// The record of an experiment over many starts (a prediction drawn from the random
    /// ranges): the caption says what defines it (`experiment`, a line) and the body it
    /// rolls but for the `varied` keys its curves differ by; the `dicesim-provenance` text
    /// holds every value, the ranges included, as the JSON its CSV starts with.
    pub fn of_experiment(
        title: &str,
        experiment: String,
        params: &Params,
        varied: &[&str],
        provenance: &serde_json::Value,
    ) -> Record {
        let caption = vec![
            experiment,
            format!(
                "{} (every value in the file's dicesim-provenance text)",
                body_line(params, varied)
            ),
        ];
        Record::captioned(title.to_string(), caption, dicesim_experiment::BUILD).with_provenance(provenance)
    }

    /// The record with `provenance` (program, setup, what defines the experiment) as the
    /// `dicesim-provenance` text: the JSON a CSV of the same experiment starts with.
    pub fn with_provenance(mut self, provenance: &serde_json::Value) -> Record {
        self.text
            .push(("dicesim-provenance".to_string(), provenance.to_string()));
        self
    }
}

/// Random starts as a caption names them: the seed and each range (`height 15 cm` where
/// the range is one value) but for those the figure's curves vary (`varied` keys: the drop
/// height by `initial.height` or `random.height`), and the orientation.
pub fn random_starts(r: &dicesim_physics::RandomRanges, seed: u64, varied: &[&str]) -> String {
    let range = |[lo, hi]: [f64; 2], unit: &str| {
        if lo == hi {
            format!("{} {unit}", setup_value(lo))
        } else {
            format!("{}…{} {unit}", setup_value(lo), setup_value(hi))
        }
    };
    let orientation = if r.random_orientation {
        "any orientation".to_string()
    } else if r.orientation_spread > 0.0 {
        format!(
            "the preset's orientation turned by up to {}°",
            setup_value(r.orientation_spread)
        )
    } else {
        "the preset's orientation".to_string()
    };
    let height_varies = !shown(varied, "initial.height") || !shown(varied, "random.height");
    let mut parts = Vec::new();
    if !height_varies {
        parts.push(format!("height {}", range(r.height, "cm")));
    }
    let mut each = Vec::new();
    for (key, what, values, unit) in [
        ("random.velocity", "velocity", r.velocity, "cm/s"),
        ("random.angular_velocity", "spin", r.angular_velocity, "rad/s"),
    ] {
        if shown(varied, key) {
            each.push(format!("{what} {}", range(values, unit)));
        }
    }
    if !each.is_empty() {
        parts.push(format!("{} each component", each.join(" and ")));
    }
    parts.push(orientation);
    format!("drawn with seed {seed}: {}", parts.join(", "))
}

/// Every value of a setup (but the random ranges, which no single roll uses), one
/// `key = value` per line, after the preset's name.
pub(crate) fn setup_text(name: &str, params: &Params, initial: &InitialCondition) -> String {
    let setup = Setup {
        params: *params,
        initial: *initial,
        ..Setup::default()
    };
    let mut lines = vec![format!("preset = \"{name}\"")];
    for spec in registry::ALL.iter().filter(|s| s.role != Role::Random) {
        let value = match (spec.read)(&setup) {
            Value::Number(x) => format!("{x}"),
            Value::Vector(v) => format!("[{}, {}, {}]", v[0], v[1], v[2]),
            Value::Range(r) => format!("[{}, {}]", r[0], r[1]),
            Value::PerCorner(v) => format!("[{}]", v.map(|x| x.to_string()).join(", ")),
            Value::List(list) => list.text(|x| x.to_string()),
            Value::Name(s) => format!("\"{s}\""),
            Value::Seed(s) => format!("{s}"),
            Value::Flag(b) => format!("{b}"),
            Value::Absent => continue,
        };
        lines.push(format!("{} = {value}", spec.key()));
    }
    lines.join("\n")
}

/// Draws with `draw` on a PNG canvas of `size` pixels and returns the encoded file with the
/// record's text chunks. Drawing into memory keeps every write error with the one place
/// that writes files.
pub(crate) fn png_bytes(
    size: (u32, u32),
    record: &Record,
    draw: impl FnOnce(DrawingArea<BitMapBackend<'_>, Shift>) -> Result<(), Error>,
) -> Result<Vec<u8>, Error> {
    let mut pixels = vec![0u8; size.0 as usize * size.1 as usize * 3];
    draw(BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area())?;
    let mut png = Vec::new();
    let mut encoder = png::Encoder::new(&mut png, size.0, size.1);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_pixel_dims(Some(png::PixelDimensions {
        xppu: PIXELS_PER_METRE,
        yppu: PIXELS_PER_METRE,
        unit: png::Unit::Meter,
    }));
    // iTXt: UTF-8, for the model's own symbols (μ, Δt, ω).
    for (keyword, text) in &record.text {
        encoder
            .add_itxt_chunk(keyword.clone(), text.clone())
            .map_err(plot_error)?;
    }
    let mut writer = encoder.write_header().map_err(plot_error)?;
    writer.write_image_data(&pixels).map_err(plot_error)?;
    writer.finish().map_err(plot_error)?;
    Ok(png)
}

/// The resolution a PNG states (its pHYs chunk), pixels per metre: 150 per inch, so a
/// figure of the design width (1200 pixels) prints 20.3 cm wide.
pub const PIXELS_PER_METRE: u32 = 5906;

/// `svg` with the record's text as its `<title>`, `<desc>` and `<metadata>` (every keyword
/// and text, the provenance among them), right after the opening `<svg …>` tag: what a PNG
/// carries in its text chunks, for any viewer or script to read.
pub(crate) fn with_svg_metadata(svg: &str, record: &Record) -> String {
    let escape = |t: &str| {
        t.replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;")
            .replace('"', "&quot;")
    };
    let text = |keyword: &str| {
        (record.text.iter())
            .find(|(k, _)| k == keyword)
            .map(|(_, t)| escape(t))
            .unwrap_or_default()
    };
    let mut head = format!(
        "<title>{}</title><desc>{}</desc><metadata><record xmlns=\"urn:dicesim:record\">",
        text("Title"),
        text("Description")
    );
    for (keyword, value) in &record.text {
        head.push_str(&format!(
            "<entry keyword=\"{}\">{}</entry>",
            escape(keyword),
            escape(value)
        ));
    }
    head.push_str("</record></metadata>");
    let at = svg
        .find("<svg")
        .and_then(|start| svg[start..].find('>').map(|end| start + end + 1))
        .unwrap_or(0);
    format!("{}{head}{}", &svg[..at], &svg[at..])
}

/// Pixels per em of caption text, at the design size.
const CAPTION_FONT: i32 = 16;
/// Pixels left of (and kept right of) a caption line, at the design size.
const CAPTION_MARGIN: i32 = 20;

/// The record's caption as drawn across an image `width` pixels wide: each line wrapped
/// at spaces to fit between the margins, never cut.
pub(crate) fn caption_lines(record: &Record, width: u32, scale: Scale) -> Vec<String> {
    let px = f64::from(scale.px(CAPTION_FONT));
    let room = f64::from(width) - 2.0 * f64::from(scale.px(CAPTION_MARGIN));
    record
        .caption
        .iter()
        .flat_map(|line| wrap(line, px, room, false))
        .collect()
}

/// Draws the record's caption lines along the bottom of `root` and returns the area above.
pub(crate) fn with_caption<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    record: &Record,
    scale: Scale,
) -> Result<DrawingArea<DB, Shift>, Error> {
    if record.caption.is_empty() {
        return Ok(root.clone());
    }
    let (width, height) = root.dim_in_pixel();
    let lines = caption_lines(record, width, scale);
    let line_px = scale.px(CAPTION_LINE as i32) as u32;
    let strip = line_px * lines.len() as u32 + scale.px(10) as u32;
    let (picture, caption) = root.split_vertically(height.saturating_sub(strip));
    for (k, line) in lines.iter().enumerate() {
        caption
            .draw(&Text::new(
                line.as_str(),
                (
                    scale.px(CAPTION_MARGIN),
                    scale.px(2) + (line_px * k as u32) as i32,
                ),
                ("sans-serif", scale.px(CAPTION_FONT)),
            ))
            .map_err(plot_error)?;
    }
    Ok(picture)
}

/// Writes `map` to `out` as a PNG or SVG image, by its extension, recording the setup its
/// cells start from (`name`, params and initial condition) and `provenance` (the JSON the
/// map's CSV starts with); nothing is written if drawing fails.
pub fn write_image(
    map: &BasinMap,
    layer: Layer,
    setup: (&str, &Params, &InitialCondition),
    provenance: &serde_json::Value,
    out: &Output,
) -> Result<(), Error> {
    let record = map_record(map, layer, Some(setup)).with_provenance(provenance);
    write_recorded_image(map, layer, &record, SIZE, out)
}

/// The bytes [`write_image`] writes to `out`, for a caller that writes them with others.
pub fn image_file_bytes(
    map: &BasinMap,
    layer: Layer,
    setup: (&str, &Params, &InitialCondition),
    provenance: &serde_json::Value,
    out: &Output,
) -> Result<Vec<u8>, Error> {
    let record = map_record(map, layer, Some(setup)).with_provenance(provenance);
    let format = ImageFormat::from_extension(out.extension())
        .ok_or_else(|| Error::Plot(format!("{}: expected a .png or .svg file", out.path().display())))?;
    image_bytes(map, layer, &record, SIZE, format)
}

/// [`write_image`] at `size` pixels, with `record`'s caption and (for a PNG) text chunks.
pub(crate) fn write_recorded_image(
    map: &BasinMap,
    layer: Layer,
    record: &Record,
    size: (u32, u32),
    out: &Output,
) -> Result<(), Error> {
    let format = ImageFormat::from_extension(out.extension())
        .ok_or_else(|| Error::Plot(format!("{}: expected a .png or .svg file", out.path().display())))?;
    out.write_bytes(&image_bytes(map, layer, record, size, format)?)?;
    Ok(())
}

/// A map's record: its title and axes, and the setup its cells start from when known
/// (`name`, params and initial condition; the two axis values vary per cell).
pub fn map_record(map: &BasinMap, layer: Layer, setup: Option<(&str, &Params, &InitialCondition)>) -> Record {
    let axes = format!("x {}, y {}", axis_range(&map.x), axis_range(&map.y));
    // The caption in the explorer's words; the text chunk keeps the keys a script reads.
    let words = format!("x {}, y {}", axis_words(&map.x), axis_words(&map.y));
    let mut record = match setup {
        Some((name, params, initial)) => {
            let varied = [map.x.key.key.as_str(), map.y.key.key.as_str()];
            let mut r = Record::of_setup_varying(&title(map, layer), name, params, initial, &varied);
            r.caption
                .insert(0, format!("{words}; every other value as below"));
            r
        }
        None => Record {
            caption: vec![words],
            text: vec![("Title".to_string(), title(map, layer))],
        },
    };
    record.text.push(("dicesim-axes".to_string(), axes));
    record
}

/// `map` as the bytes of a PNG or SVG file of `size` pixels.
pub fn image_bytes(
    map: &BasinMap,
    layer: Layer,
    record: &Record,
    size: (u32, u32),
    format: ImageFormat,
) -> Result<Vec<u8>, Error> {
    register_fonts()?;
    let scale = Scale::of(size, SIZE);
    match format {
        ImageFormat::Png => png_bytes(size, record, |area| draw(area, map, layer, record, scale)),
        ImageFormat::Svg => {
            let mut svg = String::new();
            draw(
                SVGBackend::with_string(&mut svg, size).into_drawing_area(),
                map,
                layer,
                record,
                scale,
            )?;
            Ok(with_svg_metadata(&svg, record).into_bytes())
        }
    }
}

/// The settle-time scale: s, over settled cells that were rolled (`None` if none).
pub fn time_range(map: &BasinMap) -> Option<(f64, f64)> {
    let times = map
        .cells
        .iter()
        .flatten()
        .filter(|c| c.outcome.status == Status::Settled && c.sampled)
        .map(|c| c.outcome.time_s);
    times.fold(None, |r, t| match r {
        None => Some((t, t)),
        Some((lo, hi)) => Some((t.min(lo), t.max(hi))),
    })
}

/// A cell's colour in the image, its die showing `numbers`; the explorer draws its map in
/// the same colours.
pub fn cell_colour(numbers: &[u8], cell: Option<&Cell>, layer: Layer, times: Option<(f64, f64)>) -> RGBColor {
    let Some(c) = cell else { return UNKNOWN };
    match (c.outcome.status, c.outcome.face, layer) {
        (Status::Timeout, ..) => TIMEOUT,
        (Status::Unstable, ..) => UNSTABLE,
        (Status::Settled, None, Layer::Face) => NO_FACE,
        (Status::Settled, Some(f), Layer::Face) => face_colour(numbers, f),
        (Status::Settled, _, Layer::SettleTime) if !c.sampled => INFERRED,
        (Status::Settled, _, Layer::SettleTime) => {
            let (lo, hi) = times.unwrap_or((0.0, 1.0));
            viridis((c.outcome.time_s - lo) / (hi - lo).max(1e-12))
        }
    }
}

fn title(map: &BasinMap, layer: Layer) -> String {
    let what = match layer {
        Layer::Face => "Face up",
        Layer::SettleTime => "Settle time",
    };
    let (w, h) = (map.width(), map.height());
    let how = match map.method {
        dicesim_experiment::basin::Method::Uniform => format!("uniform grid {w}×{h}"),
        dicesim_experiment::basin::Method::Adaptive => {
            format!("adaptive {w}×{h}, {} of {} cells rolled", map.sampled, w * h)
        }
    };
    format!("{what} — {how}")
}

/// An axis's key and range, to the precision its grid resolves (a one-node axis: its
/// value).
fn axis_range(axis: &dicesim_experiment::basin::Axis) -> String {
    let unit = match axis.key.unit() {
        "" => String::new(),
        u => format!(" {u}"),
    };
    if axis.cells == 1 {
        return format!("{} = {}{unit}", axis.key.key, setup_value(axis.value(0)));
    }
    let d = axis.spacing();
    format!(
        "{} from {} to {}{unit}",
        axis.key.key,
        resolved(axis.min, d),
        resolved(axis.max, d)
    )
}

/// An axis's range in the explorer's words (`spin ωx from -20 to 20 rad/s`), as a caption
/// states it.
fn axis_words(axis: &dicesim_experiment::basin::Axis) -> String {
    let unit = match axis.key.unit() {
        "" => String::new(),
        u => format!(" {u}"),
    };
    if axis.cells == 1 {
        return format!("{} = {}{unit}", axis.key.words(), setup_value(axis.value(0)));
    }
    let d = axis.spacing();
    format!(
        "{} from {} to {}{unit}",
        axis.key.words(),
        resolved(axis.min, d),
        resolved(axis.max, d)
    )
}

/// The words under (or beside) an axis: the value in the explorer's words with the unit,
/// and its range.
fn axis_title(axis: &dicesim_experiment::basin::Axis) -> String {
    let d = axis.spacing();
    format!(
        "{}: {} to {}",
        axis.key.title(),
        resolved(axis.min, d),
        resolved(axis.max, d)
    )
}

/// Labels on every axis of every figure: at most this many ticks.
pub(crate) const TICKS: usize = 10;

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    map: &BasinMap,
    layer: Layer,
    record: &Record,
    scale: Scale,
) -> Result<(), Error> {
    let px = |v: i32| scale.px(v);
    root.fill(&WHITE).map_err(plot_error)?;
    let picture = with_caption(&root, record, scale)?;
    let (width, _) = picture.dim_in_pixel();
    let (area, legend) = picture.split_horizontally(width.saturating_sub(px(LEGEND_WIDTH as i32) as u32));
    let times = time_range(map);
    let (x, y) = (&map.x, &map.y);
    let (dx, dy) = (x.spacing(), y.spacing());
    let x_range = (x.min - dx / 2.0)..(x.max + dx / 2.0);
    let mut chart = ChartBuilder::on(&area);
    chart
        .caption(title(map, layer), ("sans-serif", px(26)))
        .margin(px(20))
        .x_label_area_size(px(60))
        .y_label_area_size(px(80));
    let label_style = ("sans-serif", px(16));
    let desc_style = ("sans-serif", px(19));
    if map.height() == 1 {
        // A 1-D scan: settle time against the value, each point in its face's colour, as the
        // authors plotted it (the time spikes at the borders between faces).
        let hi = times.map_or(1.0, |t| t.1) * 1.05;
        let (xt, yt) = (
            Ticks::new(x_range.start, x_range.end, TICKS),
            Ticks::new(0.0, hi, TICKS),
        );
        let mut chart = chart.build_cartesian_2d(x_range, 0.0..hi).map_err(plot_error)?;
        chart
            .configure_mesh()
            .x_desc(axis_title(x))
            .y_desc(format!("settle time (s), {}", axis_words(y)))
            .x_labels(TICKS)
            .y_labels(TICKS)
            .x_label_formatter(&|v| xt.label(*v))
            .y_label_formatter(&|v| yt.label(*v))
            .label_style(label_style)
            .axis_desc_style(desc_style)
            .draw()
            .map_err(plot_error)?;
        let points: Vec<(f64, f64, RGBColor)> = (0..map.width())
            .filter_map(|i| {
                let c = map.cell(i, 0)?;
                Some((
                    x.value(i),
                    c.outcome.time_s,
                    cell_colour(map.numbers, Some(c), Layer::Face, times),
                ))
            })
            .collect();
        chart
            .draw_series(std::iter::once(PathElement::new(
                points.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>(),
                RGBColor(160, 160, 160),
            )))
            .map_err(plot_error)?;
        chart
            .draw_series(
                points
                    .iter()
                    .map(|&(x, y, c)| Circle::new((x, y), px(3), c.filled())),
            )
            .map_err(plot_error)?;
        face_legend(&legend, map, scale)?;
    } else {
        let y_range = (y.min - dy / 2.0)..(y.max + dy / 2.0);
        let (xt, yt) = (
            Ticks::new(x_range.start, x_range.end, TICKS),
            Ticks::new(y_range.start, y_range.end, TICKS),
        );
        let mut chart = chart.build_cartesian_2d(x_range, y_range).map_err(plot_error)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(axis_title(x))
            .y_desc(axis_title(y))
            .x_labels(TICKS)
            .y_labels(TICKS)
            .x_label_formatter(&|v| xt.label(*v))
            .y_label_formatter(&|v| yt.label(*v))
            .label_style(label_style)
            .axis_desc_style(desc_style)
            .draw()
            .map_err(plot_error)?;
        // One rectangle per run of equal colour along a row keeps the SVG small.
        let mut runs = Vec::new();
        for j in 0..map.height() {
            let mut i = 0;
            while i < map.width() {
                let colour = cell_colour(map.numbers, map.cell(i, j), layer, times);
                let start = i;
                while i + 1 < map.width()
                    && cell_colour(map.numbers, map.cell(i + 1, j), layer, times) == colour
                {
                    i += 1;
                }
                let (yc, xa, xb) = (y.value(j), x.value(start), x.value(i));
                runs.push(Rectangle::new(
                    [(xa - dx / 2.0, yc - dy / 2.0), (xb + dx / 2.0, yc + dy / 2.0)],
                    colour.filled(),
                ));
                i += 1;
            }
        }
        chart.draw_series(runs).map_err(plot_error)?;
        match layer {
            Layer::Face => face_legend(&legend, map, scale)?,
            Layer::SettleTime => time_legend(&legend, map, times, scale)?,
        }
    }
    root.present().map_err(plot_error)
}

/// The faces that occur, then whichever other endings do: the legend names only what is
/// drawn.
fn face_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    map: &BasinMap,
    scale: Scale,
) -> Result<(), Error> {
    let occurs = |status: Status, face: Option<u8>| {
        map.cells
            .iter()
            .flatten()
            .any(|c| c.outcome.status == status && (status != Status::Settled || c.outcome.face == face))
    };
    let mut entries: Vec<(String, RGBColor)> = (map.numbers.iter().enumerate())
        .filter(|&(_, &f)| occurs(Status::Settled, Some(f)))
        .map(|(k, f)| (format!("face {f}"), face_colour_at(k)))
        .collect();
    for (ending, status, colour) in [
        (Ending::WithoutFace, Status::Settled, NO_FACE),
        (Ending::DidNotSettle, Status::Timeout, TIMEOUT),
        (Ending::Unstable, Status::Unstable, UNSTABLE),
    ] {
        if occurs(status, None) {
            entries.push((ending.name().to_string(), colour));
        }
    }
    swatches(area, scale.px(80), &entries, scale)
}

/// Colour swatches with their labels from `top` down, a label too long for the strip on two
/// lines; entries closer together when at their usual spacing they would run off the strip
/// (a d20's twenty faces and three endings).
fn swatches<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    top: i32,
    entries: &[(String, RGBColor)],
    scale: Scale,
) -> Result<(), Error> {
    let px = |v: i32| scale.px(v);
    let labelled: Vec<(Vec<String>, &RGBColor)> = (entries.iter())
        .map(|(label, colour)| (label_lines(label), colour))
        .collect();
    let advance = |lines: usize| px(34 + 20 * (lines as i32 - 1));
    let needed: i32 = labelled.iter().map(|(lines, _)| advance(lines.len())).sum();
    let room = area.dim_in_pixel().1 as i32 - top - px(10);
    let mut y = top;
    for (lines, colour) in labelled {
        area.draw(&Rectangle::new(
            [(px(10), y), (px(36), y + px(24))],
            colour.filled(),
        ))
        .map_err(plot_error)?;
        for (k, line) in lines.iter().enumerate() {
            area.draw(&Text::new(
                line.as_str(),
                (px(46), y + px(3 + 20 * k as i32)),
                ("sans-serif", px(18)),
            ))
            .map_err(plot_error)?;
        }
        y += match needed > room {
            true => advance(lines.len()) * room / needed,
            false => advance(lines.len()),
        };
    }
    Ok(())
}

/// A legend's label on one line, or on two at its first space past the eighth character
/// when longer than 15 characters.
fn label_lines(label: &str) -> Vec<String> {
    match label
        .char_indices()
        .filter(|&(i, c)| c == ' ' && i >= 8)
        .map(|(i, _)| i)
        .next()
    {
        Some(i) if label.chars().count() > 15 => vec![label[..i].to_string(), label[i + 1..].to_string()],
        _ => vec![label.to_string()],
    }
}

/// A vertical colour bar from the shortest (bottom) to the longest (top) settle time.
fn time_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    map: &BasinMap,
    times: Option<(f64, f64)>,
    scale: Scale,
) -> Result<(), Error> {
    let px = |v: i32| scale.px(v);
    let (lo, hi) = times.unwrap_or((0.0, 0.0));
    let (top, bottom) = (px(90), px(520));
    area.draw(&Text::new(
        "settle time (s)",
        (px(10), top - px(40)),
        ("sans-serif", px(18)),
    ))
    .map_err(plot_error)?;
    for py in top..bottom {
        let t = (bottom - py) as f64 / (bottom - top) as f64;
        area.draw(&Rectangle::new(
            [(px(10), py), (px(40), py + 1)],
            viridis(t).filled(),
        ))
        .map_err(plot_error)?;
    }
    // Marks at round times inside the scale (a scale of one time: that time).
    let (ticks, values) = if hi > lo {
        Ticks::values(lo, hi, 5)
    } else {
        (Ticks::new(0.0, 1.0, 5), vec![lo])
    };
    for v in values.into_iter().filter(|_| times.is_some()) {
        let f = if hi > lo { (v - lo) / (hi - lo) } else { 0.0 };
        let py = bottom - ((bottom - top) as f64 * f) as i32;
        area.draw(&Rectangle::new([(px(40), py), (px(44), py + 1)], BLACK.filled()))
            .map_err(plot_error)?;
        let label = if hi > lo { ticks.label(v) } else { setup_value(v) };
        area.draw(&Text::new(label, (px(48), py - px(8)), ("sans-serif", px(16))))
            .map_err(plot_error)?;
    }
    let any = |occurs: &dyn Fn(&Cell) -> bool| map.cells.iter().flatten().any(occurs);
    let mut entries = Vec::new();
    if any(&|c| c.outcome.status == Status::Timeout) {
        entries.push((Ending::DidNotSettle.name().to_string(), TIMEOUT));
    }
    if any(&|c| c.outcome.status == Status::Unstable) {
        entries.push((Ending::Unstable.name().to_string(), UNSTABLE));
    }
    if any(&|c| c.outcome.status == Status::Settled && !c.sampled) {
        entries.push((INFERRED_WORDS.to_string(), INFERRED));
    }
    swatches(area, bottom + px(30), &entries, scale)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_caption_says_where_a_loaded_die_is_heavy() {
        let initial = InitialCondition::default();
        let mut params = Params::default();
        let fair = Record::of_setup("t", "paper", &params, &initial)
            .caption
            .join("\n");
        assert!(!fair.contains("loaded"), "{fair}");
        params.die.extra_corner_mass[7] = 0.5;
        params.die.extra_corner_mass[1] = 2.0;
        let caption = Record::of_setup("t", "x", &params, &initial).caption.join("\n");
        assert!(
            caption.contains("m 1 g, loaded: +2 g at corner 2, +0.5 g at corner 8;"),
            "{caption}"
        );
    }

    /// A polyhedral die's caption gives its kind, height and density, not the box's half
    /// size and corner mass it does not read.
    #[test]
    fn a_caption_names_a_polyhedral_die_by_its_own_keys() {
        let mut params = Params::default();
        params.die.kind = dicesim_physics::Solid::D20;
        let caption = Record::of_setup("t", "d20", &params, &InitialCondition::default())
            .caption
            .join("\n");
        assert!(
            caption.contains("; die d20 1.6 cm across, 1.18 g/cm³;"),
            "{caption}"
        );
        assert!(
            !caption.contains("a 1 cm") && !caption.contains("m 1 g"),
            "{caption}"
        );
    }

    /// A figure that varies a value never states it in its caption: a map over spin x and
    /// friction names those on its axes (in the explorer's words, with units) and writes the
    /// varied spin component as its symbol; the varied table value leaves the body line.
    #[test]
    fn a_caption_never_states_a_value_the_figure_varies() {
        let map = awkward_map(Layer::Face, 3);
        let initial = InitialCondition {
            velocity: [30.0, 0.0, 0.0],
            angular_velocity: [12.0, -20.0, 6.0],
            ..InitialCondition::default()
        };
        let record = map_record(&map, Layer::Face, Some(("paper", &Params::default(), &initial)));
        let caption = record.caption.join("\n");
        let spin_x = ScanKey::named("initial.angular_velocity.x").unwrap();
        let friction = ScanKey::named("ground.friction").unwrap();
        assert!(
            caption.contains(&format!("x {} from", spin_x.words())),
            "{caption}"
        );
        assert!(
            caption.contains(&format!("y {} from", friction.words())),
            "{caption}"
        );
        assert!(caption.contains("spin (ωx, -20, 6) rad/s"), "{caption}");
        assert!(
            !caption.contains("μ 1.2") && caption.contains("k 500000 dyn/cm"),
            "{caption}"
        );
        assert!(!caption.contains("initial.angular_velocity.x"), "{caption}");
        // The text chunk a script reads keeps the keys.
        let axes = &record.text.iter().find(|(k, _)| k == "dicesim-axes").unwrap().1;
        assert!(axes.starts_with("x initial.angular_velocity.x from"), "{axes}");
        assert_eq!(
            axis_title(&map.x),
            format!("{} (rad/s): -14.2 to -6.7", spin_x.words())
        );
        // Starts drawn for curves of several heights: no height in the caption.
        let r = dicesim_physics::RandomRanges::default();
        assert!(random_starts(&r, 1, &[]).contains("height 15 cm"));
        let varied = random_starts(&r, 1, &["initial.height"]);
        assert!(!varied.contains("height"), "{varied}");
        assert!(varied.contains("velocity -50…50 cm/s"), "{varied}");
    }

    /// A small map of the paper's roll over the issue's awkward range, rolled for real.
    fn awkward_map(layer: Layer, height: usize) -> BasinMap {
        use dicesim_experiment::{Axis, MapSpec, Method, run_map};
        let initial = InitialCondition {
            velocity: [30.0, 0.0, 0.0],
            angular_velocity: [12.0, -20.0, 6.0],
            ..InitialCondition::default()
        };
        let spec = MapSpec {
            x: Axis::parse(
                "initial.angular_velocity.x:-14.204545454545455:-6.704545454545455",
                9,
            )
            .unwrap(),
            y: Axis::parse("ground.friction:0.2:1.4", height).unwrap(),
            method: if layer == Layer::Face {
                Method::Adaptive
            } else {
                Method::Uniform
            },
        };
        let never = std::sync::atomic::AtomicBool::new(false);
        run_map(&Params::default(), &initial, &spec, 1, &never, &mut |_| {}).unwrap()
    }

    /// The text elements of an SVG (their content, unescaped enough to read) with their
    /// x position and font size.
    fn svg_texts(svg: &str) -> Vec<(f64, f64, String)> {
        let attribute = |tag: &str, name: &str| -> f64 {
            let at = tag.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
            tag[at..].split('"').next().unwrap().parse().unwrap()
        };
        svg.split("<text")
            .skip(1)
            .map(|chunk| {
                let (tag, rest) = chunk.split_once('>').unwrap();
                let content = rest
                    .split("</text>")
                    .next()
                    .unwrap()
                    .trim()
                    .replace("&apos;", "'");
                (attribute(tag, "x"), attribute(tag, "font-size"), content)
            })
            .collect()
    }

    /// Decimals of every number written in `text` (`-14.2` has 1, `9×6` none).
    fn decimals_in(text: &str) -> Vec<(String, usize)> {
        let mut found = Vec::new();
        let mut number = String::new();
        for c in text.chars().chain(std::iter::once(' ')) {
            if c.is_ascii_digit() || (c == '.' && !number.is_empty() && !number.contains('.')) {
                number.push(c);
            } else if !number.is_empty() {
                let n = number.trim_end_matches('.').to_string();
                let decimals = n.split_once('.').map_or(0, |(_, d)| d.len());
                found.push((n, decimals));
                number.clear();
            }
        }
        found
    }

    #[test]
    fn no_svg_text_carries_more_digits_than_the_grid_resolves() {
        for (layer, height) in [(Layer::Face, 6), (Layer::SettleTime, 6), (Layer::Face, 1)] {
            let map = awkward_map(layer, height);
            // Without a setup the caption is the axes' line: every number on the image
            // comes from the grid (or counts cells).
            let record = map_record(&map, layer, None);
            let svg = String::from_utf8(image_bytes(&map, layer, &record, SIZE, ImageFormat::Svg).unwrap())
                .unwrap();
            // x is 0.94 apart, friction 0.24 apart: one decimal; the time scale's marks sit
            // on a round step of its 5 at most.
            let allowed = 1.max(match (layer, time_range(&map)) {
                (Layer::SettleTime, Some((lo, hi))) => {
                    super::super::figure::decimals_for((hi - lo) / 4.0) + 1
                }
                _ => 0,
            });
            let texts = svg_texts(&svg);
            assert!(texts.iter().any(|t| t.2.contains("-14.2")), "{texts:?}");
            for (_, _, text) in &texts {
                for (number, decimals) in decimals_in(text) {
                    assert!(decimals <= allowed, "{layer:?} {height}: `{number}` in `{text}`");
                }
            }
        }
    }

    #[test]
    fn caption_lines_wrap_inside_the_image_at_every_size() {
        let map = awkward_map(Layer::Face, 6);
        let mut params = Params::default();
        params.die.extra_corner_mass = [0.25; 8];
        let initial = InitialCondition::default();
        for size in [SIZE, (600, 400), (2400, 1600)] {
            let record = map_record(
                &map,
                Layer::Face,
                Some(("a-preset-with-a-long-name", &params, &initial)),
            );
            let svg =
                String::from_utf8(image_bytes(&map, Layer::Face, &record, size, ImageFormat::Svg).unwrap())
                    .unwrap();
            let texts = svg_texts(&svg);
            let scale = Scale::of(size, SIZE);
            let lines = caption_lines(&record, size.0, scale);
            // Every caption word is drawn: nothing cut.
            assert_eq!(
                lines.concat().replace(' ', ""),
                record.caption.concat().replace(' ', "")
            );
            assert!(
                lines.len() > record.caption.len() || size.0 >= 1200,
                "{size:?}: {lines:?}"
            );
            for line in &lines {
                let width = super::super::figure::text_width(line, f64::from(scale.px(CAPTION_FONT)), false);
                assert!(
                    f64::from(scale.px(CAPTION_MARGIN)) + width <= f64::from(size.0),
                    "{size:?}: {width} px: {line}"
                );
                // And the SVG has that line as one text element.
                assert!(texts.iter().any(|t| t.2 == line.replace("&", "&amp;")), "{line}");
            }
        }
    }

    /// A 5×4 face map of a d20 (numbers 1..20), cell k showing face k + 1, and one cell of
    /// each ending without a face.
    fn d20_map() -> BasinMap {
        use dicesim_experiment::{Axis, Cell, Method};
        let numbers: &'static [u8] = &[
            1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20,
        ];
        let cell = |status, face| Cell {
            outcome: dicesim_physics::Outcome {
                status,
                face,
                steps: 10,
                time_s: 0.01,
                impacts: 0,
                first_impact: None,
            },
            start_face: 1,
            sampled: true,
        };
        let mut cells: Vec<Option<Cell>> = numbers
            .iter()
            .map(|&f| Some(cell(Status::Settled, Some(f))))
            .collect();
        cells.extend([
            Some(cell(Status::Settled, None)),
            Some(cell(Status::Timeout, None)),
            Some(cell(Status::Unstable, None)),
            None,
        ]);
        BasinMap {
            x: Axis::parse("initial.angular_velocity.x:-10:10", 6).unwrap(),
            y: Axis::parse("ground.friction:0.2:1.4", 4).unwrap(),
            method: Method::Uniform,
            cells,
            numbers,
            sampled: 23,
            complete: false,
            switched_to_uniform: None,
        }
    }

    #[test]
    fn a_d20s_faces_take_twenty_colours_and_its_key_fits_the_image() {
        // Twenty colours, none the same and none an ending's or an unknown cell's.
        let mut colours: Vec<(u8, u8, u8)> = FACE_COLOURS.iter().map(|c| (c.0, c.1, c.2)).collect();
        colours.extend([NO_FACE, TIMEOUT, UNSTABLE, UNKNOWN, INFERRED].map(|c| (c.0, c.1, c.2)));
        let all = colours.len();
        colours.sort();
        colours.dedup();
        assert_eq!(colours.len(), all);
        // A colour by place in the die's list: the d10's 0 takes the cube's 1's colour, the
        // d%'s 90 its tenth; a number the die does not show, the no-face grey.
        let d10: &[u8] = &[0, 1, 2, 3, 4, 5, 6, 7, 8, 9];
        let tens: &[u8] = &[0, 10, 20, 30, 40, 50, 60, 70, 80, 90];
        assert_eq!(face_colour(d10, 0), FACE_COLOURS[0]);
        assert_eq!(face_colour(tens, 90), FACE_COLOURS[9]);
        assert_eq!(face_colour(tens, 9), NO_FACE);
        // Past twenty, hues apart: 22 and 21 differ from each other and from the palette.
        assert_ne!(face_colour_at(20), face_colour_at(21));
        assert!(!FACE_COLOURS.contains(&face_colour_at(20)));

        let map = d20_map();
        let record = map_record(&map, Layer::Face, None);
        let svg = String::from_utf8(image_bytes(&map, Layer::Face, &record, SIZE, ImageFormat::Svg).unwrap())
            .unwrap();
        // Each face's key entry, in the die's order, then the endings: all inside the image.
        let texts: Vec<(String, f64)> = svg
            .split("<text")
            .skip(1)
            .map(|chunk| {
                let (tag, rest) = chunk.split_once('>').unwrap();
                let at = tag.find(" y=\"").unwrap() + 4;
                let y = tag[at..].split('"').next().unwrap().parse().unwrap();
                (rest.split("</text>").next().unwrap().trim().to_string(), y)
            })
            .collect();
        let key: Vec<&(String, f64)> = texts.iter().filter(|(t, _)| t.starts_with("face ")).collect();
        let names: Vec<&str> = key.iter().map(|(t, _)| t.as_str()).collect();
        let expected: Vec<String> = (1..=20).map(|f| format!("face {f}")).collect();
        assert_eq!(names, expected);
        assert!(key.windows(2).all(|w| w[0].1 < w[1].1), "top to bottom");
        let lowest = texts.iter().map(|(_, y)| *y).fold(0.0, f64::max);
        assert!(lowest + 18.0 <= f64::from(SIZE.1), "the key runs to y = {lowest}");
        // Every face's colour is drawn.
        for (k, _) in map.numbers.iter().enumerate() {
            let c = face_colour_at(k);
            let hex = format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2);
            assert!(svg.to_uppercase().contains(&hex), "face {} {hex}", k + 1);
        }
    }

    #[test]
    fn the_legend_names_only_the_faces_drawn() {
        let map = awkward_map(Layer::Face, 6);
        let record = map_record(&map, Layer::Face, None);
        let svg = String::from_utf8(image_bytes(&map, Layer::Face, &record, SIZE, ImageFormat::Svg).unwrap())
            .unwrap();
        let texts = svg_texts(&svg);
        for f in 1..=6u8 {
            let occurs = map.cells.iter().flatten().any(|c| c.outcome.face == Some(f));
            let listed = texts.iter().any(|t| t.2 == format!("face {f}"));
            assert_eq!(occurs, listed, "face {f}");
        }
        // A map of one face lists one.
        let mut one = map.clone();
        for c in one.cells.iter_mut().flatten() {
            c.outcome.face = Some(2);
        }
        let svg = String::from_utf8(image_bytes(&one, Layer::Face, &record, SIZE, ImageFormat::Svg).unwrap())
            .unwrap();
        let faces: Vec<String> = svg_texts(&svg)
            .into_iter()
            .map(|t| t.2)
            .filter(|t| t.starts_with("face "))
            .collect();
        assert_eq!(faces, ["face 2"]);
    }

    #[test]
    fn an_svg_carries_its_record_and_a_png_its_physical_size() {
        let map = awkward_map(Layer::Face, 2);
        let record =
            map_record(&map, Layer::Face, None).with_provenance(&serde_json::json!({"seed": "<1 & 2>"}));
        let svg = String::from_utf8(image_bytes(&map, Layer::Face, &record, SIZE, ImageFormat::Svg).unwrap())
            .unwrap();
        // Right inside the root element, before anything drawn.
        let root_end = svg.find("<svg").unwrap() + svg[svg.find("<svg").unwrap()..].find('>').unwrap() + 1;
        assert!(
            svg[root_end..].starts_with("<title>"),
            "{}",
            &svg[..root_end + 40]
        );
        assert!(
            svg.contains(r#"<entry keyword="dicesim-provenance">{&quot;seed&quot;:&quot;&lt;1 &amp; 2&gt;&quot;}</entry>"#),
            "{}",
            &svg[..root_end + 400]
        );
        let png = image_bytes(&map, Layer::Face, &record, SIZE, ImageFormat::Png).unwrap();
        let info = png::Decoder::new(std::io::Cursor::new(png)).read_info().unwrap();
        let dims = info.info().pixel_dims.expect("a pHYs chunk");
        assert_eq!((dims.xppu, dims.yppu, dims.unit), (5906, 5906, png::Unit::Meter));
        // 150 pixels per inch: the design width prints 8 inches wide.
        let inches = f64::from(SIZE.0) / (f64::from(dims.xppu) * 0.0254);
        assert!((inches - 8.0).abs() < 1e-3, "{inches}");
    }

    #[test]
    fn viridis_ends_and_middle() {
        assert_eq!(viridis(0.0), VIRIDIS[0]);
        assert_eq!(viridis(1.0), VIRIDIS[4]);
        assert_eq!(viridis(0.5), VIRIDIS[2]);
        assert_eq!(viridis(f64::NAN), VIRIDIS[0]);
    }
}
