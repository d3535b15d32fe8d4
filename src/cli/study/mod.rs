//! `raytracer study SCENE`: how fast each sampler's error falls, per sample (shadow rays of the
//! area lights, or paths per pixel) and per second ([`runs`]). Writes a CSV of the runs and a
//! log-log plot ([`plot`]), and prints the fitted slopes and the time each sampler needs to reach
//! a target MSE. `--skip-work` instead times the work-skipping switches against a plain render,
//! and `--adaptive` adaptive against uniform sampling at equal error ([`mod@adaptive`]).

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;

use raytracer::files::output::{Outputs, PendingFile};
use raytracer::files::shown;
use raytracer::film::ToneMap;
use raytracer::image_io::{encode_image, read_image};
use raytracer::integrator::DEFAULT_CUTOFF;
use raytracer::metric::Region;
use raytracer::render::RenderOptions;
use raytracer::sampling::Method;
use raytracer::scene::{load, LoadOptions};
mod adaptive;
mod plot;
mod runs;

use runs::StudyOptions;

use crate::interrupt::Interrupt;
use crate::{exit_code, values};

#[derive(Parser, Debug)]
#[command(
    name = "raytracer study",
    about = "Compares the samplers (random, jittered, sobol): MSE and FLIP against a reference per sample count and per second of render time.",
    after_help = "Whitted scenes: every run traces one ray per pixel centre and sets every area light's sampler and shadow-ray count. \
                  Path-traced scenes (rendermode pathtrace, or --integrator path): every run takes that many paths per pixel, all their dimensions placed by the sampler. \
                  Outputs: --csv (sampler,samples,seconds,mse,mse_region,flip), --plot (log-log PNG), the reference as EXR, and on stdout the fitted slopes and equal-error times."
)]
struct StudyCli {
    /// The scene file.
    scene: PathBuf,
    /// Folder for the CSV, the plot and the reference image.
    #[arg(long, default_value = "study")]
    out: PathBuf,
    /// CSV file to write (default OUT/study.csv).
    #[arg(long)]
    csv: Option<PathBuf>,
    /// Plot to write (default OUT/study.png).
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Rectangle x,y,width,height (e.g. a penumbra) for the region MSE that the slopes, the
    /// target and the plot use; the whole image without it.
    #[arg(long)]
    region: Option<Region>,
    /// Renders per run; the reported time is their median.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..=1000))]
    runs: u64,
    /// Largest sample count: shadow rays per area light (Whitted), or samples per pixel (path
    /// tracing).
    #[arg(long, default_value_t = 256, value_parser = clap::value_parser!(u32).range(1..=65536))]
    max_samples: u32,
    /// Reference image (EXR keeps it linear) instead of rendering one.
    #[arg(long)]
    reference: Option<PathBuf>,
    /// Shadow rays per area light (jittered, rounded up to a square), or paths per pixel (Sobol),
    /// for the rendered reference.
    #[arg(long, default_value_t = 4096, value_parser = clap::value_parser!(u32).range(1..=65536))]
    reference_samples: u32,
    /// Target MSE for the equal-error times (default: what random reaches at 256 samples, or at
    /// its largest count if that is fewer).
    #[arg(long, value_parser = values::positive_f64)]
    target_mse: Option<f64>,
    /// Samplers to run, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "random,jittered,sobol")]
    samplers: Vec<Method>,
    /// Seed of the runs.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Override the image width (keeps the aspect ratio unless --height is also given).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    width: Option<u32>,
    /// Override the image height.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    height: Option<u32>,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = values::thread_count())]
    threads: Option<u64>,
    /// A fast smoke run: at most 16 samples, a 256-sample reference, 48 pixels wide.
    #[arg(long)]
    quick: bool,
    /// Instead of the sampler study: time the scene plain, with --adaptive-lights, with
    /// --adc-bailout and with both (its own samplers, --spp per pixel), and give each one's
    /// mean FLIP against the plain render.
    #[arg(long)]
    skip_work: bool,
    /// Instead of the sampler study: uniform against adaptive sampling at equal error. Uniform
    /// runs at 1, 2, 4, … up to --max-samples pixel samples, adaptive runs (--adaptive, at most
    /// --max-samples) at each of --thresholds; the reference is --reference-samples uniform pixel
    /// samples. Sobol pixel samples in every run.
    #[arg(long, conflicts_with = "skip_work")]
    adaptive: bool,
    /// Noise thresholds of the --adaptive study's adaptive runs, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "0.04,0.02,0.01,0.005",
        requires = "adaptive",
        value_parser = values::positive_f32
    )]
    thresholds: Vec<f32>,
    /// Pixel samples in each of the --adaptive study's 8 renders that measure each pixel's
    /// noise for the best allocation (default and most: --max-samples, the noise at the errors
    /// the study compares at; a path-traced scene's rare bright paths show only in long renders).
    #[arg(
        long,
        requires = "adaptive",
        value_parser = clap::value_parser!(u32).range(1..=65536)
    )]
    variance_samples: Option<u32>,
    /// Samples per pixel for --skip-work.
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u32).range(1..=65536))]
    spp: u32,
    /// Cut-off for --skip-work's adc-bailout runs (between 0 and 1).
    #[arg(long, default_value_t = DEFAULT_CUTOFF, value_parser = values::unit_interval_f32)]
    adc_bailout: f32,
    /// Treat every warning about the scene as an error: print them all and write nothing.
    #[arg(long)]
    strict: bool,
    /// Integrator: whitted or path. Default: the scene's rendermode.
    #[arg(long)]
    integrator: Option<raytracer::integrator::IntegratorKind>,
}

/// Parses the subcommand's command line without running it.
pub(super) fn try_parse(args: &[std::ffi::OsString]) -> Result<(), clap::Error> {
    <StudyCli as Parser>::try_parse_from(args).map(drop)
}

/// Runs `raytracer study` (`args` start with the subcommand's name) and returns its exit status.
pub fn main(args: &[std::ffi::OsString]) -> ExitCode {
    let cli = match exit_code::parse::<StudyCli>(args) {
        Ok(c) => c,
        Err(code) => return code,
    };
    let pool = match values::thread_pool(cli.threads) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(exit_code::BAD_INPUT);
        }
    };
    let interrupt = Interrupt::install("no results written");
    let result = pool.install(|| {
        if cli.skip_work {
            skip_work_study(&cli)
        } else if cli.adaptive {
            adaptive_study(&cli, &interrupt)
        } else {
            sampler_study(&cli, &interrupt)
        }
    });
    match result {
        Ok(()) => ExitCode::from(exit_code::OK),
        Err(msg) => {
            eprintln!("error: {msg}");
            ExitCode::from(exit_code::BAD_INPUT)
        }
    }
}

/// Loads the scene (48 pixels wide with `--quick`) and shows its warnings (errors with
/// `--strict`).
fn load_scene(cli: &StudyCli) -> Result<raytracer::scene::Scene, String> {
    let options = LoadOptions {
        width: cli.width.or(if cli.quick { Some(48) } else { None }),
        height: cli.height,
        ..LoadOptions::default()
    };
    let scene = load(&cli.scene, &options).map_err(|e| e.to_string())?;
    if cli.strict {
        crate::strict(&scene)?;
    } else {
        for w in &scene.warnings {
            eprintln!("warning: {w}");
        }
    }
    Ok(scene)
}

/// What both studies start from: the scene, its integrator, the reference, and the outputs
/// claimed (so that an unwritable folder is reported before any run).
struct Setup {
    scene: raytracer::scene::Scene,
    integrator: raytracer::integrator::IntegratorKind,
    reference: raytracer::film::Film,
    outputs: StudyOutputs,
    /// The further outputs asked of [`setup`], in the output folder, created.
    extra: Vec<(PathBuf, PendingFile)>,
}

/// A study's CSV and plot, created and waiting for their bytes.
struct StudyOutputs {
    csv: PathBuf,
    plot: PathBuf,
    csv_out: PendingFile,
    plot_out: PendingFile,
}

impl StudyOutputs {
    /// Writes the CSV and the plot.
    fn write(self, interrupt: &Interrupt, csv: &[u8], png: &[u8]) -> Result<(), String> {
        interrupt
            .commit(self.csv_out, csv)
            .map_err(|e| e.to_string())?;
        interrupt
            .commit(self.plot_out, png)
            .map_err(|e| e.to_string())?;
        eprintln!(
            "study: wrote {} and {}",
            shown(&self.csv),
            shown(&self.plot)
        );
        Ok(())
    }
}

/// Loads the scene, claims the outputs (the CSV, the plot and `extra`, file names in the output
/// folder), and reads the reference or renders it with `render_reference(scene, integrator,
/// samples)` (`what` names its samples in the log).
fn setup(
    cli: &StudyCli,
    interrupt: &Interrupt,
    extra: &[&str],
    what: fn(raytracer::integrator::IntegratorKind) -> &'static str,
    render_reference: impl FnOnce(
        &raytracer::scene::Scene,
        raytracer::integrator::IntegratorKind,
        u32,
    ) -> Result<raytracer::film::Film, raytracer::render::RenderError>,
) -> Result<Setup, String> {
    let scene = load_scene(cli)?;
    let integrator = raytracer::integrator::IntegratorKind::chosen(cli.integrator, &scene);
    let (w, h) = (scene.camera.width, scene.camera.height);
    if let Some(r) = cli.region {
        if !r.fits(w, h) {
            return Err(format!(
                "the region {},{},{},{} does not fit the {w}×{h} image",
                r.x, r.y, r.width, r.height
            ));
        }
    }
    let claimed = claim_outputs(cli, &scene, interrupt, extra)?;
    let reference = match (&cli.reference, claimed.reference) {
        (Some(path), _) => read_reference(path, w, h)?,
        (None, pending) => {
            let n = if cli.quick {
                cli.reference_samples.min(256)
            } else {
                cli.reference_samples
            };
            eprintln!("study: reference, {n} {}, {w}×{h} …", what(integrator));
            let t = Instant::now();
            let f = render_reference(&scene, integrator, n).map_err(|e| e.to_string())?;
            eprintln!("study: reference took {:.2} s", t.elapsed().as_secs_f64());
            if let Some((path, pending)) = pending {
                let bytes =
                    encode_image(&path, &f, ToneMap::Linear, 1.0).map_err(|e| e.to_string())?;
                interrupt
                    .commit(pending, &bytes)
                    .map_err(|e| e.to_string())?;
            }
            f
        }
    };
    Ok(Setup {
        scene,
        integrator,
        reference,
        outputs: claimed.outputs,
        extra: claimed.extra,
    })
}

/// A study's outputs, claimed and created: the CSV and the plot, the further files asked for, and
/// the reference's EXR when the reference is rendered.
struct Claimed {
    outputs: StudyOutputs,
    extra: Vec<(PathBuf, PendingFile)>,
    reference: Option<(PathBuf, PendingFile)>,
}

/// Creates the output folder and claims every output against every input (the scene, its
/// assets, the reference) and the others; each is created now, so that an unwritable folder is
/// reported before the runs.
fn claim_outputs(
    cli: &StudyCli,
    scene: &raytracer::scene::Scene,
    interrupt: &Interrupt,
    extra: &[&str],
) -> Result<Claimed, String> {
    std::fs::create_dir_all(&cli.out)
        .map_err(|e| format!("cannot create {}: {e}", shown(&cli.out)))?;
    let csv = cli.csv.clone().unwrap_or(cli.out.join("study.csv"));
    let plot = cli.plot.clone().unwrap_or(cli.out.join("study.png"));
    let reference_out = cli.out.join("reference.exr");
    let mut guard = Outputs::from_inputs(scene.inputs.iter().map(PathBuf::as_path));
    if let Some(r) = &cli.reference {
        guard.input(r);
    }
    let mut claim = |path: &Path| -> Result<PendingFile, String> {
        guard.claim(path).map_err(|e| e.to_string())?;
        interrupt.create(path).map_err(|e| e.to_string())
    };
    let csv_out = claim(&csv)?;
    let plot_out = claim(&plot)?;
    let extra = extra
        .iter()
        .map(|name| {
            let path = cli.out.join(name);
            claim(&path).map(|pending| (path, pending))
        })
        .collect::<Result<Vec<_>, String>>()?;
    let reference = match cli.reference {
        Some(_) => None,
        None => Some((reference_out.clone(), claim(&reference_out)?)),
    };
    Ok(Claimed {
        outputs: StudyOutputs {
            csv,
            plot,
            csv_out,
            plot_out,
        },
        extra,
        reference,
    })
}

/// Reads the `--reference` image at `path`: finite everywhere, and `w×h` as the scene renders.
fn read_reference(path: &Path, w: u32, h: u32) -> Result<raytracer::film::Film, String> {
    let f = read_image(path).map_err(|e| e.to_string())?;
    if let Some(i) = f.pixels.iter().position(|p| !p.is_finite()) {
        return Err(format!(
            "the reference {} has a non-finite value (NaN or infinity) at pixel ({}, {})",
            shown(path),
            i as u32 % f.width,
            i as u32 / f.width
        ));
    }
    if (f.width, f.height) != (w, h) {
        return Err(format!(
            "the reference {} is {}×{}, the scene renders {w}×{h}",
            shown(path),
            f.width,
            f.height
        ));
    }
    Ok(f)
}

/// The scene's file name and the region's description, for titles.
fn described(cli: &StudyCli) -> (String, String) {
    let name = cli
        .scene
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let what = match cli.region {
        Some(r) => format!("region {},{},{},{}", r.x, r.y, r.width, r.height),
        None => "whole image".into(),
    };
    (name, what)
}

/// The sampler study: writes the CSV and the plot, and prints the slopes and the times to the
/// target MSE.
fn sampler_study(cli: &StudyCli, interrupt: &Interrupt) -> Result<(), String> {
    let Setup {
        scene,
        integrator,
        reference,
        outputs,
        extra: _,
    } = setup(cli, interrupt, &[], runs::counted, runs::reference)?;
    let counted = runs::counted(integrator);
    let (w, h) = (scene.camera.width, scene.camera.height);
    let options = StudyOptions {
        samplers: cli.samplers.clone(),
        max_samples: if cli.quick {
            cli.max_samples.min(16)
        } else {
            cli.max_samples
        },
        integrator,
        runs: cli.runs as usize,
        region: cli.region,
        seed: cli.seed,
    };
    let runs = runs::run_study(&scene, &reference, &options, |i, n, r| {
        eprintln!(
            "study: [{i}/{n}] {:<8} {:>5} {counted}  {:.4} s  MSE {:.3e}  region {:.3e}  FLIP {:.4}",
            r.sampler.to_string(),
            r.samples,
            r.seconds,
            r.mse,
            r.mse_region,
            r.flip
        );
    })
    .map_err(|e| e.to_string())?;
    if let Some(r) = runs
        .iter()
        .find(|r| !(r.mse.is_finite() && r.mse_region.is_finite() && r.flip.is_finite()))
    {
        return Err(format!(
            "the {} run with {} {counted} has a non-finite error (MSE {}, FLIP {}): no results written",
            r.sampler, r.samples, r.mse, r.flip
        ));
    }
    let (name, what) = described(cli);
    let png = plot::plot_png(&runs, &format!("{name}: {what}, {w}×{h}"), counted)?;
    outputs.write(interrupt, runs::csv_text(&runs).as_bytes(), &png)?;

    outln!(
        "MSE over the {what}; slopes fitted over runs with ≥ {} {counted}",
        runs::FIT_MIN_SAMPLES
    );
    outln!("{:<10} {:>8}", "sampler", "slope");
    for &m in &options.samplers {
        match runs::mse_slope(&runs, m) {
            Some(s) => outln!("{:<10} {s:>8.3}", m.to_string()),
            None => outln!("{:<10} {:>8}", m.to_string(), "-"),
        }
    }
    print_times_to_target(cli, &runs, &options.samplers);
    Ok(())
}

/// Prints the time each sampler needs to reach the target MSE (`--target-mse`, else what random
/// reaches at 256 samples), and its ratio to random's.
fn print_times_to_target(cli: &StudyCli, runs: &[runs::Run], samplers: &[Method]) {
    let target = cli.target_mse.or_else(|| {
        let rs = runs::runs_of(runs, Method::Random);
        let at = rs.iter().rev().find(|r| r.samples <= 256)?;
        Some(at.mse_region)
    });
    match target {
        None => outln!("no target MSE: give --target-mse or include random"),
        Some(target) => {
            outln!("time to reach MSE {target:.3e}:");
            let base = runs::time_to_reach(runs, Method::Random, target);
            for &m in samplers {
                match runs::time_to_reach(runs, m, target) {
                    Some(t) => {
                        let ratio = base
                            .map(|b| format!("  ({:.3}× random)", t / b))
                            .unwrap_or_default();
                        outln!("{:<10} {t:>10.4} s{ratio}", m.to_string());
                    }
                    None => outln!("{:<10} {:>10}", m.to_string(), "not reached"),
                }
            }
        }
    }
}

/// The largest pixel-sample count of a `--quick` adaptive study: past the first decision (16
/// samples), so that some pixels can stop.
const QUICK_ADAPTIVE_CAP: u32 = 64;

/// The adaptive study's picture of where the best allocation puts its samples, in the output
/// folder.
const ALLOCATION_MAP: &str = "allocation.png";

/// `--adaptive`: adaptive against uniform sampling at equal error; writes the CSV, the plot and
/// the allocation map, and prints the runs and the bounds.
fn adaptive_study(cli: &StudyCli, interrupt: &Interrupt) -> Result<(), String> {
    let Setup {
        scene,
        integrator,
        reference,
        outputs,
        extra,
    } = setup(
        cli,
        interrupt,
        &[ALLOCATION_MAP],
        |_| "samples per pixel",
        adaptive::reference,
    )?;
    let max_samples = if cli.quick {
        cli.max_samples.min(QUICK_ADAPTIVE_CAP)
    } else {
        cli.max_samples
    };
    let options = adaptive::AdaptiveStudyOptions {
        max_samples,
        thresholds: cli.thresholds.clone(),
        integrator,
        runs: cli.runs as usize,
        region: cli.region,
        seed: cli.seed,
        variance_samples: cli.variance_samples.unwrap_or(max_samples).min(max_samples),
    };
    let result = adaptive::run_adaptive_study(&scene, &reference, &options, |i, n, line| {
        eprintln!("study: [{i}/{n}] {line}");
    })
    .map_err(|e| e.to_string())?;
    let mut errors = result
        .uniform
        .iter()
        .map(|r| (r.mse_region, r.flip))
        .chain(result.adaptive.iter().map(|r| (r.mse_region, r.flip)));
    if errors.any(|(e, f)| !(e.is_finite() && f.is_finite())) {
        return Err("a run has a non-finite error: no results written".into());
    }
    let (name, what) = described(cli);
    let (w, h) = (scene.camera.width, scene.camera.height);
    let png = adaptive::plot_png(
        &result,
        &format!(
            "{name}: {what}, {w}×{h}, at most {} spp",
            options.max_samples
        ),
    )?;
    outputs.write(interrupt, adaptive::csv_text(&result).as_bytes(), &png)?;
    write_allocation_map(interrupt, &result, extra)?;
    print_adaptive_runs(&result, &what);
    print_allocation_bounds(&result);
    Ok(())
}

/// Writes the study's allocation map into the file [`setup`] created for it. A region without
/// noise has no allocation: its pending file is dropped, unwritten.
fn write_allocation_map(
    interrupt: &Interrupt,
    result: &adaptive::AdaptiveStudy,
    mut extra: Vec<(PathBuf, PendingFile)>,
) -> Result<(), String> {
    if let (Some(map), Some((path, pending))) = (&result.allocation_map, extra.pop()) {
        let bytes = encode_image(&path, map, ToneMap::Linear, 1.0).map_err(|e| e.to_string())?;
        interrupt
            .commit(pending, &bytes)
            .map_err(|e| e.to_string())?;
        eprintln!("study: wrote {}", shown(&path));
    }
    Ok(())
}

/// Prints the adaptive study's runs: each uniform run, and each adaptive run with its ratios to
/// uniform sampling at equal MSE over `what`.
fn print_adaptive_runs(result: &adaptive::AdaptiveStudy, what: &str) {
    outln!("MSE over the {what}; uniform and adaptive both with Sobol pixel samples");
    outln!(
        "{:<18} {:>9} {:>10} {:>11} {:>14} {:>7} {:>11} {:>7} {:>7}",
        "render",
        "spp",
        "seconds",
        "MSE",
        "uniform s",
        "ratio",
        "uniform spp",
        "ratio",
        "known"
    );
    for r in &result.uniform {
        outln!(
            "{:<18} {:>9} {:>10.4} {:>11.3e}",
            "uniform",
            r.samples,
            r.seconds,
            r.mse_region
        );
    }
    for r in &result.adaptive {
        outln!(
            "{:<18} {:>9.1} {:>10.4} {:>11.3e} {:>14} {:>7} {:>11} {:>7} {:>7}",
            format!("adaptive T={}", r.threshold),
            r.mean_samples,
            r.seconds,
            r.mse_region,
            r.uniform_seconds
                .map_or("out of range".into(), |u| format!("{u:.4}")),
            adaptive::ratio_text(r.ratio()),
            r.uniform_samples.map_or("-".into(), |u| format!("{u:.1}")),
            adaptive::ratio_text(r.samples_ratio()),
            adaptive::ratio_text(r.known_noise_ratio)
        );
    }
}

/// Prints the best allocation's share of uniform sampling's samples, at one-over-n convergence
/// and at the uniform runs' own.
fn print_allocation_bounds(result: &adaptive::AdaptiveStudy) {
    if let Some(b) = result.bound {
        outln!(
            "best allocation: {b:.2}× uniform's samples at equal MSE (each pixel's samples in \
             proportion to its noise, measured by {} renders of {} spp)",
            adaptive::VARIANCE_RENDERS,
            result.variance_samples
        );
    }
    if let Some((a, b)) = result.bound_at_rate {
        outln!(
            "best allocation at the uniform runs' convergence, MSE ∝ n^-{a:.2} from {} spp up: \
             {b:.2}× uniform's samples",
            adaptive::FIT_FROM_SAMPLES
        );
        outln!(
            "known: the samples ratio the same stopping rule would reach with an exact error \
             estimate (each pixel's noise as measured, converging at that rate)"
        );
    }
}

/// `--skip-work`: times the scene plain and with each work-skipping switch, and prints each one's
/// speed-up and error against the plain render.
fn skip_work_study(cli: &StudyCli) -> Result<(), String> {
    let scene = load_scene(cli)?;
    let base = RenderOptions {
        spp: cli.spp,
        seed: cli.seed,
        ..RenderOptions::default()
    };
    eprintln!(
        "study: {} at {}×{}, {} spp, {} run(s) each …",
        shown(&cli.scene),
        scene.camera.width,
        scene.camera.height,
        cli.spp,
        cli.runs
    );
    let rows = runs::skip_work(&scene, &base, cli.adc_bailout, cli.runs as usize)
        .map_err(|e| e.to_string())?;
    if let Some(r) = rows
        .iter()
        .find(|r| !(r.flip.is_finite() && r.mse.is_finite()))
    {
        return Err(format!(
            "the {} variant has a non-finite error (MSE {}, FLIP {})",
            r.name, r.mse, r.flip
        ));
    }
    let plain = rows[0].seconds;
    outln!(
        "{:<16} {:>9} {:>8} {:>12} {:>10} {:>11}",
        "variant",
        "seconds",
        "speed-up",
        "rays",
        "FLIP",
        "MSE"
    );
    for r in &rows {
        outln!(
            "{:<16} {:>9.4} {:>7.2}× {:>12} {:>10.5} {:>11.3e}",
            r.name,
            r.seconds,
            plain / r.seconds.max(1e-12),
            r.rays,
            r.flip,
            r.mse
        );
    }
    Ok(())
}
