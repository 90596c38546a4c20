//! Where presets are found and saved (docs/presets.md): a path given directly; else the user's
//! preset folder; else the shipped set. The user's folder wins on a name clash.

use super::contents::Preset;
use super::error::PresetError;
use super::shipped;
use crate::output::{Output, OutputError};
use std::path::{Path, PathBuf};

/// Overrides the user's preset folder (otherwise the platform's data directory + `presets/`).
pub const PRESETS_ENV: &str = "DICESIM_PRESETS";

/// Where a preset was found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Source {
    /// A file named directly (`--preset ./lab/x.toml`).
    Path(PathBuf),
    /// A file in the user's preset folder.
    User(PathBuf),
    /// Compiled into the binary from the repository's `presets/`.
    Shipped,
}

impl Source {
    /// `path`, `user` or `shipped`, as `presets list` shows it.
    pub fn kind(&self) -> &'static str {
        match self {
            Source::Path(_) => "path",
            Source::User(_) => "user",
            Source::Shipped => "shipped",
        }
    }
}

/// One line of `presets list`: a name and where it lives; the preset, or why it does not load.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// What `--preset` takes to load it.
    pub name: String,
    pub source: Source,
    pub preset: Result<Preset, PresetError>,
}

/// The places presets are looked up in and saved to.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Store {
    user_dir: Option<PathBuf>,
}

impl Store {
    /// A store whose user folder is `user_dir` (None: only paths and the shipped set).
    pub fn new(user_dir: Option<PathBuf>) -> Store {
        Store { user_dir }
    }

    /// The user folder from `DICESIM_PRESETS`, else the platform's data directory +
    /// `presets/` (e.g. `~/.local/share/dicesim/presets/`).
    pub fn from_env() -> Store {
        let user_dir = match std::env::var_os(PRESETS_ENV) {
            Some(dir) if !dir.is_empty() => Some(PathBuf::from(dir)),
            _ => directories::ProjectDirs::from("", "", "dicesim").map(|d| d.data_dir().join("presets")),
        };
        Store { user_dir }
    }

    /// The user's preset folder (it may not exist yet: saving creates it).
    pub fn user_dir(&self) -> Result<&Path, PresetError> {
        self.user_dir.as_deref().ok_or(PresetError::NoUserFolder)
    }

    /// Loads `spec`: a path if it contains `/`, ends in `.toml` or names an existing file;
    /// else the preset of that name in the user folder, else the shipped one.
    pub fn load(&self, spec: &str) -> Result<(Preset, Source), PresetError> {
        if is_path(spec) {
            let path = PathBuf::from(spec);
            return Ok((load_file(&path)?, Source::Path(path)));
        }
        check_name(spec)?;
        if let Some(path) = self.user_path(spec)
            && path.is_file()
        {
            return Ok((load_file(&path)?, Source::User(path)));
        }
        if let Some(preset) = shipped::load(spec) {
            return Ok((preset?, Source::Shipped));
        }
        let searched = match &self.user_dir {
            Some(dir) => format!("{} and the shipped presets", dir.display()),
            None => "the shipped presets".to_string(),
        };
        Err(PresetError::NotFound {
            name: spec.to_string(),
            searched,
            known: self.list().into_iter().map(|e| e.name).collect(),
        })
    }

    /// [`Store::load`], or with no name the default ([`Preset::default`]).
    pub fn load_or_default(&self, spec: Option<&str>) -> Result<(Preset, Source), PresetError> {
        match spec {
            Some(spec) => self.load(spec),
            None => Ok((Preset::default(), Source::Shipped)),
        }
    }

    /// Every preset that loads by name: the user's (sorted by name), then the shipped ones
    /// that no user preset hides. Files that fail to load are listed with their error.
    pub fn list(&self) -> Vec<Entry> {
        let mut user: Vec<Entry> = Vec::new();
        if let Some(dir) = &self.user_dir
            && let Ok(read) = std::fs::read_dir(dir)
        {
            for path in read.filter_map(|e| e.ok()).map(|e| e.path()) {
                // A crash mid-save can leave `.tmpXXXXXX` files: only `*.toml` are presets.
                let stem = match (path.extension(), path.file_stem().and_then(|s| s.to_str())) {
                    (Some(ext), Some(stem)) if ext == "toml" && check_name(stem).is_ok() => stem.to_string(),
                    _ => continue,
                };
                user.push(Entry {
                    name: stem,
                    preset: load_file(&path),
                    source: Source::User(path),
                });
            }
        }
        user.sort_by(|a, b| a.name.cmp(&b.name));
        let shipped: Vec<Entry> = shipped::SHIPPED
            .iter()
            .filter(|(name, _)| !user.iter().any(|u| u.name == *name))
            .map(|(name, _)| Entry {
                name: name.to_string(),
                source: Source::Shipped,
                preset: shipped::load(name).expect("listed in SHIPPED"),
            })
            .collect();
        user.extend(shipped);
        user
    }

    /// Where the user preset `name` is (or would be) saved.
    pub(crate) fn path_of(&self, name: &str) -> Result<PathBuf, PresetError> {
        check_name(name)?;
        Ok(self.user_dir()?.join(format!("{name}.toml")))
    }

    /// Whether saving `name` would replace a preset (the TUI asks first).
    pub fn exists(&self, name: &str) -> bool {
        self.path_of(name).is_ok_and(|p| p.exists())
    }

    /// Saves `preset` into the user folder as `<preset.name>.toml`: the whole file, written
    /// atomically. An existing file is replaced only with `replace`; on any error nothing is
    /// written and an old file is left as it was.
    pub fn save(&self, preset: &Preset, replace: bool) -> Result<PathBuf, PresetError> {
        let path = self.path_of(&preset.name)?;
        preset.validate()?;
        let text = preset.to_toml();
        // The file must read back as this preset, or saving would lose something.
        let origin = path.display().to_string();
        let reread = Preset::from_toml_str(&text, &origin)?;
        if reread != preset.as_written() {
            return Err(PresetError::Io {
                path,
                message: "the preset does not survive writing (a seed above 2⁶³ − 1?)".to_string(),
            });
        }
        if !replace && path.exists() {
            return Err(PresetError::Exists {
                name: preset.name.clone(),
                path,
            });
        }
        let dir = self.user_dir()?;
        if dir.exists() && !dir.is_dir() {
            return Err(PresetError::Io {
                path: dir.to_path_buf(),
                message: format!(
                    "is a file, but the user's presets are saved in a folder there; move it, or set {PRESETS_ENV} \
                     to another folder"
                ),
            });
        }
        std::fs::create_dir_all(dir).map_err(|e| PresetError::io(dir, &e))?;
        Output::check(&path, &["toml"], replace)
            .and_then(|out| out.write_bytes(text.as_bytes()))
            .map_err(|e| match e {
                OutputError::Exists { .. } => PresetError::Exists {
                    name: preset.name.clone(),
                    path: path.clone(),
                },
                OutputError::Write { message, .. } => PresetError::Write {
                    path: path.clone(),
                    message,
                },
                e => PresetError::Io {
                    path: path.clone(),
                    message: e.to_string(),
                },
            })?;
        Ok(path)
    }

    fn user_path(&self, name: &str) -> Option<PathBuf> {
        self.user_dir.as_ref().map(|d| d.join(format!("{name}.toml")))
    }
}

/// A `/`, a `.toml` ending, or an existing file mean a path, not a name.
fn is_path(spec: &str) -> bool {
    spec.contains('/')
        || spec.contains(std::path::MAIN_SEPARATOR)
        || spec.ends_with(".toml")
        || Path::new(spec).is_file()
}

/// A preset name is a file stem of letters, digits, `-` and `_`: never a path, never `..`.
pub fn check_name(name: &str) -> Result<(), PresetError> {
    let bad = |reason: &str| {
        Err(PresetError::BadName {
            name: name.to_string(),
            reason: reason.to_string(),
        })
    };
    if name.is_empty() {
        return bad("it is empty");
    }
    if name.contains(['/', '\\']) || name.contains("..") {
        return bad("a name is not a path; use only letters, digits, `-` and `_`");
    }
    if let Some(c) = name
        .chars()
        .find(|c| !(c.is_ascii_alphanumeric() || *c == '-' || *c == '_'))
    {
        return bad(&format!(
            "`{c}` is not allowed; use only letters, digits, `-` and `_`"
        ));
    }
    Ok(())
}

/// The largest preset file read, bytes: a whole setup takes a few kB.
pub(crate) const MAX_PRESET_BYTES: u64 = 1024 * 1024;

/// The text of the regular file at `path`, at most `max_bytes` long. Devices, pipes and
/// folders are refused without being opened, so nothing blocks (a FIFO) or reads forever
/// (`/dev/zero`).
pub fn read_regular_file(path: &Path, max_bytes: u64) -> Result<String, String> {
    use std::io::Read;
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if !meta.is_file() {
        return Err("not a regular file (a folder, device or pipe): skipped".to_string());
    }
    let too_big = || format!("larger than the {} bytes allowed", max_bytes);
    if meta.len() > max_bytes {
        return Err(too_big());
    }
    let mut text = String::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(max_bytes + 1).read_to_string(&mut text))
        .map_err(|e| e.to_string())?;
    if text.len() as u64 > max_bytes {
        return Err(too_big());
    }
    Ok(text)
}

/// Reads a preset file; errors name the path. A preset without a `name` takes its file stem.
pub fn load_file(path: &Path) -> Result<Preset, PresetError> {
    let text = read_regular_file(path, MAX_PRESET_BYTES).map_err(|message| PresetError::Io {
        path: path.to_path_buf(),
        message,
    })?;
    let mut preset = Preset::from_toml_str(&text, &path.display().to_string())?;
    if preset.name.is_empty() {
        preset.name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
    }
    Ok(preset)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_plain_file_stems() {
        for ok in ["mine", "gentle-drop", "Lab_2", "x1"] {
            check_name(ok).unwrap();
        }
        for bad in ["", "..", "a/b", "../up", "a.toml", "a b", "é", "a\\b"] {
            let e = check_name(bad).unwrap_err();
            assert!(
                e.to_string().starts_with(&format!("bad preset name `{bad}`")),
                "{e}"
            );
        }
    }

    #[test]
    fn paths_are_told_from_names() {
        assert!(is_path("./x"));
        assert!(is_path("lab/x"));
        assert!(is_path("x.toml"));
        assert!(!is_path("gentle-drop"));
        assert!(!is_path(".."));
    }

    #[test]
    fn a_file_where_the_folder_should_be_is_named() {
        let root = tempfile::tempdir().unwrap();
        let dir = root.path().join("presets");
        std::fs::write(&dir, "not a folder").unwrap();
        let preset = Preset {
            name: "mine".to_string(),
            ..Preset::default()
        };
        let e = Store::new(Some(dir.clone())).save(&preset, false).unwrap_err();
        assert!(
            e.to_string().starts_with(&format!(
                "{}: is a file, but the user's presets are saved in a folder",
                dir.display()
            )),
            "{e}"
        );
        let huge = root.path().join("huge.toml");
        std::fs::write(&huge, format!("description = \"{}\"\n", "x".repeat(2 << 20))).unwrap();
        let e = load_file(&huge).unwrap_err();
        assert!(
            e.to_string().ends_with("larger than the 1048576 bytes allowed"),
            "{e}"
        );
    }

    #[test]
    fn no_user_folder_still_finds_shipped_presets() {
        let store = Store::new(None);
        assert_eq!(store.load("icy-table").unwrap().1, Source::Shipped);
        assert_eq!(store.user_dir().unwrap_err(), PresetError::NoUserFolder);
        assert!(matches!(
            store.save(&Preset::default(), false),
            Err(PresetError::NoUserFolder)
        ));
    }
}
