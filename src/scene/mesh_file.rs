//! Reading triangle meshes from PLY and Wavefront OBJ files.
//!
//! [`read_mesh`] picks the format from the file extension (`.ply` or `.obj`,
//! case-insensitive); [`read_ply`] and [`read_obj`] read one format directly.
//! Both produce a [`MeshData`]: one shared vertex buffer (positions, and normals
//! and texture coordinates where the file gives them for every vertex) plus
//! triangles as indices into it.
//!
//! # PLY
//!
//! ASCII, `binary_little_endian` and `binary_big_endian` files are read.
//!
//! * The `vertex` element must have scalar properties `x`, `y`, `z` of any
//!   numeric type (integers are converted to `f32`, doubles are rounded to `f32`).
//! * Normals are taken from `nx`, `ny`, `nz` when all three are present on the
//!   vertices. Texture coordinates come from the first complete pair among
//!   `u`/`v`, `s`/`t` and `texture_u`/`texture_v`, and are returned as stored
//!   (no flip of `v`).
//! * The `face` element must have a list property named `vertex_indices` or
//!   `vertex_index` with an integer element type. Polygons with more than three
//!   corners are split into fans `(0, i, i + 1)`.
//! * Other elements (edges, materials, per-face texture lists, ...) and other
//!   properties are skipped. Elements declared after both `vertex` and `face`
//!   are not read at all.
//!
//! # OBJ
//!
//! OBJ files are read with `tobj`, triangulated, and re-indexed so that
//! position, normal and texture coordinate share one index; all objects and
//! groups are merged into a single mesh. Normals (`vn`) and texture coordinates
//! (`vt`) are kept only when every vertex of the merged mesh has them. Points
//! (`p`) and polylines (`l`) are ignored. Materials are ignored: `mtllib` and
//! `usemtl` lines are accepted, the `.mtl` files they name are never opened, so
//! a missing or broken one is not an error.
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
//! limit leaves is an error naming `--max-triangles`. The vertex, normal, texture coordinate and
//! triangle buffers are reserved fallibly, so a size the machine cannot hold is an error.

use std::io::{BufRead, ErrorKind};
use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};
use ply_rs_bw::parser::{ParseError, Parser, Reader};
use ply_rs_bw::ply::{
    BeginList, ElementDef, Encoding, PropertyAccess, PropertyAccessResult, PropertyType, ScalarType,
};

use crate::files::input::{self, SizeLimit};
use crate::files::shown;
use crate::memory;

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

// ---------------------------------------------------------------------------
// PLY
// ---------------------------------------------------------------------------

/// Vertex property names this reader understands, in slot order.
const VERTEX_SLOTS: [&str; 12] = [
    "x",
    "y",
    "z",
    "nx",
    "ny",
    "nz",
    "u",
    "v",
    "s",
    "t",
    "texture_u",
    "texture_v",
];
const SLOT_NX: usize = 3;
/// Texture coordinate pairs, first complete one wins.
const UV_PAIRS: [(usize, usize); 3] = [(6, 7), (8, 9), (10, 11)];
const FACE_LISTS: [&str; 2] = ["vertex_indices", "vertex_index"];

/// One PLY vertex: the known scalar properties, converted to `f32`.
struct VertexElement {
    slots: [f32; VERTEX_SLOTS.len()],
}

impl VertexElement {
    fn set(&mut self, name: &str, value: f32) -> PropertyAccessResult {
        match VERTEX_SLOTS.iter().position(|s| *s == name) {
            Some(i) => {
                self.slots[i] = value;
                PropertyAccessResult::Set
            }
            None => PropertyAccessResult::Ignored,
        }
    }
}

impl PropertyAccess for VertexElement {
    fn new() -> Self {
        Self {
            slots: [0.0; VERTEX_SLOTS.len()],
        }
    }
    fn set_char(&mut self, name: &str, value: i8) -> PropertyAccessResult {
        self.set(name, f32::from(value))
    }
    fn set_uchar(&mut self, name: &str, value: u8) -> PropertyAccessResult {
        self.set(name, f32::from(value))
    }
    fn set_short(&mut self, name: &str, value: i16) -> PropertyAccessResult {
        self.set(name, f32::from(value))
    }
    fn set_ushort(&mut self, name: &str, value: u16) -> PropertyAccessResult {
        self.set(name, f32::from(value))
    }
    fn set_int(&mut self, name: &str, value: i32) -> PropertyAccessResult {
        self.set(name, value as f32)
    }
    fn set_uint(&mut self, name: &str, value: u32) -> PropertyAccessResult {
        self.set(name, value as f32)
    }
    fn set_float(&mut self, name: &str, value: f32) -> PropertyAccessResult {
        self.set(name, value)
    }
    fn set_double(&mut self, name: &str, value: f64) -> PropertyAccessResult {
        self.set(name, value as f32)
    }
}

/// One PLY face: its index list(s); negative indices are remembered, not stored.
struct FaceElement {
    lists: [Vec<u32>; FACE_LISTS.len()],
    negative: Option<i64>,
}

impl FaceElement {
    fn slot(name: &str) -> Option<usize> {
        FACE_LISTS.iter().position(|s| *s == name)
    }

    fn store<I: Copy + Into<i64>>(&mut self, name: &str, values: &[I]) -> PropertyAccessResult {
        let Some(slot) = Self::slot(name) else {
            return PropertyAccessResult::Ignored;
        };
        let mut out = Vec::with_capacity(values.len());
        for &value in values {
            let value: i64 = value.into();
            match u32::try_from(value) {
                Ok(v) => out.push(v),
                Err(_) => {
                    self.negative.get_or_insert(value);
                }
            }
        }
        self.lists[slot] = out;
        PropertyAccessResult::Set
    }
}

impl PropertyAccess for FaceElement {
    fn new() -> Self {
        Self {
            lists: [Vec::new(), Vec::new()],
            negative: None,
        }
    }
    fn set_list_char(&mut self, name: &str, value: Vec<i8>) -> PropertyAccessResult {
        self.store(name, &value)
    }
    fn set_list_uchar(&mut self, name: &str, value: Vec<u8>) -> PropertyAccessResult {
        self.store(name, &value)
    }
    fn set_list_short(&mut self, name: &str, value: Vec<i16>) -> PropertyAccessResult {
        self.store(name, &value)
    }
    fn set_list_ushort(&mut self, name: &str, value: Vec<u16>) -> PropertyAccessResult {
        self.store(name, &value)
    }
    fn set_list_int(&mut self, name: &str, value: Vec<i32>) -> PropertyAccessResult {
        self.store(name, &value)
    }
    fn begin_list_uint(&mut self, name: &str, _len: usize) -> BeginList<'_, u32> {
        match Self::slot(name) {
            Some(slot) => BeginList::Fill(&mut self.lists[slot]),
            None => BeginList::UseSetter,
        }
    }
    fn set_list_uint(&mut self, name: &str, value: Vec<u32>) -> PropertyAccessResult {
        match Self::slot(name) {
            Some(slot) => {
                self.lists[slot] = value;
                PropertyAccessResult::Set
            }
            None => PropertyAccessResult::Ignored,
        }
    }
}

/// An element this reader does not use; its bytes are consumed and dropped.
struct SkipElement;

impl PropertyAccess for SkipElement {
    fn new() -> Self {
        SkipElement
    }
}

/// The error text of a `ply_rs_bw` error without its own "Line N: " prefix.
fn ply_error_text(error: &ParseError) -> String {
    let text = error.to_string();
    if let Some(line) = error.line() {
        if let Some(rest) = text.strip_prefix(&format!("Line {line}: ")) {
            return tidy(rest);
        }
    }
    tidy(&text)
}

/// Puts a multi-line `ply_rs_bw` message on one line.
fn tidy(text: &str) -> String {
    // Drop the parser generator's internal error dump; the quoted line says enough.
    let text = match text.find("\tError: ParseError {") {
        Some(at) => &text[..at],
        None => text,
    };
    text.replace("\r\n'", "'")
        .replace("\n'", "'")
        .split('\n')
        .map(str::trim)
        .filter(|part| !part.is_empty())
        .collect::<Vec<_>>()
        .join("; ")
}

fn is_integer(t: &ScalarType) -> bool {
    !matches!(t, ScalarType::Float | ScalarType::Double)
}

fn scalar_size(t: &ScalarType) -> u64 {
    match t {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    }
}

/// Smallest number of payload bytes one element of `def` can occupy (at least 1).
fn min_element_bytes(def: &ElementDef, encoding: Encoding) -> u64 {
    let bytes = match encoding {
        // Each property is at least a one-character token followed by a space or
        // the line break.
        Encoding::Ascii => 2 * def.properties.len() as u64,
        Encoding::BinaryBigEndian | Encoding::BinaryLittleEndian => def
            .properties
            .values()
            .map(|p| match &p.data_type {
                PropertyType::Scalar(t) => scalar_size(t),
                PropertyType::List(count, _) => scalar_size(count),
            })
            .sum(),
    };
    bytes.max(1)
}

/// Where one PLY element starts in the payload and how to read it.
struct PlyCursor<'a> {
    data: &'a [u8],
    encoding: Encoding,
    /// Next ASCII line number (1-based).
    line: usize,
    buf: String,
}

impl PlyCursor<'_> {
    /// Line of the element about to be read, for ASCII files.
    fn current_line(&self) -> Option<usize> {
        match self.encoding {
            Encoding::Ascii => Some(self.line),
            _ => None,
        }
    }

    /// Reads the next element; on error returns the line (ASCII) and a description.
    fn read<E: PropertyAccess>(
        &mut self,
        parser: &Parser<E>,
        def: &ElementDef,
    ) -> Result<E, (Option<usize>, String)> {
        match self.encoding {
            Encoding::Ascii => {
                let line = self.line;
                self.buf.clear();
                match self.data.read_line(&mut self.buf) {
                    Ok(0) => return Err((Some(line), "the file ends early".to_owned())),
                    Ok(_) => {}
                    Err(e) => return Err((Some(line), e.to_string())),
                }
                self.line += 1;
                parser
                    .read_ascii_element(self.buf.trim_end_matches(['\r', '\n']), def)
                    .map_err(|e| (Some(line), ply_error_text(&e)))
            }
            Encoding::BinaryLittleEndian => parser
                .read_little_endian_element(&mut self.data, def)
                .map_err(|e| (None, binary_error_text(&e))),
            Encoding::BinaryBigEndian => parser
                .read_big_endian_element(&mut self.data, def)
                .map_err(|e| (None, binary_error_text(&e))),
        }
    }
}

fn binary_error_text(error: &ParseError) -> String {
    if error.kind() == ErrorKind::UnexpectedEof {
        "the file ends early (truncated)".to_owned()
    } else {
        ply_error_text(error)
    }
}

fn element_error(
    path: &Path,
    def: &ElementDef,
    index: usize,
    (line, text): (Option<usize>, String),
) -> MeshFileError {
    malformed(
        path,
        line,
        format!(
            "cannot read PLY '{}' element {index} of {}: {text}",
            def.name, def.count
        ),
    )
}

/// Finds a scalar property, refusing it when it is declared as a list.
fn scalar_property(path: &Path, def: &ElementDef, name: &str) -> Result<bool, MeshFileError> {
    match def.properties.get(name).map(|p| &p.data_type) {
        None => Ok(false),
        Some(PropertyType::Scalar(_)) => Ok(true),
        Some(PropertyType::List(..)) => Err(malformed(
            path,
            None,
            format!(
                "PLY '{}' property '{name}' is declared as a list; a number was expected",
                def.name
            ),
        )),
    }
}

fn parse_ply(path: &Path, bytes: &[u8], limits: &MeshLimits) -> Result<MeshData, MeshFileError> {
    let mut reader = Reader::new(bytes);
    let header = Parser::<SkipElement>::new()
        .read_header(&mut reader)
        .map_err(|e| {
            malformed(
                path,
                e.line(),
                format!("invalid PLY header: {}", ply_error_text(&e)),
            )
        })?;
    let first_payload_line = reader.line().max(1);
    let payload = reader.into_inner();

    // --- Check the header before reading anything.
    let elements: Vec<&ElementDef> = header.elements.values().collect();
    let vertex_pos = elements
        .iter()
        .position(|e| e.name == "vertex")
        .ok_or_else(|| malformed(path, None, "the PLY header declares no 'vertex' element"))?;
    let face_pos = elements
        .iter()
        .position(|e| e.name == "face")
        .ok_or_else(|| MeshFileError::NoTriangles {
            path: path.to_path_buf(),
            detail: " (the PLY header declares no 'face' element)".to_owned(),
        })?;
    let vertex_def = elements[vertex_pos];
    let face_def = elements[face_pos];

    for name in ["x", "y", "z"] {
        if !scalar_property(path, vertex_def, name)? {
            return Err(malformed(
                path,
                None,
                format!("the PLY 'vertex' element has no '{name}' property"),
            ));
        }
    }
    let mut has_normals = true;
    for name in ["nx", "ny", "nz"] {
        has_normals &= scalar_property(path, vertex_def, name)?;
    }
    let mut uv_pair = None;
    for (u, v) in UV_PAIRS {
        let has_u = scalar_property(path, vertex_def, VERTEX_SLOTS[u])?;
        let has_v = scalar_property(path, vertex_def, VERTEX_SLOTS[v])?;
        if has_u && has_v && uv_pair.is_none() {
            uv_pair = Some((u, v));
        }
    }

    let mut face_list = None;
    for (slot, name) in FACE_LISTS.iter().enumerate() {
        match face_def.properties.get(*name).map(|p| &p.data_type) {
            Some(PropertyType::List(_, item)) if is_integer(item) => {
                face_list = Some(slot);
                break;
            }
            Some(_) => {
                return Err(malformed(
                    path,
                    None,
                    format!("the PLY 'face' property '{name}' must be a list of integers"),
                ));
            }
            None => {}
        }
    }
    let face_list = face_list.ok_or_else(|| {
        malformed(
            path,
            None,
            "the PLY 'face' element has no 'vertex_indices' or 'vertex_index' list property",
        )
    })?;

    // Elements after both vertex and face are never read, so they need not fit.
    let last = vertex_pos.max(face_pos);
    let available = payload.len() as u64;
    let mut needed = 0u64;
    for def in &elements[..=last] {
        let bytes = (def.count as u64).saturating_mul(min_element_bytes(def, header.encoding));
        needed = needed.saturating_add(bytes);
        // The final line of an ASCII file may lack its line break.
        let needed_here = match header.encoding {
            Encoding::Ascii => needed.saturating_sub(1),
            _ => needed,
        };
        if needed_here > available {
            return Err(MeshFileError::CountTooLarge {
                path: path.to_path_buf(),
                element: def.name.clone(),
                count: def.count,
                needed: needed_here,
                available,
            });
        }
    }

    let vertex_count = vertex_def.count;
    if u32::try_from(vertex_count).is_err() {
        return Err(malformed(
            path,
            None,
            format!(
                "the PLY header declares {vertex_count} vertices; at most 2^32 - 1 are supported"
            ),
        ));
    }

    // Every face is at least one triangle.
    if face_def.count as u64 > limits.triangles_left() {
        return Err(limits.too_many_triangles(
            path,
            None,
            format!(
                "the PLY header declares {} faces (each at least one triangle)",
                face_def.count
            ),
        ));
    }
    limits.check_memory(path, vertex_count as u64, face_def.count as u64)?;

    // --- Read the payload, element by element.
    let mut cursor = PlyCursor {
        data: payload,
        encoding: header.encoding,
        line: first_payload_line,
        buf: String::new(),
    };
    let mut mesh = MeshData::default();
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    for def in &elements[..=last] {
        if def.name == "vertex" {
            let parser = Parser::<VertexElement>::new();
            reserve(path, &mut mesh.positions, def.count, "vertices")?;
            if has_normals {
                reserve(path, &mut normals, def.count, "normals")?;
            }
            if uv_pair.is_some() {
                reserve(path, &mut uvs, def.count, "texture coordinates")?;
            }
            for i in 0..def.count {
                let line = cursor.current_line();
                let v = cursor
                    .read(&parser, def)
                    .map_err(|e| element_error(path, def, i, e))?;
                let s = &v.slots;
                let non_finite = |what| MeshFileError::NonFinite {
                    path: path.to_path_buf(),
                    line,
                    vertex: i,
                    what,
                };
                let p = Vec3::new(s[0], s[1], s[2]);
                if !p.is_finite() {
                    return Err(non_finite("position"));
                }
                mesh.positions.push(p);
                if has_normals {
                    let n = Vec3::new(s[SLOT_NX], s[SLOT_NX + 1], s[SLOT_NX + 2]);
                    if !n.is_finite() {
                        return Err(non_finite("normal"));
                    }
                    normals.push(n);
                }
                if let Some((u, v)) = uv_pair {
                    let uv = Vec2::new(s[u], s[v]);
                    if !uv.is_finite() {
                        return Err(non_finite("texture coordinate"));
                    }
                    uvs.push(uv);
                }
            }
        } else if def.name == "face" {
            let parser = Parser::<FaceElement>::new();
            reserve(path, &mut mesh.faces, def.count, "triangles")?;
            let mut triangles = 0u64;
            for i in 0..def.count {
                let line = cursor.current_line();
                let f = cursor
                    .read(&parser, def)
                    .map_err(|e| element_error(path, def, i, e))?;
                let out_of_range = |index: i64| MeshFileError::IndexOutOfRange {
                    path: path.to_path_buf(),
                    line,
                    face: i,
                    kind: "vertex",
                    index,
                    available: vertex_count,
                };
                if let Some(negative) = f.negative {
                    return Err(out_of_range(negative));
                }
                let indices = &f.lists[face_list];
                if indices.len() < 3 {
                    return Err(MeshFileError::FaceTooSmall {
                        path: path.to_path_buf(),
                        line,
                        face: i,
                        count: indices.len(),
                    });
                }
                if let Some(&bad) = indices.iter().find(|&&k| k as usize >= vertex_count) {
                    return Err(out_of_range(i64::from(bad)));
                }
                triangles += indices.len() as u64 - 2;
                if triangles > limits.triangles_left() {
                    return Err(limits.too_many_triangles(
                        path,
                        line,
                        format!(
                            "the PLY faces up to face {i} make {triangles} triangles (polygons \
                             split into fans)"
                        ),
                    ));
                }
                let first = indices[0];
                reserve(path, &mut mesh.faces, indices.len() - 2, "triangles")?;
                for pair in indices[1..].windows(2) {
                    mesh.faces.push([first, pair[0], pair[1]]);
                }
            }
        } else {
            let parser = Parser::<SkipElement>::new();
            for i in 0..def.count {
                cursor
                    .read(&parser, def)
                    .map_err(|e| element_error(path, def, i, e))?;
            }
        }
    }

    if mesh.faces.is_empty() {
        return Err(MeshFileError::NoTriangles {
            path: path.to_path_buf(),
            detail: String::new(),
        });
    }
    if has_normals {
        mesh.normals = Some(normals);
    }
    if uv_pair.is_some() {
        mesh.uvs = Some(uvs);
    }
    Ok(mesh)
}

// ---------------------------------------------------------------------------
// OBJ
// ---------------------------------------------------------------------------

const OBJ_KINDS: [&str; 3] = ["vertex", "texture coordinate", "normal"];

/// Parses `n` numbers of an OBJ `v`/`vt`/`vn` statement, checking they are finite.
fn obj_numbers(
    path: &Path,
    line: usize,
    words: &mut std::str::SplitWhitespace<'_>,
    n: usize,
    kind: usize,
    number: usize,
) -> Result<(), MeshFileError> {
    for _ in 0..n {
        let value = words
            .next()
            .and_then(|w| w.parse::<f32>().ok())
            .ok_or_else(|| {
                malformed(
                    path,
                    Some(line),
                    format!("OBJ {} needs {n} numbers", OBJ_KINDS[kind]),
                )
            })?;
        if !value.is_finite() {
            return Err(MeshFileError::NonFinite {
                path: path.to_path_buf(),
                line: Some(line),
                vertex: number,
                what: ["position", "texture coordinate", "normal"][kind],
            });
        }
    }
    Ok(())
}

/// Checks what `tobj` does not report precisely (or at all): numbers, face
/// syntax and every index, with line numbers; and counts the triangles the faces
/// make, so that a file over the triangle limit is refused before `tobj` builds it.
fn check_obj(path: &Path, text: &str, limits: &MeshLimits) -> Result<(), MeshFileError> {
    // Counts of v, vt, vn seen so far.
    let mut counts = [0usize; 3];
    let mut triangles = 0u64;
    // Largest positive index of each kind: (index, line, face).
    let mut largest: [Option<(usize, usize, usize)>; 3] = [None; 3];
    let mut face = 0usize;
    for (number, line_text) in text.lines().enumerate() {
        let line = number + 1;
        let mut words = line_text.split_whitespace();
        let keyword = words.next();
        match keyword {
            Some("v") => {
                obj_numbers(path, line, &mut words, 3, 0, counts[0])?;
                counts[0] += 1;
            }
            Some("vt") => {
                obj_numbers(path, line, &mut words, 2, 1, counts[1])?;
                counts[1] += 1;
            }
            Some("vn") => {
                obj_numbers(path, line, &mut words, 3, 2, counts[2])?;
                counts[2] += 1;
            }
            Some("f") | Some("l") => {
                let mut corners = 0usize;
                for word in words {
                    corners += 1;
                    let bad_corner = || {
                        malformed(
                            path,
                            Some(line),
                            format!("malformed OBJ face corner '{word}'"),
                        )
                    };
                    for (kind, part) in word.split('/').enumerate() {
                        if kind >= 3 {
                            return Err(bad_corner());
                        }
                        if part.is_empty() {
                            continue;
                        }
                        let index: isize = part.parse().map_err(|_| bad_corner())?;
                        let out_of_range = || MeshFileError::IndexOutOfRange {
                            path: path.to_path_buf(),
                            line: Some(line),
                            face,
                            kind: OBJ_KINDS[kind],
                            index: index as i64,
                            available: counts[kind],
                        };
                        if index == 0 || (index < 0 && index.unsigned_abs() > counts[kind]) {
                            return Err(out_of_range());
                        }
                        if index > 0 {
                            let index = index.unsigned_abs();
                            if largest[kind].is_none_or(|(l, _, _)| index > l) {
                                largest[kind] = Some((index, line, face));
                            }
                        }
                    }
                }
                if keyword == Some("f") {
                    if corners < 3 {
                        return Err(MeshFileError::FaceTooSmall {
                            path: path.to_path_buf(),
                            line: Some(line),
                            face,
                            count: corners,
                        });
                    }
                    triangles += corners as u64 - 2;
                    if triangles > limits.triangles_left() {
                        return Err(limits.too_many_triangles(
                            path,
                            Some(line),
                            format!(
                                "the OBJ faces up to this line make {triangles} triangles (polygons \
                                 split into fans)"
                            ),
                        ));
                    }
                    face += 1;
                }
            }
            _ => {}
        }
    }
    limits.check_memory(path, counts[0] as u64, triangles)?;
    for kind in 0..3 {
        if let Some((index, line, face)) = largest[kind] {
            if index > counts[kind] {
                return Err(MeshFileError::IndexOutOfRange {
                    path: path.to_path_buf(),
                    line: Some(line),
                    face,
                    kind: OBJ_KINDS[kind],
                    index: i64::try_from(index).unwrap_or(i64::MAX),
                    available: counts[kind],
                });
            }
        }
    }
    Ok(())
}

fn parse_obj(path: &Path, bytes: &[u8], limits: &MeshLimits) -> Result<MeshData, MeshFileError> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let valid = bytes.get(..e.valid_up_to()).unwrap_or_default();
        let line = 1 + valid.iter().filter(|&&b| b == b'\n').count();
        malformed(path, Some(line), "the OBJ file is not valid UTF-8 text")
    })?;
    check_obj(path, text, limits)?;

    // Optional tobj features (enabled elsewhere in a build) add fields that must stay off.
    #[allow(clippy::needless_update)]
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let (models, _materials) = tobj::load_obj_buf(&mut text.as_bytes(), &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| malformed(path, None, format!("invalid OBJ data: {e}")))?;

    let mut mesh = MeshData::default();
    let vertices = models.iter().map(|m| m.mesh.positions.len() / 3).sum();
    let triangles = models.iter().map(|m| m.mesh.indices.len() / 3).sum();
    reserve(path, &mut mesh.positions, vertices, "vertices")?;
    reserve(path, &mut mesh.faces, triangles, "triangles")?;
    let mut normals = Vec::new();
    if models
        .iter()
        .all(|m| m.mesh.normals.len() == m.mesh.positions.len())
    {
        reserve(path, &mut normals, vertices, "normals")?;
    }
    let mut uvs = Vec::new();
    if models
        .iter()
        .all(|m| m.mesh.texcoords.len() * 3 == m.mesh.positions.len() * 2)
    {
        reserve(path, &mut uvs, vertices, "texture coordinates")?;
    }
    let mut normals = Some(normals);
    let mut uvs = Some(uvs);
    for model in &models {
        let m = &model.mesh;
        let count = m.positions.len() / 3;
        let base = mesh.positions.len();
        mesh.positions.extend(
            m.positions
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2])),
        );
        if m.normals.len() == count * 3 {
            if let Some(n) = normals.as_mut() {
                n.extend(
                    m.normals
                        .chunks_exact(3)
                        .map(|p| Vec3::new(p[0], p[1], p[2])),
                );
            }
        } else {
            normals = None;
        }
        if m.texcoords.len() == count * 2 {
            if let Some(t) = uvs.as_mut() {
                t.extend(m.texcoords.chunks_exact(2).map(|p| Vec2::new(p[0], p[1])));
            }
        } else {
            uvs = None;
        }
        for tri in m.indices.chunks_exact(3) {
            let mut out = [0u32; 3];
            for (o, &k) in out.iter_mut().zip(tri) {
                let global = base + k as usize;
                *o = match u32::try_from(global) {
                    Ok(g) if (k as usize) < count => g,
                    _ => {
                        return Err(malformed(
                            path,
                            None,
                            format!(
                                "OBJ object '{}' has a triangle index {k} out of range \
                                 or the mesh has more than 2^32 vertices",
                                model.name
                            ),
                        ))
                    }
                };
            }
            mesh.faces.push(out);
        }
    }
    if mesh.faces.is_empty() {
        return Err(MeshFileError::NoTriangles {
            path: path.to_path_buf(),
            detail: String::new(),
        });
    }
    // Scaling by a `w` component can overflow even when each number was finite.
    if let Some(vertex) = mesh.positions.iter().position(|p| !p.is_finite()) {
        return Err(MeshFileError::NonFinite {
            path: path.to_path_buf(),
            line: None,
            vertex,
            what: "position",
        });
    }
    mesh.normals = normals;
    mesh.uvs = uvs;
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// A unique scratch folder under the system temp dir, removed on drop.
    struct TempDir(PathBuf);

    impl TempDir {
        fn new(name: &str) -> Self {
            static COUNTER: AtomicUsize = AtomicUsize::new(0);
            let dir = std::env::temp_dir().join(format!(
                "raytracer_mesh_file_{}_{}_{}",
                std::process::id(),
                name,
                COUNTER.fetch_add(1, Ordering::Relaxed)
            ));
            fs::create_dir_all(&dir).expect("create temp dir");
            TempDir(dir)
        }

        fn write(&self, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
            let path = self.0.join(name);
            fs::write(&path, bytes).expect("write temp file");
            path
        }
    }

    impl Drop for TempDir {
        fn drop(&mut self) {
            let _ = fs::remove_dir_all(&self.0);
        }
    }

    const CUBE_VERTICES: [[f32; 3]; 8] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
        [0.0, 1.0, 1.0],
    ];
    const CUBE_QUADS: [[u32; 4]; 6] = [
        [0, 3, 2, 1],
        [4, 5, 6, 7],
        [0, 1, 5, 4],
        [2, 3, 7, 6],
        [1, 2, 6, 5],
        [0, 4, 7, 3],
    ];

    fn cube_header(format: &str) -> String {
        format!(
            "ply\nformat {format} 1.0\ncomment unit cube\nelement vertex 8\n\
             property float x\nproperty float y\nproperty float z\n\
             element face 6\nproperty list uchar int vertex_indices\nend_header\n"
        )
    }

    fn cube_ascii() -> String {
        let mut s = cube_header("ascii");
        for v in CUBE_VERTICES {
            s += &format!("{} {} {}\n", v[0], v[1], v[2]);
        }
        for q in CUBE_QUADS {
            s += &format!("4 {} {} {} {}\n", q[0], q[1], q[2], q[3]);
        }
        s
    }

    fn cube_binary(big_endian: bool) -> Vec<u8> {
        let format = if big_endian {
            "binary_big_endian"
        } else {
            "binary_little_endian"
        };
        let mut out = cube_header(format).into_bytes();
        for v in CUBE_VERTICES {
            for c in v {
                out.extend(if big_endian {
                    c.to_be_bytes()
                } else {
                    c.to_le_bytes()
                });
            }
        }
        for q in CUBE_QUADS {
            out.push(4);
            for i in q {
                let i = i as i32;
                out.extend(if big_endian {
                    i.to_be_bytes()
                } else {
                    i.to_le_bytes()
                });
            }
        }
        out
    }

    fn expected_cube() -> MeshData {
        MeshData {
            positions: CUBE_VERTICES.iter().map(|v| Vec3::from_array(*v)).collect(),
            normals: None,
            uvs: None,
            faces: CUBE_QUADS
                .iter()
                .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
                .collect(),
        }
    }

    #[test]
    fn ascii_ply_cube() {
        let dir = TempDir::new("ascii_cube");
        let mesh = read_mesh(&dir.write("cube.ply", cube_ascii())).unwrap();
        assert_eq!(mesh.positions.len(), 8);
        assert_eq!(mesh.faces.len(), 12);
        assert_eq!(mesh.faces[0], [0, 3, 2]);
        assert_eq!(mesh.faces[1], [0, 2, 1]);
        assert_eq!(mesh.faces[11], [0, 7, 3]);
        assert_eq!(mesh, expected_cube());
    }

    #[test]
    fn binary_ply_cube_equals_ascii() {
        let dir = TempDir::new("binary_cube");
        let ascii = read_ply(&dir.write("a.ply", cube_ascii())).unwrap();
        let le = read_ply(&dir.write("le.ply", cube_binary(false))).unwrap();
        let be = read_mesh(&dir.write("be.PLY", cube_binary(true))).unwrap();
        assert_eq!(le, ascii);
        assert_eq!(be, ascii);
    }

    #[test]
    fn ply_normals_and_uvs() {
        let dir = TempDir::new("normals_uvs");
        for (u, v) in [("u", "v"), ("s", "t"), ("texture_u", "texture_v")] {
            let text = format!(
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                 property float z\nproperty float nx\nproperty float ny\nproperty float nz\n\
                 property float {u}\nproperty float {v}\nproperty uchar red\n\
                 element face 1\nproperty list uchar uint vertex_indices\nend_header\n\
                 0 0 0 0 0 1 0 0 255\n1 0 0 0 0 1 1 0 0\n0 1 0 0 0 1 0 1 7\n3 0 1 2\n"
            );
            let mesh = read_ply(&dir.write("nuv.ply", text)).unwrap();
            assert_eq!(mesh.faces, vec![[0, 1, 2]]);
            assert_eq!(mesh.normals, Some(vec![Vec3::Z; 3]));
            assert_eq!(
                mesh.uvs,
                Some(vec![Vec2::ZERO, Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0)])
            );
        }
        // Incomplete normals are not reported.
        let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                    property float z\nproperty float nx\nproperty float u\n\
                    element face 1\nproperty list uchar uint vertex_indices\nend_header\n\
                    0 0 0 1 0\n1 0 0 1 0\n0 1 0 1 0\n3 0 1 2\n";
        let mesh = read_ply(&dir.write("partial.ply", text)).unwrap();
        assert_eq!(mesh.normals, None);
        assert_eq!(mesh.uvs, None);
    }

    #[test]
    fn ply_various_types_and_vertex_index_name() {
        let dir = TempDir::new("types");
        let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\n\
            property double x\nproperty int y\nproperty uchar z\nelement edge 1\n\
            property list uchar float junk\nelement face 1\n\
            property list ushort short vertex_index\nproperty float area\nend_header\n"
            .to_vec();
        for (x, y, z) in [(0.5f64, 0i32, 0u8), (1.5, 2, 3), (-1.0, -4, 255)] {
            bytes.extend(x.to_le_bytes());
            bytes.extend(y.to_le_bytes());
            bytes.push(z);
        }
        bytes.push(2);
        bytes.extend(1.0f32.to_le_bytes());
        bytes.extend(2.0f32.to_le_bytes());
        bytes.extend(3u16.to_le_bytes());
        for i in [2i16, 1, 0] {
            bytes.extend(i.to_le_bytes());
        }
        bytes.extend(0.25f32.to_le_bytes());
        let mesh = read_ply(&dir.write("types.ply", bytes)).unwrap();
        assert_eq!(
            mesh.positions,
            vec![
                Vec3::new(0.5, 0.0, 0.0),
                Vec3::new(1.5, 2.0, 3.0),
                Vec3::new(-1.0, -4.0, 255.0)
            ]
        );
        assert_eq!(mesh.faces, vec![[2, 1, 0]]);
    }

    #[test]
    fn ply_index_out_of_range() {
        let dir = TempDir::new("ply_range");
        let text = cube_ascii().replace("4 1 2 6 5\n", "4 1 2 9 5\n");
        let path = dir.write("bad.ply", text);
        let err = read_ply(&path).unwrap_err();
        let msg = err.to_string();
        assert!(
            matches!(
                err,
                MeshFileError::IndexOutOfRange {
                    face: 4,
                    index: 9,
                    line: Some(23),
                    ..
                }
            ),
            "{msg}"
        );
        assert!(msg.contains("face 4") && msg.contains("index 9"), "{msg}");
        assert!(msg.contains("bad.ply") && msg.contains("line 23"), "{msg}");

        let text = cube_ascii().replace("4 1 2 6 5\n", "4 1 -2 6 5\n");
        let err = read_ply(&dir.write("neg.ply", text)).unwrap_err();
        assert!(err.to_string().contains("index -2"), "{err}");

        let mut bytes = cube_binary(false);
        let last = bytes.len() - 4;
        bytes[last..].copy_from_slice(&100i32.to_le_bytes());
        let err = read_ply(&dir.write("bad_bin.ply", bytes)).unwrap_err();
        assert!(
            matches!(
                err,
                MeshFileError::IndexOutOfRange {
                    face: 5,
                    index: 100,
                    ..
                }
            ),
            "{err}"
        );
    }

    #[test]
    fn ply_small_face_and_non_finite() {
        let dir = TempDir::new("ply_small");
        let text = cube_ascii().replace("4 0 4 7 3\n", "2 0 4\n");
        let err = read_ply(&dir.write("small.ply", text)).unwrap_err();
        assert!(
            matches!(
                err,
                MeshFileError::FaceTooSmall {
                    face: 5,
                    count: 2,
                    ..
                }
            ),
            "{err}"
        );
        assert!(err.to_string().contains("face 5"), "{err}");

        let text = cube_ascii().replacen("1 0 0\n", "1 1e39 0\n", 1);
        let err = read_ply(&dir.write("inf.ply", text)).unwrap_err();
        assert!(
            matches!(
                err,
                MeshFileError::NonFinite {
                    vertex: 1,
                    what: "position",
                    line: Some(12),
                    ..
                }
            ),
            "{err}"
        );
        assert!(err.to_string().contains("vertex 1"), "{err}");
        let mut bytes = cube_binary(false);
        let at = cube_header("binary_little_endian").len() + 12 * 3 + 4;
        bytes[at..at + 4].copy_from_slice(&f32::NAN.to_le_bytes());
        let err = read_ply(&dir.write("nan.ply", bytes)).unwrap_err();
        assert!(
            matches!(
                err,
                MeshFileError::NonFinite {
                    vertex: 3,
                    line: None,
                    ..
                }
            ),
            "{err}"
        );
    }

    #[test]
    fn truncated_binary_ply_is_an_error() {
        let dir = TempDir::new("truncated");
        let full = cube_binary(false);
        let header_len = cube_header("binary_little_endian").len();
        for len in 0..full.len() {
            let path = dir.write("t.ply", &full[..len]);
            let result = read_ply(&path);
            assert!(result.is_err(), "length {len} should fail");
            if len > header_len {
                let msg = result.unwrap_err().to_string();
                assert!(msg.contains("t.ply"), "{msg}");
            }
        }
        // Removing a byte in the middle shifts everything: still an error, no panic.
        let mut shifted = full.clone();
        shifted.remove(header_len + 5);
        assert!(read_ply(&dir.write("s.ply", shifted)).is_err());
    }

    #[test]
    fn lying_huge_counts_fail_fast() {
        // Each count is refused from the header, before anything is allocated for it (an
        // allocation of that size would abort the test process).
        let dir = TempDir::new("huge");
        for (format, count) in [
            ("binary_little_endian", "4000000000"),
            ("binary_big_endian", "18446744073709551615"),
            ("ascii", "4000000000"),
        ] {
            let mut bytes = format!(
                "ply\nformat {format} 1.0\nelement vertex {count}\nproperty float x\n\
                 property float y\nproperty float z\nelement face 1\n\
                 property list uchar int vertex_indices\nend_header\n"
            )
            .into_bytes();
            bytes.extend([0u8; 200]);
            let err = read_ply(&dir.write("huge.ply", bytes)).unwrap_err();
            assert!(matches!(err, MeshFileError::CountTooLarge { .. }), "{err}");
            assert!(err.to_string().contains("'vertex'"), "{err}");
        }
        // A huge face count, and a huge element without properties before them.
        let text = cube_ascii().replace("element face 6", "element face 3000000000");
        let err = read_ply(&dir.write("faces.ply", text)).unwrap_err();
        assert!(matches!(err, MeshFileError::CountTooLarge { .. }), "{err}");
        let mut bytes = cube_binary(false);
        let text = String::from_utf8_lossy(&bytes).into_owned();
        let at = text.find("element vertex").unwrap();
        bytes.splice(at..at, b"element nothing 4000000000000\n".iter().copied());
        let err = read_ply(&dir.write("empty_el.ply", bytes)).unwrap_err();
        assert!(matches!(err, MeshFileError::CountTooLarge { .. }), "{err}");
        // A huge list length inside the payload just runs out of data.
        let mut bytes = cube_header("binary_little_endian")
            .replace("list uchar int", "list uint int")
            .into_bytes();
        for v in CUBE_VERTICES {
            for c in v {
                bytes.extend(c.to_le_bytes());
            }
        }
        bytes.extend(u32::MAX.to_le_bytes());
        bytes.extend([0u8; 64]);
        let err = read_ply(&dir.write("list.ply", bytes)).unwrap_err();
        assert!(err.to_string().contains("face"), "{err}");
    }

    #[test]
    fn ply_lying_small_counts_and_structure_errors() {
        let dir = TempDir::new("ply_structure");
        let cases = [
            cube_ascii().replace("element vertex 8", "element vertex 10"),
            cube_ascii().replace("element vertex 8", "element vertex 6"),
            cube_ascii().replace("element face 6", "element face 7"),
            cube_ascii().replace("property float z\n", ""),
            cube_ascii().replace("vertex_indices", "corners"),
            cube_ascii().replace("list uchar int", "list uchar float"),
            cube_ascii().replace("property float x", "property list uchar float x"),
            cube_ascii().replace("element vertex", "element point"),
            cube_ascii().replace("end_header\n", ""),
            cube_ascii().replace("ply\n", "plx\n"),
            cube_ascii().replace("4 0 3 2 1", "4 0 3 2"),
            cube_ascii().replace("4 0 3 2 1", "4 0 3 2 one"),
            "ply\nformat ascii 1.0\nend_header\n".to_owned(),
            "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n\
             property float z\nelement face 0\nproperty list uchar int vertex_indices\n\
             end_header\n"
                .to_owned(),
        ];
        for (i, text) in cases.iter().enumerate() {
            let result = read_ply(&dir.write("s.ply", text));
            let err = result.expect_err(&format!("case {i} should fail"));
            assert!(err.to_string().contains("s.ply"), "{err}");
        }
        let no_faces = cube_ascii().replace("element face 6", "element fac 6");
        let err = read_ply(&dir.write("nf.ply", no_faces)).unwrap_err();
        assert!(matches!(err, MeshFileError::NoTriangles { .. }), "{err}");
        assert!(err.to_string().contains("no triangles"), "{err}");
    }

    const OBJ_QUADS: &str = "# two quads\nmtllib missing.mtl\no quad\n\
        v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n\
        vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
        vn 0 0 1\n\
        usemtl red\n\
        f 1/1/1 2/2/1 3/3/1 4/4/1\n\
        g other\n\
        f 2/1/1 5/2/1 6/3/1 3/4/1\n";

    #[test]
    fn obj_quads_with_uvs_and_normals() {
        let dir = TempDir::new("obj_quads");
        let mesh = read_mesh(&dir.write("quads.OBJ", OBJ_QUADS)).unwrap();
        assert_eq!(mesh.faces.len(), 4);
        let uvs = mesh.uvs.as_ref().expect("uvs");
        let normals = mesh.normals.as_ref().expect("normals");
        assert_eq!(uvs.len(), mesh.positions.len());
        assert_eq!(normals.len(), mesh.positions.len());
        assert!(normals.iter().all(|n| *n == Vec3::Z));
        // Every triangle corner keeps its own position/uv pairing.
        let corners = |tri: [u32; 3]| tri.map(|k| (mesh.positions[k as usize], uvs[k as usize]));
        let first = corners(mesh.faces[0]);
        assert_eq!(first[0], (Vec3::ZERO, Vec2::ZERO));
        assert_eq!(first[1], (Vec3::X, Vec2::X));
        assert_eq!(first[2], (Vec3::new(1.0, 1.0, 0.0), Vec2::ONE));
        let second = corners(mesh.faces[1]);
        assert_eq!(second[0], (Vec3::ZERO, Vec2::ZERO));
        assert_eq!(second[2], (Vec3::Y, Vec2::Y));
        let third = corners(mesh.faces[2]);
        assert_eq!(third[0], (Vec3::X, Vec2::ZERO));
        for tri in &mesh.faces {
            assert!(tri.iter().all(|&k| (k as usize) < mesh.positions.len()));
        }
        // Negative (relative) indices work too; no vt/vn gives None.
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n";
        let mesh = read_obj(&dir.write("rel.obj", text)).unwrap();
        assert_eq!(mesh.positions.len(), 3);
        assert_eq!(mesh.faces.len(), 1);
        assert_eq!(mesh.uvs, None);
        assert_eq!(mesh.normals, None);
    }

    #[test]
    fn obj_index_out_of_range() {
        let dir = TempDir::new("obj_range");
        let cases = [
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", 4, "vertex", 4),
            ("v 0 0 0\nv 1 0 0\nf 1 2 -3\nv 0 1 0\n", -3, "vertex", 3),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 0, "vertex", 4),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n",
                2,
                "texture coordinate",
                5,
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//-99999 3//1\n",
                -99999,
                "normal",
                5,
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//9223372036854775807 2 3\n",
                i64::MAX,
                "normal",
                4,
            ),
        ];
        for (text, index, kind, line) in cases {
            let err = read_obj(&dir.write("r.obj", text)).unwrap_err();
            match &err {
                MeshFileError::IndexOutOfRange {
                    index: i,
                    kind: k,
                    line: l,
                    face: 0,
                    ..
                } => {
                    assert_eq!((*i, *k, *l), (index, kind, Some(line)), "{err}");
                }
                other => panic!("unexpected error {other}"),
            }
            let msg = err.to_string();
            assert!(
                msg.contains("r.obj") && msg.contains(&format!("index {index}")),
                "{msg}"
            );
        }
    }

    #[test]
    fn obj_other_errors() {
        let dir = TempDir::new("obj_errors");
        type Check = fn(&MeshFileError) -> bool;
        let cases: [(&str, Check); 7] = [
            ("v 0 0 0\nv 1 0 0\nf 1 2\n", |e| {
                matches!(
                    e,
                    MeshFileError::FaceTooSmall {
                        count: 2,
                        line: Some(3),
                        ..
                    }
                )
            }),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\n", |e| {
                matches!(e, MeshFileError::NoTriangles { .. })
            }),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\np 3\n", |e| {
                matches!(e, MeshFileError::NoTriangles { .. })
            }),
            ("v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n", |e| {
                matches!(
                    e,
                    MeshFileError::NonFinite {
                        vertex: 1,
                        line: Some(2),
                        ..
                    }
                )
            }),
            ("v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", |e| {
                matches!(e, MeshFileError::Malformed { line: Some(1), .. })
            }),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n", |e| {
                matches!(e, MeshFileError::Malformed { line: Some(4), .. })
            }),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0 1e-45\nf 1 2 3\n", |e| {
                matches!(e, MeshFileError::NonFinite { vertex: 2, .. })
            }),
        ];
        for (i, (text, check)) in cases.into_iter().enumerate() {
            let err = read_obj(&dir.write("e.obj", text)).unwrap_err();
            assert!(check(&err), "case {i}: {err}");
            assert!(err.to_string().contains("e.obj"), "{err}");
        }
        let err = read_obj(&dir.write("bin.obj", b"v 0 0 0\n\xff\xfe\n")).unwrap_err();
        assert!(err.to_string().contains("line 2"), "{err}");
    }

    #[test]
    fn unsupported_extension_and_missing_file() {
        let dir = TempDir::new("ext");
        let path = dir.write("mesh.stl", "solid x\n");
        let msg = read_mesh(&path).unwrap_err().to_string();
        assert!(
            msg.contains("'.stl'") && msg.contains(".ply") && msg.contains(".obj"),
            "{msg}"
        );
        let path = dir.write("mesh", "ply\n");
        let err = read_mesh(&path).unwrap_err();
        assert!(matches!(
            err,
            MeshFileError::UnsupportedExtension {
                extension: None,
                ..
            }
        ));
        let err = read_mesh(&dir.0.join("absent.ply")).unwrap_err();
        assert!(matches!(err, MeshFileError::Io { .. }), "{err}");
        assert!(err.to_string().contains("absent.ply"), "{err}");
    }

    #[test]
    fn empty_and_garbage_files() {
        let dir = TempDir::new("empty");
        for name in ["empty.ply", "empty.obj"] {
            let err = read_mesh(&dir.write(name, "")).unwrap_err();
            assert!(matches!(err, MeshFileError::Empty { .. }), "{err}");
            assert!(err.to_string().contains(name), "{err}");
        }
        let mut state = 0x1234_5678_9abc_def0u64;
        let garbage: Vec<u8> = (0..4096).map(|_| xorshift(&mut state) as u8).collect();
        assert!(read_mesh(&dir.write("g.ply", &garbage)).is_err());
        assert!(read_mesh(&dir.write("g.obj", &garbage)).is_err());
        assert!(read_mesh(&dir.write("ws.obj", "\n\n  \n")).is_err());
    }

    fn xorshift(state: &mut u64) -> u64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        *state
    }

    /// Random corruption of valid files must give `Ok` or `Err`, never a panic.
    #[test]
    fn corrupted_inputs_never_panic() {
        let path = Path::new("fuzz.ply");
        let seeds: [Vec<u8>; 4] = [
            cube_ascii().into_bytes(),
            cube_binary(false),
            cube_binary(true),
            OBJ_QUADS.as_bytes().to_vec(),
        ];
        let interesting: &[&[u8]] = &[
            b"4294967295",
            b"-1",
            b"0",
            b"99999999999999999999",
            b"nan",
            b"list",
            b"/",
            b"-",
            b"\n",
            b" ",
            b"double",
            b"uint",
            b"\xff",
        ];
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        for (s, seed) in seeds.iter().enumerate() {
            for _ in 0..1500 {
                let mut data = seed.clone();
                for _ in 0..1 + xorshift(&mut state) % 4 {
                    let at = (xorshift(&mut state) as usize) % (data.len() + 1);
                    match xorshift(&mut state) % 5 {
                        0 if at < data.len() => data[at] = xorshift(&mut state) as u8,
                        1 => data.truncate(at),
                        2 if at < data.len() => {
                            data.remove(at);
                        }
                        _ => {
                            let pick =
                                interesting[xorshift(&mut state) as usize % interesting.len()];
                            data.splice(at..at, pick.iter().copied());
                        }
                    }
                }
                let result = if s == 3 {
                    parse_obj(Path::new("fuzz.obj"), &data, &MeshLimits::default())
                } else {
                    parse_ply(path, &data, &MeshLimits::default())
                };
                if let Ok(mesh) = result {
                    assert!(!mesh.faces.is_empty());
                    for tri in &mesh.faces {
                        assert!(tri.iter().all(|&k| (k as usize) < mesh.positions.len()));
                    }
                    assert!(mesh.positions.iter().all(|p| p.is_finite()));
                }
            }
        }
    }

    /// Every PLY/OBJ mesh in the coursework corpus either loads or fails cleanly.
    #[test]
    fn corpus_meshes_load_or_fail_cleanly() {
        let root = Path::new("/work/shared/coursework/corpus/assets");
        if !root.is_dir() {
            return;
        }
        let mut stack = vec![root.to_path_buf()];
        let mut files = Vec::new();
        while let Some(dir) = stack.pop() {
            let Ok(entries) = fs::read_dir(&dir) else {
                continue;
            };
            for entry in entries.flatten() {
                let path = entry.path();
                if path.is_dir() {
                    stack.push(path);
                } else if path
                    .extension()
                    .and_then(|e| e.to_str())
                    .is_some_and(|e| e.eq_ignore_ascii_case("ply") || e.eq_ignore_ascii_case("obj"))
                {
                    files.push(path);
                }
            }
        }
        files.sort();
        for path in &files {
            match read_mesh(path) {
                Ok(mesh) => {
                    assert!(!mesh.faces.is_empty());
                    let n = mesh.positions.len();
                    assert!(mesh.faces.iter().flatten().all(|&k| (k as usize) < n));
                    assert!(mesh.normals.as_ref().is_none_or(|v| v.len() == n));
                    assert!(mesh.uvs.as_ref().is_none_or(|v| v.len() == n));
                    println!(
                        "loaded {}: {} vertices, {} triangles, normals: {}, uvs: {}",
                        shown(path),
                        n,
                        mesh.faces.len(),
                        mesh.normals.is_some(),
                        mesh.uvs.is_some()
                    );
                }
                Err(e) => println!("FAILED {e}"),
            }
        }
    }

    fn limits(max_triangles: usize, triangles_before: usize) -> MeshLimits {
        MeshLimits {
            max_triangles,
            triangles_before,
            ..MeshLimits::default()
        }
    }

    #[test]
    fn obj_fan_over_the_triangle_limit_is_refused_from_the_text() {
        let dir = TempDir::new("obj_fan");
        // One polygon of 1002 corners: a fan of 1000 triangles.
        let mut text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf".to_owned();
        for _ in 0..334 {
            text.push_str(" 1 2 3");
        }
        text.push('\n');
        let path = dir.write("fan.obj", &text);
        assert_eq!(
            read_mesh_with(&path, &limits(1000, 0)).unwrap().faces.len(),
            1000
        );
        let err = read_mesh_with(&path, &limits(999, 0)).unwrap_err();
        assert!(
            matches!(err, MeshFileError::TooManyTriangles { line: Some(4), .. }),
            "{err:?}"
        );
        let msg = err.to_string();
        for part in [
            "fan.obj (line 4)",
            "1000 triangles",
            "limit of 999",
            "--max-triangles",
        ] {
            assert!(msg.contains(part), "{msg} lacks {part}");
        }
        // Triangles already in the scene count against the limit.
        let err = read_mesh_with(&path, &limits(1500, 600)).unwrap_err();
        let msg = err.to_string();
        assert!(
            msg.contains("already has 600") && msg.contains("1500"),
            "{msg}"
        );
        assert!(read_mesh_with(&path, &limits(1500, 500)).is_ok());
    }

    #[test]
    fn ply_faces_over_the_triangle_limit_are_refused() {
        let dir = TempDir::new("ply_limit");
        // Six quads: 12 triangles.
        let path = dir.write("cube.ply", cube_ascii());
        assert_eq!(
            read_mesh_with(&path, &limits(12, 0)).unwrap().faces.len(),
            12
        );
        // More faces than triangles left: refused from the header.
        let err = read_mesh_with(&path, &limits(5, 0)).unwrap_err();
        let msg = err.to_string();
        assert!(
            matches!(err, MeshFileError::TooManyTriangles { line: None, .. }),
            "{err:?}"
        );
        assert!(
            msg.contains("declares 6 faces") && msg.contains("--max-triangles"),
            "{msg}"
        );
        // Enough faces but too many triangles once the quads are split: refused while reading.
        let err = read_mesh_with(&path, &limits(11, 0)).unwrap_err();
        let msg = err.to_string();
        assert!(
            msg.contains("face 5 make 12 triangles") && msg.contains("limit of 11"),
            "{msg}"
        );
        let path = dir.write("cube-bin.ply", cube_binary(true));
        assert!(read_mesh_with(&path, &limits(11, 0)).is_err());
        assert!(read_mesh_with(&path, &limits(12, 0)).is_ok());
    }

    #[test]
    fn mesh_file_over_the_size_limit_is_refused() {
        let dir = TempDir::new("mesh_size");
        let path = dir.write("cube.ply", cube_ascii());
        let size = fs::metadata(&path).unwrap().len();
        let with_max = |max_bytes| MeshLimits {
            max_bytes,
            ..MeshLimits::default()
        };
        assert!(read_mesh_with(&path, &with_max(size)).is_ok());
        let err = read_mesh_with(&path, &with_max(size - 1)).unwrap_err();
        let msg = err.to_string();
        assert!(
            msg.contains("cube.ply") && msg.contains("--max-mesh-bytes"),
            "{msg}"
        );
    }

    #[cfg(unix)]
    #[test]
    fn fifo_and_device_meshes_are_refused_without_blocking() {
        let dir = TempDir::new("mesh_fifo");
        let fifo = dir.0.join("pipe.obj");
        let status = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap();
        assert!(status.success());
        let err = read_mesh(&fifo).unwrap_err();
        assert!(err.to_string().contains("FIFO"), "{err}");
        let zero = dir.0.join("zero.ply");
        std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
        let err = read_mesh(&zero).unwrap_err();
        assert!(err.to_string().contains("character device"), "{err}");
    }
}
