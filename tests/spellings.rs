//! The spelling tables the loader reads through are the ones `docs/scene-format.md` shows, and
//! no name stands for two concepts of one kind of thing.

mod common;

use raytracer::scene::json::same_key;
use raytracer::scene::load::spellings::{markdown, tables};

const BEGIN: &str = "<!-- spellings: generated from src/scene/load/spellings/ -->\n";
const END: &str = "<!-- spellings: end -->";

#[test]
fn the_documentation_lists_every_spelling() {
    let path = common::repo().join("docs/scene-format.md");
    let doc = std::fs::read_to_string(&path).unwrap();
    let (start, end) = (
        doc.find(BEGIN).expect("the begin marker") + BEGIN.len(),
        doc.find(END).expect("the end marker"),
    );
    let generated = markdown();
    if std::env::var_os("RAYTRACER_UPDATE_DOCS").is_some() {
        let updated = format!("{}{generated}\n{}", &doc[..start], &doc[end..]);
        std::fs::write(&path, updated).unwrap();
        return;
    }
    assert_eq!(
        doc[start..end].trim(),
        generated.trim(),
        "docs/scene-format.md is out of date: rewrite it with RAYTRACER_UPDATE_DOCS=1"
    );
}

#[test]
fn no_type_name_stands_for_two_concepts() {
    for t in tables() {
        let names: Vec<(&str, &str)> = t
            .types
            .iter()
            .flat_map(|s| s.names.iter().map(move |n| (s.concept, *n)))
            .collect();
        for (i, (c1, n1)) in names.iter().enumerate() {
            for (c2, n2) in &names[i + 1..] {
                assert!(
                    !same_key(n1, n2),
                    "{}: '{n1}' ({c1}) and '{n2}' ({c2}) are one spelling",
                    t.entity
                );
            }
        }
    }
}

/// The files that read a scene's keys: each key they ask for is a constant of
/// `src/scene/load/spellings/`, so that the tables, the documentation and the schema list it.
const READERS: &[&str] = &[
    "src/scene/load/mod.rs",
    "src/scene/load/camera.rs",
    "src/scene/load/light.rs",
    "src/scene/load/material.rs",
    "src/scene/load/mesh.rs",
    "src/scene/load/shape.rs",
    "src/scene/load/texture.rs",
    "src/scene/lights.rs",
    "src/scene/poly_sphere.rs",
    "src/scene/rectangle.rs",
    "src/scene/transform.rs",
];

#[test]
fn the_loader_spells_no_key_outside_the_tables() {
    let lookups = [
        ".get(",
        ".peek(",
        ".get_any(",
        ".has_any(",
        ".contains_any(",
        ".mark_read(",
    ];
    let with_node_first = ["required(", "required_positive(", "opt_f32(", "opt_vec3("];
    let mut found = Vec::new();
    for file in READERS {
        let text = std::fs::read_to_string(common::repo().join(file)).unwrap();
        // Without whitespace, so that a call split over lines reads as one.
        let code: String = text
            .lines()
            .filter(|l| !l.trim_start().starts_with("//"))
            .collect::<String>()
            .split_whitespace()
            .collect();
        let literal = |rest: &str| rest.starts_with('"') || rest.starts_with("&[\"");
        for call in lookups {
            for (i, _) in code.match_indices(call) {
                let rest = &code[i + call.len()..];
                if literal(rest) {
                    found.push(format!("{file}: {call}{}", &rest[..rest.len().min(30)]));
                }
            }
        }
        for call in with_node_first {
            for (i, _) in code.match_indices(call) {
                let rest = &code[i + call.len()..];
                let Some(comma) = rest.find(',') else {
                    continue;
                };
                if literal(&rest[comma + 1..]) {
                    found.push(format!("{file}: {call}{}", &rest[..rest.len().min(30)]));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "keys written outside spellings/:\n{}",
        found.join("\n")
    );
}
