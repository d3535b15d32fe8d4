//! Three students' renders of the CGR course's test scenes
//! (`../shared/coursework/corpus/reference/student_renders/`: Trenza1ore, chxag, HlnnnWnng) were
//! the first evidence for the CGR conventions. The course's own renders
//! (`../shared/coursework/official/cgr2024/`, tested in `tests/official_cgr.rs`) outrank them, and
//! the students disagree with the course by 10 to 44 of 255. So this test asks that our render sit
//! where the course's picture sits among the students: for every student render, our distance to
//! it is the course picture's distance to it within 1.5 of 255 (mean absolute difference of 8-bit
//! values, all channels; our render as the `render` command writes it). A convention that moved
//! us towards one student and away from the course would fail it.

mod common;

use std::path::{Path, PathBuf};

use common::{cgr_render, mean_abs_diff, read_rgb8, Rgb8};

const STUDENTS: [&str; 3] = [
    "Trenza1ore__std-raytracer__TestSuite__",
    "chxag__CGR-Raytracing-CW2__TestSuite__",
    "HlnnnWnng__High-Performance-Raytracer-Image-Render__TestSuite__",
];

/// The course's test scenes, as the students' renders name them, the scene file each comes from
/// (the course ships `scene.json` in binary mode; `phong_scene` is the same file in phong mode),
/// and the course's picture of it.
const SCENES: [(&str, &str, Option<&str>, &str); 5] = [
    ("phong_scene", "scene.json", Some("phong"), "scene_phong"),
    ("binary_scene", "scene.json", None, "scene_binary"),
    ("simple_phong", "simple_phong.json", None, "simple_phong"),
    ("mirror_image", "mirror_image.json", None, "mirror_image"),
    (
        "binary_primitives",
        "binary_primitives.json",
        None,
        "binary_primitives",
    ),
];

/// Largest difference between our distance to a student's render and the course picture's.
const TOLERANCE: f64 = 1.5;

fn corpus_dir() -> Option<PathBuf> {
    let dir = match std::env::var_os("RAYTRACER_CORPUS") {
        Some(d) => PathBuf::from(d),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/coursework/corpus"),
    };
    dir.join("reference/student_renders")
        .is_dir()
        .then_some(dir)
}

/// Our render of a test scene, from the corpus's copy of the course's files.
fn our_render(corpus: &Path, file: &str, mode: Option<&str>) -> Rgb8 {
    cgr_render(
        &corpus.join(format!("chxag__CGR-Raytracing-CW2__TestSuite__{file}")),
        mode,
    )
}

fn student_render(corpus: &Path, student: &str, name: &str) -> Option<Rgb8> {
    read_rgb8(&corpus.join(format!("reference/student_renders/{student}{name}.png")))
}

#[test]
fn cgr_test_scenes_sit_among_the_students_renders_where_the_course_does() {
    let Some(corpus) = corpus_dir() else {
        eprintln!("corpus not found next to the repository; set RAYTRACER_CORPUS to run this test");
        return;
    };
    let official = corpus.join("../official/cgr2024");
    let mut failures = Vec::new();
    for (name, file, mode, picture) in SCENES {
        let Some((_, _, course)) = read_rgb8(&official.join(format!("{picture}.png"))) else {
            eprintln!("{name}: the course's picture is missing; skipped");
            continue;
        };
        let (w, h, ours) = our_render(&corpus, file, mode);
        assert_eq!((w, h), (1200, 800), "{name}");
        let mut row = Vec::new();
        for student in STUDENTS {
            let Some((sw, sh, theirs)) = student_render(&corpus, student, name) else {
                continue;
            };
            assert_eq!((sw, sh), (1200, 800), "{student}{name}");
            let who = student.split("__").next().unwrap_or(student);
            let (d_ours, d_course) = (
                mean_abs_diff(&ours, &theirs),
                mean_abs_diff(&course, &theirs),
            );
            row.push(format!("{who} {d_ours:.1} (course {d_course:.1})"));
            if (d_ours - d_course).abs() > TOLERANCE {
                failures.push(format!(
                    "{name}: {d_ours:.1} from {who}'s render, where the course's picture is {d_course:.1}"
                ));
            }
        }
        assert!(row.len() >= 2, "{name}: fewer than two student renders");
        println!("{name:18} ours to each student: {}", row.join(", "));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
