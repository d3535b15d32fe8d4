//! Triangle meshes: shared vertex buffers with optional per-vertex normals and texture
//! coordinates. Planar quads and single triangles are small meshes too.
//!
//! ```json
//! { "type": "trimesh", "vertices": [[0,0,0], [1,0,0], [0,1,0]], "faces": [[0,1,2]], "material": { … } }
//! { "type": "mesh", "mPath": "../meshes/bunny.ply", "material": { … } }
//! ```

use crate::math::{Vec2, Vec3};

/// Where a mesh's texture coordinates come from.
#[derive(Debug, Clone, PartialEq)]
pub enum MeshUv {
    /// Explicit per-vertex coordinates (from a PLY/OBJ file, or a quad's corners).
    PerVertex(Vec<Vec2>),
    /// No coordinates in the input: face `i` of `n` is unwrapped onto the vertical strip
    /// `u ∈ [i/n, (i+1)/n]` of the image, its corners at `(u₀, 0)`, `(u₁, 0)`, `(u₀, 1)`
    /// (faces in file order, so neighbouring faces get neighbouring strips).
    Strip,
}

/// A triangle mesh: vertex buffers shared by its faces, which are triples of vertex indices.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    pub positions: Vec<Vec3>,
    /// Per-vertex unit normals, if the input had them.
    pub normals: Option<Vec<Vec3>>,
    pub uv: MeshUv,
    pub faces: Vec<[u32; 3]>,
}

impl Mesh {
    /// Bytes of the buffers: positions, normals, texture coordinates and faces.
    pub fn bytes(&self) -> usize {
        let uv = match &self.uv {
            MeshUv::PerVertex(uv) => std::mem::size_of_val(uv.as_slice()),
            MeshUv::Strip => 0,
        };
        std::mem::size_of_val(self.positions.as_slice())
            + self
                .normals
                .as_ref()
                .map_or(0, |n| std::mem::size_of_val(n.as_slice()))
            + uv
            + std::mem::size_of_val(self.faces.as_slice())
    }

    /// The vertex normals of a face, if the mesh has them.
    #[inline]
    pub fn vertex_normals(&self, face: usize) -> Option<[Vec3; 3]> {
        let n = self.normals.as_ref()?;
        let [a, b, c] = self.faces[face];
        Some([n[a as usize], n[b as usize], n[c as usize]])
    }

    /// The texture coordinates of a face's three corners.
    #[inline]
    pub fn face_uvs(&self, face: usize) -> [Vec2; 3] {
        match &self.uv {
            MeshUv::PerVertex(uv) => {
                let [a, b, c] = self.faces[face];
                [uv[a as usize], uv[b as usize], uv[c as usize]]
            }
            MeshUv::Strip => {
                let n = self.faces.len().max(1) as f32;
                let u0 = face as f32 / n;
                let u1 = (face + 1) as f32 / n;
                [Vec2::new(u0, 0.0), Vec2::new(u1, 0.0), Vec2::new(u0, 1.0)]
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strip_unwrap_gives_each_face_its_own_strip() {
        let mesh = Mesh {
            positions: vec![Vec3::ZERO; 4],
            normals: None,
            uv: MeshUv::Strip,
            faces: vec![[0, 1, 2], [0, 2, 3]],
        };
        assert_eq!(
            mesh.face_uvs(1),
            [
                Vec2::new(0.5, 0.0),
                Vec2::new(1.0, 0.0),
                Vec2::new(0.5, 1.0)
            ]
        );
        assert!(mesh.vertex_normals(0).is_none());
    }
}
