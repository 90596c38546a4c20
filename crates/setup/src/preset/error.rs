//! What can be wrong with a preset, said so that a user can find and fix it.

use super::contents::FORMAT;
use dicesim_physics::ParamError;
use std::fmt;
use std::path::PathBuf;

/// Where in a preset a problem is: the file (or `shipped/NAME.toml`), and the 1-based line
/// and column when known. Displays as `file:line:column`, as compilers do, so editors can jump
/// there.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    pub(crate) origin: String,
    pub line: Option<usize>,
    pub column: Option<usize>,
}

impl Location {
    /// The whole file, no position.
    pub(crate) fn file(origin: &str) -> Location {
        Location {
            origin: origin.to_string(),
            line: None,
            column: None,
        }
    }

    /// The position of byte `offset` of `text`.
    pub fn at(origin: &str, text: &str, offset: usize) -> Location {
        let offset = offset.min(text.len());
        let before = text.get(..offset).unwrap_or(text);
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        Location {
            origin: origin.to_string(),
            line: Some(before.matches('\n').count() + 1),
            column: Some(before[line_start..].chars().count() + 1),
        }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.origin)?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
            if let Some(column) = self.column {
                write!(f, ":{column}")?;
            }
        }
        Ok(())
    }
}

/// What can be wrong with a preset, an override, a name or a save.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PresetError {
    /// `--set KEY=VALUE` that names no key or gives a value of the wrong kind.
    #[error("--set {key}: {message}")]
    Override { key: String, message: String },
    /// A value outside its allowed range (from an override or a preset built in code).
    #[error("{0}")]
    OutOfRange(#[from] ParamError),
    /// The file is not TOML.
    #[error("{at}: {message}")]
    Syntax { at: Location, message: String },
    /// An unknown key, a value of the wrong type, or keys that contradict each other.
    #[error("{at}: key `{key}`: {message}")]
    Key {
        at: Location,
        key: String,
        message: String,
    },
    /// A value outside its allowed range, in a file.
    #[error("{at}: {error}")]
    Range { at: Location, error: Box<ParamError> },
    /// Written by a newer dicesim in a format this one does not know.
    #[error(
        "{at}: preset format {found} is newer than this dicesim understands (it reads format {FORMAT}); \
         update dicesim to load it"
    )]
    NewerFormat { at: Location, found: i64 },
    /// A name that is not a plain file stem.
    #[error("bad preset name `{name}`: {reason}")]
    BadName { name: String, reason: String },
    /// Saving would replace an existing preset and the user did not confirm.
    #[error("preset `{name}` already exists ({}); nothing was written", path.display())]
    Exists { name: String, path: PathBuf },
    /// No preset of that name in the user's folder or the shipped set.
    #[error("no preset named `{name}` (looked in {searched}); known presets: {}", known.join(", "))]
    NotFound {
        name: String,
        searched: String,
        known: Vec<String>,
    },
    /// Neither `DICESIM_PRESETS` nor a home directory gives a user preset folder.
    #[error("no user preset folder: there is no home directory; set DICESIM_PRESETS to a folder")]
    NoUserFolder,
    /// Reading or writing a file failed.
    #[error("{}: {message}", path.display())]
    Io { path: PathBuf, message: String },
    /// Writing a preset failed while it was written (a full disk, a lost device): a failure
    /// while running, not bad input. Nothing was saved (the write is atomic).
    #[error("{}: {message}; nothing was saved", path.display())]
    Write { path: PathBuf, message: String },
}

impl PresetError {
    pub(crate) fn io(path: impl Into<PathBuf>, e: &std::io::Error) -> PresetError {
        PresetError::Io {
            path: path.into(),
            message: e.to_string(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn location_counts_lines_and_characters_from_one() {
        let text = "a = 1\n[ground]\nfriction = \"µ\" # x\n";
        let at = Location::at("f.toml", text, text.find("# x").unwrap());
        assert_eq!((at.line, at.column), (Some(3), Some(16)));
        assert_eq!(at.to_string(), "f.toml:3:16");
        assert_eq!(Location::at("f.toml", text, 0).to_string(), "f.toml:1:1");
        assert_eq!(Location::file("f.toml").to_string(), "f.toml");
    }
}
