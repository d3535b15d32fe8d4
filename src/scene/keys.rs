//! Keys the loader never read. After a load, every member of an object the loader looked into
//! that no lookup returned is reported once per key name and file, at its first place, with the
//! nearest of the names the loader asked that object for:
//!
//! ```text
//! s.json:14:37: scene.shapes[2].material.specularexponnet: unknown key 'specularexponnet' (did you mean 'specularexponent'?); ignored
//! ```
//!
//! There is no list of known keys to keep in step with the loader: a key is known when the loader
//! reads it (`json::Node::unread_members` gives the rest). Objects the loader never looked into
//! (a library material nobody uses) are not searched, and neither is anything inside an unread
//! member. Keys the loader reads in some modes only are marked read in the others where they are
//! skipped (`json::Node::mark_read`).
//!
//! Keys that are harmless to ignore stay quiet: [`HARMLESS`], and comment keys (see
//! [`is_harmless`]).

use std::collections::HashMap;

use super::json::{same_key, work_count_add, Node};

/// Keys read nowhere and worth no warning, compared ignoring case; `parent.key` names a key only
/// in an object that is the value of `parent` (or an element of it).
pub const HARMLESS: &[&str] = &[
    // Labels and comments.
    "name",
    "id",
    "comment",
    "comments",
    "description",
    "note",
    "notes",
    "title",
    // Accelerator switches (`--accel` chooses here).
    "bvh",
    "use_bvh",
    "usebvh",
    "accelerator",
    // The output image (given on the command line).
    "output",
    // The JSON Schema an editor checks the file against.
    "$schema",
    // The model a shape was cut from, on shapes that are not meshes (a mesh's `model` is its file).
    "shapes.model",
    // A texture's size, read from the image itself.
    "twidth",
    "theight",
    "texture.width",
    "texture.height",
    "textures.width",
    "textures.height",
];

/// Unknown keys after this many distinct ones get no suggestion: each suggestion compares the key
/// with up to `json::MOST_NAMES_ASKED` names, and a hostile file can hold a million keys.
const MOST_SUGGESTIONS: usize = 1000;

/// Keys longer than this (in characters) get no suggestion: no key the loader asks for is near
/// that long, and the comparison costs the product of the lengths.
const LONGEST_SUGGESTED_KEY: usize = 64;

/// Whether `key`, a member of an object that is the value of `parent` (or an element of it), is
/// harmless to ignore: listed in [`HARMLESS`], or a comment key (one that starts with `_`, `#`
/// or `//`).
pub fn is_harmless(parent: Option<&str>, key: &str) -> bool {
    key.starts_with('_')
        || key.starts_with('#')
        || key.starts_with("//")
        || HARMLESS.iter().any(|h| match h.split_once('.') {
            Some((p, k)) => {
                k.eq_ignore_ascii_case(key) && parent.is_some_and(|q| p.eq_ignore_ascii_case(q))
            }
            None => h.eq_ignore_ascii_case(key),
        })
}

/// The key whose value holds the member at `path` (`texture` for `scene.shapes[0].texture.width`,
/// `textures` for `textures[2].width`), if any.
fn parent_key<'p>(path: &'p str, key: &str) -> Option<&'p str> {
    let mut holder = path.strip_suffix(key)?.strip_suffix('.')?;
    while holder.ends_with(']') {
        holder = &holder[..holder.rfind('[')?];
    }
    let last = holder.rsplit('.').next()?;
    (!last.is_empty()).then_some(last)
}

/// The warnings for the keys under `root` that the loader never read: one per key name, at its
/// first place in the file, as (place, message).
pub fn unknown_keys<'a, 't>(root: &Node<'a, 't>) -> Vec<(Node<'a, 't>, String)> {
    let mut firsts: Vec<(Node<'a, 't>, String, usize)> = Vec::new();
    let mut seen: HashMap<&'a str, usize> = HashMap::new();
    for unread in root.unread_members() {
        if is_harmless(parent_key(&unread.node.path, unread.key), unread.key) {
            continue;
        }
        if let Some(&i) = seen.get(unread.key) {
            firsts[i].2 += 1;
            continue;
        }
        let message = if unread.asked.iter().any(|a| same_key(a, unread.key)) {
            // Asked for but not returned: an earlier spelling of the same key was read instead.
            format!(
                "key '{}' is not read: another spelling of it, listed first in docs/scene-format.md, is; ignored",
                unread.key
            )
        } else {
            let hint = if firsts.len() < MOST_SUGGESTIONS {
                suggestion(unread.key, unread.asked.iter().map(|a| &**a))
            } else {
                String::new()
            };
            format!("unknown key '{}'{hint}; ignored", unread.key)
        };
        seen.insert(unread.key, firsts.len());
        firsts.push((unread.node, message, 0));
    }
    firsts
        .into_iter()
        .map(|(node, message, others)| {
            let message = match others {
                0 => message,
                1 => format!("{message} (also in 1 other place)"),
                n => format!("{message} (also in {n} other places)"),
            };
            (node, message)
        })
        .collect()
}

/// " (did you mean 'x'?)" when the nearest of `asked` is a likely misspelling of `key`, " (nearest
/// known key here: 'x')" otherwise, or nothing.
fn suggestion<'n>(key: &str, asked: impl Iterator<Item = &'n str>) -> String {
    let chars = key.chars().count();
    if chars > LONGEST_SUGGESTED_KEY {
        return String::new();
    }
    let lower = key.to_lowercase();
    let mut best: Option<((usize, usize), &str)> = None;
    for name in asked {
        let name_chars = name.chars().count();
        // The distance is at least the difference in length: skip names that cannot win.
        if best.is_some_and(|((d, _), _)| chars.abs_diff(name_chars) > d) {
            continue;
        }
        work_count_add(chars * name_chars);
        // Ignoring case first (`LookAt` is one edit from `lookAt`), then as written.
        let score = (
            strsim::levenshtein(&lower, &name.to_lowercase()),
            strsim::levenshtein(key, name),
        );
        if best.is_none_or(|(b, _)| score < b) {
            best = Some((score, name));
        }
    }
    match best {
        // A third of the key's characters changed is still a typo (two swapped letters are two
        // edits); more is another word.
        Some(((d, _), name)) if d <= (chars / 3).max(1) => format!(" (did you mean '{name}'?)"),
        Some((_, name)) => format!(" (nearest known key here: '{name}')"),
        None => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggestions_prefer_the_same_letters_in_any_case() {
        let asked = ["lookat", "lookAt", "fov"];
        assert_eq!(
            suggestion("LookAt", asked.iter().copied()),
            " (did you mean 'lookAt'?)"
        );
        assert_eq!(
            suggestion("specularexponnet", ["kd", "specularexponent"].into_iter()),
            " (did you mean 'specularexponent'?)"
        );
        assert_eq!(
            suggestion("animation path", asked.iter().copied()),
            " (nearest known key here: 'lookat')"
        );
        assert_eq!(suggestion(&"x".repeat(100), asked.iter().copied()), "");
    }

    #[test]
    fn comments_and_listed_keys_are_harmless() {
        for key in [
            "_comment", "// note", "#", "BVH", "use_bvh", "tWidth", "name",
        ] {
            assert!(is_harmless(None, key), "{key}");
        }
        for key in ["bvhx", "nbounce", "kd", "width"] {
            assert!(!is_harmless(None, key), "{key}");
        }
        assert!(is_harmless(Some("texture"), "width"));
        assert!(!is_harmless(Some("camera"), "width"));
    }

    #[test]
    fn the_parent_key_skips_array_indexes() {
        assert_eq!(
            parent_key("scene.shapes[0].texture.width", "width"),
            Some("texture")
        );
        assert_eq!(parent_key("texture[12].width", "width"), Some("texture"));
        assert_eq!(parent_key("width", "width"), None);
        assert_eq!(parent_key("[3].width", "width"), None);
    }
}
