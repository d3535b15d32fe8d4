//! Adaptive sampling: each pixel takes samples in rounds until its estimated error is below a
//! threshold, up to the render's `spp`.
//!
//! Round boundaries double: 4, 8, 16, … samples (fewer rounds for small `spp`), so a pixel that
//! stops after round r holds exactly samples `0..n_r` of the full pattern. After every round
//! the error of each pixel is estimated from two halves of its samples, in the way Cycles does
//! (Blender's `kernel/film/adaptive_sampling.h`, after Dammertz et al. 2010, "A hierarchical
//! automatic stopping condition for Monte Carlo global illumination"): with `I` the mean of all
//! samples and `A` the mean of the odd-numbered ones,
//!
//! ```text
//! error = (|I_r − A_r| + |I_g − A_g| + |I_b − A_b|) / (10⁻⁴ + √(I_r + I_g + I_b))
//! ```
//!
//! which is relative to the square root of the brightness, as the eye is. A pixel goes on while
//! the largest error in its 3×3 neighbourhood is above the threshold, so a pixel whose few samples
//! happen to agree inside a noisy penumbra does not stop alone. Decisions depend only on the
//! samples, never on timing or threads: the same command gives the same bytes.
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

use super::Work;

/// Adaptive-sampling settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Adaptive {
    /// A pixel stops when the error estimate of every pixel around it is at most this.
    pub threshold: f32,
    /// Stop starting pixels once this much time has passed since the render began, and keep
    /// what is there: each pixel the rounds it finished, the first round at least. The one setting whose result depends
    /// on timing, and so on the machine and its load.
    pub time_limit: Option<Duration>,
}

/// The threshold `--noise-threshold` defaults to: Cycles' default noise threshold.
pub const DEFAULT_THRESHOLD: f32 = 0.01;

/// The fewest samples a pixel takes before its error is first estimated.
const FIRST_ROUND: u32 = 4;

/// The sample counts at which rounds end: doubling from [`FIRST_ROUND`] up to `spp`.
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

/// One pixel's samples so far.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct PixelState {
    all: PixelSum,
    odd: PixelSum,
    count: u32,
    active: bool,
}

impl PixelState {
    fn error(&self) -> f32 {
        if self.count < 2 {
            return f32::INFINITY;
        }
        let i = self.all.mean(self.count);
        let a = self.odd.mean(self.count / 2);
        let e = (i - a).abs().element_sum() / (1e-4 + i.element_sum().max(0.0).sqrt());
        // NaN (a NaN sample) never converges, so it is not hidden by stopping early.
        if e.is_nan() {
            f32::INFINITY
        } else {
            e
        }
    }
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
                    // A pixel's state changes only once its round is complete.
                    let mut next = *p;
                    let x = region.x0 + i as u32;
                    for s in start..end {
                        if tracer.cancelled() {
                            return tracer.counts();
                        }
                        let c = work.sample(&mut tracer, x, y, s);
                        next.all.add(c);
                        if s % 2 == 1 {
                            next.odd.add(c);
                        }
                    }
                    next.count = end;
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
        if round + 1 < ends.len() {
            decide(&mut states, region, settings.threshold);
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
            sums.push(p.all);
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
            if !p.active {
                continue;
            }
            let mut worst = 0.0f32;
            for ny in y.saturating_sub(1)..(y + 2).min(h) {
                for nx in x.saturating_sub(1)..(x + 2).min(w) {
                    worst = worst.max(errors[ny * w + nx]);
                }
            }
            p.active = worst > threshold;
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn rounds_double_up_to_spp() {
        assert_eq!(round_ends(1), vec![1]);
        assert_eq!(round_ends(4), vec![4]);
        assert_eq!(round_ends(6), vec![4, 6]);
        assert_eq!(round_ends(64), vec![4, 8, 16, 32, 64]);
        assert_eq!(round_ends(100), vec![4, 8, 16, 32, 64, 100]);
    }

    fn state(samples: &[f32]) -> PixelState {
        let mut p = PixelState {
            active: true,
            ..PixelState::default()
        };
        for (s, &v) in samples.iter().enumerate() {
            p.all.add(Vec3::splat(v));
            if s % 2 == 1 {
                p.odd.add(Vec3::splat(v));
            }
        }
        p.count = samples.len() as u32;
        p
    }

    #[test]
    fn error_is_zero_for_equal_samples_and_grows_with_their_spread() {
        assert_eq!(state(&[0.5; 8]).error(), 0.0);
        let small = state(&[0.5, 0.52, 0.5, 0.52]).error();
        let large = state(&[0.2, 0.8, 0.2, 0.8]).error();
        assert!(small > 0.0 && large > 10.0 * small, "{small} {large}");
        assert_eq!(state(&[0.5]).error(), f32::INFINITY);
        assert_eq!(state(&[0.5, f32::NAN]).error(), f32::INFINITY);
    }

    #[test]
    fn a_noisy_pixel_keeps_its_neighbours_going() {
        let region = PixelRect::full(5, 1);
        let mut states = vec![state(&[0.5; 4]); 5];
        states[0] = state(&[0.0, 1.0, 0.0, 1.0]);
        decide(&mut states, region, 0.01);
        let active: Vec<bool> = states.iter().map(|p| p.active).collect();
        assert_eq!(active, [true, true, false, false, false]);
        // Once stopped, a pixel stays stopped.
        states[4] = state(&[0.0, 1.0, 0.0, 1.0]);
        states[4].active = false;
        decide(&mut states, region, 0.01);
        assert!(!states[3].active && !states[4].active);
    }
}
