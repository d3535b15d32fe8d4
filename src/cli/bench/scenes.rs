//! The benchmark scenes, built in code so that other tracers can build the same ones: the
//! sphere grid of the ray-throughput sets and Table 1, and the random scenes of the `auto`
//! crossover. Scenes are pure functions of their parameters.

use std::path::{Path, PathBuf};

use raytracer::camera::{Camera, Handedness};
use raytracer::geometry::{Mesh, MeshUv, Primitive, Primitives, Shape, Sphere, Triangle};
use raytracer::light::{Intensity, Light};
use raytracer::material::Material;
use raytracer::math::{orthonormal_basis, Vec2, Vec3};
use raytracer::sampling::{hash, to_unit, Method};
use raytracer::scene::{RenderMode, Scene, Variant};

/// Number of triangles of [`sphere_grid`]: `2·S²` per sphere (pole quads give degenerate
/// triangles, still counted) plus the two of the ground quad.
pub fn sphere_grid_triangles(g: u32, s: u32) -> usize {
    (g as usize).pow(2) * 2 * (s as usize).pow(2) + 2
}

/// The ray-throughput scene, specified so that other tracers can build the same one: a `G×G` grid
/// of UV spheres, sphere `(i, j)` centred at `(i − G/2 + 0.5, 0.45, j − G/2 + 0.5)` with radius
/// 0.45, each made of `S×S` latitude/longitude quads (θ from 0 to π, φ from 0 to 2π, point
/// `c + r·(sin θ cos φ, cos θ, sin θ sin φ)`) split into two triangles, on a ground quad `y = 0`
/// spanning `x, z ∈ [−G, G]`. Camera at `(0, 0.6G, −1.1G)` looking at the origin, up `+y`, 60°
/// horizontal field of view, `width × height` pixels. A point light at `(0, 2G, 0)`.
pub fn sphere_grid(g: u32, s: u32, width: u32, height: u32) -> Scene {
    let mut primitives = Primitives::default();
    primitives.push_mesh(ground_quad(g), 0);
    primitives.push_mesh(grid_spheres(g, s), 0);
    let light = grid_light(g);
    procedural_scene(
        grid_camera(g, width, height),
        primitives,
        point_light(light, light.length_squared()),
        Vec3::splat(0.05),
    )
}

/// The grid's ground: the quad `y = 0` over `x, z ∈ [−G, G]` as two triangles.
fn ground_quad(g: u32) -> Mesh {
    let gf = g as f32;
    Mesh {
        positions: vec![
            Vec3::new(-gf, 0.0, -gf),
            Vec3::new(gf, 0.0, -gf),
            Vec3::new(gf, 0.0, gf),
            Vec3::new(-gf, 0.0, gf),
        ],
        normals: None,
        uv: MeshUv::PerVertex(vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 1.0),
        ]),
        faces: vec![[0, 1, 2], [0, 2, 3]],
    }
}

/// The grid's `G×G` UV spheres of `S×S` quads each, as one mesh with vertex normals.
fn grid_spheres(g: u32, s: u32) -> Mesh {
    let ring = s as usize + 1;
    let per_sphere = ring * ring;
    let spheres = (g as usize).pow(2);
    let mut positions = Vec::with_capacity(spheres * per_sphere);
    let mut normals = Vec::with_capacity(spheres * per_sphere);
    let mut uvs = Vec::with_capacity(spheres * per_sphere);
    let mut faces = Vec::with_capacity(spheres * 2 * (s as usize).pow(2));
    let half = g as f64 / 2.0;
    for i in 0..g {
        for j in 0..g {
            let c = Vec3::new(
                (i as f64 - half + 0.5) as f32,
                0.45,
                (j as f64 - half + 0.5) as f32,
            );
            let base = positions.len() as u32;
            for a in 0..=s {
                let theta = std::f64::consts::PI * a as f64 / s as f64;
                for b in 0..=s {
                    let phi = std::f64::consts::TAU * b as f64 / s as f64;
                    let n = Vec3::new(
                        (theta.sin() * phi.cos()) as f32,
                        theta.cos() as f32,
                        (theta.sin() * phi.sin()) as f32,
                    );
                    positions.push(c + 0.45 * n);
                    normals.push(n);
                    uvs.push(Vec2::new(b as f32 / s as f32, a as f32 / s as f32));
                }
            }
            let r = ring as u32;
            for a in 0..s {
                for b in 0..s {
                    let v00 = base + a * r + b;
                    let (v10, v11, v01) = (v00 + r, v00 + r + 1, v00 + 1);
                    faces.push([v00, v10, v11]);
                    faces.push([v00, v11, v01]);
                }
            }
        }
    }
    Mesh {
        positions,
        normals: Some(normals),
        uv: MeshUv::PerVertex(uvs),
        faces,
    }
}

/// The grid's camera: at `(0, 0.6G, −1.1G)` looking at the origin, up `+y`, 60° horizontal
/// field of view.
fn grid_camera(g: u32, width: u32, height: u32) -> Camera {
    let gf = g as f32;
    let eye = Vec3::new(0.0, 0.6 * gf, -1.1 * gf);
    let fov_y = 2.0 * ((30.0f32).to_radians().tan() * height as f32 / width as f32).atan();
    Camera::new(
        eye,
        -eye,
        Vec3::Y,
        Handedness::ForwardCrossUp,
        width,
        height,
        fov_y.to_degrees(),
        None,
    )
    .expect("the grid camera's direction is not parallel to +y")
}

/// A scene built in code from its parts: Phong shading of one bounce, no ambient light, every
/// primitive of the default material (index 0), no textures, warnings or input files.
fn procedural_scene(
    camera: Camera,
    primitives: Primitives,
    light: Light,
    background: Vec3,
) -> Scene {
    Scene {
        variant: Variant::V2021,
        camera,
        nbounces: 1,
        background,
        mode: RenderMode::Phong,
        exposure: 1.0,
        ambient: Vec3::ZERO,
        reflection: raytracer::material::Reflection::Added,
        pixel_samples: None,
        pixel_method: None,
        tone_map: None,
        light_samples: None,
        lights: vec![light],
        primitives,
        materials: vec![Material::default()],
        textures: Vec::new(),
        has_transmissive: false,
        warnings: Vec::new(),
        inputs: Vec::new(),
    }
}

/// A point light at `position` whose diffuse and specular intensities are `intensity` in every
/// channel, falling off with the square of the distance.
fn point_light(position: Vec3, intensity: f32) -> Light {
    Light::Point {
        position,
        intensity: Intensity {
            diffuse: Vec3::splat(intensity),
            specular: Vec3::splat(intensity),
            falloff: raytracer::light::Falloff::InverseSquare { scale: 1.0 },
        },
    }
}

/// The light position of the grid scene: `(0, 2G, 0)`.
pub fn grid_light(g: u32) -> Vec3 {
    Vec3::new(0.0, 2.0 * g as f32, 0.0)
}

/// Bytes of the primitive records (and of the runs standing in for large meshes' records).
pub fn primitive_bytes(scene: &Scene) -> usize {
    scene.primitives.record_bytes()
}

/// The lights of a benchmark scene: its own kinds, or all point or all area lights.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LightVariant {
    /// Every light a point light (a quad becomes a point at its centre).
    Point,
    /// Every light a 16-sample jittered quad (a point becomes a square around it).
    Area,
}

impl LightVariant {
    /// The variant's name in the table's `light` column.
    pub fn name(self) -> &'static str {
        match self {
            LightVariant::Point => "point",
            LightVariant::Area => "area",
        }
    }
}

/// Shadow rays per shading point of an area light in the `area` variant.
pub const AREA_SAMPLES: u32 = 16;

/// `scene` with its lights replaced according to `variant`. An area light made from a point light
/// is a square facing the scene's centre, its side 5% of the scene's diagonal.
pub fn with_lights(scene: &Scene, variant: LightVariant) -> Scene {
    let bounds = scene
        .primitives
        .iter()
        .filter(|p| p.shape.is_bounded())
        .fold(raytracer::accel::aabb::Aabb::EMPTY, |b, p| {
            b.union(p.shape.bounds())
        });
    let (centre, diagonal) = if bounds == raytracer::accel::aabb::Aabb::EMPTY {
        (Vec3::ZERO, 1.0)
    } else {
        (bounds.center(), bounds.extent().length())
    };
    let lights = scene
        .lights
        .iter()
        .map(|l| light_variant(l, variant, centre, diagonal))
        .collect();
    Scene {
        lights,
        ..scene.clone()
    }
}

/// `l` as a light of `variant` in a scene whose bounds have `centre` and `diagonal` (see
/// [`with_lights`]).
fn light_variant(l: &Light, variant: LightVariant, centre: Vec3, diagonal: f32) -> Light {
    match (variant, l) {
        (LightVariant::Point, _) if l.is_point() => l.clone(),
        (LightVariant::Point, _) => Light::Point {
            position: l.center(),
            intensity: *l.intensity(),
        },
        (
            LightVariant::Area,
            Light::Point {
                position,
                intensity,
            },
        ) => {
            let facing = (centre - *position).normalize_or(Vec3::Y);
            let (u, v) = orthonormal_basis(facing);
            let side = 0.05 * diagonal;
            Light::quad(
                *position - 0.5 * side * (u + v),
                side * u,
                side * v,
                *intensity,
                AREA_SAMPLES,
                Method::Jittered,
            )
        }
        (LightVariant::Area, _) => l.clone().with_samples(AREA_SAMPLES, Method::Jittered),
    }
}

/// `n` primitives (alternately spheres and triangles) at hashed random places in the cube
/// `[-1, 1]³`, seen from `(0, 0, -4)`, lit by one point light. With `backdrop`, the first two
/// primitives are instead the halves of a quad behind the cube that fills the view, so that every
/// camera ray hits something.
pub fn random_scene(n: usize, width: u32, height: u32, backdrop: bool) -> Scene {
    let u = |i: usize, d: u64| to_unit(hash(&[i as u64, d, 0x5eed]));
    let v = |i: usize, d: u64| 2.0 * Vec3::new(u(i, d), u(i, d + 1), u(i, d + 2)) - Vec3::ONE;
    let mut meshes = Vec::new();
    let mut primitives = Vec::new();
    let quad = [
        Vec3::new(-4.0, -4.0, 2.0),
        Vec3::new(4.0, -4.0, 2.0),
        Vec3::new(4.0, 4.0, 2.0),
        Vec3::new(-4.0, 4.0, 2.0),
    ];
    for i in 0..n {
        let c = v(i, 0);
        let shape = if backdrop && i < 2 {
            let p = if i == 0 {
                [quad[0], quad[1], quad[2]]
            } else {
                [quad[0], quad[2], quad[3]]
            };
            lone_triangle(p, &mut meshes)
        } else if i % 2 == 0 {
            Shape::Sphere(Sphere::new(c, 0.05 + 0.2 * u(i, 3), Vec3::Y, Vec3::X))
        } else {
            lone_triangle([c, c + 0.4 * v(i, 4), c + 0.4 * v(i, 7)], &mut meshes)
        };
        primitives.push(Primitive { shape, material: 0 });
    }
    let eye = Vec3::new(0.0, 0.0, -4.0);
    let camera = Camera::new(
        eye,
        -eye,
        Vec3::Y,
        Handedness::ForwardCrossUp,
        width,
        height,
        35.0,
        None,
    )
    .expect("valid camera");
    procedural_scene(
        camera,
        Primitives::from_records(primitives, meshes),
        point_light(Vec3::new(2.0, 3.0, -3.0), 20.0),
        Vec3::ZERO,
    )
}

/// A triangle with corners `p` in a one-face mesh of its own, which is appended to `meshes`.
fn lone_triangle(p: [Vec3; 3], meshes: &mut Vec<Mesh>) -> Shape {
    meshes.push(Mesh {
        positions: p.to_vec(),
        normals: None,
        uv: MeshUv::Strip,
        faces: vec![[0, 1, 2]],
    });
    Shape::Triangle(Triangle {
        p,
        mesh: meshes.len() as u32 - 1,
        face: 0,
    })
}

/// The default folder of the bundled scenes: `scenes/` in the working directory if it has the
/// Table 1 files, else the one in the source tree this binary was built from.
pub fn default_scenes_dir() -> PathBuf {
    let here = Path::new("scenes");
    if here.join("example.json").is_file() {
        here.to_path_buf()
    } else {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_triangle_counts_are_as_specified() {
        assert_eq!(sphere_grid_triangles(4, 16), 8_194);
        assert_eq!(sphere_grid_triangles(16, 32), 524_290);
        assert_eq!(sphere_grid_triangles(32, 64), 8_388_610);
        let scene = sphere_grid(4, 16, 8, 6);
        assert_eq!(scene.primitives.len(), 8_194);
        assert_eq!(scene.primitives.triangle_count(), 8_194);
    }

    #[test]
    fn grid_vertices_lie_on_their_spheres() {
        let scene = sphere_grid(2, 8, 8, 6);
        for p in scene.primitives.iter().skip(2) {
            let Shape::Triangle(t) = &p.shape else {
                panic!("only triangles");
            };
            let c = Vec3::new(
                (t.p[0].x + 1.0).floor() - 0.5,
                0.45,
                (t.p[0].z + 1.0).floor() - 0.5,
            );
            for v in t.p {
                assert!(((v - c).length() - 0.45).abs() < 1e-5, "{v} {c}");
            }
        }
    }
}
