//! A quad light's samples from one shading point, four at a time in SIMD lanes: the sample
//! points, the shadow rays (built by [`SpawnPoints::rays_to4`] and tested four at a time against
//! each of the beam's spheres by [`Rays4`]), and the light terms. Lane by lane every value is the
//! one-sample loop's ([`Whitted::shade`]), operation for operation, and the terms are added to
//! the colour one sample after another in the loop's order, so the picture has the same bits
//! (the tests below hold the two to each other pixel by pixel on a scene with every kind of
//! blocker, and `tests/golden.rs` holds the pictures).
//!
//! What lanes do not pay for stays one lane at a time: the sample points' hashes (64-bit
//! multiplications), shapes other than spheres, and the rare shadow ray that must walk its
//! crossings through glass of `kt < 1`.

use glam::Vec4;

use super::Whitted;
use crate::accel::kernels::Rays4;
use crate::accel::Reachable;
use crate::geometry::Shape;
use crate::light::{Intensity, Light};
use crate::material::highlight4;
use crate::math::{dot4 as dot, splat4 as splat, sqrt4, Vec3};
use crate::ray::{PreparedRay, Ray, SpawnPoints};
use crate::sampling::PointSet;

use super::super::LIGHT_CLEARANCE;
use super::{ShadowCrossings, SHADOW_RAYS_PER_CANCEL_CHECK};

/// The quad light `origin + s·edge_u + t·edge_v`.
pub(super) struct Quad<'l> {
    origin: Vec3,
    edge_u: Vec3,
    edge_v: Vec3,
    intensity: &'l Intensity,
}

impl Quad<'_> {
    /// `light`, if it is a quad.
    pub fn of(light: &Light) -> Option<Quad<'_>> {
        match light {
            Light::Quad {
                origin,
                edge_u,
                edge_v,
                intensity,
                ..
            } => Some(Quad {
                origin: *origin,
                edge_u: *edge_u,
                edge_v: *edge_v,
                intensity,
            }),
            _ => None,
        }
    }

    /// Whether every point of the quad lies behind the plane through `point` with normal `n`
    /// by a margin far above rounding: then every sample's `to_light · n` comes out negative,
    /// in the lanes and in the one-sample loop alike, and the light adds nothing there.
    ///
    /// The exact `(q − point) · n` is linear in `q`, so over the parallelogram it is largest at
    /// a corner; the corners' values are taken in `f64`. A sample's computed value differs
    /// from its exact one by a few `f32` roundings of coordinates of size at most `scale`
    /// (about 10⁻⁶·`scale` for a unit `n`), and the margin is 10⁻⁴·`scale`.
    pub fn wholly_behind(&self, point: Vec3, n: Vec3) -> bool {
        let scale = [point, self.origin, self.edge_u, self.edge_v]
            .iter()
            .map(|v| f64::from(v.abs().max_element()))
            .sum::<f64>()
            * f64::from(n.abs().max_element());
        let (p, n) = (point.as_dvec3(), n.as_dvec3());
        let (o, u, v) = (
            self.origin.as_dvec3(),
            self.edge_u.as_dvec3(),
            self.edge_v.as_dvec3(),
        );
        let margin = 1e-4 * scale;
        // NaN compares false: a non-finite quad or point is never behind.
        [o, o + u, o + v, o + u + v]
            .iter()
            .all(|&c| (c - p).dot(n) < -margin)
    }

    /// Whether any of samples `0..count` of the quad (each of `share` of the light) can add to the
    /// colour of a shading point whose diffuse term is zero (`kd · base · id = 0`, a mirror or
    /// glass): one in front of the surface whose highlight is not zero, or whose strength is not
    /// finite. Where none can, every sample's terms are zeros whatever its visibility
    /// ([`negligible`](super::negligible)'s exact case), and the light needs no shadow ray, beam
    /// or probe. The arithmetic is the lanes' (and so the one-sample loop's), so the answer is
    /// theirs to the bit.
    pub fn highlight_may_show(
        &self,
        s: &Shading,
        points: &PointSet,
        count: u32,
        share: f32,
    ) -> bool {
        let (origin, edge_u, edge_v) = (splat(self.origin), splat(self.edge_u), splat(self.edge_v));
        let (point, n, ns, v) = (splat(s.point), splat(s.n), splat(s.ns), splat(s.v));
        let specular = s.ks_specular * self.intensity.specular;
        let lit = s.has_highlight && specular != Vec3::ZERO;
        (0..count).step_by(4).any(|first| {
            let lanes = (count - first).min(4);
            let target = targets(points, first, lanes, origin, edge_u, edge_v);
            let (to_light, live) = in_front(&target, lanes, point, n);
            if live == 0 {
                return false;
            }
            let d2 = dot(&to_light, &to_light);
            let unblocked = Vec4::splat(share * 1.0) * self.intensity.falloff4(d2);
            let mut shows = !unblocked.is_finite_mask().bitmask();
            if lit {
                let l_dir = to_light.map(|c| c / sqrt4(d2));
                let spec = highlights(&l_dir, ns, v, s.exponent);
                shows |= spec.cmpne(Vec4::ZERO).bitmask();
            }
            live & shows != 0
        })
    }
}

/// What the light terms of one shading point share.
pub(super) struct Shading<'s> {
    pub point: Vec3,
    pub spawn: &'s SpawnPoints,
    /// The geometric normal turned towards the viewer (what decides whether a sample is behind
    /// the surface we see).
    pub n: Vec3,
    /// The shading normal, turned the same way.
    pub ns: Vec3,
    /// Towards the viewer.
    pub v: Vec3,
    /// `kd · base` and `ks · specular`: the material's factors of the two terms.
    pub kd_base: Vec3,
    pub ks_specular: Vec3,
    /// Whether there is a highlight (`ks > 0`), and its exponent.
    pub has_highlight: bool,
    pub exponent: f32,
}

#[inline(always)]
fn lane(v: &[Vec4; 3], l: usize) -> Vec3 {
    Vec3::new(v[0][l], v[1][l], v[2][l])
}

/// `Light::sample` of a quad for samples `first..first + lanes` of `points`, in lanes: the
/// targets of their shadow rays.
#[inline(always)]
fn targets(
    points: &PointSet,
    first: u32,
    lanes: u32,
    origin: [Vec4; 3],
    edge_u: [Vec4; 3],
    edge_v: [Vec4; 3],
) -> [Vec4; 3] {
    let mut ux = Vec4::ZERO;
    let mut uy = Vec4::ZERO;
    for l in 0..lanes as usize {
        let u = points.point(first + l as u32);
        ux[l] = u.x;
        uy[l] = u.y;
    }
    [0, 1, 2].map(|a| origin[a] + ux * edge_u[a] + uy * edge_v[a])
}

/// The directions from the shading point `point` to the four `target`s, and the mask of the
/// first `lanes` of them in front of the surface of normal `n` (the one-sample loop's
/// `to_light · n > 0`).
#[inline(always)]
fn in_front(target: &[Vec4; 3], lanes: u32, point: [Vec4; 3], n: [Vec4; 3]) -> ([Vec4; 3], u32) {
    let to_light = [0, 1, 2].map(|a| target[a] - point[a]);
    let behind = dot(&to_light, &n).cmple(Vec4::ZERO).bitmask();
    (to_light, ((1u32 << lanes) - 1) & !behind)
}

/// The Blinn-Phong highlight `max(0, n·h)^exponent` of four unit directions `l_dir` towards the
/// light, with `h = normalize_or_zero(l + v)`, lane by lane the bits of the one-sample loop.
#[inline(always)]
fn highlights(l_dir: &[Vec4; 3], ns: [Vec4; 3], v: [Vec4; 3], exponent: f32) -> Vec4 {
    let h = [0, 1, 2].map(|a| l_dir[a] + v[a]);
    let rcp = Vec4::ONE / sqrt4(dot(&h, &h));
    let ok = rcp.abs().cmplt(Vec4::INFINITY) & rcp.cmpgt(Vec4::ZERO);
    let h = h.map(|c| Vec4::select(ok, c * rcp, Vec4::ZERO));
    highlight4(dot(&ns, &h).max(Vec4::ZERO), exponent)
}

impl Whitted<'_> {
    /// Adds to `color` the terms of samples `0..count` of `quad` (each of `share` of the light,
    /// `points` their points), as the one-sample loop does; `reachable` lists, per side the
    /// shadow rays leave from, the primitives they may meet. `false` if the render was cancelled
    /// on the way (then `color` holds the samples before).
    ///
    /// Kept out of line so that its lane set-up is not hoisted into every shading point of
    /// [`Whitted::shade`], point lights' included.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    pub(super) fn quad_light_lanes(
        &mut self,
        color: &mut Vec3,
        s: &Shading,
        quad: &Quad,
        points: &PointSet,
        count: u32,
        share: f32,
        surface: &std::ops::Range<u32>,
        reachable: Option<[&Reachable; 2]>,
    ) -> bool {
        let intensity = quad.intensity;
        let diffuse = s.kd_base * intensity.diffuse;
        let specular = s.ks_specular * intensity.specular;
        let (origin, edge_u, edge_v) = (splat(quad.origin), splat(quad.edge_u), splat(quad.edge_v));
        let (point, n, ns, v) = (splat(s.point), splat(s.n), splat(s.ns), splat(s.v));
        for first in (0..count).step_by(4) {
            if first % SHADOW_RAYS_PER_CANCEL_CHECK == 0 && self.cancelled() {
                return false;
            }
            let lanes = (count - first).min(4);
            let target = targets(points, first, lanes, origin, edge_u, edge_v);
            let (to_light, live) = in_front(&target, lanes, point, n);
            if live == 0 {
                continue;
            }
            let d2 = dot(&to_light, &to_light);
            let visibility = self.transmittance4(s.spawn, target, live, surface, reachable);
            // The terms, in lanes, of the samples that see the light.
            let l_dir = to_light.map(|c| c / sqrt4(d2));
            let n_dot_l = dot(&ns, &l_dir).max(Vec4::ZERO);
            let spec = if s.has_highlight {
                highlights(&l_dir, ns, v, s.exponent)
            } else {
                Vec4::ZERO
            };
            // `sample.weight` is 1 for a quad.
            let e =
                Vec4::splat(share * 1.0) * intensity.falloff4(d2) * Vec4::from_array(visibility);
            let (fd, fs) = (n_dot_l * e, spec * e);
            for l in 0..lanes as usize {
                if live & (1 << l) == 0 || visibility[l] == 0.0 {
                    continue;
                }
                *color += diffuse * fd[l];
                if s.has_highlight {
                    *color += specular * fs[l];
                }
            }
        }
        true
    }

    /// [`Whitted::transmittance`] towards four targets (the lanes `live` of `target`), lane by
    /// lane the same answer.
    fn transmittance4(
        &mut self,
        spawn: &SpawnPoints,
        target: [Vec4; 3],
        live: u32,
        surface: &std::ops::Range<u32>,
        reachable: Option<[&Reachable; 2]>,
    ) -> [f32; 4] {
        let mut answer = [1.0f32; 4];
        let Some(reachable) = reachable else {
            // No beam: each ray queries the whole accelerator.
            if live.count_ones() == 1 {
                let l = live.trailing_zeros() as usize;
                answer[l] = self.transmittance(spawn, lane(&target, l), surface, None);
                return answer;
            }
            // Rays built in lanes, with the bits `SpawnPoints::ray_to` gives each (the sides'
            // normalisations and the lengths four at a time, rather than one ray's chain of
            // square roots and divisions after another's).
            self.counts.shadow += live.count_ones() as u64;
            let rays = spawn.rays_to4(target);
            for (l, a) in answer.iter_mut().enumerate() {
                if live & (1 << l) != 0 {
                    let ray = Ray::new(lane(&rays.origin, l), lane(&rays.dir, l));
                    let (to, dist) = (lane(&target, l), rays.dist[l]);
                    *a = self.transmittance_along(&ray, dist, None, spawn, to, surface);
                }
            }
            return answer;
        };
        let scene = self.scene;
        self.counts.shadow += live.count_ones() as u64;
        if reachable.iter().all(|list| list.is_empty()) {
            return answer; // nothing any ray could meet: what the loop below finds
        }
        let rays = spawn.rays_to4(target);
        let t_max = rays.dist * Vec4::splat(1.0 - LIGHT_CLEARANCE);
        // A bound that is NaN or not positive finds nothing (`Reachable::any`): the answer is 1.
        let valid = live & t_max.cmpgt(Vec4::ZERO).bitmask();
        let rays4 = Rays4::new(rays.origin, rays.dir);
        // Lanes an opaque primitive stops.
        let mut blocked = 0u32;
        for (side, list) in reachable.iter().enumerate() {
            let below = if side == 1 { rays.below } else { !rays.below };
            let mut open = valid & below;
            if open == 0 || list.is_empty() {
                continue;
            }
            // What the any-hit query's filter notes on the way, per lane.
            let mut crossings = [ShadowCrossings::default(); 4];
            // Each lane's ray, prepared for shapes the lanes do not test, when first needed.
            let mut prepared: [Option<PreparedRay>; 4] = [None; 4];
            for (p, shape) in list.iter() {
                if open == 0 {
                    break;
                }
                let hit = match shape {
                    Shape::Sphere(sphere) => rays4.hit_sphere(sphere, t_max) & open,
                    shape => (0..4)
                        .filter(|&l| open & (1 << l) != 0)
                        .filter(|&l| {
                            let r = prepared[l].get_or_insert_with(|| {
                                PreparedRay::new(&Ray::new(
                                    lane(&rays.origin, l),
                                    lane(&rays.dir, l),
                                ))
                            });
                            shape.intersect_prepared(r, t_max[l]).is_some()
                        })
                        .fold(0, |m, l| m | 1 << l),
                };
                if hit == 0 {
                    continue;
                }
                if !scene.has_transmissive {
                    if !surface.contains(&p) {
                        blocked |= hit;
                        open &= !hit;
                    }
                    continue;
                }
                for (l, crossings) in crossings.iter_mut().enumerate() {
                    if hit & (1 << l) != 0 && crossings.blocked_by(scene, surface, p) {
                        blocked |= 1 << l;
                        open &= !(1 << l);
                    }
                }
            }
            // Rays through transmissive surfaces that `transmittance`'s shortcut does not settle
            // walk their crossings one at a time, as there.
            for (l, a) in answer.iter_mut().enumerate() {
                if open & (1 << l) != 0 && !crossings[l].settled() {
                    *a = self.walk_crossings(spawn, lane(&target, l), surface);
                }
            }
        }
        for (l, a) in answer.iter_mut().enumerate() {
            if blocked & (1 << l) != 0 {
                *a = 0.0;
            }
        }
        answer
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::accel::{Accel, AccelKind};
    use crate::integrator::TraceOptions;
    use crate::math::Vec2;
    use crate::sampling::{Method, SampleKey};
    use crate::scene::{load_str, LoadOptions};

    /// A quad light of `samples` over a floor, with occluders of every kind a beam may hold:
    /// opaque, mirror and glass spheres (`kt` 1 and below), a mesh box, a sphere under the
    /// light's plane and a wall through it, so that shadow rays leave from both sides.
    fn scene(samples: u32, method: &str) -> String {
        let m = |extra: &str| {
            format!(
                r#"{{"kd": 0.8, "ks": 0.4, "specularexponent": 30, "diffusecolor": [0.8, 0.6, 0.4] {extra}}}"#
            )
        };
        format!(
            r#"{{
  "nbounces": 3,
  "camera": {{"type": "pinhole", "width": 40, "height": 30, "fov": 50,
              "position": [0, 3, 7], "lookat": [0, -0.4, -1], "up": [0, 1, 0]}},
  "scene": {{
    "backgroundcolor": [0.1, 0.1, 0.1],
    "lightsources": [
      {{"type": "arealight", "v0": [-1, 3, -1], "v1": [1, 3, -1], "v2": [1, 3, 1], "v3": [-1, 3, 1],
        "samples": {samples}, "method": "{method}", "is": [60, 60, 60], "id": [60, 60, 60]}}
    ],
    "shapes": [
      {{"type": "plane", "v0": [-5, 0, 5], "v1": [5, 0, 5], "v2": [5, 0, -5], "v3": [-5, 0, -5],
        "material": {m0}}},
      {{"type": "plane", "v0": [2, -1, -3], "v1": [2, 4, -3], "v2": [2, 4, 3], "v3": [2, -1, 3],
        "material": {m0}}},
      {{"type": "sphere", "center": [-1.5, 0.6, 0], "radius": 0.6, "material": {m0}}},
      {{"type": "sphere", "center": [0, 0.7, 0.5], "radius": 0.5,
        "material": {glass}}},
      {{"type": "sphere", "center": [0.8, 1.2, -0.5], "radius": 0.4,
        "material": {clear}}},
      {{"type": "sphere", "center": [-0.5, 1.8, -0.8], "radius": 0.3,
        "material": {mirror}}},
      {{"type": "sphere", "center": [0.3, 3.2, 0.2], "radius": 0.3, "material": {m0}}},
      {{"type": "trimesh",
        "vertices": [[0.6, 0, 0.8], [1.2, 0, 0.8], [1.2, 0, 1.4], [0.6, 0, 1.4],
                     [0.6, 0.8, 0.8], [1.2, 0.8, 0.8], [1.2, 0.8, 1.4], [0.6, 0.8, 1.4]],
        "faces": [[0, 1, 2, 3], [4, 7, 6, 5], [0, 4, 5, 1], [1, 5, 6, 2], [2, 6, 7, 3], [3, 7, 4, 0]],
        "material": {m0}}}
    ]
  }}
}}"#,
            m0 = m(""),
            glass = m(r#", "isrefractive": true, "refractiveindex": 1.5, "kt": 0.7"#),
            clear = m(r#", "isrefractive": true, "refractiveindex": 1.0, "kt": 1.0"#),
            mirror = m(r#", "isreflective": true, "reflectivity": 0.8"#),
        )
    }

    /// `Quad::highlight_may_show` answers what the one-sample loop's own terms say: whether some
    /// sample in front of a mirror-like point (no diffuse term, a sharp highlight) has a highlight
    /// that is not zero, on points all over a sphere seen from all around, near the light and
    /// far from it.
    #[test]
    fn the_highlight_check_agrees_with_the_one_sample_terms() {
        let text = scene(4, "jittered");
        let scene = load_str(&text, Path::new("lanes.json"), &LoadOptions::default()).unwrap();
        let light = &scene.lights[0];
        let quad = Quad::of(light).unwrap();
        let (count, share) = (16, 1.0 / 16.0);
        let (mut shows, mut dark) = (0, 0);
        for k in 0..4000u32 {
            // Points on a sphere under the light, normals outward, eyes on a wider sphere.
            let f = |i: u32, m: f32| (i as f32 * m).fract();
            let dir = |a: f32, b: f32| {
                let (z, phi) = (2.0 * a - 1.0, std::f32::consts::TAU * b);
                let r = (1.0 - z * z).max(0.0).sqrt();
                Vec3::new(r * phi.cos(), z, r * phi.sin())
            };
            let normal = dir(f(k, 0.618_034), f(k, 0.754_878));
            let centre = Vec3::new(0.0, 1.0 + 1.5 * f(k, 0.569_84), 0.0);
            let point = centre + 0.5 * normal;
            let eye = centre + 4.0 * dir(f(k, 0.412_454), f(k, 0.245_122));
            let v = (eye - point).normalize();
            let hit = crate::ray::Hit {
                t: 1.0,
                point,
                error: Vec3::ZERO,
                normal,
                shading_normal: normal,
                uv: Vec2::ZERO,
                prim: 0,
            };
            let spawn = hit.spawn_points();
            let (n, ns) = if normal.dot(v) > 0.0 {
                (normal, normal)
            } else {
                (-normal, -normal)
            };
            let shading = Shading {
                point,
                spawn: &spawn,
                n,
                ns,
                v,
                kd_base: Vec3::ZERO,
                ks_specular: Vec3::splat(0.6),
                has_highlight: true,
                exponent: [200.0, 30.0, 1000.0][k as usize % 3],
            };
            let points =
                SampleKey::new(k, 0, 0, 1, 7)
                    .stream(0)
                    .point_set(Method::Jittered, 0, count);
            let check = quad.highlight_may_show(&shading, &points, count, share);
            // The one-sample loop's terms, sample by sample.
            let any = (0..count).any(|i| {
                let sample = light.sample(point, points.point(i));
                let to_light = sample.position - point;
                if to_light.dot(n) <= 0.0 {
                    return false;
                }
                let l = to_light / to_light.length_squared().sqrt();
                let falloff = light.intensity().falloff(sample.falloff_d2);
                let unblocked = share * sample.weight * falloff;
                let h = (l + v).normalize_or_zero();
                let spec = crate::material::highlight(ns.dot(h).max(0.0), shading.exponent);
                spec != 0.0 || !unblocked.is_finite()
            });
            assert_eq!(check, any, "point {point}, eye {eye}");
            if any {
                shows += 1;
            } else {
                dark += 1;
            }
        }
        assert!(shows > 200 && dark > 200, "{shows} showing, {dark} dark");
    }

    /// Where `Quad::wholly_behind` holds, every sample of the light, as the one-sample loop and
    /// the lanes place it, is behind the surface; it holds for most quads that are, and not for
    /// quads that reach in front, even by a sliver.
    #[test]
    fn a_quad_wholly_behind_has_every_sample_behind() {
        let f = |i: u32, m: f32| (i as f32 * m).fract();
        let (mut behind, mut held) = (0, 0);
        for k in 0..20_000u32 {
            // A unit normal, a point far from or near the origin, a quad above or below its
            // plane (some straddling it, some touching it at a corner).
            let a = std::f32::consts::TAU * f(k, 0.618_034);
            let z = 2.0 * f(k, 0.754_878) - 1.0;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let n = Vec3::new(r * a.cos(), z, r * a.sin());
            let point =
                Vec3::new(f(k, 0.3), f(k, 0.7), f(k, 0.11)) * [1.0, 1e3, 1e-2][k as usize % 3];
            let tangent = n.any_orthonormal_vector();
            let height = (f(k, 0.569_84) - 0.6) * 2.0;
            let origin = point + n * height + tangent * (f(k, 0.41) - 0.5) * 3.0;
            let edge_u = tangent * (0.5 + f(k, 0.245)) + n * (f(k, 0.83) - 0.5) * 0.2;
            let edge_v = n.cross(tangent) * (0.5 + f(k, 0.37)) + n * (f(k, 0.29) - 0.5) * 0.2;
            let intensity = Intensity {
                diffuse: Vec3::ONE,
                specular: Vec3::ONE,
                falloff: crate::light::Falloff::Polynomial {
                    kc: 1.0,
                    kl: 0.0,
                    kq: 0.0,
                },
            };
            let quad = Quad {
                origin,
                edge_u,
                edge_v,
                intensity: &intensity,
            };
            // The corners and a grid of samples over the parallelogram, in lanes as the loop
            // places them.
            let splats = (splat(origin), splat(edge_u), splat(edge_v));
            let grid = (0..=16).flat_map(|i| (0..=16).map(move |j| (i, j)));
            let all_behind = grid.clone().all(|(i, j)| {
                let (ux, uy) = (Vec4::splat(i as f32 / 16.0), Vec4::splat(j as f32 / 16.0));
                let (o, eu, ev) = splats;
                let target = [0, 1, 2].map(|a| o[a] + ux * eu[a] + uy * ev[a]);
                in_front(&target, 1, splat(point), splat(n)).1 == 0
            });
            let claimed = quad.wholly_behind(point, n);
            if claimed {
                held += 1;
                assert!(
                    all_behind,
                    "n {n}, point {point}, quad {origin} {edge_u} {edge_v}"
                );
            }
            behind += usize::from(all_behind);
        }
        // It finds most of the quads that are behind (the margin gives up only the ones that
        // touch the plane), and some are not.
        assert!(held > 4000 && held * 10 > behind * 9, "{held} of {behind}");
        assert!(behind < 18_000, "{behind}");
    }

    /// Every pixel's radiance with the lanes and with the one-sample loop, bit for bit.
    fn lanes_equal_the_loop(text: &str, accel: AccelKind, cutoff: Option<f32>) -> u64 {
        let scene = load_str(text, Path::new("lanes.json"), &LoadOptions::default()).unwrap();
        let accel = Accel::build(&scene.primitives, accel, 4);
        let interiors = super::super::interiors(&scene, &accel);
        let options = TraceOptions {
            cutoff,
            ..Default::default()
        };
        let mut lanes = Whitted::new(&scene, &accel, &interiors, 8, options, Method::Jittered);
        let mut one = Whitted::new(&scene, &accel, &interiors, 8, options, Method::Jittered);
        one.lanes = false;
        super::super::tests::for_each_pixel_centre(&scene, |x, y, key, ray| {
            let a = lanes.trace_camera(ray, key);
            let b = one.trace_camera(ray, key);
            assert_eq!(
                a.to_array().map(f32::to_bits),
                b.to_array().map(f32::to_bits),
                "pixel ({x}, {y}): lanes {a}, one at a time {b}"
            );
        });
        assert_eq!(lanes.counts.shadow, one.counts.shadow);
        lanes.counts.shadow
    }

    #[test]
    fn lanes_give_the_one_sample_loops_bits() {
        for (samples, method) in [
            (4, "jittered"),
            (3, "random"),
            (2, "sobol"),
            (5, "jittered"),
        ] {
            for accel in [AccelKind::None, AccelKind::Sah4] {
                for cutoff in [None, Some(crate::integrator::DEFAULT_CUTOFF)] {
                    let rays = lanes_equal_the_loop(&scene(samples, method), accel, cutoff);
                    assert!(rays > 1000, "{rays} shadow rays");
                }
            }
        }
    }
}
