//! Sampler studies for `raytracer study`: each sampler's runs at a series of sample counts scored
//! against a reference, the convergence rates and equal-error times fitted to them, and the
//! `--skip-work` comparison.

use raytracer::film::Film;
use raytracer::integrator::{IntegratorKind, TraceOptions};
use raytracer::metric::{mean_flip, mse, Region};
use raytracer::render::{render, RenderError, RenderOptions, RenderOutput};
use raytracer::sampling::Method;
use raytracer::scene::Scene;

/// The samplers a study compares, in order.
pub const SAMPLERS: [Method; 3] = [Method::Random, Method::Jittered, Method::Sobol];

/// Fits use runs with at least this many samples: below it the stratified samplers have not
/// reached their asymptotic rate (one or two samples cannot be stratified).
pub const FIT_MIN_SAMPLES: u32 = 4;

/// One render of a study.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    pub sampler: Method,
    /// Shadow rays per area light per shading point (Whitted), or paths per pixel (path
    /// tracing).
    pub samples: u32,
    /// Median render time over the repetitions, seconds (BVH build excluded).
    pub seconds: f64,
    /// MSE of the whole image against the reference.
    pub mse: f64,
    /// MSE over the study's region (equal to `mse` without one).
    pub mse_region: f64,
    /// Mean FLIP of the whole image against the reference.
    pub flip: f64,
}

/// What a study renders.
#[derive(Debug, Clone)]
pub struct StudyOptions {
    pub samplers: Vec<Method>,
    /// Largest sample count (shadow rays per area light, or samples per pixel).
    pub max_samples: u32,
    /// What renders the scene, and so what is counted.
    pub integrator: IntegratorKind,
    /// Renders per run; the time is their median.
    pub runs: usize,
    /// Region for `mse_region`; the whole image without one.
    pub region: Option<Region>,
    pub seed: u64,
}

impl Default for StudyOptions {
    fn default() -> Self {
        StudyOptions {
            samplers: SAMPLERS.to_vec(),
            max_samples: 256,
            integrator: IntegratorKind::Whitted,
            runs: 1,
            region: None,
            seed: 0,
        }
    }
}

/// The sample counts a sampler is run at: powers of 4 for jittered (full square grids), powers of
/// 2 for the others, from 1 to `max`.
pub fn sample_counts(method: Method, max: u32) -> Vec<u32> {
    let step = if method == Method::Jittered { 4 } else { 2 };
    std::iter::successors(Some(1u32), |&n| n.checked_mul(step))
        .take_while(|&n| n <= max.max(1))
        .collect()
}

/// Renders `scene` with `samples` of `method`: for Whitted, one ray per pixel centre and every
/// area light sampled at `samples` shadow rays (point lights are unchanged); for path tracing,
/// `samples` paths per pixel.
pub fn render_with(
    scene: &Scene,
    integrator: IntegratorKind,
    method: Method,
    samples: u32,
    seed: u64,
) -> Result<RenderOutput, RenderError> {
    if integrator == IntegratorKind::Path {
        return render(
            scene,
            &RenderOptions {
                spp: samples,
                pixel_method: method,
                seed,
                integrator: Some(IntegratorKind::Path),
                ..RenderOptions::default()
            },
        );
    }
    render(
        scene,
        &RenderOptions {
            spp: 1,
            pixel_method: method,
            seed,
            trace: TraceOptions {
                light_method: Some(method),
                light_samples: Some(samples),
                ..TraceOptions::default()
            },
            ..RenderOptions::default()
        },
    )
}

/// The seed of references: one no run of a study uses.
pub(super) const REFERENCE_SEED: u64 = 0x5eed_f4ef;

/// The reference: for Whitted, jittered shadow rays on a `k×k` grid with `k² ≥ samples`; for path
/// tracing, `samples` Sobol paths per pixel; under a seed no run of a study uses.
pub fn reference(
    scene: &Scene,
    integrator: IntegratorKind,
    samples: u32,
) -> Result<Film, RenderError> {
    if integrator == IntegratorKind::Path {
        return Ok(render_with(scene, integrator, Method::Sobol, samples, REFERENCE_SEED)?.film);
    }
    let k = (samples.max(1) as f64).sqrt().ceil() as u32;
    Ok(render_with(scene, integrator, Method::Jittered, k * k, REFERENCE_SEED)?.film)
}

/// What a study of `integrator` counts, for labels.
pub fn counted(integrator: IntegratorKind) -> &'static str {
    match integrator {
        IntegratorKind::Whitted => "shadow rays per light",
        IntegratorKind::Path => "samples per pixel",
    }
}

/// The median of `v` (the mean of the middle two for an even length); 0 for none.
pub fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        0.5 * (v[m - 1] + v[m])
    }
}

/// `render` done `runs` times (at least once): the last output and the median render time in
/// seconds.
pub(super) fn timed(
    runs: usize,
    mut render: impl FnMut() -> Result<RenderOutput, RenderError>,
) -> Result<(RenderOutput, f64), RenderError> {
    let mut times = Vec::with_capacity(runs.max(1));
    let mut last = None;
    for _ in 0..runs.max(1) {
        let r = render()?;
        times.push(r.render_time.as_secs_f64());
        last = Some(r);
    }
    Ok((last.expect("at least one render"), median(&mut times)))
}

/// Runs the study against `reference`, calling `progress(done, total, run)` after each run.
///
/// A study renders the scene with each sampler at a series of sample counts, and records for
/// each run its median render time, its MSE (whole image and an optional region, e.g. a
/// penumbra) and its mean FLIP against the reference. What is counted depends on the integrator
/// ([`IntegratorKind`]):
/// - Whitted: shadow rays per area light. Every run traces one ray through each pixel centre, so
///   the only error left is that of the area-light estimate: the quantity the samplers differ in.
/// - Path tracing: samples per pixel, each a whole path, with every dimension of the path (pixel,
///   lens, bounces, light samples) placed by the sampler under study.
pub fn run_study(
    scene: &Scene,
    reference: &Film,
    options: &StudyOptions,
    mut progress: impl FnMut(usize, usize, &Run),
) -> Result<Vec<Run>, RenderError> {
    let plan: Vec<(Method, u32)> = options
        .samplers
        .iter()
        .flat_map(|&m| {
            sample_counts(m, options.max_samples)
                .into_iter()
                .map(move |n| (m, n))
        })
        .collect();
    let full = Region::full(reference.width, reference.height);
    let region = options.region.unwrap_or(full);
    let mut out = Vec::with_capacity(plan.len());
    for (i, &(sampler, samples)) in plan.iter().enumerate() {
        let (r, seconds) = timed(options.runs, || {
            render_with(scene, options.integrator, sampler, samples, options.seed)
        })?;
        let film = r.film;
        let run = Run {
            sampler,
            samples,
            seconds,
            mse: mse(reference, &film, full),
            mse_region: mse(reference, &film, region),
            flip: mean_flip(reference, &film, full),
        };
        progress(i + 1, plan.len(), &run);
        out.push(run);
    }
    Ok(out)
}

/// The runs of one sampler, in sample order.
pub fn runs_of(runs: &[Run], sampler: Method) -> Vec<&Run> {
    let mut v: Vec<&Run> = runs.iter().filter(|r| r.sampler == sampler).collect();
    v.sort_by_key(|r| r.samples);
    v
}

/// Least-squares slope of `log y` against `log x` over the points with positive coordinates;
/// `None` with fewer than two such points or all `x` equal.
pub fn loglog_slope(points: &[(f64, f64)]) -> Option<f64> {
    let p: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    if p.len() < 2 {
        return None;
    }
    let n = p.len() as f64;
    let mx = p.iter().map(|q| q.0).sum::<f64>() / n;
    let my = p.iter().map(|q| q.1).sum::<f64>() / n;
    let sxx: f64 = p.iter().map(|q| (q.0 - mx).powi(2)).sum();
    let sxy: f64 = p.iter().map(|q| (q.0 - mx) * (q.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// The fitted slope of the region MSE against samples for one sampler, over runs with at least
/// [`FIT_MIN_SAMPLES`] samples: the convergence rate, log MSE against log samples by least
/// squares. For a smooth integrand independent samples give MSE ∝ n⁻¹; jittered (stratified)
/// samples n⁻³ᐟ² for a discontinuous one in 2D such as a visibility edge (Mitchell,
/// "Consequences of Stratified Sampling in Graphics", SIGGRAPH 1996); scrambled nets reach the
/// same n⁻³ᐟ² on such edges (Owen, "Scrambled net variance for integrals of smooth functions",
/// Ann. Stat. 1997, and Mitchell's analysis).
pub fn mse_slope(runs: &[Run], sampler: Method) -> Option<f64> {
    let pts: Vec<(f64, f64)> = runs_of(runs, sampler)
        .iter()
        .filter(|r| r.samples >= FIT_MIN_SAMPLES)
        .map(|r| (r.samples as f64, r.mse_region))
        .collect();
    loglog_slope(&pts)
}

/// The region MSE `sampler` reaches at `samples` (interpolated in log-log between the runs around
/// it; `None` outside the runs).
#[cfg(test)]
pub fn mse_at(runs: &[Run], sampler: Method, samples: u32) -> Option<f64> {
    let v = runs_of(runs, sampler);
    let pts: Vec<(f64, f64)> = v.iter().map(|r| (r.samples as f64, r.mse_region)).collect();
    interpolate_loglog(&pts, samples as f64)
}

/// `y` at `x` on the polyline through `points` (sorted by `x`), interpolated linearly in
/// `(log x, log y)`.
fn interpolate_loglog(points: &[(f64, f64)], x: f64) -> Option<f64> {
    points.windows(2).find_map(|w| {
        let ((x0, y0), (x1, y1)) = (w[0], w[1]);
        if x < x0.min(x1) || x > x0.max(x1) || x0 <= 0.0 || x1 <= 0.0 || y0 <= 0.0 || y1 <= 0.0 {
            return None;
        }
        if x0 == x1 {
            return Some(y0);
        }
        let t = (x.ln() - x0.ln()) / (x1.ln() - x0.ln());
        Some((y0.ln() + t * (y1.ln() - y0.ln())).exp())
    })
}

/// Render time `sampler` needs to bring the region MSE down to `target`: the first crossing of
/// its MSE-against-time curve, interpolated in log-log. `None` if it never gets there; the first
/// run's time if that is already at or below the target (an upper bound).
pub fn time_to_reach(runs: &[Run], sampler: Method, target: f64) -> Option<f64> {
    cost_to_reach(runs, sampler, target, |r| r.seconds)
}

/// What [`time_to_reach`] finds for the render time, for any cost of a run (its time, its
/// samples).
pub fn cost_to_reach(
    runs: &[Run],
    sampler: Method,
    target: f64,
    cost: impl Fn(&Run) -> f64,
) -> Option<f64> {
    let v = runs_of(runs, sampler);
    let first = v.first()?;
    if first.mse_region <= target {
        return Some(cost(first));
    }
    v.windows(2).find_map(|w| {
        let (a, b) = (w[0], w[1]);
        if !(a.mse_region > target && b.mse_region <= target) {
            return None;
        }
        let pts = [(a.mse_region, cost(a)), (b.mse_region, cost(b))];
        interpolate_loglog(&pts, target).or(Some(cost(b)))
    })
}

/// The runs as CSV: `sampler,samples,seconds,mse,mse_region,flip`.
pub fn csv_text(runs: &[Run]) -> String {
    let mut s = String::from("sampler,samples,seconds,mse,mse_region,flip\n");
    for r in runs {
        s.push_str(&format!(
            "{},{},{:.6},{:.6e},{:.6e},{:.6}\n",
            r.sampler, r.samples, r.seconds, r.mse, r.mse_region, r.flip
        ));
    }
    s
}

/// One variant of a work-skipping comparison.
#[derive(Debug, Clone, PartialEq)]
pub struct SkipRun {
    pub name: &'static str,
    /// Median render time, seconds.
    pub seconds: f64,
    /// Rays traced (all kinds).
    pub rays: u64,
    /// Mean FLIP against the plain render.
    pub flip: f64,
    /// MSE against the plain render.
    pub mse: f64,
}

/// Renders `scene` with `base` plain, with adaptive area lights, with the POV-Ray cut-off at
/// `cutoff`, and with both; returns each one's median time over `runs` and its error against
/// the plain render.
pub fn skip_work(
    scene: &Scene,
    base: &RenderOptions,
    cutoff: f32,
    runs: usize,
) -> Result<Vec<SkipRun>, RenderError> {
    let variants: [(&'static str, bool, Option<f32>); 4] = [
        ("plain", false, None),
        ("adaptive-lights", true, None),
        ("adc-bailout", false, Some(cutoff)),
        ("both", true, Some(cutoff)),
    ];
    let mut plain: Option<Film> = None;
    let mut out = Vec::new();
    for (name, adaptive, cut) in variants {
        let options = RenderOptions {
            trace: TraceOptions {
                adaptive_lights: adaptive,
                cutoff: cut,
                ..base.trace
            },
            ..base.clone()
        };
        let (r, seconds) = timed(runs, || render(scene, &options))?;
        let reference = plain.get_or_insert_with(|| r.film.clone());
        let full = Region::full(r.film.width, r.film.height);
        out.push(SkipRun {
            name,
            seconds,
            rays: r.counts.total(),
            flip: mean_flip(reference, &r.film, full),
            mse: mse(reference, &r.film, full),
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::super::plot::{colour, plot_rgb};
    use super::*;
    use raytracer::scene::{load, LoadOptions};

    fn run(sampler: Method, samples: u32, seconds: f64, e: f64) -> Run {
        Run {
            sampler,
            samples,
            seconds,
            mse: e,
            mse_region: e,
            flip: 0.0,
        }
    }

    #[test]
    fn sample_series_are_powers() {
        assert_eq!(sample_counts(Method::Jittered, 256), [1, 4, 16, 64, 256]);
        assert_eq!(sample_counts(Method::Sobol, 16), [1, 2, 4, 8, 16]);
        assert_eq!(sample_counts(Method::Random, 20), [1, 2, 4, 8, 16]);
        assert_eq!(sample_counts(Method::Random, 0), [1]);
    }

    #[test]
    fn slopes_and_crossings_of_exact_power_laws() {
        // MSE = 0.1·n^-1.5, time = 0.01·n.
        let runs: Vec<Run> = [1u32, 4, 16, 64, 256]
            .iter()
            .map(|&n| {
                run(
                    Method::Jittered,
                    n,
                    0.01 * n as f64,
                    0.1 * (n as f64).powf(-1.5),
                )
            })
            .collect();
        assert!((mse_slope(&runs, Method::Jittered).unwrap() + 1.5).abs() < 1e-9);
        // The MSE at 32 samples lies between the runs at 16 and 64.
        let at32 = mse_at(&runs, Method::Jittered, 32).unwrap();
        assert!((at32 / (0.1 * 32f64.powf(-1.5)) - 1.0).abs() < 1e-9);
        // The time to reach the MSE of n = 32 is that of 32 samples.
        let t = time_to_reach(&runs, Method::Jittered, at32).unwrap();
        assert!((t - 0.32).abs() < 1e-9, "{t}");
        assert_eq!(time_to_reach(&runs, Method::Jittered, 1e-12), None);
        assert_eq!(time_to_reach(&runs, Method::Jittered, 1.0), Some(0.01));
        assert_eq!(time_to_reach(&runs, Method::Sobol, 1.0), None);
        assert_eq!(loglog_slope(&[(1.0, 1.0)]), None);
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 2.0, 3.0]), 2.5);
    }

    #[test]
    fn the_plot_draws_text_and_lines() {
        let runs: Vec<Run> = SAMPLERS
            .iter()
            .flat_map(|&m| {
                [1u32, 4, 16]
                    .map(|n| run(m, n, 0.001 * n as f64, 0.01 / n as f64))
                    .to_vec()
            })
            .collect();
        let buf = plot_rgb(&runs, "test", "shadow rays per light", 600, 300).unwrap();
        // Something other than white was drawn, including each sampler's colour.
        let has = |c: plotters::style::RGBColor| buf.chunks_exact(3).any(|p| p == [c.0, c.1, c.2]);
        for m in SAMPLERS {
            assert!(has(colour(m)), "{m}");
        }
    }

    /// A study of a path-traced scene counts samples per pixel, and every sampler's error falls as
    /// they grow: each run's paths come from the sampler under study.
    #[test]
    fn a_path_traced_study_counts_pixel_samples_and_converges() {
        let options = LoadOptions {
            width: Some(24),
            ..Default::default()
        };
        let scene = load(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cornell.json"),
            &options,
        )
        .unwrap();
        let integrator = IntegratorKind::of_scene(&scene);
        assert_eq!(integrator, IntegratorKind::Path);
        let reference = reference(&scene, integrator, 1024).unwrap();
        let study = StudyOptions {
            max_samples: 64,
            integrator,
            ..Default::default()
        };
        let runs = run_study(&scene, &reference, &study, |_, _, _| {}).unwrap();
        for m in [Method::Random, Method::Jittered, Method::Sobol] {
            let at = |n| mse_at(&runs, m, n).unwrap();
            assert!(at(64) < 0.3 * at(4), "{m}: {} vs {}", at(64), at(4));
        }
        assert_eq!(counted(integrator), "samples per pixel");
    }
}
