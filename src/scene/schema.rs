//! The JSON Schema (draft-07) of the scene format, all variants at once, generated from the
//! loader's tables ([`tables`]) so that editors can complete and check a scene while
//! it is written (`docs/schema.md`).
//!
//! Each kind of object is a definition. Its keys match as the loader matches them, ignoring case
//! and the separators `_`, `-` and space, so each spelling is a pattern; `properties` repeats the
//! first spelling of each concept, with its description, for completion. A key the loader would
//! warn about as unknown fails validation, and so does a value of the wrong form or a missing
//! `type`. Values are checked for their form only: ranges, files and what a combination of keys
//! means are the loader's to say (`raytracer check`). Every kind of object accepts the keys of
//! every one of its types (a point light's schema accepts a `radius`).

use std::collections::BTreeMap;

use serde_json::{json, Map, Value as Json};

use super::json::{folded_key, same_key};
use super::keys::HARMLESS;
use super::load::spellings::{describe, tables, Key, Spelling, Table, Value};

/// The draft the schema follows: the newest that editors' JSON tools all read.
pub const DRAFT: &str = "http://json-schema.org/draft-07/schema#";

/// What the separators-and-case-blind key comparison skips between letters.
const SEPARATORS: &str = "[-_ ]*";

/// The schema as a JSON value.
pub fn schema() -> Json {
    let tables = tables();
    let mut definitions = Map::new();
    let mut root = Map::new();
    for t in &tables {
        let object = object_schema(t, &tables);
        match t.entity {
            "top level" => root = object,
            name => {
                definitions.insert(name.to_string(), Json::Object(object));
            }
        }
    }
    let mut out = Map::new();
    out.insert("$schema".into(), json!(DRAFT));
    out.insert("title".into(), json!("raytracer scene"));
    out.insert(
        "description".into(),
        json!(
            "A scene of the coursework ray-tracing format (2019, 2021–23 and CGR 2024+), as \
             raytracer reads it. Keys match ignoring case and the separators _, - and space."
        ),
    );
    out.extend(root);
    out.insert("definitions".into(), Json::Object(definitions));
    Json::Object(out)
}

/// The schema as the text of `docs/scene.schema.json`.
pub fn text() -> String {
    let mut s = serde_json::to_string_pretty(&schema()).expect("a JSON value always serialises");
    s.push('\n');
    s
}

/// One key of an object: its spellings' value schemas merged, and what it is.
struct Member {
    /// The spelling as the table writes it, for `properties`.
    name: &'static str,
    numbered: bool,
    values: Vec<Value>,
    concepts: Vec<&'static str>,
}

/// The schema of one kind of object.
fn object_schema(t: &Table, tables: &[Table]) -> Map<String, Json> {
    // Keys by the name the loader compares (folded), each with every value it may take here.
    let mut members: BTreeMap<(String, bool), Member> = BTreeMap::new();
    for k in &t.keys {
        for name in k.names {
            let m = members
                .entry((folded_key(name), k.numbered))
                .or_insert(Member {
                    name,
                    numbered: k.numbered,
                    values: Vec::new(),
                    concepts: Vec::new(),
                });
            if !m.values.contains(&k.value) {
                m.values.push(k.value);
            }
            if !m.concepts.contains(&k.concept) {
                m.concepts.push(k.concept);
            }
        }
    }
    // One pattern for all the keys that take the same values.
    let mut groups: BTreeMap<(String, bool), (Json, Vec<&str>)> = BTreeMap::new();
    let mut properties = Map::new();
    for m in members.values() {
        let value = either(&m.values);
        groups
            .entry((value.to_string(), m.numbered))
            .or_insert_with(|| (value, Vec::new()))
            .1
            .push(m.name);
        // Named for completion only: the pattern checks the value (a schema here too would
        // report each error twice).
        if !m.numbered && is_first_spelling(t, m.name) {
            let description = format!("{} ({})", m.concepts.join("; "), describe_all(&m.values));
            properties.insert(m.name.to_string(), json!({ "description": description }));
        }
    }
    let mut patterns = Map::new();
    for ((_, numbered), (value, names)) in groups {
        patterns.insert(key_pattern(&names, numbered), value);
    }
    // Keys read nowhere that the loader does not warn about: labels, comments, `$schema`.
    let harmless: Vec<String> = HARMLESS
        .iter()
        .filter_map(|h| match h.split_once('.') {
            Some((parent, name)) => holds(tables, parent, t.entity).then_some(name),
            None => Some(h),
        })
        .filter(|name| !members.contains_key(&(folded_key(name), false)))
        .map(case_letters)
        .collect();
    patterns.insert(format!("^({})$", harmless.join("|")), json!({}));
    patterns.insert("^(_|#|//)".into(), json!({}));
    let mut out = Map::new();
    out.insert("type".into(), json!("object"));
    out.insert("properties".into(), Json::Object(properties));
    out.insert("patternProperties".into(), Json::Object(patterns));
    out.insert("additionalProperties".into(), json!(false));
    if !t.required.is_empty() {
        let all: Vec<Json> = t
            .required
            .iter()
            .map(|names| one_of_present(names))
            .collect();
        out.insert("allOf".into(), Json::Array(all));
    }
    out
}

/// How the values are written, for a description.
fn describe_all(values: &[Value]) -> String {
    values
        .iter()
        .map(|v| describe(*v))
        .collect::<Vec<_>>()
        .join(" or ")
}

/// Whether `name` leads its row in `t` (the spelling the documentation and completion offer).
fn is_first_spelling(t: &Table, name: &str) -> bool {
    t.keys
        .iter()
        .any(|k| k.names.first().is_some_and(|first| *first == name))
}

/// Whether the objects under key `parent` (in any table) are of kind `entity`.
fn holds(tables: &[Table], parent: &str, entity: &str) -> bool {
    tables
        .iter()
        .flat_map(|t| &t.keys)
        .any(|k: &Key| k.names.iter().any(|n| same_key(n, parent)) && refers_to(k.value, entity))
}

/// Whether a value of this form holds objects of kind `entity`.
fn refers_to(value: Value, entity: &str) -> bool {
    match value {
        Value::Object(e) | Value::ListOf(e) => e == entity,
        Value::Either(vs) => vs.iter().any(|v| refers_to(*v, entity)),
        _ => false,
    }
}

/// A subschema true when the object has a key matching one of `names`.
fn one_of_present(names: &[&str]) -> Json {
    let pattern = key_pattern(names, false);
    json!({
        "description": format!("requires '{}'", names.join("' or '")),
        "not": {"propertyNames": {"not": {"pattern": pattern}}}
    })
}

/// The schema of a value that may take any of `values`.
fn either(values: &[Value]) -> Json {
    let mut all: Vec<Json> = Vec::new();
    for v in values {
        for s in alternatives(*v) {
            if !all.contains(&s) {
                all.push(s);
            }
        }
    }
    match all.len() {
        1 => all.pop().unwrap_or(Json::Null),
        _ => json!({ "anyOf": all }),
    }
}

/// The schemas of the forms `value` may take (more than one for a flag, a colour, an either).
fn alternatives(value: Value) -> Vec<Json> {
    let numbers = |n: usize| json!({"type": "array", "items": {"type": "number"}, "minItems": n, "maxItems": n});
    match value {
        Value::Number => vec![json!({"type": "number"})],
        Value::Whole => vec![json!({"type": "integer", "minimum": 0})],
        Value::Flag => vec![
            json!({"type": "boolean"}),
            json!({"type": "number"}),
            json!({"type": "string", "pattern": format!("^({}|{})$", case_letters("true"), case_letters("false"))}),
        ],
        Value::Text => vec![json!({"type": "string"})],
        Value::Vec3 => vec![numbers(3)],
        Value::Colour => vec![json!({"type": "number"}), numbers(3)],
        Value::Pair => vec![numbers(2)],
        Value::Numbers => vec![json!({"type": "array", "items": {"type": "number"}})],
        Value::Array => vec![json!({"type": "array"})],
        Value::Object(e) => vec![json!({"$ref": format!("#/definitions/{e}")})],
        Value::ListOf(e) => {
            vec![json!({"type": "array", "items": {"$ref": format!("#/definitions/{e}")}})]
        }
        Value::Word(spellings) => vec![word(spellings)],
        Value::Either(vs) => vs.iter().flat_map(|v| alternatives(*v)).collect(),
    }
}

/// A string naming one of `spellings`' concepts, as the loader compares names.
fn word(spellings: &[Spelling]) -> Json {
    let names: Vec<&str> = spellings
        .iter()
        .flat_map(|s| s.names.iter().copied())
        .collect();
    json!({
        "type": "string",
        "pattern": key_pattern(&names, false),
        "examples": names,
    })
}

/// The keys `names` as the loader matches them: any case, separators anywhere; a numbered key
/// is a name followed by a number.
fn key_pattern(names: &[&str], numbered: bool) -> String {
    let number = if numbered {
        format!("({SEPARATORS}[0-9])+")
    } else {
        String::new()
    };
    let alternatives: Vec<String> = names.iter().map(|n| letters(n)).collect();
    format!(
        "^{SEPARATORS}({}){number}{SEPARATORS}$",
        alternatives.join("|")
    )
}

/// The letters of `name` without its separators, any case, with separators between them.
fn letters(name: &str) -> String {
    folded_key(name)
        .chars()
        .map(|c| case_letters(&c.to_string()))
        .collect::<Vec<_>>()
        .join(SEPARATORS)
}

/// `text` in any case (`[Tt][Rr]…`), other characters as themselves.
fn case_letters(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_ascii_alphabetic() {
                format!("[{}{}]", c.to_ascii_uppercase(), c.to_ascii_lowercase())
            } else if r"\^$.|?*+()[]{}".contains(c) {
                format!("\\{c}")
            } else {
                c.to_string()
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn matches(pattern: &str, text: &str) -> bool {
        let schema = json!({"type": "string", "pattern": pattern});
        jsonschema::is_valid(&schema, &json!(text))
    }

    #[test]
    fn key_patterns_match_as_the_loader_compares() {
        let p = key_pattern(&["diffuseColor"], false);
        for spelled in [
            "diffusecolor",
            "DiffuseColor",
            "diffuse_color",
            "diffuse-Colour",
        ] {
            assert_eq!(
                matches(&p, spelled),
                same_key("diffuseColor", spelled),
                "{spelled}"
            );
        }
        let v = key_pattern(&["v"], true);
        assert!(matches(&v, "v0") && matches(&v, "V12") && matches(&v, "v_3"));
        assert!(!matches(&v, "v") && !matches(&v, "vs") && !matches(&v, "v0x"));
    }

    #[test]
    fn the_schema_is_a_valid_draft_07_schema() {
        let s = schema();
        let meta = jsonschema::draft7::meta::validate(&s);
        assert!(meta.is_ok(), "{:?}", meta.err());
    }
}
