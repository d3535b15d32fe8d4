//! Two facing mirrors and a bounce limit far past anything a thread's stack could recurse
//! through: the ray tree is walked without recursion, its length is set by the secondary-ray
//! budget, and the value is the sum of the reflection series the geometry gives.

use std::path::Path;

use raytracer::integrator::MAX_SECONDARY_RAYS_PER_SAMPLE;
use raytracer::render::{render, RenderOptions, RenderOutput};
use raytracer::scene::{load_str, LoadOptions};

/// `A`'s reflectivity.
const KR: f32 = 0.999;

/// A 1×1 camera at the origin looking down −z between two parallel mirrors: `A` at z = −1
/// (reflecting 0.999 and diffuse 0.001, all it can be together, lit by a point light at z = 0.5)
/// and `B` at z = +1 (a perfect black mirror). The pixel-centre ray runs along the axis and hits
/// `A`, `B`, `A`, … forever.
fn facing_mirrors(nbounces: u32) -> RenderOutput {
    let text = format!(
        r#"{{
  "nbounces": {nbounces},
  "camera": {{"width": 1, "height": 1, "fov": 10, "position": [0, 0, 0], "lookat": [0, 0, -1], "up": [0, 1, 0]}},
  "scene": {{
    "backgroundcolor": [0, 0, 1],
    "lightsources": [{{"type": "pointlight", "position": [0, 0, 0.5], "intensity": [1, 1, 1]}}],
    "shapes": [
      {{"type": "quad", "v0": [-10, -10, -1], "v1": [10, -10, -1], "v2": [10, 10, -1], "v3": [-10, 10, -1],
        "material": {{"kd": 0.001, "ks": 0, "kr": {KR}, "diffusecolor": [1, 1, 1]}}}},
      {{"type": "quad", "v0": [-10, -10, 1], "v1": [10, -10, 1], "v2": [10, 10, 1], "v3": [-10, 10, 1],
        "material": {{"kd": 0, "ks": 0, "kr": 1, "diffusecolor": [1, 1, 1]}}}}
    ]
  }}
}}"#
    );
    let options = LoadOptions {
        max_bounces: 100_000,
        ..LoadOptions::default()
    };
    let scene =
        load_str(&text, Path::new("mirrors.json"), &options).unwrap_or_else(|e| panic!("{e}"));
    render(&scene, &RenderOptions::default()).unwrap()
}

#[test]
fn facing_mirrors_sum_their_reflection_series() {
    // With no bounce, the pixel is A's direct light: kd · n·l / d² with the light 1.5 away.
    let direct = facing_mirrors(0).film.get(0, 0);
    assert!((direct.x / (0.001 / 2.25) - 1.0).abs() < 1e-4, "{direct}");
    for nbounces in [3000, 4000, 100_000] {
        let out = facing_mirrors(nbounces);
        // Every bounce is one secondary ray until the sample's budget is spent; each hit point
        // on A (the camera ray's and every second bounce's) traces one shadow ray. B's terms
        // are zeros (kd = ks = 0), so its hit points trace none.
        let bounces = nbounces.min(MAX_SECONDARY_RAYS_PER_SAMPLE) as u64;
        assert_eq!(out.counts.camera, 1);
        assert_eq!(out.counts.secondary, bounces, "nbounces {nbounces}");
        assert_eq!(out.counts.shadow, bounces / 2 + 1, "nbounces {nbounces}");
        // The pixel is A's direct light once per visit to A, at bounces 0, 2, 4, …, the k-th
        // visit weighted by KR^k; B adds nothing. Over 1,500 and 2,049 visits the sums differ
        // by a tenth, so each bounce is counted.
        let visits = (bounces / 2 + 1) as i32;
        let got = out.film.get(0, 0);
        let want = direct * (1.0 - KR.powi(visits)) / (1.0 - KR);
        assert!(
            ((got - want) / want.max(direct)).abs().max_element() < 1e-3,
            "nbounces {nbounces}: {got} vs {want}"
        );
    }
}
