//! Which scenes a batch renders, and what their outputs and reference images are called: the
//! command line's files and folders, one unique output name per scene, and the reference image
//! found for that name.

use std::collections::HashSet;
use std::path::{Component, Path, PathBuf};

use raytracer::files::shown;

/// The separator between the parent folders and the stem in an output name (`folder__stem`).
pub const NAME_SEPARATOR: &str = "__";

/// Extensions of reference images, in the order they are looked for.
pub const REFERENCE_EXTENSIONS: [&str; 5] = ["png", "ppm", "exr", "jpg", "jpeg"];

/// One entry of a batch: a scene file, or a folder that could not be read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Source {
    pub path: PathBuf,
    /// Why the entry cannot be rendered at all (a folder that could not be listed).
    pub error: Option<String>,
}

/// Whether `path` ends in `.json` (without regard to case).
fn is_json(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"))
}

/// Where `path` is, resolved through links: the path itself if it exists, else its folder's
/// resolved path and its name (for an output not written yet).
fn resolved(path: &Path) -> Option<PathBuf> {
    if let Ok(p) = path.canonicalize() {
        return Some(p);
    }
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    Some(folder.canonicalize().ok()?.join(path.file_name()?))
}

/// The scenes `args` name: a file as given (whatever its extension; a missing one fails when it
/// is loaded), a folder as its `.json` files (any case), recursively, sorted by path. Folders
/// and files in `skip` (the output folder, the summary) are not taken from folders; folders
/// reached twice (through links) are listed once. A scene named twice is kept at its first place.
pub fn collect_scenes(args: &[PathBuf], skip: &[PathBuf]) -> Vec<Source> {
    let skip: HashSet<PathBuf> = skip.iter().filter_map(|p| resolved(p)).collect();
    let mut seen = HashSet::new();
    let mut visited = HashSet::new();
    let mut out = Vec::new();
    for arg in args {
        let mut found = Vec::new();
        if arg.is_dir() {
            walk(arg, &skip, &mut visited, &mut found);
            found.sort_by(|a: &Source, b| a.path.cmp(&b.path));
        } else {
            found.push(Source {
                path: arg.clone(),
                error: None,
            });
        }
        for source in found {
            let key = resolved(&source.path).unwrap_or_else(|| source.path.clone());
            if seen.insert(key) {
                out.push(source);
            }
        }
    }
    out
}

/// Adds the `.json` files under `dir` to `out`, recursively, except what `skip` holds and folders
/// already `visited`; a folder that cannot be listed is added as a failed entry.
fn walk(
    dir: &Path,
    skip: &HashSet<PathBuf>,
    visited: &mut HashSet<PathBuf>,
    out: &mut Vec<Source>,
) {
    let key = dir.canonicalize().unwrap_or_else(|_| dir.to_path_buf());
    if skip.contains(&key) || !visited.insert(key) {
        return;
    }
    let unreadable = |e: std::io::Error| Source {
        path: dir.to_path_buf(),
        error: Some(format!("{}: cannot list the folder: {e}", shown(dir))),
    };
    let entries = match std::fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) => return out.push(unreadable(e)),
    };
    for entry in entries {
        let path = match entry {
            Ok(entry) => entry.path(),
            Err(e) => {
                out.push(unreadable(e));
                continue;
            }
        };
        if path.is_dir() {
            walk(&path, skip, visited, out);
        } else if is_json(&path) && !resolved(&path).is_some_and(|p| skip.contains(&p)) {
            out.push(Source { path, error: None });
        }
    }
}

/// The folder names above `path`, nearest first (from its resolved path where it exists).
fn parent_names(path: &Path) -> Vec<String> {
    let full = path
        .canonicalize()
        .or_else(|_| std::path::absolute(path))
        .unwrap_or_else(|_| path.to_path_buf());
    let mut names: Vec<String> = full
        .parent()
        .map(|p| {
            p.components()
                .filter_map(|c| match c {
                    Component::Normal(n) => Some(n.to_string_lossy().into_owned()),
                    _ => None,
                })
                .collect()
        })
        .unwrap_or_default();
    names.reverse();
    names
}

/// One output name per scene, unique without regard to case (for case-insensitive file
/// systems):
///
/// 1. the scene file's stem (`marking/alice/scene.json` → `scene`);
/// 2. where stems clash, the fewest parent folders that tell the scene from every other with
///    its stem are prefixed, each followed by `__` (`alice__scene`, `bob__scene`;
///    `2023__alice__scene` beside `2024__alice__scene`);
/// 3. a name still taken (files in one folder whose names differ only in case, or a stem such as
///    `alice__scene` itself) gets `-2`, `-3`, … in scene order.
pub fn output_names(scenes: &[&Path]) -> Vec<String> {
    let stems: Vec<String> = scenes
        .iter()
        .map(|p| match p.file_stem() {
            Some(s) if !s.is_empty() => s.to_string_lossy().into_owned(),
            _ => "scene".to_string(),
        })
        .collect();
    let lower_stems: Vec<String> = stems.iter().map(|s| s.to_lowercase()).collect();
    let parents: Vec<Vec<String>> = scenes.iter().map(|p| parent_names(p)).collect();
    let lower_parents: Vec<Vec<String>> = parents
        .iter()
        .map(|ps| ps.iter().map(|p| p.to_lowercase()).collect())
        .collect();
    // The `depth` nearest folders of scene `i`, as compared.
    let key = |i: usize, depth: usize| &lower_parents[i][..depth.min(lower_parents[i].len())];
    let mut by_stem: std::collections::HashMap<&str, Vec<usize>> = Default::default();
    for (i, stem) in lower_stems.iter().enumerate() {
        by_stem.entry(stem.as_str()).or_default().push(i);
    }
    let depth = |i: usize| -> usize {
        let others: Vec<usize> = by_stem[lower_stems[i].as_str()]
            .iter()
            .copied()
            .filter(|&j| j != i)
            .collect();
        if others.is_empty() {
            return 0;
        }
        (1..=parents[i].len())
            .find(|&d| others.iter().all(|&j| key(j, d) != key(i, d)))
            .unwrap_or(0)
    };
    let mut taken = HashSet::new();
    (0..scenes.len())
        .map(|i| {
            let mut parts: Vec<&str> = parents[i][..depth(i)].iter().map(String::as_str).collect();
            parts.reverse();
            parts.push(&stems[i]);
            let base = parts.join(NAME_SEPARATOR);
            let mut candidate = base.clone();
            let mut k = 2;
            while !taken.insert(candidate.to_lowercase()) {
                candidate = format!("{base}-{k}");
                k += 1;
            }
            candidate
        })
        .collect()
}

/// The reference image for the output `name` of the scene file `scene` in `dir`: the first of
/// `name.png`, `.ppm`, `.exr`, `.jpg`, `.jpeg` that exists; failing that, where `name` has
/// folders prefixed (scenes sharing a stem), the same for the scene's stem, so that
/// `alice/task1.json` and `bob/task1.json` are both compared with `task1.png`. Otherwise a
/// message saying where it looked.
pub fn find_reference(dir: &Path, name: &str, scene: &Path) -> Result<PathBuf, String> {
    let stem = scene
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .filter(|s| !s.is_empty() && s != name);
    for candidate in std::iter::once(name).chain(stem.as_deref()) {
        for ext in REFERENCE_EXTENSIONS {
            let path = dir.join(format!("{candidate}.{ext}"));
            if path.is_file() {
                return Ok(path);
            }
        }
    }
    let also = match &stem {
        Some(stem) => format!(", nor '{stem}.png' and the like"),
        None => String::new(),
    };
    Err(format!(
        "no reference image '{name}.png' (or .ppm, .exr, .jpg, .jpeg){also} in '{}'",
        shown(dir)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_stems_with_folders_only_where_stems_clash() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        for sub in ["alice", "bob", "x/alice", "c"] {
            std::fs::create_dir_all(d.join(sub)).unwrap();
        }
        let paths = [
            d.join("alice/scene.json"),
            d.join("bob/scene.json"),
            d.join("x/alice/scene.json"),
            d.join("c/only.json"),
            d.join("c/Only.JSON"),
        ];
        let refs: Vec<&Path> = paths.iter().map(PathBuf::as_path).collect();
        let names = output_names(&refs);
        let root = d.file_name().unwrap().to_string_lossy().into_owned();
        assert_eq!(
            names,
            vec![
                format!("{root}__alice__scene"),
                "bob__scene".to_string(),
                "x__alice__scene".to_string(),
                "only".to_string(),
                "Only-2".to_string(),
            ]
        );
    }

    #[test]
    fn folders_give_their_json_files_recursively_sorted_and_once() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        std::fs::create_dir_all(d.join("b/deep")).unwrap();
        std::fs::create_dir_all(d.join("out")).unwrap();
        for f in [
            "b/deep/z.json",
            "b/a.json",
            "c.JSON",
            "notes.txt",
            "out/s.json",
        ] {
            std::fs::write(d.join(f), "{}").unwrap();
        }
        let got = collect_scenes(&[d.to_path_buf(), d.join("b/a.json")], &[d.join("out")]);
        let names: Vec<PathBuf> = got
            .iter()
            .map(|s| s.path.strip_prefix(d).unwrap().into())
            .collect();
        assert_eq!(
            names,
            vec![
                PathBuf::from("b/a.json"),
                PathBuf::from("b/deep/z.json"),
                PathBuf::from("c.JSON")
            ]
        );
    }
}
