//! Every file the program writes goes through here, the CLI's `--out` and the explorer's
//! exports and saved presets alike.
//!
//! - [`Output::check`] looks at the path before any work: a known extension, an existing
//!   folder the program may write into, and no existing file unless replacing was asked for.
//! - [`Output::write`] writes into a temporary file in the same folder, flushes and syncs it,
//!   and only then renames it onto the path, so a failed write (a full disk, a lost device)
//!   leaves no partial file and an old file as it was. The error names the OS's reason.
//! - A CSV is written with its sidecar `<file>.meta.json` ([`Output::write_table`]): both
//!   checked, refused and replaced together, both or neither written.
//! - [`Output::stage`] and [`commit`] write several files of one command (a merge's
//!   outputs) the same way, all or nothing.
//!
//! A path that already is a character device (`/dev/stdout`, `/dev/full`) cannot be
//! replaced by a rename and holds no data to lose: it is written in place, its errors
//! (final flush included) still reported. Any other path that is not a regular file is
//! refused by [`Output::check`] without being opened, `--force` or not: opening a FIFO for
//! writing blocks until a reader comes (the command would hang before its first roll), a
//! socket cannot be opened at all, and a block device holds data a result must not overwrite.

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Why a file could not be written. The first four are found before any work is done.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum OutputError {
    #[error("{}: the file exists (--force replaces it)", path.display())]
    Exists { path: PathBuf },
    #[error("{}: expected {expected}", path.display())]
    Extension { path: PathBuf, expected: String },
    #[error("{}: the folder {} does not exist", path.display(), dir.display())]
    NoFolder { path: PathBuf, dir: PathBuf },
    #[error("{}: cannot write into {}: {message}", path.display(), dir.display())]
    Folder {
        path: PathBuf,
        dir: PathBuf,
        message: String,
    },
    #[error("{}: {message}; nothing was written", path.display())]
    Write { path: PathBuf, message: String },
    #[error("{}: named twice as an output (it would be written and then refused)", path.display())]
    Twice { path: PathBuf },
    #[error("{}: this command reads it ({what}); write the result elsewhere", path.display())]
    Input { path: PathBuf, what: String },
    #[error("{}: is {what}, not a file; write the result to a file", path.display())]
    NotAFile { path: PathBuf, what: &'static str },
    #[error(
        "{}: a symbolic link to {}, which does not exist (--force replaces the link)",
        path.display(),
        target.display()
    )]
    Dangling { path: PathBuf, target: PathBuf },
}

impl OutputError {
    /// Whether the path itself was refused (bad input), rather than the writing failing.
    pub fn is_refusal(&self) -> bool {
        !matches!(self, OutputError::Write { .. })
    }
}

/// What a CSV file cannot hold itself (where it came from, its columns' types) goes into a
/// sidecar beside it, `<file>.meta.json`: checked, written, refused and replaced together
/// with the CSV, so a CSV opens as a plain table in any reader and still says where it
/// came from. A CSV written to a character device (`/dev/stdout`) has none.
pub const SIDECAR_SUFFIX: &str = ".meta.json";

/// The extension whose files carry a sidecar.
const TABLE_EXTENSION: &str = "csv";

/// The sidecar of the CSV at `path`.
pub fn sidecar_path(path: &Path) -> PathBuf {
    let mut name = path.as_os_str().to_os_string();
    name.push(SIDECAR_SUFFIX);
    PathBuf::from(name)
}

/// A checked output path: where to write, in which format, whether it may replace a file,
/// and, for a CSV, its sidecar.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Output {
    path: PathBuf,
    extension: String,
    replace: bool,
    sidecar: Option<PathBuf>,
}

impl Output {
    /// Checks `path` before any work: its extension is one of `extensions` (lower case,
    /// without the dot), its folder exists and takes new files, and it names no existing
    /// regular file unless `replace`; a CSV's sidecar is checked the same way.
    pub fn check(path: &Path, extensions: &[&str], replace: bool) -> Result<Output, OutputError> {
        let extension = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .filter(|e| extensions.contains(&e.as_str()))
            // A device or standard output has no extension to tell the format: the first.
            .or_else(|| {
                (path.extension().is_none() && in_place(path))
                    .then(|| extensions.first().map(|e| e.to_string()))
                    .flatten()
            });
        let Some(extension) = extension else {
            let names: Vec<String> = extensions.iter().map(|e| format!(".{e}")).collect();
            let expected = match names.as_slice() {
                [one] => format!("a {one} file"),
                [rest @ .., last] => format!("a {} or {last} file", rest.join(", ")),
                [] => "no file".to_string(),
            };
            return Err(OutputError::Extension {
                path: path.to_path_buf(),
                expected,
            });
        };
        let mut output = Output {
            path: path.to_path_buf(),
            sidecar: (extension == TABLE_EXTENSION).then(|| sidecar_path(path)),
            extension,
            replace,
        };
        if check_target(&output.path, replace)? == Target::Device {
            // Written in place, and a device has no folder to put a sidecar in.
            output.sidecar = None;
            return Ok(output);
        }
        if let Some(sidecar) = &output.sidecar
            && check_target(sidecar, replace)? == Target::Device
        {
            return Err(OutputError::NotAFile {
                path: sidecar.clone(),
                what: "a device",
            });
        }
        let dir = output.dir();
        if !dir.is_dir() {
            return Err(OutputError::NoFolder {
                path: output.path.clone(),
                dir: dir.to_path_buf(),
            });
        }
        // The one sure test of "may write here": make a file and let it go.
        if let Err(e) = temporary_beside(&output.path) {
            return Err(OutputError::Folder {
                path: output.path.clone(),
                dir: dir.to_path_buf(),
                message: os_reason(&e),
            });
        }
        Ok(output)
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The extension that was recognised, lower case.
    pub fn extension(&self) -> &str {
        &self.extension
    }

    /// The sidecar written with this file (a CSV's `<file>.meta.json`), if it has one.
    pub fn sidecar(&self) -> Option<&Path> {
        self.sidecar.as_deref()
    }

    fn dir(&self) -> &Path {
        folder_of(&self.path)
    }

    /// Writes the file with `body`, all or nothing (see the module comment). The writer is
    /// `Send`, so an encoder that needs one (Parquet's) can own it. Not for a CSV, whose
    /// sidecar must be written with it ([`Output::write_table`]).
    pub fn write(
        &self,
        body: impl FnOnce(&mut (dyn Write + Send)) -> std::io::Result<()>,
    ) -> Result<(), OutputError> {
        self.write_with(|w| body(w).map_err(|e| self.failed(&e)), |e| e)
    }

    /// [`Output::write`] for a `body` that fails in its own terms (a merge that finds a bad
    /// part half-way): its error is returned as it is, the file's own failures through
    /// `own`, and either way nothing is left under the path.
    pub fn write_with<E>(
        &self,
        body: impl FnOnce(&mut (dyn Write + Send)) -> Result<(), E>,
        own: impl Fn(OutputError) -> E,
    ) -> Result<(), E> {
        self.write_table_with(None, body, own)
    }

    /// Writes a CSV file with `body` and its sidecar with `meta`, both or neither: a failure
    /// of either leaves no file of the two (and old ones as they were, but for a failure
    /// between the two renames, which removes what this write put there). `meta` is `None`
    /// for a file of a format without a sidecar.
    pub fn write_table(
        &self,
        meta: Option<&[u8]>,
        body: impl FnOnce(&mut (dyn Write + Send)) -> std::io::Result<()>,
    ) -> Result<(), OutputError> {
        self.write_table_with(meta, |w| body(w).map_err(|e| self.failed(&e)), |e| e)
    }

    /// [`Output::write_table`] for a `body` that fails in its own terms (see
    /// [`Output::write_with`]); `meta` is `None` for a file without a sidecar.
    pub fn write_table_with<E>(
        &self,
        meta: Option<&[u8]>,
        body: impl FnOnce(&mut (dyn Write + Send)) -> Result<(), E>,
        own: impl Fn(OutputError) -> E,
    ) -> Result<(), E> {
        let mut staged = self.stage(meta).map_err(&own)?;
        body(&mut staged)?;
        commit(vec![staged]).map_err(own)
    }

    /// Starts writing this file: its bytes go to a temporary file beside it (a device is
    /// written in place) until [`commit`] puts it, with any others staged, under its path;
    /// dropped uncommitted, it leaves nothing. `meta` is the sidecar's content: required
    /// for a file that has one, ignored for the rest.
    pub fn stage(&self, meta: Option<&[u8]>) -> Result<Staged, OutputError> {
        let failed = |e: std::io::Error| self.failed(&e);
        if in_place(&self.path) {
            // Standard output through its own descriptor, sharing its offset with what the
            // command prints (a file the shell redirected it into is not written over).
            let file = match standard_stream(&self.path) {
                Some(stream) => stream,
                None => std::fs::OpenOptions::new()
                    .write(true)
                    .open(&self.path)
                    .map_err(failed)?,
            };
            return Ok(Staged {
                path: self.path.clone(),
                replace: true,
                sink: Sink::Device(BufWriter::new(file)),
                sidecar: None,
            });
        }
        let sidecar = match (&self.sidecar, meta) {
            (None, _) => None,
            (Some(path), Some(meta)) => {
                let mut side = Staged::temporary(path, self.replace)?;
                side.write_all(meta).map_err(|e| side.failed(&e))?;
                Some(Box::new(side))
            }
            (Some(path), None) => panic!(
                "{}: a CSV is written with its sidecar (write_table)",
                path.display()
            ),
        };
        let mut staged = Staged::temporary(&self.path, self.replace)?;
        staged.sidecar = sidecar;
        Ok(staged)
    }

    /// A write to this path that failed, with the OS's reason.
    pub fn failed(&self, e: &std::io::Error) -> OutputError {
        OutputError::Write {
            path: self.path.clone(),
            message: os_reason(e),
        }
    }

    /// Writes `bytes` as the whole file.
    pub fn write_bytes(&self, bytes: &[u8]) -> Result<(), OutputError> {
        self.write(|w| w.write_all(bytes))
    }
}

/// What a path to be written is now.
#[derive(Debug, PartialEq, Eq)]
enum Target {
    /// Nothing, or a regular file that may be replaced.
    File,
    /// A character device, written in place.
    Device,
}

/// Checks what `path` is before any work: a folder or a special file is refused, an
/// existing regular file too unless `replace`.
fn check_target(path: &Path, replace: bool) -> Result<Target, OutputError> {
    if in_place(path) {
        return Ok(Target::Device);
    }
    // A link to nothing: the rename would replace the link, so it is a file that exists.
    if let (Ok(link), Err(_)) = (std::fs::symlink_metadata(path), std::fs::metadata(path))
        && link.file_type().is_symlink()
        && !replace
    {
        return Err(OutputError::Dangling {
            path: path.to_path_buf(),
            target: std::fs::read_link(path).unwrap_or_default(),
        });
    }
    match std::fs::metadata(path) {
        Ok(meta) if meta.is_dir() => Err(OutputError::NotAFile {
            path: path.to_path_buf(),
            what: "a folder",
        }),
        Ok(meta) if meta.is_file() && !replace => Err(OutputError::Exists {
            path: path.to_path_buf(),
        }),
        Ok(meta) if !meta.is_file() => match special_file(&meta) {
            None => Ok(Target::Device),
            Some(what) => Err(OutputError::NotAFile {
                path: path.to_path_buf(),
                what,
            }),
        },
        _ => Ok(Target::File),
    }
}

/// Whether `path` is written in place rather than replaced by a rename: a character device
/// (`/dev/null`, a terminal), or this program's own standard output or error by any of its
/// names (`/dev/stdout`, `/dev/fd/1`, `/proc/self/fd/2`), whatever it is — a pipe to the next
/// command, or the file the shell redirected it into.
fn in_place(path: &Path) -> bool {
    std::fs::metadata(path).is_ok_and(|m| special_file(&m).is_none() && !m.is_file() && !m.is_dir())
        || standard_stream(path).is_some()
}

/// This program's standard output or error, as a second descriptor of it, when `path` names
/// it (under `/dev` or `/proc`).
fn standard_stream(path: &Path) -> Option<std::fs::File> {
    #[cfg(unix)]
    {
        use std::os::fd::AsFd;
        use std::os::unix::fs::MetadataExt;
        if !(path.starts_with("/dev") || path.starts_with("/proc")) {
            return None;
        }
        let meta = std::fs::metadata(path).ok()?;
        let stdout = std::io::stdout();
        let stderr = std::io::stderr();
        [stdout.as_fd(), stderr.as_fd()].into_iter().find_map(|fd| {
            let file = std::fs::File::from(fd.try_clone_to_owned().ok()?);
            let m = file.metadata().ok()?;
            ((m.dev(), m.ino()) == (meta.dev(), meta.ino())).then_some(file)
        })
    }
    #[cfg(not(unix))]
    {
        let _ = path;
        None
    }
}

/// The folder a file is written in.
fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// A temporary file beside `path`, named after it, that becomes `path` by a rename.
fn temporary_beside(path: &Path) -> std::io::Result<tempfile::NamedTempFile> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let prefix = format!(".{name}.");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".part");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        // As `File::create` would make it (the umask applies), not the temp file's 0600.
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    builder.tempfile_in(folder_of(path))
}

/// Where a staged file's bytes go until it is committed.
enum Sink {
    /// A temporary file beside the path, listed in [`PENDING`] while it lives.
    Temporary(BufWriter<tempfile::NamedTempFile>, Pending),
    /// A character device, written in place.
    Device(BufWriter<std::fs::File>),
}

/// A file being written (see [`Output::stage`]): write into it, then [`commit`] it with
/// the others of one command. Dropped uncommitted, it leaves nothing behind.
pub struct Staged {
    path: PathBuf,
    replace: bool,
    sink: Sink,
    /// A CSV's sidecar, written already, committed with it.
    sidecar: Option<Box<Staged>>,
}

impl Staged {
    fn temporary(path: &Path, replace: bool) -> Result<Staged, OutputError> {
        let failed = |e: std::io::Error| OutputError::Write {
            path: path.to_path_buf(),
            message: os_reason(&e),
        };
        let tmp = temporary_beside(path).map_err(failed)?;
        let pending = Pending::register(tmp.path());
        Ok(Staged {
            path: path.to_path_buf(),
            replace,
            sink: Sink::Temporary(BufWriter::with_capacity(1 << 20, tmp), pending),
            sidecar: None,
        })
    }

    /// A write to this file that failed, with the OS's reason.
    pub fn failed(&self, e: &std::io::Error) -> OutputError {
        OutputError::Write {
            path: self.path.clone(),
            message: os_reason(e),
        }
    }

    /// Flushes and syncs the bytes: after this only the rename is left.
    fn finish(&mut self) -> Result<(), OutputError> {
        if let Some(side) = &mut self.sidecar {
            side.finish()?;
        }
        let done = match &mut self.sink {
            Sink::Device(w) => w.flush(),
            Sink::Temporary(w, _) => w.flush().and_then(|()| w.get_ref().as_file().sync_all()),
        };
        done.map_err(|e| self.failed(&e))
    }

    /// Renames the file (its sidecar first) onto its path; every path it put there is
    /// pushed onto `placed`, so a later failure can take them back.
    fn place(self, placed: &mut Vec<PathBuf>) -> Result<(), OutputError> {
        let Staged {
            path,
            replace,
            sink,
            sidecar,
        } = self;
        if let Some(side) = sidecar {
            side.place(placed)?;
        }
        let Sink::Temporary(w, _pending) = sink else {
            return Ok(());
        };
        let failed = |e: std::io::Error| OutputError::Write {
            path: path.clone(),
            message: os_reason(&e),
        };
        let tmp = w.into_inner().map_err(|e| failed(e.into_error()))?;
        let persisted = if replace {
            tmp.persist(&path)
        } else {
            tmp.persist_noclobber(&path)
        };
        // On failure the error holds the temporary file; dropping it deletes it.
        persisted.map_err(|e| match e.error.kind() {
            std::io::ErrorKind::AlreadyExists => OutputError::Exists { path: path.clone() },
            _ => failed(e.error),
        })?;
        placed.push(path);
        Ok(())
    }
}

impl Write for Staged {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match &mut self.sink {
            Sink::Temporary(w, _) => w.write(buf),
            Sink::Device(w) => w.write(buf),
        }
    }

    fn write_all(&mut self, buf: &[u8]) -> std::io::Result<()> {
        match &mut self.sink {
            Sink::Temporary(w, _) => w.write_all(buf),
            Sink::Device(w) => w.write_all(buf),
        }
    }

    fn flush(&mut self) -> std::io::Result<()> {
        match &mut self.sink {
            Sink::Temporary(w, _) => w.flush(),
            Sink::Device(w) => w.flush(),
        }
    }
}

/// Puts every staged file (and its sidecar) under its path, all or nothing: each is first
/// flushed and synced, so a full disk or a lost device fails before any file appears, and a
/// rename that still fails takes back the files this commit already put in place (a file
/// they replaced stays replaced: `--force` said it may go).
pub fn commit(files: Vec<Staged>) -> Result<(), OutputError> {
    let mut files = files;
    for f in &mut files {
        f.finish()?;
    }
    // A stop signal waits for these renames to end, so it sees none or all of them.
    let _renaming = COMMITTING.lock().unwrap_or_else(|e| e.into_inner());
    let mut placed = Vec::new();
    for f in files {
        if let Err(e) = f.place(&mut placed) {
            for p in &placed {
                let _ = std::fs::remove_file(p);
            }
            return Err(e);
        }
    }
    PLACED.lock().unwrap_or_else(|e| e.into_inner()).extend(placed);
    Ok(())
}

/// What a path that is neither a regular file nor a folder is, in words, when it must not be
/// opened as an output (see the module comment); `None` for a character device, which is
/// written in place.
fn special_file(meta: &std::fs::Metadata) -> Option<&'static str> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let kind = meta.file_type();
        if kind.is_char_device() {
            None
        } else if kind.is_fifo() {
            Some("a named pipe (FIFO)")
        } else if kind.is_socket() {
            Some("a socket")
        } else if kind.is_block_device() {
            Some("a block device")
        } else {
            Some("not a regular file")
        }
    }
    #[cfg(not(unix))]
    {
        let _ = meta;
        None
    }
}

/// Where `path` points, so two names of one file compare equal: the file itself where it
/// exists, else its folder's real path and its name.
fn identity(path: &Path) -> PathBuf {
    if let Ok(p) = std::fs::canonicalize(path) {
        return p;
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let dir = std::fs::canonicalize(dir).unwrap_or_else(|_| dir.to_path_buf());
    dir.join(path.file_name().unwrap_or_default())
}

/// Checks, before any work, that no file is named twice among `outputs` and that none (nor
/// a CSV's sidecar) is one of `inputs` (each with the words for what it is): `--force`
/// replaces an old result, never a file the command is reading.
pub fn check_apart(outputs: &[Output], inputs: &[(PathBuf, String)]) -> Result<(), OutputError> {
    let mut seen: Vec<PathBuf> = Vec::with_capacity(outputs.len());
    for o in outputs {
        let id = identity(o.path());
        if seen.contains(&id) {
            return Err(OutputError::Twice {
                path: o.path().to_path_buf(),
            });
        }
        for path in std::iter::once(o.path()).chain(o.sidecar()) {
            let id = identity(path);
            if let Some((_, what)) = inputs.iter().find(|(p, _)| identity(p) == id) {
                return Err(OutputError::Input {
                    path: path.to_path_buf(),
                    what: what.clone(),
                });
            }
        }
        seen.push(id);
    }
    Ok(())
}

/// The temporary files being written now, so a signal that stops the program at once can
/// remove them ([`stop_writing`]); each is listed while its [`Pending`] guard lives.
static PENDING: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

/// A temporary file listed in [`PENDING`] until this guard is dropped (the file is then
/// renamed onto its path or already deleted).
struct Pending(PathBuf);

impl Pending {
    fn register(path: &Path) -> Pending {
        PENDING
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .push(path.to_path_buf());
        Pending(path.to_path_buf())
    }
}

impl Drop for Pending {
    fn drop(&mut self) {
        let mut pending = PENDING.lock().unwrap_or_else(|e| e.into_inner());
        pending.retain(|p| *p != self.0);
    }
}

/// Held while a commit renames its files onto their paths, and for good by [`stop_writing`].
static COMMITTING: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// The paths commits in this program have put in place.
static PLACED: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

/// What [`stop_writing`] found: how many temporary files it removed, and the files commits
/// had already put in place (which stay).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Stopped {
    pub removed: usize,
    pub placed: Vec<PathBuf>,
}

/// For a program about to exit without unwinding (a signal that stops it at once): waits for
/// a commit that is renaming its files to end, keeps any other from starting, and removes
/// every temporary file still being written, so what it reports is what is on disk.
pub fn stop_writing() -> Stopped {
    // Never released: the program exits next, and no file may appear after the report.
    std::mem::forget(COMMITTING.lock().unwrap_or_else(|e| e.into_inner()));
    let pending = PENDING.lock().unwrap_or_else(|e| e.into_inner());
    for p in pending.iter() {
        let _ = std::fs::remove_file(p);
    }
    Stopped {
        removed: pending.len(),
        placed: PLACED.lock().unwrap_or_else(|e| e.into_inner()).clone(),
    }
}

/// The OS's reason alone: the temporary file's own name (which `tempfile` adds) means
/// nothing to the person who asked for `path`.
fn os_reason(e: &std::io::Error) -> String {
    let inner = e
        .get_ref()
        .and_then(|i| i.source())
        .and_then(|s| s.downcast_ref::<std::io::Error>());
    inner.unwrap_or(e).to_string()
}

/// The first stem for files `<stem>.<ext>` (one per extension) in `dir` that replaces no
/// file: `stem`, then `stem-2`, `stem-3`, … (the explorer's exports never ask to replace).
pub(crate) fn free_stem(dir: &Path, stem: &str, extensions: &[&str]) -> String {
    (1..)
        .map(|n| {
            if n == 1 {
                stem.to_string()
            } else {
                format!("{stem}-{n}")
            }
        })
        .find(|s| {
            extensions.iter().all(|ext| {
                let file = dir.join(format!("{s}.{ext}"));
                let free = |p: &Path| std::fs::symlink_metadata(p).is_err();
                free(&file) && (*ext != TABLE_EXTENSION || free(&sidecar_path(&file)))
            })
        })
        .unwrap_or_else(|| stem.to_string())
}

/// Files `<stem>.<ext>` in `dir`, one per extension under the first stem free for all of
/// them (see [`free_stem`]), each checked as [`Output::check`] checks: the explorer's
/// exports, which never replace a file.
pub fn free_outputs<const N: usize>(
    dir: &Path,
    stem: &str,
    extensions: [&str; N],
) -> Result<[Output; N], OutputError> {
    let stem = free_stem(dir, stem, &extensions);
    let outputs = extensions
        .iter()
        .map(|ext| Output::check(&dir.join(format!("{stem}.{ext}")), &[ext], false))
        .collect::<Result<Vec<_>, _>>()?;
    match outputs.try_into() {
        Ok(outputs) => Ok(outputs),
        Err(_) => unreachable!("one output per extension"),
    }
}

/// `text` as a file name part: letters, digits, `-` and `_` kept, anything else (a `/`, a
/// dot, a space, a control character) becomes `_`, so it can never add a path component.
pub fn safe_file_stem(text: &str) -> String {
    let stem: String = text
        .chars()
        .take(64)
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if stem.is_empty() { "_".to_string() } else { stem }
}

/// `text` safe to print on a terminal: control characters (an escape sequence, or the C1
/// introducer U+009B, could retitle the window or hide what follows) and the bidirectional
/// overrides and isolates (U+202A–U+202E, U+2066–U+2069, which reorder what follows on the
/// line) are shown escaped, `\u{1b}`, instead of sent.
pub fn printable(text: &str) -> String {
    let bidi = |c: char| matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}');
    text.chars()
        .map(|c| {
            if (c.is_control() || bidi(c)) && c != '\n' {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_existing_file_is_refused_without_replace() {
        // (A CSV's sidecar is refused the same way: a_csv_and_its_sidecar_… below.)
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.svg");
        std::fs::write(&path, "old").unwrap();
        let e = Output::check(&path, &["svg"], false).unwrap_err();
        assert_eq!(e, OutputError::Exists { path: path.clone() });
        assert!(
            e.to_string()
                .ends_with("a.svg: the file exists (--force replaces it)")
        );
        Output::check(&path, &["svg"], true)
            .unwrap()
            .write_bytes(b"new")
            .unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
    }

    #[test]
    fn paths_are_checked_before_any_work() {
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("nope").join("x.csv");
        assert!(matches!(
            Output::check(&missing, &["csv"], false),
            Err(OutputError::NoFolder { .. })
        ));
        let e = Output::check(&dir.path().join("x.txt"), &["csv", "png", "svg"], false).unwrap_err();
        assert!(
            e.to_string().ends_with("expected a .csv, .png or .svg file"),
            "{e}"
        );
        let ok = Output::check(&dir.path().join("X.PNG"), &["png"], false).unwrap();
        assert_eq!(ok.extension(), "png");
        // The writability probe leaves nothing behind.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }

    #[test]
    fn a_failed_write_leaves_no_file_and_the_old_one_intact() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.json");
        std::fs::write(&path, "old").unwrap();
        let out = Output::check(&path, &["json"], true).unwrap();
        let e = out
            .write(|w| {
                w.write_all(&[b'x'; 10_000])?;
                Err(std::io::Error::other("the disk went away"))
            })
            .unwrap_err();
        assert!(
            e.to_string().contains("the disk went away; nothing was written"),
            "{e}"
        );
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            1,
            "no temporary file left"
        );
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn the_final_flush_error_is_reported() {
        // A device is written in place, so its errors are the writer's own, final flush
        // included (a small file fits the buffer and fails only there).
        let dir = tempfile::tempdir().unwrap();
        let link = dir.path().join("full.svg");
        std::os::unix::fs::symlink("/dev/full", &link).unwrap();
        let out = Output::check(&link, &["svg"], false).unwrap();
        let e = out.write_bytes(b"<svg/>").unwrap_err();
        assert!(e.to_string().contains("No space left on device"), "{e}");
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_is_refused_at_once_without_being_opened() {
        // Reproduces `batch --out fifo.csv` (and compare, predict, basin, animate), which hung
        // in open() waiting for a reader. The check runs on a thread so a hang fails the test
        // instead of stopping it.
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("rolls.csv");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status().unwrap();
        assert!(made.success());
        for replace in [false, true] {
            let path = fifo.clone();
            let (tx, rx) = std::sync::mpsc::channel();
            std::thread::spawn(move || {
                let _ = tx.send(Output::check(&path, &["csv"], replace));
            });
            let checked = rx
                .recv_timeout(std::time::Duration::from_secs(2))
                .expect("the check came back at once");
            let e = checked.unwrap_err();
            assert_eq!(
                e,
                OutputError::NotAFile {
                    path: fifo.clone(),
                    what: "a named pipe (FIFO)"
                }
            );
            assert!(e.is_refusal());
            let text = e.to_string();
            assert!(text.starts_with(&fifo.display().to_string()), "{text}");
            assert!(text.contains("a named pipe (FIFO)"), "{text}");
        }
    }

    #[test]
    fn names_from_files_stay_one_path_component() {
        assert_eq!(safe_file_stem("x/../../escaped"), "x_______escaped");
        assert_eq!(safe_file_stem("paper"), "paper");
        assert_eq!(safe_file_stem(".."), "__");
        assert_eq!(safe_file_stem(""), "_");
        assert_eq!(safe_file_stem("a\u{1b}]0;pwned\u{7}"), "a__0_pwned_");
    }

    #[test]
    fn a_csv_and_its_sidecar_are_refused_written_and_replaced_together() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.csv");
        let sidecar = dir.path().join("a.csv.meta.json");
        // An old sidecar alone is a file the write would replace: refused without --force.
        std::fs::write(&sidecar, "old").unwrap();
        let e = Output::check(&path, &["csv"], false).unwrap_err();
        assert_eq!(
            e,
            OutputError::Exists {
                path: sidecar.clone()
            }
        );
        let out = Output::check(&path, &["csv"], true).unwrap();
        assert_eq!(out.sidecar(), Some(sidecar.as_path()));
        out.write_table(Some(b"{\"meta\":1}"), |w| w.write_all(b"x\n1\n"))
            .unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "x\n1\n");
        assert_eq!(std::fs::read_to_string(&sidecar).unwrap(), "{\"meta\":1}");
        // A failed write of the CSV leaves both old files as they were, and no temporary.
        let e = out
            .write_table(Some(b"new"), |w| {
                w.write_all(b"half")?;
                Err(std::io::Error::other("the disk went away"))
            })
            .unwrap_err();
        assert!(e.to_string().contains("the disk went away"), "{e}");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "x\n1\n");
        assert_eq!(std::fs::read_to_string(&sidecar).unwrap(), "{\"meta\":1}");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
        // Other files have no sidecar.
        let png = Output::check(&dir.path().join("a.png"), &["png"], false).unwrap();
        assert_eq!(png.sidecar(), None);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn staged_files_appear_together_or_not_at_all() {
        let dir = tempfile::tempdir().unwrap();
        let full = dir.path().join("full.parquet");
        std::os::unix::fs::symlink("/dev/full", &full).unwrap();
        let csv = Output::check(&dir.path().join("ok.csv"), &["csv"], false).unwrap();
        let device = Output::check(&full, &["parquet"], false).unwrap();
        let mut a = csv.stage(Some(b"{}")).unwrap();
        let mut b = device.stage(None).unwrap();
        a.write_all(b"x\n").unwrap();
        // A device is written in place: a write that fits its buffer fails only with the
        // flush, which commit does before it renames anything.
        b.write_all(&[0; 100]).unwrap();
        let e = commit(vec![a, b]).unwrap_err();
        assert!(e.to_string().contains("No space left on device"), "{e}");
        let mut left: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        left.sort();
        assert_eq!(
            left,
            ["full.parquet"],
            "neither the CSV nor its sidecar nor a temporary"
        );
        // Two files that can be written both appear.
        let other = Output::check(&dir.path().join("b.json"), &["json"], false).unwrap();
        let (mut a, mut b) = (csv.stage(Some(b"{}")).unwrap(), other.stage(None).unwrap());
        a.write_all(b"x\n").unwrap();
        b.write_all(b"{}").unwrap();
        commit(vec![a, b]).unwrap();
        assert!(dir.path().join("ok.csv.meta.json").is_file() && dir.path().join("b.json").is_file());
    }

    #[cfg(unix)]
    #[test]
    fn a_csv_on_a_device_has_no_sidecar() {
        // A device is written in place, with no folder of its own for a sidecar.
        let dir = tempfile::tempdir().unwrap();
        let link = dir.path().join("null.csv");
        std::os::unix::fs::symlink("/dev/null", &link).unwrap();
        let out = Output::check(&link, &["csv"], false).unwrap();
        assert_eq!(out.sidecar(), None);
        out.write_table(Some(b"{}"), |w| w.write_all(b"x\n")).unwrap();
        assert!(!dir.path().join("null.csv.meta.json").exists());
    }

    #[test]
    fn free_stems_skip_taken_names() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("r.csv"), "").unwrap();
        std::fs::write(dir.path().join("r-2.png"), "").unwrap();
        std::fs::write(dir.path().join("r-3.csv.meta.json"), "").unwrap();
        assert_eq!(free_stem(dir.path(), "r", &["csv", "png"]), "r-4");
    }
}
