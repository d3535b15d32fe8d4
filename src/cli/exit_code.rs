//! Exit statuses shared by the `raytracer` subcommands.

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
