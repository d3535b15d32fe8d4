//! The command line: one module per subcommand, each a thin layer that parses its flags, calls
//! the library and maps errors to [`exit_code`]s.
//!
//! | command | module |
//! |---|---|
//! | `raytracer SCENE OUT` | [`render`] |
//! | `raytracer merge OUT TILE...` | [`merge`] |
//! | `raytracer batch SCENES... --out DIR` | [`batch`] |
//! | `raytracer compare REF TEST` | [`compare`] |
//! | `raytracer study SCENE` | [`study`] |
//! | `raytracer bench` | [`mod@bench`] |

/// Writes to standard output like `print!`, but a closed pipe (`raytracer compare a b | head -1`)
/// is not a panic: what cannot be printed is dropped, and the command's work and exit status go
/// on.
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = write!(std::io::stdout(), $($arg)*);
    }};
}

/// [`out!`] with a newline.
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout(), $($arg)*);
    }};
}

pub mod batch;
pub mod bench;
pub mod compare;
pub mod exit_code;
pub mod image_flags;
pub mod interrupt;
pub mod merge;
pub mod render;
pub mod study;
pub mod values;

use std::ffi::OsString;
use std::process::ExitCode;

/// The subcommand `args[1]` names, if any (a scene file literally named `bench` is rendered
/// when given as `./bench`).
fn subcommand(args: &[OsString]) -> Option<&'static str> {
    let first = args.get(1)?;
    ["batch", "bench", "compare", "merge", "study"]
        .into_iter()
        .find(|name| first == name)
}

/// `--strict`: every warning about `scene` is an error. Prints each as one and fails with their
/// count; passes a scene without warnings.
fn strict(scene: &crate::scene::Scene) -> Result<(), String> {
    let n = scene.warnings.len();
    if n == 0 {
        return Ok(());
    }
    for w in &scene.warnings {
        eprintln!("error: {w}");
    }
    let s = if n == 1 { "" } else { "s" };
    Err(format!(
        "{n} warning{s} about the scene, errors under --strict; nothing written"
    ))
}

/// Runs the command line `args` (program name first) and returns the process's exit status.
pub fn main(args: &[OsString]) -> ExitCode {
    crate::files::output::report_file_size_limit();
    match subcommand(args) {
        Some("batch") => batch::main(&args[1..]),
        Some("bench") => bench::main(&args[1..]),
        Some("compare") => compare::main(&args[1..]),
        Some("merge") => merge::main(&args[1..]),
        Some("study") => study::main(&args[1..]),
        _ => render::main(args),
    }
}

/// Parses `args` as [`main`] would, without running anything: for tests and fuzzing of the
/// parser and of every flag's validation.
pub fn try_parse(args: &[OsString]) -> Result<(), clap::Error> {
    match subcommand(args) {
        Some("batch") => batch::try_parse(&args[1..]),
        Some("bench") => bench::try_parse(&args[1..]),
        Some("compare") => compare::try_parse(&args[1..]),
        Some("merge") => merge::try_parse(&args[1..]),
        Some("study") => study::try_parse(&args[1..]),
        _ => render::try_parse(args),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(line: &str) -> Result<(), clap::Error> {
        let args: Vec<OsString> = line.split(' ').map(OsString::from).collect();
        try_parse(&args)
    }

    #[test]
    fn every_subcommand_parses_and_validates_its_numbers() {
        parse("raytracer s.json o.png --spp 4 --exposure 0.5").unwrap();
        parse("raytracer compare a.png b.png --max-mse 0.01").unwrap();
        parse("raytracer study s.json --quick").unwrap();
        parse("raytracer bench --quick").unwrap();
        parse("raytracer batch a.json dir --out o --reference r --max-flip 0.05").unwrap();
        for bad in [
            "raytracer s.json o.png --exposure NaN",
            "raytracer s.json o.png --threads 0",
            "raytracer compare a.png b.png --max-flip nan",
            "raytracer study s.json --threads 0",
            "raytracer bench --runs 0",
            "raytracer s.json",
            "raytracer batch --out o",
            "raytracer batch a.json",
            "raytracer batch a.json --out o --reference r --max-flip NaN",
            "raytracer batch a.json --out o --reference r --max-flip -1",
            "raytracer batch a.json --out o --max-flip 0.1",
            "raytracer batch a.json --out o --format bmp",
        ] {
            assert!(parse(bad).is_err(), "{bad}");
        }
    }
}
