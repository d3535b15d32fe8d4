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

/// How long a signalled command may take to stop by itself before it is ended.
pub const GRACE: Duration = Duration::from_millis(50);

#[derive(Debug)]
enum Phase {
    /// Reading, building or rendering; the temporary output, once created.
    Working(Option<PathBuf>),
    /// Writing the finished output: not to be cut short.
    Writing,
}

/// The interrupt flag and what the handler must clean up.
#[derive(Debug, Clone)]
pub struct Interrupt {
    flag: Arc<AtomicBool>,
    phase: Arc<Mutex<Phase>>,
}

impl Interrupt {
    /// Installs the handler. If it cannot be installed, the signals keep their default effect,
    /// which also writes nothing (only the temporary file may then remain).
    pub fn install() -> Interrupt {
        let interrupt = Interrupt {
            flag: Arc::new(AtomicBool::new(false)),
            phase: Arc::new(Mutex::new(Phase::Working(None))),
        };
        let handler = interrupt.clone();
        let _ = ctrlc::set_handler(move || handler.on_signal());
        interrupt
    }

    fn on_signal(&self) {
        self.flag.store(true, Ordering::Relaxed);
        std::thread::sleep(GRACE);
        let phase = self.phase.lock().unwrap_or_else(|e| e.into_inner());
        if let Phase::Working(temp) = &*phase {
            if let Some(temp) = temp {
                let _ = std::fs::remove_file(temp);
            }
            eprintln!("interrupted: no image written");
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

    /// Records the temporary output the handler must remove if it ends the process.
    pub fn pending(&self, temp: &Path) {
        let mut phase = self.phase.lock().unwrap_or_else(|e| e.into_inner());
        *phase = Phase::Working(Some(temp.to_path_buf()));
    }

    /// Runs `write` (committing the finished output) without being cut short by a signal.
    pub fn writing<R>(&self, write: impl FnOnce() -> R) -> R {
        *self.phase.lock().unwrap_or_else(|e| e.into_inner()) = Phase::Writing;
        write()
    }
}
