//! Tests of the Whitted integrator: shortcuts against the plain computation, and pictures.

use std::path::Path;

use super::*;
use crate::accel::kernels::twin::Rng;
use crate::accel::AccelKind;
use crate::integrator::DEFAULT_CUTOFF;
use crate::material::highlight;
use crate::math::Vec2;
use crate::scene::{load_str, LoadOptions};

/// Zero a quarter of the time, else in `[0, 1)`.
fn often_zero(d: &mut Rng) -> f32 {
    if d.next() < 0.25 {
        0.0
    } else {
        d.next()
    }
}

/// Black half of the time, else a colour whose first channel is often zero.
fn colour(d: &mut Rng) -> Vec3 {
    if d.next() < 0.5 {
        Vec3::ZERO
    } else {
        Vec3::new(often_zero(d), d.next(), d.next())
    }
}

/// Where [`negligible`] says so without a cut-off, both terms are zeros for every visibility,
/// computed as [`Whitted::add_sample`] computes them, so leaving them out keeps every bit of
/// the colour they would have been added to.
#[test]
fn negligible_terms_without_a_cutoff_are_exact_zeros() {
    let mut d = Rng(0x9e37_79b9_7f4a_7c15);
    let mut exact = 0;
    for _ in 0..200_000 {
        // Light strengths from far below one to far above, and the odd infinite one.
        let unblocked = match (d.next() * 8.0) as u32 {
            0 => f32::INFINITY,
            1 => 1e-30 * d.next(),
            2 => 1e30 * d.next(),
            _ => d.next() * 100.0,
        };
        let n_dot_l = often_zero(&mut d);
        let spec = highlight(
            often_zero(&mut d),
            [1.0, 30.0, 200.0, 1000.0][(d.next() * 4.0) as usize],
        );
        let (diffuse, specular) = (colour(&mut d), colour(&mut d));
        for least in [0.0, 1e-4] {
            if negligible(unblocked, n_dot_l, diffuse, spec, specular, least) {
                assert!(may_be_negligible(unblocked, n_dot_l, diffuse, least));
            }
        }
        if !negligible(unblocked, n_dot_l, diffuse, spec, specular, 0.0) {
            continue;
        }
        exact += 1;
        let colour = Vec3::new(d.next(), 0.0, d.next() * 1e-3);
        for visibility in [1.0, d.next(), 1e-3 * d.next(), 0.0] {
            let e = unblocked * visibility;
            let mut c = colour;
            c += diffuse * (n_dot_l * e);
            c += specular * (spec * e);
            assert_eq!(
                c.to_array().map(f32::to_bits),
                colour.to_array().map(f32::to_bits),
                "unblocked {unblocked}, n·l {n_dot_l}, diffuse {diffuse}, spec {spec}, \
                 specular {specular}, visibility {visibility}"
            );
        }
    }
    assert!(exact > 10_000, "{exact} negligible cases");
    // Not negligible: infinite or NaN strengths, and any term above zero.
    assert!(!negligible(
        f32::INFINITY,
        0.0,
        Vec3::ZERO,
        0.0,
        Vec3::ZERO,
        1.0
    ));
    assert!(!negligible(f32::NAN, 0.0, Vec3::ZERO, 0.0, Vec3::ZERO, 1.0));
    assert!(!negligible(1.0, 1e-20, Vec3::ONE, 0.0, Vec3::ZERO, 0.0));
    assert!(!negligible(1.0, 0.0, Vec3::ZERO, 1e-40, Vec3::ONE, 0.0));
    // With a cut-off: below it in every channel, not in one.
    assert!(negligible(
        1.0,
        0.5,
        Vec3::splat(1e-3),
        0.0,
        Vec3::ONE,
        1e-3
    ));
    assert!(!negligible(
        1.0,
        0.5,
        Vec3::new(1e-3, 1e-2, 0.0),
        0.0,
        Vec3::ONE,
        1e-3
    ));
}

/// Mirror and glass spheres of `kd = 0` with sharp highlights, a diffuse one and a floor,
/// under a point light and a quad light.
const SCENE: &str = r#"{
  "nbounces": 6,
  "rendermode": "phong",
  "camera": {"type": "pinhole", "width": 48, "height": 36, "fov": 50,
             "position": [0, 2.5, 6], "lookat": [0, -0.3, -1], "up": [0, 1, 0]},
  "scene": {
    "backgroundcolor": [0.3, 0.35, 0.45],
    "lightsources": [
      {"type": "pointlight", "position": [-3, 6, 5], "intensity": [0.9, 0.9, 0.9]},
      {"type": "arealight", "v0": [1, 4, -1], "v1": [2, 4, -1], "v2": [2, 4, 0],
       "v3": [1, 4, 0], "samples": 3, "method": "jittered",
       "is": [0.4, 0.4, 0.4], "id": [0.4, 0.4, 0.4]}
    ],
    "shapes": [
      {"type": "plane", "v0": [-6, 0, 6], "v1": [6, 0, 6], "v2": [6, 0, -6], "v3": [-6, 0, -6],
       "material": {"kd": 0.8, "ks": 0.1, "specularexponent": 10,
                    "diffusecolor": [0.9, 0.9, 0.9], "specularcolor": [1, 1, 1]}},
      {"type": "sphere", "center": [-1.2, 0.8, 0], "radius": 0.8,
       "material": {"kd": 0, "ks": 0.6, "specularexponent": 200,
                    "diffusecolor": [1, 1, 1], "specularcolor": [1, 1, 1],
                    "isrefractive": true, "refractiveindex": 1.5}},
      {"type": "sphere", "center": [0.6, 0.8, -0.6], "radius": 0.8,
       "material": {"kd": 0, "ks": 0.2, "specularexponent": 200,
                    "diffusecolor": [1, 1, 1], "specularcolor": [1, 1, 1],
                    "isreflective": true, "reflectivity": 0.9}},
      {"type": "sphere", "center": [1.4, 0.4, 1.2], "radius": 0.4,
       "material": {"kd": 0.7, "ks": 0.3, "specularexponent": 40,
                    "diffusecolor": [0.8, 0.3, 0.2], "specularcolor": [1, 1, 1]}}
    ]
  }
}"#;

/// Every pixel's radiance (one sample at its centre) and the shadow rays traced, with the
/// cut-off `cutoff`, the lanes on or off, and the light cut as [`Whitted::new`] sets it or
/// (`light_cut: false`) at zero, where only exact zeros are left out.
fn render(cutoff: Option<f32>, lanes: bool, light_cut: bool) -> (Vec<Vec3>, u64) {
    let scene = load_str(SCENE, Path::new("cut.json"), &LoadOptions::default()).unwrap();
    let accel = Accel::build(&scene.primitives, AccelKind::Sah4, 4);
    let interiors = interiors(&scene, &accel);
    let options = TraceOptions {
        cutoff,
        ..Default::default()
    };
    let mut w = Whitted::new(&scene, &accel, &interiors, 8, options, Method::Jittered);
    w.lanes = lanes;
    if !light_cut {
        w.light_cut = 0.0;
    }
    let mut pixels = Vec::new();
    for_each_pixel_centre(&scene, |_, _, key, ray| {
        pixels.push(w.trace_camera(ray, key))
    });
    (pixels, w.counts.shadow)
}

/// The radiance along `ray` by plain recursion over [`Whitted::shade`]: each point's
/// refracted ray's subtree, then its reflected ray's, each scaled into the point's colour as
/// it finishes, with the sample's budget of secondary rays spent in that order.
fn recursive(
    w: &mut Whitted,
    ray: &Ray,
    depth: u32,
    key: &SampleKey,
    weight: f32,
    inside: Option<Inside>,
) -> Vec3 {
    let mut pending = Vec::new();
    let mut color = w.shade(ray, depth, key, weight, inside, &mut pending);
    // The refracted ray's subtree first: the one pushed last.
    for b in pending.into_iter().rev() {
        if w.budget == 0 {
            color += b.factor * Vec3::ZERO;
            continue;
        }
        w.budget -= 1;
        color += b.factor * recursive(w, &b.ray, b.depth, &b.key, b.weight, b.inside);
    }
    color
}

/// The explicit stack walks the ray tree as the recursion does: every pixel of a scene of
/// glass and mirror spheres, eight bounces deep, the same bits, with and without the cut-off.
#[test]
fn the_walk_sums_as_the_recursion_does() {
    let scene = load_str(SCENE, Path::new("walk.json"), &LoadOptions::default()).unwrap();
    let accel = Accel::build(&scene.primitives, AccelKind::Sah4, 4);
    let interiors = interiors(&scene, &accel);
    for cutoff in [None, Some(DEFAULT_CUTOFF)] {
        let options = TraceOptions {
            cutoff,
            ..Default::default()
        };
        let mut w = Whitted::new(&scene, &accel, &interiors, 8, options, Method::Jittered);
        let mut deepest = 0;
        for_each_pixel_centre(&scene, |x, y, key, ray| {
            let walked = w.trace_camera(ray, key);
            w.budget = MAX_SECONDARY_RAYS_PER_SAMPLE;
            let reference =
                crate::integrator::finite_radiance(recursive(&mut w, ray, 0, key, 1.0, None));
            deepest = deepest.max(MAX_SECONDARY_RAYS_PER_SAMPLE - w.budget);
            let bits = |v: Vec3| v.to_array().map(f32::to_bits);
            assert_eq!(
                bits(walked),
                bits(reference),
                "pixel ({x}, {y}), {cutoff:?}"
            );
        });
        // Trees of several levels, so that the order of the sums is tested.
        assert!(deepest >= 4, "at most {deepest} secondary rays a pixel");
    }
}

/// Where no shading point draws a sample (point lights, smooth mirrors and glass: the glass
/// peer scene), no sample key is read: every pixel is the same with a key that holds no hash
/// ([`SampleKey::unread`], what a render passes such a tracer). Where one does (the area light
/// of [`SCENE`]), the tracer says so.
#[test]
fn a_tracer_that_draws_no_sample_reads_no_key() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/peers/scenes/glass.json");
    let options = LoadOptions {
        width: Some(64),
        ..LoadOptions::default()
    };
    let scene = crate::scene::load(&path, &options).unwrap();
    let accel = Accel::build(&scene.primitives, AccelKind::Sah4, 4);
    let table = interiors(&scene, &accel);
    let options = TraceOptions::default();
    let mut w = Whitted::new(&scene, &accel, &table, 8, options, Method::Jittered);
    assert!(!w.draws());
    let mut lit = 0;
    for_each_pixel_centre(&scene, |x, y, key, ray| {
        let keyed = w.trace_camera(ray, key);
        let unread = w.trace_camera(ray, &SampleKey::unread(0, 1));
        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
        assert_eq!(bits(keyed), bits(unread), "pixel ({x}, {y})");
        lit += usize::from(keyed != scene.background);
    });
    assert!(lit > 1000, "{lit} pixels see the scene");
    let scene = load_str(SCENE, Path::new("draws.json"), &LoadOptions::default()).unwrap();
    let accel = Accel::build(&scene.primitives, AccelKind::Sah4, 4);
    let table = interiors(&scene, &accel);
    let w = Whitted::new(&scene, &accel, &table, 8, options, Method::Jittered);
    assert!(w.draws());
}

/// A point on glass pushes its reflected ray, then its refracted one, which is taken first:
/// the order the walk and its sums follow. Checked on every camera ray that enters a glass
/// sphere of [`SCENE`] (the refracted ray starts inside it, the reflected one outside).
#[test]
fn the_refracted_ray_is_pushed_last() {
    let scene = load_str(SCENE, Path::new("order.json"), &LoadOptions::default()).unwrap();
    let accel = Accel::build(&scene.primitives, AccelKind::Sah4, 4);
    let table = interiors(&scene, &accel);
    let options = TraceOptions::default();
    let mut w = Whitted::new(&scene, &accel, &table, 8, options, Method::Jittered);
    let mut entering = 0;
    for_each_pixel_centre(&scene, |x, y, key, ray| {
        let mut pending = Vec::new();
        w.shade(ray, 0, key, 1.0, None, &mut pending);
        if let [reflected, refracted] = pending.as_slice() {
            assert!(reflected.inside.is_none(), "pixel ({x}, {y})");
            entering += usize::from(refracted.inside.is_some());
        }
    });
    assert!(entering > 20, "{entering} camera rays enter glass");
}

/// Calls `f` with each pixel `(x, y)` of `scene`, row by row, its sample key (seed 7) and
/// the camera ray through its centre.
pub(super) fn for_each_pixel_centre(scene: &Scene, mut f: impl FnMut(u32, u32, &SampleKey, &Ray)) {
    for y in 0..scene.camera.height {
        for x in 0..scene.camera.width {
            let key = SampleKey::new(x, y, 0, 1, 7);
            let ray = scene
                .camera
                .generate_ray(x, y, Vec2::splat(0.5), Vec2::splat(0.5));
            f(x, y, &key, &ray);
        }
    }
}

/// With the cut-off, light terms below it are left out: fewer shadow rays, and no pixel
/// further from the render that traces them than `(nbounces + 1) · cutoff / 64`, the bound
/// [`negligible`] states.
#[test]
fn the_light_cut_saves_shadow_rays_within_its_bound() {
    let bound = 7.0 * DEFAULT_CUTOFF / LIGHT_CUT_FRACTION;
    for lanes in [true, false] {
        let (cut, cut_rays) = render(Some(DEFAULT_CUTOFF), lanes, true);
        let (all, all_rays) = render(Some(DEFAULT_CUTOFF), lanes, false);
        assert!(cut_rays < all_rays, "{cut_rays} of {all_rays} shadow rays");
        let worst = cut
            .iter()
            .zip(&all)
            .map(|(a, b)| (*a - *b).abs().max_element())
            .fold(0.0f32, f32::max);
        assert!(worst <= bound, "lanes {lanes}: {worst} > {bound}");
    }
    // Without a cut-off only exact zeros go, and the mirror and glass spheres away from
    // their highlights still save shadow rays: fewer than with the cut, more than none.
    let (_, exact_rays) = render(None, true, true);
    let (_, cut_rays) = render(Some(DEFAULT_CUTOFF), true, true);
    assert!(exact_rays > cut_rays);
}
