//! Scratch space shared by the fuzz targets: one folder per fuzzing process under the system
//! temporary directory. Only the harness writes there (the input under test); the library code
//! under test only reads.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// This process's scratch folder, created on first use.
pub fn scratch() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("raytracer-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("create the fuzz scratch folder");
        dir
    })
}

/// Writes `data` to `name` in the scratch folder and returns its path.
pub fn write_input(name: &str, data: &[u8]) -> PathBuf {
    let path = scratch().join(name);
    std::fs::write(&path, data).expect("write the fuzz input");
    path
}
