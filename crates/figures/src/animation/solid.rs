//! A polyhedral die as an animation draws it: its hull's faces and the numbers printed on
//! them, each number placed by its face's vertices (so it turns with the die) and inked from
//! a bitmap of DejaVu Sans Bold sampled where the face shows it. The box draws with its
//! pips instead (`render.rs`, [`dicesim_physics::PIP_LAYOUT`]).

use crate::figure::font;
use ab_glyph::{Font, PxScale, ScaleFont, point};
use dicesim_physics::Params;
use dicesim_physics::polyhedron::ReadAt;
use dicesim_setup::number::die_number;
use nalgebra::Vector3;

/// Pixels a label's digits are drawn at in its bitmap, cap to baseline: frames sample it
/// (a few samples a pixel), so it is larger than any number appears on a slide.
const INK_ROWS: f32 = 72.0;

/// A number's ink: a coverage bitmap (0 to 1, row by row from the top), cropped to the ink.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Ink {
    pub(crate) width: usize,
    pub(crate) height: usize,
    coverage: Vec<f32>,
}

impl Ink {
    /// `text` in DejaVu Sans Bold, underlined when `underline` (a 6 or a 9, which a die
    /// shows upside down as often as upright, as real dice mark them).
    fn of(text: &str, underline: bool) -> Ink {
        let font = font(true);
        // ab_glyph's scale is the font's height; DejaVu's digits stand 0.63 of it.
        let scale = PxScale::from(INK_ROWS / 0.63);
        let scaled = font.as_scaled(scale);
        let baseline = scaled.ascent().ceil();
        let (mut width, mut caret) = (0usize, 0.0f32);
        let mut glyphs = Vec::new();
        for c in text.chars() {
            let id = scaled.glyph_id(c);
            glyphs.push(id.with_scale_and_position(scale, point(caret, baseline)));
            caret += scaled.h_advance(id);
            width = caret.ceil() as usize;
        }
        let rows = (baseline - scaled.descent()).ceil() as usize + 1;
        let mut coverage = vec![0.0f32; width * rows];
        for glyph in glyphs {
            let Some(outline) = font.outline_glyph(glyph) else {
                continue;
            };
            let bounds = outline.px_bounds();
            outline.draw(|gx, gy, c| {
                let (x, y) = (bounds.min.x as i64 + gx as i64, bounds.min.y as i64 + gy as i64);
                if (0..width as i64).contains(&x) && (0..rows as i64).contains(&y) {
                    let cell = &mut coverage[y as usize * width + x as usize];
                    *cell = cell.max(c.clamp(0.0, 1.0));
                }
            });
        }
        if underline {
            // A bar a tenth of the digits' height, that far under the baseline.
            let bar = (INK_ROWS * 0.1).round() as usize;
            let top = baseline as usize + bar;
            for y in top..(top + bar).min(rows) {
                coverage[y * width..(y + 1) * width].fill(1.0);
            }
        }
        Ink {
            width,
            height: rows,
            coverage,
        }
        .cropped()
    }

    /// The bitmap cut down to the pixels that carry ink (one blank pixel kept round them).
    fn cropped(self) -> Ink {
        let inked = |x: usize, y: usize| self.coverage[y * self.width + x] > 0.0;
        let rows: Vec<usize> = (0..self.height)
            .filter(|&y| (0..self.width).any(|x| inked(x, y)))
            .collect();
        let columns: Vec<usize> = (0..self.width)
            .filter(|&x| (0..self.height).any(|y| inked(x, y)))
            .collect();
        let (Some(&top), Some(&bottom), Some(&left), Some(&right)) =
            (rows.first(), rows.last(), columns.first(), columns.last())
        else {
            return self;
        };
        let (top, left) = (top.saturating_sub(1), left.saturating_sub(1));
        let (bottom, right) = ((bottom + 1).min(self.height - 1), (right + 1).min(self.width - 1));
        let width = right - left + 1;
        let mut coverage = Vec::with_capacity(width * (bottom - top + 1));
        for y in top..=bottom {
            coverage.extend_from_slice(&self.coverage[y * self.width + left..y * self.width + right + 1]);
        }
        Ink {
            width,
            height: bottom - top + 1,
            coverage,
        }
    }

    /// The coverage at `(x, y)` (bitmap pixels from its top left corner, continuous),
    /// interpolated between the four pixel centres round it; 0 outside.
    pub(crate) fn at(&self, x: f64, y: f64) -> f64 {
        let (fx, fy) = (x - 0.5, y - 0.5);
        let (x0, y0) = (fx.floor(), fy.floor());
        let (tx, ty) = (fx - x0, fy - y0);
        let get = |x: f64, y: f64| -> f64 {
            if x < 0.0 || y < 0.0 || x >= self.width as f64 || y >= self.height as f64 {
                return 0.0;
            }
            f64::from(self.coverage[y as usize * self.width + x as usize])
        };
        let top = get(x0, y0) * (1.0 - tx) + get(x0 + 1.0, y0) * tx;
        let bottom = get(x0, y0 + 1.0) * (1.0 - tx) + get(x0 + 1.0, y0 + 1.0) * tx;
        top * (1.0 - ty) + bottom * ty
    }
}

/// A number printed on a face.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Label {
    /// The face it is printed on (an index into [`Polyhedral::faces`]).
    pub(crate) face: usize,
    /// The vertex its top points at; its centre is the face's centroid moved `toward_share`
    /// of the way to that vertex.
    pub(crate) toward: usize,
    pub(crate) toward_share: f64,
    /// cm, the height of its ink on the die.
    pub(crate) height: f64,
    pub(crate) ink: Ink,
}

/// A polyhedral die's look: its hull, the numbers on its faces, its size.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Polyhedral {
    /// cm, the hull's vertices from the centre of mass, in the die's frame (the frame
    /// `Roll::orientation` turns into the world).
    pub(crate) offsets: Vec<Vector3<f64>>,
    /// Each face's vertices, counter-clockwise seen from outside.
    pub(crate) faces: Vec<Vec<usize>>,
    /// The number each face shows when it is up (`None` on a die read at a vertex, the d4,
    /// whose faces each carry three): the face tinted as the face up, and the faces a pair
    /// marks.
    pub(crate) up_numbers: Vec<Option<u8>>,
    pub(crate) labels: Vec<Label>,
    /// cm, how tall it stands on a face: the table's tiles and a zoomed camera's measure,
    /// as the box's side is.
    pub(crate) side: f64,
}

impl Polyhedral {
    /// The die `params` names (`die.kind`), `None` for the box.
    pub(crate) fn of(params: &Params) -> Option<Polyhedral> {
        let die = params.polyhedral_die()?;
        let kind = params.die.kind;
        let centre = die.mass_properties().centre_of_mass;
        let shape = die.shape();
        let vertices = shape.vertices();
        let numbering = die.numbering();
        let faces: Vec<Vec<usize>> = shape.faces().iter().map(|f| f.vertices.clone()).collect();
        let words = |n: u32| die_number(kind, n as u8);
        let underlined = |n: u32| {
            let all = &numbering.numbers;
            // A 6 or a 9 where the other is on the die too (the d10, the d12, the d20).
            (n == 6 || n == 9) && all.contains(&6) && all.contains(&9)
        };
        let mut labels = Vec::new();
        for (f, corners) in faces.iter().enumerate() {
            let centroid = centroid(vertices, corners);
            let inradius = inradius(vertices, corners, &centroid);
            match numbering.read_at {
                ReadAt::TopVertex => {
                    // Each vertex's label by it: the number read with the face opposite it
                    // down (the one face it is not on).
                    for &v in corners {
                        let Some(opposite) = faces.iter().position(|c| !c.contains(&v)) else {
                            continue;
                        };
                        let n = numbering.numbers[opposite];
                        labels.push(Label {
                            face: f,
                            toward: v,
                            toward_share: 0.52,
                            height: 0.42 * inradius,
                            ink: Ink::of(&words(n), underlined(n)),
                        });
                    }
                }
                ReadAt::TopFace | ReadAt::BottomFace => {
                    let n = numbering.numbers[f];
                    let ink = Ink::of(&words(n), underlined(n));
                    // The farthest vertex is its top (a kite's apex), the first of equals.
                    let toward = corners
                        .iter()
                        .copied()
                        .reduce(|a, b| {
                            let (da, db) = ((vertices[a] - centroid).norm(), (vertices[b] - centroid).norm());
                            if db > da * (1.0 + 1e-9) { b } else { a }
                        })
                        .expect("a face has vertices");
                    // As tall as fits the incircle: the ink's box within 0.85 of its radius.
                    let aspect = ink.width as f64 / ink.height as f64;
                    let height = (0.85 * 2.0 * inradius / (1.0 + aspect * aspect).sqrt()).min(0.9 * inradius);
                    labels.push(Label {
                        face: f,
                        toward,
                        toward_share: 0.0,
                        height,
                        ink,
                    });
                }
            }
        }
        let up_numbers = (0..faces.len())
            .map(|f| match numbering.read_at {
                ReadAt::TopVertex => None,
                _ => Some(numbering.numbers[f] as u8),
            })
            .collect();
        Some(Polyhedral {
            offsets: vertices.iter().map(|v| v - centre).collect(),
            faces,
            up_numbers,
            labels,
            side: params.die.height,
        })
    }

    /// The face that shows `number` up, if one does.
    pub(crate) fn face_showing(&self, number: u8) -> Option<usize> {
        self.up_numbers.iter().position(|&n| n == Some(number))
    }
}

/// The mean of a face's vertices.
fn centroid(vertices: &[Vector3<f64>], corners: &[usize]) -> Vector3<f64> {
    corners.iter().map(|&k| vertices[k]).sum::<Vector3<f64>>() / corners.len() as f64
}

/// cm, how far `centre` lies from the nearest edge of the face `corners`.
fn inradius(vertices: &[Vector3<f64>], corners: &[usize], centre: &Vector3<f64>) -> f64 {
    (0..corners.len())
        .map(|i| {
            let (a, b) = (vertices[corners[i]], vertices[corners[(i + 1) % corners.len()]]);
            let along = (b - a).normalize();
            let r = centre - a;
            (r - along * r.dot(&along)).norm()
        })
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use dicesim_physics::Solid;

    fn die(kind: Solid) -> Polyhedral {
        let mut p = Params::default();
        p.die.kind = kind;
        Polyhedral::of(&p).expect("a polyhedral die")
    }

    /// Every face of a die read at its top face carries its number once; the d4's every
    /// face the three labels of its vertices, each the number read with the face the vertex
    /// is not on down, so the three faces round a vertex show the same number by it.
    #[test]
    fn each_face_carries_its_numbers() {
        let d20 = die(Solid::D20);
        assert_eq!(
            (d20.faces.len(), d20.offsets.len(), d20.labels.len()),
            (20, 12, 20)
        );
        let mut shown: Vec<u8> = d20.up_numbers.iter().map(|n| n.unwrap()).collect();
        shown.sort_unstable();
        assert_eq!(shown, Solid::D20.face_numbers());
        let d4 = die(Solid::D4);
        assert_eq!(d4.labels.len(), 12);
        assert!(d4.up_numbers.iter().all(Option::is_none));
        for v in 0..4 {
            let by: Vec<&Label> = d4.labels.iter().filter(|l| l.toward == v).collect();
            assert_eq!(by.len(), 3, "three faces meet at a tetrahedron's vertex");
            assert!(by.iter().all(|l| l.ink == by[0].ink));
        }
        assert!(Polyhedral::of(&Params::default()).is_none(), "the box has pips");
    }

    /// A label stays on its face: its ink's box, centred where it is put, lies inside the
    /// face (each corner of the box behind every edge of the face).
    #[test]
    fn every_label_fits_inside_its_face() {
        for kind in [
            Solid::D4,
            Solid::D8,
            Solid::D10,
            Solid::Percentile,
            Solid::D12,
            Solid::D20,
        ] {
            let d = die(kind);
            for l in &d.labels {
                let corners = &d.faces[l.face];
                let v = |k: usize| d.offsets[corners[k]];
                let c = centroid(&d.offsets, corners);
                let centre = c + (d.offsets[l.toward] - c) * l.toward_share;
                let normal = (v(1) - v(0)).cross(&(v(2) - v(0))).normalize();
                let up = (d.offsets[l.toward] - centre).normalize();
                let right = up.cross(&normal);
                let (h, w) = (
                    l.height / 2.0,
                    l.height * l.ink.width as f64 / l.ink.height as f64 / 2.0,
                );
                for (a, b) in [(-w, -h), (w, -h), (w, h), (-w, h)] {
                    let p = centre + right * a + up * b;
                    for k in 0..corners.len() {
                        let (e0, e1) = (v(k), v((k + 1) % corners.len()));
                        // Inside: left of every edge, counter-clockwise seen from outside.
                        let inside = (e1 - e0).cross(&(p - e0)).dot(&normal);
                        assert!(
                            inside > 0.0,
                            "{}: a label of face {} leaves it",
                            kind.name(),
                            l.face
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn a_two_digit_number_is_wider_than_tall_and_a_percentile_reads_00() {
        let one = Ink::of("7", false);
        let two = Ink::of("20", false);
        assert!(
            two.width > one.width && two.width > two.height,
            "{}×{}",
            two.width,
            two.height
        );
        let d100 = die(Solid::Percentile);
        let zero = d100
            .labels
            .iter()
            .find(|l| d100.up_numbers[l.face] == Some(0))
            .unwrap();
        assert_eq!(zero.ink, Ink::of("00", false));
        // A 6 on the d20 is underlined: its ink reaches lower than a 5's.
        assert!(Ink::of("6", true).height > Ink::of("5", false).height);
    }
}
