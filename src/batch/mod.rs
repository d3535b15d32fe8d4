//! Rendering many scenes in one process (`raytracer batch`): for marking a class's submissions
//! and for CI jobs that compare renders with golden images.
//!
//! - [`collect_scenes`]: the scene files of the command line (files as given; folders'
//!   `.json` files, recursively, sorted).
//! - [`output_names`]: one unique output name per scene (the file stem, with parent folders
//!   prefixed where stems clash).
//! - [`plan`] then [`run`]: each scene loaded, rendered, written atomically and, with a reference
//!   folder, compared with the reference image of the same name (MSE, mean FLIP); one [`Row`]
//!   per scene, whatever failed. Scenes run in parallel on the caller's rayon pool, each render
//!   also spreading its tiles over it; an image's bytes do not depend on that (see
//!   `crate::render`).
//! - [`csv`] and [`json`]: the summary; [`report`]: the HTML page.

pub mod report;

use std::collections::HashSet;
use std::ffi::OsString;
use std::fmt::Write as _;
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, OnceLock};
use std::time::Instant;

use crate::files::output::{OutputError, Outputs, PendingFile};
use crate::files::shown;
use crate::film::{Film, ToneMap};
use crate::image_io::{encode_image, read_image, OutputFormat};
use crate::metric::{flip_map, heat_map, mse, Region};
use crate::render::{render, RenderOptions};
use crate::scene::{load, LoadOptions, Scene};

/// The separator between the parent folders and the stem in an output name (`folder__stem`).
pub const NAME_SEPARATOR: &str = "__";

/// Extensions of reference images, in the order they are looked for.
pub const REFERENCE_EXTENSIONS: [&str; 5] = ["png", "ppm", "exr", "jpg", "jpeg"];

/// One entry of a batch: a scene file, or a folder that could not be read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Source {
    pub path: PathBuf,
    /// Why the entry cannot be rendered at all (a folder that could not be listed).
    pub error: Option<String>,
}

fn is_json(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"))
}

/// Where `path` is, resolved through links: the path itself if it exists, else its folder's
/// resolved path and its name (for an output not written yet).
fn resolved(path: &Path) -> Option<PathBuf> {
    if let Ok(p) = path.canonicalize() {
        return Some(p);
    }
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    Some(folder.canonicalize().ok()?.join(path.file_name()?))
}

/// The scenes `args` name: a file as given (whatever its extension; a missing one fails when it
/// is loaded), a folder as its `.json` files (any case), recursively, sorted by path. Folders
/// and files in `skip` (the output folder, the summary) are not taken from folders; folders
/// reached twice (through links) are listed once. A scene named twice is kept at its first place.
pub fn collect_scenes(args: &[PathBuf], skip: &[PathBuf]) -> Vec<Source> {
    let skip: HashSet<PathBuf> = skip.iter().filter_map(|p| resolved(p)).collect();
    let mut seen = HashSet::new();
    let mut visited = HashSet::new();
    let mut out = Vec::new();
    for arg in args {
        let mut found = Vec::new();
        if arg.is_dir() {
            walk(arg, &skip, &mut visited, &mut found);
            found.sort_by(|a: &Source, b| a.path.cmp(&b.path));
        } else {
            found.push(Source {
                path: arg.clone(),
                error: None,
            });
        }
        for source in found {
            let key = resolved(&source.path).unwrap_or_else(|| source.path.clone());
            if seen.insert(key) {
                out.push(source);
            }
        }
    }
    out
}

fn walk(
    dir: &Path,
    skip: &HashSet<PathBuf>,
    visited: &mut HashSet<PathBuf>,
    out: &mut Vec<Source>,
) {
    let key = dir.canonicalize().unwrap_or_else(|_| dir.to_path_buf());
    if skip.contains(&key) || !visited.insert(key) {
        return;
    }
    let unreadable = |e: std::io::Error| Source {
        path: dir.to_path_buf(),
        error: Some(format!("{}: cannot list the folder: {e}", shown(dir))),
    };
    let entries = match std::fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) => return out.push(unreadable(e)),
    };
    for entry in entries {
        let path = match entry {
            Ok(entry) => entry.path(),
            Err(e) => {
                out.push(unreadable(e));
                continue;
            }
        };
        if path.is_dir() {
            walk(&path, skip, visited, out);
        } else if is_json(&path) && !resolved(&path).is_some_and(|p| skip.contains(&p)) {
            out.push(Source { path, error: None });
        }
    }
}

/// The folder names above `path`, nearest first (from its resolved path where it exists).
fn parent_names(path: &Path) -> Vec<String> {
    let full = path
        .canonicalize()
        .or_else(|_| std::path::absolute(path))
        .unwrap_or_else(|_| path.to_path_buf());
    let mut names: Vec<String> = full
        .parent()
        .map(|p| {
            p.components()
                .filter_map(|c| match c {
                    Component::Normal(n) => Some(n.to_string_lossy().into_owned()),
                    _ => None,
                })
                .collect()
        })
        .unwrap_or_default();
    names.reverse();
    names
}

/// One output name per scene, unique without regard to case (for case-insensitive file
/// systems):
///
/// 1. the scene file's stem (`marking/alice/scene.json` → `scene`);
/// 2. where stems clash, the fewest parent folders that tell the scene from every other with
///    its stem are prefixed, each followed by `__` (`alice__scene`, `bob__scene`;
///    `2023__alice__scene` beside `2024__alice__scene`);
/// 3. a name still taken (files in one folder whose names differ only in case, or a stem such as
///    `alice__scene` itself) gets `-2`, `-3`, … in scene order.
pub fn output_names(scenes: &[&Path]) -> Vec<String> {
    let stems: Vec<String> = scenes
        .iter()
        .map(|p| match p.file_stem() {
            Some(s) if !s.is_empty() => s.to_string_lossy().into_owned(),
            _ => "scene".to_string(),
        })
        .collect();
    let lower_stems: Vec<String> = stems.iter().map(|s| s.to_lowercase()).collect();
    let parents: Vec<Vec<String>> = scenes.iter().map(|p| parent_names(p)).collect();
    let lower_parents: Vec<Vec<String>> = parents
        .iter()
        .map(|ps| ps.iter().map(|p| p.to_lowercase()).collect())
        .collect();
    // The `depth` nearest folders of scene `i`, as compared.
    let key = |i: usize, depth: usize| &lower_parents[i][..depth.min(lower_parents[i].len())];
    let mut by_stem: std::collections::HashMap<&str, Vec<usize>> = Default::default();
    for (i, stem) in lower_stems.iter().enumerate() {
        by_stem.entry(stem.as_str()).or_default().push(i);
    }
    let depth = |i: usize| -> usize {
        let others: Vec<usize> = by_stem[lower_stems[i].as_str()]
            .iter()
            .copied()
            .filter(|&j| j != i)
            .collect();
        if others.is_empty() {
            return 0;
        }
        (1..=parents[i].len())
            .find(|&d| others.iter().all(|&j| key(j, d) != key(i, d)))
            .unwrap_or(0)
    };
    let mut taken = HashSet::new();
    (0..scenes.len())
        .map(|i| {
            let mut parts: Vec<&str> = parents[i][..depth(i)].iter().map(String::as_str).collect();
            parts.reverse();
            parts.push(&stems[i]);
            let base = parts.join(NAME_SEPARATOR);
            let mut candidate = base.clone();
            let mut k = 2;
            while !taken.insert(candidate.to_lowercase()) {
                candidate = format!("{base}-{k}");
                k += 1;
            }
            candidate
        })
        .collect()
}

/// The reference image for the output `name` of the scene file `scene` in `dir`: the first of
/// `name.png`, `.ppm`, `.exr`, `.jpg`, `.jpeg` that exists; failing that, where `name` has
/// folders prefixed (scenes sharing a stem), the same for the scene's stem, so that
/// `alice/task1.json` and `bob/task1.json` are both compared with `task1.png`. Otherwise a
/// message saying where it looked.
pub fn find_reference(dir: &Path, name: &str, scene: &Path) -> Result<PathBuf, String> {
    let stem = scene
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .filter(|s| !s.is_empty() && s != name);
    for candidate in std::iter::once(name).chain(stem.as_deref()) {
        for ext in REFERENCE_EXTENSIONS {
            let path = dir.join(format!("{candidate}.{ext}"));
            if path.is_file() {
                return Ok(path);
            }
        }
    }
    let also = match &stem {
        Some(stem) => format!(", nor '{stem}.png' and the like"),
        None => String::new(),
    };
    Err(format!(
        "no reference image '{name}.png' (or .ppm, .exr, .jpg, .jpeg){also} in '{}'",
        shown(dir)
    ))
}

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
    fn create(&self, path: &Path) -> Result<PendingFile, OutputError>;
    fn commit(&self, pending: PendingFile, bytes: &[u8]) -> Result<(), OutputError>;
}

/// [`Writer`] straight through [`PendingFile`].
#[derive(Debug, Clone, Copy, Default)]
pub struct Direct;

impl Writer for Direct {
    fn create(&self, path: &Path) -> Result<PendingFile, OutputError> {
        PendingFile::create(path)
    }
    fn commit(&self, pending: PendingFile, bytes: &[u8]) -> Result<(), OutputError> {
        pending.commit(bytes)
    }
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
pub struct Row {
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

impl Row {
    fn new(job: &Job) -> Row {
        Row {
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
pub fn run(
    jobs: &[Job],
    options: &RunOptions,
    writer: &dyn Writer,
    done: &(dyn Fn(&Row) + Sync),
) -> Vec<Row> {
    let lanes = rayon::current_num_threads().clamp(1, jobs.len().max(1));
    let next = AtomicUsize::new(0);
    let rows: Vec<OnceLock<Row>> = jobs.iter().map(|_| OnceLock::new()).collect();
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
                let mut row = Row::new(job);
                row.fail("not run".into());
                row
            })
        })
        .collect()
}

fn run_one(job: &Job, options: &RunOptions, writer: &dyn Writer) -> Row {
    let mut row = Row::new(job);
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

fn render_and_compare(
    job: &Job,
    options: &RunOptions,
    writer: &dyn Writer,
    row: &mut Row,
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
fn compare(job: &Job, reference: &Path, options: &RunOptions, row: &mut Row) -> Result<(), String> {
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

/// Counts of rows by status.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Totals {
    pub scenes: usize,
    pub ok: usize,
    pub failed: usize,
    pub over_threshold: usize,
}

impl Totals {
    pub fn of(rows: &[Row]) -> Totals {
        let mut t = Totals {
            scenes: rows.len(),
            ..Totals::default()
        };
        for row in rows {
            match row.status {
                Status::Ok => t.ok += 1,
                Status::Failed => t.failed += 1,
                Status::OverThreshold => t.over_threshold += 1,
            }
        }
        t
    }
}

/// The summary's columns; the last four only when comparing.
pub const COLUMNS: [&str; 14] = [
    "scene",
    "output",
    "status",
    "error",
    "width",
    "height",
    "spp",
    "seconds",
    "rays",
    "warnings",
    "reference",
    "mse",
    "flip",
    "pass",
];

/// A summary value.
enum Value {
    Text(Option<String>),
    Number(Option<f64>),
    Count(Option<u64>),
    Bool(Option<bool>),
}

fn path_text(p: &Path) -> String {
    p.to_string_lossy().into_owned()
}

/// The values of a row, column by column (see [`COLUMNS`]).
fn values(row: &Row, comparing: bool) -> Vec<Value> {
    let mut v = vec![
        Value::Text(Some(path_text(&row.scene))),
        Value::Text(row.output.as_deref().map(path_text)),
        Value::Text(Some(row.status.name().to_string())),
        Value::Text(row.error.clone()),
        Value::Count(row.width.map(u64::from)),
        Value::Count(row.height.map(u64::from)),
        Value::Count(row.spp.map(u64::from)),
        Value::Number(row.seconds.map(|s| (s * 1e4).round() / 1e4)),
        Value::Count(row.rays),
        Value::Count(Some(row.warnings.len() as u64)),
    ];
    if comparing {
        let c = row.comparison.clone().unwrap_or_default();
        v.push(Value::Text(c.reference.as_deref().map(path_text)));
        v.push(Value::Number(c.mse));
        v.push(Value::Number(c.flip));
        v.push(Value::Bool(c.pass));
    }
    v
}

fn number_text(x: f64) -> String {
    if x.is_nan() {
        "NaN".into()
    } else {
        format!("{x}")
    }
}

/// A text cell of the summary. One that starts with `=`, `+`, `-`, `@`, a tab or a carriage
/// return gets a leading `'`, so that a spreadsheet shows it as text rather than running it as a
/// formula (OWASP, "CSV Injection"): scene names and error messages come from students' files.
fn csv_field(text: &str) -> String {
    let guarded;
    let text = if text.starts_with(['=', '+', '-', '@', '\t', '\r']) {
        guarded = format!("'{text}");
        guarded.as_str()
    } else {
        text
    };
    if text.contains([',', '"', '\n', '\r']) || text.starts_with(' ') || text.ends_with(' ') {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// The summary as CSV (RFC 4180: fields with commas, quotes, line breaks or edge spaces quoted,
/// quotes doubled; CRLF line ends), a header line first. Empty fields for values that do not
/// apply; `NaN` where a metric has no value.
pub fn csv(rows: &[Row], comparing: bool) -> String {
    let n = if comparing { COLUMNS.len() } else { 10 };
    let mut out = COLUMNS[..n].join(",");
    out.push_str("\r\n");
    for row in rows {
        let fields: Vec<String> = values(row, comparing)
            .into_iter()
            .map(|v| match v {
                Value::Text(t) => csv_field(t.as_deref().unwrap_or("")),
                Value::Number(x) => x.map(number_text).unwrap_or_default(),
                Value::Count(x) => x.map(|x| x.to_string()).unwrap_or_default(),
                Value::Bool(b) => b.map(|b| b.to_string()).unwrap_or_default(),
            })
            .collect();
        out.push_str(&fields.join(","));
        out.push_str("\r\n");
    }
    out
}

/// `text` as a JSON string literal.
pub fn json_string(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 2);
    out.push('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if (c as u32) < 0x20 || c == '\u{2028}' || c == '\u{2029}' => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// The summary as JSON: `{"totals": {...}, "scenes": [{column: value, ...}, ...]}` with the
/// columns of [`csv`]; `null` for values that do not apply or are not numbers.
pub fn json(rows: &[Row], comparing: bool) -> String {
    let t = Totals::of(rows);
    let mut out = format!(
        "{{\n  \"totals\": {{\"scenes\": {}, \"ok\": {}, \"failed\": {}, \"over_threshold\": {}}},\n  \"scenes\": [",
        t.scenes, t.ok, t.failed, t.over_threshold
    );
    for (i, row) in rows.iter().enumerate() {
        out.push_str(if i == 0 { "\n    {" } else { ",\n    {" });
        for (j, (column, value)) in COLUMNS.iter().zip(values(row, comparing)).enumerate() {
            if j > 0 {
                out.push_str(", ");
            }
            let value = match value {
                Value::Text(t) => t.as_deref().map(json_string),
                Value::Number(x) => x.filter(|x| x.is_finite()).map(|x| format!("{x}")),
                Value::Count(x) => x.map(|x| x.to_string()),
                Value::Bool(b) => b.map(|b| b.to_string()),
            };
            let _ = write!(out, "\"{column}\": {}", value.as_deref().unwrap_or("null"));
        }
        out.push('}');
    }
    out.push_str(if rows.is_empty() {
        "]\n}\n"
    } else {
        "\n  ]\n}\n"
    });
    out
}

/// The summary format for `path`: CSV for `.csv`, JSON for `.json`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SummaryFormat {
    Csv,
    Json,
}

impl SummaryFormat {
    pub fn from_path(path: &Path) -> Option<SummaryFormat> {
        let ext: OsString = path.extension()?.to_ascii_lowercase();
        match ext.to_str()? {
            "csv" => Some(SummaryFormat::Csv),
            "json" => Some(SummaryFormat::Json),
            _ => None,
        }
    }

    pub fn write(self, rows: &[Row], comparing: bool) -> String {
        match self {
            SummaryFormat::Csv => csv(rows, comparing),
            SummaryFormat::Json => json(rows, comparing),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_stems_with_folders_only_where_stems_clash() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        for sub in ["alice", "bob", "x/alice", "c"] {
            std::fs::create_dir_all(d.join(sub)).unwrap();
        }
        let paths = [
            d.join("alice/scene.json"),
            d.join("bob/scene.json"),
            d.join("x/alice/scene.json"),
            d.join("c/only.json"),
            d.join("c/Only.JSON"),
        ];
        let refs: Vec<&Path> = paths.iter().map(PathBuf::as_path).collect();
        let names = output_names(&refs);
        let root = d.file_name().unwrap().to_string_lossy().into_owned();
        assert_eq!(
            names,
            vec![
                format!("{root}__alice__scene"),
                "bob__scene".to_string(),
                "x__alice__scene".to_string(),
                "only".to_string(),
                "Only-2".to_string(),
            ]
        );
    }

    #[test]
    fn folders_give_their_json_files_recursively_sorted_and_once() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        std::fs::create_dir_all(d.join("b/deep")).unwrap();
        std::fs::create_dir_all(d.join("out")).unwrap();
        for f in [
            "b/deep/z.json",
            "b/a.json",
            "c.JSON",
            "notes.txt",
            "out/s.json",
        ] {
            std::fs::write(d.join(f), "{}").unwrap();
        }
        let got = collect_scenes(&[d.to_path_buf(), d.join("b/a.json")], &[d.join("out")]);
        let names: Vec<PathBuf> = got
            .iter()
            .map(|s| s.path.strip_prefix(d).unwrap().into())
            .collect();
        assert_eq!(
            names,
            vec![
                PathBuf::from("b/a.json"),
                PathBuf::from("b/deep/z.json"),
                PathBuf::from("c.JSON")
            ]
        );
    }

    fn row(error: Option<&str>) -> Row {
        Row {
            scene: PathBuf::from("dir, with comma/\"q\".json"),
            name: "q".into(),
            output: None,
            status: if error.is_some() {
                Status::Failed
            } else {
                Status::Ok
            },
            error: error.map(String::from),
            width: Some(4),
            height: Some(2),
            spp: None,
            seconds: Some(0.5),
            rays: Some(8),
            warnings: vec![],
            comparison: Some(Comparison {
                reference: None,
                mse: Some(f64::NAN),
                flip: Some(0.25),
                pass: Some(false),
            }),
            images: Images::default(),
        }
    }

    #[test]
    fn csv_text_that_a_spreadsheet_would_run_is_kept_as_text() {
        assert_eq!(csv_field("=HYPERLINK(\"x\")"), "\"'=HYPERLINK(\"\"x\"\")\"");
        assert_eq!(csv_field("@sum"), "'@sum");
        assert_eq!(csv_field("-2+3"), "'-2+3");
        assert_eq!(csv_field("scenes/a=b.json"), "scenes/a=b.json");
    }

    #[test]
    fn csv_quotes_what_needs_quoting() {
        let text = csv(&[row(Some("line 1\nline \"2\""))], true);
        let lines: Vec<&str> = text.split("\r\n").collect();
        assert_eq!(lines[0], COLUMNS.join(","));
        assert_eq!(
            lines[1],
            "\"dir, with comma/\"\"q\"\".json\",,failed,\"line 1\nline \"\"2\"\"\",4,2,,0.5,8,0,,NaN,0.25,false"
        );
        let plain = csv(&[row(None)], false);
        assert!(plain
            .starts_with("scene,output,status,error,width,height,spp,seconds,rays,warnings\r\n"));
    }

    #[test]
    fn json_escapes_strings_and_writes_null_for_missing_values() {
        let text = json(&[row(Some("bad \u{1b} \"x\"\\"))], true);
        assert!(text.contains(r#""error": "bad \u001b \"x\"\\""#), "{text}");
        assert!(
            text.contains(r#""mse": null, "flip": 0.25, "pass": false"#),
            "{text}"
        );
        assert!(
            text.contains(r#""totals": {"scenes": 1, "ok": 0, "failed": 1, "over_threshold": 0}"#)
        );
        assert_eq!(json(&[], false), "{\n  \"totals\": {\"scenes\": 0, \"ok\": 0, \"failed\": 0, \"over_threshold\": 0},\n  \"scenes\": []\n}\n");
    }

    #[test]
    fn error_lines_are_one_line_and_name_the_scene() {
        let mut r = row(Some("first\nsecond"));
        r.scene = PathBuf::from("s.json");
        assert_eq!(r.error_line().unwrap(), "s.json: first; second");
        r.error = Some("s.json:1:2: invalid JSON".into());
        assert_eq!(r.error_line().unwrap(), "s.json:1:2: invalid JSON");
    }
}
