//! A lesson: the steps a teacher walks a class through in the explorer, one `[[step]]` of a
//! TOML file each (docs/lesson.md). A step names the preset it opens and how to show it
//! (speed, arrows, plot, screen, twin) and says one sentence, which the explorer shows in
//! large type. The shipped lesson is the crate's `lesson.toml`, whose steps also carry the
//! README's words and the keys its test presses; a teacher's own file needs only the
//! step's own keys. A file is read as a preset is: an unknown key, a value of the wrong
//! kind, a preset that does not load or a sentence the large type cannot show is refused
//! with the file, line and column.

use crate::tui::vocabulary::big_type;
use dicesim_setup::preset::{Location, Preset, Speed, Store};
use dicesim_setup::quantity::QUANTITIES;
use serde::Deserialize;
use std::ops::Range;
use toml::Spanned;

/// The shipped lesson, the README's "In the classroom".
pub const SHIPPED: &str = include_str!("../lesson.toml");

/// Columns of large type a sentence has on a projector's 80×24 (the card's inner width).
pub(crate) const SAY_COLUMNS: usize = 76;
/// Lines of large type a sentence may take there.
pub(crate) const SAY_LINES: usize = 4;

/// A lesson read and checked: every step's preset loaded.
#[derive(Debug, Clone, PartialEq)]
pub struct Lesson {
    /// Where it was read from, as messages name it.
    pub origin: String,
    pub steps: Vec<Step>,
}

/// One step: what it opens and shows, and its sentence.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// A few words, shown small above the sentence (and in the README, in bold).
    pub title: String,
    /// The sentence the class reads, in large type.
    pub say: String,
    /// The preset the step opens, with the step's view over its own.
    pub preset: Box<Preset>,
    /// The plot: `None` the energy terms (also when the step names none, so a step looks the
    /// same whichever step came before), `Some(i)` `QUANTITIES[i]` against time.
    pub plot: Option<usize>,
    /// The plot's value axis fitted to the time on screen (`y`) or the whole roll's.
    pub fit: Option<bool>,
    /// The presentation view (`P`) rather than the die screen.
    pub presentation: bool,
    /// The chaos twin turned off (a step's `twin = false`).
    pub twin_off: bool,
    /// The row of the parameter list selected (index into the rows the preset's contact
    /// law reads), for the value the step asks the class to change.
    pub select: Option<usize>,
    /// The shipped file's own: the keys its test presses, what it then sees, the README's words.
    pub keys: Vec<String>,
    pub see: Vec<String>,
    pub text: String,
    /// Line of the file where the step's table begins.
    pub line: usize,
}

/// Why a lesson file was refused: where, and what is wrong.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{at}: {message}")]
pub struct LessonError {
    pub at: Location,
    pub message: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    /// The README's words before the steps.
    #[serde(default)]
    #[allow(dead_code, reason = "read by the README's test, tests/cli/docs.rs")]
    intro: String,
    step: Vec<Spanned<StepFile>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct StepFile {
    title: String,
    say: Spanned<String>,
    preset: Spanned<String>,
    speed: Option<Speed>,
    arrows: Option<bool>,
    plot: Option<Spanned<String>>,
    fit: Option<bool>,
    screen: Option<Spanned<String>>,
    twin: Option<Spanned<TwinFile>>,
    select: Option<Spanned<String>>,
    #[serde(default)]
    keys: Vec<String>,
    #[serde(default)]
    see: Vec<String>,
    #[serde(default)]
    text: String,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum TwinFile {
    On(bool),
    Epsilon(f64),
}

/// The words a step's `plot` takes: the energy terms, or a quantity by its CSV column.
pub(crate) fn plot_names() -> impl Iterator<Item = &'static str> {
    std::iter::once("energy").chain(QUANTITIES.iter().map(|q| q.column))
}

impl Lesson {
    /// The lesson in `text` (from `origin`, as messages name it), its presets loaded from `store`.
    pub fn read(text: &str, origin: &str, store: &Store) -> Result<Lesson, LessonError> {
        let at = |span: Option<Range<usize>>| match span {
            Some(s) => Location::at(origin, text, s.start),
            None => Location::at(origin, text, 0),
        };
        let file: File = toml::from_str(text).map_err(|e| LessonError {
            at: at(e.span()),
            message: e.message().to_string(),
        })?;
        if file.step.is_empty() {
            return Err(LessonError {
                at: at(None),
                message: "a lesson needs at least one [[step]]".to_string(),
            });
        }
        let refuse = |span: Range<usize>, message: String| LessonError {
            at: at(Some(span)),
            message,
        };
        let mut steps = Vec::new();
        for spanned in file.step {
            let span = spanned.span();
            let s = spanned.into_inner();
            let say = s.say.get_ref();
            let missing = big_type::missing(say);
            if !missing.is_empty() {
                let list: String = missing.iter().collect();
                return Err(refuse(
                    s.say.span(),
                    format!(
                        "key `say`: large type has no letter for `{list}` (it has A–Z, 0–9 and . , : ; ! ? ' \" - + = × / % ( ) ° ·)"
                    ),
                ));
            }
            match big_type::wrap(say, SAY_COLUMNS) {
                Some(lines) if lines.len() <= SAY_LINES => {}
                _ => {
                    return Err(refuse(
                        s.say.span(),
                        format!(
                            "key `say`: too long for large type on an 80×24 screen ({SAY_LINES} lines of about \
                             19 letters); put the rest in what you say aloud"
                        ),
                    ));
                }
            }
            let (mut preset, _) = store
                .load(s.preset.get_ref())
                .map_err(|e| refuse(s.preset.span(), format!("key `preset`: {e}")))?;
            let plot = match &s.plot {
                None => None,
                Some(p) if p.get_ref() == "energy" => None,
                Some(p) => match QUANTITIES.iter().position(|q| q.column == p.get_ref()) {
                    Some(i) => Some(i),
                    None => {
                        return Err(refuse(
                            p.span(),
                            format!(
                                "key `plot`: no plot `{}`; one of {}",
                                p.get_ref(),
                                plot_names().collect::<Vec<_>>().join(", ")
                            ),
                        ));
                    }
                },
            };
            let presentation = match &s.screen {
                None => false,
                Some(n) => match n.get_ref().as_str() {
                    "die" => false,
                    "map" => {
                        preset.view.screen = Some(dicesim_setup::preset::Screen::Map);
                        false
                    }
                    "presentation" => true,
                    other => {
                        return Err(refuse(
                            n.span(),
                            format!("key `screen`: no screen `{other}`; one of die, map, presentation"),
                        ));
                    }
                },
            };
            if s.screen.as_ref().is_some_and(|n| n.get_ref() != "map") {
                preset.view.screen = Some(dicesim_setup::preset::Screen::Die);
            }
            if let Some(speed) = s.speed {
                preset.view.speed = Some(speed);
            }
            if let Some(arrows) = s.arrows {
                preset.view.arrows = Some(arrows);
            }
            let mut twin_off = false;
            if let Some(t) = &s.twin {
                match t.get_ref() {
                    TwinFile::On(false) => twin_off = true,
                    TwinFile::On(true) => {
                        preset.view.twin =
                            Some(preset.view.twin.unwrap_or(dicesim_setup::chaos::DEFAULT_EPSILON))
                    }
                    TwinFile::Epsilon(e) => {
                        let limits = dicesim_physics::Limits {
                            key: "twin",
                            ..dicesim_setup::chaos::EPSILON
                        };
                        limits.check(*e).map_err(|e| refuse(t.span(), e.to_string()))?;
                        preset.view.twin = Some(*e);
                    }
                }
            }
            let rows = crate::tui::vocabulary::param::listed(&preset.params());
            let select = match &s.select {
                None => None,
                Some(k) => Some(rows.iter().position(|p| p.key() == k.get_ref()).ok_or_else(|| {
                    refuse(
                        k.span(),
                        format!(
                            "key `select`: `{}` is not a row of {}'s parameter list; one of {}",
                            k.get_ref(),
                            preset.name,
                            rows.iter().map(|p| p.key()).collect::<Vec<_>>().join(", ")
                        ),
                    )
                })?),
            };
            steps.push(Step {
                title: s.title,
                say: s.say.into_inner(),
                preset: Box::new(preset),
                plot,
                fit: s.fit,
                presentation,
                twin_off,
                select,
                keys: s.keys,
                see: s.see,
                text: s.text,
                line: Location::at(origin, text, span.start).line.unwrap_or(1),
            });
        }
        Ok(Lesson {
            origin: origin.to_string(),
            steps,
        })
    }

    /// The shipped lesson, its presets the shipped ones (or the user's of the same name).
    pub fn shipped(store: &Store) -> Result<Lesson, LessonError> {
        Lesson::read(SHIPPED, "lesson.toml", store)
    }

    /// The lesson in the file at `path`.
    pub fn from_file(path: &std::path::Path, store: &Store) -> Result<Lesson, LessonError> {
        let origin = path.display().to_string();
        let text =
            dicesim_setup::preset::read_regular_file(path, 1 << 20).map_err(|message| LessonError {
                at: Location::at(&origin, "", 0),
                message,
            })?;
        Lesson::read(&text, &origin, store)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refused(text: &str) -> String {
        Lesson::read(text, "mine.toml", &Store::new(None))
            .expect_err("refused")
            .to_string()
    }

    const STEP: &str = "[[step]]\ntitle = \"Drop\"\nsay = \"Watch it fall.\"\npreset = \"paper\"\n";

    #[test]
    fn the_shipped_lesson_reads_and_every_sentence_fits_the_large_type() {
        let lesson = Lesson::shipped(&Store::new(None)).expect("the shipped lesson reads");
        assert!(lesson.steps.len() >= 10);
        for s in &lesson.steps {
            let lines = big_type::wrap(&s.say, SAY_COLUMNS).expect("no word too wide");
            assert!(lines.len() <= SAY_LINES, "{}", s.say);
        }
    }

    /// The picker's "for the lesson" lists every preset the shipped lesson opens, in the
    /// order it first opens them (steps 10 to 12's included).
    #[test]
    fn the_pickers_lesson_presets_are_the_lessons() {
        let lesson = Lesson::shipped(&Store::new(None)).expect("reads");
        let mut opened: Vec<&str> = Vec::new();
        for s in &lesson.steps {
            if !opened.contains(&s.preset.name.as_str()) {
                opened.push(&s.preset.name);
            }
        }
        assert_eq!(opened, dicesim_setup::preset::LESSON);
    }

    #[test]
    fn a_teachers_step_needs_only_its_title_sentence_and_preset() {
        let l = Lesson::read(STEP, "mine.toml", &Store::new(None)).expect("reads");
        assert_eq!(l.steps[0].preset.name, "paper");
        assert_eq!((l.steps[0].plot, l.steps[0].line), (None, 1));
    }

    #[test]
    fn a_malformed_lesson_is_refused_naming_its_line() {
        // An unknown key, on line 5.
        let e = refused(&format!("{STEP}colour = \"red\"\n"));
        assert!(e.starts_with("mine.toml:5:") && e.contains("colour"), "{e}");
        // A preset that does not exist, on line 4.
        let e = refused(&STEP.replace("\"paper\"", "\"no-such\""));
        assert!(e.starts_with("mine.toml:4:") && e.contains("no-such"), "{e}");
        // A sentence with a letter the large type lacks, on line 3.
        let e = refused(&STEP.replace("Watch it fall.", "ω grows"));
        assert!(e.starts_with("mine.toml:3:") && e.contains("`ω`"), "{e}");
        // Too long for four lines.
        let long = "word ".repeat(60);
        let e = refused(&STEP.replace("Watch it fall.", &long));
        assert!(e.starts_with("mine.toml:3:") && e.contains("too long"), "{e}");
        // A plot that is not one, a speed off the ladder, a twin out of range.
        let e = refused(&format!("{STEP}plot = \"colour\"\n"));
        assert!(e.starts_with("mine.toml:5:") && e.contains("e_total_erg"), "{e}");
        let e = refused(&format!("{STEP}speed = \"3×\"\n"));
        assert!(e.starts_with("mine.toml:5:"), "{e}");
        let e = refused(&format!("{STEP}twin = 5.0\n"));
        assert!(e.starts_with("mine.toml:5:") && e.contains("twin"), "{e}");
        // Not TOML at all, and no steps.
        assert!(refused("[[step]\n").starts_with("mine.toml:1:"));
        assert!(refused("intro = \"x\"\n").contains("step"));
    }
}
