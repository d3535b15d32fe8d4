//! Errors and warnings from reading a scene, each with the file and the place in it.

use std::fmt;
use std::path::PathBuf;

use crate::files::shown;

/// Where in a scene file something is: 1-based line and column, and the JSON path
/// (`scene.shapes[3].material.kd`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    pub file: PathBuf,
    pub line: usize,
    pub column: usize,
    pub path: String,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", shown(&self.file), self.line, self.column)?;
        if !self.path.is_empty() {
            write!(f, ": {}", self.path)?;
        }
        Ok(())
    }
}

/// Why a scene could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The scene file itself could not be read.
    #[error("{}: cannot read the scene file: {source}", shown(file))]
    Read {
        file: PathBuf,
        source: std::io::Error,
    },
    /// The text is not JSON (comments and trailing commas are accepted).
    #[error("{}:{line}:{column}: invalid JSON: {message}", shown(file))]
    Syntax {
        file: PathBuf,
        line: usize,
        column: usize,
        message: String,
    },
    /// A value is missing, of the wrong type, out of range, or refers to an asset that cannot be
    /// loaded.
    #[error("{location}: {message}")]
    Invalid { location: Location, message: String },
}

impl SceneError {
    /// The location, for errors that have one inside the file.
    pub fn location(&self) -> Option<&Location> {
        match self {
            SceneError::Invalid { location, .. } => Some(location),
            _ => None,
        }
    }
}

/// Something the loader skipped or interpreted, worth telling the user.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Warning {
    pub location: Location,
    pub message: String,
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.location, self.message)
    }
}
