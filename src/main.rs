//! The `raytracer` binary: see [`raytracer::cli`].

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<std::ffi::OsString> = std::env::args_os().collect();
    raytracer::cli::main(&args)
}
