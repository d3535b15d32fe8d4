//! Adaptive against uniform sampling at equal error, for `raytracer study --adaptive`.
//!
//! The reference is a uniform render of many pixel samples. Uniform runs at 1, 2, 4, … samples
//! per pixel up to the cap give render time as a function of the error (MSE over the study's
//! region); adaptive runs (`--adaptive`, at most the cap, one per noise threshold) are each
//! scored by their error, and their time is divided by the time uniform sampling needs for that
//! error, interpolated in log-log between the uniform runs around it: the equal-error time ratio
//! (below 1, adaptive sampling wins). Both place pixel samples with Owen-scrambled Sobol points,
//! what `--adaptive` uses by default, so the ratio measures the adaptivity alone; every other
//! sample of the scene (area lights, the lens, a path's bounces) is the render's own.

use super::{
    bounds, draw_axes, draw_legend, encode_png, register_font, runs_of, time_to_reach, timed, Run,
    REFERENCE_SEED,
};
use crate::film::Film;
use crate::integrator::Kind;
use crate::metric::{mean_flip, mse, Region};
use crate::render::adaptive::Adaptive;
use crate::render::{render, RenderError, RenderOptions, RenderOutput};
use crate::sampling::Method;
use crate::scene::Scene;

/// The noise thresholds a study runs by default, loosest first.
pub const THRESHOLDS: [f32; 4] = [0.04, 0.02, 0.01, 0.005];

/// What an adaptive study renders.
#[derive(Debug, Clone)]
pub struct AdaptiveStudyOptions {
    /// The most samples a pixel takes: the adaptive cap and the largest uniform run.
    pub max_samples: u32,
    pub thresholds: Vec<f32>,
    pub integrator: Kind,
    /// Renders per run; the time is their median.
    pub runs: usize,
    /// Region the error is measured over; the whole image without one.
    pub region: Option<Region>,
    pub seed: u64,
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
}

impl AdaptiveRun {
    /// Adaptive time over uniform time at the same error.
    pub fn ratio(&self) -> Option<f64> {
        self.uniform_seconds.map(|u| self.seconds / u)
    }
}

/// The runs of an adaptive study.
#[derive(Debug, Clone, PartialEq)]
pub struct AdaptiveStudy {
    /// Uniform runs (sampler Sobol), in sample order.
    pub uniform: Vec<Run>,
    pub adaptive: Vec<AdaptiveRun>,
}

/// A render of `scene` by `integrator` at `spp` Sobol pixel samples, adaptive with `threshold`
/// if one is given.
fn render_pixels(
    scene: &Scene,
    integrator: Kind,
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
pub fn reference(scene: &Scene, integrator: Kind, spp: u32) -> Result<Film, RenderError> {
    Ok(render_pixels(scene, integrator, spp, None, REFERENCE_SEED)?.film)
}

/// Runs the study against `reference`, calling `progress(done, total, line)` after each run.
pub fn run_adaptive_study(
    scene: &Scene,
    reference: &Film,
    options: &AdaptiveStudyOptions,
    mut progress: impl FnMut(usize, usize, String),
) -> Result<AdaptiveStudy, RenderError> {
    let full = Region::full(reference.width, reference.height);
    let region = options.region.unwrap_or(full);
    let counts = super::sample_counts(Method::Sobol, options.max_samples);
    let total = counts.len() + options.thresholds.len();
    let timed = |threshold: Option<f32>, spp: u32| {
        timed(options.runs, || {
            render_pixels(scene, options.integrator, spp, threshold, options.seed)
        })
    };
    let mut uniform = Vec::with_capacity(counts.len());
    for (i, &spp) in counts.iter().enumerate() {
        let (r, seconds) = timed(None, spp)?;
        let run = Run {
            sampler: Method::Sobol,
            samples: spp,
            seconds,
            mse: mse(reference, &r.film, full),
            mse_region: mse(reference, &r.film, region),
            flip: mean_flip(reference, &r.film, full),
        };
        progress(
            i + 1,
            total,
            format!(
                "uniform  {spp:>5} spp        {seconds:.4} s  MSE {:.3e}",
                run.mse_region
            ),
        );
        uniform.push(run);
    }
    let mut adaptive = Vec::with_capacity(options.thresholds.len());
    for (i, &threshold) in options.thresholds.iter().enumerate() {
        let (r, seconds) = timed(Some(threshold), options.max_samples)?;
        let samples = r.sample_counts.as_deref().unwrap_or(&[]);
        let mean_samples = if samples.is_empty() {
            options.max_samples as f64
        } else {
            samples.iter().map(|&k| k as f64).sum::<f64>() / samples.len() as f64
        };
        let mse_region = mse(reference, &r.film, region);
        let run = AdaptiveRun {
            threshold,
            mean_samples,
            seconds,
            mse: mse(reference, &r.film, full),
            mse_region,
            flip: mean_flip(reference, &r.film, full),
            uniform_seconds: uniform_time_at(&uniform, mse_region),
        };
        progress(
            counts.len() + i + 1,
            total,
            format!(
                "adaptive T = {threshold} ({mean_samples:.1} spp)  {seconds:.4} s  MSE {mse_region:.3e}  ratio {}",
                run.ratio().map_or("-".into(), |x| format!("{x:.2}×"))
            ),
        );
        adaptive.push(run);
    }
    Ok(AdaptiveStudy { uniform, adaptive })
}

/// The time uniform sampling needs for `target`: [`time_to_reach`] within the uniform runs'
/// range of errors, `None` outside it (no extrapolation, not even to the first run's time).
fn uniform_time_at(uniform: &[Run], target: f64) -> Option<f64> {
    let worst = runs_of(uniform, Method::Sobol).first()?.mse_region;
    if target > worst {
        return None;
    }
    time_to_reach(uniform, Method::Sobol, target)
}

/// The study as CSV: `render,threshold,samples,mean_samples,seconds,mse,mse_region,flip,
/// uniform_seconds,ratio`, uniform rows first (their threshold, uniform time and ratio empty).
pub fn csv_text(study: &AdaptiveStudy) -> String {
    let mut s = String::from(
        "render,threshold,samples,mean_samples,seconds,mse,mse_region,flip,uniform_seconds,ratio\n",
    );
    for r in &study.uniform {
        s.push_str(&format!(
            "uniform,,{},{},{:.6},{:.6e},{:.6e},{:.6},,\n",
            r.samples, r.samples, r.seconds, r.mse, r.mse_region, r.flip
        ));
    }
    let cap = study.uniform.last().map_or(0, |r| r.samples);
    for r in &study.adaptive {
        let opt = |v: Option<f64>| v.map_or(String::new(), |x| format!("{x:.6}"));
        s.push_str(&format!(
            "adaptive,{},{cap},{:.3},{:.6},{:.6e},{:.6e},{:.6},{},{}\n",
            r.threshold,
            r.mean_samples,
            r.seconds,
            r.mse,
            r.mse_region,
            r.flip,
            opt(r.uniform_seconds),
            opt(r.ratio())
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

    /// The uniform time at an error is interpolated in log-log between the runs around it, and
    /// is unknown past their range: a ratio is never extrapolated.
    #[test]
    fn equal_error_time_interpolates_inside_the_uniform_range_only() {
        // MSE ∝ 1/spp, time ∝ spp: the time for MSE e is 1/e.
        let u = uniform(&[(1, 1.0, 1.0), (2, 2.0, 0.5), (4, 4.0, 0.25)]);
        let t = uniform_time_at(&u, 0.4).unwrap();
        assert!((t - 2.5).abs() < 1e-9, "{t}");
        assert_eq!(uniform_time_at(&u, 2.0), None);
        assert_eq!(uniform_time_at(&u, 0.1), None);
        let run = AdaptiveRun {
            threshold: 0.01,
            mean_samples: 1.5,
            seconds: 1.0,
            mse: 0.4,
            mse_region: 0.4,
            flip: 0.0,
            uniform_seconds: Some(t),
        };
        assert!((run.ratio().unwrap() - 0.4).abs() < 1e-9);
        let csv = csv_text(&AdaptiveStudy {
            uniform: u,
            adaptive: vec![run],
        });
        assert_eq!(csv.lines().count(), 5);
        assert!(csv
            .lines()
            .last()
            .unwrap()
            .starts_with("adaptive,0.01,4,1.500,"));
    }
}
