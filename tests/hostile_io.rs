//! Files and flags a hostile or careless user can hand any subcommand: special files as inputs,
//! outputs aimed at inputs, file-size limits, NaN in images and thresholds, nonsense flags, and
//! paths with control characters. Each is run through the command line: a clear error, the right
//! exit status, nothing the user had is lost, and no temporary file is left.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use common::*;
use glam::Vec3;
use raytracer::film::{Film, ToneMap};
use raytracer::image_io::write_image;

/// Runs the binary; a run that has not ended after `HANG` is killed and fails the test (a guard
/// against hangs, not a timing measurement: every case here ends in well under a second).
fn raytracer(args: &[&dyn AsRef<std::ffi::OsStr>]) -> Output {
    const HANG: Duration = Duration::from_secs(120);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_raytracer"));
    for a in args {
        cmd.arg(a);
    }
    let mut child = cmd
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run raytracer");
    let start = Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if start.elapsed() > HANG {
            let _ = child.kill();
            panic!("raytracer {:?} hung", cmd.get_args().collect::<Vec<_>>());
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().expect("output")
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// A message states its cause once: no "X (os error N): X (os error N)".
fn assert_said_once(msg: &str) {
    assert!(msg.matches("os error").count() <= 1, "doubled cause: {msg}");
}

const SMALL: &str = r#"{ "nbounces": 1,
  "camera": { "type": "pinhole", "width": 24, "height": 16, "fov": 40,
              "position": [0, -4, 1], "lookat": [0, 1, -0.1], "up": [0, 0, 1] },
  "scene": { "backgroundcolor": [0.1, 0.1, 0.1],
    "lightsources": [ { "type": "pointlight", "position": [0, -3, 3], "intensity": [9, 9, 9] } ],
    "shapes": [ { "type": "sphere", "center": [0, 0, 0.5], "radius": 0.5,
                  "material": { "kd": 0.8, "diffusecolor": [0.9, 0.3, 0.2] } } ] } }"#;

/// A scene with a textured sphere and an OBJ mesh, both files beside it.
fn scene_with_assets() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("tex.ppm"),
        b"P3\n2 2\n255\n255 0 0 0 255 0 0 0 255 255 255 255\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("tri.obj"),
        "v -1 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n",
    )
    .unwrap();
    let scene = dir.path().join("scene.json");
    std::fs::write(
        &scene,
        r#"{ "camera": { "width": 16, "height": 12, "fov": 40,
                          "position": [0, -4, 1], "lookat": [0, 1, -0.1], "up": [0, 0, 1] },
             "scene": { "lightsources": [ { "type": "pointlight", "position": [0, -3, 3], "intensity": [9, 9, 9] } ],
               "shapes": [
                 { "type": "sphere", "center": [0.5, 0, 0.5], "radius": 0.5,
                   "material": { "kd": 0.8, "texture": "tex.ppm" } },
                 { "type": "mesh", "filename": "tri.obj", "material": { "kd": 0.5 } } ] } }"#,
    )
    .unwrap();
    (dir, scene)
}

#[cfg(unix)]
fn mkfifo(path: &Path) {
    let status = Command::new("mkfifo").arg(path).status().unwrap();
    assert!(status.success());
}

#[cfg(unix)]
#[test]
fn special_files_as_scenes_are_refused_without_blocking_or_reading() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("scene-pipe.json");
    mkfifo(&fifo);
    let out = dir.path().join("out.png");
    for (scene, what) in [
        (fifo.as_path(), "FIFO"),
        (Path::new("/dev/zero"), "character device"),
        (dir.path(), "folder"),
    ] {
        let o = raytracer(&[&scene, &out]);
        let msg = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{msg}");
        assert!(msg.contains(what), "{msg}");
        assert!(msg.contains(&scene.display().to_string()), "{msg}");
        assert_said_once(&msg);
    }
    assert_eq!(names(dir.path()), vec!["scene-pipe.json"]);
}

#[cfg(unix)]
#[test]
fn special_files_as_images_to_compare_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let img = dir.path().join("a.png");
    write_image(&img, &Film::new(4, 4), ToneMap::Linear, 1.0).unwrap();
    let fifo = dir.path().join("b.png");
    mkfifo(&fifo);
    for other in [fifo.as_path(), Path::new("/dev/zero")] {
        let o = raytracer(&[&"compare", &img, &other]);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        assert!(stderr(&o).contains("not a regular file"), "{}", stderr(&o));
    }
}

#[test]
fn a_scene_over_the_size_limit_is_refused_before_reading() {
    let (dir, scene) = write_scene(SMALL);
    let out = dir.path().join("out.png");
    let o = raytracer(&[&scene, &out, &"--max-scene-bytes", &"100"]);
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{msg}");
    assert!(msg.contains("scene.json") && msg.contains("--max-scene-bytes"));
    assert!(msg.contains("over the limit of 100 bytes"), "{msg}");
    // At the default limit: a sparse 65 MiB file, refused from its size alone.
    let big = dir.path().join("big.json");
    std::fs::File::create(&big)
        .unwrap()
        .set_len(65 << 20)
        .unwrap();
    let o = raytracer(&[&big, &out]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("67108864"), "{}", stderr(&o));
    assert!(!out.exists());
}

#[test]
fn a_render_never_writes_over_a_texture_or_mesh_it_uses() {
    let (dir, scene) = scene_with_assets();
    let before: Vec<(PathBuf, Vec<u8>)> = ["scene.json", "tex.ppm", "tri.obj"]
        .iter()
        .map(|n| {
            let p = dir.path().join(n);
            let b = std::fs::read(&p).unwrap();
            (p, b)
        })
        .collect();
    // The texture by its own name, and the mesh and the scene through links with image names.
    let mut targets = vec![dir.path().join("tex.ppm")];
    let hard = dir.path().join("hard.png");
    std::fs::hard_link(dir.path().join("scene.json"), &hard).unwrap();
    targets.push(hard);
    #[cfg(unix)]
    {
        let soft = dir.path().join("soft.png");
        std::os::unix::fs::symlink(dir.path().join("tri.obj"), &soft).unwrap();
        targets.push(soft);
    }
    for target in &targets {
        let o = raytracer(&[&scene, target]);
        let msg = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{}: {msg}", target.display());
        assert!(msg.contains("refusing to write"), "{msg}");
    }
    for (p, b) in &before {
        assert_eq!(&std::fs::read(p).unwrap(), b, "{} changed", p.display());
    }
    // Somewhere else, it renders.
    let o = raytracer(&[&scene, &dir.path().join("out.png"), &"-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn compare_never_writes_its_heat_map_over_an_image_it_reads() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.png");
    let b = dir.path().join("b.png");
    write_image(&a, &Film::new(8, 8), ToneMap::Linear, 1.0).unwrap();
    let grey = Film::from_pixels(8, 8, vec![Vec3::splat(0.5); 64]);
    write_image(&b, &grey, ToneMap::Linear, 1.0).unwrap();
    let (ba, bb) = (std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    for target in [&a, &b] {
        let o = raytracer(&[&"compare", &a, &b, &"--diff", target]);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(stderr(&o).contains("refusing to write"), "{}", stderr(&o));
    }
    assert_eq!(std::fs::read(&a).unwrap(), ba);
    assert_eq!(std::fs::read(&b).unwrap(), bb);
    let heat = dir.path().join("heat.png");
    let o = raytracer(&[&"compare", &a, &b, &"--diff", &heat]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(names(dir.path()), vec!["a.png", "b.png", "heat.png"]);
}

#[test]
fn study_never_writes_over_its_scene_its_reference_or_itself() {
    let (dir, scene) = write_scene(SMALL);
    let kept = std::fs::read(&scene).unwrap();
    let out = dir.path().join("study");
    let reference = dir.path().join("ref.exr");
    write_image(&reference, &Film::new(24, 16), ToneMap::Linear, 1.0).unwrap();
    let kept_ref = std::fs::read(&reference).unwrap();
    let csv = dir.path().join("x.csv");
    let cases: [&[&dyn AsRef<std::ffi::OsStr>]; 3] = [
        &[&"--csv", &scene],
        &[&"--plot", &reference, &"--reference", &reference],
        &[&"--csv", &csv, &"--plot", &csv],
    ];
    for extra in cases {
        let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> =
            vec![&"study", &scene, &"--quick", &"--out", &out];
        args.extend_from_slice(extra);
        let o = raytracer(&args);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        assert!(stderr(&o).contains("refusing to write"), "{}", stderr(&o));
    }
    assert_eq!(std::fs::read(&scene).unwrap(), kept);
    assert_eq!(std::fs::read(&reference).unwrap(), kept_ref);
    assert!(!csv.exists());
}

#[test]
fn bench_never_writes_its_csv_over_a_scene_it_reads() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["example.json", "demo.json"] {
        std::fs::copy(repo().join("scenes").join(name), dir.path().join(name)).unwrap();
    }
    let demo = dir.path().join("demo.json");
    let kept = std::fs::read(&demo).unwrap();
    let o = raytracer(&[
        &"bench",
        &"--quick",
        &"--scenes",
        &dir.path(),
        &"--csv",
        &demo,
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("refusing to write"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&demo).unwrap(), kept);
}

#[test]
fn an_output_that_is_a_device_or_folder_is_refused() {
    let (dir, scene) = write_scene(SMALL);
    let folder = dir.path().join("out.png");
    std::fs::create_dir(&folder).unwrap();
    let o = raytracer(&[&scene, &folder]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("folder, not a regular file"));
    // A link with an image's name that leads to a device: renaming over it would replace the
    // link, and writing through it would feed the device.
    #[cfg(unix)]
    {
        let link = dir.path().join("null.png");
        std::os::unix::fs::symlink("/dev/null", &link).unwrap();
        let o = raytracer(&[&scene, &link]);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        assert!(stderr(&o).contains("not a regular file"), "{}", stderr(&o));
        assert!(std::fs::symlink_metadata(&link).unwrap().is_symlink());
    }
}

/// A missing output folder is reported before the render: this render would take hours.
#[test]
fn an_unwritable_output_is_reported_before_rendering() {
    let (dir, scene) = write_scene(SMALL);
    let out = dir.path().join("missing/out.png");
    let o = raytracer(&[
        &scene,
        &out,
        &"--width",
        &"8000",
        &"--spp",
        &"4096",
        &"--max-pixels",
        &"100000000",
    ]);
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{msg}");
    assert!(msg.contains("does not exist"), "{msg}");
    assert_said_once(&msg);
}

/// Under a file-size limit (`ulimit -f`, in 1024-byte blocks) the write fails with a message, not
/// SIGXFSZ; the temporary file is removed and the earlier file kept.
#[cfg(unix)]
#[test]
fn a_file_size_limit_is_an_error_that_leaves_nothing_behind() {
    let (dir, scene) = write_scene(SMALL);
    for ext in ["png", "exr", "ppm"] {
        let out = dir.path().join(format!("out.{ext}"));
        std::fs::write(&out, b"earlier").unwrap();
        let o = Command::new("bash")
            .arg("-c")
            .arg("ulimit -f 1 && exec \"$0\" \"$1\" \"$2\" --width 256 --quiet")
            .arg(env!("CARGO_BIN_EXE_raytracer"))
            .arg(&scene)
            .arg(&out)
            .output()
            .unwrap();
        let msg = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{ext}: {msg}");
        assert!(msg.contains("File too large"), "{msg}");
        assert!(msg.contains("ulimit -f"), "{msg}");
        assert_eq!(std::fs::read(&out).unwrap(), b"earlier");
    }
    assert_eq!(
        names(dir.path()),
        vec!["out.exr", "out.png", "out.ppm", "scene.json"]
    );
}

/// NaN fails every threshold: an all-NaN image, one NaN pixel, and NaN given as a threshold.
#[test]
fn nan_fails_every_threshold() {
    let dir = tempfile::tempdir().unwrap();
    let good = Film::from_pixels(8, 8, vec![Vec3::splat(0.25); 64]);
    let mut one = good.clone();
    one.pixels[27] = Vec3::new(f32::NAN, 0.25, 0.25);
    let all = Film::from_pixels(8, 8, vec![Vec3::splat(f32::NAN); 64]);
    let paths: Vec<PathBuf> = ["good.exr", "one.exr", "all.exr"]
        .iter()
        .map(|n| dir.path().join(n))
        .collect();
    for (p, f) in paths.iter().zip([&good, &one, &all]) {
        write_image(p, f, ToneMap::Linear, 1.0).unwrap();
    }
    let o = raytracer(&[&"compare", &paths[0], &paths[0], &"--max-mse", &"0"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    for bad in &paths[1..] {
        for flag in ["--max-mse", "--max-flip"] {
            let o = raytracer(&[&"compare", &paths[0], bad, &flag, &"1"]);
            assert_eq!(o.status.code(), Some(3), "{flag} {}", stderr(&o));
            assert!(stderr(&o).contains("NaN"), "{}", stderr(&o));
        }
    }
    for value in ["nan", "NaN", "inf", "-1"] {
        for flag in ["--max-mse", "--max-flip"] {
            let o = raytracer(&[&"compare", &paths[0], &paths[0], &flag, &value]);
            assert_eq!(o.status.code(), Some(2), "{flag} {value}: {}", stderr(&o));
        }
    }
}

#[test]
fn study_with_a_nan_reference_fails_and_writes_no_results() {
    let (dir, scene) = write_scene(SMALL);
    let reference = dir.path().join("ref.exr");
    let mut f = Film::from_pixels(24, 16, vec![Vec3::splat(0.1); 24 * 16]);
    f.pixels[5] = Vec3::splat(f32::NAN);
    write_image(&reference, &f, ToneMap::Linear, 1.0).unwrap();
    let out = dir.path().join("study");
    let o = raytracer(&[
        &"study",
        &scene,
        &"--quick",
        &"--out",
        &out,
        &"--reference",
        &reference,
    ]);
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{msg}");
    assert!(
        msg.contains("non-finite") && msg.contains("ref.exr"),
        "{msg}"
    );
    assert!(names(&out).is_empty(), "{:?}", names(&out));
}

/// Every number on a command line is checked as its twin in the scene file is.
#[test]
fn nonsense_flags_are_usage_errors() {
    let (dir, scene) = write_scene(SMALL);
    let out = dir.path().join("out.png");
    let cases: &[&[&str]] = &[
        &["--exposure", "nan"],
        &["--exposure", "-1"],
        &["--exposure", "inf"],
        &["--adc-bailout", "nan"],
        &["--adc-bailout", "-0.5"],
        &["--adc-bailout", "2"],
        &["--threads", "0"],
        &["--spp", "0"],
    ];
    for extra in cases {
        let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![&scene, &out];
        for e in extra.iter() {
            args.push(e);
        }
        let o = raytracer(&args);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {}", stderr(&o));
    }
    for extra in [
        ["--threads", "0"],
        ["--adc-bailout", "nan"],
        ["--target-mse", "nan"],
    ] {
        let o = raytracer(&[&"study", &scene, &"--quick", &extra[0], &extra[1]]);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {}", stderr(&o));
    }
    assert!(!out.exists());
    assert_eq!(names(dir.path()), vec!["scene.json"]);
}

#[test]
fn control_characters_in_paths_are_escaped_in_messages() {
    let dir = tempfile::tempdir().unwrap();
    let evil = dir.path().join("evil\u{1b}[2J\nname.json");
    let o = raytracer(&[&evil, &dir.path().join("out.png")]);
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{msg}");
    assert!(msg.contains("evil\\u{1b}[2J\\nname.json"), "{msg}");
    assert!(!msg.contains('\u{1b}'), "{msg}");
    assert_said_once(&msg);
}

/// A full disk: a 16 KiB tmpfs (mounting needs root; elsewhere the case says it was not run).
/// The message is the OS's ("No space left on device"), not an encoder's, for every format.
#[cfg(target_os = "linux")]
#[test]
fn a_full_disk_says_so() {
    struct Mount(PathBuf);
    impl Drop for Mount {
        fn drop(&mut self) {
            let _ = Command::new("umount").arg(&self.0).status();
        }
    }
    let (_dir, scene) = write_scene(SMALL);
    let root = tempfile::tempdir().unwrap();
    let mounted = Command::new("mount")
        .args(["-t", "tmpfs", "-o", "size=16k", "tmpfs"])
        .arg(root.path())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !mounted {
        eprintln!("a_full_disk_says_so: not run (cannot mount a tmpfs here)");
        return;
    }
    let _mount = Mount(root.path().to_path_buf());
    // Fill it, so that even a small, well-compressed PNG does not fit.
    let filler = root.path().join("filler");
    let _ = std::fs::write(&filler, vec![7u8; 64 << 10]);
    for ext in ["png", "exr", "ppm"] {
        let out = root.path().join(format!("out.{ext}"));
        let o = raytracer(&[&scene, &out, &"--width", &"200", &"--quiet"]);
        let msg = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{ext}: {msg}");
        assert!(msg.contains("No space left on device"), "{msg}");
        assert_said_once(&msg);
        assert_eq!(names(root.path()), vec!["filler"]);
    }
}

/// An image file larger than any honest encoding of an allowed image is refused from its size
/// (decoders such as JPEG's read the whole file first): a sparse file, never read.
#[test]
fn an_oversized_image_file_is_refused_from_its_size() {
    let dir = tempfile::tempdir().unwrap();
    let tex = dir.path().join("huge.jpg");
    std::fs::File::create(&tex)
        .unwrap()
        .set_len(200 << 20)
        .unwrap();
    let scene = dir.path().join("scene.json");
    std::fs::write(
        &scene,
        r#"{ "camera": { "width": 8, "height": 6, "fov": 40 },
             "scene": { "shapes": [ { "type": "sphere", "center": [0, 0, -3], "radius": 1,
                                      "material": { "texture": "huge.jpg" } } ] } }"#,
    )
    .unwrap();
    let out = dir.path().join("out.png");
    let o = raytracer(&[&scene, &out, &"--max-texture-pixels", &"1024"]);
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{msg}");
    assert!(
        msg.contains("huge.jpg") && msg.contains("over the limit"),
        "{msg}"
    );
    assert!(msg.contains("--max-texture-pixels"), "{msg}");
    assert!(!out.exists());
}

/// Ctrl-C while a large mesh is read (a phase that does not look at the flag) still ends the
/// command with 130 and leaves the earlier image and no temporary file.
#[cfg(unix)]
#[test]
fn an_interrupt_while_reading_the_scene_ends_cleanly() {
    use std::fmt::Write as _;
    let dir = tempfile::tempdir().unwrap();
    let n = 400;
    let mut obj = String::new();
    for i in 0..n {
        for j in 0..n {
            writeln!(obj, "v {i} {j} {}", (i * j % 7) as f32 * 0.1).unwrap();
        }
    }
    for i in 0..n - 1 {
        for j in 0..n - 1 {
            let a = i * n + j + 1;
            writeln!(
                obj,
                "f {a} {} {}\nf {} {} {}",
                a + 1,
                a + n,
                a + 1,
                a + n + 1,
                a + n
            )
            .unwrap();
        }
    }
    std::fs::write(dir.path().join("big.obj"), obj).unwrap();
    let scene = dir.path().join("scene.json");
    std::fs::write(
        &scene,
        r#"{ "camera": { "width": 64, "height": 48, "fov": 40, "position": [200, -300, 200],
                          "lookat": [0, 1, -0.5], "up": [0, 0, 1] },
             "scene": { "lightsources": [ { "type": "pointlight", "position": [200, 200, 400], "intensity": [9, 9, 9] } ],
                        "shapes": [ { "type": "mesh", "filename": "big.obj", "material": { "kd": 0.5 } } ] } }"#,
    )
    .unwrap();
    let out = dir.path().join("out.png");
    std::fs::write(&out, b"an earlier render").unwrap();
    let child = Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .arg(&scene)
        .arg(&out)
        .args(["--spp", "4096", "--quiet"])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(100));
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let o = child.wait_with_output().unwrap();
    // On a machine so loaded that the signal came before the handler was installed, the default
    // action ended the process instead; nothing may be left behind either way.
    use std::os::unix::process::ExitStatusExt;
    if o.status.signal() != Some(2) {
        assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
        assert!(stderr(&o).contains("no image written"), "{}", stderr(&o));
    }
    assert_eq!(std::fs::read(&out).unwrap(), b"an earlier render");
    assert_eq!(names(dir.path()), vec!["big.obj", "out.png", "scene.json"]);
}

/// A study stopped by SIGTERM while it renders its reference ends with 130 and leaves none of its
/// temporary outputs (CSV, plot, reference) in its folder.
#[cfg(unix)]
#[test]
fn an_interrupted_study_leaves_no_temporary_files() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("study");
    let child = Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .arg("study")
        .arg(repo().join("scenes/penumbra.json"))
        .arg("--out")
        .arg(&out)
        .args(["--reference-samples", "65536"])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Wait until the study has created its folder (and so its temporary outputs).
    let start = Instant::now();
    while !out.is_dir() && start.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(200));
    let killed = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
    assert!(stderr(&o).contains("no results written"), "{}", stderr(&o));
    assert!(names(&out).is_empty(), "{:?}", names(&out));
}
