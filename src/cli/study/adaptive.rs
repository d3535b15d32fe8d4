//! Adaptive against uniform sampling at equal error, for `raytracer study --adaptive`: the runs,
//! the best allocation of samples that the pixels' measured noise allows, and their CSV and plot.

use super::plot::{bounds, draw_axes, draw_legend, encode_png, register_font};
use super::runs::{cost_to_reach, loglog_slope, runs_of, timed, Run, REFERENCE_SEED};
use raytracer::film::Film;
use raytracer::integrator::IntegratorKind;
use raytracer::metric::{mean_flip, mse, Region};
use raytracer::render::adaptive::{brightness_scale, samples_with_known_errors, Adaptive};
use raytracer::render::{render, RenderError, RenderOptions, RenderOutput};
use raytracer::sampling::Method;
use raytracer::scene::Scene;

/// What an adaptive study renders.
#[derive(Debug, Clone)]
pub struct AdaptiveStudyOptions {
    /// The most samples a pixel takes: the adaptive cap and the largest uniform run.
    pub max_samples: u32,
    pub thresholds: Vec<f32>,
    pub integrator: IntegratorKind,
    /// Renders per run; the time is their median.
    pub runs: usize,
    /// Region the error is measured over; the whole image without one.
    pub region: Option<Region>,
    pub seed: u64,
    /// Pixel samples in each of the [`VARIANCE_RENDERS`] renders that measure each pixel's noise
    /// for the best allocation: rare bright paths, a path-traced scene's caustics, show only in
    /// renders long enough to meet them (docs/adaptive.md, "Path tracing at tight thresholds").
    pub variance_samples: u32,
}

/// One adaptive render of a study.
#[derive(Debug, Clone, PartialEq)]
pub struct AdaptiveRun {
    pub threshold: f32,
    /// Samples per pixel, on average over the image.
    pub mean_samples: f64,
    /// Median render time, seconds (BVH build excluded).
    pub seconds: f64,
    pub mse: f64,
    pub mse_region: f64,
    pub flip: f64,
    /// The time uniform sampling needs for `mse_region`; `None` outside the uniform runs' range.
    pub uniform_seconds: Option<f64>,
    /// The samples per pixel uniform sampling needs for `mse_region`, likewise.
    pub uniform_samples: Option<f64>,
    /// [`PixelNoise::known_noise_share`] at this threshold: the samples ratio the same rule
    /// would reach with an exact error estimate, at the uniform runs' convergence.
    pub known_noise_ratio: Option<f64>,
}

impl AdaptiveRun {
    /// Adaptive time over uniform time at the same error.
    pub fn ratio(&self) -> Option<f64> {
        self.uniform_seconds.map(|u| self.seconds / u)
    }

    /// Adaptive samples over uniform samples at the same error: the ratio without the clock, the
    /// same on every machine and run, and in the units of [`PixelNoise::allocation_bound`]. It leaves out
    /// that the pixels adaptive sampling spends its samples on may cost more a sample than the
    /// image's average, and the rounds' own cost.
    pub fn samples_ratio(&self) -> Option<f64> {
        self.uniform_samples.map(|u| self.mean_samples / u)
    }
}

/// The runs of an adaptive study.
#[derive(Debug, Clone, PartialEq)]
pub struct AdaptiveStudy {
    /// Uniform runs (sampler Sobol), in sample order.
    pub uniform: Vec<Run>,
    pub adaptive: Vec<AdaptiveRun>,
    /// [`PixelNoise::allocation_bound`] of the scene over the study's region at one-over-n
    /// convergence: no allocation of samples by the pixels' noise does better where each
    /// pixel's error falls as one over its samples.
    pub bound: Option<f64>,
    /// The exponent `a` of the uniform runs' convergence, MSE ∝ n^−a, fitted from
    /// [`FIT_FROM_SAMPLES`] samples up, and [`PixelNoise::allocation_bound`] at it: the bound where every
    /// pixel converges as the image does.
    pub bound_at_rate: Option<(f64, f64)>,
    /// Pixel samples in each of the [`VARIANCE_RENDERS`] renders the bound was measured from.
    pub variance_samples: u32,
    /// Where the best allocation puts its samples, at the uniform runs' convergence (or at
    /// one-over-n without a fitted rate): [`allocation_map`] of the study's region.
    pub allocation_map: Option<Film>,
}

/// Renders, under seeds of their own, of [`AdaptiveStudyOptions::variance_samples`] uniform
/// Sobol pixel samples each: the spread of their pixels gives each pixel's variance for
/// [`PixelNoise::allocation_bound`].
pub const VARIANCE_RENDERS: u64 = 8;
/// The fewest samples of the uniform runs the convergence rate is fitted to: fewer are
/// dominated by aliasing more than by noise.
pub const FIT_FROM_SAMPLES: u32 = 16;
/// The first of the variance renders' seeds (the runs use `--seed`, the reference its own).
const VARIANCE_SEED: u64 = 0x0a11_0ca7_e000;

/// Each pixel's variance over independent renders alike but for their seeds: the noise
/// [`PixelNoise::allocation_bound`] allocates samples to.
#[derive(Debug, Clone, PartialEq)]
pub struct PixelNoise {
    /// σᵢ² of each pixel of the region, row-major, per channel (their sum is the pixel's σᵢ²).
    variances: Vec<[f64; 3]>,
    /// The renders they were measured from.
    renders: usize,
}

impl PixelNoise {
    /// The variances of the pixels of `region` over `films`; `None` for fewer than two films.
    pub fn measure(films: &[Film], region: Region) -> Option<PixelNoise> {
        let k = films.len();
        if k < 2 {
            return None;
        }
        let mut variances = Vec::with_capacity(region.width as usize * region.height as usize);
        for y in region.y..region.y + region.height {
            for x in region.x..region.x + region.width {
                let var = [0, 1, 2].map(|c| {
                    let value = |f: &Film| f64::from(f.get(x, y)[c]);
                    let mean = films.iter().map(value).sum::<f64>() / k as f64;
                    let squares = films.iter().map(|f| (value(f) - mean).powi(2));
                    squares.sum::<f64>() / (k - 1) as f64
                });
                variances.push(var);
            }
        }
        Some(PixelNoise {
            variances,
            renders: k,
        })
    }

    /// The least share of uniform sampling's samples with which any allocation of samples to
    /// the pixels reaches uniform sampling's expected MSE over them, when each pixel's error
    /// variance falls as σᵢ²·(m/nᵢ)^a, σᵢ² its variance at the m samples it was measured at
    /// (a = 1: independent samples; stratified ones converge faster, a > 1). An adaptive render
    /// can go below it where rare bright paths carry the variance: it stops a pixel that has
    /// not met one yet, leaving it a bias smaller than the variance it skips.
    ///
    /// Minimising Σnᵢ under a fixed Σσᵢ²·nᵢ^−a (a Lagrange multiplier) gives nᵢ ∝ σᵢ^(2p) with
    /// p = 1/(a + 1), and the share `(S^(a+1) / (N^a · Σσᵢ²))^(1/a)` with S = Σσᵢ^(2p) over the
    /// N pixels. For a = 1 that is (Σσᵢ)² / (N·Σσᵢ²) (nᵢ ∝ σᵢ; Cauchy–Schwarz): 1 when every
    /// pixel is as noisy as the others, small when the noise sits in few pixels. The faster
    /// pixels converge, the less moving samples between them buys, and the share tends to 1 as
    /// a grows.
    ///
    /// The power σ̂^(2p) estimated from k renders is low on average by the factor E[(χ²_ν/ν)^p],
    /// ν = k − 1 (for p = ½ that is c₄(k) of Gurland & Tripathi 1971, 0.965 at k = 8), which the
    /// share corrects for; fewer degrees of freedom than RGB's could give make that correction
    /// the cautious one. Past the model: a real adaptive render also pays for its floor of
    /// samples, its rounds and its estimate, and pixels converge at rates of their own (an edge
    /// slower than a smooth gradient). `None` for a noiseless region or `a` ≤ 0.
    pub fn allocation_bound(&self, a: f64) -> Option<f64> {
        let (p, powers) = self.allocation_powers(a)?;
        let sum_var = self.total();
        if sum_var.is_nan() || sum_var <= 0.0 {
            return None;
        }
        let sum_power = powers.sum::<f64>() / chi_moment((self.renders - 1) as f64, p);
        let n = self.variances.len() as f64;
        let share = (sum_power.ln() * (a + 1.0) - n.ln() * a - sum_var.ln()) / a;
        Some(share.exp().min(1.0))
    }

    /// Each pixel's samples under the allocation [`PixelNoise::allocation_bound`] finds at
    /// convergence rate `a`, nᵢ ∝ σᵢ^(2/(a + 1)), over their mean: 1 in every pixel where all
    /// are equally noisy, more where the noise is. `None` where the bound is.
    pub fn allocation(&self, a: f64) -> Option<Vec<f64>> {
        let n: Vec<f64> = self.allocation_powers(a)?.1.collect();
        let mean = n.iter().sum::<f64>() / n.len() as f64;
        (mean > 0.0 && mean.is_finite()).then(|| n.iter().map(|x| x / mean).collect())
    }

    /// The exponent p = 1/(a + 1) of the best allocation at convergence rate `a`, nᵢ ∝ (σᵢ²)^p,
    /// and each pixel's (σᵢ²)^p (its variance summed over RGB); `None` for `a` ≤ 0 or NaN.
    fn allocation_powers(&self, a: f64) -> Option<(f64, impl Iterator<Item = f64> + '_)> {
        if a.is_nan() || a <= 0.0 {
            return None;
        }
        let p = 1.0 / (a + 1.0);
        Some((
            p,
            self.variances
                .iter()
                .map(move |v| v.iter().sum::<f64>().powf(p)),
        ))
    }

    /// Σσᵢ² over the pixels.
    fn total(&self) -> f64 {
        self.variances.iter().flatten().sum()
    }

    /// The share of uniform sampling's samples an adaptive render at `threshold` (at most `spp` a
    /// pixel) would take for uniform sampling's MSE if its error estimate were exact: the
    /// stopping rule itself ([`samples_with_known_errors`]), with pixel i's error after n samples
    /// modelled from its measured noise, channel by channel, as √(σ²·(m/n)^a) (m the samples of
    /// the renders the variances were measured from), over 10⁻⁴ + √(RGB sum) of its value in
    /// `reference` (of `region`'s size and place), as the estimate scales it. Each σ̂ is divided
    /// by its bias, c₄ of the renders. Both MSEs come from the same model, Σσᵢ²·(m/nᵢ)^a, so the
    /// share is at least [`PixelNoise::allocation_bound`] at `a`: what separates the two is the
    /// rule (its rounds, neighbourhood and relative threshold), and what separates this from a
    /// real render's samples ratio is the estimate. `None` where the bound is.
    pub fn known_noise_share(
        &self,
        reference: &Film,
        region: Region,
        measured: u32,
        a: f64,
        (spp, threshold): (u32, f32),
    ) -> Option<f64> {
        let total = self.total();
        if a.is_nan() || a <= 0.0 || total.is_nan() || total <= 0.0 {
            return None;
        }
        let width = region.width as usize;
        let bias = chi_moment((self.renders - 1) as f64, 0.5);
        let brightness: Vec<f64> = (0..self.variances.len())
            .map(|i| {
                let (x, y) = (region.x + (i % width) as u32, region.y + (i / width) as u32);
                f64::from(brightness_scale(reference.get(x, y)))
            })
            .collect();
        let m = f64::from(measured);
        let at = |n: u32| (m / f64::from(n)).powf(a);
        let samples =
            samples_with_known_errors((width, region.height as usize), spp, threshold, |i, n| {
                let spread: f64 = self.variances[i].iter().map(|v| (v * at(n)).sqrt()).sum();
                (spread / bias / brightness[i]) as f32
            });
        let mse: f64 = (self.variances.iter().zip(&samples))
            .map(|(v, &n)| v.iter().sum::<f64>() * at(n))
            .sum();
        // Uniform sampling reaches that MSE at N samples: total·(m/N)^a = mse.
        let uniform = m * (total / mse).powf(1.0 / a);
        let mean = samples.iter().map(|&n| f64::from(n)).sum::<f64>() / samples.len() as f64;
        Some(mean / uniform)
    }
}

/// E[(X/ν)^p] for X ~ χ²_ν: (2/ν)^p · Γ(ν/2 + p) / Γ(ν/2). For p = ½ and ν = k − 1 this is
/// c₄(k), the mean of the sample standard deviation of k normal values over the true one.
fn chi_moment(nu: f64, p: f64) -> f64 {
    (p * (2.0 / nu).ln() + ln_gamma(nu / 2.0 + p) - ln_gamma(nu / 2.0)).exp()
}

/// ln Γ(x) for x > 0: Stirling's series to its x⁻⁷ term after shifting x past 12 with
/// Γ(x + 1) = x·Γ(x), where the first omitted term, 1/(1188x⁹), is below 2·10⁻¹³ (Abramowitz &
/// Stegun 6.1.40).
fn ln_gamma(mut x: f64) -> f64 {
    let mut shift = 0.0;
    while x < 12.0 {
        shift += x.ln();
        x += 1.0;
    }
    let (inv, inv2) = (1.0 / x, 1.0 / (x * x));
    let series = inv * (1.0 / 12.0 - inv2 * (1.0 / 360.0 - inv2 * (1.0 / 1260.0 - inv2 / 1680.0)));
    (x - 0.5) * x.ln() - x + 0.5 * (2.0 * std::f64::consts::PI).ln() + series - shift
}

/// The exponent `a` of MSE ∝ n^−a over the uniform runs of [`FIT_FROM_SAMPLES`] samples or more;
/// `None` with fewer than two of them.
fn convergence_exponent(uniform: &[Run]) -> Option<f64> {
    let points: Vec<(f64, f64)> = runs_of(uniform, Method::Sobol)
        .into_iter()
        .filter(|r| r.samples >= FIT_FROM_SAMPLES)
        .map(|r| (f64::from(r.samples), r.mse_region))
        .collect();
    if points.len() < 2 {
        return None;
    }
    loglog_slope(&points).map(|slope| -slope)
}

/// A render of `scene` by `integrator` at `spp` Sobol pixel samples, adaptive with `threshold`
/// if one is given.
fn render_pixels(
    scene: &Scene,
    integrator: IntegratorKind,
    spp: u32,
    threshold: Option<f32>,
    seed: u64,
) -> Result<RenderOutput, RenderError> {
    render(
        scene,
        &RenderOptions {
            spp,
            pixel_method: Method::Sobol,
            seed,
            integrator: Some(integrator),
            adaptive: threshold.map(|threshold| Adaptive {
                threshold,
                time_limit: None,
            }),
            ..RenderOptions::default()
        },
    )
}

/// The reference of an adaptive study: `spp` uniform Sobol pixel samples, under a seed no run
/// uses.
pub fn reference(scene: &Scene, integrator: IntegratorKind, spp: u32) -> Result<Film, RenderError> {
    Ok(render_pixels(scene, integrator, spp, None, REFERENCE_SEED)?.film)
}

/// Runs the study against `reference`, calling `progress(done, total, line)` after each run.
///
/// Uniform runs at 1, 2, 4, … samples per pixel up to the cap give render time as a function of
/// the error (MSE over the study's region); adaptive runs (`--adaptive`, at most the cap, one per
/// noise threshold) are each scored by their error, and their time is divided by the time uniform
/// sampling needs for that error, interpolated in log-log between the uniform runs around it: the
/// equal-error time ratio (below 1, adaptive sampling wins). Both place pixel samples with
/// Owen-scrambled Sobol points, what `--adaptive` uses by default, so the ratio measures the
/// adaptivity alone; every other sample of the scene (area lights, the lens, a path's bounces) is
/// the render's own.
pub fn run_adaptive_study(
    scene: &Scene,
    reference: &Film,
    options: &AdaptiveStudyOptions,
    mut progress: impl FnMut(usize, usize, String),
) -> Result<AdaptiveStudy, RenderError> {
    let runner = Runner::new(scene, reference, options);
    let counts = super::runs::sample_counts(Method::Sobol, options.max_samples);
    let total = counts.len() + 1 + options.thresholds.len();
    let mut uniform = Vec::with_capacity(counts.len());
    for (i, &spp) in counts.iter().enumerate() {
        let run = runner.uniform_run(spp)?;
        progress(
            i + 1,
            total,
            format!(
                "uniform  {spp:>5} spp        {:.4} s  MSE {:.3e}",
                run.seconds, run.mse_region
            ),
        );
        uniform.push(run);
    }
    let variance_samples = options.variance_samples;
    let noise = runner.pixel_noise()?;
    let bound = noise.as_ref().and_then(|n| n.allocation_bound(1.0));
    let rate = convergence_exponent(&uniform);
    let bound_at_rate = rate.and_then(|a| Some((a, noise.as_ref()?.allocation_bound(a)?)));
    progress(
        counts.len() + 1,
        total,
        format!(
            "best allocation: {} of uniform's samples, {} at the uniform runs' convergence \
             ({VARIANCE_RENDERS} renders of {variance_samples} spp)",
            ratio_text(bound),
            ratio_text(bound_at_rate.map(|b| b.1))
        ),
    );
    let mut adaptive = Vec::with_capacity(options.thresholds.len());
    for (i, &threshold) in options.thresholds.iter().enumerate() {
        let run = runner.adaptive_run(threshold, &uniform, noise.as_ref(), rate)?;
        progress(
            counts.len() + 1 + i + 1,
            total,
            format!(
                "adaptive T = {threshold} ({:.1} spp)  {:.4} s  MSE {:.3e}  ratio {}, samples {} (known noise {})",
                run.mean_samples,
                run.seconds,
                run.mse_region,
                ratio_text(run.ratio()),
                ratio_text(run.samples_ratio()),
                ratio_text(run.known_noise_ratio)
            ),
        );
        adaptive.push(run);
    }
    let allocation_map = noise
        .as_ref()
        .and_then(|n| n.allocation(rate.unwrap_or(1.0)))
        .map(|shares| allocation_map(&shares, runner.region.width));
    Ok(AdaptiveStudy {
        uniform,
        adaptive,
        bound,
        bound_at_rate,
        variance_samples,
        allocation_map,
    })
}

/// Renders an adaptive study's runs and scores them against its reference.
struct Runner<'a> {
    scene: &'a Scene,
    reference: &'a Film,
    options: &'a AdaptiveStudyOptions,
    /// The whole image.
    full: Region,
    /// The region the study's error is measured over.
    region: Region,
}

impl<'a> Runner<'a> {
    /// The runs of a study of `scene` against `reference`.
    fn new(scene: &'a Scene, reference: &'a Film, options: &'a AdaptiveStudyOptions) -> Runner<'a> {
        let full = Region::full(reference.width, reference.height);
        Runner {
            scene,
            reference,
            options,
            full,
            region: options.region.unwrap_or(full),
        }
    }

    /// `options.runs` renders at `spp` pixel samples, adaptive with `threshold` if one is given:
    /// the last and the median time.
    fn timed(&self, threshold: Option<f32>, spp: u32) -> Result<(RenderOutput, f64), RenderError> {
        let options = self.options;
        timed(options.runs, || {
            render_pixels(self.scene, options.integrator, spp, threshold, options.seed)
        })
    }

    /// The uniform run at `spp` pixel samples.
    fn uniform_run(&self, spp: u32) -> Result<Run, RenderError> {
        let (r, seconds) = self.timed(None, spp)?;
        Ok(Run {
            sampler: Method::Sobol,
            samples: spp,
            seconds,
            mse: mse(self.reference, &r.film, self.full),
            mse_region: mse(self.reference, &r.film, self.region),
            flip: mean_flip(self.reference, &r.film, self.full),
        })
    }

    /// Each pixel's noise over the region, from [`VARIANCE_RENDERS`] uniform renders of
    /// [`AdaptiveStudyOptions::variance_samples`] under seeds of their own.
    fn pixel_noise(&self) -> Result<Option<PixelNoise>, RenderError> {
        let options = self.options;
        let films = (0..VARIANCE_RENDERS)
            .map(|k| {
                let seed = VARIANCE_SEED + k;
                let spp = options.variance_samples;
                Ok(render_pixels(self.scene, options.integrator, spp, None, seed)?.film)
            })
            .collect::<Result<Vec<Film>, RenderError>>()?;
        Ok(PixelNoise::measure(&films, self.region))
    }

    /// The adaptive run at `threshold`, compared with the `uniform` runs at its error and, at
    /// the convergence `rate`, with the rule's samples under the measured `noise`.
    fn adaptive_run(
        &self,
        threshold: f32,
        uniform: &[Run],
        noise: Option<&PixelNoise>,
        rate: Option<f64>,
    ) -> Result<AdaptiveRun, RenderError> {
        let options = self.options;
        let (r, seconds) = self.timed(Some(threshold), options.max_samples)?;
        let samples = r.sample_counts.as_deref().unwrap_or(&[]);
        let mean_samples = if samples.is_empty() {
            options.max_samples as f64
        } else {
            samples.iter().map(|&k| k as f64).sum::<f64>() / samples.len() as f64
        };
        let mse_region = mse(self.reference, &r.film, self.region);
        Ok(AdaptiveRun {
            threshold,
            mean_samples,
            seconds,
            mse: mse(self.reference, &r.film, self.full),
            mse_region,
            flip: mean_flip(self.reference, &r.film, self.full),
            uniform_seconds: uniform_at(uniform, mse_region, |r| r.seconds),
            uniform_samples: uniform_at(uniform, mse_region, |r| f64::from(r.samples)),
            known_noise_ratio: rate.and_then(|a| {
                let plan = (options.max_samples, threshold);
                let measured = options.variance_samples;
                noise?.known_noise_share(self.reference, self.region, measured, a, plan)
            }),
        })
    }
}

/// The share of the pixels that [`allocation_map`] shows below full scale: the rest, a few
/// pixels of outlying noise, would otherwise set the scale and leave every other pixel dark.
const MAP_QUANTILE: f64 = 0.995;

/// A picture of `allocation` (row-major, `width` wide, as [`PixelNoise::allocation`] gives
/// it): each pixel's samples over those at the 99.5th percentile of the pixels, clamped to 1, in
/// the colours of `--sample-map` (dark: few samples, yellow: the most).
pub fn allocation_map(allocation: &[f64], width: u32) -> Film {
    let mut sorted = allocation.to_vec();
    sorted.sort_by(f64::total_cmp);
    let at = ((sorted.len() as f64 * MAP_QUANTILE) as usize).min(sorted.len().saturating_sub(1));
    let scale = sorted.get(at).copied().filter(|s| *s > 0.0).unwrap_or(1.0);
    let shares: Vec<f32> = allocation
        .iter()
        .map(|x| (x / scale).min(1.0) as f32)
        .collect();
    let height = (allocation.len() as u32).checked_div(width).unwrap_or(0);
    raytracer::metric::heat_map(width, height, &shares)
}

/// A ratio as the study prints it, two decimals and `×`, or `-` where there is none.
pub fn ratio_text(ratio: Option<f64>) -> String {
    ratio.map_or("-".into(), |x| format!("{x:.2}×"))
}

/// What uniform sampling spends (`cost`: its time, its samples) to reach `target`:
/// [`cost_to_reach`] within the uniform runs' range of errors, `None` outside it (no
/// extrapolation, not even to the first run's cost).
fn uniform_at(uniform: &[Run], target: f64, cost: impl Fn(&Run) -> f64) -> Option<f64> {
    let worst = runs_of(uniform, Method::Sobol).first()?.mse_region;
    if target > worst {
        return None;
    }
    cost_to_reach(uniform, Method::Sobol, target, cost)
}

/// The study as CSV: `render,threshold,samples,mean_samples,seconds,mse,mse_region,flip,
/// uniform_seconds,ratio,uniform_samples,samples_ratio,known_noise_ratio`, uniform rows first
/// (their threshold and last five columns empty), then the adaptive rows, then a `best_allocation` row whose
/// `samples_ratio` (and, as before, `ratio`) is [`PixelNoise::allocation_bound`] at one-over-n convergence,
/// and a `best_allocation_at_rate` row with the bound at the uniform runs' convergence.
pub fn csv_text(study: &AdaptiveStudy) -> String {
    let mut s = String::from(
        "render,threshold,samples,mean_samples,seconds,mse,mse_region,flip,uniform_seconds,ratio,\
         uniform_samples,samples_ratio,known_noise_ratio\n",
    );
    for r in &study.uniform {
        s.push_str(&format!(
            "uniform,,{},{},{:.6},{:.6e},{:.6e},{:.6},,,,,\n",
            r.samples, r.samples, r.seconds, r.mse, r.mse_region, r.flip
        ));
    }
    let cap = study.uniform.last().map_or(0, |r| r.samples);
    for r in &study.adaptive {
        let opt = |v: Option<f64>| v.map_or(String::new(), |x| format!("{x:.6}"));
        s.push_str(&format!(
            "adaptive,{},{cap},{:.3},{:.6},{:.6e},{:.6e},{:.6},{},{},{},{},{}\n",
            r.threshold,
            r.mean_samples,
            r.seconds,
            r.mse,
            r.mse_region,
            r.flip,
            opt(r.uniform_seconds),
            opt(r.ratio()),
            opt(r.uniform_samples),
            opt(r.samples_ratio()),
            opt(r.known_noise_ratio)
        ));
    }
    if let Some(b) = study.bound {
        s.push_str(&format!("best_allocation,,,,,,,,,{b:.6},,{b:.6},\n"));
    }
    if let Some((_, b)) = study.bound_at_rate {
        s.push_str(&format!(
            "best_allocation_at_rate,,,,,,,,,{b:.6},,{b:.6},\n"
        ));
    }
    s
}

/// The log-log plot of the error against render time: the uniform runs as a line, each adaptive
/// run as a labelled point, as PNG bytes.
pub fn plot_png(study: &AdaptiveStudy, title: &str) -> Result<Vec<u8>, String> {
    use plotters::prelude::*;
    let (w, h) = (900u32, 560u32);
    register_font();
    let mut buf = vec![255u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let positive = |v: f64| v.is_finite() && v > 0.0;
        let points = |it: &mut dyn Iterator<Item = (f64, f64)>| -> Vec<(f64, f64)> {
            it.filter(|&(x, y)| positive(x) && positive(y)).collect()
        };
        let uni = points(&mut study.uniform.iter().map(|r| (r.seconds, r.mse_region)));
        let ada = points(&mut study.adaptive.iter().map(|r| (r.seconds, r.mse_region)));
        let all: Vec<(f64, f64)> = uni.iter().chain(&ada).copied().collect();
        let (xmin, xmax) = bounds(&all.iter().map(|p| p.0).collect::<Vec<_>>());
        let (ymin, ymax) = bounds(&all.iter().map(|p| p.1).collect::<Vec<_>>());
        let mut chart = ChartBuilder::on(&root)
            .margin(14)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .caption(title, ("sans-serif", 17))
            .build_cartesian_2d((xmin..xmax).log_scale(), (ymin..ymax).log_scale())
            .map_err(|e| e.to_string())?;
        draw_axes(&mut chart, "render seconds")?;
        let blue = RGBColor(31, 119, 180);
        let orange = RGBColor(255, 127, 14);
        chart
            .draw_series(LineSeries::new(uni.clone(), blue.stroke_width(2)))
            .map_err(|e| e.to_string())?
            .label("uniform (1, 2, 4, … spp)")
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], blue.stroke_width(2))
            });
        chart
            .draw_series(uni.iter().map(|&p| Circle::new(p, 3, blue.filled())))
            .map_err(|e| e.to_string())?;
        // Each adaptive run is a point marked with its threshold, and a legend line with its
        // equal-error time ratio.
        for r in study
            .adaptive
            .iter()
            .filter(|r| positive(r.seconds) && positive(r.mse_region))
        {
            let p = (r.seconds, r.mse_region);
            let legend = match r.ratio() {
                Some(q) => format!("adaptive T = {}: {q:.2}× uniform's time", r.threshold),
                None => format!("adaptive T = {}: past the uniform runs", r.threshold),
            };
            chart
                .draw_series(std::iter::once(
                    EmptyElement::at(p)
                        + Circle::new((0, 0), 5, orange.filled())
                        + Text::new(format!("T={}", r.threshold), (7, -16), ("sans-serif", 12)),
                ))
                .map_err(|e| e.to_string())?
                .label(legend)
                .legend(move |(x, y)| Circle::new((x + 10, y), 5, orange.filled()));
        }
        draw_legend(&mut chart)?;
        root.present().map_err(|e| e.to_string())?;
    }
    encode_png(&buf, w, h)
}

#[cfg(test)]
mod tests {
    use super::*;
    use raytracer::math::Vec3;

    fn uniform(points: &[(u32, f64, f64)]) -> Vec<Run> {
        points
            .iter()
            .map(|&(samples, seconds, e)| Run {
                sampler: Method::Sobol,
                samples,
                seconds,
                mse: e,
                mse_region: e,
                flip: 0.0,
            })
            .collect()
    }

    /// The χ² moments against known values: c₄ tabulated (k = 2: √(2/π); k = 8: 0.9650), the
    /// mean of χ²_ν/ν (1) and ln Γ at ½ and at integers.
    #[test]
    fn chi_moments_match_their_tables() {
        let c4 = |k: usize| chi_moment((k - 1) as f64, 0.5);
        assert!((c4(2) - (2.0 / std::f64::consts::PI).sqrt()).abs() < 1e-12);
        assert!((c4(3) - 0.886_226_925).abs() < 1e-9);
        assert!((c4(8) - 0.965_030).abs() < 1e-6);
        assert!((chi_moment(7.0, 1.0) - 1.0).abs() < 1e-12);
        assert!((ln_gamma(0.5) - std::f64::consts::PI.sqrt().ln()).abs() < 1e-12);
        assert!((ln_gamma(5.0) - 24f64.ln()).abs() < 1e-12);
        assert!((ln_gamma(12.0) - 39_916_800f64.ln()).abs() < 1e-11);
    }

    /// Eight 4×4 films whose pixel p is 1 ± `amplitude(p)`, the sign alternating from film to
    /// film: each pixel's variance is amplitude²·8/7.
    fn films(amplitude: &dyn Fn(u32) -> f32) -> Vec<Film> {
        (0..8)
            .map(|i| {
                let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
                let pixels = (0..16)
                    .map(|p| Vec3::splat(1.0 + sign * amplitude(p)))
                    .collect();
                Film::from_pixels(4, 4, pixels)
            })
            .collect()
    }

    /// The allocation itself: alike everywhere for equal noise; where half the pixels are twice
    /// as noisy (σ), at one-over-n they take twice the samples of the others (nᵢ ∝ σᵢ), and
    /// at a = 3 √2 times (nᵢ ∝ σᵢ^½); no allocation for no noise. Its map scales to the pixel
    /// at the 99.5th percentile, so one outlying pixel does not darken the rest.
    #[test]
    fn the_allocation_follows_the_noise_and_its_map_ignores_an_outlier() {
        let full = Region::full(4, 4);
        let allocation = |amplitude: &dyn Fn(u32) -> f32, a: f64| {
            PixelNoise::measure(&films(amplitude), full).and_then(|n| n.allocation(a))
        };
        let even = allocation(&|_| 0.1, 1.0).unwrap();
        assert!(even.iter().all(|&x| (x - 1.0).abs() < 1e-9), "{even:?}");
        for (a, ratio) in [(1.0, 2.0), (3.0, 2f64.sqrt())] {
            let half = allocation(&|p| if p < 8 { 0.2 } else { 0.1 }, a).unwrap();
            let mean = half.iter().sum::<f64>() / 16.0;
            assert!((mean - 1.0).abs() < 1e-9, "{half:?}");
            assert!(
                (half[0] / half[15] - ratio).abs() < 1e-6,
                "a = {a}: {half:?}"
            );
        }
        assert_eq!(allocation(&|_| 0.0, 1.0), None);
        assert_eq!(allocation(&|_| 0.1, 0.0), None);

        // 400 pixels: a ramp of allocations, and one pixel a hundred times the largest.
        let mut shares: Vec<f64> = (0..400).map(|i| 1.0 + f64::from(i) / 100.0).collect();
        shares[7] = 500.0;
        let map = allocation_map(&shares, 20);
        assert_eq!((map.width, map.height), (20, 20));
        let brightness = |i: u32| map.get(i % 20, i / 20).element_sum();
        assert!(brightness(398) > brightness(200), "the ramp shows");
        assert!(brightness(200) > brightness(0));
        assert_eq!(brightness(7), brightness(399), "the outlier at full scale");
    }

    /// The allocation bound of films whose noise is known: equal noise everywhere gives 1, noise
    /// in a quarter of the pixels (none elsewhere) gives ¼ at any rate of convergence (every
    /// sample goes there), and unequal noise everywhere gains less the faster pixels converge.
    #[test]
    fn allocation_bound_follows_where_the_noise_is() {
        let full = Region::full(4, 4);
        let allocation_bound = |films: &[Film], a: f64| {
            PixelNoise::measure(films, full).and_then(|n| n.allocation_bound(a))
        };
        for a in [1.0, 1.5, 2.0] {
            let p = 1.0 / (a + 1.0);
            let correction = chi_moment(7.0, p).powf((a + 1.0) / a);
            let even = allocation_bound(&films(&|_| 0.1), a).unwrap();
            assert!((even - 1.0).abs() < 1e-6, "{even}");
            let quarter = |p: u32| if p < 4 { 0.1 } else { 0.0 };
            let quarter = allocation_bound(&films(&quarter), a).unwrap();
            assert!((quarter - 0.25 / correction).abs() < 1e-6, "{a}: {quarter}");
            // Noise in every pixel but unequal: strictly between.
            let ramp = allocation_bound(&films(&|p| 0.01 * (1 + p) as f32), a).unwrap();
            assert!(ramp > quarter && ramp < even, "{ramp}");
        }
        let ramp = |a| allocation_bound(&films(&|p| 0.01 * (1 + p) as f32), a).unwrap();
        assert!(ramp(1.0) < ramp(1.5) && ramp(1.5) < ramp(2.0));
        assert_eq!(allocation_bound(&films(&|_| 0.0), 1.0), None);
        assert_eq!(allocation_bound(&films(&|_| 0.1)[..1], 1.0), None);
        assert_eq!(allocation_bound(&films(&|_| 0.1), 0.0), None);
    }

    /// The stopping rule with each pixel's noise known: equal noise gives every pixel the same
    /// samples, uniform sampling's (a share of 1); noise in the top row of a 4×4 image keeps
    /// that row and the next going (the 3×3 neighbourhood) while the rest stop at 8, so at the
    /// cap of 256 the share is (8·256 + 8·8)/(16·256), twice the best allocation's ¼.
    #[test]
    fn known_noise_share_is_the_rule_s_own_allocation() {
        let full = Region::full(4, 4);
        let reference = Film::from_pixels(4, 4, vec![Vec3::ONE; 16]);
        for a in [1.0, 1.34] {
            let even = PixelNoise::measure(&films(&|_| 0.1), full).unwrap();
            for threshold in [0.04, 0.01, 1e-6] {
                let share = even.known_noise_share(&reference, full, 16, a, (256, threshold));
                assert!(
                    (share.unwrap() - 1.0).abs() < 1e-9,
                    "{a} {threshold}: {share:?}"
                );
            }
            let top = PixelNoise::measure(&films(&|p| if p < 4 { 0.1 } else { 0.0 }), full);
            let top = top.unwrap();
            let share = top.known_noise_share(&reference, full, 16, a, (256, 1e-6));
            let share = share.unwrap();
            assert!(
                (share - (8.0 * 256.0 + 64.0) / (16.0 * 256.0)).abs() < 1e-9,
                "{share}"
            );
            assert!(share > top.allocation_bound(a).unwrap());
        }
        let quiet = PixelNoise::measure(&films(&|_| 0.0), full).unwrap();
        assert_eq!(
            quiet.known_noise_share(&reference, full, 16, 1.0, (256, 0.01)),
            None
        );
    }

    /// The convergence exponent is fitted from 16 samples up: a curve falling as 1/n² there is
    /// found to be a = 2 whatever its first runs do.
    #[test]
    fn convergence_is_fitted_past_the_first_runs() {
        let u = uniform(&[
            (1, 0.1, 1.0),
            (4, 0.4, 0.9),
            (16, 1.6, 1.0 / 256.0),
            (32, 3.2, 1.0 / 1024.0),
            (64, 6.4, 1.0 / 4096.0),
        ]);
        let a = convergence_exponent(&u).unwrap();
        assert!((a - 2.0).abs() < 1e-9, "{a}");
        assert_eq!(convergence_exponent(&u[..3]), None);
    }

    /// The uniform time and samples at an error are interpolated in log-log between the runs
    /// around it, and are unknown past their range: a ratio is never extrapolated.
    #[test]
    fn equal_error_cost_interpolates_inside_the_uniform_range_only() {
        // MSE ∝ 1/spp, time = 0.5 s a sample: MSE e takes 1/e samples and 0.5/e seconds.
        let u = uniform(&[(1, 0.5, 1.0), (2, 1.0, 0.5), (4, 2.0, 0.25)]);
        let seconds = |r: &Run| r.seconds;
        let t = uniform_at(&u, 0.4, seconds).unwrap();
        assert!((t - 1.25).abs() < 1e-9, "{t}");
        let n = uniform_at(&u, 0.4, |r| f64::from(r.samples)).unwrap();
        assert!((n - 2.5).abs() < 1e-9, "{n}");
        assert_eq!(uniform_at(&u, 2.0, seconds), None);
        assert_eq!(uniform_at(&u, 0.1, seconds), None);
        let run = AdaptiveRun {
            threshold: 0.01,
            mean_samples: 1.5,
            seconds: 1.0,
            mse: 0.4,
            mse_region: 0.4,
            flip: 0.0,
            uniform_seconds: Some(t),
            uniform_samples: Some(n),
            known_noise_ratio: Some(0.55),
        };
        assert!((run.ratio().unwrap() - 0.8).abs() < 1e-9);
        assert!((run.samples_ratio().unwrap() - 0.6).abs() < 1e-9);
        let csv = csv_text(&AdaptiveStudy {
            uniform: u,
            adaptive: vec![run],
            bound: Some(0.25),
            bound_at_rate: Some((1.5, 0.3)),
            variance_samples: 16,
            allocation_map: None,
        });
        assert_eq!(csv.lines().count(), 7);
        let columns = csv.lines().next().unwrap().split(',').count();
        assert!(
            csv.lines().all(|l| l.split(',').count() == columns),
            "{csv}"
        );
        let adaptive = csv.lines().nth(4).unwrap();
        assert!(adaptive.starts_with("adaptive,0.01,4,1.500,"), "{adaptive}");
        assert!(
            adaptive.ends_with(",0.800000,2.500000,0.600000,0.550000"),
            "{adaptive}"
        );
        assert_eq!(
            csv.lines().nth(5),
            Some("best_allocation,,,,,,,,,0.250000,,0.250000,")
        );
        assert_eq!(
            csv.lines().last(),
            Some("best_allocation_at_rate,,,,,,,,,0.300000,,0.300000,")
        );
    }
}
