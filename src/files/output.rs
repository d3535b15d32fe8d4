//! Writing outputs: atomically, never onto an input, with the folder checked before any work.
//!
//! A [`PendingFile`] is a temporary file created in the output's folder when the command starts
//! (so a missing or unwritable folder is reported before a long render, not after it); the
//! finished bytes are written, synced and renamed over the target in [`PendingFile::commit`]. On
//! any failure, or if the command stops first (an error, Ctrl-C), the temporary file is removed
//! and whatever was at the target stays as it was.
//!
//! [`Outputs`] refuses an output that is one of the command's inputs (the same file, by device
//! and inode, whatever links lead to it), one of its other outputs, or an existing path that is
//! not a regular file (writing "over" `/dev/null` as root would replace the device).

use std::io::{self, Write};
use std::path::{Path, PathBuf};

use super::{input, shown};

/// Why an output cannot be written. Every message names the output.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The output is the same file as an input.
    #[error(
        "refusing to write '{}': it is the input '{}'",
        shown(output),
        shown(input)
    )]
    IsInput { output: PathBuf, input: PathBuf },
    /// Two outputs of one command are the same file.
    #[error(
        "refusing to write '{}' twice: it is also the output '{}'",
        shown(output),
        shown(other)
    )]
    Twice { output: PathBuf, other: PathBuf },
    /// Something that is not a regular file is already at the path.
    #[error("cannot write '{}': it is {kind}, not a regular file", shown(path))]
    NotRegular { path: PathBuf, kind: &'static str },
    /// The folder the output should go into does not exist (or is not a folder).
    #[error(
        "cannot write '{}': folder '{}' does not exist or is not a folder",
        shown(path),
        shown(folder)
    )]
    MissingFolder { path: PathBuf, folder: PathBuf },
    /// An I/O operation failed.
    #[error("cannot write '{}': {action}: {}", shown(path), describe_io(source))]
    Write {
        path: PathBuf,
        action: &'static str,
        #[source]
        source: io::Error,
    },
}

/// An OS error in words, with a hint where the usual cause is not obvious.
fn describe_io(e: &io::Error) -> String {
    #[cfg(unix)]
    if e.raw_os_error() == Some(libc::EFBIG) {
        return format!("{e}: the process's file-size limit (ulimit -f) is smaller than the file");
    }
    e.to_string()
}

/// The identity of an existing file: device and inode where the OS has them.
#[derive(Debug, Clone, PartialEq, Eq)]
struct FileId(#[cfg(unix)] (u64, u64), #[cfg(not(unix))] PathBuf);

fn file_id(path: &Path) -> Option<FileId> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        let m = std::fs::metadata(path).ok()?;
        Some(FileId((m.dev(), m.ino())))
    }
    #[cfg(not(unix))]
    {
        path.canonicalize().ok().map(FileId)
    }
}

/// Where a path that may not exist yet would be: its folder resolved through links, and its name.
fn planned_location(path: &Path) -> Option<PathBuf> {
    let folder = folder_of(path).canonicalize().ok()?;
    Some(folder.join(path.file_name()?))
}

fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// The inputs and outputs of one command; see the module documentation.
#[derive(Debug, Default)]
pub struct Outputs {
    inputs: Vec<(PathBuf, FileId)>,
    outputs: Vec<(PathBuf, Option<FileId>, Option<PathBuf>)>,
}

impl Outputs {
    pub fn new() -> Outputs {
        Outputs::default()
    }

    /// Records an input (ignored if it does not exist: nothing there can be lost).
    pub fn input(&mut self, path: &Path) {
        if let Some(id) = file_id(path) {
            self.inputs.push((path.to_path_buf(), id));
        }
    }

    /// A guard over the inputs in `paths`.
    pub fn from_inputs<'p>(paths: impl IntoIterator<Item = &'p Path>) -> Outputs {
        let mut o = Outputs::new();
        for p in paths {
            o.input(p);
        }
        o
    }

    /// Checks that `path` may be written: not an input, not another output, not something other
    /// than a regular file. Records it as an output.
    pub fn claim(&mut self, path: &Path) -> Result<(), OutputError> {
        if let Some(kind) = std::fs::metadata(path)
            .ok()
            .and_then(|meta| input::irregular_kind(&meta))
        {
            return Err(OutputError::NotRegular {
                path: path.to_path_buf(),
                kind,
            });
        }
        let id = file_id(path);
        if let Some(id) = &id {
            if let Some((input, _)) = self.inputs.iter().find(|(_, i)| i == id) {
                return Err(OutputError::IsInput {
                    output: path.to_path_buf(),
                    input: input.clone(),
                });
            }
        }
        let planned = planned_location(path);
        let clash = self.outputs.iter().find(|(_, other_id, other_place)| {
            (id.is_some() && *other_id == id) || (planned.is_some() && *other_place == planned)
        });
        if let Some((other, _, _)) = clash {
            return Err(OutputError::Twice {
                output: path.to_path_buf(),
                other: other.clone(),
            });
        }
        self.outputs.push((path.to_path_buf(), id, planned));
        Ok(())
    }
}

/// An output being prepared: a temporary file beside the target, renamed over it by
/// [`PendingFile::commit`], removed if dropped uncommitted.
#[derive(Debug)]
pub struct PendingFile {
    path: PathBuf,
    tmp: tempfile::NamedTempFile,
}

impl PendingFile {
    /// Creates the temporary file in `path`'s folder: fails at once if the folder is missing or
    /// cannot be written.
    pub fn create(path: &Path) -> Result<PendingFile, OutputError> {
        let folder = folder_of(path);
        if !folder.is_dir() {
            return Err(OutputError::MissingFolder {
                path: path.to_path_buf(),
                folder: folder.to_path_buf(),
            });
        }
        let mut builder = tempfile::Builder::new();
        builder.prefix(".tmp-output-");
        // Temporary files are private (0600) by default; the output should get the permissions of
        // any new file (0666 less the umask), as if it had been created directly.
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            builder.permissions(std::fs::Permissions::from_mode(0o666));
        }
        let tmp = builder
            .tempfile_in(folder)
            .map_err(|source| OutputError::Write {
                path: path.to_path_buf(),
                action: "cannot create a file in its folder",
                source,
            })?;
        Ok(PendingFile {
            path: path.to_path_buf(),
            tmp,
        })
    }

    /// The temporary file's path (for a signal handler that must remove it before exiting).
    pub fn temp_path(&self) -> &Path {
        self.tmp.path()
    }

    /// Writes `bytes`, syncs them and renames the file over the target. On error the temporary
    /// file is removed and the target is untouched.
    pub fn commit(mut self, bytes: &[u8]) -> Result<(), OutputError> {
        let path = self.path.clone();
        let fail = |action: &'static str| {
            let path = path.clone();
            move |source: io::Error| OutputError::Write {
                path,
                action,
                source,
            }
        };
        self.tmp
            .as_file_mut()
            .write_all(bytes)
            .map_err(fail("writing its data"))?;
        self.tmp
            .as_file()
            .sync_all()
            .map_err(fail("syncing its data to disk"))?;
        self.tmp
            .persist(&self.path)
            .map_err(|e| fail("renaming the finished file into place")(e.error))?;
        Ok(())
    }
}

/// Writes `bytes` to `path` atomically (see [`PendingFile`]).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    PendingFile::create(path)?.commit(bytes)
}

/// Makes a write past the process's file-size limit (`ulimit -f`, common in marking sandboxes)
/// fail with `EFBIG`, which is reported and cleaned up like any write error, instead of raising
/// `SIGXFSZ`, whose default action kills the process and leaves its temporary file behind.
pub fn report_file_size_limit() {
    #[cfg(unix)]
    // SAFETY: setting a signal's disposition to SIG_IGN installs no handler code; it is done once
    // at start-up, and the only effect is that write(2) returns EFBIG instead of the signal.
    unsafe {
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn an_input_cannot_be_an_output_through_any_link() {
        let dir = tempfile::tempdir().unwrap();
        let scene = dir.path().join("scene.json");
        fs::write(&scene, b"{}").unwrap();
        let hard = dir.path().join("hard.png");
        fs::hard_link(&scene, &hard).unwrap();
        let mut o = Outputs::new();
        o.input(&scene);
        let err = o.claim(&hard).unwrap_err();
        assert!(matches!(err, OutputError::IsInput { .. }), "{err}");
        #[cfg(unix)]
        {
            let soft = dir.path().join("soft.png");
            std::os::unix::fs::symlink(&scene, &soft).unwrap();
            assert!(matches!(o.claim(&soft), Err(OutputError::IsInput { .. })));
        }
        let dotted = dir.path().join(".").join("scene.json");
        assert!(matches!(o.claim(&dotted), Err(OutputError::IsInput { .. })));
        o.claim(&dir.path().join("new.png")).unwrap();
    }

    #[test]
    fn two_outputs_cannot_be_one_file_even_before_they_exist() {
        let dir = tempfile::tempdir().unwrap();
        let mut o = Outputs::new();
        o.claim(&dir.path().join("a.csv")).unwrap();
        let same = dir.path().join(".").join("a.csv");
        assert!(matches!(o.claim(&same), Err(OutputError::Twice { .. })));
        o.claim(&dir.path().join("b.csv")).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_device_or_folder_is_not_an_output() {
        let mut o = Outputs::new();
        let err = o.claim(Path::new("/dev/null")).unwrap_err();
        assert!(matches!(err, OutputError::NotRegular { .. }), "{err}");
        let dir = tempfile::tempdir().unwrap();
        assert!(matches!(
            o.claim(dir.path()),
            Err(OutputError::NotRegular { .. })
        ));
    }

    #[test]
    fn pending_file_is_created_early_and_removed_unless_committed() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.png");
        fs::write(&target, b"old").unwrap();
        let pending = PendingFile::create(&target).unwrap();
        assert_eq!(names(dir.path()).len(), 2);
        drop(pending);
        assert_eq!(names(dir.path()), vec!["out.png"]);
        assert_eq!(fs::read(&target).unwrap(), b"old");
        write_atomic(&target, b"new").unwrap();
        assert_eq!(fs::read(&target).unwrap(), b"new");
        assert_eq!(names(dir.path()), vec!["out.png"]);
    }

    #[test]
    fn a_missing_folder_is_reported_before_any_work() {
        let dir = tempfile::tempdir().unwrap();
        let err = PendingFile::create(&dir.path().join("nope").join("out.png")).unwrap_err();
        assert!(matches!(err, OutputError::MissingFolder { .. }), "{err}");
    }
}
