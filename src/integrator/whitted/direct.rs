//! Direct light at a Whitted shading point: shadow rays towards each light sample, the light
//! terms left out because they are zero or below the cut-off, and adaptive probes of area lights.

use crate::accel::{Beam, Reachable};
use crate::light::{Light, LightSample};
use crate::material::highlight;
use crate::math::{Vec2, Vec3};
use crate::ray::Side;
use crate::sampling::{CameraSamples, Method, SampleKey};
use quad_lanes::{Quad, Shading};
use std::ops::Range;

use super::*;

/// Most primitives an area light's shadow rays from one point test one by one (see [`Beam`]);
/// past this many the whole accelerator is queried instead, which for a tree of that size costs
/// about as much.
pub(super) const BEAM_CANDIDATE_LIMIT: usize = 16;

/// Probe points of [`TraceOptions::adaptive_lights`]: a 3×3 grid over the light (corners, edge
/// midpoints, centre), the outer ones inset slightly so that a light whose edge touches a wall is
/// not probed through the wall. Corners alone (POV-Ray's first level) miss an occluder smaller
/// than the light that hides its middle: the umbra under it vanishes.
pub(super) const ADAPTIVE_PROBES: [Vec2; 9] = {
    const E: f32 = 1e-3;
    [
        Vec2::new(E, E),
        Vec2::new(0.5, E),
        Vec2::new(1.0 - E, E),
        Vec2::new(E, 0.5),
        Vec2::new(0.5, 0.5),
        Vec2::new(1.0 - E, 0.5),
        Vec2::new(E, 1.0 - E),
        Vec2::new(0.5, 1.0 - E),
        Vec2::new(1.0 - E, 1.0 - E),
    ]
};

/// The light terms a shading point leaves untraced under the cut-off are below
/// `cutoff / LIGHT_CUT_FRACTION` of radiance, shared among the scene's lights (see
/// [`negligible`]).
pub(super) const LIGHT_CUT_FRACTION: f32 = 64.0;

/// Whether a light sample's terms, `diffuse · (n·l · e)` and `specular · (spec · e)` with
/// `e = unblocked · visibility` (the visibility in `[0, 1]`), can be left out without tracing
/// the shadow ray that finds the visibility:
///
/// - **exactly**, whatever `least`, where both terms are zeros for every visibility: the
///   diffuse colour is zero and so is the highlight (or its colour). Adding them would leave the
///   colour as it is. The common case is a mirror or glass (`kd = 0`) away from its highlight,
///   where `spec` underflows to zero (`0.597^200` does). With `unblocked` finite, `e` is finite,
///   and a product of zero with a finite number is a zero; a visibility below one only shrinks
///   a product that already rounds to zero. An infinite or NaN `unblocked` always goes to the
///   full computation.
/// - **below the cut-off**, where the unblocked terms are below `least` (the light's
///   [`Whitted::light_cut`]) in every channel. A pixel's sum then loses less than
///   `cutoff / LIGHT_CUT_FRACTION` of radiance per level of its ray tree, all lights together
///   (the weights of a level's shading points sum to at most one where `kr + kt ≤ 1`): with the
///   default cut-off of 1/255 and `nbounces` up to 14, under a quarter of an 8-bit step.
///   `least` is 0 without a cut-off (`--no-skip`), and only the exact case remains.
#[inline(always)]
pub(super) fn negligible(
    unblocked: f32,
    n_dot_l: f32,
    diffuse: Vec3,
    spec: f32,
    specular: Vec3,
    least: f32,
) -> bool {
    let zero =
        unblocked.is_finite() && diffuse == Vec3::ZERO && (spec == 0.0 || specular == Vec3::ZERO);
    // NaN compares false: a NaN term is never cut.
    zero || (least > 0.0
        && ((diffuse * n_dot_l + specular * spec) * unblocked)
            .abs()
            .max_element()
            < least)
}

/// A test that [`negligible`] may hold, from the diffuse term alone, before the highlight's
/// half vector and power are worked out: where it fails, so does [`negligible`] (for
/// non-negative colours, `n·l` and highlight, the diffuse term is a lower bound of the sum it
/// compares), and the shadow ray is traced as it always was.
#[inline(always)]
pub(super) fn may_be_negligible(unblocked: f32, n_dot_l: f32, diffuse: Vec3, least: f32) -> bool {
    unblocked.is_finite()
        && (diffuse == Vec3::ZERO
            || (least > 0.0 && (diffuse.abs().max_element() * n_dot_l * unblocked).abs() < least))
}

/// How one light sample's terms are weighted, and how its visibility is found.
#[derive(Clone, Copy)]
pub(super) struct SampleWeighting<'r> {
    /// The sample's share of the light: `1/n` of an area light's `n` samples.
    pub(super) share: f32,
    /// The transmittance towards the light where adaptive probes found it
    /// ([`TraceOptions::adaptive_lights`]); traced otherwise.
    pub(super) known: Option<f32>,
    /// The primitives the shadow ray can meet from either spawn origin, where a beam listed
    /// them (see [`Whitted::transmittance`]).
    pub(super) only: Option<[&'r Reachable; 2]>,
    /// The least terms worth tracing (see [`negligible`]). Only single-sample lights are cut: for
    /// an area light's samples the test costs more than the shadow rays it saves.
    pub(super) cut: Option<f32>,
}

impl SampleWeighting<'_> {
    /// A light's one sample, its terms cut below `least`.
    pub(super) fn single(least: f32) -> SampleWeighting<'static> {
        SampleWeighting {
            share: 1.0,
            known: None,
            only: None,
            cut: Some(least),
        }
    }
}

impl Whitted<'_> {
    /// Adds to `color` the terms of the `count > 1` samples of `light` (light `li`) at the shading
    /// point, each carrying `1/count` of what one sample alone would. `false` if the render was
    /// cancelled on the way (then `color` holds the samples before).
    ///
    /// Kept out of line, so that [`Whitted::shade`] stays small for point lights.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    pub(super) fn area_light(
        &mut self,
        color: &mut Vec3,
        shading: &Shading,
        li: usize,
        light: &Light,
        count: u32,
        method: Method,
        key: &SampleKey,
    ) -> bool {
        let scene = self.scene;
        let spawn = shading.spawn;
        let share = 1.0 / count as f32;
        if self.camera.spp() != key.spp {
            self.camera = CameraSamples::new(self.camera.method, key.spp);
        }
        let points = key
            .stream(li as u64)
            .light_set(method, &self.camera, 0, count);
        let quad = Quad::of(light);
        if let Some(quad) = &quad {
            if quad.wholly_behind(shading.point, shading.n) {
                return true; // every sample is behind the side we see
            }
            // A mirror or glass away from the light's highlight: every sample's terms are zeros.
            let no_diffuse = shading.kd_base * light.intensity().diffuse == Vec3::ZERO;
            if no_diffuse && !quad.highlight_may_show(shading, &points, count, share) {
                return true;
            }
        }
        let surface = light.surface();
        let known = if self.options.adaptive_lights && count > ADAPTIVE_PROBES.len() as u32 {
            self.uniform_visibility(shading, light, &surface)
        } else {
            None
        };
        if known == Some(0.0) {
            return true; // every probe is blocked: the light is taken as fully hidden
        }
        // The primitives this light's shadow rays may meet, once for all of them, and of
        // those the ones the rays from each spawn origin may meet.
        let mut candidates = std::mem::take(&mut self.candidates);
        let mut reachable = std::mem::take(&mut self.reachable);
        let only = known
            .is_none()
            .then(|| self.light_bounds[li])
            .flatten()
            .and_then(|b| Beam::new(shading.point, &b, spawn.offset()))
            .filter(|beam| {
                let prims = &scene.primitives;
                let limit = BEAM_CANDIDATE_LIMIT;
                let buffer = self.light_buffers.get(li).and_then(Option::as_ref);
                buffer
                    .and_then(|b| {
                        let (point, offset) = (shading.point, spawn.offset());
                        b.beam_candidates(beam, point, offset, limit, &mut candidates)
                    })
                    .unwrap_or_else(|| {
                        self.accel
                            .beam_candidates(prims, beam, limit, &mut candidates)
                    })
            })
            .map(|beam| {
                let origins = [Side::Above, Side::Below].map(|side| spawn.origin_on(side));
                Reachable::fill_each(
                    &mut reachable,
                    &scene.primitives,
                    &beam,
                    &candidates,
                    &origins,
                );
                [&reachable[0], &reachable[1]]
            });
        let weighting = SampleWeighting {
            share,
            known,
            only,
            cut: None,
        };
        let done = match (quad, known, self.lanes) {
            (Some(quad), None, true) => {
                self.quad_light_lanes(color, shading, &quad, &points, count, share, &surface, only)
            }
            _ => (0..count).all(|s| {
                if s % SHADOW_RAYS_PER_CANCEL_CHECK == 0 && self.cancelled() {
                    return false;
                }
                let sample = light.sample(shading.point, points.point(s));
                self.add_sample(color, shading, light, &surface, &sample, &weighting);
                true
            }),
        };
        self.candidates = candidates;
        self.reachable = reachable;
        done
    }

    /// Adds to `color` the diffuse and highlight terms of one light sample (of a light whose own
    /// primitives are `surface`), weighted and seen as `weighting` says. Nothing for a sample
    /// behind the side of the surface we see: no shadow ray is traced for it.
    #[inline(always)]
    pub(super) fn add_sample(
        &mut self,
        color: &mut Vec3,
        shading: &Shading,
        light: &Light,
        surface: &Range<u32>,
        sample: &LightSample,
        weighting: &SampleWeighting,
    ) {
        let SampleWeighting {
            share,
            known,
            only,
            cut,
        } = *weighting;
        let to_light = sample.position - shading.point;
        if to_light.dot(shading.n) <= 0.0 {
            return; // the light is behind the side we see: no shadow ray needed
        }
        let d2 = to_light.length_squared();
        let intensity = light.intensity();
        let l = to_light / d2.sqrt();
        // The sample's terms as if nothing were in the way; the transmittance only scales them.
        let unblocked = share * sample.weight * intensity.falloff(sample.falloff_d2);
        let n_dot_l = shading.ns.dot(l).max(0.0);
        let diffuse = shading.kd_base * intensity.diffuse;
        let highlight_terms = || {
            let h = (l + shading.v).normalize_or_zero();
            let spec = highlight(shading.ns.dot(h).max(0.0), shading.exponent);
            (shading.ks_specular * intensity.specular, spec)
        };
        let mut terms = None;
        if let Some(least) = cut {
            if may_be_negligible(unblocked, n_dot_l, diffuse, least) {
                let (specular, spec) = if shading.has_highlight {
                    *terms.insert(highlight_terms())
                } else {
                    (Vec3::ZERO, 0.0)
                };
                if negligible(unblocked, n_dot_l, diffuse, spec, specular, least) {
                    return; // e.g. a mirror or glass away from its highlight: no shadow ray
                }
            }
        }
        let visibility = match known {
            Some(v) => v,
            None => self.transmittance(shading.spawn, sample.position, surface, only),
        };
        if visibility == 0.0 {
            return;
        }
        let e = unblocked * visibility;
        *color += diffuse * (n_dot_l * e);
        if shading.has_highlight {
            let (specular, spec) = terms.unwrap_or_else(highlight_terms);
            *color += specular * (spec * e);
        }
    }

    /// Adaptive area-light sampling: the transmittance the light's probe points all see from
    /// the shading point, or `None` when they disagree or a probe point is behind the surface.
    pub(super) fn uniform_visibility(
        &mut self,
        shading: &Shading,
        light: &Light,
        surface: &Range<u32>,
    ) -> Option<f32> {
        let mut seen = None;
        for u in ADAPTIVE_PROBES {
            let p = light.sample(shading.point, u).position;
            if (p - shading.point).dot(shading.n) <= 0.0 {
                return None;
            }
            let v = self.transmittance(shading.spawn, p, surface, None);
            match seen {
                None => seen = Some(v),
                Some(s) if s != v => return None,
                Some(_) => {}
            }
        }
        seen
    }
}
