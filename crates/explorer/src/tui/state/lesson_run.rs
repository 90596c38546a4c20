//! A lesson being walked: which step is open and whether its card (the sentence in large
//! type) is up. The steps come from [`crate::lesson::Lesson`]; the lesson's keys
//! (`input/lesson_keys.rs`) move through them, and any other key puts the card down and
//! works on the screen under it, so the teacher can do anything between two steps.

use crate::lesson::{Lesson, Step};

#[derive(Debug, Clone, PartialEq)]
pub(crate) struct LessonRun {
    pub(crate) lesson: Lesson,
    /// The step open (index into the lesson's steps); `None` before the first.
    pub(crate) at: Option<usize>,
    /// Whether the step's card is up, over the screen.
    pub(crate) card: bool,
}

impl LessonRun {
    /// `lesson`, no step open yet.
    pub(crate) fn new(lesson: Lesson) -> LessonRun {
        LessonRun {
            lesson,
            at: None,
            card: false,
        }
    }

    /// The step open, if any.
    pub(crate) fn step(&self) -> Option<&Step> {
        self.at.and_then(|i| self.lesson.steps.get(i))
    }

    /// How many steps the lesson has.
    pub(crate) fn len(&self) -> usize {
        self.lesson.steps.len()
    }
}
