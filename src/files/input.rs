//! Opening and reading input files: scenes, meshes, textures, reference images.
//!
//! Only regular files are read. A path naming a folder, a FIFO (which would block the open until
//! a writer comes), a character device such as `/dev/zero` (which never ends) or a socket is
//! refused before anything is read. The file is opened without blocking and checked again through
//! its handle, so a file swapped for a FIFO between the check and the open is refused too.
//! Whole-file reads take a [`SizeLimit`] that names the flag raising it.

use std::fs::{File, Metadata};
use std::io::{self, Read};
use std::path::Path;

use super::raise_hint;

/// A cap on the bytes a whole-file read accepts, with the command-line flag that raises it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SizeLimit {
    pub bytes: u64,
    /// The flag that sets it, e.g. `--max-scene-bytes`, for the error message; `None` where no
    /// flag raises it.
    pub flag: Option<&'static str>,
}

/// What kind of file `meta` describes, for messages ("a folder", "a FIFO (named pipe)", …), or
/// `None` for a regular file.
pub fn irregular_kind(meta: &Metadata) -> Option<&'static str> {
    let t = meta.file_type();
    if t.is_file() {
        return None;
    }
    if t.is_dir() {
        return Some("a folder");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return Some("a FIFO (named pipe)");
        }
        if t.is_char_device() {
            return Some("a character device");
        }
        if t.is_block_device() {
            return Some("a block device");
        }
        if t.is_socket() {
            return Some("a socket");
        }
    }
    Some("an unknown kind of file")
}

/// An error saying what `meta` is if it is not a regular file ("it is a FIFO (named pipe), not a
/// regular file").
pub fn check_regular(meta: &Metadata) -> io::Result<()> {
    match irregular_kind(meta) {
        None => Ok(()),
        Some(kind) => Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("it is {kind}, not a regular file"),
        )),
    }
}

/// Opens `path` for reading if it is a regular file (after following symbolic links). The error
/// says what the path is instead (a folder, a FIFO, a device) or why it cannot be opened; it
/// does not repeat the path, which the caller names.
pub fn open(path: &Path) -> io::Result<File> {
    check_regular(&std::fs::metadata(path)?)?;
    let file = open_nonblocking(path)?;
    check_regular(&file.metadata()?)?;
    Ok(file)
}

#[cfg(unix)]
fn open_nonblocking(path: &Path) -> io::Result<File> {
    use std::os::unix::fs::OpenOptionsExt;
    // O_NONBLOCK only changes opening a FIFO (it returns at once instead of waiting for a writer);
    // reads from a regular file are unaffected.
    std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
}

#[cfg(not(unix))]
fn open_nonblocking(path: &Path) -> io::Result<File> {
    File::open(path)
}

/// The size of the open regular file `file`, checked against `limit`.
pub fn checked_size(file: &File, limit: SizeLimit) -> io::Result<u64> {
    let size = file.metadata()?.len();
    if size > limit.bytes {
        return Err(too_large(size, limit));
    }
    Ok(size)
}

fn too_large(size: u64, limit: SizeLimit) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidData,
        format!(
            "the file is {} bytes, over the limit of {} bytes{}",
            size,
            limit.bytes,
            raise_hint(limit.flag)
        ),
    )
}

/// Reads the whole regular file at `path`, refusing it if it holds more than `limit` bytes
/// (checked from its size before reading, and again while reading in case it grows). The buffer
/// is reserved fallibly: a size the machine cannot hold is an error, not an abort.
pub fn read(path: &Path, limit: SizeLimit) -> io::Result<Vec<u8>> {
    let file = open(path)?;
    let size = checked_size(&file, limit)?;
    let mut bytes = Vec::new();
    bytes.try_reserve_exact(size as usize).map_err(|_| {
        io::Error::new(
            io::ErrorKind::OutOfMemory,
            format!("not enough memory to read its {size} bytes"),
        )
    })?;
    file.take(limit.bytes.saturating_add(1))
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit.bytes {
        return Err(too_large(bytes.len() as u64, limit));
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    const BIG: SizeLimit = SizeLimit {
        bytes: 1 << 20,
        flag: Some("--max-test-bytes"),
    };

    #[test]
    fn reads_a_regular_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.json");
        std::fs::write(&path, b"{}").unwrap();
        assert_eq!(read(&path, BIG).unwrap(), b"{}");
    }

    #[test]
    fn refuses_a_file_over_the_limit_and_names_the_flag() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.json");
        std::fs::write(&path, vec![b' '; 101]).unwrap();
        let limit = SizeLimit {
            bytes: 100,
            flag: Some("--max-x"),
        };
        let msg = read(&path, limit).unwrap_err().to_string();
        assert!(msg.contains("101 bytes") && msg.contains("100") && msg.contains("--max-x"));
        std::fs::write(&path, vec![b' '; 100]).unwrap();
        assert_eq!(read(&path, limit).unwrap().len(), 100);
    }

    #[test]
    fn refuses_a_folder() {
        let dir = tempfile::tempdir().unwrap();
        let msg = read(dir.path(), BIG).unwrap_err().to_string();
        assert_eq!(msg, "it is a folder, not a regular file");
    }

    #[cfg(unix)]
    #[test]
    fn refuses_devices_and_fifos_without_blocking() {
        let msg = read(Path::new("/dev/zero"), BIG).unwrap_err().to_string();
        assert!(msg.contains("character device"), "{msg}");
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("pipe");
        let status = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap();
        assert!(status.success());
        // Opening a FIFO for reading blocks until a writer comes; this returns at once.
        let msg = open(&fifo).unwrap_err().to_string();
        assert!(msg.contains("FIFO"), "{msg}");
    }

    #[test]
    fn a_missing_file_is_the_os_error() {
        let err = read(Path::new("/no/such/file.json"), BIG).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::NotFound);
    }
}
