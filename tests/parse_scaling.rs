//! Loading stays linear in the size of the file, whatever its shape: objects with tens of
//! thousands of members, hundreds of thousands of warnings on one line, long material libraries.
//! Work is counted in steps ([`work_count`]), never timed: each hostile file is generated at two
//! sizes and the larger may cost at most a little over twice the smaller.

use std::path::Path;

use raytracer::scene::json::work_count;
use raytracer::scene::{load_str, LoadOptions, Scene};

const CAMERA: &str = r#""camera": {"width": 4, "height": 4, "fov": 45, "position": [0, 0, 5], "lookat": [0, 0, -1]}"#;

/// Most growth in counted work allowed when the input doubles.
const MOST_GROWTH: f64 = 2.2;

fn joined(n: usize, item: impl Fn(usize) -> String) -> String {
    (0..n).map(item).collect::<Vec<_>>().join(", ")
}

/// A mesh written with `vertex`/`face` counts and one key per vertex and per face.
fn counted_mesh(n: usize) -> String {
    let faces = n / 3;
    format!(
        r#"{{{CAMERA}, "shapes": [{{"type": "trimesh", "vertex": {n}, {}, "face": {faces}, {}}}]}}"#,
        joined(n, |i| format!(
            r#""v{i}": [{}, {}, {}]"#,
            i % 7,
            i % 5,
            i % 3
        )),
        joined(faces, |i| format!(
            r#""f{i}": [{}, {}, {}]"#,
            3 * i,
            3 * i + 1,
            3 * i + 2
        )),
    )
}

/// A counted mesh (which the loader asks for one key per vertex and face) that also holds `n`
/// keys the loader does not know: each is compared with the names asked of the mesh.
fn counted_mesh_with_unknown_keys(n: usize) -> String {
    let mesh = counted_mesh(n);
    let at = mesh.find(r#""vertex""#).unwrap();
    format!("{}{}, {}", &mesh[..at], unknown_keys(n), &mesh[at..])
}

fn unknown_keys(n: usize) -> String {
    joined(n, |i| format!(r#""unknown{i}": {i}"#))
}

/// The `scene` object with `n` members the loader does not know.
fn scene_with_unknown_keys(n: usize) -> String {
    format!(
        r#"{{{CAMERA}, "scene": {{{}, "shapes": [{{"type": "sphere", "center": [0, 0, 0], "radius": 1}}]}}}}"#,
        unknown_keys(n)
    )
}

/// One shape with `n` members the loader does not know.
fn shape_with_unknown_keys(n: usize) -> String {
    format!(
        r#"{{{CAMERA}, "shapes": [{{"type": "sphere", "center": [0, 0, 0], "radius": 1, {}}}]}}"#,
        unknown_keys(n)
    )
}

/// `n` shapes of an unknown type, each a warning, all on one line.
fn warnings_on_one_line(n: usize) -> String {
    format!(
        r#"{{{CAMERA}, "shapes": [{}]}}"#,
        joined(n, |_| r#"{"type": "spher"}"#.to_string())
    )
}

/// `n` named materials, each used by one sphere (in the opposite order).
fn material_library(n: usize) -> String {
    format!(
        r#"{{{CAMERA}, "materials": [{}], "shapes": [{}]}}"#,
        joined(n, |i| format!(r#"{{"name": "m{i}", "kd": 0.5}}"#)),
        joined(n, |i| format!(
            r#"{{"type": "sphere", "center": [0, 0, {}], "radius": 0.1, "material": "m{}"}}"#,
            -(i as f64),
            n - 1 - i
        )),
    )
}

/// The scene and the work counted while loading it.
fn load_counted(text: &str) -> (Scene, u64) {
    let before = work_count();
    let scene = load_str(text, Path::new("hostile.json"), &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    (scene, work_count() - before)
}

/// Loads `file(n)` and `file(2n)`, checks each with `check`, and that the work at most about
/// doubled.
fn scales_linearly(name: &str, file: impl Fn(usize) -> String, check: impl Fn(usize, &Scene)) {
    let n = 10_000;
    let (small, small_work) = load_counted(&file(n));
    let (large, large_work) = load_counted(&file(2 * n));
    check(n, &small);
    check(2 * n, &large);
    let growth = large_work as f64 / small_work as f64;
    assert!(
        growth <= MOST_GROWTH,
        "{name}: {small_work} steps for {n}, {large_work} for {} (×{growth:.2})",
        2 * n
    );
}

#[test]
fn a_mesh_with_a_key_per_vertex_loads_in_linear_work() {
    scales_linearly("counted mesh", counted_mesh, |n, s| {
        assert_eq!(s.primitives.len(), n / 3)
    });
}

#[test]
fn objects_with_many_unknown_keys_load_in_linear_work() {
    // One warning per unknown key.
    scales_linearly("scene object", scene_with_unknown_keys, |n, s| {
        assert_eq!(s.primitives.len(), 1);
        assert_eq!(s.warnings.len(), n);
    });
    scales_linearly("shape", shape_with_unknown_keys, |n, s| {
        assert_eq!(s.primitives.len(), 1);
        assert_eq!(s.warnings.len(), n);
    });
    scales_linearly(
        "counted mesh with unknown keys",
        counted_mesh_with_unknown_keys,
        |n, s| {
            assert_eq!(s.primitives.len(), n / 3);
            assert_eq!(s.warnings.len(), n);
        },
    );
}

#[test]
fn warnings_on_one_line_load_in_linear_work() {
    scales_linearly("warnings", warnings_on_one_line, |n, s| {
        assert_eq!(s.warnings.len(), n);
        assert!(s.primitives.is_empty());
    });
}

#[test]
fn warnings_on_one_line_keep_their_columns() {
    let text = warnings_on_one_line(3);
    let (scene, _) = load_counted(&text);
    let columns: Vec<usize> = scene.warnings.iter().map(|w| w.location.column).collect();
    // Each warning points at its `"spher"` string: find them in the text.
    let expected: Vec<usize> = text
        .match_indices(r#""spher""#)
        .map(|(i, _)| text[..i].chars().count() + 1)
        .collect();
    assert_eq!(columns, expected);
}

#[test]
fn a_long_material_library_loads_in_linear_work() {
    scales_linearly("material library", material_library, |n, s| {
        assert_eq!(s.primitives.len(), n);
        assert_eq!(s.materials.len(), n);
    });
}
