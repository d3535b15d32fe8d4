//! Rendering many scenes in one process (`raytracer batch`): each scene loaded, rendered, written
//! atomically and, with a reference folder, compared with its reference image (MSE, mean FLIP);
//! one [`SceneRow`] per scene, whatever failed. Scenes run in parallel on the caller's rayon
//! pool, each render also spreading its tiles over it; an image's bytes do not depend on that.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, OnceLock};
use std::time::Instant;

use raytracer::files::output::{OutputError, Outputs, PendingFile};
use raytracer::files::shown;
use raytracer::film::{Film, ToneMap};
use raytracer::image_io::{encode_image, read_image, OutputFormat};
use raytracer::metric::{flip_map, heat_map, mse, Region};
use raytracer::render::{render, RenderOptions};
use raytracer::scene::{load, LoadOptions, Scene};

use super::discover::{find_reference, output_names, Source};

/// The file extension of an output format.
pub fn extension(format: OutputFormat) -> &'static str {
    match format {
        OutputFormat::Png => "png",
        OutputFormat::Ppm => "ppm",
        OutputFormat::Exr => "exr",
    }
}

/// One scene of a batch, with where its image goes and what it is compared with.
#[derive(Debug, Clone)]
pub struct Job {
    pub scene: PathBuf,
    /// Why it cannot be run at all (a folder that could not be listed, an output that may not
    /// be written).
    pub error: Option<String>,
    /// The output name ([`output_names`]).
    pub name: String,
    pub output: PathBuf,
    /// With a reference folder: the reference image, or why there is none.
    pub reference: Option<Result<PathBuf, String>>,
}

/// The jobs for `sources`: outputs `out_dir/<name>.<format>`, references looked up in
/// `reference_dir`. Every output is claimed against every scene file, every reference and the
/// other outputs ([`Outputs`]); one that may not be written fails its job.
pub fn plan(
    sources: &[Source],
    out_dir: &Path,
    format: OutputFormat,
    reference_dir: Option<&Path>,
) -> Vec<Job> {
    let paths: Vec<&Path> = sources.iter().map(|s| s.path.as_path()).collect();
    let names = output_names(&paths);
    let mut jobs: Vec<Job> = sources
        .iter()
        .zip(names)
        .map(|(source, name)| Job {
            scene: source.path.clone(),
            error: source.error.clone(),
            output: out_dir.join(format!("{name}.{}", extension(format))),
            reference: reference_dir.map(|dir| find_reference(dir, &name, &source.path)),
            name,
        })
        .collect();
    let mut guard = Outputs::new();
    for job in &jobs {
        guard.input(&job.scene);
        if let Some(Ok(reference)) = &job.reference {
            guard.input(reference);
        }
    }
    for job in jobs.iter_mut().filter(|j| j.error.is_none()) {
        if let Err(e) = guard.claim(&job.output) {
            job.error = Some(e.to_string());
        }
    }
    jobs
}

/// How finished files are written: created before the work, committed whole (see
/// [`PendingFile`]). The command line's writer also removes them on Ctrl-C.
pub trait Writer: Sync {
    /// Creates the temporary file that becomes `path`.
    fn create(&self, path: &Path) -> Result<PendingFile, OutputError>;
    /// Writes `bytes` and puts the file in place.
    fn commit(&self, pending: PendingFile, bytes: &[u8]) -> Result<(), OutputError>;
}

/// How one scene's image is made: its render options and tone map.
#[derive(Debug, Clone)]
pub struct ImagePlan {
    pub render: RenderOptions,
    pub tonemap: ToneMap,
    pub exposure: f32,
}

/// What every scene of a batch shares.
pub struct RunOptions<'a> {
    pub load: LoadOptions,
    /// The image options for a loaded scene (the command line's flags over the scene's own).
    pub plan: &'a (dyn Fn(&Scene) -> ImagePlan + Sync),
    /// Mean FLIP above this fails a comparison.
    pub max_flip: Option<f64>,
    /// Keep PNG bytes of the render, the reference and the heat map in each row (for the
    /// report).
    pub keep_images: bool,
    /// Stops the batch: renders stop within a sample, scenes not started are skipped.
    pub cancel: Arc<AtomicBool>,
}

/// How a scene ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Status {
    /// Could not be loaded, rendered, written or compared.
    Failed,
    /// Rendered and compared, worse than the threshold.
    OverThreshold,
    /// Rendered (and within the threshold, if compared).
    Ok,
}

impl Status {
    /// The status in the summary's `status` column.
    pub fn name(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Failed => "failed",
            Status::OverThreshold => "over-threshold",
        }
    }
}

/// A scene's comparison with its reference.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Comparison {
    pub reference: Option<PathBuf>,
    pub mse: Option<f64>,
    /// Mean FLIP over the image.
    pub flip: Option<f64>,
    /// Within `--max-flip`; `None` without a threshold. A scene that could not be compared does
    /// not pass.
    pub pass: Option<bool>,
}

/// PNG files for the report.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Images {
    pub render: Option<Vec<u8>>,
    pub reference: Option<Vec<u8>>,
    pub heat: Option<Vec<u8>>,
}

/// The outcome of one scene: a line of the summary, a card of the report.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneRow {
    pub scene: PathBuf,
    pub name: String,
    /// The image written, if one was.
    pub output: Option<PathBuf>,
    pub status: Status,
    /// What failed, naming the file.
    pub error: Option<String>,
    pub width: Option<u32>,
    pub height: Option<u32>,
    pub spp: Option<u32>,
    /// Wall-clock seconds from loading the scene to its image being written (with scenes in
    /// parallel, shared with the others).
    pub seconds: Option<f64>,
    pub rays: Option<u64>,
    /// The loader's warnings about the scene.
    pub warnings: Vec<String>,
    /// With a reference folder.
    pub comparison: Option<Comparison>,
    pub images: Images,
}

impl SceneRow {
    /// The row of `job` before it runs: ok, nothing known yet.
    fn new(job: &Job) -> SceneRow {
        SceneRow {
            scene: job.scene.clone(),
            name: job.name.clone(),
            output: None,
            status: Status::Ok,
            error: None,
            width: None,
            height: None,
            spp: None,
            seconds: None,
            rays: None,
            warnings: Vec::new(),
            comparison: job.reference.as_ref().map(|r| Comparison {
                reference: r.as_ref().ok().cloned(),
                ..Comparison::default()
            }),
            images: Images::default(),
        }
    }

    /// Marks the scene failed with `error`; a comparison it had does not pass.
    fn fail(&mut self, error: String) {
        self.status = Status::Failed;
        self.error = Some(error);
        if let Some(c) = &mut self.comparison {
            c.pass = c.pass.map(|_| false);
        }
    }

    /// The error on one line, naming the scene file (for stderr).
    pub fn error_line(&self) -> Option<String> {
        let error = self.error.as_ref()?;
        let one_line = error.replace("\r\n", "; ").replace(['\n', '\r'], "; ");
        let scene = shown(&self.scene).to_string();
        Some(if one_line.starts_with(&scene) {
            one_line
        } else {
            format!("{scene}: {one_line}")
        })
    }
}

/// Renders every job on the current rayon pool, calling `done` with each row as it is finished
/// (from the worker threads). Returns the rows in job order. A scene's failure is its row's;
/// nothing here fails the batch.
///
/// One lane per worker thread takes the next job whenever it finishes one, so at most that many
/// scenes are in memory at once; each render also splits its tiles over the pool, so when fewer
/// scenes than threads are left (or one scene is large) the idle threads help with its tiles.
pub fn render_all(
    jobs: &[Job],
    options: &RunOptions,
    writer: &dyn Writer,
    done: &(dyn Fn(&SceneRow) + Sync),
) -> Vec<SceneRow> {
    let lanes = rayon::current_num_threads().clamp(1, jobs.len().max(1));
    let next = AtomicUsize::new(0);
    let rows: Vec<OnceLock<SceneRow>> = jobs.iter().map(|_| OnceLock::new()).collect();
    rayon::scope(|s| {
        for _ in 0..lanes {
            s.spawn(|_| {
                let mut i = next.fetch_add(1, Ordering::Relaxed);
                while let (Some(job), Some(slot)) = (jobs.get(i), rows.get(i)) {
                    let row = run_one(job, options, writer);
                    done(&row);
                    let _ = slot.set(row);
                    i = next.fetch_add(1, Ordering::Relaxed);
                }
            });
        }
    });
    rows.into_iter()
        .zip(jobs)
        .map(|(row, job)| {
            row.into_inner().unwrap_or_else(|| {
                let mut row = SceneRow::new(job);
                row.fail("not run".into());
                row
            })
        })
        .collect()
}

/// One job's row: failed at once for a job that cannot run or once the batch is cancelled, else
/// rendered and compared.
fn run_one(job: &Job, options: &RunOptions, writer: &dyn Writer) -> SceneRow {
    let mut row = SceneRow::new(job);
    if options.max_flip.is_some() {
        if let Some(c) = &mut row.comparison {
            c.pass = Some(false);
        }
    }
    if let Some(e) = &job.error {
        row.fail(e.clone());
        return row;
    }
    if options.cancel.load(Ordering::Relaxed) {
        row.fail("interrupted before it started".into());
        return row;
    }
    if let Err(e) = render_and_compare(job, options, writer, &mut row) {
        row.fail(e);
    }
    row
}

/// Loads, renders and writes `job`'s scene and compares the image with its reference, filling
/// `row` as it goes; the first failure's message.
fn render_and_compare(
    job: &Job,
    options: &RunOptions,
    writer: &dyn Writer,
    row: &mut SceneRow,
) -> Result<(), String> {
    let start = Instant::now();
    let scene = load(&job.scene, &options.load).map_err(|e| e.to_string())?;
    row.warnings = scene.warnings.iter().map(|w| w.to_string()).collect();
    // The scene's own files, textures and meshes included, are never overwritten.
    Outputs::from_inputs(scene.inputs.iter().map(PathBuf::as_path))
        .claim(&job.output)
        .map_err(|e| e.to_string())?;
    let pending = writer.create(&job.output).map_err(|e| e.to_string())?;
    let plan = (options.plan)(&scene);
    let render_options = RenderOptions {
        cancel: Some(options.cancel.clone()),
        ..plan.render.clone()
    };
    row.width = Some(scene.camera.width);
    row.height = Some(scene.camera.height);
    row.spp = Some(render_options.spp);
    let out = render(&scene, &render_options).map_err(|e| e.to_string())?;
    if out.cancelled {
        return Err("interrupted".into());
    }
    row.rays = Some(out.counts.total());
    let bytes = encode_image(&job.output, &out.film, plan.tonemap, plan.exposure)
        .map_err(|e| e.to_string())?;
    writer.commit(pending, &bytes).map_err(|e| e.to_string())?;
    row.output = Some(job.output.clone());
    row.seconds = Some(start.elapsed().as_secs_f64());
    if options.keep_images {
        row.images.render = Some(if extension_is(&job.output, "png") {
            bytes
        } else {
            as_png(&out.film, plan.tonemap, plan.exposure)?
        });
    }
    drop(out);
    match &job.reference {
        None => Ok(()),
        Some(Err(e)) => Err(e.clone()),
        Some(Ok(reference)) => compare(job, reference, options, row),
    }
}

/// Whether `path`'s extension is `ext` (without regard to case).
fn extension_is(path: &Path, ext: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

/// A film as PNG bytes.
fn as_png(film: &Film, tonemap: ToneMap, exposure: f32) -> Result<Vec<u8>, String> {
    encode_image(Path::new("image.png"), film, tonemap, exposure).map_err(|e| e.to_string())
}

/// Compares the image written for `job` (read back, as `raytracer compare` reads it) with
/// `reference`.
fn compare(
    job: &Job,
    reference: &Path,
    options: &RunOptions,
    row: &mut SceneRow,
) -> Result<(), String> {
    let test = read_image(&job.output).map_err(|e| e.to_string())?;
    let golden = read_image(reference).map_err(|e| e.to_string())?;
    if options.keep_images {
        row.images.reference = Some(as_png(&golden, ToneMap::Linear, 1.0)?);
    }
    if (golden.width, golden.height) != (test.width, test.height) {
        return Err(format!(
            "the render is {}×{} but the reference '{}' is {}×{}",
            test.width,
            test.height,
            shown(reference),
            golden.width,
            golden.height
        ));
    }
    let map = flip_map(&golden, &test);
    let flip = map.iter().map(|&v| f64::from(v)).sum::<f64>() / map.len().max(1) as f64;
    let comparison = row.comparison.get_or_insert_with(Comparison::default);
    comparison.mse = Some(mse(&golden, &test, Region::full(test.width, test.height)));
    comparison.flip = Some(flip);
    if let Some(max) = options.max_flip {
        // NaN is never within.
        let pass = flip <= max;
        comparison.pass = Some(pass);
        if !pass {
            row.status = Status::OverThreshold;
            row.error = Some(format!("mean FLIP {flip:.6} is above --max-flip {max}"));
        }
    }
    if options.keep_images {
        let heat = heat_map(test.width, test.height, &map);
        row.images.heat = Some(as_png(&heat, ToneMap::Linear, 1.0)?);
    }
    Ok(())
}
