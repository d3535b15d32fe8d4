//! The path tracer (`integrator::path`) against analytic answers: furnaces per bounce limit,
//! direct light equal to the Whitted diffuse term, and finite radiance in hostile scenes.

mod common;

use common::{load_json, write_scene};
use raytracer::film::Film;
use raytracer::integrator::IntegratorKind;
use raytracer::math::Vec3;
use raytracer::render::{render, RenderOptions};
use raytracer::sampling::Method;
use raytracer::scene::{load, LoadOptions};

fn mean(film: &Film) -> Vec3 {
    film.pixels.iter().copied().sum::<Vec3>() / film.pixels.len() as f32
}

fn path(spp: u32) -> RenderOptions {
    RenderOptions {
        spp,
        pixel_method: Method::Sobol,
        integrator: Some(IntegratorKind::Path),
        ..Default::default()
    }
}

/// A camera inside a closed diffuse sphere of radius 1 and albedo `a`, looking away from the
/// centre, where `light` sits.
fn enclosure(a: f32, nbounces: u32, light: &str) -> String {
    format!(
        r#"{{ "rendermode": "pathtrace", "nbounces": {nbounces},
  "camera": {{ "type": "pinhole", "width": 16, "height": 16, "position": [0, 0, 0.5],
              "lookAt": [0, 0, 1], "upVector": [0, 1, 0], "fov": 60, "exposure": 1 }},
  "scene": {{ "backgroundcolor": [0, 0, 0], "lightsources": [ {light} ],
    "shapes": [ {{ "type": "sphere", "center": [0, 0, 0], "radius": 1,
                  "material": {{ "kd": 1, "ks": 0, "diffusecolor": [{a}, {a}, {a}] }} }} ] }} }}"#
    )
}

/// A point light at the centre of the sphere lights every point of its wall alike, with
/// irradiance `π·I / R²`; a uniformly bright inside of radiance `L` gives every wall point the
/// irradiance `π·L`. So the wall's radiance is `I·Σ_{j=1}^{N+1} a^j` for `nbounces` N.
#[test]
fn a_point_lit_sphere_converges_to_the_furnace_radiance_per_bounce_limit() {
    let light = r#"{ "type": "pointlight", "position": [0, 0, 0], "intensity": [1, 1, 1] }"#;
    for (a, n) in [
        (0.5f32, 0u32),
        (0.5, 1),
        (0.5, 3),
        (0.5, 8),
        (0.8, 2),
        (0.8, 12),
    ] {
        let scene = load_json(&enclosure(a, n, light));
        let got = mean(&render(&scene, &path(64)).unwrap().film);
        let want: f32 = (1..=n + 1).map(|j| a.powi(j as i32)).sum();
        for c in [got.x, got.y, got.z] {
            assert!(
                (c / want - 1.0).abs() < 0.01,
                "a {a}, nbounces {n}: {c} vs {want}"
            );
        }
    }
}

/// A sphere light of radius r at the centre (radiance `Le = I / (4 r²)`) gives each wall point
/// the irradiance `π·Le·s²` (s = r/R) and hides the fraction `s²` of its cosine-weighted view
/// of the wall: the radiance is `Le·s²·Σ_{j=1}^{N+1} a^j (1 − s²)^(j−1)`. Light samples,
/// scattered rays that hit the light and their MIS weights all take part.
#[test]
fn a_sphere_lit_sphere_converges_to_the_furnace_radiance_per_bounce_limit() {
    let r = 0.25f32;
    let light = format!(
        r#"{{ "type": "arealight", "intensity": [2, 2, 2],
             "shape": {{ "type": "sphere", "center": [0, 0, 0], "radius": {r} }} }}"#
    );
    let le = 2.0 / (4.0 * r * r);
    let s2 = r * r;
    for (a, n) in [(0.5f32, 0u32), (0.5, 2), (0.9, 6)] {
        let scene = load_json(&enclosure(a, n, &light));
        let got = mean(&render(&scene, &path(64)).unwrap().film);
        let want: f32 = le
            * s2
            * (1..=n + 1)
                .map(|j| a.powi(j as i32) * (1.0 - s2).powi(j as i32 - 1))
                .sum::<f32>();
        assert!(
            (got.x / want - 1.0).abs() < 0.01,
            "a {a}, nbounces {n}: {} vs {want}",
            got.x
        );
    }
}

/// With no bounces, a diffuse scene lit by point lights of inverse-square fall-off is path
/// traced to the Whitted render's diffuse term (the lights' radiant intensity is `π·I`, the
/// BRDF `kd·c/π`), in the 2019 (`intensity`) and 2021–23 (`is`/`id`, power) conventions.
#[test]
fn direct_light_equals_the_whitted_diffuse_term() {
    let v2021 = r#"{ "nbounces": 0,
      "camera": { "type": "pinhole", "width": 48, "height": 32, "fov": 50,
                  "position": [0, 1, 4], "lookat": [0, -0.2, -1], "up": [0, 1, 0] },
      "scene": { "backgroundcolor": [0, 0, 0], "lightsources": [
          { "type": "pointlight", "position": [1, 3, 1], "is": [0, 0, 0], "id": [60, 50, 40] },
          { "type": "pointlight", "position": [-2, 1.5, 2], "is": [0, 0, 0], "id": [10, 20, 30] } ],
        "shapes": [
          { "type": "sphere", "center": [0, 0.7, 0], "radius": 0.7,
            "material": { "kd": 0.8, "ks": 0, "diffusecolor": [0.9, 0.4, 0.2] } },
          { "type": "plane", "v0": [-3, 0, -3], "v1": [3, 0, -3], "v2": [3, 0, 3], "v3": [-3, 0, 3],
            "material": { "kd": 0.6, "ks": 0, "diffusecolor": [0.5, 0.7, 0.9] } } ] } }"#;
    let v2019 = r#"{ "nbounces": 0,
      "camera": { "type": "pinhole", "width": 40, "height": 40, "fov": 60 },
      "scene": { "backgroundcolor": [0, 0, 0], "lightsources": [
          { "type": "pointlight", "position": [0.5, 1, 0.5], "intensity": [2, 2, 2] } ],
        "shapes": [
          { "type": "sphere", "center": [0, 0, -2], "radius": 0.6,
            "material": { "kd": 0.9, "ks": 0, "diffusecolor": [0.8, 0.8, 0.3] } },
          { "type": "triangle", "v0": [-2, -0.6, -1], "v1": [2, -0.6, -1], "v2": [0, -0.6, -4],
            "material": { "kd": 0.7, "ks": 0, "diffusecolor": [0.3, 0.8, 0.8] } } ] } }"#;
    for json in [v2021, v2019] {
        let scene = load_json(json);
        let whitted = render(&scene, &RenderOptions::default()).unwrap().film;
        let traced = render(
            &scene,
            &RenderOptions {
                integrator: Some(IntegratorKind::Path),
                ..Default::default()
            },
        )
        .unwrap()
        .film;
        let mut lit = 0;
        for (w, p) in whitted.pixels.iter().zip(&traced.pixels) {
            let d = (*w - *p).abs().max_element();
            assert!(d <= 1e-5 * w.max_element().max(1e-3), "{w} vs {p}");
            lit += (w.max_element() > 0.01) as u32;
        }
        assert!(
            lit as usize > whitted.pixels.len() / 3,
            "the test scene is lit"
        );
    }
}

/// The file's `rendermode` picks the path tracer, with no warning; `--integrator` (here the
/// option) overrides it.
#[test]
fn rendermode_pathtrace_selects_the_path_tracer() {
    let json = enclosure(
        0.5,
        3,
        r#"{ "type": "pointlight", "position": [0, 0, 0], "intensity": [1, 1, 1] }"#,
    );
    let scene = load_json(&json);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(IntegratorKind::of_scene(&scene), IntegratorKind::Path);
    let traced = mean(&render(&scene, &RenderOptions::default()).unwrap().film);
    let whitted = mean(
        &render(
            &scene,
            &RenderOptions {
                integrator: Some(IntegratorKind::Whitted),
                ..Default::default()
            },
        )
        .unwrap()
        .film,
    );
    // Whitted light has no indirect part: it stops at the direct term (plus CGR ambient).
    assert!((traced.x - 0.9375).abs() < 0.01, "{traced}");
    assert!((whitted.x - traced.x).abs() > 0.1, "{whitted} vs {traced}");
    for spelling in ["pathtracing", "path", "pathtracer", "PathTrace"] {
        let (_dir, p) = write_scene(&json.replace("\"pathtrace\"", &format!("\"{spelling}\"")));
        let s = load(&p, &LoadOptions::default()).unwrap();
        assert_eq!(
            IntegratorKind::of_scene(&s),
            IntegratorKind::Path,
            "{spelling}"
        );
        assert!(s.warnings.is_empty(), "{spelling}: {:?}", s.warnings);
    }
}

/// Lights on surfaces, a light inside glass, a point light on a wall, huge intensities: every
/// pixel of the film stays finite and non-negative.
#[test]
fn hostile_scenes_put_no_nan_or_infinity_on_the_film() {
    let json = r#"{ "rendermode": "pathtrace", "nbounces": 12,
      "camera": { "type": "pinhole", "width": 24, "height": 24, "position": [0, 1, 3],
                  "lookAt": [0, 1, 0], "upVector": [0, 1, 0], "fov": 70, "exposure": 1 },
      "scene": { "backgroundcolor": [0.2, 0.2, 0.2], "lightsources": [
          { "type": "pointlight", "position": [0, 0, 0], "intensity": [1e30, 1e30, 1e30] },
          { "type": "pointlight", "position": [0, 0.5, 0], "intensity": [1, 1, 1] },
          { "type": "arealight", "v0": [-0.5, 0, -0.5], "v1": [0.5, 0, -0.5], "v2": [0.5, 0, 0.5],
            "v3": [-0.5, 0, 0.5], "intensity": [3, 3, 3] } ],
        "shapes": [
          { "type": "plane", "v0": [-3, 0, -3], "v1": [3, 0, -3], "v2": [3, 0, 3], "v3": [-3, 0, 3],
            "material": { "kd": 1, "ks": 1, "specularexponent": 100000, "diffusecolor": [1, 1, 1] } },
          { "type": "sphere", "center": [0, 0.5, 0], "radius": 0.4,
            "material": { "isrefractive": true, "refractiveindex": 40, "kd": 0 } },
          { "type": "sphere", "center": [0.8, 0.5, 0], "radius": 0.3,
            "material": { "isreflective": true, "reflectivity": 1 } } ] } }"#;
    let scene = load_json(json);
    let film = render(&scene, &path(16)).unwrap().film;
    let bad = film
        .pixels
        .iter()
        .filter(|c| !(c.is_finite() && c.min_element() >= 0.0))
        .count();
    assert_eq!(bad, 0);
}

/// The physically based material forms of path-tracing files: `diffuse` + `albedo`, `metal`
/// (a tinted mirror, or a glossy lobe when rough), `dielectric` + `ior`, `emissive` colour ×
/// intensity, and `emittance`.
#[test]
fn material_types_map_onto_the_bsdf_and_emitters() {
    let json = r#"{ "rendermode": "path", "nbounces": 2,
      "camera": { "type": "pinhole", "width": 8, "height": 8, "position": [0, 1, 3],
                  "lookAt": [0, 1, 0], "upVector": [0, 1, 0], "fov": 40 },
      "scene": { "backgroundcolor": [0, 0, 0], "lightsources": [],
        "shapes": [
          { "type": "sphere", "center": [-1, 0, 0], "radius": 0.3,
            "material": { "type": "diffuse", "albedo": [0.2, 0.4, 0.6] } },
          { "type": "sphere", "center": [0, 0, 0], "radius": 0.3,
            "material": { "type": "metal", "albedo": [0.9, 0.6, 0.3], "roughness": 0 } },
          { "type": "sphere", "center": [1, 0, 0], "radius": 0.3,
            "material": { "type": "metal", "albedo": [0.5, 0.5, 0.5], "roughness": 0.5 } },
          { "type": "sphere", "center": [2, 0, 0], "radius": 0.3,
            "material": { "type": "dielectric", "ior": 1.33 } },
          { "type": "rectangle", "v0": [-1, 2, -1], "v1": [1, 2, -1], "v2": [1, 2, 1], "v3": [-1, 2, 1],
            "material": { "type": "emissive", "colour": [1, 0.5, 0.25], "intensity": 8 } },
          { "type": "sphere", "center": [0, 3, 0], "radius": 0.5,
            "material": { "kd": 0, "emittance": [2, 2, 2] } } ] } }"#;
    let scene = load_json(json);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let m = |i: usize| &scene.materials[scene.primitives.material(i as u32) as usize];
    assert_eq!(
        (m(0).kd, m(0).ks, m(0).diffuse),
        (1.0, 0.0, Vec3::new(0.2, 0.4, 0.6))
    );
    assert_eq!(
        (m(1).kr, m(1).kd, m(1).mirror),
        (1.0, 0.0, Vec3::new(0.9, 0.6, 0.3))
    );
    assert_eq!((m(2).kr, m(2).ks, m(2).exponent), (0.0, 1.0, 6.0));
    assert_eq!((m(3).kt, m(3).eta, m(3).kd), (1.0, 1.33, 0.0));
    assert_eq!(m(4).emission, Vec3::new(8.0, 4.0, 2.0));
    // The emitting quad (two triangles) and sphere are the scene's two lights.
    assert_eq!(scene.lights.len(), 2);
    assert_eq!(scene.lights[0].surface(), 4..6);
    assert_eq!(scene.lights[1].surface(), 6..7);
}

/// A quad of emissive material is the area light the equivalent quad light is: seen directly
/// it shows its radiance, and the floor below it is lit alike.
#[test]
fn an_emissive_shape_lights_the_scene_as_its_quad_light_would() {
    let scene = |light: &str, shape: &str| {
        format!(
            r#"{{ "rendermode": "pathtrace", "nbounces": 0,
      "camera": {{ "type": "pinhole", "width": 32, "height": 32, "position": [0, 1, 3],
                  "lookAt": [0, 0.8, 0], "upVector": [0, 1, 0], "fov": 60 }},
      "scene": {{ "backgroundcolor": [0, 0, 0], "lightsources": [ {light} ],
        "shapes": [ {shape}
          {{ "type": "quad", "v0": [-2, 0, -2], "v1": [2, 0, -2], "v2": [2, 0, 2], "v3": [-2, 0, 2],
            "material": {{ "kd": 0.8, "ks": 0, "diffusecolor": [1, 1, 1] }} }} ] }} }}"#
        )
    };
    let corners = r#""v0": [-0.5, 1.5, -0.5], "v1": [0.5, 1.5, -0.5], "v2": [0.5, 1.5, 0.5], "v3": [-0.5, 1.5, 0.5]"#;
    // Radiance 5 over an area of 1: intensity 5/π.
    let quad_light = format!(
        r#"{{ "type": "arealight", {corners}, "normal": [0, -1, 0], "intensity": [{i}, {i}, {i}] }}"#,
        i = 5.0 / std::f32::consts::PI
    );
    let glowing = format!(
        r#"{{ "type": "quad", {corners}, "material": {{ "type": "emissive", "colour": [1, 1, 1], "intensity": 5 }} }},"#
    );
    let a = render(&load_json(&scene(&quad_light, "")), &path(64))
        .unwrap()
        .film;
    let b = render(&load_json(&scene("", &glowing)), &path(64))
        .unwrap()
        .film;
    // The floor (the bottom rows) is lit alike.
    let floor = |f: &Film| -> f32 {
        f.pixels[24 * 32..].iter().map(|c| c.x).sum::<f32>() / (8 * 32) as f32
    };
    assert!(floor(&a) > 0.1);
    assert!(
        (floor(&a) / floor(&b) - 1.0).abs() < 0.02,
        "{} vs {}",
        floor(&a),
        floor(&b)
    );
    // The emitter is seen from below at its radiance: the camera looks up at it from y = 1.
    let brightest = |f: &Film| f.pixels.iter().map(|c| c.x).fold(0.0f32, f32::max);
    assert!((brightest(&a) - 5.0).abs() < 1e-3, "{}", brightest(&a));
    assert!((brightest(&b) - 5.0).abs() < 1e-3, "{}", brightest(&b));
}

/// A scene with a ball of `material` on a diffuse floor, under a point light and a quad light.
fn ball(material: &str, mode: &str) -> String {
    format!(
        r#"{{ "rendermode": "{mode}", "nbounces": 3,
      "camera": {{ "type": "pinhole", "width": 32, "height": 24, "position": [0, 1, 3],
                  "lookAt": [0, 0.4, 0], "upVector": [0, 1, 0], "fov": 50, "exposure": 1 }},
      "scene": {{ "backgroundcolor": [0.1, 0.2, 0.3], "lightsources": [
          {{ "type": "pointlight", "position": [1, 2, 1], "intensity": [1, 1, 1] }},
          {{ "type": "arealight", "v0": [-1, 2, -1], "v1": [0, 2, -1], "v2": [0, 2, 0],
             "v3": [-1, 2, 0], "intensity": [1, 0.8, 0.6] }} ],
        "shapes": [
          {{ "type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": {material} }},
          {{ "type": "plane", "v0": [-3, 0, -3], "v1": [3, 0, -3], "v2": [3, 0, 3], "v3": [-3, 0, 3],
            "material": {{ "kd": 0.8, "ks": 0, "diffusecolor": [0.9, 0.5, 0.3] }} }} ] }} }}"#
    )
}

/// A reflective material's `roughness` r makes its mirror the normalised Blinn-Phong lobe of
/// the microfacet roughness r² (exponent 2/r⁴ − 2: 30 for r = 0.5). Path traced, the rough
/// mirror and the glossy lobe of that exponent sample the same directions and carry the same
/// weights, so the two renders agree to rounding; the rough mirror is not a delta (it sees the
/// point light, which a perfect mirror never does).
#[test]
fn a_rough_mirror_is_path_traced_as_the_glossy_lobe_of_its_roughness() {
    let rough = load_json(&ball(
        r#"{ "kd": 0, "ks": 0, "isreflective": true, "reflectivity": 1, "roughness": 0.5 }"#,
        "pathtrace",
    ));
    assert!(rough.warnings.is_empty(), "{:?}", rough.warnings);
    let glossy = load_json(&ball(
        r#"{ "kd": 0, "ks": 1, "specularexponent": 30, "specularcolor": [1, 1, 1] }"#,
        "pathtrace",
    ));
    let perfect = load_json(&ball(
        r#"{ "kd": 0, "ks": 0, "isreflective": true, "reflectivity": 1, "roughness": 0 }"#,
        "pathtrace",
    ));
    let [a, b, c] = [&rough, &glossy, &perfect].map(|s| render(s, &path(16)).unwrap().film);
    let mse = |x: &Film, y: &Film| {
        x.pixels
            .iter()
            .zip(&y.pixels)
            .map(|(p, q)| (*p - *q).length_squared() as f64 / 3.0)
            .sum::<f64>()
            / x.pixels.len() as f64
    };
    assert!(mse(&a, &b) < 1e-8, "rough vs glossy: {}", mse(&a, &b));
    assert!(mse(&a, &c) > 1e-4, "rough vs perfect: {}", mse(&a, &c));
}

/// Whitted mode blurs a rough mirror by distribution ray tracing: the reflected edge of a lit
/// floor against the background spreads over more pixels as the roughness grows, and a roughness
/// above 1 on a mirror is taken as 1 with a warning. A roughness on a material with no mirror
/// part (as some CGR files give) changes nothing and is no warning.
#[test]
fn whitted_blurs_a_rough_mirror_and_ignores_roughness_without_one() {
    let mirror = |r: f32| {
        load_json(&ball(
            &format!(
                r#"{{ "kd": 0, "ks": 0, "isreflective": true, "reflectivity": 1, "roughness": {r} }}"#
            ),
            "phong",
        ))
    };
    let options = RenderOptions {
        spp: 64,
        pixel_method: Method::Sobol,
        ..Default::default()
    };
    // The image's total variation (the summed differences of neighbouring pixels): a blurred
    // reflection has less of it; nothing else in the scene depends on the roughness.
    let variation = |r: f32| {
        let film = render(&mirror(r), &options).unwrap().film;
        let w = film.width as usize;
        let px = &film.pixels;
        (0..px.len())
            .map(|i| {
                let right = if (i + 1) % w != 0 {
                    (px[i + 1] - px[i]).abs().element_sum()
                } else {
                    0.0
                };
                let down = px
                    .get(i + w)
                    .map_or(0.0, |q| (*q - px[i]).abs().element_sum());
                (right + down) as f64
            })
            .sum::<f64>()
    };
    let (sharp, soft, softer) = (variation(0.0), variation(0.3), variation(0.6));
    assert!(sharp > soft && soft > softer, "{sharp} {soft} {softer}");
    let clamped = mirror(3.0);
    assert_eq!(clamped.warnings.len(), 1, "{:?}", clamped.warnings);
    assert!(
        clamped.warnings[0].message.contains("roughness"),
        "{:?}",
        clamped.warnings
    );
    let plain =
        r#"{ "kd": 0.9, "ks": 0.1, "specularexponent": 20, "diffusecolor": [0.3, 0.9, 0.2] }"#;
    let with = plain.replace("\"kd\"", "\"roughness\": 20, \"kd\"");
    let (a, b) = (
        load_json(&ball(plain, "phong")),
        load_json(&ball(&with, "phong")),
    );
    assert!(b.warnings.is_empty(), "{:?}", b.warnings);
    assert_eq!(
        render(&a, &options).unwrap().film.pixels,
        render(&b, &options).unwrap().film.pixels
    );
}
