//! `raytracer merge OUT TILE.exr...`: puts the tiles of a split render (crops and sample ranges,
//! in any order) back together into one image, byte for byte the image of the render done whole
//! with the same tone map and exposure.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;

use raytracer::files::output::Outputs;
use raytracer::files::shown;
use raytracer::film::ToneMap;
use raytracer::image_io::{encode_image, OutputFormat};
use raytracer::parts::merge::{assemble, read_tiles};

use super::exit_code::{self, Failure};
use super::interrupt::Interrupt;
use super::values;

#[derive(Parser, Debug)]
#[command(
    name = "raytracer merge",
    about = "Merges the EXR tiles of a render split with --crop and --sample-range into the whole image.",
    after_help = "Exit codes: 0 merged; 1 a tile cannot be read, is not a raytracer tile, or the tiles do not make one image (a gap, an overlap, a different scene, size or spp); 2 usage error; 130 interrupted. Nothing is written unless the merge succeeds.\n\
                  The output's bytes equal those of `raytracer SCENE OUT` with the same options: the tiles hold exact sample sums."
)]
struct MergeCli {
    /// The image to write: .ppm, .png or .exr.
    output: PathBuf,
    /// The tiles (EXR files written by renders with --crop and/or --sample-range).
    #[arg(required = true)]
    tiles: Vec<PathBuf>,
    /// Tone map for 8-bit output, as for a render (default: the one the scene asks for, else
    /// linear).
    #[arg(long)]
    tonemap: Option<ToneMap>,
    /// Multiplies the scene's exposure, as for a render.
    #[arg(long, default_value_t = 1.0, value_parser = values::non_negative_f32)]
    exposure: f32,
    /// Refuse tiles of images with more pixels than this.
    #[arg(long, default_value_t = raytracer::scene::load::DEFAULT_MAX_PIXELS)]
    max_pixels: u64,
    /// No summary line.
    #[arg(short, long)]
    quiet: bool,
}

/// What an interrupted merge did not write.
const NOT_WRITTEN: &str = "no image written";

/// Parses the subcommand's command line without running it.
pub(super) fn try_parse(args: &[std::ffi::OsString]) -> Result<(), clap::Error> {
    <MergeCli as Parser>::try_parse_from(args).map(drop)
}

/// Runs `raytracer merge` (`args` start with the subcommand's name) and returns its exit status.
pub fn main(args: &[std::ffi::OsString]) -> ExitCode {
    let cli = match exit_code::parse::<MergeCli>(args) {
        Ok(c) => c,
        Err(code) => return code,
    };
    let interrupt = Interrupt::install(NOT_WRITTEN);
    match run(&cli, &interrupt) {
        Ok(()) => ExitCode::from(exit_code::OK),
        Err(failure) => failure.report(),
    }
}

/// Reads the tiles, assembles them and writes the image.
fn run(cli: &MergeCli, interrupt: &Interrupt) -> Result<(), Failure> {
    if OutputFormat::from_path(&cli.output).is_none() {
        return Err(Failure::Usage(format!(
            "cannot tell the image format of '{}': use .ppm, .png or .exr",
            shown(&cli.output)
        )));
    }
    Outputs::from_inputs(cli.tiles.iter().map(PathBuf::as_path))
        .claim(&cli.output)
        .map_err(|e| Failure::Usage(e.to_string()))?;
    let pending = interrupt.create(&cli.output)?;
    let tiles = read_tiles(&cli.tiles, cli.max_pixels).map_err(Failure::Input)?;
    let film = assemble(&tiles).map_err(|e| Failure::Input(e.to_string()))?;
    if interrupt.is_set() {
        return Err(Failure::Interrupted(NOT_WRITTEN));
    }
    let tonemap = ToneMap::chosen(cli.tonemap, tiles[0].part.tone_map);
    let exposure = tiles[0].part.display_exposure(tonemap) * cli.exposure;
    let bytes = encode_image(&cli.output, &film, tonemap, exposure)
        .map_err(|e| Failure::Input(e.to_string()))?;
    interrupt.commit(pending, &bytes)?;
    if !cli.quiet {
        eprintln!(
            "{}: {}×{} from {} tiles",
            shown(&cli.output),
            film.width,
            film.height,
            tiles.len()
        );
    }
    Ok(())
}
