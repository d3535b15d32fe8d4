//! Meshes: from a mesh file, a procedural sphere, or vertices and faces written in the scene.

use super::required;
use super::spellings::{shape, type_of, SHAPE_TYPES};
use super::Loader;
use crate::geometry::MeshUv;
use crate::math::{Vec2, Vec3};
use crate::scene::json::Node;
use crate::scene::mesh_file::{read_mesh_with, MeshData, MeshLimits};
use crate::scene::{poly_sphere, transform, SceneError};

impl Loader<'_> {
    /// A mesh shape: poly spheres, a mesh file, or a mesh written in the scene, placed by its
    /// scale, rotation and translation keys.
    pub(super) fn mesh(&mut self, s: &Node, material: u32) -> Result<(), SceneError> {
        if !s.contains_any(shape::MESH_FILE) && poly_sphere::applies(s) {
            let budget = self.options.max_triangles.saturating_sub(self.triangles);
            for m in poly_sphere::read(s, budget)? {
                let uv = m.uvs.map_or(MeshUv::Strip, MeshUv::PerVertex);
                self.add_mesh(s, m.positions, m.normals, uv, m.faces, material)?;
            }
            return Ok(());
        }
        let mut data = if let Some(fnode) = s.get_any(shape::MESH_FILE) {
            let rel = fnode.str()?;
            let path = self.find_asset(&fnode, rel)?;
            let limits = MeshLimits {
                max_bytes: self.options.max_mesh_bytes,
                max_triangles: self.options.max_triangles,
                triangles_before: self.triangles,
                max_memory: self.options.max_memory,
            };
            let mut data =
                read_mesh_with(&path, &limits).map_err(|e| fnode.error(e.to_string()))?;
            // Counts the scene repeats from the file's header (`vs`, `fs`) must agree with it: the
            // vertices exactly, the faces at most (the file's polygons become more triangles).
            for (keys, what, count, exact) in [
                (shape::VERTEX_COUNT, "vertices", data.positions.len(), true),
                (shape::FACE_COUNT, "faces", data.faces.len(), false),
            ] {
                if let Some(n) = s.get_any(keys) {
                    let said = n.u32()?;
                    if said as usize != count && (exact || said as usize > count) {
                        self.warn(
                            &n,
                            format!(
                                "the scene says the mesh has {said} {what}, its file {count}; \
                                 the file's are used"
                            ),
                        );
                    }
                }
            }
            // PLY and OBJ files put v = 0 at the bottom of the image (the OpenGL convention of
            // the tools that write them); textures here have v = 0 at the top row.
            if let Some(uvs) = data.uvs.as_mut() {
                uvs.iter_mut().for_each(|uv| uv.y = 1.0 - uv.y);
            }
            data
        } else {
            self.inline_mesh(s)?
        };
        // Scale, then rotate, then translate.
        let placement = transform::mesh_placement(s)?;
        transform::place_mesh(&placement, &mut data.positions, &mut data.normals);
        let uv = match data.uvs {
            Some(uv) => MeshUv::PerVertex(uv),
            None => MeshUv::Strip,
        };
        self.add_mesh(s, data.positions, data.normals, uv, data.faces, material)
    }

    /// A mesh written in the scene file: its vertices, its faces (polygons are fanned into
    /// triangles) and optional per-vertex uvs (`texturemap`).
    pub(super) fn inline_mesh(&mut self, s: &Node) -> Result<MeshData, SceneError> {
        let counted = s
            .get_any(shape::COUNTED_VERTICES)
            .filter(|n| n.numbers().is_err() && n.u32().is_ok());
        let (positions, vn) = if let Some(count) = counted {
            (counted_vertices(s, &count)?, count)
        } else if let Some(list) = s
            .get_any(shape::TRIANGLE_OBJECTS)
            .filter(|t| t.elements().is_ok_and(|e| e.iter().all(|x| x.is_object())))
        {
            return self.triangle_objects(s, &list);
        } else {
            let vn = required(s, shape::VERTICES)?;
            let mut positions = Vec::new();
            for v in vn.elements()? {
                positions.push(v.vec3()?);
            }
            (positions, vn)
        };
        let polygons = polygons(s, &vn, &positions)?;
        let faces = fan(polygons)?;
        let uvs = texture_map(s, positions.len())?;
        Ok(MeshData {
            positions,
            normals: None,
            uvs,
            faces,
        })
    }

    /// A mesh written as a `triangles` list of triangle objects, each with its corners
    /// `v0`..`v2` (and perhaps its `type` and the mesh's `material` again).
    fn triangle_objects(&mut self, s: &Node, list: &Node) -> Result<MeshData, SceneError> {
        let mut positions = Vec::new();
        let mut faces = Vec::new();
        let mesh_material = s.get_any(shape::MATERIAL).and_then(|m| m.str().ok());
        for t in list.elements()? {
            if let Some(k) = t.get_any(shape::TYPE) {
                if type_of(SHAPE_TYPES, k.str()?) != Some("triangle") {
                    return Err(k.error("a mesh's triangles are triangles"));
                }
            }
            if let Some(m) = t.get_any(shape::MATERIAL) {
                if m.str().ok() != mesh_material {
                    self.warn(
                        &m,
                        "a triangle of a mesh has a material of its own; the mesh's is used",
                    );
                }
            }
            let n = positions.len() as u32;
            for k in &shape::CORNER_NAMES[0][..3] {
                positions.push(required(&t, &[k])?.vec3()?);
            }
            faces.push([n, n + 1, n + 2]);
        }
        if faces.is_empty() {
            return Err(list.error("the mesh has no triangles"));
        }
        Ok(MeshData {
            positions,
            normals: None,
            uvs: None,
            faces,
        })
    }
}

/// One face of an inline mesh: the node it was read from (for messages) and its vertex indices.
type Polygon<'a, 't> = (Node<'a, 't>, Vec<u32>);

/// The vertices of a mesh that gives their count in `vertex` and each in a key `v0`, `v1`, ….
fn counted_vertices(s: &Node, count: &Node) -> Result<Vec<Vec3>, SceneError> {
    let mut positions = Vec::new();
    for i in 0..count.u32()? {
        let key = format!("{}{i}", shape::VERTEX_PREFIX);
        positions.push(required(s, &[&key])?.vec3()?);
    }
    Ok(positions)
}

/// An inline mesh's faces, under any of their spellings: polygon sizes (`faceindex`) with a flat
/// index list (`vertexindex`); a `face` count with `f0`, `f1`, … keys; lists of index lists
/// (`faces`, `tris`, …); or, for a mesh given by `points` alone, consecutive triples when their
/// count is a multiple of 3 and one convex polygon otherwise. `vn` is the node of the vertices.
fn polygons<'a, 't>(
    s: &Node<'a, 't>,
    vn: &Node<'a, 't>,
    positions: &[Vec3],
) -> Result<Vec<Polygon<'a, 't>>, SceneError> {
    let vertices = positions.len();
    // One face written as a list of vertex indices.
    let indices = |f: &Node| -> Result<Vec<u32>, SceneError> {
        f.numbers()?
            .into_iter()
            .map(|i| vertex_index(f, i, vertices))
            .collect()
    };
    let mut polygons: Vec<Polygon> = Vec::new();
    if let (Some(sizes), Some(flat)) =
        (s.get_any(shape::FACE_SIZES), s.get_any(shape::FLAT_INDICES))
    {
        polygons = sized_faces(s, &sizes, &flat, vertices)?;
    } else if let Some(count) = s.get_any(shape::COUNTED_FACES).filter(|n| n.u32().is_ok()) {
        for i in 0..count.u32()? {
            let f = required(s, &[&format!("{}{i}", shape::FACE_PREFIX)])?;
            let ids = indices(&f)?;
            polygons.push((f, ids));
        }
    } else if let Some(fnode) = s.get_any(shape::FACES) {
        for f in fnode.elements()? {
            let ids = indices(&f)?;
            polygons.push((f, ids));
        }
    } else if vn.path.ends_with("points") && !positions.is_empty() {
        let n = positions.len() as u32;
        if n.is_multiple_of(3) {
            for t in 0..n / 3 {
                polygons.push((vn.clone(), vec![3 * t, 3 * t + 1, 3 * t + 2]));
            }
        } else {
            polygons.push((vn.clone(), (0..n).collect()));
        }
    } else {
        return Err(required(s, shape::FACES)
            .err()
            .unwrap_or_else(|| s.error("missing faces")));
    }
    if polygons.is_empty() {
        return Err(s.error("the mesh has no faces"));
    }
    Ok(polygons)
}

/// Faces given by their sizes (`sizes`, `faceindex`) and one flat list of all their vertex
/// indices (`flat`, `vertexindex`); a `faces` count beside them must agree.
fn sized_faces<'a, 't>(
    s: &Node<'a, 't>,
    sizes: &Node<'a, 't>,
    flat: &Node<'a, 't>,
    vertices: usize,
) -> Result<Vec<Polygon<'a, 't>>, SceneError> {
    let mut polygons = Vec::new();
    let idx = flat.numbers()?;
    let mut at = 0usize;
    for (k, size) in sizes.numbers()?.into_iter().enumerate() {
        // `at + n` could overflow for a huge size (1e30 saturates to usize::MAX), so the
        // size is compared with what is left; `at <= idx.len()` holds on every pass.
        let n = size.max(0.0) as usize;
        let left = idx.len() - at;
        if n > left {
            return Err(sizes.error(format!(
                "face {k} needs {size} indices but '{}' has only {left} left",
                flat.key().unwrap_or("vertexindex")
            )));
        }
        let ids = idx[at..at + n]
            .iter()
            .map(|&i| vertex_index(flat, i, vertices))
            .collect::<Result<Vec<_>, _>>()?;
        polygons.push((sizes.clone(), ids));
        at += n;
    }
    if let Some(count) = s.get_any(shape::FACE_TOTAL).filter(|n| n.u32().is_ok()) {
        if count.u32()? as usize != polygons.len() {
            return Err(count.error(format!(
                "the mesh says it has {} faces but lists the sizes of {}",
                count.u32()?,
                polygons.len()
            )));
        }
    }
    Ok(polygons)
}

/// The vertex index `i` read at `node`, checked against the mesh's count of `vertices`.
fn vertex_index(node: &Node, i: f64, vertices: usize) -> Result<u32, SceneError> {
    if i < 0.0 || i.fract() != 0.0 || i >= vertices as f64 {
        return Err(node.error(format!(
            "vertex index {i} is out of range (the mesh has {vertices} vertices)"
        )));
    }
    Ok(i as u32)
}

/// The triangles of `polygons`, each fanned from its first vertex.
fn fan(polygons: Vec<Polygon>) -> Result<Vec<[u32; 3]>, SceneError> {
    let mut faces = Vec::new();
    for (node, ids) in polygons {
        if ids.len() < 3 {
            return Err(node.error(format!(
                "a face needs at least 3 vertex indices, found {}",
                ids.len()
            )));
        }
        for k in 1..ids.len() - 1 {
            faces.push([ids[0], ids[k], ids[k + 1]]);
        }
    }
    Ok(faces)
}

/// A mesh's per-vertex texture coordinates (`texturemap`: one `[u, v]` per vertex), if it gives
/// them.
fn texture_map(s: &Node, vertices: usize) -> Result<Option<Vec<Vec2>>, SceneError> {
    let Some(t) = s.get_any(shape::TEXTURE_MAP) else {
        return Ok(None);
    };
    let mut uv = Vec::new();
    for e in t.elements()? {
        let v = e.numbers()?;
        if v.len() != 2 {
            return Err(e.error(format!("expected 2 numbers, found {}", v.len())));
        }
        uv.push(Vec2::new(v[0] as f32, v[1] as f32));
    }
    if uv.len() != vertices {
        return Err(t.error(format!(
            "{} texture coordinates for {vertices} vertices",
            uv.len()
        )));
    }
    Ok(Some(uv))
}
