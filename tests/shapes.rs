//! The shape and texture forms of real scene files beyond corners and spheres: infinite planes,
//! rotated boxes and rectangles, placed meshes, `rectangleXY`-style rectangles, generated poly
//! spheres and the named texture library (see docs/scene-format.md).

mod common;

use common::*;
use raytracer::accel::{Accel, AccelKind};
use raytracer::geometry::{MeshUv, Shape};
use raytracer::math::{Vec2, Vec3};
use raytracer::ray::Ray;
use raytracer::scene::{load, LoadOptions};

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() < 1e-5
}

const CAM: &str = r#""camera": { "type": "pinhole", "width": 16, "height": 16, "fov": 40 }"#;

/// The corner positions of the scene's only mesh.
fn mesh_points(json: &str) -> Vec<Vec3> {
    let s = load_json(json);
    assert_eq!(s.primitives.meshes().len(), 1, "{json}");
    s.primitives.meshes()[0].positions.clone()
}

#[test]
fn an_infinite_plane_lies_at_distance_along_its_normal_and_is_hit_far_outside_every_box() {
    // The floor of the isaacery scenes: spheres of radius 1 at y = 0 rest on n·x = d = −1.
    let s = load_json(&format!(
        r#"{{ {CAM}, "scene": {{ "shapes": [
            {{ "type": "sphere", "center": [-1, 0, -3], "radius": 1 }},
            {{ "type": "sphere", "center": [1, 0, -3], "radius": 1 }},
            {{ "type": "sphere", "center": [3, 0, -3], "radius": 1 }},
            {{ "type": "sphere", "center": [5, 0, -3], "radius": 1 }},
            {{ "type": "sphere", "center": [7, 0, -3], "radius": 1 }},
            {{ "type": "sphere", "center": [9, 0, -3], "radius": 1 }},
            {{ "type": "sphere", "center": [11, 0, -3], "radius": 1 }},
            {{ "type": "sphere", "center": [13, 0, -3], "radius": 1 }},
            {{ "type": "plane", "distance": -1, "normal": [0, 2, 0] }} ] }} }}"#
    ));
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    let Shape::Plane(p) = &s.primitives.get(8).shape else {
        panic!("not a plane: {:?}", s.primitives.get(8).shape);
    };
    assert_eq!((p.normal, p.distance), (Vec3::Y, -1.0));
    for kind in [AccelKind::Sah, AccelKind::None] {
        let accel = Accel::build(&s.primitives, kind, 4);
        // Straight down onto a sphere: the sphere's top at y = 1.
        let down = Ray::new(Vec3::new(-1.0, 10.0, -3.0), -Vec3::Y);
        let (i, c) = accel.closest(&s.primitives, &down, f32::INFINITY).unwrap();
        assert_eq!((i, c.t), (0, 9.0), "{kind}");
        // Thousands of units from every sphere: the floor at y = −1.
        let far = Ray::new(Vec3::new(-4000.0, 10.0, 2500.0), -Vec3::Y);
        let (i, c) = accel.closest(&s.primitives, &far, f32::INFINITY).unwrap();
        assert_eq!((i, c.t), (8, 11.0), "{kind}");
        let hit = s.primitives.get(8).hit(&far, c, i, s.primitives.meshes());
        assert_eq!(hit.point, Vec3::new(-4000.0, -1.0, 2500.0));
        assert_eq!(hit.uv, Vec2::new(-4000.0, 2500.0));
        // Under the floor, looking down: nothing.
        let under = Ray::new(Vec3::new(0.0, -2.0, -3.0), -Vec3::Y);
        assert!(accel
            .closest(&s.primitives, &under, f32::INFINITY)
            .is_none());
    }
}

#[test]
fn a_box_given_by_corners_turns_about_the_origin_and_one_given_by_its_centre_about_that() {
    // min/max with `rotation` [0, 90, 0]: a quarter turn about +y takes (x, y, z) to (z, y, −x).
    let p = mesh_points(&format!(
        r#"{{ {CAM}, "shapes": [ {{ "type": "box", "min": [2, 0, 0], "max": [3, 1, 1],
              "rotation": [0, 90, 0] }} ] }}"#
    ));
    let expect = |q: Vec3| Vec3::new(q.z, q.y, -q.x);
    for (got, corner) in p.iter().zip([
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(3.0, 0.0, 0.0),
        Vec3::new(2.0, 1.0, 0.0),
        Vec3::new(3.0, 1.0, 0.0),
        Vec3::new(2.0, 0.0, 1.0),
        Vec3::new(3.0, 0.0, 1.0),
        Vec3::new(2.0, 1.0, 1.0),
        Vec3::new(3.0, 1.0, 1.0),
    ]) {
        assert_eq!(*got, expect(corner));
    }
    // Centre and `rot` [0, 45, 0]: the corners stay at the centre's height range, on a circle of
    // radius √2/2 about the centre, at 45° to the axes.
    let c = Vec3::new(1.5, 0.5, -1.5);
    let p = mesh_points(&format!(
        r#"{{ {CAM}, "shapes": [ {{ "type": "box", "center": [1.5, 0.5, -1.5], "rot": [0, 45, 0],
              "width": 1, "height": 1, "depth": 1 }} ] }}"#
    ));
    for q in &p {
        let d = *q - c;
        assert!((d.y.abs() - 0.5).abs() < 1e-6);
        assert!((Vec2::new(d.x, d.z).length() - 0.5f32.sqrt()).abs() < 1e-6);
        assert!(d.x.abs() < 1e-6 || d.z.abs() < 1e-6, "{d}: not on an axis");
    }
    // Euler order x, then y, then z: [90, 90, 0] takes the corner (1, 0, 0) of a unit cube at
    // the origin to (0, 0, −1) (x turn: unchanged; y turn: x → −z).
    let p = mesh_points(&format!(
        r#"{{ {CAM}, "shapes": [ {{ "type": "box", "min": [0, 0, 0], "max": [1, 1, 1],
              "rotation": [90, 90, 0] }} ] }}"#
    ));
    assert!(p.contains(&Vec3::new(0.0, 0.0, -1.0)), "{p:?}");
}

#[test]
fn a_rectangle_given_by_centre_and_rotation_stands_where_its_rotation_says() {
    // The wall of the box-and-planes example: an xz rectangle turned −90° about z is the plane
    // x = −1.5, spanning y and z by ±10.
    let p = mesh_points(&format!(
        r#"{{ {CAM}, "geometry": [ {{ "type": "plane", "center": [-1.5, 0.5, -1],
              "rot": [0, 0, -90], "width": 20, "height": 20 }} ] }}"#
    ));
    assert_eq!(p.len(), 4);
    for q in &p {
        assert_eq!(q.x, -1.5);
        assert_eq!((q.y - 0.5).abs(), 10.0);
        assert_eq!((q.z + 1.0).abs(), 10.0);
    }
    // Unrotated, it is a floor.
    let p = mesh_points(&format!(
        r#"{{ {CAM}, "geometry": [ {{ "type": "plane", "center": [0, -1, 0], "rot": [0, 0, 0],
              "width": 20, "height": 4 }} ] }}"#
    ));
    assert!(p
        .iter()
        .all(|q| q.y == -1.0 && q.x.abs() == 10.0 && q.z.abs() == 2.0));
}

#[test]
fn meshes_are_scaled_then_rotated_then_translated() {
    let tri = r#""vertices": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "faces": [[0, 1, 2]]"#;
    // Euler [0, 0, 90] about z: x → y, y → −x; scale 2 first, then the offset.
    let p = mesh_points(&format!(
        r#"{{ {CAM}, "shapes": [ {{ "type": "trimesh", {tri}, "scale": 2, "euler": [0, 0, 90],
              "offset": [10, 0, 0] }} ] }}"#
    ));
    assert_eq!(
        p,
        vec![
            Vec3::new(10.0, 2.0, 0.0),
            Vec3::new(8.0, 0.0, 0.0),
            Vec3::new(10.0, 0.0, 2.0)
        ]
    );
    // r1, r2, r3 are the images of the axes: the dragon's rows [1,0,0], [0,0,1], [0,−1,0] stand
    // a y-up model up along +z.
    let p = mesh_points(&format!(
        r#"{{ {CAM}, "shapes": [ {{ "type": "trimesh", {tri}, "scale": 15, "pos": [0, 2.7, -0.5],
              "r1": [1, 0, 0], "r2": [0, 0, 1], "r3": [0, -1, 0] }} ] }}"#
    ));
    assert!(close(p[1], Vec3::new(0.0, 2.7, 14.5)), "{p:?}"); // +y went up (+z)
    assert!(close(p[2], Vec3::new(0.0, -12.3, -0.5)), "{p:?}"); // +z went to −y
                                                                // A non-uniform scale before the rotation: [2, 1, 1] then 90° about z puts x's stretch on y.
    let p = mesh_points(&format!(
        r#"{{ {CAM}, "shapes": [ {{ "type": "trimesh", {tri}, "scale": [2, 1, 1],
              "rotation": [0, 0, 90] }} ] }}"#
    ));
    assert_eq!(p[0], Vec3::new(0.0, 2.0, 0.0));
    assert_eq!(p[1], Vec3::new(-1.0, 0.0, 0.0));
}

#[test]
fn mesh_file_normals_follow_the_inverse_transpose() {
    let dir = tempfile::tempdir().unwrap();
    // One triangle in the plane x + y = 1 with its normal (1, 1, 0)/√2 at every vertex.
    let n = 0.5f32.sqrt();
    std::fs::write(
        dir.path().join("t.ply"),
        format!(
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
             property float z\nproperty float nx\nproperty float ny\nproperty float nz\n\
             element face 1\nproperty list uchar int vertex_indices\nend_header\n\
             1 0 0 {n} {n} 0\n0 1 0 {n} {n} 0\n1 0 1 {n} {n} 0\n3 0 1 2\n"
        ),
    )
    .unwrap();
    let scene = dir.path().join("s.json");
    std::fs::write(
        &scene,
        format!(
            r#"{{ {CAM}, "shapes": [ {{ "type": "ply", "path": "t.ply", "scale": [3, 1, 1],
                  "euler": [0, 0, 30] }} ] }}"#
        ),
    )
    .unwrap();
    let s = load(&scene, &LoadOptions::default()).unwrap();
    let m = &s.primitives.meshes()[0];
    let face_normal = (m.positions[1] - m.positions[0])
        .cross(m.positions[2] - m.positions[0])
        .normalize();
    for vn in m.normals.as_ref().expect("normals kept") {
        assert!((vn.length() - 1.0).abs() < 1e-5);
        // Still perpendicular to the (stretched, turned) face: the plain image would not be.
        assert!(
            vn.dot(face_normal).abs() > 1.0 - 1e-5,
            "{vn} vs {face_normal}"
        );
    }
}

#[test]
fn rectangle_xy_xz_and_yz_span_their_ranges_with_upright_uvs() {
    let s = load_json(&format!(
        r#"{{ {CAM}, "shapes": [
            {{ "type": "rectangleXY", "x0": -0.7, "x1": -0.4, "y0": -0.6, "y1": -0.2, "z": -0.4 }},
            {{ "type": "rectanglexz", "x0": 0, "x1": 5, "z0": 5, "z1": 0, "y": 1 }},
            {{ "type": "rectangleYZ", "y0": 0, "y1": 2, "z0": 0, "z1": 3, "k": 7 }} ] }}"#
    ));
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    let xy = &s.primitives.meshes()[0];
    assert!(xy.positions.iter().all(|p| p.z == -0.4));
    assert!(xy.positions.contains(&Vec3::new(-0.7, -0.2, -0.4)));
    // Image pixel (0, 0) at the top-left corner (x0, y1) seen from +z.
    let MeshUv::PerVertex(uv) = &xy.uv else {
        panic!("no uvs")
    };
    let i = xy
        .positions
        .iter()
        .position(|p| *p == Vec3::new(-0.7, -0.2, -0.4))
        .unwrap();
    assert_eq!(uv[i], Vec2::ZERO);
    let meshes = s.primitives.meshes();
    assert!(meshes[1].positions.iter().all(|p| p.y == 1.0));
    assert!(meshes[1].positions.contains(&Vec3::new(5.0, 1.0, 5.0)));
    assert!(meshes[2].positions.iter().all(|p| p.x == 7.0));
    assert!(meshes[2].positions.contains(&Vec3::new(7.0, 2.0, 3.0)));
}

#[test]
fn a_trimesh_of_n_poly_spheres_builds_n_spheres() {
    let s = load_json(&format!(
        r#"{{ {CAM}, "shapes": [ {{ "id": "polygon", "type": "trimesh", "scale": 0.3,
              "locX": 1.0, "locY": -2.5, "locZ": 0.0, "n": 3 }} ] }}"#
    ));
    assert_eq!(s.primitives.meshes().len(), 3);
    let c = Vec3::new(1.0, -2.5, 0.0);
    for (k, m) in s.primitives.meshes().iter().enumerate() {
        let d = 5 + k;
        assert_eq!(m.faces.len(), 2 * d * d - 2 * d);
        assert!(m
            .positions
            .iter()
            .all(|p| ((*p - c).length() - 0.6).abs() < 1e-5));
    }
}

const LIT: &str = r#""camera": { "type": "pinhole", "width": 12, "height": 12, "fov": 40,
    "position": [0, 0, 3], "lookat": [0, 0, -1], "up": [0, 1, 0] },
    "lightsources": [ { "type": "pointlight", "position": [0, 0, 3], "intensity": 9 } ]"#;

#[test]
fn a_constant_library_texture_colours_the_hit_like_a_diffuse_colour() {
    let colour = "[0.04, 0.42, 0.01]";
    let textured = render_default(&format!(
        r#"{{ {LIT},
            "textures": [ {{ "name": "tex1", "type": "constant", "colour": {colour} }} ],
            "materials": [ {{ "name": "mat1", "kd": 0.75, "texture": "tex1",
                              "diffusecolor": [1, 0, 1] }} ],
            "shapes": [ {{ "type": "plane", "normal": [0, 0, 1], "distance": -1, "material": "mat1" }} ] }}"#
    ));
    let plain = render_default(&format!(
        r#"{{ {LIT},
            "shapes": [ {{ "type": "plane", "normal": [0, 0, 1], "distance": -1,
                           "material": {{ "kd": 0.75, "diffusecolor": {colour} }} }} ] }}"#
    ));
    for (i, (a, b)) in textured.pixels.iter().zip(&plain.pixels).enumerate() {
        assert_eq!(a, b, "pixel {i}");
    }
    // Not black: the plane fills the view and is lit.
    assert!(plain.pixels.iter().all(|p| p.y > 0.0));
}

#[test]
fn image_library_textures_take_their_offsets_and_load_once() {
    let dir = tempfile::tempdir().unwrap();
    // A 4×1 image: red, green, blue, white.
    std::fs::write(
        dir.path().join("strip.ppm"),
        b"P3\n4 1\n255\n255 0 0  0 255 0  0 0 255  255 255 255\n",
    )
    .unwrap();
    let scene = dir.path().join("s.json");
    std::fs::write(
        &scene,
        format!(
            r#"{{ {CAM}, "scene": {{
                "textures": [ {{ "name": "a", "type": "image", "image": "strip.ppm" }},
                              {{ "name": "b", "type": "image", "image": "strip.ppm", "offset_u": 0.25,
                                 "offset_v": 0.5 }} ],
                "shapes": [ {{ "type": "sphere", "center": [0, 0, -3], "radius": 1, "material": {{ "texture": "a" }} }},
                            {{ "type": "sphere", "center": [0, 0, -6], "radius": 1, "material": {{ "texture": "b" }} }},
                            {{ "type": "sphere", "center": [0, 0, -9], "radius": 1, "material": {{ "texture": "b" }} }} ] }} }}"#
        ),
    )
    .unwrap();
    let s = load(&scene, &LoadOptions::default()).unwrap();
    // One image, and one shifted copy for the second entry, used by two shapes.
    assert_eq!(s.textures.len(), 2);
    let (a, b) = (&s.textures[0], &s.textures[1]);
    assert_eq!(b.offset, Vec2::new(0.25, -0.5));
    assert_eq!(s.materials[1].texture, s.materials[2].texture);
    // Texel 1 (green) of the plain image is what the shifted one shows a quarter to the left.
    assert_eq!(a.sample(Vec2::new(0.375, 0.5)), Vec3::Y);
    assert_eq!(b.sample(Vec2::new(0.125, 0.0)), Vec3::Y);
}

#[test]
fn unknown_texture_names_warn_once_per_name() {
    let s = load_json(&format!(
        r#"{{ {CAM}, "shapes": [
            {{ "type": "sphere", "center": [0, 0, -3], "radius": 1, "material": {{ "texture": "rainbow" }} }},
            {{ "type": "sphere", "center": [0, 1, -3], "radius": 1, "material": {{ "texture": "rainbow" }} }},
            {{ "type": "sphere", "center": [0, 2, -3], "radius": 1, "material": {{ "texture": "wood" }} }} ] }}"#
    ));
    let messages: Vec<&str> = s.warnings.iter().map(|w| w.message.as_str()).collect();
    assert_eq!(messages.len(), 2, "{messages:?}");
    assert!(messages[0].contains("no texture named 'rainbow'"));
    assert!(messages[0].contains("diffuse colour is used"));
    assert!(messages[1].contains("'wood'"));
    assert!(s.materials.iter().all(|m| m.texture.is_none()));
}
