//! One frame of an animation, a pure function of the dice's state: the table's tiles with
//! the dice's shadows, each die a solid shaded body with its pips (the box) or its numbers
//! (a polyhedral die, [`super::solid`]), the face up tinted, the corners touching the table
//! marked, and a caption band with the time and the setup.
//!
//! Every colour is an entry of one fixed palette ([`PALETTE`]): the die's shades are ramps
//! of it and text is drawn as coverage steps of one ramp. So a frame is stored as palette
//! indices, the GIF and APNG encoders take it as it is (no quantiser, nothing that could
//! depend on the machine), and the same setup gives the same bytes.

use super::solid::{Label, Polyhedral};
use crate::figure::{font, wrap};
use crate::plane::{convex_hull as hull, inside};
use ab_glyph::{Font, PxScale, ScaleFont, point};
use dicesim_physics::PIP_LAYOUT;
use dicesim_physics::body::FACE_CORNERS;
use nalgebra::Vector3;
use std::sync::Arc;

/// The palette index no drawing uses: a delta frame's "unchanged" pixel.
pub(crate) const CLEAR: u8 = 0;
const BACKGROUND: u8 = 1;
/// The caption band; coverage 0 of the text ramp.
pub(crate) const BAND: u8 = TEXT;
pub(crate) const TEXT: u8 = 2;
pub(crate) const TEXT_STEPS: u8 = 16;
pub(crate) const TILE_LIGHT: u8 = 18;
pub(crate) const TILE_DARK: u8 = 19;
pub(crate) const SHADOW_LIGHT: u8 = 20;
pub(crate) const SHADOW_DARK: u8 = 21;
pub(crate) const CONTACT: u8 = 22;
pub(crate) const EDGE: u8 = 23;
const TWIN_EDGE: u8 = 24;
const TABLE_EDGE: u8 = 25;
pub(crate) const PIP: u8 = 26;
pub(crate) const PIP_STEPS: u8 = 6;
/// Ramps of shades, dark to light: the die, its face up, the twin, the twin's face up, and
/// the marked face pair's two faces.
pub(crate) const RAMP: u8 = 32;
pub(crate) const RAMP_STEPS: u8 = 36;
const RAMPS: usize = 6;

/// A ramp's base colour (lit squarely) for each.
const RAMP_COLOURS: [[f64; 3]; RAMPS] = [
    [250.0, 246.0, 236.0], // ivory
    [255.0, 214.0, 140.0], // the face up: warm (Okabe–Ito orange, lightened)
    [170.0, 210.0, 240.0], // the twin: sky blue
    [110.0, 205.0, 170.0], // the twin's face up: bluish green
    [240.0, 120.0, 80.0],  // the pair's lower face: vermilion
    [180.0, 120.0, 230.0], // its opposite: purple
];

/// The ramp of the marked pair's lower face; its opposite's follows.
pub(crate) const PAIR_RAMP: u8 = 4;

// The ranges of the palette do not overlap, and the ramps fit in it.
const _: () = assert!(TEXT + TEXT_STEPS <= TILE_LIGHT && PIP + PIP_STEPS <= RAMP);
const _: () = assert!(RAMP as u32 + RAMPS as u32 * RAMP_STEPS as u32 <= 256);

/// The fixed 256-colour palette, RGB.
pub(crate) const PALETTE: [[u8; 3]; 256] = palette();

const fn mix(a: [u8; 3], b: [u8; 3], num: u32, den: u32) -> [u8; 3] {
    let mut out = [0u8; 3];
    let mut i = 0;
    while i < 3 {
        out[i] = ((a[i] as u32 * (den - num) + b[i] as u32 * num + den / 2) / den) as u8;
        i += 1;
    }
    out
}

const fn palette() -> [[u8; 3]; 256] {
    let mut p = [[0u8; 3]; 256];
    p[CLEAR as usize] = [255, 0, 255]; // never shown: transparent where used
    p[BACKGROUND as usize] = [226, 231, 236];
    let band = [255, 255, 255];
    let ink = [25, 25, 30];
    let mut k = 0;
    while k < TEXT_STEPS as u32 {
        p[(TEXT as u32 + k) as usize] = mix(band, ink, k, TEXT_STEPS as u32 - 1);
        k += 1;
    }
    p[TILE_LIGHT as usize] = [214, 200, 176];
    p[TILE_DARK as usize] = [190, 172, 146];
    p[SHADOW_LIGHT as usize] = [150, 140, 124];
    p[SHADOW_DARK as usize] = [133, 121, 102];
    p[CONTACT as usize] = [213, 94, 0];
    p[EDGE as usize] = [45, 45, 50];
    p[TWIN_EDGE as usize] = [0, 94, 158];
    p[TABLE_EDGE as usize] = [150, 132, 108];
    let mut k = 0;
    while k < PIP_STEPS as u32 {
        p[(PIP as u32 + k) as usize] = mix([20, 20, 24], [70, 70, 78], k, PIP_STEPS as u32 - 1);
        k += 1;
    }
    let mut r = 0;
    while r < RAMPS {
        let mut k = 0;
        while k < RAMP_STEPS as u32 {
            // Lit from 45 % (in shade) to 100 % of the base colour.
            let lit = 45 + 55 * k / (RAMP_STEPS as u32 - 1);
            let base = RAMP_COLOURS[r];
            let mut c = [0u8; 3];
            let mut i = 0;
            while i < 3 {
                c[i] = (base[i] as u32 * lit / 100) as u8;
                i += 1;
            }
            p[RAMP as usize + r * RAMP_STEPS as usize + k as usize] = c;
            k += 1;
        }
        r += 1;
    }
    p
}

/// A frame: `width` × `height` palette indices, row by row from the top.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Frame {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) pixels: Vec<u8>,
}

impl Frame {
    pub(crate) fn new(width: u32, height: u32, fill: u8) -> Frame {
        Frame {
            width,
            height,
            pixels: vec![fill; width as usize * height as usize],
        }
    }

    pub(crate) fn set(&mut self, x: i64, y: i64, colour: u8) {
        if x >= 0 && y >= 0 && (x as u32) < self.width && (y as u32) < self.height {
            self.pixels[y as usize * self.width as usize + x as usize] = colour;
        }
    }

    /// Fills the convex polygon `points` (pixel coordinates), each pixel whose centre is
    /// inside it taking `colour(x, y)`.
    fn fill_convex(&mut self, points: &[(f64, f64)], mut colour: impl FnMut(i64, i64) -> u8) {
        if points.len() < 3 || points.iter().any(|p| !(p.0.is_finite() && p.1.is_finite())) {
            return;
        }
        let top = points.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        let bottom = points.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
        let y0 = (top - 0.5).ceil().max(0.0) as i64;
        let y1 = ((bottom - 0.5).floor() as i64).min(i64::from(self.height) - 1);
        for y in y0..=y1 {
            let yc = y as f64 + 0.5;
            let (mut left, mut right) = (f64::INFINITY, f64::NEG_INFINITY);
            for k in 0..points.len() {
                let (p, q) = (points[k], points[(k + 1) % points.len()]);
                if (p.1 <= yc && yc < q.1) || (q.1 <= yc && yc < p.1) {
                    let x = p.0 + (yc - p.1) / (q.1 - p.1) * (q.0 - p.0);
                    left = left.min(x);
                    right = right.max(x);
                }
            }
            if left > right {
                continue;
            }
            let x0 = (left - 0.5).ceil().max(0.0) as i64;
            let x1 = ((right - 0.5).floor() as i64).min(i64::from(self.width) - 1);
            for x in x0..=x1 {
                let c = colour(x, y);
                self.set(x, y, c);
            }
        }
    }

    /// A line `width` pixels wide from `a` to `b`, with round-enough ends.
    fn line(&mut self, a: (f64, f64), b: (f64, f64), width: f64, colour: u8) {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let length = (dx * dx + dy * dy).sqrt();
        let h = width / 2.0;
        let (nx, ny) = if length > 1e-9 {
            (-dy / length * h, dx / length * h)
        } else {
            (h, 0.0)
        };
        let (ex, ey) = if length > 1e-9 {
            (dx / length * h, dy / length * h)
        } else {
            (0.0, h)
        };
        let quad = [
            (a.0 + nx - ex, a.1 + ny - ey),
            (b.0 + nx + ex, b.1 + ny + ey),
            (b.0 - nx + ex, b.1 - ny + ey),
            (a.0 - nx - ex, a.1 - ny - ey),
        ];
        self.fill_convex(&quad, |_, _| colour);
    }

    /// `text` with its baseline's left end at `(x, y)`, `px` pixels per em, on the caption
    /// band (its anti-aliased edges are steps of the text ramp).
    fn text(&mut self, x: f64, y: f64, text: &str, px: f64, bold: bool) {
        let font = font(bold);
        let scaled = font.as_scaled(PxScale::from(px as f32));
        let mut caret = x as f32;
        let mut previous = None;
        for c in text.chars() {
            let id = scaled.glyph_id(c);
            if let Some(p) = previous {
                caret += scaled.kern(p, id);
            }
            let glyph = id.with_scale_and_position(PxScale::from(px as f32), point(caret, y as f32));
            caret += scaled.h_advance(id);
            previous = Some(id);
            let Some(outline) = font.outline_glyph(glyph) else {
                continue;
            };
            let bounds = outline.px_bounds();
            outline.draw(|gx, gy, coverage| {
                let (px_x, px_y) = (bounds.min.x as i64 + gx as i64, bounds.min.y as i64 + gy as i64);
                let step = (coverage.clamp(0.0, 1.0) * f32::from(TEXT_STEPS - 1)).round() as u8;
                if step == 0 || px_x < 0 || px_y < 0 || px_x >= i64::from(self.width) {
                    return;
                }
                let i = px_y as usize * self.width as usize + px_x as usize;
                if let Some(old) = self.pixels.get_mut(i)
                    && (TEXT..TEXT + TEXT_STEPS).contains(old)
                {
                    *old = (*old).max(TEXT + step);
                }
            });
        }
    }
}

/// One die at one instant: its corners (cm, world frame: the box's 8 in the physics' corner
/// order, a polyhedral die's hull vertices in its [`Polyhedral::offsets`]' order) and its
/// centre of mass.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct DieShot {
    pub(crate) corners: Vec<Vector3<f64>>,
    pub(crate) centre: Vector3<f64>,
    /// The number drawn as the face up (the box's face 1..6, a die's number read).
    pub(crate) up: Option<u8>,
}

/// The body the dice of a scene are: the box, drawn with its pips, or a polyhedral die.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Body {
    Box,
    Polyhedron(Arc<Polyhedral>),
}

/// What one frame shows: the die, the twin if there is one, and the headline (time,
/// faces; its lines split at `\n`) above the setup.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Shot {
    pub(crate) die: DieShot,
    pub(crate) twin: Option<DieShot>,
    pub(crate) headline: String,
    /// s of playback from the first frame to this one.
    pub(crate) played_s: f64,
}

/// The share of a frame's height a zoomed (framing) camera gives the die's side once the
/// drop allows: a third, and a little more, whatever its turn.
pub(crate) const ZOOMED_SIDE: f64 = 0.36;

/// The table a zoomed camera keeps in view in front of the die's shadow, in die sides:
/// enough of the tiles under it that the fall reads as a fall towards them.
pub(crate) const TABLE_BELOW: f64 = 0.5;

/// The least a zoomed camera shows the die once it has closed in: its bounding sphere
/// across this share of the picture's height. A drop of many die sides (the tennis
/// racket's 4 m) then follows the die, not the table, until the table comes into view.
pub(crate) const DIE_AT_LEAST: f64 = 0.25;

/// s of playback over which a zoomed camera closes in from the first frame's wide view
/// (the die and the table, however far apart) to [`DIE_AT_LEAST`].
pub(crate) const CLOSE_IN_S: f64 = 1.0;

/// The headline's size, as a share of the frame's height (of a 4:3 slide's, in a wider
/// frame). 24-point type on a slide 7.5 inches (540 points) high, the least a projector's
/// back row reads, has an em of 1/22.5 of it; a size here is the font's height (ascent to
/// descent, as ab_glyph scales it), 1.164 em in DejaVu Sans, so 1/19 of the frame is an em
/// of 1/22.2.
const HEADLINE_SIZES_PER_HEIGHT: f64 = 19.0;

/// The pixel sizes (ascent to descent) of the headline and of the caption under it (the
/// setup, read closer up: 0.65 of the headline) for a `width` × `height` frame: in
/// proportion to the frame, so a larger frame is the same slide drawn sharper, never
/// under 9 and 8 pixels.
pub(crate) fn caption_sizes(width: u32, height: u32) -> (f64, f64) {
    let slide_height = f64::from(height).min(f64::from(width) * 0.75);
    let headline = (slide_height / HEADLINE_SIZES_PER_HEIGHT).max(9.0);
    (headline, (headline * 0.65).max(8.0))
}

/// The camera: orthographic, turned `yaw` degrees about the vertical and looking down
/// `pitch` degrees, as the explorer's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    pub yaw_deg: f64,
    pub pitch_deg: f64,
}

impl Camera {
    /// The explorer's default view.
    pub const DEFAULT: Camera = Camera {
        yaw_deg: 30.0,
        pitch_deg: 25.0,
    };

    fn trig(&self) -> (f64, f64, f64, f64) {
        let (sy, cy) = self.yaw_deg.to_radians().sin_cos();
        let (sp, cp) = self.pitch_deg.to_radians().sin_cos();
        (sy, cy, sp, cp)
    }

    /// `p` on the view plane: (across, up), cm.
    fn project(&self, p: &Vector3<f64>) -> (f64, f64) {
        let (sy, cy, sp, cp) = self.trig();
        let across = cy * p.x + sy * p.y;
        let away = -sy * p.x + cy * p.y;
        (across, p.z * cp + away * sp)
    }

    /// The unit vector from the scene towards the viewer.
    fn towards_viewer(&self) -> Vector3<f64> {
        let (sy, cy, sp, cp) = self.trig();
        Vector3::new(sy * cp, -cy * cp, sp)
    }

    /// The light: from above, a little to the viewer's left and in front.
    fn light(&self) -> Vector3<f64> {
        let (sy, cy, ..) = self.trig();
        let across = Vector3::new(cy, sy, 0.0);
        (0.55 * self.towards_viewer() + Vector3::z() - 0.45 * across).normalize()
    }
}

/// Everything the frames of one animation share: the size, the camera, the part of the
/// world in view, the table and the caption.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Scene {
    width: u32,
    height: u32,
    camera: Camera,
    /// Pixels per cm, and the pixel of the view plane's origin.
    scale: f64,
    origin: (f64, f64),
    /// The table top, cm: x and y ranges; tiles `tile` cm square.
    table: [(f64, f64); 2],
    tile: f64,
    /// The caption's fixed lines (already wrapped), and the pixel sizes of its text.
    caption: Vec<String>,
    headline_px: f64,
    caption_px: f64,
    headline_lines: usize,
    band: u32,
    margin: f64,
    /// The camera follows the dice, framing them and the table under them
    /// ([`Scene::framing`]), at most at [`ZOOMED_SIDE`] of the frame's height.
    follow: bool,
    /// The marked face pair, its lower number and its opposite's: coloured and its axis
    /// drawn, on the die (not its twin).
    face_pair: Option<(u8, u8)>,
    body: Body,
}

/// How a scene is seen: the camera, whether it follows and frames the die, which face pair
/// is marked (its two numbers, the lower first).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct View {
    pub(crate) camera: Camera,
    pub(crate) zoom: bool,
    pub(crate) face_pair: Option<(u8, u8)>,
}

impl Scene {
    /// The scene of `width` × `height` pixels that holds every one of `shots` whole, seen
    /// by `camera`, with `caption` (the setup) under each headline.
    pub(crate) fn new(
        width: u32,
        height: u32,
        (view, body): (View, Body),
        shots: &[Shot],
        caption: &[String],
    ) -> Scene {
        let camera = view.camera;
        let (w, h) = (f64::from(width), f64::from(height));
        let (headline_px, caption_px) = caption_sizes(width, height);
        let margin = (headline_px * 0.6).round();
        let text_width_px = w - 2.0 * margin;
        let headline_lines = shots
            .iter()
            .map(|s| wrap_lines(&s.headline, headline_px, text_width_px, true).len())
            .max()
            .unwrap_or(1);
        let caption: Vec<String> = caption
            .iter()
            .flat_map(|line| wrap(line, caption_px, text_width_px, false))
            .collect();
        let band = (margin * 0.8
            + headline_lines as f64 * headline_px * 1.25
            + caption.len() as f64 * caption_px * 1.25
            + margin * 0.5)
            .ceil()
            .min(h * 0.6) as u32;

        // The table: the dice's whole path, a die and a half around it.
        let dice = || {
            shots
                .iter()
                .flat_map(|s| std::iter::once(&s.die).chain(s.twin.as_ref()))
        };
        let side = match &body {
            Body::Box => dice().next().map_or(2.0, |d| {
                (d.corners[4] - d.corners[0])
                    .norm()
                    .max((d.corners[2] - d.corners[0]).norm())
            }),
            Body::Polyhedron(die) => die.side,
        }
        .max(1e-6);
        let (mut x, mut y) = (
            (f64::INFINITY, f64::NEG_INFINITY),
            (f64::INFINITY, f64::NEG_INFINITY),
        );
        for d in dice() {
            for c in &d.corners {
                x = (x.0.min(c.x), x.1.max(c.x));
                y = (y.0.min(c.y), y.1.max(c.y));
            }
        }
        if !x.0.is_finite() {
            (x, y) = ((-side, side), (-side, side));
        }
        let pad = 1.5 * side;
        let table = [(x.0 - pad, x.1 + pad), (y.0 - pad, y.1 + pad)];
        // The view: the dice and the table a die's side around their path (the rest of
        // the table runs out of the picture).
        let mut points: Vec<(f64, f64)> = Vec::new();
        for &tx in &[x.0 - side, x.1 + side] {
            for &ty in &[y.0 - side, y.1 + side] {
                points.push(camera.project(&Vector3::new(tx, ty, 0.0)));
            }
        }
        for d in dice() {
            points.extend(d.corners.iter().map(|c| camera.project(c)));
        }
        let (mut lo, mut hi) = (
            (f64::INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        for p in points.iter().filter(|p| p.0.is_finite() && p.1.is_finite()) {
            lo = (lo.0.min(p.0), lo.1.min(p.1));
            hi = (hi.0.max(p.0), hi.1.max(p.1));
        }
        let picture = (w - 2.0 * margin, h - f64::from(band) - 2.0 * margin);
        let span = ((hi.0 - lo.0).max(1e-6), (hi.1 - lo.1).max(1e-6));
        // The whole path in view, or (zoomed) at most the die's side a third of the frame
        // and more ([`Scene::framing`] widens it while the drop needs the room).
        let scale = if view.zoom {
            ZOOMED_SIDE * h / side
        } else {
            (picture.0 / span.0).min(picture.1 / span.1).max(1e-6)
        };
        let centre = ((lo.0 + hi.0) / 2.0, (lo.1 + hi.1) / 2.0);
        let origin = (
            w / 2.0 - centre.0 * scale,
            f64::from(band) + margin + picture.1 / 2.0 + centre.1 * scale,
        );
        Scene {
            width,
            height,
            camera,
            scale,
            origin,
            table,
            tile: side,
            caption,
            headline_px,
            caption_px,
            headline_lines,
            band,
            margin,
            follow: view.zoom,
            face_pair: view.face_pair,
            body,
        }
    }

    /// The picture: the frame below the caption band, inside the margins (pixels: left,
    /// top, right, bottom).
    pub(crate) fn picture(&self) -> (f64, f64, f64, f64) {
        let top = f64::from(self.band) + self.margin;
        (
            self.margin,
            top,
            f64::from(self.width) - self.margin,
            f64::from(self.height) - self.margin,
        )
    }

    /// A following camera's scale (pixels per cm) and origin for `shot`: what the frame
    /// must hold is each die's bounding sphere (a disc of its radius around its centre,
    /// whatever its turn, so the camera does not breathe with the tumbling) and the table
    /// below it: its shadow (within the radius of the foot) and [`TABLE_BELOW`] of a side
    /// more towards the viewer. The scale is the
    /// largest that fits that box in the picture, and no larger than the zoom's; the box is
    /// centred. High in the drop the view is wide, with the table at its foot; it closes
    /// in as the die comes down, and frames the die at a third of the height near the
    /// table. The across extent is the spheres' alone: a foot is straight below its
    /// centre, at the same place across.
    ///
    /// A drop too tall for that to show the die (more than some seven bounding spheres)
    /// starts so, and closes in over [`CLOSE_IN_S`] of playback until the die's sphere is
    /// at least [`DIE_AT_LEAST`] of the picture high; the view then keeps the die inside
    /// and as much of the table below it as there is room for.
    fn framing(&self, shot: &Shot) -> (f64, (f64, f64)) {
        let sp = self.camera.pitch_deg.to_radians().sin();
        let (mut lo, mut hi) = (
            (f64::INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        let radius = |die: &DieShot| {
            die.corners
                .iter()
                .map(|c| (c - die.centre).norm())
                .fold(0.0, f64::max)
        };
        for die in std::iter::once(&shot.die).chain(shot.twin.as_ref()) {
            let r = radius(die);
            let (across, up) = self.camera.project(&die.centre);
            let foot = self
                .camera
                .project(&Vector3::new(die.centre.x, die.centre.y, 0.0));
            // The shadow reaches the sphere's radius from the foot; the table `TABLE_BELOW`
            // sides nearer the viewer than that shows sin(pitch) times as far below the foot
            // (a quarter at least, so a view along the table still shows a strip of it).
            let below = foot.1 - (r + TABLE_BELOW * self.tile) * sp.max(0.25);
            lo = (lo.0.min(across - r), lo.1.min((up - r).min(below)));
            hi = (hi.0.max(across + r), hi.1.max(up + r));
        }
        let (left, top, right, bottom) = self.picture();
        let (width, height) = (right - left, bottom - top);
        let span = ((hi.0 - lo.0).max(1e-6), (hi.1 - lo.1).max(1e-6));
        let fit = (width / span.0).min(height / span.1);
        let r = radius(&shot.die).max(1e-6);
        let x = (shot.played_s / CLOSE_IN_S).clamp(0.0, 1.0);
        let least = DIE_AT_LEAST * height / (2.0 * r) * x * x * (3.0 - 2.0 * x);
        let scale = self.scale.min(fit.max(least)).max(1e-6);
        // The box's centre, moved (when it does not fit) as little as keeps the die whole
        // and half its sphere's radius clear of the picture's edge.
        let (across, up) = self.camera.project(&shot.die.centre);
        let (half_w, half_h) = (width / (2.0 * scale), height / (2.0 * scale));
        let keep = |centre: f64, at: f64, half: f64| {
            let (a, b) = (at + 1.5 * r - half, at - 1.5 * r + half);
            if a <= b { centre.clamp(a, b) } else { at }
        };
        let centre = (
            keep((lo.0 + hi.0) / 2.0, across, half_w),
            keep((lo.1 + hi.1) / 2.0, up, half_h),
        );
        let origin = (
            (left + right) / 2.0 - centre.0 * scale,
            (top + bottom) / 2.0 + centre.1 * scale,
        );
        (scale, origin)
    }

    fn pixel(&self, p: &Vector3<f64>) -> (f64, f64) {
        let (across, up) = self.camera.project(p);
        (
            self.origin.0 + across * self.scale,
            self.origin.1 - up * self.scale,
        )
    }

    /// The table point (cm) seen at pixel centre `(x, y)`, if the view sees the table top.
    fn table_point(&self, x: f64, y: f64) -> Option<(f64, f64)> {
        let (sy, cy, sp, _) = self.camera.trig();
        if sp < 0.02 {
            return None;
        }
        let across = (x - self.origin.0) / self.scale;
        let up = (self.origin.1 - y) / self.scale;
        let away = up / sp;
        Some((cy * across - sy * away, sy * across + cy * away))
    }

    /// The frame of `shot`: pure, the same pixels for the same shot. A following camera
    /// frames it ([`Scene::framing`]).
    pub(crate) fn render(&self, shot: &Shot) -> Frame {
        self.seen_by_camera(shot).render_here(shot)
    }

    /// This scene as the camera has it for `shot`: itself, or a following camera's framing.
    pub(crate) fn seen_by_camera(&self, shot: &Shot) -> Scene {
        if !self.follow {
            return self.clone();
        }
        let (scale, origin) = self.framing(shot);
        Scene {
            scale,
            origin,
            ..self.clone()
        }
    }

    /// The frame of `shot` from this scene's origin.
    fn render_here(&self, shot: &Shot) -> Frame {
        let mut frame = Frame::new(self.width, self.height, BACKGROUND);
        let line_width = (f64::from(self.height) / 320.0).max(1.0);
        let dice: Vec<(&DieShot, bool)> = std::iter::once((&shot.die, false))
            .chain(shot.twin.as_ref().map(|t| (t, true)))
            .collect();

        // The table and the shadows (the light of the shadows straight above: each die's
        // footprint, the hull of its corners' feet).
        let shadows: Vec<Vec<(f64, f64)>> = dice
            .iter()
            .map(|(d, _)| hull(&d.corners.iter().map(|c| (c.x, c.y)).collect::<Vec<_>>()))
            .collect();
        let [tx, ty] = self.table;
        let table_corners: Vec<(f64, f64)> = [(tx.0, ty.0), (tx.1, ty.0), (tx.1, ty.1), (tx.0, ty.1)]
            .iter()
            .map(|&(x, y)| self.pixel(&Vector3::new(x, y, 0.0)))
            .collect();
        let table_outline = hull(&table_corners);
        frame.fill_convex(&table_outline, |x, y| {
            let Some((wx, wy)) = self.table_point(x as f64 + 0.5, y as f64 + 0.5) else {
                return TILE_LIGHT;
            };
            let dark = ((wx / self.tile).floor() + (wy / self.tile).floor()).rem_euclid(2.0) >= 1.0;
            let shaded = shadows.iter().any(|s| inside(s, (wx, wy)));
            match (dark, shaded) {
                (false, false) => TILE_LIGHT,
                (true, false) => TILE_DARK,
                (false, true) => SHADOW_LIGHT,
                (true, true) => SHADOW_DARK,
            }
        });
        for k in 0..table_outline.len() {
            let (a, b) = (table_outline[k], table_outline[(k + 1) % table_outline.len()]);
            frame.line(a, b, line_width, TABLE_EDGE);
        }

        // The dice, the farther first.
        let viewer = self.camera.towards_viewer();
        let mut order = dice.clone();
        order.sort_by(|a, b| a.0.centre.dot(&viewer).total_cmp(&b.0.centre.dot(&viewer)));
        for &(die, twin) in &order {
            match &self.body {
                Body::Box => self.draw_die(&mut frame, die, twin, line_width),
                Body::Polyhedron(solid) => self.draw_polyhedron(&mut frame, (die, solid), twin, line_width),
            }
        }
        // The twin's edges over everything: where the two dice still coincide, its outline
        // shows on the first die's faces.
        if let Some(twin) = &shot.twin {
            for (a, b) in self.visible_edges(twin, &viewer) {
                frame.line(
                    self.pixel(&twin.corners[a]),
                    self.pixel(&twin.corners[b]),
                    line_width,
                    TWIN_EDGE,
                );
            }
        }

        // The caption band: the headline, then the setup.
        let band_pixels = (self.band as usize * self.width as usize).min(frame.pixels.len());
        frame.pixels[..band_pixels].fill(BAND);
        let mut baseline = self.margin * 0.8 + self.headline_px;
        let text_width_px = f64::from(self.width) - 2.0 * self.margin;
        let headline = wrap_lines(&shot.headline, self.headline_px, text_width_px, true);
        for line in headline.iter().take(self.headline_lines) {
            frame.text(self.margin, baseline, line, self.headline_px, true);
            baseline += self.headline_px * 1.25;
        }
        baseline +=
            (self.headline_lines - headline.len().min(self.headline_lines)) as f64 * self.headline_px * 1.25;
        for line in &self.caption {
            frame.text(self.margin, baseline, line, self.caption_px, false);
            baseline += self.caption_px * 1.25;
        }
        frame
    }

    /// The marked pair's faces (0-based) of the box, `(lower, its opposite)`; none on a twin.
    fn pair(&self, twin: bool) -> Option<(usize, usize)> {
        self.face_pair
            .filter(|_| !twin)
            .map(|(low, high)| (usize::from(low) - 1, usize::from(high) - 1))
    }

    /// The pair's body axis sticking out of face `f` (0-based), half a side past it.
    fn pair_stick(&self, frame: &mut Frame, die: &DieShot, f: usize, line_width: f64) {
        self.stick(frame, die, face_centre(die, f), line_width);
    }

    /// A body axis from the face centred at `centre` on to 1.7 times as far from the die's.
    fn stick(&self, frame: &mut Frame, die: &DieShot, centre: Vector3<f64>, line_width: f64) {
        let tip = die.centre + (centre - die.centre) * 1.7;
        frame.line(self.pixel(&centre), self.pixel(&tip), 2.5 * line_width, EDGE);
    }

    /// The edges of the die the viewer sees, as pairs of its corners.
    fn visible_edges(&self, die: &DieShot, viewer: &Vector3<f64>) -> Vec<(usize, usize)> {
        match &self.body {
            Body::Box => visible_edges(die, viewer),
            Body::Polyhedron(solid) => {
                let mut edges = Vec::new();
                for corners in solid
                    .faces
                    .iter()
                    .filter(|c| polygon_normal(die, c).dot(viewer) > 0.0)
                {
                    for k in 0..corners.len() {
                        let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
                        let e = (a.min(b), a.max(b));
                        if !edges.contains(&e) {
                            edges.push(e);
                        }
                    }
                }
                edges
            }
        }
    }

    /// A polyhedral die: its faces the viewer sees, shaded as the box's are, each with its
    /// numbers; the face up tinted (none on the d4, read at a vertex), the marked pair
    /// coloured with its axis, the edges, and the corners touching the table.
    fn draw_polyhedron(
        &self,
        frame: &mut Frame,
        (die, solid): (&DieShot, &Polyhedral),
        twin: bool,
        line_width: f64,
    ) {
        let viewer = self.camera.towards_viewer();
        let light = self.camera.light();
        let pair = self
            .face_pair
            .filter(|_| !twin)
            .and_then(|(low, high)| Some((solid.face_showing(low)?, solid.face_showing(high)?)));
        let seen = |f: usize| polygon_normal(die, &solid.faces[f]).dot(&viewer) > 0.0;
        let centre_of = |f: usize| polygon_centre(die, &solid.faces[f]);
        for f in pair.iter().flat_map(|&(a, b)| [a, b]).filter(|&f| !seen(f)) {
            self.stick(frame, die, centre_of(f), line_width);
        }
        for (f, corners) in solid.faces.iter().enumerate() {
            let normal = polygon_normal(die, corners);
            let facing = normal.dot(&viewer);
            if facing.is_nan() || facing <= 0.0 {
                continue;
            }
            let lit = 0.3 + 0.7 * normal.dot(&light).max(0.0);
            let up = die.up.is_some() && solid.up_numbers[f] == die.up;
            let ramp = match pair {
                Some((low, _)) if f == low => RAMP + RAMP_STEPS * PAIR_RAMP,
                Some((_, high)) if f == high => RAMP + RAMP_STEPS * (PAIR_RAMP + 1),
                _ => RAMP + RAMP_STEPS * (2 * u8::from(twin) + u8::from(up)),
            };
            let shade = ramp + (lit * f64::from(RAMP_STEPS - 1)).round() as u8;
            let outline: Vec<(f64, f64)> = corners.iter().map(|&k| self.pixel(&die.corners[k])).collect();
            frame.fill_convex(&outline, |_, _| shade);
            // Ink in the pips' colour; the glyphs' edges a darker shade of the face.
            let ink = PIP + (lit * f64::from(PIP_STEPS - 1)).round() as u8;
            let edge = ramp + (0.4 * lit * f64::from(RAMP_STEPS - 1)).round() as u8;
            for label in solid.labels.iter().filter(|l| l.face == f) {
                self.draw_label(frame, (die, corners), label, (ink, edge));
            }
        }
        let edge = if twin { TWIN_EDGE } else { EDGE };
        for (a, b) in self.visible_edges(die, &viewer) {
            frame.line(
                self.pixel(&die.corners[a]),
                self.pixel(&die.corners[b]),
                line_width,
                edge,
            );
        }
        for f in pair.iter().flat_map(|&(a, b)| [a, b]).filter(|&f| seen(f)) {
            self.stick(frame, die, centre_of(f), line_width);
        }
        // A corner touching the table (at or below it), where the viewer sees it.
        let seen_corner = |k: usize| (0..solid.faces.len()).any(|f| solid.faces[f].contains(&k) && seen(f));
        for k in (0..die.corners.len()).filter(|&k| die.corners[k].z <= 0.0 && seen_corner(k)) {
            self.contact_mark(frame, die.corners[k], line_width);
        }
    }

    /// A number on the face `corners` of `die`: its ink bitmap laid on the face (its top
    /// towards the label's vertex) and seen by the camera; each pixel takes `ink` where the
    /// bitmap covers most of it (3 × 3 samples), `edge` where it covers a part.
    fn draw_label(
        &self,
        frame: &mut Frame,
        (die, corners): (&DieShot, &[usize]),
        label: &Label,
        (ink, edge): (u8, u8),
    ) {
        let middle = polygon_centre(die, corners);
        let towards = die.corners[label.toward];
        let centre = middle + (towards - middle) * label.toward_share;
        let normal = polygon_normal(die, corners);
        let up = (towards - centre).normalize();
        let right = up.cross(&normal);
        let bitmap = &label.ink;
        let (w, h) = (bitmap.width as f64, bitmap.height as f64);
        // cm per bitmap pixel, and a bitmap pixel's step right and up on the frame.
        let k = label.height / h;
        let o = self.pixel(&centre);
        let step = |d: Vector3<f64>| {
            let p = self.pixel(&(centre + d * k));
            (p.0 - o.0, p.1 - o.1)
        };
        let (r, u) = (step(right), step(up));
        let det = r.0 * u.1 - r.1 * u.0;
        // Seen edge-on (or not at all: NaN), the face shows no number.
        if det.is_nan() || det.abs() <= 1e-6 {
            return;
        }
        let box_corners = [
            (-w / 2.0, -h / 2.0),
            (w / 2.0, -h / 2.0),
            (w / 2.0, h / 2.0),
            (-w / 2.0, h / 2.0),
        ]
        .map(|(a, b)| (o.0 + r.0 * a + u.0 * b, o.1 + r.1 * a + u.1 * b));
        let (x0, x1, y0, y1) = box_corners.iter().fold(
            (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY),
            |(x0, x1, y0, y1), p| (x0.min(p.0), x1.max(p.0), y0.min(p.1), y1.max(p.1)),
        );
        if !(x0.is_finite() && y0.is_finite()) {
            return;
        }
        const SAMPLES: usize = 3;
        for y in y0.floor() as i64..=y1.ceil() as i64 {
            for x in x0.floor() as i64..=x1.ceil() as i64 {
                let mut covered = 0.0;
                for (i, j) in (0..SAMPLES * SAMPLES).map(|n| (n % SAMPLES, n / SAMPLES)) {
                    let qx = x as f64 + (i as f64 + 0.5) / SAMPLES as f64 - o.0;
                    let qy = y as f64 + (j as f64 + 0.5) / SAMPLES as f64 - o.1;
                    // (qx, qy) = a·r + b·u, a across the bitmap from its centre, b up it.
                    let a = (qx * u.1 - qy * u.0) / det;
                    let b = (r.0 * qy - r.1 * qx) / det;
                    covered += bitmap.at(a + w / 2.0, h / 2.0 - b);
                }
                covered /= (SAMPLES * SAMPLES) as f64;
                if covered >= 0.5 {
                    frame.set(x, y, ink);
                } else if covered >= 0.2 {
                    frame.set(x, y, edge);
                }
            }
        }
    }

    /// The orange dot on a corner touching the table.
    fn contact_mark(&self, frame: &mut Frame, corner: Vector3<f64>, line_width: f64) {
        let (x, y) = self.pixel(&corner);
        let r = (2.2 * line_width).max(2.0);
        let disc: Vec<(f64, f64)> = (0..16)
            .map(|i| {
                let (s, c) = (f64::from(i) * std::f64::consts::TAU / 16.0).sin_cos();
                (x + r * c, y + r * s)
            })
            .collect();
        frame.fill_convex(&disc, |_, _| CONTACT);
    }

    fn draw_die(&self, frame: &mut Frame, die: &DieShot, twin: bool, line_width: f64) {
        let viewer = self.camera.towards_viewer();
        let light = self.camera.light();
        let pair = self.pair(twin);
        // The axis behind the die first, where a face of the pair looks away.
        for f in pair.iter().flat_map(|&(a, b)| [a, b]) {
            if !face_seen(die, f, &viewer) {
                self.pair_stick(frame, die, f, line_width);
            }
        }
        for (f, corners) in FACE_CORNERS.iter().enumerate() {
            let centre = face_centre(die, f);
            let normal = (centre - die.centre).normalize();
            let facing = normal.dot(&viewer);
            if facing.is_nan() || facing <= 0.0 {
                continue;
            }
            let lit = 0.3 + 0.7 * normal.dot(&light).max(0.0);
            let up = die.up == Some(f as u8 + 1);
            let ramp = match pair {
                Some((low, _)) if f == low => RAMP + RAMP_STEPS * PAIR_RAMP,
                Some((_, high)) if f == high => RAMP + RAMP_STEPS * (PAIR_RAMP + 1),
                _ => RAMP + RAMP_STEPS * (2 * u8::from(twin) + u8::from(up)),
            };
            let shade = ramp + (lit * f64::from(RAMP_STEPS - 1)).round() as u8;
            // A face's corners in order around it: FACE_CORNERS lists them as a grid.
            let outline =
                [corners[0], corners[1], corners[3], corners[2]].map(|k| self.pixel(&die.corners[k]));
            frame.fill_convex(&outline, |_, _| shade);
            let pip = PIP + (lit * f64::from(PIP_STEPS - 1)).round() as u8;
            let u = (die.corners[corners[1]] - die.corners[corners[0]]) / 2.0;
            let w = (die.corners[corners[2]] - die.corners[corners[0]]) / 2.0;
            for &(a, b) in PIP_LAYOUT[f] {
                let disc: Vec<(f64, f64)> = (0..24)
                    .map(|k| {
                        let phi = f64::from(k) * std::f64::consts::TAU / 24.0;
                        let (s, c) = phi.sin_cos();
                        self.pixel(&(centre + (a + PIP_RADIUS * c) * u + (b + PIP_RADIUS * s) * w))
                    })
                    .collect();
                frame.fill_convex(&disc, |_, _| pip);
            }
        }
        let edge = if twin { TWIN_EDGE } else { EDGE };
        for (a, b) in visible_edges(die, &viewer) {
            frame.line(
                self.pixel(&die.corners[a]),
                self.pixel(&die.corners[b]),
                line_width,
                edge,
            );
        }
        for f in pair.iter().flat_map(|&(a, b)| [a, b]) {
            if face_seen(die, f, &viewer) {
                self.pair_stick(frame, die, f, line_width);
            }
        }
        // A corner touching the table (at or below it), where the viewer sees it.
        let seen = seen_corners(die, &viewer);
        for k in (0..8).filter(|&k| die.corners[k].z <= 0.0 && seen[k]) {
            self.contact_mark(frame, die.corners[k], line_width);
        }
    }
}

/// `text`'s lines (split at `\n`) each wrapped to `max_width` pixels.
fn wrap_lines(text: &str, px: f64, max_width: f64, bold: bool) -> Vec<String> {
    text.lines()
        .flat_map(|line| wrap(line, px, max_width, bold))
        .collect()
}

/// A pip's radius, in units of the face's half side.
const PIP_RADIUS: f64 = 0.17;

fn face_centre(die: &DieShot, f: usize) -> Vector3<f64> {
    FACE_CORNERS[f]
        .iter()
        .map(|&k| die.corners[k])
        .sum::<Vector3<f64>>()
        / 4.0
}

/// The mean of the corners of a polyhedral die's face.
fn polygon_centre(die: &DieShot, corners: &[usize]) -> Vector3<f64> {
    corners.iter().map(|&k| die.corners[k]).sum::<Vector3<f64>>() / corners.len() as f64
}

/// The outward unit normal of a polyhedral die's face (its corners counter-clockwise seen
/// from outside).
fn polygon_normal(die: &DieShot, corners: &[usize]) -> Vector3<f64> {
    let (a, b, c) = (
        die.corners[corners[0]],
        die.corners[corners[1]],
        die.corners[corners[2]],
    );
    (b - a).cross(&(c - a)).normalize()
}

fn face_seen(die: &DieShot, f: usize, viewer: &Vector3<f64>) -> bool {
    (face_centre(die, f) - die.centre).dot(viewer) > 0.0
}

fn seen_corners(die: &DieShot, viewer: &Vector3<f64>) -> [bool; 8] {
    let mut seen = [false; 8];
    for f in (0..6).filter(|&f| face_seen(die, f, viewer)) {
        for &k in &FACE_CORNERS[f] {
            seen[k] = true;
        }
    }
    seen
}

/// The edges of a convex body the viewer sees: those of a seen face (two corners of a face
/// that differ in one coordinate of the body frame, i.e. not its diagonal).
fn visible_edges(die: &DieShot, viewer: &Vector3<f64>) -> Vec<(usize, usize)> {
    let mut edges = Vec::new();
    for f in (0..6).filter(|&f| face_seen(die, f, viewer)) {
        let c = FACE_CORNERS[f];
        for (a, b) in [(c[0], c[1]), (c[1], c[3]), (c[3], c[2]), (c[2], c[0])] {
            let e = (a.min(b), a.max(b));
            if !edges.contains(&e) {
                edges.push(e);
            }
        }
    }
    edges
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_palette_ramps_are_distinct_and_nothing_draws_the_clear_index() {
        let mut seen = std::collections::HashSet::new();
        for c in &PALETTE[1..RAMP as usize + RAMPS * RAMP_STEPS as usize] {
            seen.insert(*c);
        }
        // Ramps may meet in their darkest steps, but the colours stay many.
        assert!(seen.len() > 200, "{}", seen.len());
    }

    #[test]
    fn no_caption_line_is_wider_than_the_frame() {
        use crate::figure::text_width;
        let die = DieShot {
            corners: dicesim_physics::body::body_corner_offsets(1.0)
                .map(|c| c + Vector3::new(0.0, 0.0, 1.0))
                .to_vec(),
            centre: Vector3::new(0.0, 0.0, 1.0),
            up: Some(4),
        };
        let shot = Shot {
            twin: Some(die.clone()),
            die,
            played_s: 0.0,
            headline: "a-preset-with-a-rather-long-name · t = 12.34 s · did not settle within 30 s\n\
                       twin (ε 1e-9): did not settle within 30 s, 0.01 cm apart"
                .to_string(),
        };
        let caption = [
            "a-preset-with-a-rather-long-name: height 15 cm, velocity (30, 0, 0) cm/s, spin (12, -20, 6) rad/s".to_string(),
            "table k 500000 dyn/cm, γ 0.005 s/cm, μ 1.2; die a 1 cm, m 1 g; g 980 cm/s², Δt 0.001 s".to_string(),
        ];
        for (w, h) in [(64, 64), (160, 120), (640, 480), (1920, 1080)] {
            let view = View {
                camera: Camera::DEFAULT,
                zoom: false,
                face_pair: None,
            };
            let scene = Scene::new(w, h, (view, Body::Box), std::slice::from_ref(&shot), &caption);
            // Between the margins on either side.
            let room = f64::from(w) - 2.0 * scene.margin;
            for line in &scene.caption {
                assert!(
                    text_width(line, scene.caption_px, false) <= room,
                    "{w}×{h}: {line}"
                );
            }
            let headline = wrap_lines(
                &shot.headline,
                scene.headline_px,
                f64::from(w) - 2.0 * scene.margin,
                true,
            );
            assert_eq!(headline.len(), scene.headline_lines);
            for line in &headline {
                assert!(
                    text_width(line, scene.headline_px, true) <= room,
                    "{w}×{h}: {line}"
                );
            }
            // The frame draws: the band and the picture below it.
            let frame = scene.render(&shot);
            assert_eq!(frame.pixels.len(), (w * h) as usize);
        }
    }

    #[test]
    fn hull_and_inside_agree_on_a_square() {
        let h = hull(&[(0.0, 0.0), (1.0, 0.0), (0.5, 0.5), (1.0, 1.0), (0.0, 1.0)]);
        assert_eq!(h.len(), 4);
        assert!(inside(&h, (0.5, 0.5)));
        assert!(!inside(&h, (1.5, 0.5)));
    }
}
