//! Generated "poly spheres": a mesh given by a centre, a size and a count instead of vertices.
//!
//! ```json
//! { "type": "trimesh", "scale": 0.3, "locX": 1.0, "locY": -2.5, "locZ": 0.0, "n": 5 }
//! ```
//! is `n` faceted spheres of radius `2 · scale` centred on `(locX, locY, locZ)`, the k-th
//! (k = 0 … n − 1) cut into `5 + k` latitude bands and `5 + k` longitude segments: the
//! polygonal sphere of the file's own program (radius 2, scaled, with 5, 6, … divisions), all
//! of them, coincident as that program draws them. Each vertex carries the sphere's radial normal,
//! so the facets shade smoothly, and texture coordinates in the frame of the analytic sphere
//! (`v = 0` at the +y pole, `u = 0` facing −x, growing towards +z; see `docs/scene-format.md`).

use super::error::SceneError;
use super::json::Node;
use super::load::spellings::shape;
use super::mesh_file::MeshData;
use crate::math::{Vec2, Vec3};

/// Radius of the unit poly sphere before `scale`.
pub const BASE_RADIUS: f32 = 2.0;
/// Divisions of the first sphere; each further one has one more.
pub const FIRST_DIVISIONS: u32 = 5;
/// Most spheres one shape may ask for: the k-th has about 2·(5 + k)² triangles, so this caps a
/// shape at about 16 million triangles (the scene's triangle limit applies on top).
pub const MAX_COUNT: u32 = 256;

/// Whether `s` is written in this form: none of the vertex keys of an inline mesh, and the
/// count `n` with a centre key.
pub fn applies(s: &Node) -> bool {
    s.contains_any(shape::SPHERE_COUNT)
        && shape::SPHERE_CENTRE.iter().any(|k| s.contains_any(k))
        && !s.contains_any(shape::INLINE_VERTICES)
}

/// Triangles of [`uv_sphere`] with `divisions` bands: a row of `d` at each pole, `2d` in each of
/// the `d − 2` rows between.
pub fn triangle_count(divisions: u32) -> u64 {
    let d = u64::from(divisions.max(3));
    2 * d * d - 2 * d
}

/// Reads the form and builds its meshes, one [`MeshData`] per sphere, unless they would hold
/// more than `max_triangles` (checked before anything is built).
pub fn read(s: &Node, max_triangles: usize) -> Result<Vec<MeshData>, SceneError> {
    let coord = |k: &[&str]| -> Result<f32, SceneError> {
        s.get_any(k)
            .map(|n| n.f32())
            .transpose()
            .map(|v| v.unwrap_or(0.0))
    };
    let [x, y, z] = shape::SPHERE_CENTRE;
    let center = Vec3::new(coord(x)?, coord(y)?, coord(z)?);
    let scale = match s.get_any(shape::SCALE) {
        Some(n) => n.f32()?,
        None => 1.0,
    };
    let radius = BASE_RADIUS * scale;
    if radius <= 0.0 {
        let at = s.get_any(shape::SCALE).unwrap_or_else(|| s.clone());
        return Err(at.error(format!("the scale must be > 0, found {scale}")));
    }
    let count_node = s.get_any(shape::SPHERE_COUNT).unwrap_or_else(|| s.clone());
    let count = count_node.u32()?;
    if count == 0 || count > MAX_COUNT {
        return Err(count_node.error(format!(
            "the number of spheres must be between 1 and {MAX_COUNT}, found {count}"
        )));
    }
    let total: u64 = (0..count)
        .map(|k| triangle_count(FIRST_DIVISIONS + k))
        .sum();
    if total > max_triangles as u64 {
        return Err(count_node.error(format!(
            "{count} spheres make {total} triangles, over the scene's limit (raise it with --max-triangles)"
        )));
    }
    Ok((0..count)
        .map(|k| uv_sphere(center, radius, FIRST_DIVISIONS + k))
        .collect())
}

/// A sphere of `divisions` latitude bands and as many longitude segments, with radial normals.
/// The seam column is doubled (so that `u` runs from 0 to 1 across it) and so are the poles
/// (one per column); pole quads become single triangles.
pub fn uv_sphere(center: Vec3, radius: f32, divisions: u32) -> MeshData {
    let d = divisions.max(3);
    let (pole, meridian) = (Vec3::Y, Vec3::NEG_X);
    let east = pole.cross(meridian);
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    for i in 0..=d {
        let theta = std::f32::consts::PI * i as f32 / d as f32;
        for j in 0..=d {
            let phi = std::f32::consts::TAU * j as f32 / d as f32;
            let n = theta.cos() * pole + theta.sin() * (phi.cos() * meridian + phi.sin() * east);
            positions.push(center + radius * n);
            normals.push(n);
            uvs.push(Vec2::new(j as f32 / d as f32, i as f32 / d as f32));
        }
    }
    let at = |i: u32, j: u32| i * (d + 1) + j;
    let mut faces = Vec::new();
    for i in 0..d {
        for j in 0..d {
            let (a, b, c, e) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if i > 0 {
                faces.push([a, b, e]);
            }
            if i + 1 < d {
                faces.push([e, b, c]);
            }
        }
    }
    MeshData {
        positions,
        normals: Some(normals),
        uvs: Some(uvs),
        faces,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangle_count_is_what_uv_sphere_builds() {
        for d in [1, 3, 5, 6, 17, 40] {
            let m = uv_sphere(Vec3::ZERO, 1.0, d);
            assert_eq!(m.faces.len() as u64, triangle_count(d), "divisions {d}");
        }
    }

    #[test]
    fn vertices_lie_on_the_sphere_and_faces_close_it() {
        let c = Vec3::new(1.0, -2.5, 0.0);
        let m = uv_sphere(c, 0.6, 5);
        for p in &m.positions {
            assert!(((*p - c).length() - 0.6).abs() < 1e-5);
        }
        // 5 bands of 5 segments: two triangles per quad, one at each pole row.
        assert_eq!(m.faces.len(), 2 * 5 * 5 - 2 * 5);
        // Closed: the signed volume is that of the inscribed polyhedron, a bit under 4/3 π r³.
        let volume: f32 = m
            .faces
            .iter()
            .map(|f| {
                let [a, b, e] = f.map(|i| m.positions[i as usize] - c);
                a.dot(b.cross(e)) / 6.0
            })
            .sum::<f32>()
            .abs();
        let ball = 4.0 / 3.0 * std::f32::consts::PI * 0.6f32.powi(3);
        assert!(volume < ball && volume > 0.6 * ball, "{volume} vs {ball}");
        // The top pole is +y with v = 0.
        assert_eq!(m.uvs.as_ref().unwrap()[0].y, 0.0);
        assert!((m.positions[0] - (c + 0.6 * Vec3::Y)).length() < 1e-6);
    }
}
