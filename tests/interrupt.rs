//! Stopping a render: the cancel flag is looked at per camera sample, per shading point and per
//! batch of shadow rays, so even one very long camera sample stops soon. Counted in rays, never
//! timed. And an image too large to allocate is an error, not an abort.

use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;

use raytracer::accel::{Accel, AccelKind};
use raytracer::integrator::{Integrator, IntegratorKind, TraceOptions};
use raytracer::render::{render, render_with_accel_counting, RenderError, RenderOptions};
use raytracer::sampling::SampleKey;
use raytracer::scene::{load_str, LoadOptions, Scene};

/// A `size`×`size` view of a floor under an area light of `side`² jittered shadow rays per
/// shading point, and a mirror sphere (so camera samples also spawn reflections).
fn heavy_scene(size: u32, side: u32, nbounces: u32) -> Scene {
    let text = format!(
        r#"{{
  "nbounces": {nbounces},
  "camera": {{"width": {size}, "height": {size}, "fov": 60, "position": [0, 1, 3], "lookat": [0, -0.3, -1], "up": [0, 1, 0]}},
  "scene": {{
    "lightsources": [{{"type": "arealight", "v0": [-1, 2, -1], "v1": [1, 2, -1], "v2": [1, 2, 1], "v3": [-1, 2, 1],
                       "is": [20, 20, 20], "id": [20, 20, 20], "samples": {side}, "method": "jittered"}}],
    "shapes": [
      {{"type": "quad", "v0": [-5, 0, -5], "v1": [5, 0, -5], "v2": [5, 0, 5], "v3": [-5, 0, 5],
        "material": {{"kd": 0.8, "ks": 0.1, "specularexponent": 10, "diffusecolor": [1, 1, 1], "kr": 0.5}}}},
      {{"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": {{"kd": 0.2, "kr": 0.8}}}}
    ]
  }}
}}"#
    );
    let options = LoadOptions {
        max_bounces: 100_000,
        ..LoadOptions::default()
    };
    load_str(&text, Path::new("heavy.json"), &options).unwrap_or_else(|e| panic!("{e}"))
}

fn cancelled_options(flag: &Arc<AtomicBool>) -> RenderOptions {
    RenderOptions {
        cancel: Some(flag.clone()),
        ..RenderOptions::default()
    }
}

#[test]
fn a_render_cancelled_before_it_starts_traces_nothing() {
    let scene = heavy_scene(8, 256, 3);
    let flag = Arc::new(AtomicBool::new(true));
    let out = render(&scene, &cancelled_options(&flag)).unwrap();
    assert!(out.cancelled);
    assert_eq!(out.counts.total(), 0);
}

#[test]
fn a_cancelled_camera_sample_stops_inside_its_shadow_rays_and_its_ray_tree() {
    // One camera sample here would take 65,536 shadow rays per shading point and, with the
    // mirrors, thousands of shading points.
    let scene = heavy_scene(8, 256, 100_000);
    let accel = Accel::build(&scene.primitives, AccelKind::Auto, 4);
    let flag = AtomicBool::new(true);
    for kind in [IntegratorKind::Whitted, IntegratorKind::Path] {
        let integrator = Integrator::new(&scene, &accel, kind);
        let mut tracer = integrator.tracer(
            u32::MAX,
            TraceOptions::default(),
            raytracer::sampling::Method::Sobol,
            Some(&flag),
        );
        for (x, y) in [(4, 7), (4, 4), (1, 6)] {
            let key = SampleKey::new(x, y, 0, 1, 0);
            let ray = scene.camera.generate_ray(
                x,
                y,
                raytracer::math::Vec2::splat(0.5),
                raytracer::math::Vec2::splat(0.5),
            );
            // Each of these pixels sees the floor or the sphere: a shading point with shadow rays.
            assert!(accel
                .closest(&scene.primitives, &ray, f32::INFINITY)
                .is_some());
            tracer.trace_camera(&ray, &key);
        }
        let counts = tracer.counts();
        assert_eq!(counts.camera, 3, "{kind}");
        assert_eq!(counts.secondary, 0, "{kind}");
        assert_eq!(counts.shadow, 0, "{kind}");
    }
}

#[test]
fn a_render_stops_soon_after_another_thread_sets_the_flag() {
    // 32×32 pixels of 64² shadow rays per shading point; the flag is set once 8 pixels are done.
    let size = 32;
    let scene = heavy_scene(size, 64, 3);
    let accel = Accel::build(&scene.primitives, AccelKind::Auto, 4);
    let flag = Arc::new(AtomicBool::new(false));
    let done = AtomicU64::new(0);
    let options = cancelled_options(&flag);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a thread pool");
    let out = std::thread::scope(|s| {
        s.spawn(|| {
            while done.load(Ordering::Relaxed) < 8 {
                std::thread::yield_now();
            }
            flag.store(true, Ordering::Relaxed);
        });
        pool.install(|| render_with_accel_counting(&scene, &accel, &options, &done))
            .unwrap()
    });
    assert!(out.cancelled);
    let pixels = (size * size) as u64;
    assert!(done.load(Ordering::Relaxed) >= 8);
    assert!(
        out.counts.camera < pixels / 4,
        "{} of {pixels} camera rays traced after the flag",
        out.counts.camera
    );
    // The full render takes 4096 shadow rays for every pixel that sees the floor.
    assert!(out.counts.shadow < pixels / 4 * 4096, "{:?}", out.counts);
}

#[test]
fn an_image_too_large_to_allocate_is_an_error() {
    let text = r#"{"camera": {"width": 4294967295, "height": 4294967295, "fov": 45},
                   "shapes": [{"type": "sphere", "center": [0, 0, -3], "radius": 1}]}"#;
    let options = LoadOptions {
        max_pixels: u64::MAX,
        ..LoadOptions::default()
    };
    let scene = load_str(text, Path::new("huge.json"), &options).unwrap_or_else(|e| panic!("{e}"));
    match render(&scene, &RenderOptions::default()) {
        Err(e @ RenderError::TooLarge { .. }) => {
            let message = e.to_string();
            assert!(message.contains("4294967295×4294967295"), "{message}");
        }
        Ok(_) => panic!("a {0}×{0} film was allocated", u32::MAX),
        Err(e) => panic!("{e}"),
    }
}
