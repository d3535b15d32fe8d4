//! Scene loader and renderer: arbitrary bytes as a scene file, loaded with small limits and, when
//! they load, rendered at 4×4 pixels and tone-mapped in memory.
//!
//! UTF-8 inputs go through `load_str`; other inputs are written to a file and go through `load`
//! (which must refuse them). The scene "lives" in a scratch folder holding copies of the bundled
//! meshes and textures, so relative asset paths in the inputs (`meshes/blob.ply`,
//! `../textures/checker.png`, as the bundled scenes write them) resolve to real files; the
//! loader's last fall-back, the working directory, is wherever the fuzzer runs (libFuzzer's corpus
//! and artifact paths are relative to it, so the harness does not change it). The library only
//! reads; the harness writes only into its scratch folder.
#![no_main]

mod common;

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use raytracer::accel::AccelKind;
use raytracer::film::{to_rgb8, ToneMap};
use raytracer::render::{render, RenderOptions};
use raytracer::scene::{load, load_str, LoadOptions};

/// Small limits, so that one input renders in milliseconds; every bundled scene fits them.
fn options() -> LoadOptions {
    LoadOptions {
        width: Some(4),
        height: Some(4),
        asset_dirs: Vec::new(),
        max_pixels: 16,
        max_bounces: 8,
        max_triangles: 20_000,
        max_light_samples: 16,
    }
}

/// Recursion depth of the render, below the loader's bounce limit: a glass tree of depth 4 is at
/// most 31 rays per sample.
const RENDER_DEPTH: u32 = 4;

/// `<scratch>/scenes/fuzz.json`, with `<scratch>/scenes/meshes` and `<scratch>/textures` filled.
fn scene_path() -> &'static Path {
    static PATH: OnceLock<PathBuf> = OnceLock::new();
    PATH.get_or_init(|| {
        let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let root = common::scratch();
        copy_dir(&repo.join("scenes/meshes"), &root.join("scenes/meshes"));
        copy_dir(&repo.join("textures"), &root.join("textures"));
        // One render thread: jobs run side by side as processes.
        std::env::set_var("RAYON_NUM_THREADS", "1");
        root.join("scenes/fuzz.json")
    })
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).expect("create an asset folder");
    for entry in std::fs::read_dir(from)
        .expect("list an asset folder")
        .flatten()
    {
        let p = entry.path();
        if p.is_file() {
            if let Some(name) = p.file_name() {
                std::fs::copy(&p, to.join(name)).expect("copy an asset");
            }
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let opts = options();
    let (file, result) = match std::str::from_utf8(data) {
        Ok(text) => {
            let path = scene_path();
            (path.to_path_buf(), load_str(text, path, &opts))
        }
        Err(_) => {
            let raw = common::write_input("raw.json", data);
            let r = load(&raw, &opts);
            assert!(r.is_err(), "a file that is not UTF-8 loaded");
            (raw, r)
        }
    };
    let scene = match result {
        Ok(scene) => scene,
        Err(e) => {
            // Every error starts with the scene file (asset errors name the asset after it).
            let text = e.to_string();
            let name = file.display().to_string();
            assert!(text.starts_with(&name), "error without the file: {text}");
            return;
        }
    };
    let pixels = scene.camera.width as usize * scene.camera.height as usize;
    assert_eq!(pixels, 16);
    // Vary the sampling and the accelerator a little with the input.
    let render_options = RenderOptions {
        spp: 1 + (data.len() % 2) as u32,
        accel: if data.len().is_multiple_of(3) {
            AccelKind::None
        } else {
            AccelKind::Auto
        },
        max_depth: RENDER_DEPTH,
        ..RenderOptions::default()
    };
    let out = render(&scene, &render_options);
    for map in [ToneMap::Linear, ToneMap::Srgb, ToneMap::Reinhard] {
        let bytes = to_rgb8(&out.film, map, scene.exposure);
        assert_eq!(bytes.len(), 3 * pixels);
    }
});
