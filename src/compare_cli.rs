//! `raytracer compare REF TEST`: image error metrics on the command line, for marking scripts and
//! CI. Exit status 0 when within the given thresholds, 3 when worse, 1 when an image cannot be
//! read or the sizes or region do not fit, 2 on a usage error.

use raytracer::files::shown;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;

use raytracer::film::ToneMap;
use raytracer::image_io::{read_image, write_image};
use raytracer::metric::{flip_map, heat_map, mse, psnr, Region};

use crate::exit_code;

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
    /// Fail (exit 3) if the MSE is above this.
    #[arg(long)]
    max_mse: Option<f64>,
    /// Fail (exit 3) if the mean FLIP is above this.
    #[arg(long)]
    max_flip: Option<f64>,
    /// Write a FLIP heat map (PNG, PPM or EXR) here.
    #[arg(long)]
    diff: Option<PathBuf>,
}

pub fn main(args: &[std::ffi::OsString]) -> ExitCode {
    let cli = match exit_code::parse::<CompareCli>(args) {
        Ok(c) => c,
        Err(code) => return code,
    };
    match run(&cli) {
        Ok(worse) => ExitCode::from(if worse {
            exit_code::WORSE
        } else {
            exit_code::OK
        }),
        Err(msg) => {
            eprintln!("error: {msg}");
            ExitCode::from(exit_code::BAD_INPUT)
        }
    }
}

/// Prints the metrics; `Ok(true)` when a threshold is exceeded.
fn run(cli: &CompareCli) -> Result<bool, String> {
    let reference = read_image(&cli.reference).map_err(|e| e.to_string())?;
    let test = read_image(&cli.test).map_err(|e| e.to_string())?;
    if (reference.width, reference.height) != (test.width, test.height) {
        return Err(format!(
            "the images differ in size: {} is {}×{}, {} is {}×{}",
            shown(&cli.reference),
            reference.width,
            reference.height,
            shown(&cli.test),
            test.width,
            test.height
        ));
    }
    let region = cli
        .region
        .unwrap_or(Region::full(reference.width, reference.height));
    if !region.fits(reference.width, reference.height) {
        return Err(format!(
            "the region {},{},{},{} does not fit the {}×{} images",
            region.x, region.y, region.width, region.height, reference.width, reference.height
        ));
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
    println!("mse {e:.6e}");
    println!("psnr {:.3} dB", psnr(e));
    println!("flip {flip:.6}");
    if let Some(path) = &cli.diff {
        let heat = heat_map(reference.width, reference.height, &map);
        write_image(path, &heat, ToneMap::Linear, 1.0).map_err(|e| e.to_string())?;
    }
    let mut worse = false;
    if let Some(m) = cli.max_mse {
        if e > m {
            eprintln!("MSE {e:.6e} is above --max-mse {m:e}");
            worse = true;
        }
    }
    if let Some(m) = cli.max_flip {
        if flip > m {
            eprintln!("mean FLIP {flip:.6} is above --max-flip {m}");
            worse = true;
        }
    }
    Ok(worse)
}
