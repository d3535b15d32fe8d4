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
//! | `raytracer check SCENE...` | [`check`] |
//! | `raytracer watch SCENE` | [`watch`] |
//! | `raytracer schema` | [`schema`] |

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

mod batch;
mod bench;
mod check;
mod compare;
mod exit_code;
mod image_flags;
mod interrupt;
mod load_flags;
mod merge;
mod render;
mod schema;
mod study;
mod values;
mod watch;

use std::ffi::OsString;
use std::process::ExitCode;

/// The subcommand `args[1]` names, if any (a scene file literally named `bench` is rendered
/// when given as `./bench`).
fn subcommand(args: &[OsString]) -> Option<&'static str> {
    let first = args.get(1)?;
    [
        "batch", "bench", "check", "compare", "merge", "schema", "study", "watch",
    ]
    .into_iter()
    .find(|name| first == name)
}

/// `--strict`: every warning about `scene` is an error. Prints each as one and fails with their
/// count; passes a scene without warnings.
fn strict(scene: &raytracer::scene::Scene) -> Result<(), String> {
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
fn main() -> ExitCode {
    let args: Vec<OsString> = std::env::args_os().collect();
    let args = &args[..];
    raytracer::files::output::report_file_size_limit();
    match subcommand(args) {
        Some("batch") => batch::main(&args[1..]),
        Some("bench") => bench::main(&args[1..]),
        Some("check") => check::main(&args[1..]),
        Some("compare") => compare::main(&args[1..]),
        Some("merge") => merge::main(&args[1..]),
        Some("schema") => schema::main(&args[1..]),
        Some("study") => study::main(&args[1..]),
        Some("watch") => watch::main(&args[1..]),
        _ => render::main(args),
    }
}

/// Parses `args` as [`main`] would, without running anything: for tests and fuzzing of the
/// parser and of every flag's validation.
pub fn try_parse(args: &[OsString]) -> Result<(), clap::Error> {
    match subcommand(args) {
        Some("batch") => batch::try_parse(&args[1..]),
        Some("bench") => bench::try_parse(&args[1..]),
        Some("check") => check::try_parse(&args[1..]),
        Some("compare") => compare::try_parse(&args[1..]),
        Some("merge") => merge::try_parse(&args[1..]),
        Some("schema") => schema::try_parse(&args[1..]),
        Some("study") => study::try_parse(&args[1..]),
        Some("watch") => watch::try_parse(&args[1..]),
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

    /// Words a command line is made of: every flag and value of `fuzz/cli_args.dict` (the
    /// dictionary of the parser's fuzzing), paths and awkward numbers.
    fn words() -> Vec<String> {
        let mut words: Vec<String> = include_str!("../../fuzz/cli_args.dict")
            .lines()
            .filter_map(|l| l.trim().strip_prefix('"')?.strip_suffix('"'))
            .filter(|w| !w.contains('\\'))
            .map(str::to_string)
            .collect();
        for w in [
            "s.json", "o.png", "o.exr", "dir", "4", "0", "-1", "0.5", "1e-45", "65536", "2,3", "",
        ] {
            words.push(w.to_string());
        }
        words
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(3000))]

        /// Any command line of up to 24 words, flags and values in any order: parsing never
        /// panics, an accepted line is accepted again, and every rejection says why.
        #[test]
        fn any_command_line_parses_or_is_refused_with_a_message(
            picks in proptest::collection::vec((0usize..1000, "[ -~]{0,6}"), 0..24)
        ) {
            let words = words();
            let mut args = vec![OsString::from("raytracer")];
            for (i, free) in picks {
                // One word in eight is free text, the rest come from the dictionary.
                args.push(OsString::from(if i % 8 == 7 { free } else { words[i % words.len()].clone() }));
            }
            match try_parse(&args) {
                Ok(()) => proptest::prop_assert!(try_parse(&args).is_ok()),
                Err(e) => proptest::prop_assert!(!e.to_string().is_empty()),
            }
        }
    }
}
