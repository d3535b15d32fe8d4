//! `raytracer SCENE OUT`: render a scene to an image.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Parser;

use raytracer::files::output::{Outputs, PendingFile};
use raytracer::files::shown;
use raytracer::film::{Film, PixelRect, ToneMap};
use raytracer::image_io::{encode_image, OutputFormat};
use raytracer::parts::{self, Part};
use raytracer::render::{render, RenderError, RenderOptions, RenderOutput};
use raytracer::scene::{load, Scene};

use super::exit_code::{self, Failure};
use super::image_flags::ImageFlags;
use super::interrupt::Interrupt;
use super::load_flags::LoadFlags;
use super::values;

#[derive(Parser, Debug)]
#[command(
    name = "raytracer",
    version,
    about = "Renders a coursework JSON scene to a PPM, PNG or EXR image.",
    after_help = "Exit codes: 0 rendered; 1 the scene or an asset is bad (or the image could not be written; with --strict, also when the scene has warnings); 2 usage error (also: the output is one of the scene's files); 130 interrupted (nothing written).\n\
                  Output format by extension: .ppm (binary P6), .png (8-bit), .exr (linear 32-bit float, not tone-mapped).\n\
                  Inputs must be regular files (not FIFOs or devices); the image is written atomically and never onto the scene, a texture or a mesh it uses.\n\
                  Image comparison: raytracer compare --help. Many scenes at once: raytracer batch --help. Benchmarks: raytracer bench --help."
)]
struct RenderCli {
    /// The scene file (JSON; comments and trailing commas allowed).
    scene: PathBuf,
    /// The image to write: .ppm, .png or .exr.
    output: PathBuf,
    #[command(flatten)]
    image: ImageFlags,
    #[command(flatten)]
    load: LoadFlags,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = values::thread_count())]
    threads: Option<u64>,
    /// Render only the pixels x ∈ [X0, X1), y ∈ [Y0, Y1) (origin top left) of the image, as an
    /// EXR tile for `raytracer merge` (the output must be .exr).
    #[arg(long, value_name = "X0,Y0,X1,Y1", conflicts_with = "tile")]
    crop: Option<PixelRect>,
    /// Render cell COL,ROW (from 0,0 at the top left) of the grid given by --tiles, as an EXR
    /// tile: the crop of columns ⌊COL·width/COLS⌋ .. ⌊(COL+1)·width/COLS⌋, rows likewise.
    #[arg(long, value_name = "COL,ROW", requires = "tiles", value_parser = values::pair)]
    tile: Option<(u32, u32)>,
    /// The grid of --tile: COLS columns by ROWS rows.
    #[arg(long, value_name = "COLS,ROWS", requires = "tile", value_parser = values::pair)]
    tiles: Option<(u32, u32)>,
    /// Trace only samples A ≤ i < B of each pixel's --spp (which stays the total, so the samples
    /// are those of the whole render), as an EXR tile for `raytracer merge` (output .exr).
    #[arg(long, value_name = "A..B", value_parser = values::sample_range, conflicts_with = "adaptive")]
    sample_range: Option<std::ops::Range<u32>>,
    /// With --adaptive: also write the samples each pixel took, as a heat map (black: none,
    /// yellow: all of --spp), to this image.
    #[arg(long, value_name = "FILE", requires = "adaptive")]
    sample_map: Option<PathBuf>,
    /// No progress bar, no warnings, no summary line.
    #[arg(short, long)]
    quiet: bool,
    /// Treat every warning about the scene as an error: print them all and write nothing.
    #[arg(long)]
    strict: bool,
}

/// What an interrupted render did not write.
const NOT_WRITTEN: &str = "no image written";

/// Runs `raytracer SCENE OUT` (`args` start with the program's name) and returns its exit status.
pub fn main(args: &[std::ffi::OsString]) -> ExitCode {
    let cli = match exit_code::parse::<RenderCli>(args) {
        Ok(c) => c,
        Err(code) => return code,
    };
    let interrupt = Interrupt::install(NOT_WRITTEN);
    match run(&cli, &interrupt) {
        Ok(()) => ExitCode::from(exit_code::OK),
        Err(failure) => failure.report(),
    }
}

/// Parses a render command line without running it.
pub(super) fn try_parse(args: &[std::ffi::OsString]) -> Result<(), clap::Error> {
    <RenderCli as Parser>::try_parse_from(args).map(drop)
}

/// Checks the flags, loads the scene, renders it on the `--threads` pool and writes the image
/// (and the `--sample-map`).
fn run(cli: &RenderCli, interrupt: &Interrupt) -> Result<(), Failure> {
    let part = check_output(cli)?;
    let scene = load_scene(cli)?;
    let (pending, pending_map) = create_outputs(cli, &scene, interrupt)?;
    if interrupt.is_set() {
        return Err(Failure::Interrupted(NOT_WRITTEN));
    }
    let options = RenderOptions {
        progress: !cli.quiet && std::io::stderr().is_terminal(),
        cancel: Some(interrupt.flag()),
        crop: crop(cli, &scene)?,
        samples: cli.sample_range.clone(),
        keep_sums: part,
        ..cli.image.render_options(&scene)
    };
    let fingerprint = if part {
        parts::fingerprint(&scene, &options).map_err(|e| Failure::Input(e.to_string()))?
    } else {
        0
    };
    let mut out = render_on_pool(cli, &scene, &options)?;
    if out.cancelled || interrupt.is_set() {
        return Err(Failure::Interrupted(NOT_WRITTEN));
    }
    let bytes = encode(cli, &scene, &options, fingerprint, &mut out)?;
    if let (Some(pending_map), Some(counts), Some(path)) =
        (pending_map, &out.sample_counts, &cli.sample_map)
    {
        let map = sample_map(counts, options.spp, &out.film);
        let map_bytes = encode_image(path, &map, ToneMap::Linear, 1.0)
            .map_err(|e| Failure::Input(e.to_string()))?;
        interrupt.commit(pending_map, &map_bytes)?;
    }
    interrupt.commit(pending, &bytes)?;
    if !cli.quiet {
        eprintln!("{}", summary(&cli.output, &out, options.spp));
    }
    Ok(())
}

/// Checks that the output's format is known, and is EXR for a part of a render (`--crop`,
/// `--tile`, `--sample-range`); whether it is such a part.
fn check_output(cli: &RenderCli) -> Result<bool, Failure> {
    if OutputFormat::from_path(&cli.output).is_none() {
        return Err(Failure::Usage(format!(
            "cannot tell the image format of '{}': use .ppm, .png or .exr",
            shown(&cli.output)
        )));
    }
    let part = cli.crop.is_some() || cli.tile.is_some() || cli.sample_range.is_some();
    if part && OutputFormat::from_path(&cli.output) != Some(OutputFormat::Exr) {
        return Err(Failure::Usage(format!(
            "--crop, --tile and --sample-range write a tile for `raytracer merge`, which must be an .exr file, not '{}'",
            shown(&cli.output)
        )));
    }
    Ok(part)
}

/// Loads the scene within the flags' limits, once the output is known not to be the scene file,
/// and shows its warnings (errors with `--strict`).
fn load_scene(cli: &RenderCli) -> Result<Scene, Failure> {
    Outputs::from_inputs([cli.scene.as_path()]).claim(&cli.output)?;
    let load_options = cli.load.options();
    let scene = load(&cli.scene, &load_options).map_err(|e| Failure::Input(e.to_string()))?;
    if cli.strict {
        super::strict(&scene)?;
    } else if !cli.quiet {
        for w in &scene.warnings {
            eprintln!("warning: {w}");
        }
    }
    Ok(scene)
}

/// Claims the image and the `--sample-map` against every file the scene reads, and creates them
/// now, so that a folder that cannot be written is reported before the render; each is removed
/// unless its finished bytes are committed.
fn create_outputs(
    cli: &RenderCli,
    scene: &Scene,
    interrupt: &Interrupt,
) -> Result<(PendingFile, Option<PendingFile>), Failure> {
    let mut outputs = Outputs::from_inputs(scene.inputs.iter().map(PathBuf::as_path));
    outputs.claim(&cli.output)?;
    if let Some(map) = &cli.sample_map {
        if OutputFormat::from_path(map).is_none() {
            return Err(Failure::Usage(format!(
                "cannot tell the image format of --sample-map '{}': use .ppm, .png or .exr",
                shown(map)
            )));
        }
        outputs.claim(map)?;
    }
    let pending = interrupt.create(&cli.output)?;
    let pending_map = match &cli.sample_map {
        Some(map) => Some(interrupt.create(map)?),
        None => None,
    };
    Ok((pending, pending_map))
}

/// Renders `scene` on the `--threads` pool.
fn render_on_pool(
    cli: &RenderCli,
    scene: &Scene,
    options: &RenderOptions,
) -> Result<RenderOutput, Failure> {
    let pool = values::thread_pool(cli.threads).map_err(Failure::Input)?;
    pool.install(|| render(scene, options))
        .map_err(|e| match e {
            // The render checks the crop and range against the scene: the flags' fault.
            RenderError::CropOutside { .. } => Failure::Usage(format!("--crop: {e}")),
            RenderError::SampleRange { .. } => Failure::Usage(format!(
                "--sample-range: {e} (--spp is the whole render's count)"
            )),
            _ => Failure::Input(e.to_string()),
        })
}

/// The output's bytes: an EXR tile for `raytracer merge` when the render kept its sums, else the
/// image, tone-mapped as the flags and the scene say.
fn encode(
    cli: &RenderCli,
    scene: &Scene,
    options: &RenderOptions,
    fingerprint: u64,
    out: &mut RenderOutput,
) -> Result<Vec<u8>, Failure> {
    match Part::of_render(scene, options, fingerprint, out) {
        Some(part) => parts::exr::encode(&part).map_err(|e| {
            Failure::Input(format!(
                "{}: cannot encode the tile: {e}",
                shown(&cli.output)
            ))
        }),
        None => {
            let exposure = cli.image.display_exposure(scene);
            encode_image(&cli.output, &out.film, cli.image.tone_map(scene), exposure)
                .map_err(|e| Failure::Input(e.to_string()))
        }
    }
}

/// The `--sample-map` picture of `film`: each pixel's samples (`counts`) over `spp`, as a heat map.
fn sample_map(counts: &[u32], spp: u32, film: &Film) -> Film {
    let spp = spp.max(1) as f32;
    let share: Vec<f32> = counts.iter().map(|&k| k as f32 / spp).collect();
    raytracer::metric::heat_map(film.width, film.height, &share)
}

/// The line a finished render prints: the image, its size, samples, times, rays and Mrays/s.
fn summary(output: &Path, out: &RenderOutput, spp: u32) -> String {
    let secs = out.render_time.as_secs_f64();
    let rays = out.counts.total();
    format!(
        "{}: {}×{}, {}, {:.3} s (build {:.3} s), {} rays, {:.2} Mrays/s",
        shown(output),
        out.film.width,
        out.film.height,
        match &out.sample_counts {
            Some(counts) => format!(
                "{:.1} spp on average (at most {})",
                counts.iter().map(|&k| f64::from(k)).sum::<f64>() / counts.len().max(1) as f64,
                spp
            ),
            None => format!("{spp} spp"),
        },
        secs,
        out.build_time.as_secs_f64(),
        rays,
        rays as f64 / secs.max(1e-9) / 1e6
    )
}

/// The pixels to render: `--crop`, or the `--tile` cell of the `--tiles` grid.
fn crop(cli: &RenderCli, scene: &Scene) -> Result<Option<PixelRect>, Failure> {
    let size = (scene.camera.width, scene.camera.height);
    match (cli.tile, cli.tiles) {
        (Some(cell), Some(grid)) => PixelRect::grid_cell(size, cell, grid).map(Some).ok_or_else(|| {
            Failure::Usage(format!(
                "--tile {},{} is not a cell of a --tiles {},{} grid over the {}×{} image (0 ≤ COL < COLS ≤ width, 0 ≤ ROW < ROWS ≤ height)",
                cell.0, cell.1, grid.0, grid.1, size.0, size.1
            ))
        }),
        _ => Ok(cli.crop),
    }
}
