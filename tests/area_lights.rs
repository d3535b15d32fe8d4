//! Sphere lights and shapes of the scene named as lights (`shapeid`): their power, their shadows,
//! and their determinism, checked through whole renders.

mod common;

use common::*;
use raytracer::film::Film;
use raytracer::light::Light;
use raytracer::math::Vec3;
use raytracer::render::{render, RenderOptions};

/// A white floor (z = 0, kd = 1) seen from 2 above through a 1° view: the 3 × 3 pixels all see
/// floor points within 0.02 of the origin. `lights` and `extra` (more shapes) are spliced in.
fn floor_scene(lights: &str, extra: &str) -> String {
    format!(
        r#"{{ "nbounces": 0,
             "camera": {{ "type": "pinhole", "width": 3, "height": 3, "fov": 1,
                          "position": [0, 0, 2], "lookat": [0, 0, -1], "up": [0, 1, 0] }},
             "scene": {{ "backgroundcolor": [0, 0, 0],
               "lightsources": [ {lights} ],
               "shapes": [
                 {{ "type": "plane", "v0": [-50, -50, 0], "v1": [50, -50, 0], "v2": [50, 50, 0], "v3": [-50, 50, 0],
                   "material": {{ "kd": 1.0, "ks": 0.0, "specularexponent": 1, "diffusecolor": [1, 1, 1] }} }}
                 {extra} ] }} }}"#
    )
}

fn sphere_light(center: [f32; 3], radius: f32, samples: u32) -> String {
    format!(
        r#"{{ "type": "arealight", "intensity": [100, 100, 100], "samplesize": {samples},
             "shape": {{ "type": "sphere", "center": {center:?}, "radius": {radius} }} }}"#
    )
}

fn point_light(position: [f32; 3]) -> String {
    format!(r#"{{ "type": "pointlight", "intensity": [100, 100, 100], "position": {position:?} }}"#)
}

/// The largest relative difference between the red channels of two images.
fn worst_ratio(a: &Film, b: &Film) -> f32 {
    a.pixels
        .iter()
        .zip(&b.pixels)
        .map(|(x, y)| {
            assert!(y.x > 0.0);
            (x.x / y.x - 1.0).abs()
        })
        .fold(0.0, f32::max)
}

/// Far from a small sphere light, the floor is lit as by a point light of the same intensity at
/// its centre: within 0.1% (a sphere of radius 0.05 at a distance of 20).
#[test]
fn a_far_sphere_light_matches_the_point_light_at_its_centre() {
    let options = RenderOptions::default();
    let sphere = render_json(
        &floor_scene(&sphere_light([0.0, 0.0, 20.0], 0.05, 8), ""),
        &options,
    );
    let point = render_json(&floor_scene(&point_light([0.0, 0.0, 20.0]), ""), &options);
    assert!((point.get(1, 1).x - 0.25).abs() < 1e-3); // 100 / 20²
    let worst = worst_ratio(&sphere, &point);
    assert!(worst < 1e-3, "{worst}");
}

/// A sphere wholly above the floor's horizon gives a point light's irradiance even close by (a
/// property of uniformly bright balls): radius 1 at a distance of 10, within 0.5%.
#[test]
fn a_near_sphere_light_above_the_horizon_still_matches() {
    let options = RenderOptions::default();
    let sphere = render_json(
        &floor_scene(&sphere_light([0.0, 0.0, 10.0], 1.0, 16), ""),
        &options,
    );
    let point = render_json(&floor_scene(&point_light([0.0, 0.0, 10.0]), ""), &options);
    let worst = worst_ratio(&sphere, &point);
    assert!(worst < 5e-3, "{worst}");
}

/// An opaque half-plane whose edge passes under the sphere light's centre, straight above the
/// floor point, hides half of the sphere: the point gets half the light (within 3%, 32² shadow
/// rays).
#[test]
fn an_occluder_over_half_the_sphere_leaves_half_the_light() {
    let light = sphere_light([0.0, 0.0, 10.0], 1.0, 32);
    let blocker = r#", { "type": "plane", "v0": [-20, -20, 5], "v1": [0, -20, 5], "v2": [0, 20, 5], "v3": [-20, 20, 5],
                          "material": { "kd": 1.0, "diffusecolor": [1, 1, 1] } }"#;
    let options = RenderOptions::default();
    let open = render_json(&floor_scene(&light, ""), &options);
    let half = render_json(&floor_scene(&light, blocker), &options);
    let ratio = half.get(1, 1).x / open.get(1, 1).x;
    assert!((ratio - 0.5).abs() < 0.03, "{ratio}");
}

/// A sphere of the scene named by `shapeid` is the same light as that sphere given as the light's
/// own `shape`: its own surface never shadows it, so the floor is lit to the bit alike.
#[test]
fn a_named_sphere_lights_like_its_shape_twin() {
    let named = floor_scene(
        r#"{ "type": "arealight", "intensity": [100, 100, 100], "samplesize": 8, "shapeid": "sun" }"#,
        r#", { "id": "sun", "type": "sphere", "center": [0.3, 0.2, 10], "radius": 1.5,
               "material": { "kd": 1.0, "diffusecolor": [1, 1, 1] } }"#,
    );
    let scene = load_json(&named);
    let Light::Sphere {
        center,
        radius,
        surface,
        ..
    } = &scene.lights[0]
    else {
        panic!("{:?}", scene.lights[0]);
    };
    assert_eq!((*center, *radius), (Vec3::new(0.3, 0.2, 10.0), 1.5));
    assert_eq!(*surface, 2..3); // after the floor's two triangles
    let twin = floor_scene(&sphere_light([0.3, 0.2, 10.0], 1.5, 8), "");
    let options = RenderOptions::default();
    let a = render(&scene, &options).unwrap().film;
    let b = render_json(&twin, &options);
    assert_eq!(a.pixels, b.pixels);
}

/// A ceiling quad named by `shapeid` (as in the coursework files that use it) is sampled
/// uniformly by area: its samples lie on it, and it lights a floor as the same quad given as a
/// `v0`..`v3` area light does (on average over the image, within 1%). It stays a shape: the
/// scene still holds its two triangles.
#[test]
fn a_named_quad_lights_like_the_same_quad_light() {
    let corners = r#""v0": [1.2, 4.5, 2.5], "v1": [0.8, 4.5, 2.5], "v2": [0.8, 1.5, 2.5], "v3": [1.2, 1.5, 2.5]"#;
    let scene = |light: &str, extra: &str| {
        format!(
            r#"{{ "nbounces": 0,
                 "camera": {{ "type": "pinhole", "width": 24, "height": 24, "fov": 60,
                              "position": [1, 3, 2], "lookat": [0, 0, -1], "up": [0, 1, 0] }},
                 "scene": {{ "backgroundcolor": [0, 0, 0],
                   "lightsources": [ {light} ],
                   "shapes": [
                     {{ "type": "plane", "v0": [-9, -9, 0], "v1": [9, -9, 0], "v2": [9, 9, 0], "v3": [-9, 9, 0],
                       "material": {{ "kd": 1.0, "diffusecolor": [1, 1, 1] }} }}
                     {extra} ] }} }}"#
        )
    };
    let named = scene(
        r#"{ "type": "arealight", "shapeid": "myarealightshape", "position": [0, 1, 1.5],
             "samples": 8, "is": [100, 100, 100], "id": [100, 100, 100] }"#,
        &format!(
            r#", {{ "id": "myarealightshape", "type": "plane", {corners},
                   "material": {{ "kd": 0.7, "diffusecolor": [1, 1, 1] }} }}"#
        ),
    );
    let quad = scene(
        &format!(
            r#"{{ "type": "arealight", {corners}, "samples": 8, "is": [100, 100, 100], "id": [100, 100, 100] }}"#
        ),
        "",
    );
    let named_scene = load_json(&named);
    assert_eq!(named_scene.primitives.len(), 4);
    let Light::Triangles {
        triangles, surface, ..
    } = &named_scene.lights[0]
    else {
        panic!("{:?}", named_scene.lights[0]);
    };
    assert_eq!(*surface, 2..4);
    assert_eq!(triangles.len(), 2);
    for i in 0..64 {
        let u =
            raytracer::math::Vec2::new((i % 8) as f32 / 8.0 + 0.06, (i / 8) as f32 / 8.0 + 0.06);
        let p = named_scene.lights[0].sample(Vec3::ZERO, u).position;
        assert!(
            p.z == 2.5 && (0.8..=1.2).contains(&p.x) && (1.5..=4.5).contains(&p.y),
            "{p}"
        );
    }
    let options = RenderOptions::default();
    let a = render(&named_scene, &options).unwrap().film;
    let b = render_json(&quad, &options);
    // The camera is below the ceiling quad and sees only the floor.
    let mean = |f: &Film| f.pixels.iter().map(|p| p.x as f64).sum::<f64>() / f.pixels.len() as f64;
    let (ma, mb) = (mean(&a), mean(&b));
    assert!(mb > 0.01, "{mb}");
    assert!((ma / mb - 1.0).abs() < 0.01, "{ma} vs {mb}");
}

/// Sphere and shape lights draw every number from the sample key: one thread and two threads
/// give the same pixels.
#[test]
fn sphere_and_shape_lights_render_alike_on_any_thread_count() {
    let json = floor_scene(
        &format!(
            r#"{}, {{ "type": "arealight", "shapeid": "lamp", "samples": 16, "method": "sobol", "intensity": [30, 30, 30] }}"#,
            sphere_light([2.0, 1.0, 6.0], 1.0, 5).replace("\"samplesize\"", "\"method\": \"random\", \"samplesize\"")
        ),
        r#", { "id": "lamp", "type": "triangle", "v0": [-3, -3, 4], "v1": [3, -3, 4], "v2": [0, 3, 4] },
             { "type": "sphere", "center": [0.5, 0.5, 1], "radius": 0.4 }"#,
    )
    .replace("\"width\": 3, \"height\": 3, \"fov\": 1", "\"width\": 32, \"height\": 32, \"fov\": 120");
    let scene = load_json(&json);
    assert!(matches!(scene.lights[0], Light::Sphere { .. }));
    assert!(matches!(scene.lights[1], Light::Triangles { .. }));
    let options = RenderOptions {
        spp: 2,
        ..RenderOptions::default()
    };
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render(&scene, &options).unwrap().film)
    };
    let one = on(1);
    let two = on(2);
    assert!(one.pixels == two.pixels);
    assert!(one.pixels.iter().any(|p| p.x > 0.0));
}

/// The other forms: a light's own quad `shape` is a quad light on its corners; a `shapeid` naming
/// a skipped shape skips the light (warning); of two shapes with the id the first is used
/// (warning); a light with only a position is a point light there (warning that says so).
#[test]
fn shape_quads_skipped_and_duplicate_ids_and_bare_positions() {
    let scene = load_json(&floor_scene(
        r#"{ "type": "arealight", "intensity": 100, "position": [0, -10, 0],
             "shape": { "type": "plane", "points": [[-3, -8, -3], [-3, -8, 3], [3, -8, 3], [3, -8, -3]] } },
           { "type": "arealight", "shapeid": "gone", "intensity": 1 },
           { "type": "arealight", "shapeid": "twice", "intensity": 1 },
           { "type": "arealight", "position": [0, 1, 0.5], "intensity": 1 }"#,
        r#", { "id": "gone", "type": "sphereee", "center": [0, 0, 5], "radius": 1 },
             { "id": "twice", "type": "sphere", "center": [0, 0, 5], "radius": 1 },
             { "id": "twice", "type": "sphere", "center": [0, 0, 9], "radius": 2 }"#,
    ));
    assert_eq!(scene.lights.len(), 3, "{:?}", scene.lights);
    let Light::Quad {
        origin,
        edge_u,
        edge_v,
        ..
    } = &scene.lights[0]
    else {
        panic!("{:?}", scene.lights[0]);
    };
    assert_eq!(*origin, Vec3::new(-3.0, -8.0, -3.0));
    assert_eq!(edge_u.cross(*edge_v).length(), 36.0);
    let Light::Sphere { center, .. } = &scene.lights[1] else {
        panic!("{:?}", scene.lights[1]);
    };
    assert_eq!(*center, Vec3::new(0.0, 0.0, 5.0));
    let Light::Point { position, .. } = &scene.lights[2] else {
        panic!("{:?}", scene.lights[2]);
    };
    assert_eq!(*position, Vec3::new(0.0, 1.0, 0.5));
    let messages: Vec<String> = scene.warnings.iter().map(|w| w.to_string()).collect();
    let has = |path: &str, text: &str| {
        messages
            .iter()
            .any(|m| m.contains(path) && m.contains(text))
    };
    assert!(
        has(
            "scene.lightsources[1].shapeid",
            "'gone' (scene.shapes[1]) was skipped"
        ),
        "{messages:?}"
    );
    assert!(
        has(
            "scene.lightsources[2].shapeid",
            "several shapes have the id 'twice'"
        ),
        "{messages:?}"
    );
    assert!(
        has(
            "scene.lightsources[3]",
            "given only by a position (no corners, edges, 'shape' or 'shapeid'); treated as a point light at [0, 1, 0.5]"
        ),
        "{messages:?}"
    );
}
