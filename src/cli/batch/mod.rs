//! `raytracer batch SCENES... --out DIR`: many scenes in one process, each image written as
//! `raytracer SCENE OUT` writes it, with a summary, optional comparison against reference
//! images and an HTML report (`docs/batch.md`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use clap::Parser;

mod discover;
mod report;
mod run;
pub(crate) mod summary;

use raytracer::files::output::{OutputError, Outputs, PendingFile};
use raytracer::files::shown;
use run::{ImagePlan, Job, RunOptions, SceneRow, Status};
use summary::{SummaryFormat, Totals};

use raytracer::image_io::OutputFormat;

use crate::exit_code::{self, Failure};
use crate::image_flags::ImageFlags;
use crate::interrupt::Interrupt;
use crate::load_flags::LoadFlags;
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
    #[arg(long, value_parser = values::thread_count())]
    threads: Option<u64>,
    /// How every scene is read: image size, asset folders, and the limits a scene must stay
    /// within (a scene over one fails alone).
    #[command(flatten)]
    load: LoadFlags,
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
        match self.load.size() {
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

/// Runs `raytracer batch` (`args` start with the subcommand's name) and returns its exit status.
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

/// Whether `path` ends in one of `extensions` (without regard to case).
fn has_extension(path: &Path, extensions: &[&str]) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| extensions.iter().any(|x| e.eq_ignore_ascii_case(x)))
}

/// Where the batch's summary and report go, and the summary's format.
struct Destinations {
    summary: PathBuf,
    summary_format: SummaryFormat,
    report: Option<PathBuf>,
}

/// The summary and the report, created and waiting for their bytes.
struct PendingResults {
    summary: PendingFile,
    report: Option<PendingFile>,
}

/// Checks the flags and folders, renders every scene, and writes the summary and the report.
fn run(cli: &BatchCli, interrupt: &Interrupt) -> Result<Totals, Failure> {
    let destinations = destinations(cli)?;
    prepare_folders(cli)?;
    let jobs = plan_jobs(cli)?;
    let pending = create_results(&jobs, &destinations, interrupt)?;
    let rows = render_jobs(cli, &jobs, destinations.report.is_some(), interrupt)?;
    if interrupt.is_set() {
        return Err(Failure::Interrupted(NOT_WRITTEN));
    }
    write_results(cli, &rows, &destinations, pending, interrupt)?;
    let totals = Totals::of(&rows);
    if !cli.quiet {
        eprintln!("{}", totals_line(cli, &totals, &destinations));
    }
    Ok(totals)
}

/// The summary's path and format and the report's path (by default beside the images), checked.
fn destinations(cli: &BatchCli) -> Result<Destinations, Failure> {
    let summary = cli
        .summary
        .clone()
        .unwrap_or_else(|| cli.out.join("summary.csv"));
    let summary_format = SummaryFormat::from_path(&summary).ok_or_else(|| {
        Failure::Usage(format!(
            "cannot tell the summary format of '{}': use .csv or .json",
            shown(&summary)
        ))
    })?;
    let report = cli
        .report
        .clone()
        .or_else(|| cli.reference.as_ref().map(|_| cli.out.join("report.html")));
    if let Some(path) = &report {
        if !has_extension(path, &["html", "htm"]) {
            return Err(Failure::Usage(format!(
                "the report '{}' must be an .html file",
                shown(path)
            )));
        }
    }
    Ok(Destinations {
        summary,
        summary_format,
        report,
    })
}

/// Checks the reference folder, creates the output folder, and refuses the two being one.
fn prepare_folders(cli: &BatchCli) -> Result<(), Failure> {
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
    Ok(())
}

/// The scenes the command line names, with their outputs and references.
fn plan_jobs(cli: &BatchCli) -> Result<Vec<Job>, Failure> {
    // Not the output folder (its summary.json, from an earlier run). A summary given inside a
    // scene folder stays a scene, and writing over it is refused when it is claimed.
    let sources = discover::collect_scenes(&cli.scenes, std::slice::from_ref(&cli.out));
    if sources.is_empty() {
        return Err(Failure::Usage(
            "no scene files: the folders given hold no .json files".into(),
        ));
    }
    let format = OutputFormat::from(cli.format);
    Ok(run::plan(
        &sources,
        &cli.out,
        format,
        cli.reference.as_deref(),
    ))
}

/// Claims and creates the summary and the report before any scene is rendered: never a scene or
/// a reference, and their folders checked now.
fn create_results(
    jobs: &[Job],
    destinations: &Destinations,
    interrupt: &Interrupt,
) -> Result<PendingResults, Failure> {
    let mut guard = Outputs::from_inputs(jobs.iter().map(|j| j.scene.as_path()));
    for job in jobs {
        if let Some(Ok(reference)) = &job.reference {
            guard.input(reference);
        }
    }
    guard.claim(&destinations.summary)?;
    let summary = interrupt.create(&destinations.summary)?;
    let report = match &destinations.report {
        Some(path) => {
            guard.claim(path)?;
            Some(interrupt.create(path)?)
        }
        None => None,
    };
    Ok(PendingResults { summary, report })
}

/// Renders the jobs on the `--threads` pool, showing each scene as it finishes; `keep_images`
/// keeps the PNGs the report shows.
fn render_jobs(
    cli: &BatchCli,
    jobs: &[Job],
    keep_images: bool,
    interrupt: &Interrupt,
) -> Result<Vec<SceneRow>, Failure> {
    let flags = &cli.image;
    let plan = |scene: &raytracer::scene::Scene| ImagePlan {
        render: flags.render_options(scene),
        tonemap: flags.tone_map(scene),
        exposure: flags.display_exposure(scene),
    };
    let options = RunOptions {
        load: cli.load.options(),
        plan: &plan,
        max_flip: cli.max_flip,
        keep_images,
        cancel: interrupt.flag(),
    };
    let writer = Serial {
        interrupt,
        lock: Mutex::new(()),
    };
    let finished = AtomicUsize::new(0);
    let done = |row: &SceneRow| {
        let k = finished.fetch_add(1, Ordering::Relaxed) + 1;
        if !interrupt.is_set() {
            show_row(cli, row, k, jobs.len());
        }
    };
    let pool = values::thread_pool(cli.threads).map_err(Failure::Input)?;
    Ok(pool.install(|| run::render_all(jobs, &options, &writer, &done)))
}

/// Prints a finished scene, the `k`th of `total`: its warnings and error, or its line.
fn show_row(cli: &BatchCli, row: &SceneRow, k: usize, total: usize) {
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
}

/// Writes the summary and, if one is wanted, the report.
fn write_results(
    cli: &BatchCli,
    rows: &[SceneRow],
    destinations: &Destinations,
    pending: PendingResults,
    interrupt: &Interrupt,
) -> Result<(), Failure> {
    let summary = destinations
        .summary_format
        .write(rows, cli.reference.is_some());
    interrupt.commit(pending.summary, summary.as_bytes())?;
    if let (Some(pending), Some(_)) = (pending.report, &destinations.report) {
        let info = report::ReportInfo {
            reference_dir: cli.reference.clone(),
            max_flip: cli.max_flip,
            settings: cli.settings(),
        };
        let page = report::html(rows, &info);
        interrupt.commit(pending, page.as_bytes())?;
    }
    Ok(())
}

/// The batch's last line: scenes by how they ended, and where the summary and report are.
fn totals_line(cli: &BatchCli, totals: &Totals, destinations: &Destinations) -> String {
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
    line.push_str(&format!("; summary {}", shown(&destinations.summary)));
    if let Some(path) = &destinations.report {
        line.push_str(&format!(", report {}", shown(path)));
    }
    line
}

/// A finished scene in a line: where its image went, its size, samples, time and rays, and its
/// comparison.
fn describe(row: &SceneRow) -> String {
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
