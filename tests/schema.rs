//! The JSON Schema (`raytracer schema`, `docs/scene.schema.json`) against the loader, checked with
//! the `jsonschema` validator: the file in the repository is the one the tables generate; every
//! bundled scene and every corpus scene that loads without a warning validates; every corpus
//! scene with an unknown key, and every bad input whose error is one of form (a wrong type, a
//! missing `type` or camera), does not.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use raytracer::scene::schema;
use raytracer::scene::{load, LoadOptions};
use serde_json::Value;

fn validator() -> jsonschema::Validator {
    jsonschema::draft7::new(&schema::schema()).expect("the schema compiles")
}

/// The file's JSON, with comments and trailing commas as the loader (and an editor's JSON with
/// comments) reads them; `None` if it is not JSON.
fn read_json(path: &Path) -> Option<Value> {
    let text = std::fs::read_to_string(path).ok()?;
    jsonc_parser::parse_to_serde_value(&text, &Default::default()).ok()
}

/// The validator's errors for `path`, one line each with the instance's place.
fn errors(v: &jsonschema::Validator, json: &Value) -> Vec<String> {
    v.iter_errors(json)
        .map(|e| format!("{}: {e}", e.instance_path()))
        .collect()
}

#[test]
fn the_repository_schema_is_the_generated_one() {
    let path = common::repo().join("docs/scene.schema.json");
    let generated = schema::text();
    if std::env::var_os("RAYTRACER_UPDATE_DOCS").is_some() {
        std::fs::write(&path, &generated).unwrap();
        return;
    }
    let kept = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        kept == generated,
        "docs/scene.schema.json is out of date: rewrite it with RAYTRACER_UPDATE_DOCS=1 cargo test --release --test schema"
    );
    let o = common::raytracer(&[&"schema"]);
    assert!(o.status.success(), "{}", common::stderr(&o));
    assert_eq!(String::from_utf8_lossy(&o.stdout), generated);
}

#[test]
fn every_bundled_scene_validates() {
    let v = validator();
    let scenes = common::bundled_scenes();
    assert!(scenes.len() >= 10);
    for path in scenes {
        let scene = load(&path, &LoadOptions::default()).unwrap();
        let json = read_json(&path).expect("bundled scenes are JSON");
        let e = errors(&v, &json);
        assert!(
            scene.warnings.is_empty() && e.is_empty(),
            "{}: {:?} {e:?}",
            path.display(),
            scene.warnings
        );
    }
}

/// The corpus scenes' expected outcomes (`tests/corpus*_expected.tsv`): for each scene that
/// loads, its warnings.
fn corpus_outcomes() -> Vec<(PathBuf, Vec<String>)> {
    let shared = common::repo().join("../shared/coursework");
    let mut out = Vec::new();
    for (dir, list) in [
        ("corpus", "tests/corpus_expected.tsv"),
        ("corpus2", "tests/corpus2_expected.tsv"),
    ] {
        let dir = shared.join(dir);
        if !dir.join("MANIFEST.tsv").is_file() {
            continue;
        }
        let text = std::fs::read_to_string(common::repo().join(list)).unwrap();
        let mut scenes: BTreeMap<&str, Option<Vec<String>>> = BTreeMap::new();
        for line in text.lines().filter(|l| !l.starts_with('#')) {
            let cols: Vec<&str> = line.splitn(3, '\t').collect();
            match cols[..] {
                [file, "rendered"] => {
                    scenes.entry(file).or_insert_with(|| Some(Vec::new()));
                }
                [file, "warning", w] => {
                    if let Some(Some(ws)) = scenes.get_mut(file) {
                        ws.push(w.to_string());
                    }
                }
                _ => {}
            }
        }
        for (file, warnings) in scenes {
            if let Some(ws) = warnings {
                out.push((dir.join(file), ws));
            }
        }
    }
    out
}

#[test]
fn corpus_scenes_validate_exactly_when_they_load_without_unknown_keys() {
    let outcomes = corpus_outcomes();
    if outcomes.is_empty() {
        eprintln!("no corpus beside the repository: nothing to validate");
        return;
    }
    let v = validator();
    let (mut clean, mut unknown, mut not_json) = (0, 0, 0);
    let mut failures = Vec::new();
    for (path, warnings) in &outcomes {
        let Some(json) = read_json(path) else {
            not_json += 1;
            continue;
        };
        let e = errors(&v, &json);
        let name = path.file_name().unwrap().to_string_lossy();
        if warnings.is_empty() {
            clean += 1;
            if !e.is_empty() {
                failures.push(format!("{name} loads without warnings but fails: {e:?}"));
            }
        } else if warnings.iter().any(|w| w.contains("unknown key")) {
            unknown += 1;
            if e.is_empty() {
                failures.push(format!(
                    "{name} has an unknown key but validates: {warnings:?}"
                ));
            }
        }
    }
    eprintln!(
        "{clean} warning-free corpus scenes validate, {unknown} with an unknown key fail; \
         {not_json} are not JSON"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(clean >= 150 && unknown >= 1, "{clean} and {unknown}");
}

/// Whether a loader error is one of form: a value of the wrong JSON type, or a missing key the
/// schema requires.
fn is_structural(message: &str) -> bool {
    [
        "expected an object",
        "expected an array",
        "expected a number",
        "expected a string",
        "expected true or false",
        "expected a whole number",
        "is an object, found",
        "a scene is a JSON object",
        "missing required key 'type'",
        "missing required key 'camera'",
        "missing required key 'fov'",
    ]
    .iter()
    .any(|m| message.contains(m))
}

#[test]
fn bad_inputs_of_form_fail_validation() {
    let v = validator();
    let dir = common::repo().join("tests/bad_input");
    let mut structural = 0;
    let mut failures = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "json") {
            continue;
        }
        let Some(json) = read_json(&path) else {
            continue;
        };
        let Err(error) = load(&path, &LoadOptions::default()) else {
            continue;
        };
        let message = error.to_string();
        if is_structural(&message) {
            structural += 1;
            if errors(&v, &json).is_empty() {
                failures.push(format!("{}: {message}", path.display()));
            }
        }
    }
    eprintln!("{structural} bad inputs with an error of form fail validation");
    assert!(failures.is_empty(), "validate:\n{}", failures.join("\n"));
    assert!(structural >= 10, "{structural} structural bad inputs");
}

#[test]
fn a_misspelled_key_fails_where_it_is_and_a_schema_key_is_no_warning() {
    let text = r#"{"$schema": "../docs/scene.schema.json",
        "camera": {"width": 4, "height": 4, "fov": 45, "Look_At": [0, 0, -1]},
        "scene": {"shapes": [{"type": "sphere", "center": [0, 0, -3], "radius": 1,
                              "specularexponnet": 8}]}}"#;
    let json: Value = serde_json::from_str(text).unwrap();
    let e = errors(&validator(), &json);
    assert_eq!(e.len(), 1, "{e:?}");
    assert!(
        e[0].starts_with("/scene/shapes/0:") && e[0].contains("specularexponnet"),
        "{e:?}"
    );
    let scene = common::load_json(text);
    assert_eq!(scene.warnings.len(), 1, "{:?}", scene.warnings);
    assert!(scene.warnings[0].message.contains("specularexponnet"));
}

/// Every object of `json`, by its JSON pointer.
fn object_pointers(json: &Value, at: String, out: &mut Vec<String>) {
    match json {
        Value::Object(o) => {
            out.push(at.clone());
            for (k, v) in o {
                object_pointers(v, format!("{at}/{k}"), out);
            }
        }
        Value::Array(a) => {
            for (i, v) in a.iter().enumerate() {
                object_pointers(v, format!("{at}/{i}"), out);
            }
        }
        _ => {}
    }
}

#[test]
fn a_stray_key_fails_in_every_object_of_every_bundled_scene() {
    let v = validator();
    let mut checked = 0;
    for path in common::bundled_scenes() {
        let json = read_json(&path).unwrap();
        let mut pointers = Vec::new();
        object_pointers(&json, String::new(), &mut pointers);
        for p in pointers {
            let mut stray = json.clone();
            let object = stray
                .pointer_mut(&p)
                .and_then(Value::as_object_mut)
                .unwrap();
            object.insert("strayKey".into(), Value::Bool(true));
            let e = errors(&v, &stray);
            assert!(
                e.iter()
                    .any(|e| e.starts_with(&format!("{p}:")) && e.contains("strayKey")),
                "{} at '{p}': {e:?}",
                path.display()
            );
            checked += 1;
        }
    }
    assert!(checked > 100, "{checked} objects");
}
