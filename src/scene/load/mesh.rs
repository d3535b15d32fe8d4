//! Meshes: from a mesh file, a procedural sphere, or vertices and faces written in the scene.

use super::required;
use super::spellings::{type_of, SHAPE_TYPES};
use super::Loader;
use crate::geometry::MeshUv;
use crate::math::Vec2;
use crate::scene::json::Node;
use crate::scene::mesh_file::{read_mesh_with, MeshData, MeshLimits};
use crate::scene::{poly_sphere, transform, SceneError};

/// The keys that name a mesh file.
pub(super) const MESH_FILE_KEYS: &[&str] = &[
    "mPath",
    "plyPath",
    "modelpath",
    "model",
    "path",
    "file",
    "filename",
];

impl Loader<'_> {
    pub(super) fn mesh(&mut self, s: &Node, material: u32) -> Result<(), SceneError> {
        if !s.contains_any(MESH_FILE_KEYS) && poly_sphere::applies(s) {
            let budget = self.options.max_triangles.saturating_sub(self.triangles);
            for m in poly_sphere::read(s, budget)? {
                let uv = m.uvs.map_or(MeshUv::Strip, MeshUv::PerVertex);
                self.add_mesh(s, m.positions, m.normals, uv, m.faces, material)?;
            }
            return Ok(());
        }
        let mut data = if let Some(fnode) = s.get_any(MESH_FILE_KEYS) {
            let rel = fnode.str()?;
            let path = self.resolve(&fnode, rel)?;
            let limits = MeshLimits {
                max_bytes: self.options.max_mesh_bytes,
                max_triangles: self.options.max_triangles,
                triangles_before: self.triangles,
                max_memory: self.options.max_memory,
            };
            let mut data =
                read_mesh_with(&path, &limits).map_err(|e| fnode.error(e.to_string()))?;
            // Counts the scene repeats from the file's header (`vs`, `fs`) must agree with it.
            for (key, what, count) in [
                ("vs", "vertices", data.positions.len()),
                ("fs", "faces", data.faces.len()),
            ] {
                if let Some(n) = s.get(key) {
                    let said = n.u32()?;
                    if said as usize != count && (key == "vs" || said as usize > count) {
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

    /// A mesh written in the scene file. Spellings: `vertices`/`vs` with `faces`/`fs`/`tris`/
    /// `triangles` (lists of index lists, polygons are fanned); `vertex`/`face` counts with
    /// `v0…`/`f0…` keys; `vertexindex`/`verticesOnEachFace` (flat) with `faceindex`/
    /// `numVerticesOnEachFace` (polygon sizes, their count in `faces`) and `texturemap`
    /// (per-vertex uv); `points` alone (consecutive triples when the count is a multiple of 3,
    /// otherwise one convex polygon).
    pub(super) fn inline_mesh(&mut self, s: &Node) -> Result<MeshData, SceneError> {
        let mut positions = Vec::new();
        let counted = s
            .get("vertex")
            .filter(|n| n.numbers().is_err() && n.u32().is_ok());
        let vn = if let Some(count) = counted {
            for i in 0..count.u32()? {
                positions.push(required(s, &[&format!("v{i}")])?.vec3()?);
            }
            count
        } else if let Some(list) = s
            .get("triangles")
            .filter(|t| t.elements().is_ok_and(|e| e.iter().all(|x| x.is_object())))
        {
            // A list of triangle objects, each with its corners.
            let mut faces = Vec::new();
            let mesh_material = s.peek("material").and_then(|m| m.str().ok());
            for t in list.elements()? {
                // Each may say it is a triangle and name the mesh's material again.
                if let Some(k) = t.get("type") {
                    if type_of(SHAPE_TYPES, k.str()?) != Some("triangle") {
                        return Err(k.error("a mesh's triangles are triangles"));
                    }
                }
                if let Some(m) = t.get("material") {
                    if m.str().ok() != mesh_material {
                        self.warn(
                            &m,
                            "a triangle of a mesh has a material of its own; the mesh's is used",
                        );
                    }
                }
                let n = positions.len() as u32;
                for k in ["v0", "v1", "v2"] {
                    positions.push(required(&t, &[k])?.vec3()?);
                }
                faces.push([n, n + 1, n + 2]);
            }
            if faces.is_empty() {
                return Err(list.error("the mesh has no triangles"));
            }
            return Ok(MeshData {
                positions,
                normals: None,
                uvs: None,
                faces,
            });
        } else {
            let vn = required(s, &["vertices", "vs", "vertex", "points"])?;
            for v in vn.elements()? {
                positions.push(v.vec3()?);
            }
            vn
        };
        let check = |node: &Node, i: f64| -> Result<u32, SceneError> {
            if i < 0.0 || i.fract() != 0.0 || i >= positions.len() as f64 {
                return Err(node.error(format!(
                    "vertex index {i} is out of range (the mesh has {} vertices)",
                    positions.len()
                )));
            }
            Ok(i as u32)
        };
        // One face written as a list of vertex indices.
        let indices = |f: &Node| -> Result<Vec<u32>, SceneError> {
            f.numbers()?.into_iter().map(|i| check(f, i)).collect()
        };
        let mut polygons: Vec<(Node, Vec<u32>)> = Vec::new();
        if let (Some(sizes), Some(flat)) = (
            s.get_any(&["faceindex", "numVerticesOnEachFace"]),
            s.get_any(&["vertexindex", "verticesOnEachFace"]),
        ) {
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
                    .map(|&i| check(&flat, i))
                    .collect::<Result<Vec<_>, _>>()?;
                polygons.push((sizes.clone(), ids));
                at += n;
            }
            // A count of the faces beside the sizes must agree with them.
            if let Some(count) = s.get("faces").filter(|n| n.u32().is_ok()) {
                if count.u32()? as usize != polygons.len() {
                    return Err(count.error(format!(
                        "the mesh says it has {} faces but lists the sizes of {}",
                        count.u32()?,
                        polygons.len()
                    )));
                }
            }
        } else if let Some(count) = s.get("face").filter(|n| n.u32().is_ok()) {
            for i in 0..count.u32()? {
                let f = required(s, &[&format!("f{i}")])?;
                let ids = indices(&f)?;
                polygons.push((f, ids));
            }
        } else if let Some(fnode) = s.get_any(&["faces", "fs", "tris", "triangles", "face"]) {
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
            return Err(required(s, &["faces", "fs", "tris", "triangles"])
                .err()
                .unwrap_or_else(|| s.error("missing faces")));
        }
        if polygons.is_empty() {
            return Err(s.error("the mesh has no faces"));
        }
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
        let uvs = match s.get("texturemap") {
            Some(t) => {
                let mut uv = Vec::new();
                for e in t.elements()? {
                    let v = e.numbers()?;
                    if v.len() != 2 {
                        return Err(e.error(format!("expected 2 numbers, found {}", v.len())));
                    }
                    uv.push(Vec2::new(v[0] as f32, v[1] as f32));
                }
                if uv.len() != positions.len() {
                    return Err(t.error(format!(
                        "{} texture coordinates for {} vertices",
                        uv.len(),
                        positions.len()
                    )));
                }
                Some(uv)
            }
            None => None,
        };
        Ok(MeshData {
            positions,
            normals: None,
            uvs,
            faces,
        })
    }
}
