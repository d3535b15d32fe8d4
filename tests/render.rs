//! Whole renders of small scenes, checked against what geometry and optics say each pixel must be.

mod common;

use common::*;
use raytracer::math::Vec3;
use raytracer::ray::Ray;
use raytracer::render::{render, RenderOptions};

/// Binary mode, 2019-style default camera (origin, looking down −z), fov 90°, 64×64; a sphere of
/// radius 1 at distance 5 has a silhouette of angular radius asin(1/5), i.e. tan = 0.2041 → 6.53
/// pixels from the centre.
#[test]
fn sphere_silhouette_is_where_the_camera_maths_puts_it() {
    let film = render_default(
        r#"{ "nbounces": 0, "rendermode": "binary",
             "camera": { "type": "pinhole", "width": 64, "height": 64, "fov": 90 },
             "scene": { "backgroundcolor": [0, 0, 0], "lightsources": [],
                        "shapes": [ { "type": "sphere", "center": [0, 0, -5], "radius": 1 } ] } }"#,
    );
    let radius_px = (1.0f32 / 24.0f32.sqrt()) * 32.0; // tan(asin(1/5)) · (64/2) / tan(45°)
    let mut checked = 0;
    for y in 0..64 {
        for x in 0..64 {
            let d = ((x as f32 + 0.5 - 32.0).powi(2) + (y as f32 + 0.5 - 32.0).powi(2)).sqrt();
            let c = film.get(x, y);
            if d < radius_px - 0.3 {
                assert_eq!(c, Vec3::new(1.0, 0.0, 0.0), "pixel ({x},{y}) inside");
                checked += 1;
            } else if d > radius_px + 0.3 {
                assert_eq!(c, Vec3::ZERO, "pixel ({x},{y}) outside");
                checked += 1;
            }
        }
    }
    assert!(checked > 4000);
}

/// A floor lit by one point light with a sphere between them: every pixel is in shadow exactly
/// when the segment from its floor point to the light passes through the sphere.
#[test]
fn shadow_falls_where_the_light_says() {
    let scene = load_json(
        r#"{ "nbounces": 0,
             "camera": { "type": "pinhole", "width": 80, "height": 60, "fov": 60,
                         "position": [0, -6, 8], "lookat": [0, 0.6, -0.8], "up": [0, 0, 1] },
             "scene": { "backgroundcolor": [0, 0, 0],
               "lightsources": [ { "type": "pointlight", "position": [-3, 0, 4], "is": [50, 50, 50], "id": [50, 50, 50] } ],
               "shapes": [
                 { "type": "sphere", "center": [-1.5, 0, 2], "radius": 0.6,
                   "material": { "kd": 0.0, "ks": 0.0, "specularexponent": 1, "diffusecolor": [1, 1, 1] } },
                 { "type": "plane", "v0": [-6, 6, 0], "v1": [6, 6, 0], "v2": [6, -6, 0], "v3": [-6, -6, 0],
                   "material": { "kd": 1.0, "ks": 0.0, "specularexponent": 1, "diffusecolor": [1, 1, 1] } } ] } }"#,
    );
    let film = render(&scene, &RenderOptions::default()).unwrap().film;
    let light = Vec3::new(-3.0, 0.0, 4.0);
    let (center, r) = (Vec3::new(-1.5, 0.0, 2.0), 0.6f32);
    let (mut shadowed, mut lit) = (0, 0);
    for y in 0..60 {
        for x in 0..80 {
            let ray: Ray = scene.camera.generate_ray(
                x,
                y,
                raytracer::math::Vec2::splat(0.5),
                Default::default(),
            );
            // Pixels that see the sphere itself, or miss the floor, are not about the shadow.
            let to_c = center - ray.origin;
            let closest = to_c - to_c.dot(ray.dir) * ray.dir;
            if closest.length() < r + 0.05 || ray.dir.z >= 0.0 {
                continue;
            }
            let t = -ray.origin.z / ray.dir.z;
            let p = ray.at(t);
            if p.x.abs() > 5.9 || p.y.abs() > 5.9 {
                continue;
            }
            // Distance from the sphere's centre to the segment p → light.
            let seg = light - p;
            let s = ((center - p).dot(seg) / seg.length_squared()).clamp(0.0, 1.0);
            let dist = (p + s * seg - center).length();
            if (dist - r).abs() < 0.02 {
                continue; // within rounding of the penumbra-free edge
            }
            let c = film.get(x, y);
            if dist < r {
                assert_eq!(c, Vec3::ZERO, "pixel ({x},{y}) at {p} should be in shadow");
                shadowed += 1;
            } else {
                assert!(c.x > 0.01, "pixel ({x},{y}) at {p} should be lit, got {c}");
                lit += 1;
            }
        }
    }
    assert!(
        shadowed > 30 && lit > 1000,
        "shadowed {shadowed}, lit {lit}"
    );
}

/// A 2×2 texture on a quad facing the camera: texel (0,0) at corner v0 (top left in the image),
/// the first row along v0→v1.
#[test]
fn texture_texels_land_on_the_expected_pixels() {
    let dir = tempfile::tempdir().unwrap();
    // P3: red, green / blue, white.
    std::fs::write(
        dir.path().join("tex.ppm"),
        "P3\n2 2\n255\n255 0 0  0 255 0\n0 0 255  255 255 255\n",
    )
    .unwrap();
    let scene_path = dir.path().join("scene.json");
    std::fs::write(
        &scene_path,
        r#"{ "nbounces": 0,
             "camera": { "type": "pinhole", "width": 40, "height": 40, "fov": 40,
                         "position": [0, 0, 3], "lookat": [0, 0, -1], "up": [0, 1, 0] },
             "scene": { "backgroundcolor": [0, 0, 0],
               "lightsources": [ { "type": "pointlight", "position": [0, 0, 3], "is": [0, 0, 0], "id": [100, 100, 100] } ],
               "shapes": [ { "type": "plane", "v0": [-1, 1, 0], "v1": [1, 1, 0], "v2": [1, -1, 0], "v3": [-1, -1, 0],
                   "material": { "kd": 1.0, "ks": 0.0, "specularexponent": 1, "diffusecolor": [0, 0, 0], "tPath": "tex.ppm" } } ] } }"#,
    )
    .unwrap();
    let scene = raytracer::scene::load(&scene_path, &Default::default()).unwrap();
    let film = render(&scene, &RenderOptions::default()).unwrap().film;
    // The quad spans ±1 at distance 3: tan = 1/3 against tan(20°) = 0.364, i.e. ±18.3 px around
    // 20, so the texel centres (u, v = 1/4, 3/4) fall near pixels 10.9 and 29.2.
    let expect = [
        ((10, 10), Vec3::new(1.0, 0.0, 0.0)),
        ((29, 10), Vec3::new(0.0, 1.0, 0.0)),
        ((10, 29), Vec3::new(0.0, 0.0, 1.0)),
        ((29, 29), Vec3::new(1.0, 1.0, 1.0)),
    ];
    for ((x, y), texel) in expect {
        let c = film.get(x, y);
        let n = c / c.max_element();
        assert!(
            (n - texel).abs().max_element() < 0.1,
            "pixel ({x},{y}) is {c}, expected the colour of {texel}"
        );
    }
}

const GLASS_SCENE: &str = r#"{ "nbounces": 4,
  "camera": { "type": "pinhole", "width": 48, "height": 36, "fov": 50,
              "position": [0, -4, 1], "lookat": [0, 1, 0], "up": [0, 0, 1] },
  "scene": { "backgroundcolor": [0.1, 0.2, 0.3],
    "lightsources": [ { "type": "pointlight", "position": [1, -2, 3], "is": [80, 80, 80], "id": [80, 80, 80] } ],
    "shapes": [
      GLASS
      { "type": "plane", "v0": [-3, 3, -1], "v1": [3, 3, -1], "v2": [3, 3, 3], "v3": [-3, 3, 3],
        "material": { "kd": 0.9, "ks": 0.3, "specularexponent": 8, "diffusecolor": [0.9, 0.5, 0.2] } },
      { "type": "plane", "v0": [-3, -3, 0], "v1": [3, -3, 0], "v2": [3, 3, 0], "v3": [-3, 3, 0],
        "material": { "kd": 0.8, "ks": 0.0, "specularexponent": 1, "diffusecolor": [0.3, 0.8, 0.3] } } ] } }"#;

/// Glass with η = 1, no reflection and no local shading bends nothing, reflects nothing and casts
/// no shadow: the image is the same as without it.
#[test]
fn glass_with_eta_one_is_invisible() {
    let glass = r#"{ "type": "sphere", "center": [0, 0.5, 0.8], "radius": 0.7,
        "material": { "kd": 0, "ks": 0, "specularexponent": 1, "diffusecolor": [1, 1, 1], "kt": 1.0, "eta": 1.0 } },"#;
    let with = render_default(&GLASS_SCENE.replace("GLASS", glass));
    let without = render_default(&GLASS_SCENE.replace("GLASS", ""));
    let diff = max_abs_diff(&with, &without);
    assert!(diff < 1e-4, "largest difference {diff}");
    // With a real index of refraction the sphere shows.
    let real = render_default(
        &GLASS_SCENE.replace("GLASS", &glass.replace("\"eta\": 1.0", "\"eta\": 1.5")),
    );
    assert!(max_abs_diff(&real, &without) > 0.1);
}

const AREA_SCENE: &str = r#"{ "nbounces": 2,
  "camera": { "type": "thinlens", "width": 40, "height": 30, "fov": 45, "aperture": 0.2, "focusdistance": 5,
              "position": [0, -5, 2], "lookat": [0, 1, -0.3], "up": [0, 0, 1] },
  "scene": { "backgroundcolor": [0.05, 0.05, 0.05],
    "lightsources": [ { "type": "arealight", "v0": [-1, -1, 3], "v1": [1, -1, 3], "v2": [1, 1, 3], "v3": [-1, 1, 3],
                        "samples": 3, "method": "jittered", "is": [60, 60, 60], "id": [60, 60, 60] } ],
    "shapes": [ { "type": "sphere", "center": [0, 0, 0.7], "radius": 0.6,
                  "material": { "kd": 0.7, "ks": 0.4, "specularexponent": 20, "diffusecolor": [0.8, 0.2, 0.2], "kr": 0.3 } },
                { "type": "plane", "v0": [-4, -4, 0], "v1": [4, -4, 0], "v2": [4, 4, 0], "v3": [-4, 4, 0],
                  "material": { "kd": 0.8, "ks": 0.1, "specularexponent": 4, "diffusecolor": [0.9, 0.9, 0.9] } } ] } }"#;

/// The image depends only on (pixel, sample, dimension, seed): one thread, two threads and a second
/// run give identical pixels; another seed gives other pixels.
#[test]
fn renders_are_identical_on_any_thread_count() {
    let scene = load_json(AREA_SCENE);
    let options = RenderOptions {
        spp: 4,
        ..RenderOptions::default()
    };
    let on = |threads: usize, options: &RenderOptions| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render(&scene, options).unwrap().film)
    };
    let one = on(1, &options);
    let two = on(2, &options);
    let again = on(2, &options);
    assert!(one.pixels == two.pixels && two.pixels == again.pixels);
    let other_seed = on(
        2,
        &RenderOptions {
            seed: 7,
            ..options.clone()
        },
    );
    assert!(one.pixels != other_seed.pixels);
}

/// The eight-wide tree's queries take AVX2 where the CPU has it and the baseline's SSE where
/// not: every bundled scene renders to the same pixels either way (40 pixels wide).
#[test]
fn renders_are_identical_whichever_instructions_the_queries_take() {
    use raytracer::accel::{Accel, AccelKind, Isa};
    use raytracer::render::render_with_accel;
    use raytracer::scene::{load, LoadOptions};

    let scenes = bundled_scenes();
    for path in &scenes {
        let small = LoadOptions {
            width: Some(40),
            ..LoadOptions::default()
        };
        let scene = load(path, &small).unwrap_or_else(|e| panic!("{e}"));
        let options = RenderOptions {
            spp: 2,
            ..RenderOptions::default()
        };
        let tree = Accel::build(&scene.primitives, AccelKind::Sah8, 4);
        let films = [Isa::BASELINE, Isa::detect()].map(|isa| {
            let accel = tree.clone().with_isa(isa);
            render_with_accel(&scene, &accel, &options).unwrap().film
        });
        let bits = |f: &raytracer::film::Film| {
            f.pixels
                .iter()
                .flat_map(|p| p.to_array().map(f32::to_bits))
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(&films[0]), bits(&films[1]), "{}", path.display());
    }
    assert!(scenes.len() >= 15, "{} scenes", scenes.len());
}

/// Area-light shadows are soft: the penumbra has values strictly between the umbra and full light,
/// and the random and jittered estimators agree on average.
#[test]
fn area_lights_cast_soft_shadows_and_samplers_agree() {
    let scene = AREA_SCENE.replace("\"type\": \"thinlens\"", "\"type\": \"pinhole\"");
    let jittered = render_json(
        &scene,
        &RenderOptions {
            spp: 16,
            ..Default::default()
        },
    );
    let random = render_json(
        &scene
            .replace("\"jittered\"", "\"random\"")
            .replace("\"samples\": 3", "\"samples\": 9"),
        &RenderOptions {
            spp: 16,
            ..Default::default()
        },
    );
    let distinct: std::collections::BTreeSet<u32> = jittered
        .pixels
        .iter()
        .map(|p| (p.y * 1000.0) as u32)
        .collect();
    assert!(
        distinct.len() > 200,
        "only {} distinct levels",
        distinct.len()
    );
    let mean =
        |f: &raytracer::film::Film| f.pixels.iter().map(|p| p.element_sum() as f64).sum::<f64>();
    let (a, b) = (mean(&jittered), mean(&random));
    assert!((a - b).abs() / a < 0.02, "jittered {a} vs random {b}");
}

/// A thin lens blurs what is off the focal plane and keeps what is on it sharp.
#[test]
fn thin_lens_blurs_only_off_the_focal_plane() {
    let scene = |focus: f32| {
        format!(
            r#"{{ "nbounces": 0, "rendermode": "binary",
                 "camera": {{ "type": "thinlens", "width": 64, "height": 64, "fov": 30,
                             "aperture": 0.5, "focusdistance": {focus},
                             "position": [0, 0, 0], "lookAt": [0, 0, -1], "upVector": [0, 1, 0] }},
                 "scene": {{ "backgroundcolor": [0, 0, 0], "lightsources": [],
                            "shapes": [ {{ "type": "sphere", "center": [0, 0, -10], "radius": 0.5 }} ] }} }}"#
        )
    };
    let options = RenderOptions {
        spp: 64,
        ..Default::default()
    };
    // Pixels that are neither fully hit nor fully missed: the blurred edge.
    let partial = |focus: f32| {
        render_json(&scene(focus), &options)
            .pixels
            .iter()
            .filter(|p| p.x > 0.02 && p.x < 0.98)
            .count()
    };
    let sharp = partial(10.0);
    let blurred = partial(4.0);
    assert!(
        blurred > 3 * sharp,
        "in focus {sharp} edge pixels, out of focus {blurred}"
    );
}

/// A mirror shows what is in front of it: a red sphere seen in a mirror quad behind it.
#[test]
fn mirror_reflects_the_scene() {
    let json = r#"{ "nbounces": 1,
      "camera": { "type": "pinhole", "width": 32, "height": 32, "fov": 30,
                  "position": [0, -5, 0], "lookat": [0, 1, 0], "up": [0, 0, 1] },
      "scene": { "backgroundcolor": [0, 0, 0],
        "lightsources": [ { "type": "pointlight", "position": [0, -4, 3], "is": [0, 0, 0], "id": [400, 400, 400] } ],
        "shapes": [
          { "type": "sphere", "center": [0, -8, 0], "radius": 1,
            "material": { "kd": 1, "ks": 0, "specularexponent": 1, "diffusecolor": [1, 0, 0] } },
          { "type": "plane", "v0": [-3, 2, -3], "v1": [3, 2, -3], "v2": [3, 2, 3], "v3": [-3, 2, 3],
            "material": { "kd": 0, "ks": 0, "specularexponent": 1, "diffusecolor": [0, 0, 0], "kr": 1 } } ] } }"#;
    // The sphere is behind the camera; only its reflection can be red at the image centre.
    let c = render_default(json).get(16, 16);
    assert!(c.x > 0.05 && c.y == 0.0 && c.z == 0.0, "centre pixel {c}");
    let no_bounce = render_default(&json.replace("\"nbounces\": 1", "\"nbounces\": 0")).get(16, 16);
    assert_eq!(no_bounce, Vec3::ZERO);
}

/// Two facing glass panes at nbounces 50 would spawn 2^50 rays per pixel; the per-sample budget
/// keeps the render finite and the result finite.
#[test]
fn glass_ray_trees_are_bounded() {
    let json = r#"{ "nbounces": 50,
      "camera": { "type": "pinhole", "width": 8, "height": 8, "fov": 20,
                  "position": [0, -5, 0], "lookat": [0, 1, 0], "up": [0, 0, 1] },
      "scene": { "backgroundcolor": [0.5, 0.5, 0.5],
        "lightsources": [ { "type": "pointlight", "position": [0, -4, 3], "is": [50, 50, 50], "id": [50, 50, 50] } ],
        "shapes": [
          { "type": "plane", "v0": [-3, 0, -3], "v1": [3, 0, -3], "v2": [3, 0, 3], "v3": [-3, 0, 3],
            "material": { "kd": 0, "ks": 0, "specularexponent": 1, "diffusecolor": [0, 0, 0], "kr": 0.5, "kt": 0.9, "eta": 1.5 } },
          { "type": "plane", "v0": [-3, 0.5, -3], "v1": [3, 0.5, -3], "v2": [3, 0.5, 3], "v3": [-3, 0.5, 3],
            "material": { "kd": 0, "ks": 0, "specularexponent": 1, "diffusecolor": [0, 0, 0], "kr": 0.5, "kt": 0.9, "eta": 1.5 } } ] } }"#;
    let scene = load_json(json);
    let out = render(&scene, &RenderOptions::default()).unwrap();
    let per_sample = out.counts.secondary / 64;
    assert!(per_sample <= raytracer::integrator::MAX_SECONDARY_RAYS_PER_SAMPLE as u64);
    assert!(out.film.pixels.iter().all(|p| p.is_finite()));
}
