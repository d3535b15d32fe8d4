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

use libfuzzer_sys::fuzz_target;
use raytracer::scene::{load, load_str};

fuzz_target!(|data: &[u8]| {
    let opts = common::load_options();
    let (file, result) = match std::str::from_utf8(data) {
        Ok(text) => {
            let path = common::scene_path();
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
            common::check_scene_error(&file, &e);
            return;
        }
    };
    // Vary the sampling and the accelerator a little with the input.
    let choice = common::RenderChoice {
        spp: 1 + (data.len() % 2) as u32,
        plain_list: data.len().is_multiple_of(3),
    };
    common::render_scene(&scene, choice);
});
