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
