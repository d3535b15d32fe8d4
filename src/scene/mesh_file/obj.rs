//! The Wavefront OBJ reader.
//!
//! OBJ files are read with `tobj`, triangulated, and re-indexed so that
//! position, normal and texture coordinate share one index; all objects and
//! groups are merged into a single mesh. Normals (`vn`) and texture coordinates
//! (`vt`) are kept only when every vertex of the merged mesh has them. Points
//! (`p`) and polylines (`l`) are ignored. Materials are ignored: `mtllib` and
//! `usemtl` lines are accepted, the `.mtl` files they name are never opened, so
//! a missing or broken one is not an error.

use std::path::Path;

use glam::{Vec2, Vec3};

use super::{malformed, reserve, MeshData, MeshFileError, MeshLimits};

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

/// What [`check_obj`] has counted so far.
#[derive(Default)]
struct ObjTally {
    /// `v`, `vt` and `vn` statements seen.
    counts: [usize; 3],
    /// Triangles the `f` lines make, polygons split into fans.
    triangles: u64,
    /// Largest positive index of each kind, with where it was: `(index, line, face)`.
    largest: [Option<(usize, usize, usize)>; 3],
    /// `f` lines seen so far: the number of the face being read.
    faces: usize,
}

/// Checks what `tobj` does not report precisely (or at all): numbers, face
/// syntax and every index, with line numbers; and counts the triangles the faces
/// make, so that a file over the triangle limit is refused before `tobj` builds it.
fn check_obj(path: &Path, text: &str, limits: &MeshLimits) -> Result<(), MeshFileError> {
    let mut tally = ObjTally::default();
    for (number, line_text) in text.lines().enumerate() {
        let line = number + 1;
        let mut words = line_text.split_whitespace();
        let keyword = words.next();
        match keyword {
            Some("v") => {
                obj_numbers(path, line, &mut words, 3, 0, tally.counts[0])?;
                tally.counts[0] += 1;
            }
            Some("vt") => {
                obj_numbers(path, line, &mut words, 2, 1, tally.counts[1])?;
                tally.counts[1] += 1;
            }
            Some("vn") => {
                obj_numbers(path, line, &mut words, 3, 2, tally.counts[2])?;
                tally.counts[2] += 1;
            }
            Some("f") | Some("l") => {
                let corners = tally.check_corners(path, line, words)?;
                if keyword == Some("f") {
                    tally.add_face(path, line, corners, limits)?;
                }
            }
            _ => {}
        }
    }
    limits.check_memory(path, tally.counts[0] as u64, tally.triangles)?;
    tally.check_largest(path)
}

impl ObjTally {
    /// Checks the corners of an `f` or `l` line, `v/vt/vn` each, and returns how many there are.
    fn check_corners(
        &mut self,
        path: &Path,
        line: usize,
        words: std::str::SplitWhitespace<'_>,
    ) -> Result<usize, MeshFileError> {
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
                    face: self.faces,
                    kind: OBJ_KINDS[kind],
                    index: index as i64,
                    available: self.counts[kind],
                };
                if index == 0 || (index < 0 && index.unsigned_abs() > self.counts[kind]) {
                    return Err(out_of_range());
                }
                if index > 0 {
                    let index = index.unsigned_abs();
                    if self.largest[kind].is_none_or(|(l, _, _)| index > l) {
                        self.largest[kind] = Some((index, line, self.faces));
                    }
                }
            }
        }
        Ok(corners)
    }

    /// Counts an `f` line of `corners` corners, refusing one that is not a polygon or that takes
    /// the triangles over what `limits` leave.
    fn add_face(
        &mut self,
        path: &Path,
        line: usize,
        corners: usize,
        limits: &MeshLimits,
    ) -> Result<(), MeshFileError> {
        if corners < 3 {
            return Err(MeshFileError::FaceTooSmall {
                path: path.to_path_buf(),
                line: Some(line),
                face: self.faces,
                count: corners,
            });
        }
        self.triangles += corners as u64 - 2;
        if self.triangles > limits.triangles_left() {
            return Err(limits.too_many_triangles(
                path,
                Some(line),
                format!(
                    "the OBJ faces up to this line make {} triangles (polygons \
                     split into fans)",
                    self.triangles
                ),
            ));
        }
        self.faces += 1;
        Ok(())
    }

    /// Refuses a positive index past the last entry of its kind in the whole file (an index may
    /// name an entry defined after the face).
    fn check_largest(&self, path: &Path) -> Result<(), MeshFileError> {
        for (kind, largest) in self.largest.iter().enumerate() {
            if let Some((index, line, face)) = *largest {
                if index > self.counts[kind] {
                    return Err(MeshFileError::IndexOutOfRange {
                        path: path.to_path_buf(),
                        line: Some(line),
                        face,
                        kind: OBJ_KINDS[kind],
                        index: i64::try_from(index).unwrap_or(i64::MAX),
                        available: self.counts[kind],
                    });
                }
            }
        }
        Ok(())
    }
}

/// The file as UTF-8 text, or an error naming the line of the first bad byte.
fn obj_text<'a>(path: &Path, bytes: &'a [u8]) -> Result<&'a str, MeshFileError> {
    std::str::from_utf8(bytes).map_err(|e| {
        let valid = bytes.get(..e.valid_up_to()).unwrap_or_default();
        let line = 1 + valid.iter().filter(|&&b| b == b'\n').count();
        malformed(path, Some(line), "the OBJ file is not valid UTF-8 text")
    })
}

/// The models `tobj` reads from `text`, triangulated and single-indexed; `.mtl` files are not
/// opened.
fn load_models(path: &Path, text: &str) -> Result<Vec<tobj::Model>, MeshFileError> {
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
    Ok(models)
}

/// The mesh being merged from `tobj`'s models: normals and texture coordinates stay `Some` while
/// every model so far has them for every vertex.
struct ObjMerge {
    mesh: MeshData,
    normals: Option<Vec<Vec3>>,
    uvs: Option<Vec<Vec2>>,
}

impl ObjMerge {
    /// Room for every model's vertices and triangles, and for normals and texture coordinates
    /// where every model has them.
    fn reserved(path: &Path, models: &[tobj::Model]) -> Result<ObjMerge, MeshFileError> {
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
        Ok(ObjMerge {
            mesh,
            normals: Some(normals),
            uvs: Some(uvs),
        })
    }

    /// Appends one model's vertices and its triangles, re-indexed past the vertices before it.
    fn append(&mut self, path: &Path, model: &tobj::Model) -> Result<(), MeshFileError> {
        let m = &model.mesh;
        let count = m.positions.len() / 3;
        let base = self.mesh.positions.len();
        self.mesh.positions.extend(
            m.positions
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2])),
        );
        if m.normals.len() == count * 3 {
            if let Some(n) = self.normals.as_mut() {
                n.extend(
                    m.normals
                        .chunks_exact(3)
                        .map(|p| Vec3::new(p[0], p[1], p[2])),
                );
            }
        } else {
            self.normals = None;
        }
        if m.texcoords.len() == count * 2 {
            if let Some(t) = self.uvs.as_mut() {
                t.extend(m.texcoords.chunks_exact(2).map(|p| Vec2::new(p[0], p[1])));
            }
        } else {
            self.uvs = None;
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
            self.mesh.faces.push(out);
        }
        Ok(())
    }
}

/// Reads an OBJ file: the text is checked by [`check_obj`] before `tobj` reads it, and all its
/// objects and groups are merged into one mesh.
pub(super) fn parse_obj(
    path: &Path,
    bytes: &[u8],
    limits: &MeshLimits,
) -> Result<MeshData, MeshFileError> {
    let text = obj_text(path, bytes)?;
    check_obj(path, text, limits)?;
    let models = load_models(path, text)?;

    let mut merge = ObjMerge::reserved(path, &models)?;
    for model in &models {
        merge.append(path, model)?;
    }
    let ObjMerge {
        mut mesh,
        normals,
        uvs,
    } = merge;
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
