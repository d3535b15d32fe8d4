//! The spelling tables the loader reads through are the ones `docs/scene-format.md` shows, and
//! no name stands for two concepts of one kind of thing.

mod common;

use raytracer::scene::json::same_key;
use raytracer::scene::load::spellings::{markdown, tables};

const BEGIN: &str = "<!-- spellings: generated from src/scene/load/spellings.rs -->\n";
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
