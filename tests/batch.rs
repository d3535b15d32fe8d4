//! `raytracer batch`: many scenes in one run, each image the bytes `raytracer SCENE OUT` writes,
//! failures reported per scene, the summary, comparisons with references and the HTML report.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::*;

/// A 32×32 scene: a sphere of `colour` on a floor under an area light.
fn scene(colour: &str) -> String {
    format!(
        r#"{{ "nbounces": 1,
  "camera": {{ "type": "pinhole", "width": 32, "height": 32, "fov": 40,
              "position": [0, -4, 1], "lookat": [0, 1, -0.1], "up": [0, 0, 1] }},
  "scene": {{ "backgroundcolor": [0.1, 0.1, 0.1],
    "lightsources": [ {{ "type": "arealight", "v0": [-1, -1, 3], "v1": [1, -1, 3], "v2": [1, 1, 3], "v3": [-1, 1, 3],
                        "samples": 2, "method": "random", "is": [40, 40, 40], "id": [40, 40, 40] }} ],
    "shapes": [ {{ "type": "sphere", "center": [0, 0, 0.5], "radius": 0.5,
                  "material": {{ "kd": 0.8, "ks": 0.2, "specularexponent": 8, "diffusecolor": [{colour}] }} }},
                {{ "type": "quad", "v0": [-3, -3, 0], "v1": [3, -3, 0], "v2": [3, 3, 0], "v3": [-3, 3, 0],
                  "material": {{ "kd": 0.7, "diffusecolor": [0.8, 0.8, 0.8] }} }} ] }} }}"#
    )
}

/// A folder `scenes` with two good scenes (`red.json`, `blue.json`) and one broken one.
fn scene_folder(root: &Path) -> PathBuf {
    let dir = root.join("scenes");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("red.json"), scene("0.9, 0.2, 0.1")).unwrap();
    std::fs::write(dir.join("blue.json"), scene("0.1, 0.3, 0.9")).unwrap();
    std::fs::write(
        dir.join("broken.json"),
        r#"{ "camera": { "width": 32,, } }"#,
    )
    .unwrap();
    dir
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The CSV line of the summary whose scene path ends with `name`.
fn summary_line<'a>(summary: &'a str, name: &str) -> &'a str {
    summary
        .lines()
        .find(|l| l.split(',').next().is_some_and(|s| s.ends_with(name)))
        .unwrap_or_else(|| panic!("no line for {name} in\n{summary}"))
}

#[test]
fn good_scenes_are_the_single_render_bytes_and_a_broken_one_is_reported() {
    let tmp = tempfile::tempdir().unwrap();
    let scenes = scene_folder(tmp.path());
    let out = tmp.path().join("out");
    let flags = ["--spp", "3", "--seed", "7", "--tonemap", "srgb"];
    let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![&"batch", &scenes, &"--out", &out];
    args.extend(flags.iter().map(|f| f as &dyn AsRef<std::ffi::OsStr>));
    let o = raytracer(&args);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let err = stderr(&o);
    let broken_lines: Vec<&str> = err.lines().filter(|l| l.contains("broken.json")).collect();
    assert_eq!(broken_lines.len(), 1, "{err}");
    assert!(broken_lines[0].starts_with("error: "), "{err}");
    assert!(broken_lines[0].contains("invalid JSON"), "{err}");
    assert!(!out.join("broken.png").exists());

    for name in ["red", "blue"] {
        let single = tmp.path().join(format!("{name}-single.png"));
        let file = scenes.join(format!("{name}.json"));
        let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![&file, &single, &"-q"];
        args.extend(flags.iter().map(|f| f as &dyn AsRef<std::ffi::OsStr>));
        let s = raytracer(&args);
        assert!(s.status.success(), "{}", stderr(&s));
        assert_eq!(
            std::fs::read(out.join(format!("{name}.png"))).unwrap(),
            std::fs::read(&single).unwrap(),
            "{name}"
        );
    }

    // The same bytes on one thread.
    let one = tmp.path().join("one");
    let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> =
        vec![&"batch", &scenes, &"--out", &one, &"--threads", &"1", &"-q"];
    args.extend(flags.iter().map(|f| f as &dyn AsRef<std::ffi::OsStr>));
    assert_eq!(raytracer(&args).status.code(), Some(1));
    for name in ["red.png", "blue.png"] {
        assert_eq!(
            std::fs::read(one.join(name)).unwrap(),
            std::fs::read(out.join(name)).unwrap()
        );
    }

    let summary = read(&out.join("summary.csv"));
    let lines: Vec<&str> = summary.lines().collect();
    assert_eq!(
        lines[0],
        "scene,output,status,error,width,height,spp,seconds,rays,warnings"
    );
    assert_eq!(lines.len(), 4, "{summary}");
    // Sorted by path.
    assert!(lines[1].contains("blue.json") && lines[2].contains("broken.json"));
    let broken = summary_line(&summary, "broken.json");
    assert!(
        broken.contains(",,failed,") && broken.contains("invalid JSON"),
        "{broken}"
    );
    let red = summary_line(&summary, "red.json");
    assert!(red.contains("red.png,ok,,32,32,3,"), "{red}");
    // No temporary files are left.
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["blue.png", "red.png", "summary.csv"]);
}

#[test]
fn a_scene_over_a_limit_fails_alone_and_names_its_flag() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("scenes");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("small.json"), scene("0.9, 0.2, 0.1")).unwrap();
    let big = scene("0.1, 0.3, 0.9").replace(
        r#""width": 32, "height": 32"#,
        r#""width": 64, "height": 64"#,
    );
    std::fs::write(dir.join("big.json"), big).unwrap();
    let out = tmp.path().join("out");
    // 32 × 32 = 1,024 pixels are within the limit, 64 × 64 = 4,096 are not.
    let o = raytracer(&[
        &"batch",
        &dir,
        &"--out",
        &out,
        &"--max-pixels",
        &"2000",
        &"-q",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let summary = read(&out.join("summary.csv"));
    let big = summary_line(&summary, "big.json");
    assert!(
        big.contains(",failed,")
            && big.contains("over the limit of 2000 pixels")
            && big.contains("--max-pixels"),
        "{big}"
    );
    assert!(
        summary_line(&summary, "small.json").contains("small.png,ok,,32,32,"),
        "{summary}"
    );
    assert!(out.join("small.png").is_file() && !out.join("big.png").exists());
}

#[test]
fn references_pass_when_identical_and_fail_when_perturbed_with_a_report() {
    let tmp = tempfile::tempdir().unwrap();
    let scenes = tmp.path().join("scenes");
    std::fs::create_dir_all(&scenes).unwrap();
    std::fs::write(scenes.join("red.json"), scene("0.9, 0.2, 0.1")).unwrap();
    // A name that must be escaped in the page.
    let odd = "a&b <i>";
    std::fs::write(scenes.join(format!("{odd}.json")), scene("0.2, 0.8, 0.2")).unwrap();
    let golden = tmp.path().join("golden");
    let o = raytracer(&[&"batch", &scenes, &"--out", &golden, &"-q"]);
    assert!(o.status.success(), "{}", stderr(&o));

    let out = tmp.path().join("out");
    let o = raytracer(&[
        &"batch",
        &scenes,
        &"--out",
        &out,
        &"--reference",
        &golden,
        &"--max-flip",
        &"0.01",
        &"--summary",
        &tmp.path().join("summary.json"),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let summary = read(&tmp.path().join("summary.json"));
    assert!(
        summary.contains(r#""ok": 2, "failed": 0, "over_threshold": 0"#),
        "{summary}"
    );
    assert!(
        summary.contains(r#""mse": 0, "flip": 0, "pass": true"#),
        "{summary}"
    );
    let page = read(&out.join("report.html"));
    assert!(
        page.contains("a&amp;b &lt;i&gt;") && !page.contains("<i>"),
        "unescaped name"
    );
    assert!(page.matches("data:image/png;base64,").count() >= 6);

    // Perturb one reference: brighter everywhere.
    let reference = golden.join("red.png");
    let mut film = raytracer::image_io::read_image(&reference).unwrap();
    for p in &mut film.pixels {
        *p = (*p + raytracer::math::Vec3::splat(0.3)).min(raytracer::math::Vec3::ONE);
    }
    raytracer::image_io::write_image(&reference, &film, raytracer::film::ToneMap::Linear, 1.0)
        .unwrap();
    let report = tmp.path().join("marking.html");
    let o = raytracer(&[
        &"batch",
        &scenes,
        &"--out",
        &out,
        &"--reference",
        &golden,
        &"--max-flip",
        &"0.01",
        &"--report",
        &report,
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("red.json: mean FLIP"), "{}", stderr(&o));
    let summary = read(&out.join("summary.csv"));
    assert!(summary
        .lines()
        .next()
        .unwrap()
        .ends_with(",reference,mse,flip,pass"));
    let red = summary_line(&summary, "red.json");
    assert!(
        red.contains(",over-threshold,") && red.ends_with(",false"),
        "{red}"
    );
    let flip: f64 = red.split(',').nth(12).unwrap().parse().unwrap();
    assert!(flip > 0.01, "{red}");
    let page = read(&report);
    assert!(page.contains("1 over threshold") && page.contains("1 passed"));
    assert!(page.contains("<h2>red</h2>") && page.contains("a&amp;b &lt;i&gt;"));
    assert!(
        page.contains("mean FLIP") && page.contains("MSE") && page.contains(&format!("{flip:.4}"))
    );
    // Failures first.
    assert!(page.find("<h2>red</h2>").unwrap() < page.find("a&amp;b &lt;i&gt;").unwrap());
    assert!(!page.contains("http://") && !page.contains("https://"));

    // A missing reference and a size mismatch fail their scenes, with a message.
    std::fs::remove_file(&reference).unwrap();
    let o = raytracer(&[
        &"batch",
        &scenes,
        &"--out",
        &out,
        &"--reference",
        &golden,
        &"-q",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("no reference image 'red.png'"),
        "{}",
        stderr(&o)
    );
    let o = raytracer(&[
        &"batch",
        &scenes.join(format!("{odd}.json")),
        &"--out",
        &out,
        &"--reference",
        &golden,
        &"--width",
        &"16",
        &"-q",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("the render is 16×16 but the reference"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn scenes_sharing_a_stem_get_distinct_outputs() {
    let tmp = tempfile::tempdir().unwrap();
    for student in ["alice", "bob"] {
        let dir = tmp.path().join("submissions").join(student);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("scene.json"), scene("0.5, 0.5, 0.5")).unwrap();
    }
    let out = tmp.path().join("out");
    let o = raytracer(&[&"batch", &tmp.path().join("submissions"), &"--out", &out]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.join("alice__scene.png").is_file());
    assert!(out.join("bob__scene.png").is_file());

    // With no `alice__scene.png` in the reference folder, both are compared with `scene.png`.
    let model = tmp.path().join("model");
    std::fs::create_dir_all(&model).unwrap();
    std::fs::write(model.join("scene.json"), scene("0.5, 0.5, 0.5")).unwrap();
    let golden = tmp.path().join("golden");
    let o = raytracer(&[&"batch", &model, &"--out", &golden, &"-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = raytracer(&[
        &"batch",
        &tmp.path().join("submissions"),
        &"--out",
        &out,
        &"--reference",
        &golden,
        &"--max-flip",
        &"0",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary = read(&out.join("summary.csv"));
    assert_eq!(
        summary.matches("golden/scene.png,0,0,true").count(),
        2,
        "{summary}"
    );
}

#[test]
fn usage_errors_exit_2() {
    let tmp = tempfile::tempdir().unwrap();
    let scenes = scene_folder(tmp.path());
    let out = tmp.path().join("out");
    let empty = tmp.path().join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let nope = tmp.path().join("nope");
    let red = scenes.join("red.json");
    let cases: Vec<Vec<&dyn AsRef<std::ffi::OsStr>>> = vec![
        vec![&"batch", &"--out", &out],
        vec![&"batch", &scenes],
        vec![
            &"batch",
            &scenes,
            &"--out",
            &out,
            &"--reference",
            &scenes,
            &"--max-flip",
            &"NaN",
        ],
        vec![
            &"batch",
            &scenes,
            &"--out",
            &out,
            &"--reference",
            &scenes,
            &"--max-flip",
            &"-1",
        ],
        vec![&"batch", &scenes, &"--out", &out, &"--max-flip", &"0.1"],
        vec![&"batch", &scenes, &"--out", &out, &"--format", &"bmp"],
        vec![&"batch", &scenes, &"--out", &out, &"--summary", &"s.txt"],
        vec![&"batch", &scenes, &"--out", &out, &"--reference", &nope],
        vec![&"batch", &scenes, &"--out", &out, &"--reference", &out],
        vec![&"batch", &empty, &"--out", &out],
        vec![&"batch", &scenes, &"--out", &out, &"--summary", &red],
    ];
    for args in cases {
        let o = raytracer(&args);
        assert_eq!(o.status.code(), Some(2), "{:?}: {}", o.status, stderr(&o));
    }
    assert_eq!(read(&scenes.join("red.json")), scene("0.9, 0.2, 0.1"));
}

/// Ctrl-C stops the batch: exit 130, no summary, no temporary files.
#[cfg(unix)]
#[test]
fn an_interrupted_batch_leaves_no_partial_files() {
    let tmp = tempfile::tempdir().unwrap();
    let scenes = tmp.path().join("scenes");
    std::fs::create_dir_all(&scenes).unwrap();
    let demo = read(&repo().join("scenes/demo.json"));
    for i in 0..4 {
        std::fs::write(scenes.join(format!("demo{i}.json")), &demo).unwrap();
    }
    let out = tmp.path().join("out");
    let child = Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .arg("batch")
        .arg(&scenes)
        .arg("--out")
        .arg(&out)
        .arg("--asset-dir")
        .arg(repo().join("scenes"))
        .args(["--spp", "64", "--quiet"])
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(700));
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
    assert!(stderr(&o).contains("no summary or report written"));
    for entry in std::fs::read_dir(&out).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        assert!(name.ends_with(".png") && name.starts_with("demo"), "{name}");
    }
}
