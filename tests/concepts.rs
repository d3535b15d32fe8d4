//! The concepts files give under names of their own, each rendered and checked against its
//! geometry: a sphere light's soft shadow, a checkerboard's squares, depth of field's blur
//! growing away from the focal plane, an emissive quad lighting a floor as the same quad light.

mod common;

use common::*;
use raytracer::film::Film;
use raytracer::light::Light;
use raytracer::math::Vec3;
use raytracer::render::RenderOptions;

fn options(spp: u32) -> RenderOptions {
    RenderOptions {
        spp,
        ..RenderOptions::default()
    }
}

fn at(f: &Film, x: u32, y: u32) -> Vec3 {
    f.pixels[(y * f.width + x) as usize]
}

/// A floor seen from above, a small ball over it (if `ball`), and `light` above the ball.
fn shadow_scene(light: &str, ball: bool) -> String {
    let ball = if ball {
        r#", {"type": "sphere", "center": [0, 1, 0], "radius": 0.4,
              "material": {"kd": 0, "ks": 0, "diffusecolor": [0, 0, 0]}}"#
    } else {
        ""
    };
    format!(
        r#"{{"camera": {{"width": 64, "height": 64, "fov": 60, "position": [0, 4, 0.001],
             "lookat": [0, -1, 0], "up": [0, 0, -1]}},
           "scene": {{"backgroundcolor": [0, 0, 0], "lightsources": [{light}],
             "shapes": [
               {{"type": "quad", "v0": [-5, 0, -5], "v1": [5, 0, -5], "v2": [5, 0, 5],
                 "v3": [-5, 0, 5], "material": {{"kd": 1, "ks": 0, "diffusecolor": [1, 1, 1]}}}}
               {ball}]}}}}"#
    )
}

/// Floor pixels (outside the ball's own disc in the image) that the ball leaves between a
/// tenth and nine tenths of their light: the shadow's penumbra.
fn penumbra_pixels(light: &str) -> usize {
    let shadowed = render_json(&shadow_scene(light, true), &options(4));
    let open = render_json(&shadow_scene(light, false), &options(4));
    let mut n = 0;
    for y in 0..open.height {
        for x in 0..open.width {
            let (dx, dy) = (x as f32 - 31.5, y as f32 - 31.5);
            if dx.hypot(dy) < 9.0 {
                continue; // the ball itself
            }
            let v = at(&shadowed, x, y).x / at(&open, x, y).x;
            if v > 0.1 && v < 0.9 {
                n += 1;
            }
        }
    }
    n
}

#[test]
fn a_sphere_light_by_any_name_casts_a_soft_shadow() {
    let spellings = [
        r#"{"type": "spherelight", "position": [0, 3, 0], "radius": 0.6, "intensity": [9, 9, 9], "samples": 64, "method": "random"}"#,
        r#"{"type": "arealight", "position": [0, 3, 0], "radius": 0.6, "intensity": [9, 9, 9], "samples": 64, "method": "random"}"#,
    ];
    let hard =
        penumbra_pixels(r#"{"type": "pointlight", "position": [0, 3, 0], "intensity": [9, 9, 9]}"#);
    for light in spellings {
        let scene = load_json(&shadow_scene(light, true));
        assert!(
            matches!(scene.lights[0], Light::Sphere { radius, .. } if radius == 0.6),
            "{light}"
        );
        assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
        let soft = penumbra_pixels(light);
        // The penumbra's width on the floor is about (0.6 + 0.4)·1/2 = 0.5 units across, a ring
        // of several pixels; a point light's shadow edge is one pixel wide.
        assert!(
            soft > 4 * hard.max(10),
            "penumbra {soft} pixels, point light {hard}"
        );
    }
}

#[test]
fn a_checkerboard_paints_its_squares_in_uv() {
    let scene = |texture: &str| {
        format!(
            r#"{{"camera": {{"width": 40, "height": 40, "fov": 90, "position": [0, 0, 1],
                 "lookat": [0, 0, -1], "up": [0, 1, 0]}},
               "scene": {{"ambientlight": [1, 1, 1], "shapes": [
                 {{"type": "quad", "v0": [-1, 1, 0], "v1": [1, 1, 0], "v2": [1, -1, 0],
                   "v3": [-1, -1, 0], "material": {{"ka": 1, "kd": 0, "ks": 0,
                   "diffusecolor": [0.5, 0.5, 0.5], "texture": {texture}}}}}]}}}}"#
        )
    };
    let red = Vec3::new(1.0, 0.0, 0.0);
    let blue = Vec3::new(0.0, 0.0, 1.0);
    // Four squares across the quad's uv: rows and columns of 10 pixels alternate.
    let f = render_json(
        &scene(r#"{"type": "checkerboard", "color1": [1, 0, 0], "color2": [0, 0, 1], "scale": 4}"#),
        &options(1),
    );
    for (i, j) in [(0, 0), (1, 0), (0, 1), (3, 3), (2, 1)] {
        let expected = if (i + j) % 2 == 0 { red } else { blue };
        let c = at(&f, 10 * i + 5, 10 * j + 5);
        assert!(
            (c - expected).abs().max_element() < 1e-5,
            "square {i},{j}: {c}"
        );
    }
    // Named alone, one renderer's checkerboard: ten black and white squares across.
    let f = render_json(&scene(r#""checkerboard""#), &options(1));
    assert!(at(&f, 1, 1).max_element() < 1e-5 && at(&f, 5, 1).min_element() > 0.999);
}

/// Width in pixels of the blurred edge of a half-plane at depth `z` in front of a camera with
/// a lens focused at 4 (mean over the rows of the pixels between 5% and 95% white).
fn edge_width(z: f32) -> f32 {
    let json = format!(
        r#"{{"camera": {{"type": "finiteAperture", "width": 64, "height": 16, "fov": 3,
             "position": [0, 0, 0], "lookAt": [0, 0, -1], "upVector": [0, 1, 0],
             "apertureSize": 0.08, "focusDistance": 4, "exposure": 1}},
           "rendermode": "phong",
           "scene": {{"backgroundcolor": [0, 0, 0], "ambientlight": [1, 1, 1], "shapes": [
             {{"type": "quad", "v0": [0, -500, {z}], "v1": [500, -500, {z}],
               "v2": [500, 500, {z}], "v3": [0, 500, {z}],
               "material": {{"ka": 1, "kd": 0, "ks": 0, "diffusecolor": [1, 1, 1]}}}}]}}}}"#
    );
    let scene = load_json(&json);
    let lens = scene.camera.lens.expect("a lens");
    assert_eq!((lens.radius, lens.focus_distance), (0.08, 4.0));
    let f = raytracer::render::render(&scene, &options(256))
        .unwrap()
        .film;
    let partial = f.pixels.iter().filter(|p| p.x > 0.05 && p.x < 0.95).count();
    partial as f32 / f.height as f32
}

#[test]
fn depth_of_field_blur_grows_away_from_the_focal_plane() {
    let (focused, nearer, farther) = (edge_width(-4.0), edge_width(-2.0), edge_width(-12.0));
    // The blur, 2·0.08·|z − 4|/z across on the plane in focus, is 0.16 at z = 2 and 0.11 at 12;
    // that plane is 2·4·tan 6° = 0.84 across the image's 64 pixels: 12 and 8 pixels wide.
    assert!(focused <= 1.5, "in focus: {focused} pixels");
    assert!(
        nearer > 6.0 && farther > 4.0,
        "near: {nearer}, far {farther}"
    );
    assert!(nearer > farther, "near {nearer}, far {farther}");
}

#[test]
fn an_emissive_quad_lights_a_floor_as_the_same_quad_light() {
    // A 1 × 1 ceiling quad at height 2 over a floor, seen from the side below it.
    let corners = r#""v0": [-0.5, 2, -3.5], "v1": [0.5, 2, -3.5], "v2": [0.5, 2, -2.5], "v3": [-0.5, 2, -2.5]"#;
    let floor = r#"{"type": "quad", "v0": [-4, 0, -8], "v1": [4, 0, -8], "v2": [4, 0, 0],
        "v3": [-4, 0, 0], "material": {"kd": 1, "ks": 0, "diffusecolor": [1, 1, 1]}}"#;
    let camera = r#""camera": {"width": 48, "height": 32, "fov": 50, "position": [0, 1, 1],
        "lookat": [0, -0.45, -1], "up": [0, 1, 0]}"#;
    // Radiance L from area A: intensity L·A/π.
    let radiance = 3.0_f32;
    let intensity = radiance / std::f32::consts::PI;
    let shape = format!(
        r#"{{{camera}, "scene": {{"shapes": [{floor}, {{"type": "quad", {corners},
            "material": {{"emissioncolor": [{radiance}, {radiance}, {radiance}]}}}}]}}}}"#
    );
    let light = format!(
        r#"{{{camera}, "scene": {{"lightsources": [{{"type": "arealight", {corners},
            "intensity": [{intensity}, {intensity}, {intensity}]}}], "shapes": [{floor}]}}}}"#
    );
    let (a, b) = (load_json(&shape), load_json(&light));
    assert!(a.warnings.is_empty() && b.warnings.is_empty());
    let (fa, fb) = (
        raytracer::render::render(&a, &options(16)).unwrap().film,
        raytracer::render::render(&b, &options(16)).unwrap().film,
    );
    let mean = |f: &Film| f.pixels.iter().map(|p| p.x as f64).sum::<f64>() / f.pixels.len() as f64;
    let (ma, mb) = (mean(&fa), mean(&fb));
    assert!(mb > 0.01, "the floor is lit: {mb}");
    assert!(
        (ma - mb).abs() < 0.02 * mb,
        "emissive quad {ma}, quad light {mb}"
    );
}
