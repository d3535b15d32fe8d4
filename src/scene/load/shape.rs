//! Shapes: spheres, cylinders, triangles, quads, planes, boxes and the meshes they become.

use super::spellings::{shape, type_names, type_of, SHAPE_TYPES};
use super::texture::Libraries;
use super::{nearest, required, required_positive, Loader, SPHERE_POLE, SPHERE_SEAM};
use crate::accel::aabb::Aabb;
use crate::geometry::{Cylinder, Mesh, MeshUv, Plane, Primitive, Shape, Sphere};
use crate::math::{Vec2, Vec3};
use crate::scene::json::Node;
use crate::scene::transform::{self, Affine};
use crate::scene::{rectangle, RenderMode, SceneError};

impl Loader<'_> {
    /// Reads the shape `s` into the scene's primitives, with its material; a shape of unknown
    /// `type` is skipped with a warning.
    pub(super) fn shape(
        &mut self,
        s: &Node,
        mode: RenderMode,
        libraries: &mut Libraries,
    ) -> Result<(), SceneError> {
        if !s.is_object() {
            return Err(s.error(format!("a shape is an object, found {}", s.kind())));
        }
        let type_node = required(s, shape::TYPE)?;
        let name = type_node.str()?;
        let Some(kind) = type_of(SHAPE_TYPES, name) else {
            let near = nearest(name, &type_names(SHAPE_TYPES));
            s.mark_all_read(); // skipped whole, with this warning
            self.warn(
                &type_node,
                format!("unknown shape type '{name}' (nearest known: '{near}'); skipped"),
            );
            return Ok(());
        };
        let material = self.material(s, mode, libraries)?;
        match kind {
            "sphere" => self.sphere_shape(s, material),
            "cylinder" => self.cylinder_shape(s, material),
            "triangle" => self.triangle_shape(s, material),
            "quad" => self.quad_shape(s, material),
            "box" => self.box_shape(s, material),
            "rectanglexy" | "rectanglexz" | "rectangleyz" => {
                let r = rectangle::read(s, kind)?;
                self.add_mesh(
                    s,
                    r.corners.to_vec(),
                    None,
                    MeshUv::PerVertex(r.uvs.to_vec()),
                    vec![[0, 1, 2], [0, 2, 3]],
                    material,
                )
            }
            _ => self.mesh(s, material),
        }
    }

    /// A sphere: a centre and a radius.
    fn sphere_shape(&mut self, s: &Node, material: u32) -> Result<(), SceneError> {
        let center = required(s, shape::CENTRE)?.vec3()?;
        let radius = required_positive(s, shape::RADIUS)?;
        self.primitives.push(Primitive {
            shape: Shape::Sphere(Sphere::new(center, radius, SPHERE_POLE, SPHERE_SEAM)),
            material,
        });
        Ok(())
    }

    /// A closed cylinder: a centre, an axis, a radius and its half-height (`height`).
    fn cylinder_shape(&mut self, s: &Node, material: u32) -> Result<(), SceneError> {
        let center = required(s, shape::CENTRE)?.vec3()?;
        let an = required(s, shape::AXIS)?;
        let axis = an.vec3()?;
        if axis.length_squared() == 0.0 {
            return Err(an.error("the axis must not be zero"));
        }
        let radius = required_positive(s, shape::RADIUS)?;
        let half = required_positive(s, shape::HEIGHT)?;
        self.primitives.push(Primitive {
            shape: Shape::Cylinder(Cylinder::new(center, axis, radius, half)),
            material,
        });
        Ok(())
    }

    /// A triangle: three corners, with optional uvs.
    fn triangle_shape(&mut self, s: &Node, material: u32) -> Result<(), SceneError> {
        let p = self.corners(s, 3)?;
        if (p[1] - p[0]).cross(p[2] - p[0]) == Vec3::ZERO {
            return Err(s.error("the triangle has zero area (its corners are collinear)"));
        }
        let uv = self.corner_uvs(s, 3)?.unwrap_or_else(|| {
            vec![
                Vec2::new(0.0, 0.0),
                Vec2::new(1.0, 0.0),
                Vec2::new(1.0, 1.0),
            ]
        });
        self.add_mesh(s, p, None, MeshUv::PerVertex(uv), vec![[0, 1, 2]], material)
    }

    /// A quad (`plane` and its spellings): an infinite plane when it gives a normal and a distance
    /// but no corners, otherwise a parallelogram from its corners, two opposite corners of an
    /// axis-aligned rectangle, or a centre and a size.
    fn quad_shape(&mut self, s: &Node, material: u32) -> Result<(), SceneError> {
        let has_corners = s.contains_any(shape::ANY_CORNERS);
        if (s.contains_any(shape::NORMAL) || s.contains_any(shape::DISTANCE)) && !has_corners {
            let plane = infinite_plane(s)?;
            self.primitives.push(Primitive {
                shape: Shape::Plane(plane),
                material,
            });
            return Ok(());
        }
        let [corner1, corner2] = shape::OPPOSITE_CORNERS;
        let p = if let (Some(a), Some(b)) = (s.get_any(corner1), s.get_any(corner2)) {
            axis_rectangle(s, a.vec3()?, b.vec3()?)?
        } else if !has_corners && s.contains_any(shape::BOX_CENTRE) {
            centred_rectangle(s)?
        } else {
            self.corners(s, 4)?
        };
        // Corners in "Z order" are put in cycle order; explicit uvs follow their corners,
        // the default ones put image pixel (0,0) at v0 and the first row along v0→v1.
        let order = cycle_order([p[0], p[1], p[2], p[3]]);
        let p: Vec<Vec3> = order.iter().map(|&i| p[i]).collect();
        let area2 = (p[1] - p[0]).cross(p[2] - p[0]) + (p[2] - p[0]).cross(p[3] - p[0]);
        if area2 == Vec3::ZERO {
            return Err(s.error("the quad has zero area (its corners are collinear)"));
        }
        let uv = match self.corner_uvs(s, 4)? {
            Some(uv) => order.iter().map(|&i| uv[i]).collect(),
            None => vec![
                Vec2::new(0.0, 0.0),
                Vec2::new(1.0, 0.0),
                Vec2::new(1.0, 1.0),
                Vec2::new(0.0, 1.0),
            ],
        };
        self.add_mesh(
            s,
            p,
            None,
            MeshUv::PerVertex(uv),
            vec![[0, 1, 2], [0, 2, 3]],
            material,
        )
    }

    /// An axis-aligned box, from its `min` and `max` corners or its centre and edge lengths,
    /// optionally rotated.
    fn box_shape(&mut self, s: &Node, material: u32) -> Result<(), SceneError> {
        let (min, max) = if let Some(c) = s.get_any(shape::BOX_CENTRE) {
            // Centre and edge lengths along x (`width`), y (`height`), z (`depth`).
            let c = c.vec3()?;
            let size = Vec3::new(
                required(s, shape::WIDTH)?.f32()?,
                required(s, shape::HEIGHT)?.f32()?,
                required(s, shape::DEPTH)?.f32()?,
            );
            (c - 0.5 * size, c + 0.5 * size)
        } else {
            (
                required(s, shape::MIN)?.vec3()?,
                required(s, shape::MAX)?.vec3()?,
            )
        };
        let (mut p, faces) = box_mesh(min.min(max), min.max(max));
        // A box given by its centre turns about its centre; one given by its corners
        // turns about the world origin (docs/scene-format.md gives the evidence).
        if let Some(r) = transform::rotation(s)? {
            let pivot = if s.has_any(shape::BOX_CENTRE) {
                0.5 * (min + max)
            } else {
                Vec3::ZERO
            };
            let a = Affine {
                linear: r,
                translation: pivot - r * pivot,
            };
            p.iter_mut().for_each(|q| *q = a.point(*q));
        }
        self.add_mesh(s, p, None, MeshUv::Strip, faces, material)
    }

    /// The corner points of a triangle (`n = 3`) or quad (`n = 4`), under any of the spellings.
    pub(super) fn corners(&self, s: &Node, n: usize) -> Result<Vec<Vec3>, SceneError> {
        for keys in shape::CORNER_NAMES {
            if s.get(keys[0]).is_some() {
                return keys[..n]
                    .iter()
                    .map(|k| required(s, &[k])?.vec3())
                    .collect();
            }
        }
        if let Some(list) = s.get_any(shape::POINTS) {
            let e = list.elements()?;
            if n == 4 && e.len() == 3 {
                // Three corners of a parallelogram: complete it at the corner opposite the one
                // where the edges meet squarely.
                let (o, a, b) = right_angle_corner(e[0].vec3()?, e[1].vec3()?, e[2].vec3()?);
                return Ok(vec![o, o + a, o + a + b, o + b]);
            }
            if e.len() != n {
                return Err(list.error(format!("expected {n} points, found {}", e.len())));
            }
            return e.iter().map(|p| p.vec3()).collect();
        }
        Err(s.error(format!(
            "missing the corners 'v0'..'v{}' (or 'point1'..'point{n}', or 'points')",
            n - 1
        )))
    }

    /// The uvs of a triangle's or quad's `n` corners (`uv0`.. or `uv1`..), if it gives them all.
    pub(super) fn corner_uvs(&self, s: &Node, n: usize) -> Result<Option<Vec<Vec2>>, SceneError> {
        for keys in shape::CORNER_UVS {
            if s.get(keys[0]).is_some() && s.get(keys[n - 1]).is_some() {
                let mut out = Vec::with_capacity(n);
                for k in &keys[..n] {
                    let node = required(s, &[k])?;
                    let v = node.numbers()?;
                    if v.len() != 2 {
                        return Err(node.error(format!("expected 2 numbers, found {}", v.len())));
                    }
                    out.push(Vec2::new(v[0] as f32, v[1] as f32));
                }
                return Ok(Some(out));
            }
        }
        Ok(None)
    }

    /// Adds a triangle mesh with `material` to the primitives, within the triangle limit.
    pub(super) fn add_mesh(
        &mut self,
        node: &Node,
        positions: Vec<Vec3>,
        normals: Option<Vec<Vec3>>,
        uv: MeshUv,
        faces: Vec<[u32; 3]>,
        material: u32,
    ) -> Result<(), SceneError> {
        self.triangles += faces.len();
        if self.triangles > self.options.max_triangles {
            return Err(node.error(format!(
                "the scene has over {} triangles (raise the limit with --max-triangles)",
                self.options.max_triangles
            )));
        }
        let mesh = Mesh {
            positions,
            normals,
            uv,
            faces,
        };
        self.primitives.push_mesh(mesh, material);
        Ok(())
    }
}

/// An area light's parallelogram from four corners: the corners in cycle order c0..c3, then the
/// origin c0 and the edges c1 − c0 and c3 − c0 (the corner opposite c0 is not used).
pub(super) fn quad_edges(p: [Vec3; 4]) -> (Vec3, Vec3, Vec3) {
    let [i0, i1, _, i3] = cycle_order(p);
    (p[i0], p[i1] - p[i0], p[i3] - p[i0])
}

/// The order that lists four corners as a cycle. They already are when the diagonals `p0p2` and
/// `p1p3` share a midpoint; corners written in "Z order" (`p3` opposite `p0`, as some files do)
/// are reordered to `p0, p1, p3, p2`.
pub(super) fn cycle_order(p: [Vec3; 4]) -> [usize; 4] {
    let cycle = (p[0] + p[2] - p[1] - p[3]).length_squared();
    let z_order = (p[0] + p[3] - p[1] - p[2]).length_squared();
    if z_order < cycle {
        [0, 1, 3, 2]
    } else {
        [0, 1, 2, 3]
    }
}

/// Three corners of a rectangle: the one where the edges meet most squarely is the origin.
pub(super) fn right_angle_corner(a: Vec3, b: Vec3, c: Vec3) -> (Vec3, Vec3, Vec3) {
    let score = |o: Vec3, x: Vec3, y: Vec3| {
        let (u, v) = ((x - o).normalize_or_zero(), (y - o).normalize_or_zero());
        u.dot(v).abs()
    };
    let options = [(a, b, c), (b, a, c), (c, a, b)];
    let (o, x, y) = options
        .into_iter()
        .min_by(|p, q| score(p.0, p.1, p.2).total_cmp(&score(q.0, q.1, q.2)))
        .unwrap_or((a, b, c));
    (o, x - o, y - o)
}

/// An axis-aligned rectangle from two opposite corners that share one coordinate.
pub(super) fn axis_rectangle(s: &Node, a: Vec3, b: Vec3) -> Result<Vec<Vec3>, SceneError> {
    let d = (b - a).abs();
    let flat = if d.x <= d.y && d.x <= d.z {
        0
    } else if d.y <= d.z {
        1
    } else {
        2
    };
    let (i, j) = ((flat + 1) % 3, (flat + 2) % 3);
    let mut c1 = a;
    c1[i] = b[i];
    let mut c3 = a;
    c3[j] = b[j];
    if d[flat] != 0.0 {
        return Err(s.error("the corners of an axis-aligned rectangle must share one coordinate"));
    }
    if d[i] == 0.0 || d[j] == 0.0 {
        return Err(s.error("the rectangle's corners span no area"));
    }
    Ok(vec![a, c1, b, c3])
}

/// The infinite plane `normal · x = distance` (unit normal): `{"normal": [0, 1, 0], "distance":
/// -1}` is the floor `y = −1`. The corpus files put the plane where the rest of the scene rests
/// only under this sign (docs/scene-format.md).
pub(super) fn infinite_plane(s: &Node) -> Result<Plane, SceneError> {
    let nn = required(s, shape::NORMAL)?;
    let normal = nn.vec3()?;
    if normal == Vec3::ZERO {
        return Err(nn.error("the plane's normal must not be zero"));
    }
    let len = normal.length();
    if !(len.is_finite() && len > 0.0 && (normal / len).is_finite()) {
        return Err(nn.error(format!(
            "the plane's normal [{}, {}, {}] is too long or too short to normalise",
            normal.x, normal.y, normal.z
        )));
    }
    let distance = required(s, shape::DISTANCE)?.f32()?;
    Ok(Plane::new(normal, distance))
}

/// A rectangle given by its centre, `width` (along x) and `height` (along z), lying in the
/// plane y = centre.y with normal +y before the optional rotation (`rot`, `rotation`, `euler`:
/// Euler degrees, see [`transform`]) about its centre. Corners in cycle order, starting at
/// (−width/2, −height/2).
pub(super) fn centred_rectangle(s: &Node) -> Result<Vec<Vec3>, SceneError> {
    let c = required(s, shape::BOX_CENTRE)?.vec3()?;
    let w = required_positive(s, shape::WIDTH)?;
    let h = required_positive(s, shape::HEIGHT)?;
    let r = transform::rotation(s)?.unwrap_or(glam::Mat3::IDENTITY);
    let local = [
        Vec3::new(-0.5 * w, 0.0, -0.5 * h),
        Vec3::new(0.5 * w, 0.0, -0.5 * h),
        Vec3::new(0.5 * w, 0.0, 0.5 * h),
        Vec3::new(-0.5 * w, 0.0, 0.5 * h),
    ];
    Ok(local.iter().map(|&p| c + r * p).collect())
}

/// The 12 triangles of an axis-aligned box.
pub(super) fn box_mesh(lo: Vec3, hi: Vec3) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let corners = Aabb::new(lo, hi);
    let p: Vec<Vec3> = (0..8).map(|i| corners.corner(i)).collect();
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let faces = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    (p, faces)
}
