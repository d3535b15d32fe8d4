//! One ray set of `raytracer bench --rays` traced once, so that a profiler can count what a query
//! costs: `benches/peers/embree.py --instructions` runs it under callgrind beside Embree, which
//! traces the same rays.
//!
//! ```sh
//! cargo build --release --example ray_set
//! valgrind --tool=callgrind --toggle-collect='ray_set::trace*' \
//!     target/release/examples/ray_set 4 sah4 primary
//! ```
//!
//! Arguments: the grid (`4`: G=4, S=16, 8,194 triangles; `16`: G=16, S=32, 524,290), the tree
//! (`sah`, `sah4`, `sah8`, or `sah8-baseline` for the eight-wide tree with the baseline
//! instructions where the CPU has AVX2), and the set (`primary`, `shadow`, `incoherent`). The
//! scene, the tree and the rays are those of the benchmark; only the functions `trace_closest`
//! and `trace_any` trace them. Prints the rays traced and how many hit.

use raytracer::accel::kernels::Isa;
use raytracer::accel::{Accel, AccelKind};
use raytracer::geometry::Primitives;
use raytracer::ray::Ray;

// The benchmark's own scene, ray-set and timing code, shared with `raytracer bench` by path: the
// command line is a binary, so its modules are not part of the library.
#[allow(dead_code)]
#[path = "../src/cli/bench/rays.rs"]
mod rays;
#[allow(dead_code)]
#[path = "../src/cli/bench/scenes.rs"]
mod scenes;
#[allow(dead_code)]
#[path = "../src/cli/bench/timing.rs"]
mod timing;

use rays::{ray_sets, RayKind};
use scenes::{grid_light, sphere_grid};

/// Closest-hit queries for each of `rays`: the hits.
#[inline(never)]
fn trace_closest(accel: &Accel, prims: &Primitives, rays: &[Ray]) -> usize {
    rays.iter()
        .filter(|r| accel.closest(prims, r, f32::INFINITY).is_some())
        .count()
}

/// Any-hit queries for each of `rays` up to its distance: the rays blocked.
#[inline(never)]
fn trace_any(accel: &Accel, prims: &Primitives, rays: &[(Ray, f32)]) -> usize {
    rays.iter()
        .filter(|(r, t)| accel.any(prims, r, *t, |_| true))
        .count()
}

/// The command line, for errors.
const USAGE: &str = "usage: ray_set 4|16 sah|sah4|sah8|sah8-baseline primary|shadow|incoherent";

/// Leaves with `why` (if any) and the usage line, status 2.
fn usage(why: &str) -> ! {
    if !why.is_empty() {
        eprintln!("{why}");
    }
    eprintln!("{USAGE}");
    std::process::exit(2)
}

/// Builds the grid and the tree, traces the chosen set once and prints the count.
fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [grid, tree, set] = args.as_slice() else {
        usage("")
    };
    let (g, s) = match grid.as_str() {
        "4" => (4, 16),
        "16" => (16, 32),
        _ => usage(&format!("no grid {grid}")),
    };
    let (kind, isa) = match tree.strip_suffix("-baseline") {
        Some(kind) => (kind, Some(Isa::BASELINE)),
        None => (tree.as_str(), None),
    };
    let kind: AccelKind = kind.parse().unwrap_or_else(|e: String| usage(&e));
    let Some(set) = RayKind::ALL.into_iter().find(|k| k.name() == set) else {
        usage(&format!("no ray set {set}"))
    };
    let scene = sphere_grid(g, s, 640, 480);
    let prims = &scene.primitives;
    // The benchmark's leaf size (`raytracer bench --leaf-size`, 4).
    let mut accel = Accel::build(prims, kind, 4);
    if let Some(isa) = isa {
        accel = accel.with_isa(isa);
    }
    // The benchmark's seed, so that these are the rays `bench --rays --export` writes.
    let sets = ray_sets(&scene, &accel, grid_light(g), 0);
    let (rays, hits) = match set {
        RayKind::Primary => (
            sets.primary.len(),
            trace_closest(&accel, prims, &sets.primary),
        ),
        RayKind::Shadow => (sets.shadow.len(), trace_any(&accel, prims, &sets.shadow)),
        RayKind::Incoherent => (
            sets.incoherent.len(),
            trace_closest(&accel, prims, &sets.incoherent),
        ),
    };
    println!("{rays} rays, {hits} hit");
}
