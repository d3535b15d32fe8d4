//! The `auto` crossover: the query times of each accelerator on random scenes of growing size,
//! which show whether a small scene is better served by no tree than by the one `auto` builds.

use super::rays::{ray_sets, trace_set, RayKind};
use super::scenes::random_scene;
use super::timing::timed;
use std::time::Duration;

use raytracer::accel::{Accel, AccelKind};
use raytracer::light::Light;
use raytracer::math::Vec3;

/// Query times of `random_scene(n, backdrop)` with `none`, `flat`, `sah` and `sah4` (the tree
/// `auto` builds), for each `n`: the three ray sets of [`ray_sets`] (camera rays at 320×240,
/// shadow rays to the light, random secondary rays) traced on this thread, medians of `runs`.
/// Timing the queries alone, not whole renders, keeps shading and ray generation, which the
/// accelerators share, out of the comparison.
pub fn crossover(
    sizes: &[usize],
    backdrop: bool,
    runs: usize,
    leaf_size: usize,
) -> Vec<(usize, [Duration; 4])> {
    sizes
        .iter()
        .map(|&n| {
            let scene = random_scene(n, 320, 240, backdrop);
            let light = match scene.lights.first() {
                Some(Light::Point { position, .. }) => *position,
                _ => Vec3::Y,
            };
            let sah = Accel::build(&scene.primitives, AccelKind::Sah, leaf_size);
            let sets = ray_sets(&scene, &sah, light, 0);
            let time = |accel: &Accel| {
                timed(runs, || {
                    RayKind::ALL
                        .iter()
                        .map(|&k| trace_set(&scene, accel, &sets, k, false))
                        .sum::<u64>()
                })
                .0
            };
            let flat = Accel::build(&scene.primitives, AccelKind::Flat, leaf_size);
            let sah4 = Accel::build(&scene.primitives, AccelKind::Sah4, leaf_size);
            (
                n,
                [time(&Accel::List), time(&flat), time(&sah), time(&sah4)],
            )
        })
        .collect()
}
