//! Adaptive sampling: each pixel takes samples in rounds until its estimated error is below a
//! threshold, up to the render's `spp`.
//!
//! Round boundaries double: 4, 8, 16, … samples (fewer rounds for small `spp`), so a pixel that
//! stops after round r holds exactly samples `0..n_r` of the full pattern. After every round from
//! the `EARLY_DECISION`th sample on (where a pixel needs half the threshold to stop; from the
//! `FIRST_DECISION`th on, the threshold), the error of each pixel is estimated from how far apart
//! the means of four groups of its samples lie, after Dammertz et al. 2010 ("A hierarchical automatic
//! stopping condition for Monte Carlo global illumination") and Cycles (Blender's
//! `kernel/film/adaptive_sampling.h`), which compare two groups. The groups are the four
//! consecutive quarters of the pixel's `n` samples (a round's two halves and the two halves of
//! what came before it); with `m_j` the mean of group j (of `c_j` samples) and `I` the mean of all
//! `n`, per channel
//!
//! ```text
//! s² = Σ_j c_j (m_j − I)² / 3                  (the variance of one sample)
//! error = (s_r + s_g + s_b) / √n / (10⁻⁴ + √(I_r + I_g + I_b))
//! ```
//!
//! the standard error of `I` when the groups are independent, relative to the square root of the
//! brightness, as the eye is. With two groups (`c_j = n/2`) this is half the difference of their
//! means, Cycles' and Dammertz's estimate; four groups give it three degrees of freedom instead of
//! one, so a noisy pixel looks converged by chance far less often. Cycles splits odd-numbered
//! from even-numbered samples; with Owen-scrambled Sobol points (the default under `--adaptive`)
//! those lie in opposite halves of the pixel, so their difference measures the pixel's gradient
//! and an edge would never look converged. Each quarter here is an aligned block of Sobol points,
//! stratified over the whole pixel.
//!
//! A pixel goes on while the largest error in its 3×3 neighbourhood is above the threshold, so a
//! pixel whose few samples happen to agree inside a noisy penumbra does not stop alone. Decisions
//! depend only on the samples, never on timing or threads: the same command gives the same bytes.
//!
//! With a time limit ([`Adaptive::time_limit`]) rounds go on until the time is spent and the
//! pixels keep the rounds they finished: the one mode whose bytes depend on the machine.
//!
//! A crop decides as the whole render does: a pixel's decision after round r depends on the
//! pixels within r + 1 of it, so a crop is traced with an apron of one pixel per round around it
//! and only the crop is kept.

use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

use rayon::prelude::*;

use crate::film::{PixelRect, PixelSum};
use crate::integrator::RayCounts;
use crate::math::Vec3;

use super::Work;

/// Adaptive-sampling settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Adaptive {
    /// A pixel stops when the error estimate of every pixel around it is at most this.
    pub threshold: f32,
    /// Stop starting pixels once this much time has passed since the render began, and keep
    /// what is there: each pixel the rounds it finished, the first round at least. The one
    /// setting whose result depends on timing, and so on the machine and its load.
    pub time_limit: Option<Duration>,
}

/// The threshold `--noise-threshold` defaults to: Cycles' default noise threshold.
pub const DEFAULT_THRESHOLD: f32 = 0.01;

/// The fewest samples a pixel takes before its error is first estimated.
const FIRST_ROUND: u32 = 4;

/// The samples after which a pixel may stop at the full threshold (above 0). Deciding from 4
/// samples lets pixels of a noisy region stop on a lucky draw. Cycles waits longer for its
/// estimate, max(4, ⌈16/T^0.3⌉) samples (64 at T = 0.01, Blender's `scene/integrator.cpp`), which
/// would make the in-focus half of a thin-lens scene take 64 samples where 16 already agree
/// (docs/adaptive.md).
const FIRST_DECISION: u32 = 16;

/// The samples after which a pixel may stop early, at [`EARLY_SHARE`] of the threshold: where
/// every error around a pixel is that far below the threshold after 8 samples, 8 more rarely
/// change the answer, so stopping there saves samples at loose thresholds and leaves tight ones
/// alone (docs/adaptive.md).
const EARLY_DECISION: u32 = 8;
const EARLY_SHARE: f32 = 0.5;

/// The threshold the decision after `end` samples applies, `None` where no pixel may stop yet.
/// A threshold of 0 stops only pixels whose samples all agree: nothing to wait for.
fn decision_threshold(end: u32, threshold: f32) -> Option<f32> {
    if threshold <= 0.0 || end >= FIRST_DECISION {
        Some(threshold)
    } else if end >= EARLY_DECISION {
        Some(threshold * EARLY_SHARE)
    } else {
        None
    }
}

/// The sample counts at which rounds end: doubling from `FIRST_ROUND` up to `spp`.
pub fn round_ends(spp: u32) -> Vec<u32> {
    let mut ends = Vec::new();
    let mut n = FIRST_ROUND.min(spp);
    loop {
        ends.push(n);
        if n >= spp {
            return ends;
        }
        n = n.saturating_mul(2).min(spp);
    }
}

/// The pixels an adaptive render of `window` (in an image of `full` pixels) traces at `spp`:
/// the window and an apron of one pixel per round around it, within the image.
pub(super) fn traced_region(window: PixelRect, full: PixelRect, spp: u32) -> PixelRect {
    let apron = round_ends(spp).len() as u32;
    PixelRect {
        x0: window.x0.saturating_sub(apron),
        y0: window.y0.saturating_sub(apron),
        x1: window.x1.saturating_add(apron).min(full.x1),
        y1: window.y1.saturating_add(apron).min(full.y1),
    }
}

/// The groups a pixel's samples are split into for its error estimate.
const GROUPS: usize = 4;

/// One pixel's samples so far.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct PixelState {
    /// The sums of the four consecutive quarters of the pixel's samples, and how many each holds.
    groups: [PixelSum; GROUPS],
    group_counts: [u32; GROUPS],
    count: u32,
    active: bool,
}

impl PixelState {
    /// Adds samples `start..end` of the pixel, `sample(s)` giving sample `s`, and regroups them:
    /// the first round's samples make four groups, a later round's two halves become the last two
    /// groups and the four groups before them merge pairwise into the first two.
    fn add_round(&mut self, start: u32, end: u32, mut sample: impl FnMut(u32) -> Vec3) {
        if start > 0 {
            let [mut a, b, mut c, d] = self.groups;
            a.merge(&b);
            c.merge(&d);
            let k = self.group_counts;
            self.groups = [a, c, PixelSum::default(), PixelSum::default()];
            self.group_counts = [k[0] + k[1], k[2] + k[3], 0, 0];
        }
        let mid = start + (end - start) / 2;
        for s in start..end {
            let c = sample(s);
            let g = if start == 0 {
                (s as usize * GROUPS) / end as usize
            } else if s < mid {
                2
            } else {
                3
            };
            self.groups[g].add(c);
            self.group_counts[g] += 1;
        }
        self.count = end;
    }

    /// The exact sum of all the pixel's samples: its groups' together (so a sample is added to
    /// one sum, not two).
    fn all(&self) -> PixelSum {
        let mut all = self.groups[0];
        for g in &self.groups[1..] {
            all.merge(g);
        }
        all
    }

    /// The estimated standard error of the pixel's mean, relative to the square root of its
    /// brightness: from the spread of its groups' means (see the module docs).
    fn error(&self) -> f32 {
        let n = self.count;
        let used = self.group_counts.iter().filter(|&&c| c > 0).count();
        if used < 2 {
            return f32::INFINITY;
        }
        let i = self.all().mean(n);
        let mut squares = Vec3::ZERO;
        for (sum, &c) in self.groups.iter().zip(&self.group_counts) {
            if c > 0 {
                let d = sum.mean(c) - i;
                squares += d * d * c as f32;
            }
        }
        let variance = squares / (used - 1) as f32;
        let standard_error = (variance / n as f32).to_array().map(f32::sqrt);
        let e = standard_error.iter().sum::<f32>() / brightness_scale(i);
        // NaN (a NaN sample) never converges, so it is not hidden by stopping early.
        if e.is_nan() {
            f32::INFINITY
        } else {
            e
        }
    }
}

/// What a pixel's standard errors (summed over RGB) are divided by: 10⁻⁴ + √(RGB sum of its
/// mean), the square root of its brightness as Cycles scales it (see the module docs).
#[inline]
pub fn brightness_scale(mean: Vec3) -> f32 {
    1e-4 + mean.element_sum().max(0.0).sqrt()
}

/// What an adaptive render of a window traced.
pub(super) struct Traced {
    /// Exact sums over the window, row-major.
    pub sums: Vec<PixelSum>,
    /// Samples taken by each pixel of the window.
    pub counts: Vec<u32>,
    pub rays: RayCounts,
    pub cancelled: bool,
}

/// Traces `work.window` adaptively with `settings`, into `states`: one per pixel of `region`
/// ([`traced_region`]), allocated by the caller.
pub(super) fn trace(
    work: &Work,
    settings: Adaptive,
    mut states: Vec<PixelState>,
    region: PixelRect,
) -> Traced {
    let ends = round_ends(work.spp);
    let w = work.window;
    let rw = region.width() as usize;
    debug_assert_eq!(states.len() as u64, region.area());
    for p in &mut states {
        p.active = true;
    }
    let deadline = settings.time_limit.map(|t| Instant::now() + t);
    let out_of_time = || deadline.is_some_and(|d| Instant::now() >= d);
    let mut rays = RayCounts::default();
    let mut start = 0;
    let mut cancelled = false;
    for (round, &end) in ends.iter().enumerate() {
        let counts = states
            .par_chunks_mut(rw)
            .enumerate()
            .map(|(row, pixels)| {
                let y = region.y0 + row as u32;
                let mut tracer = work.tracer();
                for (i, p) in pixels.iter_mut().enumerate() {
                    if !p.active {
                        continue;
                    }
                    if round > 0 && out_of_time() {
                        break;
                    }
                    // A pixel's state changes only once its round is complete; once the render
                    // is cancelled the round's remaining samples are skipped and it is dropped.
                    let mut next = *p;
                    let x = region.x0 + i as u32;
                    next.add_round(start, end, |s| {
                        if tracer.cancelled() {
                            Vec3::ZERO
                        } else {
                            work.sample(&mut tracer, x, y, s)
                        }
                    });
                    if tracer.cancelled() {
                        return tracer.counts();
                    }
                    *p = next;
                }
                tracer.counts()
            })
            .reduce(RayCounts::default, |mut a, b| {
                a.add(&b);
                a
            });
        rays.add(&counts);
        if super::cancelled(work.options) {
            cancelled = true;
            break;
        }
        if out_of_time() {
            break;
        }
        start = end;
        let threshold = decision_threshold(end, settings.threshold);
        if let Some(threshold) = threshold.filter(|_| round + 1 < ends.len()) {
            decide(&mut states, region, threshold);
            if !states.iter().any(|p| p.active) {
                break;
            }
        }
    }

    let n = w.area() as usize;
    let (mut sums, mut counts) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for y in w.y0..w.y1 {
        let row = (y - region.y0) as usize * rw;
        for x in w.x0..w.x1 {
            let p = &states[row + (x - region.x0) as usize];
            sums.push(p.all());
            counts.push(p.count);
        }
    }
    if let Some(done) = work.pixels_done {
        done.fetch_add(n as u64, Ordering::Relaxed);
    }
    Traced {
        sums,
        counts,
        rays,
        cancelled,
    }
}

/// Keeps active the pixels of `region` with an error above `threshold` in their 3×3
/// neighbourhood (clipped to the region); a pixel that stopped stays stopped.
fn decide(states: &mut [PixelState], region: PixelRect, threshold: f32) {
    let (w, h) = (region.width() as usize, region.height() as usize);
    let errors: Vec<f32> = states.par_iter().map(PixelState::error).collect();
    states.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, p) in row.iter_mut().enumerate() {
            if p.active {
                p.active = worst_around(&errors, (w, h), (x, y)) > threshold;
            }
        }
    });
}

/// The largest of `errors` (row-major, `w × h`) in the 3×3 neighbourhood of `(x, y)`, clipped
/// to the image.
#[inline]
fn worst_around(errors: &[f32], (w, h): (usize, usize), (x, y): (usize, usize)) -> f32 {
    let mut worst = 0.0f32;
    for ny in y.saturating_sub(1)..(y + 2).min(h) {
        for nx in x.saturating_sub(1)..(x + 2).min(w) {
            worst = worst.max(errors[ny * w + nx]);
        }
    }
    worst
}

/// The samples each pixel of a `w × h` image takes under this module's stopping rule (its
/// rounds up to `spp`, its decisions at `threshold`, its neighbourhood) when the error a pixel's
/// estimate gives after `n` samples is known: `error(i, n)` for pixel `i`, row-major. What an
/// adaptive render would do with an exact estimate; `raytracer study --adaptive` feeds it each
/// pixel's measured noise, to tell what the rule itself costs from what its estimate costs.
pub fn samples_with_known_errors(
    (w, h): (usize, usize),
    spp: u32,
    threshold: f32,
    error: impl Fn(usize, u32) -> f32,
) -> Vec<u32> {
    let ends = round_ends(spp);
    let mut samples = vec![0u32; w * h];
    let mut active = vec![true; w * h];
    for (round, &end) in ends.iter().enumerate() {
        for (n, _) in samples.iter_mut().zip(&active).filter(|(_, &a)| a) {
            *n = end;
        }
        let Some(threshold) = decision_threshold(end, threshold).filter(|_| round + 1 < ends.len())
        else {
            continue;
        };
        let errors: Vec<f32> = samples
            .iter()
            .enumerate()
            .map(|(i, &n)| error(i, n))
            .collect();
        for (i, a) in active.iter_mut().enumerate().filter(|(_, a)| **a) {
            *a = worst_around(&errors, (w, h), (i % w, i / w)) > threshold;
        }
        if !active.contains(&true) {
            break;
        }
    }
    samples
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// With known errors the rule stops each pixel at the first decision whose threshold its
    /// neighbourhood's errors meet, and a noisy pixel keeps its neighbours going.
    #[test]
    fn known_errors_stop_pixels_at_the_rule_s_decisions() {
        // Error c/√n: after n samples at most T once n ≥ (c/T)².
        let stop =
            |c: f32| samples_with_known_errors((1, 1), 256, 0.01, |_, n| c / (n as f32).sqrt())[0];
        assert_eq!(stop(0.0), 8); // at 8, under T/2
        assert_eq!(stop(0.014), 8); // 0.0049 ≤ 0.005
        assert_eq!(stop(0.015), 16); // 0.0053 > T/2 at 8; 0.0038 ≤ T at 16
        assert_eq!(stop(0.04), 16);
        assert_eq!(stop(0.05), 32);
        assert_eq!(stop(0.1), 128);
        assert_eq!(stop(1.0), 256); // never under: the cap

        // A 5×4 image, flat but for one pixel: it and its 3×3 neighbourhood take what it needs.
        let n = samples_with_known_errors((5, 4), 256, 0.01, |i, n| {
            if i == 7 {
                0.1 / (n as f32).sqrt()
            } else {
                0.0
            }
        });
        for (i, &k) in n.iter().enumerate() {
            let (x, y) = (i % 5, i / 5);
            let near = x.abs_diff(2) <= 1 && y.abs_diff(1) <= 1;
            assert_eq!(k, if near { 128 } else { 8 }, "pixel ({x}, {y}): {n:?}");
        }
        // Fewer samples than a decision needs: every pixel takes them all.
        assert_eq!(
            samples_with_known_errors((2, 2), 6, 0.01, |_, _| 0.0),
            [6; 4]
        );
    }

    #[test]
    fn pixels_stop_before_16_samples_only_far_below_the_threshold() {
        assert_eq!(decision_threshold(4, 0.01), None);
        assert_eq!(decision_threshold(8, 0.01), Some(0.005));
        assert_eq!(decision_threshold(12, 0.01), Some(0.005));
        assert_eq!(decision_threshold(16, 0.01), Some(0.01));
        assert_eq!(decision_threshold(64, 0.01), Some(0.01));
        assert_eq!(decision_threshold(4, 0.0), Some(0.0));
    }

    #[test]
    fn rounds_double_up_to_spp() {
        assert_eq!(round_ends(1), vec![1]);
        assert_eq!(round_ends(4), vec![4]);
        assert_eq!(round_ends(6), vec![4, 6]);
        assert_eq!(round_ends(64), vec![4, 8, 16, 32, 64]);
        assert_eq!(round_ends(100), vec![4, 8, 16, 32, 64, 100]);
    }

    /// A pixel that took `samples` in rounds doubling from 4, as a render does.
    fn state(samples: &[f32]) -> PixelState {
        let mut p = PixelState {
            active: true,
            ..PixelState::default()
        };
        let n = samples.len() as u32;
        let mut start = 0;
        for end in round_ends(n) {
            p.add_round(start, end, |s| Vec3::splat(samples[s as usize]));
            start = end;
        }
        p
    }

    #[test]
    fn rounds_regroup_into_four_quarters() {
        let samples: Vec<f32> = (0..16).map(|s| s as f32).collect();
        let p = state(&samples);
        assert_eq!(p.count, 16);
        assert_eq!(p.group_counts, [4, 4, 4, 4]);
        let means: Vec<f32> = (0..4).map(|j| p.groups[j].mean(4).x).collect();
        assert_eq!(means, [1.5, 5.5, 9.5, 13.5]);
        assert_eq!(p.all().mean(16).x, 7.5);
        // A last round short of doubling (8 to 12): its halves are smaller than the groups
        // before it.
        let p = state(&samples[..12]);
        assert_eq!(p.group_counts, [4, 4, 2, 2]);
    }

    #[test]
    fn error_is_zero_for_equal_samples_and_grows_with_their_spread() {
        assert_eq!(state(&[0.5; 8]).error(), 0.0);
        let small = state(&[0.5, 0.5, 0.52, 0.52]).error();
        let large = state(&[0.2, 0.2, 0.8, 0.8]).error();
        assert!(small > 0.0 && large > 10.0 * small, "{small} {large}");
        assert_eq!(state(&[0.5]).error(), f32::INFINITY);
        assert_eq!(state(&[0.5, f32::NAN]).error(), f32::INFINITY);
    }

    /// Owen-scrambled Sobol puts a pixel's odd-numbered samples in one half of it and the even
    /// ones in the other, so on an edge they differ however many there are; each quarter of the
    /// samples covers the whole pixel alike, so the quarters agree.
    #[test]
    fn an_edge_sampled_evenly_on_both_sides_converges() {
        let edge = state(&[0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0]);
        assert_eq!(edge.error(), 0.0);
    }

    /// Groups of one sample each give the textbook standard error s/√n; two groups of n/2 give
    /// half the difference of their means (Dammertz et al., Cycles).
    #[test]
    fn error_is_the_standard_error_of_the_mean() {
        let brightness = |mean: f32| 1e-4 + (3.0 * mean).sqrt();
        let four = state(&[0.4, 0.4, 0.6, 0.6]);
        let s = (4.0 * 0.01f32 / 3.0).sqrt();
        let want = 3.0 * s / 2.0 / brightness(0.5);
        assert!((four.error() - want).abs() < 1e-6, "{}", four.error());
        let mut two = PixelState::default();
        two.add_round(0, 2, |s| Vec3::splat([0.4, 0.6][s as usize]));
        let want = 3.0 * 0.1 / brightness(0.5);
        assert!((two.error() - want).abs() < 1e-6, "{}", two.error());
    }

    /// Four groups estimate a pixel's error with three degrees of freedom: over many pixels of
    /// independent noise the estimate's spread is well under the one-degree estimate's 0.76 of
    /// its mean (that of |N(0, 1)|), and its mean is c₄(4) = 0.921 of the true standard error.
    #[test]
    fn the_estimate_is_steady_across_pixels_alike() {
        let mut rng = 0x2545_f491_4f6c_dd1du64;
        let mut normal = move || {
            // Sum of 12 uniforms minus 6: mean 0, variance 1.
            (0..12)
                .map(|_| {
                    rng ^= rng << 13;
                    rng ^= rng >> 7;
                    rng ^= rng << 17;
                    (rng >> 40) as f32 / (1u64 << 24) as f32
                })
                .sum::<f32>()
                - 6.0
        };
        let (sigma, mean, n) = (0.1f32, 0.5f32, 16usize);
        let errors: Vec<f32> = (0..4000)
            .map(|_| {
                let samples: Vec<f32> = (0..n).map(|_| mean + sigma * normal()).collect();
                state(&samples).error()
            })
            .collect();
        let m = errors.iter().sum::<f32>() / errors.len() as f32;
        let sd = (errors.iter().map(|e| (e - m).powi(2)).sum::<f32>() / errors.len() as f32).sqrt();
        let truth = 3.0 * sigma / (n as f32).sqrt() / (1e-4 + (3.0 * mean).sqrt());
        assert!(
            (m / truth - 0.921).abs() < 0.03,
            "{} of the truth",
            m / truth
        );
        assert!(sd / m < 0.5, "spread {} of the mean", sd / m);
    }

    #[test]
    fn a_noisy_pixel_keeps_its_neighbours_going() {
        let region = PixelRect::full(5, 1);
        let mut states = vec![state(&[0.5; 4]); 5];
        states[0] = state(&[0.0, 0.0, 1.0, 1.0]);
        decide(&mut states, region, 0.01);
        let active: Vec<bool> = states.iter().map(|p| p.active).collect();
        assert_eq!(active, [true, true, false, false, false]);
        // Once stopped, a pixel stays stopped.
        states[4] = state(&[0.0, 0.0, 1.0, 1.0]);
        states[4].active = false;
        decide(&mut states, region, 0.01);
        assert!(!states[3].active && !states[4].active);
    }
}
