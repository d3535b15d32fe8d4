//! Inputs that once crashed, hung or exhausted memory (found by the fuzz targets in `fuzz/`, see
//! `docs/fuzzing.md`), kept in `tests/bad_input/fuzz-*`. Each must now fail cleanly with a message
//! that names the file, or render, through the library and (scenes) through the command line, and
//! quickly.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use raytracer::render::{render, RenderOptions};
use raytracer::scene::mesh_file::read_mesh;
use raytracer::scene::{load, LoadOptions};

/// What an input must do now.
#[derive(Debug, Clone, Copy)]
enum Expect {
    /// Fail with an error that names the file and contains this text.
    Error(&'static str),
    /// Load and render (for an input whose fixed behaviour is to render; none so far).
    #[allow(dead_code)]
    Render,
}

/// Every `fuzz-*` file in `tests/bad_input/` and what it must do. A new file must be listed here.
const CASES: &[(&str, Expect)] = &[(
    "fuzz-scene_loader-huge-face-size.json",
    Expect::Error("needs 1000000000000000000000000000000 indices"),
)];

/// Generous: each case takes milliseconds; a regression to a hang or a huge allocation does not.
const TIME_LIMIT: Duration = Duration::from_secs(20);

fn bad_input() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_input")
}

fn is_scene(name: &str) -> bool {
    name.ends_with(".json")
}

#[test]
fn every_fuzz_input_is_listed_and_every_listed_input_exists() {
    let mut on_disk: Vec<String> = std::fs::read_dir(bad_input())
        .expect("tests/bad_input exists")
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.starts_with("fuzz-"))
        .collect();
    on_disk.sort();
    let mut listed: Vec<String> = CASES.iter().map(|(n, _)| n.to_string()).collect();
    listed.sort();
    assert_eq!(on_disk, listed);
}

#[test]
fn the_library_fails_cleanly_or_renders() {
    for &(name, expect) in CASES {
        let path = bad_input().join(name);
        let start = Instant::now();
        let result: Result<(), String> = if is_scene(name) {
            // Rendered small: these tests are about not crashing, not about pictures.
            let options = LoadOptions {
                width: Some(16),
                ..LoadOptions::default()
            };
            load(&path, &options)
                .map(|scene| {
                    let film = render(&scene, &RenderOptions::default()).unwrap().film;
                    assert_eq!(film.width, 16, "{name}");
                })
                .map_err(|e| e.to_string())
        } else {
            read_mesh(&path).map(|_| ()).map_err(|e| e.to_string())
        };
        assert!(
            start.elapsed() < TIME_LIMIT,
            "{name} took {:?}",
            start.elapsed()
        );
        match (expect, result) {
            (Expect::Render, Ok(())) => {}
            (Expect::Error(text), Err(message)) => {
                assert!(
                    message.contains(&path.display().to_string()),
                    "{name}: the message does not name the file: {message}"
                );
                assert!(message.contains(text), "{name}: {message}");
            }
            (Expect::Render, Err(message)) => panic!("{name} no longer renders: {message}"),
            (Expect::Error(_), Ok(())) => panic!("{name} loaded; an error was expected"),
        }
    }
}

#[test]
fn the_command_line_fails_cleanly_or_renders() {
    for &(name, expect) in CASES.iter().filter(|(n, _)| is_scene(n)) {
        let path = bad_input().join(name);
        let dir = tempfile::tempdir().expect("temp dir");
        let out = dir.path().join("out.png");
        let start = Instant::now();
        let run = Command::new(env!("CARGO_BIN_EXE_raytracer"))
            .arg(&path)
            .arg(&out)
            .args(["--width", "16", "--quiet"])
            .current_dir(dir.path())
            .output()
            .expect("run raytracer");
        assert!(
            start.elapsed() < TIME_LIMIT,
            "{name} took {:?}",
            start.elapsed()
        );
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(!stderr.contains("panicked"), "{name}: {stderr}");
        match expect {
            Expect::Render => {
                assert_eq!(run.status.code(), Some(0), "{name}: {stderr}");
                assert!(out.is_file(), "{name}: no image written");
            }
            Expect::Error(text) => {
                assert_eq!(run.status.code(), Some(1), "{name}: {stderr}");
                assert!(
                    stderr.contains(&path.display().to_string()),
                    "{name}: the message does not name the file: {stderr}"
                );
                assert!(stderr.contains(text), "{name}: {stderr}");
                assert!(!out.exists(), "{name}: an image was written");
            }
        }
        // Nothing but the (possible) image appears in the working folder.
        let left: Vec<_> = std::fs::read_dir(dir.path())
            .expect("list the temp dir")
            .filter_map(|e| e.ok().map(|e| e.file_name()))
            .filter(|n| n != "out.png")
            .collect();
        assert!(left.is_empty(), "{name} left {left:?}");
    }
}
