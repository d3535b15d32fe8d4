//! Ctrl-C, SIGTERM and SIGHUP for a command that writes an output: stop within a fraction of a
//! second whatever it is doing, leave no temporary file, write nothing, exit 130.
//!
//! The signal sets a flag that the render reads at every camera sample and shading point, so a
//! render stops by itself almost at once and the command returns, removing its temporary output
//! on the way. Reading a scene and building the accelerator do not read the flag; if the command
//! has not ended [`GRACE`] after the signal, the handler removes the temporary output itself and
//! ends the process. Once the finished image is being written, the write is let complete (it is
//! short, and atomic either way).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use super::exit_code;
use raytracer::files::output::{OutputError, PendingFile};

/// How long a signalled command may take to stop by itself before it is ended.
pub const GRACE: Duration = Duration::from_millis(50);

/// What the command is doing, which decides what the handler may do.
#[derive(Debug)]
enum Phase {
    /// Reading, building or rendering; the temporary outputs created so far.
    Working(Vec<PathBuf>),
    /// Writing the finished output: not to be cut short.
    Writing,
}

/// The interrupt flag and what the handler must clean up.
#[derive(Debug, Clone)]
pub struct Interrupt {
    flag: Arc<AtomicBool>,
    phase: Arc<Mutex<Phase>>,
    /// What the handler prints when it ends the process, e.g. "no image written".
    message: &'static str,
}

impl Interrupt {
    /// Installs the handler. If it cannot be installed, the signals keep their default effect,
    /// which also writes nothing (only the temporary file may then remain).
    pub fn install(message: &'static str) -> Interrupt {
        let interrupt = Interrupt {
            flag: Arc::new(AtomicBool::new(false)),
            phase: Arc::new(Mutex::new(Phase::Working(Vec::new()))),
            message,
        };
        let handler = interrupt.clone();
        let _ = ctrlc::set_handler(move || handler.on_signal());
        interrupt
    }

    /// Sets the flag; if the command has not stopped within [`GRACE`] and is not writing its
    /// output, removes the temporary outputs and ends the process.
    fn on_signal(&self) {
        self.flag.store(true, Ordering::Relaxed);
        std::thread::sleep(GRACE);
        let phase = self.phase.lock().unwrap_or_else(|e| e.into_inner());
        if let Phase::Working(temps) = &*phase {
            for temp in temps {
                let _ = std::fs::remove_file(temp);
            }
            eprintln!("interrupted: {}", self.message);
            std::process::exit(i32::from(exit_code::INTERRUPTED));
        }
    }

    /// The flag the render reads.
    pub fn flag(&self) -> Arc<AtomicBool> {
        self.flag.clone()
    }

    /// Whether a signal came.
    pub fn is_set(&self) -> bool {
        self.flag.load(Ordering::Relaxed)
    }

    /// Records a temporary output the handler must remove if it ends the process.
    fn pending(&self, temp: &Path) {
        let mut phase = self.phase.lock().unwrap_or_else(|e| e.into_inner());
        if let Phase::Working(temps) = &mut *phase {
            temps.push(temp.to_path_buf());
        }
    }

    /// Creates the temporary output for `path` (see [`PendingFile`]) and records it.
    pub fn create(&self, path: &Path) -> Result<PendingFile, OutputError> {
        let pending = PendingFile::create(path)?;
        self.pending(pending.temp_path());
        Ok(pending)
    }

    /// Commits `pending` with `bytes`, not to be cut short by a signal.
    pub fn commit(&self, pending: PendingFile, bytes: &[u8]) -> Result<(), OutputError> {
        let temp = pending.temp_path().to_path_buf();
        self.writing(&temp, || pending.commit(bytes))
    }

    /// Runs `write` (committing the finished output whose temporary file is `temp`) without
    /// being cut short by a signal; the other temporary outputs stay the handler's to remove.
    fn writing<R>(&self, temp: &Path, write: impl FnOnce() -> R) -> R {
        let rest = {
            let mut phase = self.phase.lock().unwrap_or_else(|e| e.into_inner());
            let rest = match &mut *phase {
                Phase::Working(temps) => {
                    temps.retain(|t| t != temp);
                    std::mem::take(temps)
                }
                Phase::Writing => Vec::new(),
            };
            *phase = Phase::Writing;
            rest
        };
        let result = write();
        *self.phase.lock().unwrap_or_else(|e| e.into_inner()) = Phase::Working(rest);
        result
    }
}
