//! Reading triangle meshes from PLY and Wavefront OBJ files.
//!
//! [`read_mesh`] picks the format from the file extension (`.ply` or `.obj`,
//! case-insensitive); [`read_ply`] and [`read_obj`] read one format directly. Each format has
//! its reader: `ply.rs` and `obj.rs`.
//! Both produce a [`MeshData`]: one shared vertex buffer (positions, and normals
//! and texture coordinates where the file gives them for every vertex) plus
//! triangles as indices into it.
//!
//! # What is refused
//!
//! Every problem is reported as a [`MeshFileError`] whose message names the file,
//! what is wrong and where: the line for ASCII PLY and OBJ where it is known,
//! otherwise the element or face number (counting from 0 in file order).
//! Nothing read from the file can cause a panic. Refused are:
//!
//! * empty files, unreadable files, text that is not UTF-8 where text is expected;
//! * malformed headers, missing `x`/`y`/`z` or face index lists, float index lists;
//! * element counts that cannot fit in the bytes following the PLY header. This
//!   is checked from the header alone before any payload is read or any buffer is
//!   sized, so a file claiming billions of vertices fails at once;
//! * data that ends early (truncated binary or missing ASCII lines) or does not parse;
//! * faces with fewer than three corners, negative indices, and indices that do
//!   not name an existing vertex (OBJ: also texture coordinate and normal indices,
//!   including relative indices reaching before the first entry and index `0`);
//! * non-finite (NaN or infinite) positions, normals or texture coordinates;
//! * more than 2^32 - 1 vertices (indices are `u32`);
//! * files without a single triangle, including PLY files without a `face` element.
//!
//! # Limits
//!
//! [`read_mesh_with`] takes [`MeshLimits`]. The file is read whole, so it must be a regular file
//! (a FIFO or a device is refused without blocking) of at most [`MeshLimits::max_bytes`]. The
//! triangles it asks for are counted before anything is built: the PLY header's face count (each
//! face is at least one triangle), then every face's fan as it is read; for OBJ, the corners of
//! every `f` line in the text, before it is handed to `tobj`. Going over what the scene's triangle
//! limit leaves is an error naming `--max-triangles`; memory the counts need past
//! [`MeshLimits::max_memory`] is an error naming `--max-memory`. The vertex, normal, texture
//! coordinate and triangle buffers are reserved fallibly, so a size the machine cannot hold is an
//! error.

use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};

use crate::files::input::{self, SizeLimit};
use crate::files::shown;
use crate::memory;

mod obj;
mod ply;

use obj::parse_obj;
use ply::parse_ply;

/// A triangle mesh as read from a file: shared vertex buffers and triangle indices.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MeshData {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Per-vertex normals, when the file has them for every vertex (PLY nx,ny,nz; OBJ vn).
    pub normals: Option<Vec<Vec3>>,
    /// Per-vertex texture coordinates, when the file has them (PLY u,v or s,t or texture_u/texture_v; OBJ vt).
    pub uvs: Option<Vec<Vec2>>,
    /// Triangles as indices into the vertex buffers; polygons are split into fans.
    pub faces: Vec<[u32; 3]>,
}

/// What one mesh file may ask for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MeshLimits {
    /// Largest file accepted, in bytes (flag `--max-mesh-bytes`).
    pub max_bytes: u64,
    /// The scene's limit on triangles, all meshes together (flag `--max-triangles`).
    pub max_triangles: usize,
    /// Triangles the scene already has before this file.
    pub triangles_before: usize,
    /// Memory the scene's meshes may take, all together (flag `--max-memory`; by default what
    /// the process can have): a file whose estimate ([`memory::mesh_bytes`]) does not fit
    /// beside the triangles before it is refused before it is read. `None`: not checked.
    pub max_memory: Option<u64>,
}

impl Default for MeshLimits {
    fn default() -> Self {
        MeshLimits {
            max_bytes: super::load::DEFAULT_MAX_MESH_BYTES,
            max_triangles: super::load::DEFAULT_MAX_TRIANGLES,
            triangles_before: 0,
            max_memory: None,
        }
    }
}

impl MeshLimits {
    /// Triangles this file may add.
    fn triangles_left(&self) -> u64 {
        self.max_triangles.saturating_sub(self.triangles_before) as u64
    }

    /// Refuses a file of `vertices` and `triangles` (at least) whose memory does not fit in
    /// [`MeshLimits::max_memory`] beside the triangles before it.
    fn check_memory(
        &self,
        path: &Path,
        vertices: u64,
        triangles: u64,
    ) -> Result<(), MeshFileError> {
        let Some(limit) = self.max_memory else {
            return Ok(());
        };
        let before = memory::mesh_bytes(0, self.triangles_before as u64);
        let needed = memory::mesh_bytes(vertices, triangles);
        if needed <= limit.saturating_sub(before) {
            return Ok(());
        }
        Err(MeshFileError::TooLargeForMemory {
            path: path.to_path_buf(),
            vertices,
            triangles,
            needed,
            available: limit.saturating_sub(before),
        })
    }

    /// The error for a file asking for more triangles than are left; `what` says how many.
    fn too_many_triangles(&self, path: &Path, line: Option<usize>, what: String) -> MeshFileError {
        MeshFileError::TooManyTriangles {
            path: path.to_path_buf(),
            line,
            what,
            limit: self.max_triangles,
            before: self.triangles_before,
        }
    }
}

/// Why a mesh file could not be read.
///
/// Every message starts with the file path, then the line in parentheses when it
/// is known. Vertex and face numbers count from 0 in file order; OBJ index values
/// are quoted as written in the file (1-based or negative).
#[derive(Debug, thiserror::Error)]
pub enum MeshFileError {
    /// The file could not be opened or read.
    #[error("{}: cannot read mesh file: {source}", shown(.path))]
    Io {
        /// The mesh file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// The extension is neither `.ply` nor `.obj`.
    #[error(
        "{}: unsupported mesh file extension {}; supported extensions are .ply and .obj",
        shown(.path),
        describe_extension(.extension)
    )]
    UnsupportedExtension {
        /// The mesh file.
        path: PathBuf,
        /// The extension found, if any.
        extension: Option<String>,
    },
    /// The file has no bytes at all.
    #[error("{}: file is empty", shown(.path))]
    Empty {
        /// The mesh file.
        path: PathBuf,
    },
    /// The file does not follow the format (syntax, header, structure, truncation).
    #[error("{}{}: {message}", shown(.path), line_suffix(.line))]
    Malformed {
        /// The mesh file.
        path: PathBuf,
        /// The 1-based line, when known.
        line: Option<usize>,
        /// What is wrong and where.
        message: String,
    },
    /// A PLY header declares more elements than the rest of the file can hold.
    #[error(
        "{}: the PLY header declares {count} '{element}' elements; with the elements before \
         them that needs at least {needed} bytes, but only {available} bytes follow the header \
         (truncated or corrupt file)",
        shown(.path)
    )]
    CountTooLarge {
        /// The mesh file.
        path: PathBuf,
        /// The element whose count does not fit.
        element: String,
        /// Its declared count.
        count: usize,
        /// Smallest payload size the header implies up to and including this element.
        needed: u64,
        /// Bytes present after the header.
        available: u64,
    },
    /// A face lists fewer than three corners.
    #[error(
        "{}{}: face {face} has {count} vertex indices; at least 3 are needed",
        shown(.path),
        line_suffix(.line)
    )]
    FaceTooSmall {
        /// The mesh file.
        path: PathBuf,
        /// The 1-based line, when known.
        line: Option<usize>,
        /// The face number, from 0.
        face: usize,
        /// How many indices it has.
        count: usize,
    },
    /// A face refers to a vertex (or OBJ texture coordinate / normal) that does not exist.
    #[error(
        "{}{}: face {face} refers to {kind} index {index}, which is out of range \
         ({available} {} defined)",
        shown(.path),
        line_suffix(.line),
        plural(.kind)
    )]
    IndexOutOfRange {
        /// The mesh file.
        path: PathBuf,
        /// The 1-based line, when known.
        line: Option<usize>,
        /// The face number, from 0.
        face: usize,
        /// What the index refers to: "vertex", "texture coordinate" or "normal".
        kind: &'static str,
        /// The index as stored in the file.
        index: i64,
        /// How many entries of that kind are available.
        available: usize,
    },
    /// A position, normal or texture coordinate is NaN or infinite.
    #[error(
        "{}{}: vertex {vertex} has a non-finite {what}",
        shown(.path),
        line_suffix(.line)
    )]
    NonFinite {
        /// The mesh file.
        path: PathBuf,
        /// The 1-based line, when known.
        line: Option<usize>,
        /// The vertex number (OBJ: of that kind of entry), from 0.
        vertex: usize,
        /// "position", "normal" or "texture coordinate".
        what: &'static str,
    },
    /// The file asks for more triangles than the scene's triangle limit leaves for it.
    #[error(
        "{}{}: {what}{}",
        shown(.path),
        line_suffix(.line),
        triangle_limit_suffix(*.limit, *.before)
    )]
    TooManyTriangles {
        /// The mesh file.
        path: PathBuf,
        /// The 1-based line, when known.
        line: Option<usize>,
        /// How many triangles the file asks for, and where that was counted.
        what: String,
        /// The scene's triangle limit.
        limit: usize,
        /// Triangles the scene has before this file.
        before: usize,
    },
    /// Loading and tracing the mesh would need more memory than the render may have.
    #[error(
        "{}: its {vertices} vertices and {triangles} triangles need about {} to load and trace, \
         and {} can be had for them (raise it with --max-memory if the machine has more)",
        shown(.path),
        memory::shown(*.needed),
        memory::shown(*.available)
    )]
    TooLargeForMemory {
        /// The mesh file.
        path: PathBuf,
        /// Vertices the file declares.
        vertices: u64,
        /// Triangles it makes (for a PLY file, at least one a face).
        triangles: u64,
        /// The estimate of the bytes they take ([`memory::mesh_bytes`]).
        needed: u64,
        /// The bytes left for this file.
        available: u64,
    },
    /// A buffer the file asks for could not be allocated.
    #[error("{}: not enough memory for {count} {what}", shown(.path))]
    OutOfMemory {
        /// The mesh file.
        path: PathBuf,
        /// How many items.
        count: usize,
        /// What they are ("vertices", "triangles", ...).
        what: &'static str,
    },
    /// The file parsed but contains no triangles.
    #[error("{}: no triangles in mesh file{}", shown(.path), .detail)]
    NoTriangles {
        /// The mesh file.
        path: PathBuf,
        /// Extra explanation, starting with a separator, or empty.
        detail: String,
    },
}

fn triangle_limit_suffix(limit: usize, before: usize) -> String {
    if before == 0 {
        format!(", over the limit of {limit} triangles (raise it with --max-triangles)")
    } else {
        format!(
            "; the scene already has {before} triangles and its limit is {limit} \
             (raise it with --max-triangles)"
        )
    }
}

/// Reserves room for `count` more items in `v`, or reports that the memory is not there. Growth
/// is amortised (an empty `v` gets exactly `count`), so reserving face by face past the first
/// estimate stays linear.
fn reserve<T>(
    path: &Path,
    v: &mut Vec<T>,
    count: usize,
    what: &'static str,
) -> Result<(), MeshFileError> {
    v.try_reserve(count)
        .map_err(|_| MeshFileError::OutOfMemory {
            path: path.to_path_buf(),
            count,
            what,
        })
}

fn line_suffix(line: &Option<usize>) -> String {
    match line {
        Some(l) => format!(" (line {l})"),
        None => String::new(),
    }
}

fn describe_extension(extension: &Option<String>) -> String {
    match extension {
        Some(e) => format!("'.{e}'"),
        None => "(none)".to_owned(),
    }
}

fn plural(kind: &str) -> &'static str {
    match kind {
        "vertex" => "vertices",
        "normal" => "normals",
        _ => "texture coordinates",
    }
}

fn malformed(path: &Path, line: Option<usize>, message: impl Into<String>) -> MeshFileError {
    MeshFileError::Malformed {
        path: path.to_path_buf(),
        line,
        message: message.into(),
    }
}

/// Reads a mesh, choosing the format from the extension (`ply` or `obj`, any case), under the
/// default [`MeshLimits`].
pub fn read_mesh(path: &Path) -> Result<MeshData, MeshFileError> {
    read_mesh_with(path, &MeshLimits::default())
}

/// [`read_mesh`] under `limits`.
pub fn read_mesh_with(path: &Path, limits: &MeshLimits) -> Result<MeshData, MeshFileError> {
    let extension = path.extension().map(|e| e.to_string_lossy().into_owned());
    match extension.as_deref().map(str::to_ascii_lowercase).as_deref() {
        Some("ply") => parse_ply(path, &read_bytes(path, limits)?, limits),
        Some("obj") => parse_obj(path, &read_bytes(path, limits)?, limits),
        _ => Err(MeshFileError::UnsupportedExtension {
            path: path.to_path_buf(),
            extension,
        }),
    }
}

/// Reads an ASCII or binary PLY mesh under the default [`MeshLimits`].
pub fn read_ply(path: &Path) -> Result<MeshData, MeshFileError> {
    let limits = MeshLimits::default();
    parse_ply(path, &read_bytes(path, &limits)?, &limits)
}

/// Reads a Wavefront OBJ mesh under the default [`MeshLimits`]; materials are ignored.
pub fn read_obj(path: &Path) -> Result<MeshData, MeshFileError> {
    let limits = MeshLimits::default();
    parse_obj(path, &read_bytes(path, &limits)?, &limits)
}

/// The whole file: a regular file (never a FIFO or a device) of at most `limits.max_bytes`.
fn read_bytes(path: &Path, limits: &MeshLimits) -> Result<Vec<u8>, MeshFileError> {
    let limit = SizeLimit {
        bytes: limits.max_bytes,
        flag: Some("--max-mesh-bytes"),
    };
    let bytes = input::read(path, limit).map_err(|source| MeshFileError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    if bytes.is_empty() {
        return Err(MeshFileError::Empty {
            path: path.to_path_buf(),
        });
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests;
