//! The loader's reading of each variant, spelling and convention (see docs/scene-format.md).

mod common;

use common::*;
use raytracer::film::ToneMap;
use raytracer::geometry::{MeshUv, Shape};
use raytracer::light::{Falloff, Light};
use raytracer::material::Reflection;
use raytracer::math::{Vec2, Vec3};
use raytracer::scene::{load, LoadOptions, RenderMode, Variant};

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() < 1e-5
}

const CAM_2021: &str = r#""camera": { "type": "pinhole", "width": 40, "height": 20, "fov": 30,
    "position": [1, 2, 3], "lookat": [0, 1, 0], "up": [0, 0, 1] }"#;

#[test]
fn variants_are_told_apart_and_lookat_spellings_differ() {
    // 2021: `lookat` is a direction.
    let s = load_json(&format!(r#"{{ {CAM_2021}, "scene": {{}} }}"#));
    assert_eq!(s.variant, Variant::V2021);
    assert!(close(s.camera.forward, Vec3::Y));
    assert!(close(s.camera.right, Vec3::X)); // forward × up
                                             // CGR: `lookAt` is a target point, and the image x axis is up × forward.
    let s = load_json(
        r#"{ "rendermode": "phong", "camera": { "type": "pinhole", "width": 40, "height": 20, "fov": 30,
             "position": [1, 2, 3], "lookAt": [1, 5, 3], "upVector": [0, 0, 1], "exposure": 2 }, "scene": {} }"#,
    );
    assert_eq!(s.variant, Variant::Cgr);
    assert!(close(s.camera.forward, Vec3::Y));
    assert!(close(s.camera.right, -Vec3::X));
    assert_eq!(s.exposure, 2.0);
    // CGR camera keys without `rendermode` are CGR too.
    let s = load_json(
        r#"{ "camera": { "width": 4, "height": 4, "fov": 30, "position": [0, 0, 0],
             "lookAt": [0, 0, -1], "upVector": [0, 1, 0] }, "scene": {} }"#,
    );
    assert_eq!(s.variant, Variant::Cgr);
    // 2019: no pose: at the origin, looking down −z, +y up.
    let s = load_json(
        r#"{ "camera": { "type": "pinhole", "width": 4, "height": 4, "fov": 30 }, "scene": {} }"#,
    );
    assert_eq!(s.variant, Variant::V2019);
    assert_eq!(
        (s.camera.position, s.camera.forward, s.camera.up),
        (Vec3::ZERO, -Vec3::Z, Vec3::Y)
    );
    // A zero `lookat` direction is read as the point to look at, with a warning.
    let s = load_json(
        r#"{ "camera": { "width": 4, "height": 4, "fov": 30, "position": [0, 0, 3], "lookat": [0, 0, 0], "up": [0, 1, 0] }, "scene": {} }"#,
    );
    assert!(close(s.camera.forward, -Vec3::Z));
    assert_eq!(
        s.warnings
            .iter()
            .filter(|w| w.message.contains("is a direction"))
            .count(),
        1
    );
}

#[test]
fn fov_is_vertical_and_hfov_horizontal() {
    let s = load_json(r#"{ "camera": { "width": 200, "height": 100, "hfov": 90 }, "scene": {} }"#);
    // tan(hfov/2) = aspect · tan(fov_y/2) → fov_y = 2·atan(1/2).
    assert!((s.camera.fov_y() - 2.0 * 0.5f32.atan()).abs() < 1e-5);
}

#[test]
fn size_overrides_keep_the_aspect_ratio() {
    let (_d, path) = write_scene(&format!(r#"{{ {CAM_2021}, "scene": {{}} }}"#));
    let s = load(
        &path,
        &LoadOptions {
            width: Some(100),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!((s.camera.width, s.camera.height), (100, 50));
    let s = load(
        &path,
        &LoadOptions {
            height: Some(10),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!((s.camera.width, s.camera.height), (20, 10));
}

#[test]
fn light_spellings_and_falloff() {
    let s = load_json(&format!(
        r#"{{ {CAM_2021}, "scene": {{ "lightsources": [
            {{ "type": "pointlight", "position": [0, 0, 1], "is": [1, 2, 3], "id": [4, 5, 6] }},
            {{ "type": "pointlight", "position": [0, 0, 1], "intensity": [0.5, 0.5, 0.5] }},
            {{ "type": "arealight", "v0": [0, 0, 0], "v1": [1, 0, 0], "v2": [0, 1, 0], "v3": [1, 1, 0],
               "samples": 3, "method": "jittered", "is": [1, 1, 1], "id": [1, 1, 1] }},
            {{ "type": "arealight", "position": [0, 5, 0], "u": [1, 0, 0], "v": [0, 0, 1], "width": 2, "height": 4,
               "samples": 5, "method": "random", "intensity": [1, 1, 1] }},
            {{ "type": "pointlightss", "position": [0, 0, 0] }} ] }} }}"#
    ));
    assert_eq!(s.lights.len(), 4);
    let four_pi = 4.0 * std::f32::consts::PI;
    let Light::Point { intensity, .. } = &s.lights[0] else {
        panic!()
    };
    assert_eq!(
        (intensity.specular, intensity.diffuse),
        (Vec3::new(1.0, 2.0, 3.0), Vec3::new(4.0, 5.0, 6.0))
    );
    let Falloff::InverseSquare { scale } = intensity.falloff else {
        panic!("{:?}", intensity.falloff)
    };
    assert!((scale - 1.0 / four_pi).abs() < 1e-7);
    let Light::Point { intensity, .. } = &s.lights[1] else {
        panic!()
    };
    assert_eq!(intensity.falloff, Falloff::InverseSquare { scale: 1.0 });
    // Corners in "Z order" (v3 opposite v0) become the same parallelogram; jittered samples is
    // the grid side.
    let Light::Quad {
        origin,
        edge_u,
        edge_v,
        samples,
        ..
    } = &s.lights[2]
    else {
        panic!()
    };
    assert_eq!(
        (*origin, *edge_u, *edge_v, *samples),
        (Vec3::ZERO, Vec3::X, Vec3::Y, 9)
    );
    // Centre + unit directions + size; random samples is the total.
    let Light::Quad {
        origin,
        edge_u,
        edge_v,
        samples,
        ..
    } = &s.lights[3]
    else {
        panic!()
    };
    assert_eq!(
        (*origin, *edge_u, *edge_v, *samples),
        (Vec3::new(-1.0, 5.0, -2.0), Vec3::X * 2.0, Vec3::Z * 4.0, 5)
    );
    // The disabled light is skipped with a warning naming the nearest type.
    assert!(s
        .warnings
        .iter()
        .any(|w| w.message.contains("'pointlightss'") && w.message.contains("'pointlight'")));
}

#[test]
fn material_spellings_map_onto_kr_kt_eta() {
    let s = load_json(&format!(
        r#"{{ {CAM_2021}, "scene": {{ "shapes": [
            {{ "type": "sphere", "center": [0, 0, 0], "radius": 1,
               "material": {{ "isreflective": true, "reflectivity": 0.4, "isrefractive": true, "refractiveindex": 1.3 }} }},
            {{ "type": "sphere", "center": [0, 0, 0], "radius": 1,
               "material": {{ "isreflective": false, "reflectivity": 1.0, "isrefractive": false, "refractiveindex": 0 }} }},
            {{ "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": {{ "kr": 0.3, "kt": 0.5 }} }} ] }} }}"#
    ));
    let m = &s.materials;
    assert_eq!((m[0].kr, m[0].kt, m[0].eta), (0.4, 1.0, 1.3));
    assert_eq!((m[1].kr, m[1].kt), (0.0, 0.0));
    assert_eq!((m[2].kr, m[2].kt, m[2].eta), (0.3, 0.5, 1.5));
    // A named material library.
    let s = load_json(&format!(
        r#"{{ {CAM_2021}, "scene": {{ "materials": [ {{ "name": "red", "colour": [1, 0, 0], "alpha": 7 }} ],
            "shapes": [ {{ "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "red" }} ] }} }}"#
    ));
    assert_eq!(
        (s.materials[0].diffuse, s.materials[0].exponent),
        (Vec3::X, 7.0)
    );
}

#[test]
fn quads_keep_v0_at_texel_zero_and_z_order_is_repaired() {
    let cycle = load_json(&format!(
        r#"{{ {CAM_2021}, "scene": {{ "shapes": [ {{ "type": "plane",
            "v0": [0, 0, 0], "v1": [1, 0, 0], "v2": [1, 1, 0], "v3": [0, 1, 0] }} ] }} }}"#
    ));
    let z_order = load_json(&format!(
        r#"{{ {CAM_2021}, "scene": {{ "shapes": [ {{ "type": "plane",
            "v0": [0, 0, 0], "v1": [1, 0, 0], "v2": [0, 1, 0], "v3": [1, 1, 0] }} ] }} }}"#
    ));
    for s in [&cycle, &z_order] {
        assert_eq!(s.primitives.len(), 2);
        let m = &s.primitives.meshes()[0];
        assert_eq!(
            m.positions,
            vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y]
        );
        assert_eq!(
            m.uv,
            MeshUv::PerVertex(vec![Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y])
        );
    }
}

#[test]
fn file_meshes_flip_v_to_the_image_convention() {
    let (dir, path) = write_scene(&format!(
        r#"{{ {CAM_2021}, "scene": {{ "shapes": [ {{ "type": "mesh", "mPath": "tri.obj", "scale": 2, "position": [0, 0, 1] }} ] }} }}"#
    ));
    std::fs::write(
        dir.path().join("tri.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n",
    )
    .unwrap();
    let s = load(&path, &LoadOptions::default()).unwrap();
    let m = &s.primitives.meshes()[0];
    assert_eq!(
        m.positions,
        vec![Vec3::Z, Vec3::new(2.0, 0.0, 1.0), Vec3::new(0.0, 2.0, 1.0)]
    );
    assert_eq!(
        m.uv,
        MeshUv::PerVertex(vec![Vec2::Y, Vec2::ONE, Vec2::ZERO])
    );
    let Shape::Triangle(t) = &s.primitives.get(0).shape else {
        panic!()
    };
    assert_eq!(t.p[1], Vec3::new(2.0, 0.0, 1.0));
}

#[test]
fn assets_resolve_from_the_scene_folder_then_by_bare_name() {
    // The official example's textures lie next to it, not in ../textures/.
    let official = repo().join("../shared/coursework/official/example.json");
    if official.is_file() {
        let s = load(&official, &LoadOptions::default()).unwrap();
        assert_eq!(s.textures.len(), 2);
    }
    let s = load(&repo().join("scenes/example.json"), &LoadOptions::default()).unwrap();
    assert_eq!(s.textures.len(), 2);
    assert_eq!((s.textures[0].width, s.textures[0].height), (852, 480));
}

#[test]
fn binary_mode_ignores_exposure_and_materials() {
    let s = load_json(
        r#"{ "rendermode": "binary", "camera": { "width": 4, "height": 4, "fov": 30, "exposure": 0.1 },
             "scene": { "shapes": [ { "type": "sphere", "center": [0, 0, -3], "radius": 1,
                                      "material": { "texture": "missing.png" } } ] } }"#,
    );
    assert_eq!((s.mode, s.exposure), (RenderMode::Binary, 1.0));
    assert!(s.textures.is_empty());
}

#[test]
fn bad_values_are_errors_with_paths() {
    let cases = [
        (
            r#"{ "camera": { "width": 4, "height": 4, "fov": 180 } }"#,
            "camera.fov",
        ),
        (
            r#"{ "camera": { "width": 0, "height": 4, "fov": 30 } }"#,
            "camera.width",
        ),
        (
            r#"{ "camera": { "width": 4, "height": 4, "fov": 30 }, "scene": { "shapes": [
            { "type": "rectangle", "corner1": [0, 0, 0], "corner2": [1, 1, 1] } ] } }"#,
            "scene.shapes[0]",
        ),
        (
            r#"{ "camera": { "width": 4, "height": 4, "fov": 30 }, "scene": { "shapes": [
            { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": { "specularexponent": -2 } } ] } }"#,
            "scene.shapes[0].material",
        ),
        (
            r#"{ "camera": { "width": 4, "height": 4, "fov": 30 }, "scene": { "shapes": [
            { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": { "kt": 1, "eta": 0 } } ] } }"#,
            "material.eta",
        ),
        (
            r#"{ "camera": { "width": 4, "height": 4, "fov": 30 }, "scene": { "lightsources": [
            { "type": "arealight", "v0": [0,0,0], "v1": [1,0,0], "v2": [1,1,0], "v3": [0,1,0], "samples": 1000 } ] } }"#,
            "samples",
        ),
        (
            r#"{ "camera": { "width": 4, "height": 4, "fov": 30, "type": "thinlens", "aperture": 0.1 } }"#,
            "focus distance",
        ),
        (r#"[1, 2, 3]"#, "(root)"),
        (
            r#"{ "camera": { "width": 4, "height": 4, "fov": 30 } } trailing"#,
            "invalid JSON",
        ),
    ];
    for (json, needle) in cases {
        let (_d, path) = write_scene(json);
        let e = load(&path, &LoadOptions::default())
            .err()
            .unwrap_or_else(|| panic!("accepted {json}"));
        let msg = e.to_string();
        assert!(
            msg.contains(needle) && msg.contains("scene.json:"),
            "{needle}: {msg}"
        );
    }
}

/// Every bundled scene loads without warnings and renders a finite, non-black thumbnail.
#[test]
fn bundled_scenes_load_cleanly() {
    let mut n = 0;
    for path in bundled_scenes() {
        let options = LoadOptions {
            width: Some(32),
            ..Default::default()
        };
        let scene = load(&path, &options).unwrap_or_else(|e| panic!("{e}"));
        assert!(
            scene.warnings.is_empty(),
            "{}: {:?}",
            path.display(),
            scene.warnings
        );
        let film = raytracer::render::render(&scene, &Default::default())
            .unwrap()
            .film;
        assert!(film.pixels.iter().all(|p| p.is_finite()));
        assert!(
            film.pixels.iter().any(|p| p.max_element() > 0.05),
            "{} is black",
            path.display()
        );
        n += 1;
    }
    assert!(n >= 16, "{n} scenes");
}

#[test]
fn cgr_lights_do_not_fall_off_and_the_background_is_the_ambient_light() {
    let cgr = |scene: &str| {
        load_json(&format!(
            r#"{{ "rendermode": "phong", "camera": {{ "width": 4, "height": 4, "fov": 30,
                 "position": [0, 0, 0], "lookAt": [0, 0, -1], "upVector": [0, 1, 0], "exposure": 0.1 }},
                 "scene": {scene} }}"#
        ))
    };
    let s = cgr(r#"{ "lightsources": [
        { "type": "pointlight", "position": [0, 1, 0], "intensity": [0.75, 0.75, 0.75] },
        { "type": "pointlight", "position": [0, 1, 0], "intensity": [1, 1, 1], "kc": 1, "kl": 0.22, "kq": 0.2 } ],
        "shapes": [ { "type": "sphere", "center": [0, 0, -3], "radius": 1, "material": { "ka": 0.5 } } ] }"#);
    assert_eq!(s.lights[0].intensity().falloff, Falloff::NONE);
    assert_eq!(
        s.lights[1].intensity().falloff,
        Falloff::Polynomial {
            kc: 1.0,
            kl: 0.22,
            kq: 0.2
        }
    );
    // No background: black, and so no ambient light.
    assert_eq!(s.ambient, Vec3::ZERO);
    assert_eq!(s.materials[0].ka, 0.5);
    assert_eq!(s.reflection, Reflection::Blended);
    assert_eq!(s.tone_map, Some(ToneMap::Cgr));
    // The exposure is kept for the `exposure` tone map only.
    assert_eq!(s.exposure, 0.1);
    assert_eq!(s.display_exposure(ToneMap::Linear), 1.0);
    assert_eq!(s.display_exposure(ToneMap::Exposure), 0.1);

    // The background colour is the ambient light (a negative channel gives none)...
    let s = cgr(r#"{ "backgroundcolor": [0.25, -0.5, 0.1] }"#);
    assert_eq!(s.ambient, Vec3::new(0.25, 0.0, 0.1));
    // ... unless the file gives its own: a scene key, or lights of type `ambient` (summed).
    let s = cgr(r#"{ "backgroundcolor": [0.25, 0.25, 0.25], "ambientlight": [0.5, 0.4, 0.3] }"#);
    assert_eq!(s.ambient, Vec3::new(0.5, 0.4, 0.3));
    let s = cgr(
        r#"{ "lightsources": [ { "type": "ambient", "intensity": 0.1 },
                                       { "type": "ambient", "intensity": [0.1, 0.2, 0.3] } ] }"#,
    );
    assert!((s.ambient - Vec3::new(0.2, 0.3, 0.4)).abs().max_element() < 1e-6);

    // 2021–23 files keep inverse-square lights, no ambient light and added mirrors, and their
    // exposure scales radiance.
    let s = load_json(&format!(
        r#"{{ {CAM_2021}, "scene": {{ "lightsources": [
            {{ "type": "pointlight", "position": [0, 0, 1], "intensity": [1, 1, 1] }} ] }} }}"#
    ));
    assert_eq!(
        s.lights[0].intensity().falloff,
        Falloff::InverseSquare { scale: 1.0 }
    );
    assert_eq!(s.ambient, Vec3::ZERO);
    assert_eq!(s.reflection, Reflection::Added);
    assert_eq!(s.display_exposure(ToneMap::Linear), s.exposure);
}

#[test]
fn material_keys_on_the_shape_a_diffuse_texture_and_a_lens_size() {
    let tex = repo().join("textures/checker.png");
    let s = load_json(&format!(
        r#"{{ "camera": {{ "type": "thinlens", "width": 4, "height": 4, "fov": 30, "position": [0, 0, 0],
               "lookat": [0, 0, -1], "up": [0, 1, 0], "focusdistance": 4, "size": 0.05 }},
             "scene": {{ "shapes": [
               {{ "type": "sphere", "center": [0, 0, -3], "radius": 1, "color": [1, 0, 0], "reflectivity": 0.5 }},
               {{ "type": "sphere", "center": [0, 0, -6], "radius": 1, "material": {{ "diffuse": "{}" }} }},
               {{ "type": "sphere", "center": [0, 0, -9], "radius": 1, "material": {{ "diffuse": [0, 0, 1] }} }} ] }} }}"#,
        tex.display()
    ));
    // A shape without a `material` carries its own keys.
    assert_eq!(s.materials[0].diffuse, Vec3::new(1.0, 0.0, 0.0));
    assert_eq!(s.materials[0].kr, 0.5);
    // `diffuse` is a texture when it is a file name, a colour otherwise.
    assert!(s.materials[1].texture.is_some());
    assert_eq!(s.materials[2].diffuse, Vec3::new(0.0, 0.0, 1.0));
    assert!(s.materials[2].texture.is_none());
    // A lens `size` is its diameter.
    assert_eq!(s.camera.lens.map(|l| l.radius), Some(0.025));
    // Without a camera `sampler` the command line's default applies.
    assert_eq!(s.pixel_method, None);
    let c = load_json(
        r#"{ "camera": { "width": 4, "height": 4, "fov": 30, "sampler": "random" }, "scene": {} }"#,
    );
    assert_eq!(c.pixel_method, Some(raytracer::sampling::Method::Random));
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
}
