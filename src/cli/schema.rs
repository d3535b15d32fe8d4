//! `raytracer schema`: prints the JSON Schema of the scene format, for editors
//! (`docs/schema.md`). The repository keeps the same text in `docs/scene.schema.json`.

use std::ffi::OsString;
use std::process::ExitCode;

use clap::Parser;

use crate::exit_code;

#[derive(Parser, Debug)]
#[command(
    name = "raytracer schema",
    about = "Prints the JSON Schema (draft-07) of the scene format, generated from the spellings the loader reads: point an editor's JSON checking at it to complete keys and see mistakes as you type.",
    after_help = "docs/schema.md shows how to use it in VS Code and other editors. The same text is docs/scene.schema.json in the repository."
)]
struct SchemaCli {}

/// Parses the subcommand's command line without running it.
pub(super) fn try_parse(args: &[OsString]) -> Result<(), clap::Error> {
    <SchemaCli as Parser>::try_parse_from(args).map(drop)
}

/// Runs `raytracer schema` (`args` start with the subcommand's name) and returns its exit status.
pub fn main(args: &[OsString]) -> ExitCode {
    if let Err(code) = exit_code::parse::<SchemaCli>(args) {
        return code;
    }
    out!("{}", raytracer::scene::schema::text());
    ExitCode::from(exit_code::OK)
}
