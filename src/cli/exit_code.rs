//! Exit statuses shared by the `raytracer` subcommands, and the failures that lead to them.

use raytracer::files::output::OutputError;

/// Success: the image was written, or the comparison is within its thresholds.
pub const OK: u8 = 0;
/// A scene, asset or image is bad, or an output could not be written.
pub const BAD_INPUT: u8 = 1;
/// The command line is wrong.
pub const USAGE: u8 = 2;
/// `compare`: the test image is worse than a threshold.
pub const WORSE: u8 = 3;
/// Interrupted (128 + SIGINT, as shells report it); nothing was written.
pub const INTERRUPTED: u8 = 130;

/// Parses a command line; on `--help`/`--version` prints and exits OK, on an error prints it and
/// exits with [`USAGE`].
pub fn parse<T: clap::Parser>(
    args: impl IntoIterator<Item = impl Into<std::ffi::OsString> + Clone>,
) -> Result<T, std::process::ExitCode> {
    T::try_parse_from(args).map_err(|e| {
        let code = if e.use_stderr() { USAGE } else { OK };
        let _ = e.print();
        std::process::ExitCode::from(code)
    })
}

/// Why a subcommand stopped without finishing its work; [`Failure::report`] prints it and gives
/// the exit status.
pub enum Failure {
    /// The command line is wrong, or an output would be one of the inputs.
    Usage(String),
    /// A bad scene, asset or image, or an output that cannot be written. The message names the
    /// file and carries its cause in its own text, so it is printed once, without a source chain.
    Input(String),
    /// A signal stopped the work; the message says what was not written.
    Interrupted(&'static str),
}

impl Failure {
    /// Prints the failure on stderr and returns its exit status.
    pub fn report(self) -> std::process::ExitCode {
        let code = match self {
            Failure::Usage(msg) => {
                eprintln!("error: {msg}");
                USAGE
            }
            Failure::Input(msg) => {
                eprintln!("error: {msg}");
                BAD_INPUT
            }
            Failure::Interrupted(what) => {
                eprintln!("interrupted: {what}");
                INTERRUPTED
            }
        };
        std::process::ExitCode::from(code)
    }
}

impl From<String> for Failure {
    fn from(msg: String) -> Failure {
        Failure::Input(msg)
    }
}

impl From<OutputError> for Failure {
    /// An output that is an input (or another output) is a usage error; any other output
    /// failure is the output's.
    fn from(e: OutputError) -> Failure {
        match e {
            OutputError::IsInput { .. } | OutputError::Twice { .. } => {
                Failure::Usage(e.to_string())
            }
            _ => Failure::Input(e.to_string()),
        }
    }
}
