//! The PLY reader: ASCII, `binary_little_endian` and `binary_big_endian` files.
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

use std::io::{BufRead, ErrorKind};
use std::path::Path;

use glam::{Vec2, Vec3};
use ply_rs_bw::parser::{ParseError, Parser, Reader};
use ply_rs_bw::ply::{
    BeginList, ElementDef, Encoding, Header, PropertyAccess, PropertyAccessResult, PropertyType,
    ScalarType,
};

use super::{malformed, reserve, MeshData, MeshFileError, MeshLimits};

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
/// The slot of `nx`; `ny` and `nz` follow it.
const SLOT_NX: usize = 3;
/// Texture coordinate pairs, first complete one wins.
const UV_PAIRS: [(usize, usize); 3] = [(6, 7), (8, 9), (10, 11)];
/// Names of the face's vertex index list, first found wins.
const FACE_LISTS: [&str; 2] = ["vertex_indices", "vertex_index"];

/// One PLY vertex: the known scalar properties, converted to `f32`.
struct VertexElement {
    slots: [f32; VERTEX_SLOTS.len()],
}

impl VertexElement {
    /// Stores `value` in the slot of property `name`, if this reader knows it.
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
    /// The [`FACE_LISTS`] entry named `name`.
    fn slot(name: &str) -> Option<usize> {
        FACE_LISTS.iter().position(|s| *s == name)
    }

    /// Stores an index list of a signed or narrow type, keeping the first negative index aside.
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

/// Whether `t` is an integer type.
fn is_integer(t: &ScalarType) -> bool {
    !matches!(t, ScalarType::Float | ScalarType::Double)
}

/// Bytes of one binary value of type `t`.
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
    /// The ASCII line being read, kept to reuse its allocation.
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

/// [`ply_error_text`] for a binary payload, where running out of bytes means truncation.
fn binary_error_text(error: &ParseError) -> String {
    if error.kind() == ErrorKind::UnexpectedEof {
        "the file ends early (truncated)".to_owned()
    } else {
        ply_error_text(error)
    }
}

/// The error for element `index` of `def` that could not be read.
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

/// The header's elements as this reader uses them.
struct Layout<'h> {
    /// The elements up to the later of `vertex` and `face`, in file order: those after both are
    /// never read.
    read: Vec<&'h ElementDef>,
    vertex: &'h ElementDef,
    face: &'h ElementDef,
    /// Whether the vertices have `nx`, `ny` and `nz`.
    has_normals: bool,
    /// The [`VERTEX_SLOTS`] of the texture coordinate pair read, if any.
    uv_pair: Option<(usize, usize)>,
    /// The [`FACE_LISTS`] entry that holds a face's vertex indices.
    face_list: usize,
}

/// Finds the `vertex` and `face` elements and the properties read from them.
fn header_layout<'h>(path: &Path, header: &'h Header) -> Result<Layout<'h>, MeshFileError> {
    let mut elements: Vec<&ElementDef> = header.elements.values().collect();
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
    let vertex = elements[vertex_pos];
    let face = elements[face_pos];
    let (has_normals, uv_pair) = vertex_properties(path, vertex)?;
    let face_list = face_list_slot(path, face)?;
    elements.truncate(vertex_pos.max(face_pos) + 1);
    Ok(Layout {
        read: elements,
        vertex,
        face,
        has_normals,
        uv_pair,
        face_list,
    })
}

/// Checks `x`, `y`, `z` and finds whether normals and which texture coordinates are there.
fn vertex_properties(
    path: &Path,
    vertex: &ElementDef,
) -> Result<(bool, Option<(usize, usize)>), MeshFileError> {
    for name in ["x", "y", "z"] {
        if !scalar_property(path, vertex, name)? {
            return Err(malformed(
                path,
                None,
                format!("the PLY 'vertex' element has no '{name}' property"),
            ));
        }
    }
    let mut has_normals = true;
    for name in ["nx", "ny", "nz"] {
        has_normals &= scalar_property(path, vertex, name)?;
    }
    let mut uv_pair = None;
    for (u, v) in UV_PAIRS {
        let has_u = scalar_property(path, vertex, VERTEX_SLOTS[u])?;
        let has_v = scalar_property(path, vertex, VERTEX_SLOTS[v])?;
        if has_u && has_v && uv_pair.is_none() {
            uv_pair = Some((u, v));
        }
    }
    Ok((has_normals, uv_pair))
}

/// The [`FACE_LISTS`] entry of the face's vertex index list, which must hold integers.
fn face_list_slot(path: &Path, face: &ElementDef) -> Result<usize, MeshFileError> {
    for (slot, name) in FACE_LISTS.iter().enumerate() {
        match face.properties.get(*name).map(|p| &p.data_type) {
            Some(PropertyType::List(_, item)) if is_integer(item) => return Ok(slot),
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
    Err(malformed(
        path,
        None,
        "the PLY 'face' element has no 'vertex_indices' or 'vertex_index' list property",
    ))
}

impl Layout<'_> {
    /// Refuses element counts that cannot fit in the `available` payload bytes.
    fn check_room(
        &self,
        path: &Path,
        encoding: Encoding,
        available: u64,
    ) -> Result<(), MeshFileError> {
        let mut needed = 0u64;
        for def in &self.read {
            let bytes = (def.count as u64).saturating_mul(min_element_bytes(def, encoding));
            needed = needed.saturating_add(bytes);
            // The final line of an ASCII file may lack its line break.
            let needed_here = match encoding {
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
        Ok(())
    }

    /// Refuses a header whose vertex count, face count or memory is over `limits`.
    fn check_limits(&self, path: &Path, limits: &MeshLimits) -> Result<(), MeshFileError> {
        let vertex_count = self.vertex.count;
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
        let face_count = self.face.count;
        if face_count as u64 > limits.triangles_left() {
            return Err(limits.too_many_triangles(
                path,
                None,
                format!("the PLY header declares {face_count} faces (each at least one triangle)"),
            ));
        }
        limits.check_memory(path, vertex_count as u64, face_count as u64)
    }
}

/// What the payload gives: the mesh, with normals and texture coordinates beside it until the
/// end.
#[derive(Default)]
struct PlyBuffers {
    mesh: MeshData,
    normals: Vec<Vec3>,
    uvs: Vec<Vec2>,
}

/// Reads the `vertex` element `def`: positions, and normals and texture coordinates where the
/// layout has them, each checked to be finite.
fn read_vertices(
    path: &Path,
    cursor: &mut PlyCursor<'_>,
    def: &ElementDef,
    layout: &Layout<'_>,
    out: &mut PlyBuffers,
) -> Result<(), MeshFileError> {
    let (has_normals, uv_pair) = (layout.has_normals, layout.uv_pair);
    let parser = Parser::<VertexElement>::new();
    reserve(path, &mut out.mesh.positions, def.count, "vertices")?;
    if has_normals {
        reserve(path, &mut out.normals, def.count, "normals")?;
    }
    if uv_pair.is_some() {
        reserve(path, &mut out.uvs, def.count, "texture coordinates")?;
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
        out.mesh.positions.push(p);
        if has_normals {
            let n = Vec3::new(s[SLOT_NX], s[SLOT_NX + 1], s[SLOT_NX + 2]);
            if !n.is_finite() {
                return Err(non_finite("normal"));
            }
            out.normals.push(n);
        }
        if let Some((u, v)) = uv_pair {
            let uv = Vec2::new(s[u], s[v]);
            if !uv.is_finite() {
                return Err(non_finite("texture coordinate"));
            }
            out.uvs.push(uv);
        }
    }
    Ok(())
}

/// Reads the `face` element `def` into `faces`, checking every index and splitting polygons into
/// fans, under the triangles `limits` leave.
fn read_faces(
    path: &Path,
    cursor: &mut PlyCursor<'_>,
    def: &ElementDef,
    layout: &Layout<'_>,
    limits: &MeshLimits,
    faces: &mut Vec<[u32; 3]>,
) -> Result<(), MeshFileError> {
    let (face_list, vertex_count) = (layout.face_list, layout.vertex.count);
    let parser = Parser::<FaceElement>::new();
    reserve(path, faces, def.count, "triangles")?;
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
        reserve(path, faces, indices.len() - 2, "triangles")?;
        for pair in indices[1..].windows(2) {
            faces.push([first, pair[0], pair[1]]);
        }
    }
    Ok(())
}

/// Reads past an element this reader does not use.
fn skip_element(
    path: &Path,
    cursor: &mut PlyCursor<'_>,
    def: &ElementDef,
) -> Result<(), MeshFileError> {
    let parser = Parser::<SkipElement>::new();
    for i in 0..def.count {
        cursor
            .read(&parser, def)
            .map_err(|e| element_error(path, def, i, e))?;
    }
    Ok(())
}

/// Reads a PLY file: the header is checked against the payload's size and `limits` before any
/// element is read.
pub(super) fn parse_ply(
    path: &Path,
    bytes: &[u8],
    limits: &MeshLimits,
) -> Result<MeshData, MeshFileError> {
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

    let layout = header_layout(path, &header)?;
    layout.check_room(path, header.encoding, payload.len() as u64)?;
    layout.check_limits(path, limits)?;

    let mut cursor = PlyCursor {
        data: payload,
        encoding: header.encoding,
        line: first_payload_line,
        buf: String::new(),
    };
    let mut out = PlyBuffers::default();
    for def in &layout.read {
        if def.name == "vertex" {
            read_vertices(path, &mut cursor, def, &layout, &mut out)?;
        } else if def.name == "face" {
            read_faces(path, &mut cursor, def, &layout, limits, &mut out.mesh.faces)?;
        } else {
            skip_element(path, &mut cursor, def)?;
        }
    }

    let PlyBuffers {
        mut mesh,
        normals,
        uvs,
    } = out;
    if mesh.faces.is_empty() {
        return Err(MeshFileError::NoTriangles {
            path: path.to_path_buf(),
            detail: String::new(),
        });
    }
    if layout.has_normals {
        mesh.normals = Some(normals);
    }
    if layout.uv_pair.is_some() {
        mesh.uvs = Some(uvs);
    }
    Ok(mesh)
}
