//! Keys the loader never reads are warned about once per key and file, at the key's first place
//! and with the nearest key the loader asked that object for; harmless keys, objects the loader
//! never looked into and keys it reads only in other modes stay quiet.

use std::path::Path;

use raytracer::scene::{load_str, LoadOptions, Scene, Warning};

const CAMERA: &str = r#""camera": { "type": "pinhole", "width": 8, "height": 6, "fov": 40,
    "position": [0, -4, 1], "lookat": [0, 1, 0], "up": [0, 0, 1] }"#;

fn load(text: &str) -> Scene {
    load_str(text, Path::new("k.json"), &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// The warnings about unread keys.
fn key_warnings(scene: &Scene) -> Vec<&Warning> {
    scene
        .warnings
        .iter()
        .filter(|w| w.message.contains("key '"))
        .collect()
}

#[test]
fn a_misspelt_key_is_warned_once_at_its_first_place_with_a_suggestion() {
    let text = format!(
        r#"{{ {CAMERA}, "scene": {{ "lightsources": [],
  "shapes": [
    {{ "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": {{ "kd": 0.5 }} }},
    {{ "type": "sphere", "center": [2, 0, 0], "radius": 1,
      "material": {{ "kd": 0.5, "specularexponnet": 20 }} }},
    {{ "type": "sphere", "center": [4, 0, 0], "radius": 1,
      "material": {{ "specularexponnet": 30 }} }} ] }} }}"#
    );
    let scene = load(&text);
    let warnings = key_warnings(&scene);
    assert_eq!(warnings.len(), 1, "{:?}", scene.warnings);
    let w = warnings[0];
    assert_eq!(w.location.path, "scene.shapes[1].material.specularexponnet");
    // At the member's value on its line (line 6 of the text).
    let line = text.lines().nth(5).unwrap();
    assert_eq!(w.location.line, 6);
    assert_eq!(w.location.column, line.find("20").unwrap() + 1);
    assert_eq!(
        w.message,
        "unknown key 'specularexponnet' (did you mean 'specularexponent'?); ignored (also in 1 other place)"
    );
    // The misspelt value was not read: the default exponent stands.
    assert_eq!(
        scene.materials[1].exponent,
        raytracer::material::Material::default().exponent
    );
}

#[test]
fn harmless_keys_and_comments_are_quiet() {
    let text = format!(
        r#"{{ {CAMERA}, "_comment": "a test scene", "output": "out.ppm", "bvh": true,
  "scene": {{ "//": "lights first", "description": "one sphere", "use_bvh": false, "lightsources": [],
    "shapes": [ {{ "type": "sphere", "name": "ball", "id": 3, "center": [0, 0, 0], "radius": 1,
      "material": {{ "kd": 0.5, "comment": "matte" }} }} ] }} }}"#
    );
    let scene = load(&text);
    assert!(key_warnings(&scene).is_empty(), "{:?}", scene.warnings);
}

#[test]
fn an_unread_key_is_reported_but_not_what_it_holds() {
    let text = format!(
        r#"{{ {CAMERA}, "scene": {{ "lightsources": [],
    "shapes": [ {{ "type": "sphere", "center": [0, 0, 0], "radius": 1,
      "extras": {{ "kdd": 1, "more": [ {{ "x": 1 }} ] }} }} ] }} }}"#
    );
    let scene = load(&text);
    let paths: Vec<&str> = key_warnings(&scene)
        .iter()
        .map(|w| w.location.path.as_str())
        .collect();
    assert_eq!(paths, ["scene.shapes[0].extras"]);
}

#[test]
fn library_materials_warn_only_when_used() {
    let text = format!(
        r#"{{ {CAMERA}, "materials": [ {{ "name": "used", "kdd": 0.5 }}, {{ "name": "unused", "kss": 1 }} ],
  "scene": {{ "lightsources": [],
    "shapes": [ {{ "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "used" }} ] }} }}"#
    );
    let scene = load(&text);
    let warnings = key_warnings(&scene);
    assert_eq!(warnings.len(), 1, "{:?}", scene.warnings);
    assert_eq!(warnings[0].location.path, "materials[0].kdd");
    assert!(warnings[0].message.contains("did you mean 'kd'?"));
}

#[test]
fn keys_read_in_other_modes_and_skipped_objects_are_quiet() {
    // A texture in binary mode, the lens of a camera typed pinhole (which has the lens it gives),
    // an object of an unknown type.
    let text = r#"{ "rendermode": "binary",
  "camera": { "type": "pinhole", "width": 8, "height": 6, "fov": 40, "aperture": 0.1, "focusdistance": 3,
              "samplesize": 16 },
  "scene": { "lightsources": [ { "type": "spotlight", "cone": 30 } ],
    "shapes": [ { "type": "sphere", "center": [0, 0, -3], "radius": 1,
                  "material": { "kd": 0.5, "tPath": "not-read.png" } },
                { "type": "torus", "radius1": 1, "radius2": 0.2 } ] } }"#;
    let scene = load(text);
    assert!(key_warnings(&scene).is_empty(), "{:?}", scene.warnings);
    // The unknown types are still warned about, once each.
    assert_eq!(scene.warnings.len(), 2, "{:?}", scene.warnings);
    assert!(scene.camera.lens.is_some());
    assert_eq!(scene.pixel_samples, Some(16));
}

#[test]
fn a_second_spelling_beside_the_one_read_is_named_as_such() {
    let text = format!(
        r#"{{ {CAMERA}, "scene": {{ "lightsources": [],
    "shapes": [ {{ "type": "sphere", "center": [0, 0, 0], "radius": 1,
      "material": {{ "diffusecolor": [1, 0, 0], "colour": [0, 1, 0] }} }} ] }} }}"#
    );
    let scene = load(&text);
    let warnings = key_warnings(&scene);
    assert_eq!(warnings.len(), 1, "{:?}", scene.warnings);
    assert_eq!(warnings[0].location.path, "scene.shapes[0].material.colour");
    assert!(
        warnings[0].message.contains("another spelling"),
        "{}",
        warnings[0].message
    );
}

#[test]
fn a_file_without_a_scene_fails_and_an_empty_scene_warns() {
    let e = load_str(
        &format!("{{ {CAMERA}, \"shape\": {{}} }}"),
        Path::new("k.json"),
        &LoadOptions::default(),
    )
    .err()
    .map(|e| e.to_string())
    .unwrap_or_default();
    assert!(
        e.starts_with("k.json:1:1: (root): nothing to render"),
        "{e}"
    );
    let scene = load(&format!(
        r#"{{ {CAMERA}, "scene": {{ "shapes": [], "lightsources": [] }} }}"#
    ));
    assert_eq!(scene.warnings.len(), 1, "{:?}", scene.warnings);
    assert_eq!(scene.warnings[0].location.path, "scene");
    assert!(scene.warnings[0]
        .message
        .contains("no shapes and no lights"));
    // Top-level lists are a scene too.
    let scene = load(&format!(
        r#"{{ {CAMERA}, "shapes": [ {{ "type": "sphere", "center": [0, 0, 0], "radius": 1 }} ] }}"#
    ));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

#[test]
fn scene_sample_counts_are_read_with_their_spellings() {
    let with = |keys: &str, camera_type: &str| {
        load(&format!(
            r#"{{ {keys} "camera": {{ "type": "{camera_type}", "width": 8, "height": 6, "fov": 40,
                 "aperture": 0.2, "focusdistance": 4, "samplesize": 9 }},
                 "scene": {{ "lightsources": [], "shapes": [] }} }}"#
        ))
    };
    let s = with(r#""pixelsample": 32, "lightsample": 4,"#, "pinhole");
    assert_eq!((s.pixel_samples, s.light_samples), (Some(32), Some(4)));
    // One count for both.
    let s = with(r#""sample_number": 15,"#, "pinhole");
    assert_eq!((s.pixel_samples, s.light_samples), (Some(15), Some(15)));
    let s = with(r#""camera samples": 8, "shadow samples": 2,"#, "pinhole");
    assert_eq!((s.pixel_samples, s.light_samples), (Some(8), Some(2)));
    // A camera's lens samples are its samples per pixel, whatever its type when it gives an
    // aperture.
    assert_eq!(with("", "thinlens").pixel_samples, Some(9));
    assert_eq!(with("", "pinhole").pixel_samples, Some(9));
    // The top level wins over the camera; 0 means one sample.
    assert_eq!(with(r#""nspp": 0,"#, "thinlens").pixel_samples, Some(1));
}
