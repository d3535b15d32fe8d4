//! `raytracer compare REF TEST`: image error metrics on the command line, for marking scripts and
//! CI. Exit status 0 when within the given thresholds, 3 when worse, 1 when an image cannot be
//! read or the sizes or region do not fit, 2 on a usage error.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;

use raytracer::files::output::Outputs;
use raytracer::files::shown;
use raytracer::film::ToneMap;
use raytracer::image_io::{encode_image, read_image};
use raytracer::metric::{flip_map, heat_map, mse, psnr, Region};

use super::exit_code::{self, Failure};
use super::interrupt::Interrupt;
use super::values;

#[derive(Parser, Debug)]
#[command(
    name = "raytracer compare",
    about = "Compares a test image with a reference: MSE of linear RGB in [0,1] (8-bit values / 255), PSNR and mean FLIP.",
    after_help = "Exit codes: 0 within thresholds; 1 an image cannot be read or the sizes/region do not fit; 2 usage error; 3 worse than a threshold.\n\
                  Images: PNG, JPEG, PPM (P3/P6) or EXR (linear floats)."
)]
struct CompareCli {
    /// The reference image.
    reference: PathBuf,
    /// The image to judge.
    test: PathBuf,
    /// Only pixels in this rectangle: x,y,width,height.
    #[arg(long)]
    region: Option<Region>,
    /// Fail (exit 3) if the MSE is above this (or not a number: an image holds NaN).
    #[arg(long, value_parser = values::non_negative_f64)]
    max_mse: Option<f64>,
    /// Fail (exit 3) if the mean FLIP is above this (or not a number).
    #[arg(long, value_parser = values::non_negative_f64)]
    max_flip: Option<f64>,
    /// Write a FLIP heat map (PNG, PPM or EXR) here.
    #[arg(long)]
    diff: Option<PathBuf>,
}

/// Whether `value` is within `max`; NaN is never within.
fn within(value: f64, max: f64) -> bool {
    value <= max
}

/// Parses the subcommand's command line without running it.
pub(super) fn try_parse(args: &[std::ffi::OsString]) -> Result<(), clap::Error> {
    <CompareCli as Parser>::try_parse_from(args).map(drop)
}

/// Runs `raytracer compare` (`args` start with the subcommand's name) and returns its exit status.
pub fn main(args: &[std::ffi::OsString]) -> ExitCode {
    let cli = match exit_code::parse::<CompareCli>(args) {
        Ok(c) => c,
        Err(code) => return code,
    };
    let interrupt = Interrupt::install("no heat map written");
    match run(&cli, &interrupt) {
        Ok(worse) => ExitCode::from(if worse {
            exit_code::WORSE
        } else {
            exit_code::OK
        }),
        Err(failure) => failure.report(),
    }
}

/// Prints the metrics; `Ok(true)` when a threshold is exceeded.
fn run(cli: &CompareCli, interrupt: &Interrupt) -> Result<bool, Failure> {
    // The heat map may be neither image; its folder is checked before the work.
    let diff_out = match &cli.diff {
        Some(path) => {
            let mut guard = Outputs::from_inputs([cli.reference.as_path(), cli.test.as_path()]);
            guard
                .claim(path)
                .map_err(|e| Failure::Usage(e.to_string()))?;
            Some(interrupt.create(path).map_err(|e| e.to_string())?)
        }
        None => None,
    };
    let reference = read_image(&cli.reference).map_err(|e| e.to_string())?;
    let test = read_image(&cli.test).map_err(|e| e.to_string())?;
    if (reference.width, reference.height) != (test.width, test.height) {
        return Err(Failure::Input(format!(
            "the images differ in size: {} is {}×{}, {} is {}×{}",
            shown(&cli.reference),
            reference.width,
            reference.height,
            shown(&cli.test),
            test.width,
            test.height
        )));
    }
    let region = cli
        .region
        .unwrap_or(Region::full(reference.width, reference.height));
    if !region.fits(reference.width, reference.height) {
        return Err(Failure::Input(format!(
            "the region {},{},{},{} does not fit the {}×{} images",
            region.x, region.y, region.width, region.height, reference.width, reference.height
        )));
    }
    let e = mse(&reference, &test, region);
    let map = flip_map(&reference, &test);
    let mut sum = 0.0f64;
    for y in region.y..region.y + region.height {
        for x in region.x..region.x + region.width {
            sum += map[(y * reference.width + x) as usize] as f64;
        }
    }
    let flip = sum / (region.width as f64 * region.height as f64);
    outln!("mse {e:.6e}");
    outln!("psnr {:.3} dB", psnr(e));
    outln!("flip {flip:.6}");
    for (name, path, image) in [
        ("reference", &cli.reference, &reference),
        ("test", &cli.test, &test),
    ] {
        let bad = image.pixels.iter().filter(|p| !p.is_finite()).count();
        if bad > 0 {
            eprintln!(
                "the {name} image {} has {bad} pixel(s) with NaN or infinite values",
                shown(path)
            );
        }
    }
    if let (Some(path), Some(pending)) = (&cli.diff, diff_out) {
        let heat = heat_map(reference.width, reference.height, &map);
        let bytes = encode_image(path, &heat, ToneMap::Linear, 1.0).map_err(|e| e.to_string())?;
        interrupt
            .commit(pending, &bytes)
            .map_err(|e| e.to_string())?;
    }
    let mut worse = false;
    if let Some(m) = cli.max_mse {
        if !within(e, m) {
            eprintln!("MSE {e:.6e} is above --max-mse {m:e}");
            worse = true;
        }
    }
    if let Some(m) = cli.max_flip {
        if !within(flip, m) {
            eprintln!("mean FLIP {flip:.6} is above --max-flip {m}");
            worse = true;
        }
    }
    Ok(worse)
}
