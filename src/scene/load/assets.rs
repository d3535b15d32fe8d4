//! Where a scene's assets (textures, meshes) are found.

use std::path::{Component, Path, PathBuf};

use super::Loader;
use crate::files::input;
use crate::files::shown;
use crate::scene::json::Node;
use crate::scene::SceneError;

impl Loader<'_> {
    /// The first existing file among the scene's folder, the asset folders and the working
    /// directory joined with `rel`, recorded as one of the scene's inputs; one that is not a
    /// regular file is an error, never opened. An absolute path from another machine
    /// (`C:\Users\…\Textures\grass.ppm`) is looked for by its trailing parts, longest first.
    pub(super) fn find_asset(&mut self, node: &Node, rel: &str) -> Result<PathBuf, SceneError> {
        let rel_path = PathBuf::from(rel.replace('\\', "/"));
        let mut tried = Vec::new();
        let mut bases = vec![self.base.clone()];
        bases.extend(self.options.asset_dirs.iter().cloned());
        if let Ok(cwd) = std::env::current_dir() {
            bases.push(cwd);
        }
        let foreign = rel_path.is_absolute() || has_drive_letter(rel);
        let mut candidates: Vec<PathBuf> = if foreign {
            let parts: Vec<_> = rel_path
                .components()
                .filter(|c| matches!(c, Component::Normal(_)))
                .skip(usize::from(has_drive_letter(rel)))
                .collect();
            let mut c = vec![rel_path.clone()];
            for skip in 1..parts.len() {
                let tail: PathBuf = parts[skip..].iter().collect();
                c.extend(bases.iter().map(|b| b.join(&tail)));
            }
            c
        } else {
            bases.iter().map(|b| join_lexically(b, &rel_path)).collect()
        };
        // Last, the bare file name beside the scene (assets copied next to it).
        if let Some(name) = rel_path.file_name() {
            candidates.push(self.base.join(name));
        }
        for candidate in candidates {
            if let Ok(meta) = std::fs::metadata(&candidate) {
                if let Err(e) = input::check_regular(&meta) {
                    return Err(node.error(format!("cannot read '{}': {e}", shown(&candidate))));
                }
                if !self.inputs.contains(&candidate) {
                    self.inputs.push(candidate.clone());
                }
                return Ok(candidate);
            }
            if !tried.contains(&candidate) {
                tried.push(candidate);
            }
        }
        // The first and the last candidates tried say where it was looked for.
        let list: Vec<String> = if tried.len() > 8 {
            let mut l: Vec<String> = tried[..4].iter().map(|p| shown(p).to_string()).collect();
            l.push(format!("{} more", tried.len() - 8));
            l.extend(
                tried[tried.len() - 4..]
                    .iter()
                    .map(|p| shown(p).to_string()),
            );
            l
        } else {
            tried.iter().map(|p| shown(p).to_string()).collect()
        };
        Err(node.error(format!(
            "file '{rel}' not found (tried {})",
            list.join(", ")
        )))
    }
}

/// `a` joined with `b`, with `.` and `..` removed lexically (so a folder named in the path need
/// not exist, as with paths written relative to a build folder).
fn join_lexically(a: &Path, b: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in a.join(b).components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                if !out.pop() {
                    out.push("..");
                }
            }
            other => out.push(other),
        }
    }
    out
}

/// Whether `path` starts with a Windows drive (`C:\` or `C:/`).
fn has_drive_letter(path: &str) -> bool {
    let b = path.as_bytes();
    b.len() >= 3 && b[0].is_ascii_alphabetic() && b[1] == b':' && matches!(b[2], b'\\' | b'/')
}
