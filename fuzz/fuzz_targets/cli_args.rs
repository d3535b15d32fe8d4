//! Fuzz target: the command-line parser of every subcommand, with every flag's validation.
//!
//! The input is split at NUL bytes into at most 24 arguments (bytes that are not UTF-8 stay as
//! they are: command lines are OS strings), preceded by the program name, and parsed with
//! `raytracer::cli::try_parse`, which runs clap and each flag's value parser without starting
//! any work. Checked: no panic; an accepted command line parses the same way twice; every
//! rejection has a message.

#![no_main]

use std::ffi::OsString;
use std::os::unix::ffi::OsStringExt;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut args = vec![OsString::from("raytracer")];
    args.extend(
        data.split(|&b| b == 0)
            .take(24)
            .map(|a| OsString::from_vec(a.to_vec())),
    );
    match raytracer::cli::try_parse(&args) {
        Ok(()) => assert!(raytracer::cli::try_parse(&args).is_ok()),
        Err(e) => assert!(!e.to_string().is_empty()),
    }
});
