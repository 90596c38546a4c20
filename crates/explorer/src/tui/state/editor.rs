//! Text being typed: a value, the batch size, ε, a map range. State only; the keys that
//! reach it come already read through the key table.

use crate::tui::vocabulary::key_table::{Action, Input, Scope, label};

/// A value being typed in (Enter on a parameter).
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Editor {
    pub(crate) text: String,
    /// Why the last Enter was refused.
    pub(crate) error: Option<String>,
}

/// What a key did to a number being typed.
pub(crate) enum Typed {
    Cancelled,
    /// Enter: the trimmed text, parsed (or why it is not a number).
    Submitted(Result<f64, String>),
    Editing,
}

impl Editor {
    /// Every printable character is typed (up to `limit`, so the text fits its line);
    /// Backspace deletes; Enter submits the number; Esc cancels. Typing clears the last error.
    pub(crate) fn input(&mut self, input: &Input, limit: usize) -> Typed {
        match input {
            Input::Act {
                action: Action::Close,
                ..
            } => return Typed::Cancelled,
            Input::Act {
                action: Action::Delete,
                ..
            } => {
                self.text.pop();
            }
            Input::Type(c) => {
                if self.text.chars().count() < limit {
                    self.text.push(*c);
                }
            }
            Input::Act {
                action: Action::Confirm,
                ..
            } => {
                let text = self.text.trim();
                return Typed::Submitted(match text.parse::<f64>() {
                    Ok(v) => Ok(v),
                    Err(_) if text.is_empty() => Err(format!(
                        "type a number, or {} to cancel",
                        label(Scope::Text, Action::Close)
                    )),
                    Err(_) => Err(format!("`{text}` is not a number")),
                });
            }
            _ => return Typed::Editing,
        }
        self.error = None;
        Typed::Editing
    }
}

/// Characters a typed value may hold: more than any number needs, fewer than its line.
pub(crate) const VALUE_CHARS: usize = 24;
