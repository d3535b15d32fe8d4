//! `raytracer batch SCENES... --out DIR`: many scenes in one process, each image written as
//! `raytracer SCENE OUT` writes it, with a summary, optional comparison against reference
//! images and an HTML report (`crate::batch`, `docs/batch.md`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use clap::Parser;

mod discover;
mod report;
mod run;
mod summary;

use raytracer::files::output::{OutputError, Outputs, PendingFile};
use raytracer::files::shown;
use run::{ImagePlan, Row, RunOptions, Status};
use summary::{SummaryFormat, Totals};

use raytracer::image_io::OutputFormat;
use raytracer::scene::LoadOptions;

use crate::exit_code::{self, Failure};
use crate::image_flags::ImageFlags;
use crate::interrupt::Interrupt;
use crate::values;

/// Image formats for `--format`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum Format {
    Png,
    Ppm,
    Exr,
}

impl From<Format> for OutputFormat {
    fn from(f: Format) -> OutputFormat {
        match f {
            Format::Png => OutputFormat::Png,
            Format::Ppm => OutputFormat::Ppm,
            Format::Exr => OutputFormat::Exr,
        }
    }
}

#[derive(Parser, Debug)]
#[command(
    name = "raytracer batch",
    bin_name = "raytracer batch",
    about = "Renders many scenes in one process: scene files, and folders of them (their .json files, recursively, sorted).",
    after_help = "Outputs: DIR/<name>.<format>, where <name> is the scene file's stem; where two scenes share a stem, the fewest parent folders that tell them apart are put in front, each followed by '__' (alice/scene.json, bob/scene.json -> alice__scene.png, bob__scene.png); a name still taken gets -2, -3, ... Every image is the one `raytracer SCENE OUT` writes with the same options, on any thread count.\n\
                  Summary columns: scene, output, status (ok, failed, over-threshold), error, width, height, spp, seconds, rays, warnings; with --reference also reference, mse, flip, pass.\n\
                  References: DIR2/<name>.png, else .ppm, .exr, .jpg, .jpeg, else the same for the scene's stem (alice__task1 falls back to task1.png); a missing reference or a size mismatch fails the scene.\n\
                  Exit codes: 0 every scene rendered (and passed); 1 a scene failed or is over --max-flip, or the summary or report could not be written; 2 usage error; 130 interrupted (images finished so far are kept, no summary or report written, no partial files).\n\
                  See docs/batch.md."
)]
struct BatchCli {
    /// Scene files (.json) and folders of them.
    #[arg(required = true, value_name = "SCENES")]
    scenes: Vec<PathBuf>,
    /// The folder the images go into (created if missing).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Image format of the outputs.
    #[arg(long, value_enum, default_value = "png")]
    format: Format,
    /// The summary: .csv or .json, one row per scene [default: DIR/summary.csv].
    #[arg(long, value_name = "FILE")]
    summary: Option<PathBuf>,
    /// Compare each render with the reference image of the same name in this folder (MSE and
    /// mean FLIP, as `raytracer compare`).
    #[arg(long, value_name = "DIR2")]
    reference: Option<PathBuf>,
    /// A scene whose mean FLIP against its reference is above X fails (exit 1).
    #[arg(long, value_name = "X", requires = "reference", value_parser = values::non_negative_f64)]
    max_flip: Option<f64>,
    /// Write an HTML report (self-contained: images inline) [default: DIR/report.html with
    /// --reference].
    #[arg(long, value_name = "FILE.html")]
    report: Option<PathBuf>,
    #[command(flatten)]
    image: ImageFlags,
    /// Worker threads shared by all scenes (default: all cores).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=4096))]
    threads: Option<u64>,
    /// Override every image's width (keeps each scene's aspect ratio unless --height is also
    /// given).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    width: Option<u32>,
    /// Override every image's height.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    height: Option<u32>,
    /// Extra folder to resolve texture and mesh paths against (repeatable).
    #[arg(long = "asset-dir")]
    asset_dirs: Vec<PathBuf>,
    /// No line per scene, no warnings, no totals (errors are still printed).
    #[arg(short, long)]
    quiet: bool,
}

impl BatchCli {
    /// The shared options in words, for the report.
    fn settings(&self) -> String {
        let mut parts = vec![
            match self.image.spp {
                Some(spp) => format!("{spp} spp"),
                None => "each scene's spp".to_string(),
            },
            format!("seed {}", self.image.seed),
            match self.image.tonemap {
                Some(map) => format!("tone map {}", map.name()),
                None => "each scene's tone map (linear unless it asks for one)".to_string(),
            },
        ];
        if self.image.exposure != 1.0 {
            parts.push(format!("exposure ×{}", self.image.exposure));
        }
        match (self.width, self.height) {
            (Some(w), Some(h)) => parts.push(format!("{w}×{h}")),
            (Some(w), None) => parts.push(format!("width {w}")),
            (None, Some(h)) => parts.push(format!("height {h}")),
            (None, None) => {}
        }
        parts.join(", ")
    }
}

/// What an interrupted batch did not write.
const NOT_WRITTEN: &str = "the images finished so far are kept; no summary or report written";

pub fn main(args: &[std::ffi::OsString]) -> ExitCode {
    let cli = match exit_code::parse::<BatchCli>(args) {
        Ok(c) => c,
        Err(code) => return code,
    };
    let interrupt = Interrupt::install(NOT_WRITTEN);
    match run(&cli, &interrupt) {
        Ok(totals) if totals.ok == totals.scenes => ExitCode::from(exit_code::OK),
        Ok(_) => ExitCode::from(exit_code::BAD_INPUT),
        Err(failure) => failure.report(),
    }
}

/// Parses a batch command line without running it.
pub(super) fn try_parse(args: &[std::ffi::OsString]) -> Result<(), clap::Error> {
    <BatchCli as Parser>::try_parse_from(args).map(drop)
}

/// [`run::Writer`] through the interrupt handler, one file at a time: the handler's record of
/// temporary files is kept for one command writing one file at a time.
struct Serial<'a> {
    interrupt: &'a Interrupt,
    lock: Mutex<()>,
}

impl run::Writer for Serial<'_> {
    fn create(&self, path: &Path) -> Result<PendingFile, OutputError> {
        let _one = self.lock.lock().unwrap_or_else(|e| e.into_inner());
        self.interrupt.create(path)
    }
    fn commit(&self, pending: PendingFile, bytes: &[u8]) -> Result<(), OutputError> {
        let _one = self.lock.lock().unwrap_or_else(|e| e.into_inner());
        self.interrupt.commit(pending, bytes)
    }
}

fn has_extension(path: &Path, extensions: &[&str]) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| extensions.iter().any(|x| e.eq_ignore_ascii_case(x)))
}

fn run(cli: &BatchCli, interrupt: &Interrupt) -> Result<Totals, Failure> {
    let summary_path = cli
        .summary
        .clone()
        .unwrap_or_else(|| cli.out.join("summary.csv"));
    let summary_format = SummaryFormat::from_path(&summary_path).ok_or_else(|| {
        Failure::Usage(format!(
            "cannot tell the summary format of '{}': use .csv or .json",
            shown(&summary_path)
        ))
    })?;
    let report_path = cli
        .report
        .clone()
        .or_else(|| cli.reference.as_ref().map(|_| cli.out.join("report.html")));
    if let Some(path) = &report_path {
        if !has_extension(path, &["html", "htm"]) {
            return Err(Failure::Usage(format!(
                "the report '{}' must be an .html file",
                shown(path)
            )));
        }
    }
    if let Some(dir) = &cli.reference {
        if !dir.is_dir() {
            return Err(Failure::Usage(format!(
                "the reference folder '{}' does not exist or is not a folder",
                shown(dir)
            )));
        }
    }
    std::fs::create_dir_all(&cli.out).map_err(|e| {
        Failure::Input(format!(
            "cannot create the output folder '{}': {e}",
            shown(&cli.out)
        ))
    })?;
    if let Some(dir) = &cli.reference {
        if dir.canonicalize().ok() == cli.out.canonicalize().ok() {
            return Err(Failure::Usage(format!(
                "the output folder '{}' is the reference folder: the renders would replace the references",
                shown(&cli.out)
            )));
        }
    }
    // Not the output folder (its summary.json, from an earlier run). A summary given inside a
    // scene folder stays a scene, and writing over it is refused below.
    let sources = discover::collect_scenes(&cli.scenes, std::slice::from_ref(&cli.out));
    if sources.is_empty() {
        return Err(Failure::Usage(
            "no scene files: the folders given hold no .json files".into(),
        ));
    }
    let format = OutputFormat::from(cli.format);
    let jobs = run::plan(&sources, &cli.out, format, cli.reference.as_deref());

    // The summary and the report: never a scene or a reference; their folders are checked now.
    let mut guard = Outputs::from_inputs(jobs.iter().map(|j| j.scene.as_path()));
    for job in &jobs {
        if let Some(Ok(reference)) = &job.reference {
            guard.input(reference);
        }
    }
    guard.claim(&summary_path)?;
    let summary_pending = interrupt.create(&summary_path)?;
    let report_pending = match &report_path {
        Some(path) => {
            guard.claim(path)?;
            Some(interrupt.create(path)?)
        }
        None => None,
    };

    let flags = &cli.image;
    let plan = |scene: &raytracer::scene::Scene| ImagePlan {
        render: flags.render_options(scene),
        tonemap: flags.tone_map(scene),
        exposure: flags.display_exposure(scene),
    };
    let options = RunOptions {
        load: LoadOptions {
            width: cli.width,
            height: cli.height,
            asset_dirs: cli.asset_dirs.clone(),
            max_memory: raytracer::memory::available(),
            ..LoadOptions::default()
        },
        plan: &plan,
        max_flip: cli.max_flip,
        keep_images: report_path.is_some(),
        cancel: interrupt.flag(),
    };
    let writer = Serial {
        interrupt,
        lock: Mutex::new(()),
    };
    let finished = AtomicUsize::new(0);
    let total = jobs.len();
    let done = |row: &Row| {
        let k = finished.fetch_add(1, Ordering::Relaxed) + 1;
        if interrupt.is_set() {
            return;
        }
        if !cli.quiet {
            for w in &row.warnings {
                eprintln!("warning: {w}");
            }
        }
        if row.status != Status::Ok {
            if let Some(line) = row.error_line() {
                eprintln!("error: {line}");
            }
        } else if !cli.quiet {
            eprintln!("[{k}/{total}] {}", describe(row));
        }
    };
    let pool = values::thread_pool(cli.threads).map_err(Failure::Input)?;
    let rows = pool.install(|| run::run(&jobs, &options, &writer, &done));
    if interrupt.is_set() {
        return Err(Failure::Interrupted(NOT_WRITTEN));
    }

    let summary = summary_format.write(&rows, cli.reference.is_some());
    interrupt.commit(summary_pending, summary.as_bytes())?;
    if let (Some(pending), Some(_)) = (report_pending, &report_path) {
        let info = report::ReportInfo {
            reference_dir: cli.reference.clone(),
            max_flip: cli.max_flip,
            settings: cli.settings(),
        };
        let page = report::html(&rows, &info);
        interrupt.commit(pending, page.as_bytes())?;
    }
    let totals = Totals::of(&rows);
    if !cli.quiet {
        let mut line = format!(
            "{} scene{}: {} ok, {} failed",
            totals.scenes,
            if totals.scenes == 1 { "" } else { "s" },
            totals.ok,
            totals.failed
        );
        if cli.max_flip.is_some() {
            line.push_str(&format!(", {} over --max-flip", totals.over_threshold));
        }
        line.push_str(&format!("; summary {}", shown(&summary_path)));
        if let Some(path) = &report_path {
            line.push_str(&format!(", report {}", shown(path)));
        }
        eprintln!("{line}");
    }
    Ok(totals)
}

/// A finished scene in a line: where its image went, its size, samples, time and rays, and its
/// comparison.
fn describe(row: &Row) -> String {
    let mut line = format!("{}", shown(&row.scene));
    if let Some(out) = &row.output {
        line.push_str(&format!(" → {}", shown(out)));
    }
    if let (Some(w), Some(h), Some(spp)) = (row.width, row.height, row.spp) {
        line.push_str(&format!(": {w}×{h}, {spp} spp"));
    }
    if let Some(s) = row.seconds {
        line.push_str(&format!(", {s:.3} s"));
    }
    if let Some(rays) = row.rays {
        line.push_str(&format!(", {rays} rays"));
    }
    if let Some(c) = &row.comparison {
        if let (Some(m), Some(f)) = (c.mse, c.flip) {
            line.push_str(&format!(", mse {m:.3e}, flip {f:.4}"));
        }
    }
    line
}
