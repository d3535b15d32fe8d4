//! The transmittance of a shadow ray: one any-hit query for most rays, and a walk through the
//! transmissive surfaces crossed, one closest hit at a time, for rays through tinted glass.

use super::LIGHT_CLEARANCE;
use crate::accel::Reachable;
use crate::math::Vec3;
use crate::ray::{Ray, Side, SpawnPoints};
use crate::scene::Scene;
use std::ops::Range;

use super::*;

/// Most transmissive surfaces a shadow ray passes through before it counts as blocked.
pub(super) const MAX_SHADOW_CROSSINGS: u32 = 32;

/// What a shadow ray's any-hit query notes of the surfaces it hits, in a scene with transmissive
/// ones: how many it passes (its own light's and transmissive ones), whether any is
/// transmissive, and whether every one of those lets everything through (`kt = 1`).
#[derive(Debug, Clone, Copy)]
pub(super) struct ShadowCrossings {
    passed: u32,
    crosses: bool,
    clear: bool,
}

impl Default for ShadowCrossings {
    fn default() -> ShadowCrossings {
        ShadowCrossings {
            passed: 0,
            crosses: false,
            clear: true,
        }
    }
}

impl ShadowCrossings {
    /// Notes a hit on primitive `p`: whether it stops the ray, as an opaque surface that is not
    /// part of the light (`surface`) does.
    #[inline]
    pub(super) fn blocked_by(&mut self, scene: &Scene, surface: &Range<u32>, p: u32) -> bool {
        self.passed += 1;
        if surface.contains(&p) {
            return false;
        }
        let material = &scene.materials[scene.primitives.material(p) as usize];
        let transmissive = material.is_transmissive();
        self.crosses |= transmissive;
        self.clear &= material.kt == 1.0;
        !transmissive
    }

    /// Whether a ray that nothing blocked sees all of the light without walking its crossings:
    /// with no transmissive surface on the way, or only ones of kt = 1 that the walk could not
    /// cross more than its limit of times (a primitive is crossed at most twice by a line), the
    /// product is 1.
    #[inline]
    pub(super) fn settled(&self) -> bool {
        !self.crosses || (self.clear && 2 * self.passed <= MAX_SHADOW_CROSSINGS)
    }
}

impl Whitted<'_> {
    /// Fraction of light reaching the shading point of `from` from `target`: 0 behind an opaque
    /// surface, multiplied by `kt` for every transmissive surface crossed. The primitives in
    /// `surface` (the light's own, for a shape that emits) are passed through: a light is never
    /// its own shadow.
    ///
    /// One any-hit query answers most rays: it stops at the first opaque blocker (the answer is
    /// 0, whatever else lies on the way) and notes the transmissive surfaces the ray crosses; when
    /// it crosses none, or only surfaces of `kt = 1` (a product of ones, whatever their order
    /// and number within the crossing limit), the answer is 1. Only rays through glass of
    /// `kt < 1` and nothing opaque walk their crossings one closest hit at a time, as the
    /// product of `kt` needs.
    ///
    /// `only`, where given, lists every primitive the ray can meet when it leaves from either
    /// spawn origin (see [`Beam`]; [`Side`] as index); the any-hit query tests just those, and a
    /// ray that can meet none is not traced: its answer is 1.
    pub(super) fn transmittance(
        &mut self,
        from: &SpawnPoints,
        target: Vec3,
        surface: &Range<u32>,
        only: Option<[&Reachable; 2]>,
    ) -> f32 {
        self.counts.shadow += 1;
        let side = from.side_to(target);
        let only = only.map(|lists| lists[side as usize]);
        if only.is_some_and(|c| c.is_empty()) {
            return 1.0; // what the query below answers when it has nothing to test
        }
        let (ray, dist) = from.ray_from(side, target);
        self.transmittance_along(&ray, dist, only, from, target, surface)
    }

    /// [`Whitted::transmittance`] for the ray `from` builds towards `target` (its
    /// [`SpawnPoints::ray_to`], `dist` long), already found (and counted), where `only` is the
    /// list of its side.
    #[inline(always)]
    pub(super) fn transmittance_along(
        &mut self,
        ray: &Ray,
        dist: f32,
        only: Option<&Reachable>,
        from: &SpawnPoints,
        target: Vec3,
        surface: &Range<u32>,
    ) -> f32 {
        let scene = self.scene;
        let t_max = dist * (1.0 - LIGHT_CLEARANCE);
        if !scene.has_transmissive {
            let blocked = self.any_hit(only, ray, t_max, |p| !surface.contains(&p));
            return if blocked { 0.0 } else { 1.0 };
        }
        let mut crossings = ShadowCrossings::default();
        if self.any_hit(only, ray, t_max, |p| {
            crossings.blocked_by(scene, surface, p)
        }) {
            return 0.0;
        }
        if crossings.settled() {
            return 1.0;
        }
        self.walk_crossings(from, target, surface)
    }

    /// Whether `ray` hits a primitive for which `blocks` holds before `t_max`: among `only`
    /// where given (see [`Whitted::transmittance`]), else through the accelerator. Generic over
    /// `blocks`, so that each caller's test is inlined into the query, not called through a
    /// pointer at every primitive hit.
    #[inline(always)]
    pub(super) fn any_hit(
        &self,
        only: Option<&Reachable>,
        ray: &Ray,
        t_max: f32,
        blocks: impl FnMut(u32) -> bool,
    ) -> bool {
        match only {
            Some(candidates) => candidates.any(ray, t_max, blocks),
            None => self.accel.any(&self.scene.primitives, ray, t_max, blocks),
        }
    }

    /// The transmittance towards `target` one closest hit at a time: the product of the `kt`
    /// of every surface crossed (the light's own passed through), 0 at an opaque one or past
    /// [`MAX_SHADOW_CROSSINGS`] crossings. What [`Whitted::transmittance`] falls back to for rays
    /// through glass of `kt < 1`.
    pub(super) fn walk_crossings(
        &mut self,
        from: &SpawnPoints,
        target: Vec3,
        surface: &Range<u32>,
    ) -> f32 {
        let scene = self.scene;
        let prims = &scene.primitives;
        let (mut ray, dist) = from.ray_to(target);
        let mut t_max = dist * (1.0 - LIGHT_CLEARANCE);
        let mut through = 1.0;
        let mut inside = None;
        for _ in 0..MAX_SHADOW_CROSSINGS {
            let found = match inside {
                Some(i) => self.interiors.closest(self.accel, prims, i, &ray, t_max),
                None => self.accel.closest(prims, &ray, t_max),
            };
            let Some((p, c)) = found else {
                return through;
            };
            let prim = &prims.get(p);
            let material = &scene.materials[prim.material as usize];
            if !surface.contains(&p) {
                if !material.is_transmissive() {
                    return 0.0;
                }
                through *= material.kt;
            }
            let h = prim.hit_with(&ray, c, p, prims.meshes(), false);
            let spawn = h.spawn_points();
            let side = spawn.side_to(target);
            let (next, d) = spawn.ray_from(side, target);
            inside = self.interiors.of(p).filter(|_| side == Side::Below);
            ray = next;
            t_max = d * (1.0 - LIGHT_CLEARANCE);
        }
        0.0
    }
}
