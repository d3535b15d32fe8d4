//! Every real scene file of the two coursework corpora (`../shared/coursework/corpus/`, 219 files,
//! and `../shared/coursework/corpus2/`, 48 more from other repositories) is loaded and rendered at
//! 64 pixels wide, 1 sample per pixel, at most 2 bounces. None may panic; each either renders or
//! fails with a clean error that names the file. Of the scenes whose assets are all in the corpus,
//! at least 95% of the first corpus's (two use a schema of their own) and all of the second's must
//! render, and a scene whose assets are missing must fail by naming the missing file.
//!
//! The test prints each scene's warnings and compares them, and whether it rendered, with
//! `tests/corpus_expected.tsv` and `tests/corpus2_expected.tsv`: a scene that stops rendering, or
//! gains a warning the file does not list, fails the test. A scene that loses one, or starts
//! rendering, is reported; rewrite the lists with
//! `RAYTRACER_UPDATE_CORPUS=1 cargo test --release --test corpus` after looking at the change.

use std::collections::{BTreeMap, BTreeSet};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Component, Path, PathBuf};

use raytracer::film::Film;
use raytracer::integrator::{TraceOptions, DEFAULT_CUTOFF};
use raytracer::math::Vec3;
use raytracer::metric::{mse, Region};
use raytracer::render::{render, RenderOptions};
use raytracer::scene::{load, LoadOptions, Scene, SceneError};

fn corpus_dir() -> Option<PathBuf> {
    let dir = match std::env::var_os("RAYTRACER_CORPUS") {
        Some(d) => PathBuf::from(d),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/coursework/corpus"),
    };
    dir.join("MANIFEST.tsv").is_file().then_some(dir)
}

/// The second corpus, beside the first.
fn corpus2_dir() -> Option<PathBuf> {
    let dir = corpus_dir()?.join("../corpus2");
    dir.join("MANIFEST.tsv").is_file().then_some(dir)
}

/// One of the two corpora: where it is, its scenes, and what the test expects of them.
struct Corpus {
    dir: PathBuf,
    entries: Vec<Entry>,
    /// The list of expected outcomes, relative to the repository.
    expected: &'static str,
    /// Percentage of the scenes with all their assets that must render.
    must_render: usize,
}

/// Both corpora that are next to the repository.
fn corpora() -> Vec<Corpus> {
    let mut out = Vec::new();
    if let Some(dir) = corpus_dir() {
        let entries = read_manifest(&dir);
        assert!(
            entries.len() >= 200,
            "manifest lists {} scenes",
            entries.len()
        );
        out.push(Corpus {
            dir,
            entries,
            expected: "tests/corpus_expected.tsv",
            must_render: 95,
        });
    }
    if let Some(dir) = corpus2_dir() {
        let entries = read_manifest2(&dir);
        assert!(
            entries.len() >= 48,
            "manifest lists {} scenes",
            entries.len()
        );
        out.push(Corpus {
            dir,
            entries,
            expected: "tests/corpus2_expected.tsv",
            must_render: 100,
        });
    }
    if out.is_empty() {
        eprintln!("corpus not found next to the repository; set RAYTRACER_CORPUS to run this test");
    }
    out
}

/// One scene row of the manifest: the file and its asset references (`ref -> assets/…` or a
/// reason the asset is absent).
struct Entry {
    file: String,
    refs: Vec<(String, String)>,
}

fn read_manifest(dir: &Path) -> Vec<Entry> {
    let text = std::fs::read_to_string(dir.join("MANIFEST.tsv")).expect("manifest readable");
    let mut out = Vec::new();
    for line in text.lines().skip(1) {
        let cols: Vec<&str> = line.split('\t').collect();
        if cols.len() < 7 || !cols[0].ends_with(".json") || cols[0].contains('/') {
            continue;
        }
        let notes = cols[6];
        let mut refs = Vec::new();
        if let Some(rest) = notes.split("assets:").nth(1) {
            for part in rest.split(';') {
                if let Some((r, a)) = part.split_once("->") {
                    refs.push((r.trim().to_string(), a.trim().to_string()));
                }
            }
        }
        out.push(Entry {
            file: cols[0].to_string(),
            refs,
        });
    }
    out
}

/// The second corpus's manifest: scenes under `scenes/`, and an `assets` column of
/// `ref -> assets/… (how it was matched)` or `ref -> why it is absent`, separated by `;`.
fn read_manifest2(dir: &Path) -> Vec<Entry> {
    let text = std::fs::read_to_string(dir.join("MANIFEST.tsv")).expect("manifest readable");
    let mut out = Vec::new();
    for line in text.lines().skip(1) {
        let cols: Vec<&str> = line.split('\t').collect();
        if cols.len() < 6 || !cols[0].ends_with(".json") {
            continue;
        }
        let refs = cols[5]
            .split(';')
            .filter_map(|part| part.split_once("->"))
            .map(|(r, a)| {
                let a = a.trim();
                let stored = a.split(" (").next().unwrap_or(a);
                (r.trim().to_string(), stored.to_string())
            })
            .collect();
        out.push(Entry {
            file: format!("scenes/{}", cols[0]),
            refs,
        });
    }
    out
}

/// A folder `base` such that `base` joined with `reference` (lexically) names `asset`: the asset
/// path minus the reference's tail, plus one stand-in folder per leading `..`.
fn base_for(corpus: &Path, reference: &str, asset: &str) -> Option<PathBuf> {
    let reference = reference.replace('\\', "/");
    let ups = Path::new(&reference)
        .components()
        .take_while(|c| matches!(c, Component::ParentDir | Component::CurDir))
        .filter(|c| matches!(c, Component::ParentDir))
        .count();
    let tail: PathBuf = Path::new(&reference)
        .components()
        .skip_while(|c| matches!(c, Component::ParentDir | Component::CurDir))
        .collect();
    let asset = Path::new(asset);
    if !asset.ends_with(&tail) || tail.as_os_str().is_empty() {
        return None;
    }
    let depth = tail.components().count();
    let mut base: PathBuf = asset
        .components()
        .take(asset.components().count() - depth)
        .collect();
    for _ in 0..ups {
        base.push("_");
    }
    Some(corpus.join(base))
}

/// Loads the scene of `e` at `width` pixels wide, its assets found through the manifest.
fn load_entry(dir: &Path, e: &Entry, width: u32) -> Result<Scene, SceneError> {
    // A reference whose tail is not the asset's (an absolute path from the author's machine,
    // matched by its file name) is looked for under the asset's repository folder.
    let asset_dirs: Vec<PathBuf> = e
        .refs
        .iter()
        .filter_map(|(r, a)| {
            base_for(dir, r, a).or_else(|| {
                let mut parts = Path::new(a).components();
                match (parts.next(), parts.next()) {
                    (Some(top), Some(repo)) if a.starts_with("assets/") => {
                        Some(dir.join(top).join(repo))
                    }
                    _ => None,
                }
            })
        })
        .collect();
    let options = LoadOptions {
        width: Some(width),
        asset_dirs,
        ..LoadOptions::default()
    };
    load(&dir.join(&e.file), &options)
}

#[test]
fn every_corpus_scene_renders_or_fails_cleanly() {
    for corpus in corpora() {
        check(&corpus);
    }
}

/// The rules of the module's doc for one corpus.
fn check(corpus: &Corpus) {
    let (dir, entries) = (&corpus.dir, &corpus.entries);

    let mut rendered = Vec::new();
    let mut failed: BTreeMap<String, (bool, String)> = BTreeMap::new();
    let mut panicked = Vec::new();
    let mut warnings = 0usize;
    let mut complete = 0usize;
    let mut outcomes: BTreeMap<String, Outcome> = BTreeMap::new();
    for e in entries {
        let assets_present = e.refs.iter().all(|(_, a)| a.starts_with("assets/"));
        if assets_present {
            complete += 1;
        }
        let result = catch_unwind(AssertUnwindSafe(|| {
            let scene = load_entry(dir, e, 64)?;
            let out = render(
                &scene,
                &RenderOptions {
                    max_depth: 2,
                    ..RenderOptions::default()
                },
            )
            .unwrap();
            let warned: Vec<String> = scene
                .warnings
                .iter()
                .map(|w| format!("{}: {}", w.location.path, w.message))
                .collect();
            Ok::<_, raytracer::scene::SceneError>((warned, out))
        }));
        match result {
            Ok(Ok((w, out))) => {
                warnings += w.len();
                outcomes.insert(e.file.clone(), Outcome::Rendered(w));
                assert_eq!(out.film.width, 64);
                assert!(out.film.pixels.iter().all(|p| p.is_finite()), "{}", e.file);
                rendered.push(e.file.clone());
            }
            Ok(Err(err)) => {
                let msg = err.to_string();
                // Absolute paths from the author's machine are not in the manifest's asset list.
                let absolute_asset = msg.contains("not found")
                    && (msg.contains("file '/") || msg.contains(":/") && msg.contains("file 'C:"));
                let assets_present = assets_present && !absolute_asset;
                if !assets_present && e.refs.iter().all(|(_, a)| a.starts_with("assets/")) {
                    complete -= 1;
                }
                assert!(
                    msg.contains(&e.file),
                    "the error for {} does not name the file: {msg}",
                    e.file
                );
                failed.insert(e.file.clone(), (assets_present, msg));
                outcomes.insert(e.file.clone(), Outcome::Failed);
            }
            Err(_) => panicked.push(e.file.clone()),
        }
    }

    let complete_failed: Vec<_> = failed.iter().filter(|(_, (p, _))| *p).collect();
    println!(
        "{}: {} scenes, {} rendered, {} clean errors ({} with all assets present), {} panics, {} warnings",
        dir.display(),
        entries.len(),
        rendered.len(),
        failed.len(),
        complete_failed.len(),
        panicked.len(),
        warnings
    );
    for (file, (present, msg)) in &failed {
        println!(
            "  {} {file}: {msg}",
            if *present { "FAILED " } else { "missing" }
        );
    }
    assert!(panicked.is_empty(), "panicked: {panicked:?}");
    compare_with_expected(&outcomes, corpus.expected);
    let rendered_complete = complete - complete_failed.len();
    println!("corpus: {rendered_complete} of {complete} scenes with all assets present rendered");
    assert!(
        rendered_complete * 100 >= complete * corpus.must_render,
        "only {rendered_complete} of {complete} scenes with all assets rendered"
    );
    for (file, (present, msg)) in &failed {
        if !present {
            assert!(
                msg.contains("not found") || msg.contains("JSON"),
                "{file} lacks assets but failed for another reason: {msg}"
            );
        }
    }
}

/// What loading and rendering one scene gave.
#[derive(Debug, PartialEq)]
enum Outcome {
    /// Rendered, with these warnings (`json.path: message`).
    Rendered(Vec<String>),
    /// A clean error.
    Failed,
}

/// The expected outcomes: `scene<TAB>rendered`, `scene<TAB>error`, and one
/// `scene<TAB>warning<TAB>json.path: message` line per warning.
fn read_expected(expected: &str) -> BTreeMap<String, (bool, BTreeSet<String>)> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(expected);
    let text = std::fs::read_to_string(&path).unwrap_or_default();
    let mut out: BTreeMap<String, (bool, BTreeSet<String>)> = BTreeMap::new();
    for line in text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.is_empty())
    {
        let mut cols = line.splitn(3, '\t');
        let (Some(file), Some(kind)) = (cols.next(), cols.next()) else {
            panic!("{expected}: bad line {line:?}");
        };
        let entry = out.entry(file.to_string()).or_default();
        match (kind, cols.next()) {
            ("rendered", None) => entry.0 = true,
            ("error", None) => entry.0 = false,
            ("warning", Some(w)) => {
                entry.1.insert(w.to_string());
            }
            _ => panic!("{expected}: bad line {line:?}"),
        }
    }
    out
}

fn write_expected(outcomes: &BTreeMap<String, Outcome>, expected: &str) {
    let mut text = String::from(
        "# What tests/corpus.rs expects of each corpus scene: rendered or error, and each warning\n\
         # (json.path: message). Rewritten by RAYTRACER_UPDATE_CORPUS=1.\n",
    );
    for (file, outcome) in outcomes {
        match outcome {
            Outcome::Failed => text += &format!("{file}\terror\n"),
            Outcome::Rendered(warnings) => {
                text += &format!("{file}\trendered\n");
                let unique: BTreeSet<&String> = warnings.iter().collect();
                for w in unique {
                    text += &format!("{file}\twarning\t{}\n", w.replace(['\t', '\n'], " "));
                }
            }
        }
    }
    std::fs::write(Path::new(env!("CARGO_MANIFEST_DIR")).join(expected), text)
        .expect("expected outcomes written");
}

/// Prints each scene's warnings, and fails on a scene that stopped rendering or gained a
/// warning since `expected` (its list of outcomes) was written.
fn compare_with_expected(outcomes: &BTreeMap<String, Outcome>, expected_file: &str) {
    if std::env::var_os("RAYTRACER_UPDATE_CORPUS").is_some_and(|v| v == "1") {
        write_expected(outcomes, expected_file);
        println!("corpus: rewrote {expected_file}");
        return;
    }
    let expected = read_expected(expected_file);
    let mut worse = Vec::new();
    let mut better = Vec::new();
    for (file, outcome) in outcomes {
        let (was_rendered, was_warned) = expected.get(file).cloned().unwrap_or_default();
        let known = expected.contains_key(file);
        match outcome {
            Outcome::Failed if was_rendered => worse.push(format!("{file}: no longer renders")),
            Outcome::Failed => {}
            Outcome::Rendered(warnings) => {
                println!("  {file}: {} warning(s)", warnings.len());
                for w in warnings {
                    println!("      {w}");
                    if !was_warned.contains(w) {
                        worse.push(format!("{file}: new warning: {w}"));
                    }
                }
                if known && !was_rendered {
                    better.push(format!("{file}: renders now"));
                }
                for w in &was_warned {
                    if !warnings.contains(w) {
                        better.push(format!("{file}: no longer warns: {w}"));
                    }
                }
            }
        }
    }
    for b in &better {
        println!("  better than {expected_file}: {b}");
    }
    assert!(
        worse.is_empty(),
        "worse than {expected_file} (rewrite it with RAYTRACER_UPDATE_CORPUS=1 if intended):\n{}",
        worse.join("\n")
    );
}

/// The command line's default work skipping (reflection and refraction rays traced down to a
/// weight of 1/255, `--adc-bailout`; `--no-skip` turns it off) keeps every corpus scene that
/// renders within MSE 10⁻⁵ of its full-work render: the pictures at 64 pixels wide, one sample,
/// each file's own bounce count, compared as the default tone map shows them (linear, clamped to
/// [0, 1]).
#[test]
fn the_default_cutoff_keeps_every_corpus_scene_within_mse_1e5() {
    let corpora = corpora();
    if corpora.is_empty() {
        return;
    }
    let shown = |f: &Film| {
        let pixels = f
            .pixels
            .iter()
            .map(|c| c.clamp(Vec3::ZERO, Vec3::ONE))
            .collect();
        Film::from_pixels(f.width, f.height, pixels)
    };
    let (mut compared, mut rays_full, mut rays_skip) = (0usize, 0u64, 0u64);
    let mut worst = (0.0f64, String::new());
    for (dir, e) in corpora
        .iter()
        .flat_map(|c| c.entries.iter().map(move |e| (&c.dir, e)))
    {
        let Ok(scene) = load_entry(dir, e, 64) else {
            continue;
        };
        let run = |cutoff| {
            let options = RenderOptions {
                trace: TraceOptions {
                    cutoff,
                    ..TraceOptions::default()
                },
                ..RenderOptions::default()
            };
            render(&scene, &options).unwrap()
        };
        let (full, skip) = (run(None), run(Some(DEFAULT_CUTOFF)));
        let (a, b) = (shown(&full.film), shown(&skip.film));
        let e_mse = mse(&a, &b, Region::full(a.width, a.height));
        assert!(
            e_mse <= 1e-5,
            "{}: MSE {e_mse} with the default cut-off",
            e.file
        );
        if e_mse > worst.0 {
            worst = (e_mse, e.file.clone());
        }
        compared += 1;
        rays_full += full.counts.total();
        rays_skip += skip.counts.total();
    }
    println!(
        "default cut-off: {compared} corpus scenes, largest MSE {:.2e} ({}), {rays_skip} of {rays_full} rays",
        worst.0, worst.1
    );
    assert!(compared >= 150, "only {compared} corpus scenes rendered");
}
