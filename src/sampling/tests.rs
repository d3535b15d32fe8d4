//! Tests of the samplers: nets, strata, determinism and the estimates they give.

use super::sobol::*;
use super::*;
use crate::math::Vec2;

/// A padded dimension is stratified over all of a pixel's points: with 4 camera samples of
/// 4 points each, jittered puts one point in each cell of a 4×4 grid, and Sobol's 16 points
/// form a (0,4,2)-net (one in each 1/4 × 1/4 cell too).
#[test]
fn padded_points_are_stratified_across_the_pixel() {
    for method in [Method::Jittered, Method::Sobol] {
        let mut cells = [0u32; 16];
        for s in 0..4 {
            let key = SampleKey::new(3, 5, s, 4, 9);
            for j in 0..4 {
                let u = key.padded(method, 7, j, 4);
                assert!((0.0..1.0).contains(&u.x) && (0.0..1.0).contains(&u.y));
                cells[(u.x * 4.0) as usize + 4 * (u.y * 4.0) as usize] += 1;
            }
        }
        assert_eq!(cells, [1; 16], "{method}");
        // The 4D form's first two dimensions are the 2D point.
        let key = SampleKey::new(3, 5, 2, 4, 9);
        if method == Method::Sobol {
            let [a, b, _, _] = key.padded4(method, 7, 1, 4);
            assert_eq!(Vec2::new(a, b), key.padded(method, 7, 1, 4));
        }
    }
}

/// The point set's hoisted form against the per-point computation it replaces.
#[test]
fn point_set_equals_the_per_point_formula() {
    let reference = |key: &SampleKey, method, dim: u64, i: u32, count: u32| {
        let h = hash(&[key.key, dim, i as u64]);
        let u = Vec2::new(to_unit(h), to_unit(mix64(h)));
        match method {
            Method::Random => u,
            Method::Jittered => {
                let shuffle = (hash(&[key.key, dim]) & 0xffff_ffff) as u32;
                stratum_point(i, count, square_side(count), u, shuffle)
            }
            Method::Sobol => sobol2(i, (hash(&[key.key, dim, 0x50b0]) >> 32) as u32),
        }
    };
    let key = SampleKey::new(5, 9, 2, 4, 77).stream(3);
    for method in [Method::Random, Method::Jittered, Method::Sobol] {
        for count in [1, 2, 7, 16, 64, 100, 101] {
            for dim in [0, 3] {
                let set = key.point_set(method, dim, count);
                for i in 0..count {
                    let want = reference(&key, method, dim, i, count);
                    assert_eq!(set.point(i), want, "{method:?} {count} {dim} {i}");
                }
            }
        }
    }
}

/// A packed Sobol point gives back every point it can hold exactly, and keeps a sample key
/// at 32 bytes.
#[test]
fn sobol_pairs_hold_sobol_points_exactly() {
    assert_eq!(SobolPair::NONE.get(), None);
    for seed in [0, 9, 0xfeed_f00d] {
        for i in (0..1u32 << 16).step_by(7).chain([0xffff]) {
            let [a, b, c, d] = sobol4(i, seed);
            for p in [Vec2::new(a, b), Vec2::new(c, d)] {
                assert_eq!(SobolPair::new(p).get(), Some(p), "{i} {seed}");
            }
        }
    }
    let ends = [0.0, 1.0 - 1.0 / SOBOL_ONE];
    for (x, y) in ends.iter().flat_map(|&x| ends.map(|y| (x, y))) {
        let p = Vec2::new(x, y);
        assert_eq!(SobolPair::new(p).get(), Some(p));
    }
    assert_eq!(std::mem::size_of::<SampleKey>(), 32);
}

/// A digital shift is exact and its own inverse, and it maps a Sobol net to a net: the
/// first 2ᵏ points of a pixel's pattern, shifted alike, still put one point in every
/// elementary cell of their area.
#[test]
fn digital_shifts_keep_nets() {
    for seed in [0, 7, 0xdead_beef] {
        for shift in [
            0u64,
            1,
            0x7f_ffff,
            0x1234_5678_9abc_def0,
            mix64(seed as u64),
        ] {
            let (sx, sy) = (shift as u32, (shift >> 32) as u32);
            for n in [4, 16, 64, 256] {
                let points: Vec<Vec2> = (0..n)
                    .map(|i| {
                        let p = sobol2(i, seed);
                        let q = Vec2::new(digital_shift(p.x, sx), digital_shift(p.y, sy));
                        assert!((0.0..1.0).contains(&q.x) && (0.0..1.0).contains(&q.y));
                        let back = Vec2::new(digital_shift(q.x, sx), digital_shift(q.y, sy));
                        assert_eq!(back, p);
                        q
                    })
                    .collect();
                assert!(is_net(&points), "seed {seed}, shift {shift:x}, {n} points");
            }
        }
    }
}

/// The table-driven Sobol points against the crate they stand in for, over every index the
/// crate supports and a spread of seeds.
#[test]
fn sobol_tables_reproduce_the_crate() {
    for (d, row) in SOBOL_REV_VECTORS.iter().enumerate() {
        let single = sobol_burley::parts::sobol_int4_rev(0x8000_0000 >> d, 0);
        assert_eq!(
            <[u32; 4]>::from(single),
            *row,
            "direction numbers of bit {d}"
        );
    }
    for seed in [0u32, 1, 0x9e37_79b9, 0xdead_beef, u32::MAX] {
        for index in 0..1u32 << 16 {
            let ours = sobol_set0(index, seed).map(f32::to_bits);
            let crate_point = sobol_burley::sample_4d(index, 0, seed).map(f32::to_bits);
            assert_eq!(ours, crate_point, "index {index}, seed {seed:#x}");
        }
    }
}

#[test]
fn permute_is_a_bijection() {
    for len in [1u32, 2, 3, 7, 16, 100, 257] {
        for key in [0u32, 1, 0xdead_beef] {
            let mut seen = vec![false; len as usize];
            for i in 0..len {
                let p = permute(i, len, key);
                assert!(p < len);
                assert!(!seen[p as usize], "len {len} key {key}: {p} twice");
                seen[p as usize] = true;
            }
        }
    }
}

#[test]
fn jittered_square_counts_fill_every_cell_once() {
    let key = SampleKey::new(3, 4, 0, 1, 7);
    let mut cells = [0u32; 16];
    for i in 0..16 {
        let p = key.point_set(Method::Jittered, 5, 16).point(i);
        assert!(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0);
        cells[(p.y * 4.0) as usize * 4 + (p.x * 4.0) as usize] += 1;
    }
    assert!(cells.iter().all(|&c| c == 1), "{cells:?}");
}

#[test]
fn jittered_other_counts_are_latin_hypercubes() {
    let n = 12;
    let mut rows = vec![0u32; n];
    let mut cols = vec![0u32; n];
    for s in 0..n as u32 {
        let p = SampleKey::new(1, 2, s, n as u32, 9).pixel_pattern(Method::Jittered, 0);
        rows[(p.x * n as f32) as usize] += 1;
        cols[(p.y * n as f32) as usize] += 1;
    }
    assert!(rows.iter().all(|&c| c == 1) && cols.iter().all(|&c| c == 1));
}

/// Whether `points` has exactly one point in each cell of every `2^a × 2^b` grid with
/// `a + b = log2(points.len())` (the (0,m,2)-net property).
fn is_net(points: &[Vec2]) -> bool {
    let m = points.len().trailing_zeros();
    (0..=m).all(|a| {
        let (nx, ny) = (1usize << a, 1usize << (m - a));
        let mut cells = vec![0u32; points.len()];
        for p in points {
            cells[(p.y * ny as f32) as usize * nx + (p.x * nx as f32) as usize] += 1;
        }
        cells.iter().all(|&c| c == 1)
    })
}

/// Every point of a light set of pixel `(x, y)` under `seed`: `spp` camera samples of `count`
/// points each, a camera sample's points together.
fn light_points(
    method: Method,
    across: Method,
    (x, y, seed): (u32, u32, u64),
    spp: u32,
    count: u32,
) -> Vec<Vec<Vec2>> {
    (0..spp)
        .map(|s| {
            let set = SampleKey::new(x, y, s, spp, seed).stream(2).light_set(
                method,
                &CameraSamples::new(across, spp),
                0,
                count,
            );
            (0..count).map(|i| set.point(i)).collect()
        })
        .collect()
}

/// How many of `points` fall in each cell of a `columns × rows` grid, row by row.
fn cell_counts(points: &[Vec2], columns: usize, rows: usize) -> Vec<u32> {
    let mut cells = vec![0u32; columns * rows];
    for p in points {
        assert!(
            (0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y),
            "{p}"
        );
        cells[(p.y * rows as f32) as usize * columns + (p.x * columns as f32) as usize] += 1;
    }
    cells
}

/// With one camera sample a light set is the camera sample's own point set, bit for bit.
#[test]
fn one_camera_sample_keeps_its_own_light_set() {
    let key = SampleKey::new(5, 9, 0, 1, 77).stream(3);
    for method in [Method::Random, Method::Jittered, Method::Sobol] {
        for across in [Method::Random, Method::Jittered, Method::Sobol] {
            for count in [1, 2, 7, 16, 64] {
                let (ours, own) = (
                    key.light_set(method, &CameraSamples::new(across, 1), 4, count),
                    key.point_set(method, 4, count),
                );
                for i in 0..count {
                    assert_eq!(ours.point(i), own.point(i), "{method} {across} {count}");
                }
            }
        }
    }
}

/// Each camera sample's points are what the light asks for (one in each of its `k×k` cells,
/// or a Sobol net), and the pixel's points together are stratified finer: jittered cells cut
/// into one part per camera sample (`√spp` square, else the squarest grid), each part holding
/// one point, or, spread with Sobol points, each cell's points a net; Sobol, the pixel's
/// points one net.
#[test]
fn light_sets_are_stratified_over_the_pixel() {
    for pixel in [(0, 0, 0), (3, 4, 7), (100, 7, 12345)] {
        for (spp, columns) in [(4, 2), (8, 2), (16, 4), (12, 3)] {
            let rows = spp as usize / columns;
            for across in [Method::Jittered, Method::Sobol] {
                let sets = light_points(Method::Jittered, across, pixel, spp, 16);
                for set in &sets {
                    assert_eq!(cell_counts(set, 4, 4), [1; 16], "{across} {spp}");
                }
                if across == Method::Jittered {
                    let all: Vec<Vec2> = sets.concat();
                    let cells = cell_counts(&all, 4 * columns, 4 * rows);
                    assert!(cells.iter().all(|&c| c == 1), "{spp}: {cells:?}");
                } else if spp.is_power_of_two() {
                    // Each cell's points over the pixel, scaled to the unit square: a net.
                    for cell in 0..16 {
                        let corner = Vec2::new((cell % 4) as f32, (cell / 4) as f32);
                        let inside: Vec<Vec2> = sets
                            .iter()
                            .flatten()
                            .map(|p| *p * 4.0 - corner)
                            .filter(|q| q.cmpge(Vec2::ZERO).all() && q.cmplt(Vec2::ONE).all())
                            .collect();
                        assert_eq!(inside.len(), spp as usize);
                        assert!(is_net(&inside), "{spp} cell {cell}: {inside:?}");
                    }
                }
            }
            // Random cells stay independent: some pixel's part holds two points.
            let all = light_points(Method::Jittered, Method::Random, pixel, spp, 16).concat();
            assert!(cell_counts(&all, 4 * columns, 4 * rows).contains(&0));
        }
        let sets = light_points(Method::Sobol, Method::Jittered, pixel, 8, 16);
        assert!(sets.iter().all(|set| is_net(set)));
        assert!(is_net(&sets.concat()));
    }
}

/// The variance of pixel estimates `values` of `truth`, after checking that their mean lies
/// within four standard errors of it.
fn unbiased_variance(values: &[f64], truth: f64) -> f64 {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    assert!(
        (mean - truth).abs() < 4.0 * (var / n).sqrt() + 1e-9,
        "{mean} against {truth}"
    );
    var
}

/// Under a pinhole camera the lights' Sobol pattern over the pixel is the camera sample's own
/// point, dimensions 2 and 3, so a shadow edge that moves across the light as the point moves
/// across the pixel is estimated with less variance than by a pattern scrambled apart from
/// the film, and both estimates are unbiased.
#[test]
fn pinhole_film_and_light_points_are_stratified_together() {
    // Lit where the light point lies below a line that rises with the film point's x.
    let lit = |film: Vec2, p: Vec2| f64::from(u8::from(p.y < 0.1 + 0.8 * film.x));
    let truth = 0.5;
    let (spp, count, pixels) = (64, 16, 1000u32);
    let stats = |shared: bool| {
        let values: Vec<f64> = (0..pixels)
            .map(|x| {
                let camera = CameraSamples::new(Method::Sobol, spp);
                let mut sum = 0.0;
                for s in 0..spp {
                    let mut key = SampleKey::new(x, 3, s, spp, 11);
                    let film = if shared {
                        key.pinhole_pattern(Method::Sobol)
                    } else {
                        key.pixel_pattern(Method::Sobol, 0)
                    };
                    let set = key.stream(0).light_set(Method::Jittered, &camera, 0, count);
                    sum += (0..count).map(|i| lit(film, set.point(i))).sum::<f64>();
                }
                sum / (spp * count) as f64
            })
            .collect();
        unbiased_variance(&values, truth)
    };
    let (shared, apart) = (stats(true), stats(false));
    assert!(shared * 1.5 < apart, "{shared} against {apart}");
}

/// The variance of a pixel's estimate of the lit part of a light, 16 camera samples of 16
/// shadow rays, with a straight edge across the light: sets spread over the pixel cut it at
/// least threefold against a set per camera sample, and both estimates are unbiased.
#[test]
fn light_sets_over_the_pixel_estimate_with_less_variance() {
    // The part of the unit square below the line y = 0.3 + 0.45·x.
    let lit = |p: Vec2| f64::from(u8::from(p.y < 0.3 + 0.45 * p.x));
    let truth = 0.3 + 0.45 / 2.0;
    let (spp, count, pixels) = (16, 16, 2000u32);
    let stats = |estimate: &dyn Fn(u32) -> f64| {
        let values: Vec<f64> = (0..pixels).map(estimate).collect();
        unbiased_variance(&values, truth)
    };
    for (method, across) in [
        (Method::Jittered, Method::Jittered),
        (Method::Jittered, Method::Sobol),
        (Method::Sobol, Method::Jittered),
    ] {
        let total = (spp * count) as f64;
        let own = stats(&|x| {
            (0..spp)
                .map(|s| {
                    let set = SampleKey::new(x, 1, s, spp, 5).point_set(method, 0, count);
                    (0..count).map(|i| lit(set.point(i))).sum::<f64>()
                })
                .sum::<f64>()
                / total
        });
        let spread = stats(&|x| {
            let sets = light_points(method, across, (x, 1, 5), spp, count);
            sets.concat().into_iter().map(lit).sum::<f64>() / total
        });
        assert!(
            spread * 3.0 < own,
            "{method} {across}: {spread} against {own}"
        );
    }
}

#[test]
fn sobol_sets_are_stratified_nets_in_the_unit_square() {
    for (x, y, seed) in [(0, 0, 0), (3, 4, 7), (100, 7, 12345)] {
        let key = SampleKey::new(x, y, 0, 1, seed).stream(2);
        for m in 0..=8 {
            let n = 1u32 << m;
            let set: Vec<Vec2> = (0..n)
                .map(|i| key.point_set(Method::Sobol, 0, n).point(i))
                .collect();
            assert!(set
                .iter()
                .all(|p| (0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y)));
            assert!(is_net(&set), "{n} points at ({x}, {y}) seed {seed}");
        }
        // In particular, the first 16 points fill the 4×4 grid one per cell.
        let mut cells = [0u32; 16];
        for i in 0..16 {
            let p = key.point_set(Method::Sobol, 0, 16).point(i);
            cells[(p.y * 4.0) as usize * 4 + (p.x * 4.0) as usize] += 1;
        }
        assert!(cells.iter().all(|&c| c == 1), "{cells:?}");
    }
    // Per-pixel patterns too: the 64 camera samples of a pixel form a net.
    let pattern: Vec<Vec2> = (0..64)
        .map(|s| SampleKey::new(5, 9, s, 64, 3).pixel_pattern(Method::Sobol, 0))
        .collect();
    assert!(is_net(&pattern));
}

/// A pixel's film and lens points, camera sample by camera sample: with Sobol points the
/// film is dimension 0's pattern, every power-of-two prefix of each lens coordinate is
/// stratified, and film and lens are stratified against each other, where two 2D patterns
/// scrambled apart pair their points at random.
#[test]
fn film_and_lens_points_are_stratified_against_each_other() {
    // Samples whose film coordinate `f` and lens coordinate `l` (0 = x, 1 = y) fall in each
    // cell of a `g×g` grid over the unit square they span.
    let cells = |pairs: &[(Vec2, Vec2)], f: usize, l: usize, g: usize| {
        let mut cells = vec![0u32; g * g];
        for (film, lens) in pairs {
            cells[(film[f] * g as f32) as usize * g + (lens[l] * g as f32) as usize] += 1;
        }
        cells
    };
    let axes = [(0, 0), (0, 1), (1, 0), (1, 1)];
    for (x, y, seed) in [(0, 0, 0), (3, 4, 7), (100, 7, 12345), (17, 90, 2)] {
        let key = |s: u32| SampleKey::new(x, y, s, 64, seed);
        let pairs: Vec<(Vec2, Vec2)> = (0..64)
            .map(|s| key(s).camera_pattern(Method::Sobol))
            .collect();
        for (s, (film, _)) in pairs.iter().enumerate() {
            assert_eq!(*film, key(s as u32).pixel_pattern(Method::Sobol, 0));
        }
        for n in [4, 8, 16, 32, 64] {
            let prefix = &pairs[..n];
            for axis in 0..2 {
                let mut strata = vec![0u32; n];
                for (_, lens) in prefix {
                    strata[(lens[axis] * n as f32) as usize] += 1;
                }
                assert!(
                    strata.iter().all(|&c| c == 1),
                    "lens axis {axis}, {n} samples"
                );
            }
            // From 8 samples on: at 4, dimensions 1 to 3 are tied (see `camera_pattern`).
            for (f, l) in axes.into_iter().filter(|_| n >= 8) {
                let quarters = cells(prefix, f, l, 2);
                assert_eq!(
                    quarters,
                    [n as u32 / 4; 4],
                    "film {f} lens {l}, {n} samples"
                );
            }
        }
        for (f, l) in axes {
            assert!(
                cells(&pairs, f, l, 8).iter().all(|&c| c == 1),
                "film {f} lens {l}"
            );
        }
        // Two patterns scrambled apart: random pairs, which leave about 64·(63/64)^64 ≈ 23
        // of the 64 cells empty.
        let apart: Vec<(Vec2, Vec2)> = (0..64)
            .map(|s| {
                let k = key(s);
                (
                    k.pixel_pattern(Method::Sobol, 0),
                    k.pixel_pattern(Method::Sobol, 1),
                )
            })
            .collect();
        for (f, l) in axes {
            let empty = cells(&apart, f, l, 8).iter().filter(|&&c| c == 0).count();
            assert!(empty >= 12, "film {f} lens {l}: {empty} empty");
        }
    }
    // Random points are the two patterns they were.
    let key = SampleKey::new(5, 6, 3, 16, 9);
    let (film, lens) = key.camera_pattern(Method::Random);
    assert_eq!(film, key.pixel_pattern(Method::Random, 0));
    assert_eq!(lens, key.pixel_pattern(Method::Random, 1));
}

/// Jittered film and lens points of a pixel of `k²` samples, `k` odd or a power of two from
/// 4: one sample in every cell of the `k×k` grid of each pair of their four coordinates, and
/// the film the pattern it was. Other counts pair the lens with the film at random, as before.
#[test]
fn jittered_film_and_lens_points_form_an_orthogonal_array() {
    for (k, seed) in [
        (3, 0),
        (4, 1),
        (5, 2),
        (7, 3),
        (8, 4),
        (9, 5),
        (16, 6),
        (32, 7),
    ] {
        let n = k * k;
        for (x, y) in [(0, 0), (13, 7), (200, 91)] {
            let key = |s: u32| SampleKey::new(x, y, s, n, seed);
            let points: Vec<[f32; 4]> = (0..n)
                .map(|s| {
                    let (film, lens) = key(s).camera_pattern(Method::Jittered);
                    assert_eq!(film, key(s).pixel_pattern(Method::Jittered, 0));
                    [film.x, film.y, lens.x, lens.y]
                })
                .collect();
            for a in 0..4 {
                for b in a + 1..4 {
                    let mut cells = vec![0u32; n as usize];
                    for p in &points {
                        let (u, v) = ((p[a] * k as f32) as u32, (p[b] * k as f32) as u32);
                        cells[(u.min(k - 1) * k + v.min(k - 1)) as usize] += 1;
                    }
                    assert!(
                        cells.iter().all(|&c| c == 1),
                        "k = {k}, pixel ({x}, {y}), coordinates {a} and {b}"
                    );
                }
            }
        }
    }
    for n in [4, 36, 100, 7, 1] {
        for s in 0..n {
            let key = SampleKey::new(5, 6, s, n, 9);
            assert_eq!(
                key.camera_pattern(Method::Jittered).1,
                key.pixel_pattern(Method::Jittered, 1),
                "{n} samples"
            );
        }
    }
}

#[test]
fn sobol_sets_are_deterministic_and_decorrelated() {
    let a = SampleKey::new(10, 20, 3, 8, 42);
    let b = SampleKey::new(10, 20, 3, 8, 42);
    for i in 0..8 {
        assert_eq!(
            a.point_set(Method::Sobol, 0, 8).point(i),
            b.point_set(Method::Sobol, 0, 8).point(i)
        );
        assert_eq!(
            a.pixel_pattern(Method::Sobol, 1),
            b.pixel_pattern(Method::Sobol, 1)
        );
    }
    // Different pixels, seeds, lights (streams) and set dimensions give different points.
    let p = a.point_set(Method::Sobol, 0, 8).point(0);
    assert_ne!(
        p,
        SampleKey::new(11, 20, 3, 8, 42)
            .point_set(Method::Sobol, 0, 8)
            .point(0)
    );
    assert_ne!(
        p,
        SampleKey::new(10, 20, 3, 8, 43)
            .point_set(Method::Sobol, 0, 8)
            .point(0)
    );
    assert_ne!(p, a.stream(1).point_set(Method::Sobol, 0, 8).point(0));
    assert_ne!(p, a.point_set(Method::Sobol, 1, 8).point(0));
    assert_ne!(
        a.pixel_pattern(Method::Sobol, 0),
        a.pixel_pattern(Method::Sobol, 1)
    );
    // Pixel (dimension 0) and lens (dimension 1) patterns are not paired up: over many
    // pixels, the correlation of their x coordinates is near zero.
    let n = 4096;
    let (mut sxy, mut sx, mut sy, mut sxx, mut syy) = (0.0f64, 0.0, 0.0, 0.0, 0.0);
    for k in 0..n {
        let key = SampleKey::new(k % 64, k / 64, k % 16, 16, 1);
        let (u, v) = (
            key.pixel_pattern(Method::Sobol, 0).x as f64,
            key.pixel_pattern(Method::Sobol, 1).x as f64,
        );
        (sx, sy, sxy, sxx, syy) = (sx + u, sy + v, sxy + u * v, sxx + u * u, syy + v * v);
    }
    let nf = n as f64;
    let cov = sxy / nf - sx * sy / nf / nf;
    let r = cov / ((sxx / nf - (sx / nf).powi(2)) * (syy / nf - (sy / nf).powi(2))).sqrt();
    assert!(r.abs() < 0.05, "correlation {r}");
    // Indices past the crate's 2^16 points still give valid, distinct points.
    let far = sobol2(70_000, 9);
    assert!((0.0..1.0).contains(&far.x) && far != sobol2(70_000 - (1 << 16), 9));
    assert_eq!("sobol".parse::<Method>(), Ok(Method::Sobol));
    assert_eq!(Method::Sobol.to_string(), "sobol");
}

#[test]
fn values_depend_only_on_their_coordinates() {
    let a = SampleKey::new(10, 20, 3, 8, 42);
    let b = SampleKey::new(10, 20, 3, 8, 42);
    assert_eq!(a.uniform(5), b.uniform(5));
    assert_ne!(a.uniform(5), a.uniform(6));
    assert_ne!(a.uniform(5), SampleKey::new(10, 20, 3, 8, 43).uniform(5));
    assert_ne!(a.stream(1).uniform(0), a.stream(2).uniform(0));
}

#[test]
fn uniform_values_have_the_right_mean() {
    let key = SampleKey::new(0, 0, 0, 1, 1);
    let n = 100_000;
    let mean: f64 = (0..n).map(|d| key.uniform(d) as f64).sum::<f64>() / n as f64;
    assert!((mean - 0.5).abs() < 0.005, "{mean}");
}

/// Half vectors are unit length, and their cosines follow the lobe's distribution: the share
/// with `cos θ ≥ c` is `1 − c^(e+1)`; for a near-mirror exponent the angles stay resolved.
#[test]
fn blinn_phong_half_vectors_follow_the_lobe() {
    for e in [0.0f32, 10.0, 1000.0, 19998.0] {
        let c = 0.5f32.powf(1.0 / (e + 1.0)); // the median cosine
        let n = 4096;
        let mut above = 0;
        for i in 0..n {
            let u = Vec2::new((i as f32 + 0.5) / n as f32, (i * 37 % n) as f32 / n as f32);
            let h = blinn_phong_half_vector(e, u);
            assert!((h.length() - 1.0).abs() < 1e-5, "e {e}: {h}");
            above += (h.z >= c) as usize;
        }
        assert!(
            (above as f32 / n as f32 - 0.5).abs() < 0.01,
            "e {e}: {above}"
        );
    }
    // Near a mirror, neighbouring samples give distinct angles (no 3·10⁻⁴ steps).
    let a = blinn_phong_half_vector(19998.0, Vec2::new(0.5, 0.0)).x;
    let b = blinn_phong_half_vector(19998.0, Vec2::new(0.5001, 0.0)).x;
    assert!(a > 0.0 && a != b && (a - b).abs() < 1e-5, "{a} {b}");
}

#[test]
fn concentric_disk_stays_inside() {
    for i in 0..100 {
        for j in 0..100 {
            let p = concentric_disk(Vec2::new(i as f32 / 99.0, j as f32 / 99.0));
            assert!(p.length() <= 1.0 + 1e-6);
        }
    }
    assert_eq!(concentric_disk(Vec2::splat(0.5)), Vec2::ZERO);
}

/// A path sampler reads the padded sets dimension by dimension, after the camera's two, and a
/// skipped request keeps the dimensions of what follows.
#[test]
fn the_path_sampler_counts_dimensions_in_request_order() {
    for method in [Method::Random, Method::Jittered, Method::Sobol] {
        let key = SampleKey::new(3, 5, 2, 16, 7);
        let mut sampler = PathSampler::new(&key, method);
        assert_eq!(sampler.get4(), key.padded4(method, 2, 0, 1));
        let light = sampler.get_set();
        for j in 0..4 {
            assert_eq!(light.point(j, 4), key.padded(method, 3, j, 4));
        }
        sampler.skip(2);
        assert_eq!(sampler.dimension(), 6);
        assert_eq!(sampler.get4(), key.padded4(method, 6, 0, 1));
        assert_ne!(key.padded4(method, 6, 0, 1), key.padded4(method, 2, 0, 1));
    }
}
