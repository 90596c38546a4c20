//! Where presets are found and saved (docs/presets.md): a path given directly; else the user's
//! preset folder; else the shipped set. The user's folder wins on a name clash.

use super::{Preset, PresetError, shipped};
use std::io::Write;
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
    pub(crate) fn kind(&self) -> &'static str {
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
    pub(crate) fn user_dir(&self) -> Result<&Path, PresetError> {
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
        std::fs::create_dir_all(dir).map_err(|e| PresetError::io(dir, &e))?;
        write_atomic(&path, &text, replace).map_err(|e| match e.kind() {
            std::io::ErrorKind::AlreadyExists => PresetError::Exists {
                name: preset.name.clone(),
                path: path.clone(),
            },
            _ => PresetError::io(&path, &e),
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

/// Reads a preset file; errors name the path. A preset without a `name` takes its file stem.
pub fn load_file(path: &Path) -> Result<Preset, PresetError> {
    let text = std::fs::read_to_string(path).map_err(|e| PresetError::io(path, &e))?;
    let mut preset = Preset::from_toml_str(&text, &path.display().to_string())?;
    if preset.name.is_empty() {
        preset.name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
    }
    Ok(preset)
}

/// A temporary file in the target's folder, synced, then renamed over (or, without
/// `replace`, beside) the target, so a crash leaves the old file or the new one, never half.
fn write_atomic(path: &Path, text: &str, replace: bool) -> std::io::Result<()> {
    let dir = path.parent().unwrap_or(Path::new("."));
    let mut tmp = tempfile::NamedTempFile::new_in(dir)?;
    tmp.write_all(text.as_bytes())?;
    tmp.as_file().sync_all()?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        // Temp files are created 0600; a preset is meant to be shared.
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(0o644))?;
    }
    let persisted = if replace {
        tmp.persist(path)
    } else {
        tmp.persist_noclobber(path)
    };
    // On failure the error holds the temp file; dropping it deletes it.
    persisted.map(drop).map_err(|e| e.error)
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
