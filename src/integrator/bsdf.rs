//! Scattering at a surface, for the path tracer: the scene's materials as energy-conserving BSDFs.
//!
//! A material of base colour `c` (its texture, or `diffusecolor`) becomes the mixture
//!
//! ```text
//! f = s·(ρd/π + ρg·N(e)·cos^e θh)  +  r·(perfect mirror)  +  t·(smooth dielectric)
//! ```
//! with `ρd = kd·c`, `ρg = ks·specularcolor`, `e` = `specularexponent`, `θh` the angle between the
//! shading normal and the half vector of the two directions, and the lobe weights
//! - `r` = `reflectivity` (`kr`) of a reflective material, at most 1 (the mirror reflects the
//!   colour `mirror`: a metal's `albedo`, else white). A rough mirror (a finite
//!   `mirror_exponent`, from the material's `roughness`) is a normalised Blinn-Phong lobe of that
//!   exponent in place of the delta: `r·mirror·N(e_m)·cos^e_m θh`;
//! - `t` = the transmission `kt` of a refractive one (`isrefractive`), at most `1 − r`;
//! - `s = 1 − r − t` for the surface's own diffuse and glossy reflection.
//!
//! The glossy lobe is Blinn-Phong normalised by Giesen's factor
//! `N(e) = (e+2)(e+4) / (8π (2^(−e/2) + e))` (F. Giesen, "Derivation of the normalization factor
//! for Blinn-Phong", 2009), which makes its directional albedo exactly 1 at normal incidence; it is
//! lower at every other angle (checked by the tests here), so the lobe never reflects more than
//! it receives. **Energy is conserved** by scaling `ρd` and `ρg` together so that
//! `max over channels of (ρd + ρg) ≤ 1`, and the three lobe weights sum to one. The smooth lobes
//! and the rough mirror are symmetric in the two directions (reciprocal); the perfect mirror
//! reflects about the geometric normal and the dielectric splits by the exact Fresnel
//! reflectance, refracting by Snell's law (total internal reflection included; no absorption).
//! Sampling picks a lobe with the probability of its weight, so a mirror of reflectance `r` and
//! a surface of weight `1 − r` stay unbiased together; a direction drawn from any lobe that is
//! not a delta carries the density of all of them (the one-sample mixture), which is what MIS
//! against light samples needs.
//!
//! `ka` and the scene's ambient light belong to Whitted shading and are not used here.

use crate::material::{highlight, Material, Shares};
use crate::math::{fresnel_dielectric, local_to_world, reflect, refract, Vec2, Vec3};
use crate::sampling::blinn_phong_half_vector;

use std::f32::consts::{FRAC_1_PI, PI};

/// A sampled direction and what it carries.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BsdfSample {
    /// The new direction, away from the surface.
    pub dir: Vec3,
    /// `f · |cos θ| / pdf` (what the path throughput is multiplied by).
    pub weight: Vec3,
    /// Solid-angle density of `dir` among all the BSDF's samples (for MIS); meaningless for a
    /// delta lobe.
    pub pdf: f32,
    /// Whether the direction came from a mirror or dielectric lobe: no light sample could have
    /// chosen it.
    pub delta: bool,
}

/// The BSDF at one shading point, with directions in world space. `wo` is always the direction
/// back along the incoming ray (away from the surface).
#[derive(Debug, Clone, Copy)]
pub struct Bsdf {
    /// Shading normal, facing the side the ray came from (sampled directions are mapped from
    /// its [`local_to_world`] frame).
    n: Vec3,
    /// Geometric normal, facing the side the ray came from.
    ng: Vec3,
    diffuse: Vec3,
    glossy: Vec3,
    exponent: f32,
    /// Giesen's normalisation of the glossy lobe.
    norm: f32,
    /// Colour of the mirror lobe.
    tint: Vec3,
    /// Exponent of the mirror lobe (`INFINITY`: a delta) and its normalisation.
    mirror_exponent: f32,
    mirror_norm: f32,
    /// Lobe weights, summing to 1.
    smooth: f32,
    mirror: f32,
    glass: f32,
    /// Probability of sampling the glossy lobe within the smooth part.
    p_glossy: f32,
    /// `η_incident / η_transmitted` for light crossing from the ray's side.
    eta: f32,
    /// Colour of the light the glass lets through.
    transmit: Vec3,
}

/// Giesen's normalisation of a Blinn-Phong lobe of exponent `e ≥ 0`.
pub fn blinn_phong_norm(e: f32) -> f32 {
    (e + 2.0) * (e + 4.0) / (8.0 * PI * ((-e / 2.0).exp2() + e))
}

impl Bsdf {
    /// The BSDF of `material` with base colour `base`, for a ray that arrived from the side of
    /// `ng` (the geometric normal, turned towards the ray's origin) at a point with shading
    /// normal `ns` (turned the same way); `front` says whether that side is the outside.
    pub fn new(material: &Material, base: Vec3, ns: Vec3, ng: Vec3, front: bool) -> Bsdf {
        let Shares {
            mirror,
            glass,
            own: smooth,
        } = material.shares();
        let mut diffuse = (material.kd * base).max(Vec3::ZERO);
        let mut glossy = (material.ks * material.specular).max(Vec3::ZERO);
        let peak = (diffuse + glossy).max_element();
        if peak > 1.0 {
            diffuse /= peak;
            glossy /= peak;
        }
        let (sd, sg) = (diffuse.element_sum(), glossy.element_sum());
        let exponent = material.exponent.max(0.0);
        let n = if ns.dot(ng) > 0.0 { ns } else { ng };
        Bsdf {
            n,
            ng,
            diffuse,
            glossy,
            exponent,
            norm: if glossy == Vec3::ZERO {
                0.0
            } else {
                blinn_phong_norm(exponent)
            },
            tint: material.mirror,
            transmit: material.transmit,
            mirror_exponent: material.mirror_exponent,
            mirror_norm: if material.mirror_exponent.is_finite() {
                blinn_phong_norm(material.mirror_exponent.max(0.0))
            } else {
                0.0
            },
            smooth,
            mirror,
            glass,
            p_glossy: if sd + sg > 0.0 { sg / (sd + sg) } else { 0.0 },
            eta: if front {
                1.0 / material.eta
            } else {
                material.eta
            },
        }
    }

    /// Whether the smooth lobes reflect anything.
    fn smooth_reflects(&self) -> bool {
        self.smooth > 0.0 && (self.diffuse + self.glossy).max_element() > 0.0
    }

    /// Whether the mirror lobe is a rough one (not a delta) and reflects anything.
    fn rough_mirror(&self) -> bool {
        self.mirror > 0.0 && self.mirror_exponent.is_finite() && self.tint.max_element() > 0.0
    }

    /// Whether a lobe that is not a delta reflects anything: only then is light sampling worth
    /// a shadow ray.
    pub fn has_non_delta(&self) -> bool {
        self.smooth_reflects() || self.rough_mirror()
    }

    /// `f(wo, wi)` of the lobes that are not deltas (a delta is 0 in every given direction),
    /// weighted by their shares.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.eval_pdf(wo, wi).0
    }

    /// The solid-angle density with which [`Bsdf::sample`] picks `wi` (the lobes' shares
    /// included).
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.eval_pdf(wo, wi).1
    }

    /// [`Bsdf::eval`] and [`Bsdf::pdf`] together, sharing the cosines and the half vector: a
    /// light sample needs both.
    pub fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        if !self.has_non_delta() {
            return (Vec3::ZERO, 0.0);
        }
        let Some(ci) = self.reflected_cosine(wo, wi) else {
            return (Vec3::ZERO, 0.0);
        };
        // The half vector's cosines with the normal and with `wo`, worked out only for a lobe
        // that needs them (a diffuse surface does not).
        let half = || {
            let h = (wo + wi).normalize_or_zero();
            (self.n.dot(h).max(0.0), wo.dot(h))
        };
        // The density of `wi` for half vectors drawn from a lobe of exponent `e`, whose value
        // at `h` is `lobe` (the Jacobian of the reflection is 1/(4·wo·h)).
        let lobe_pdf = |e: f32, lobe: f32, oh: f32| {
            if oh > 0.0 {
                (e + 1.0) / (2.0 * PI) * lobe / (4.0 * oh)
            } else {
                0.0
            }
        };
        let (mut f, mut p) = (Vec3::ZERO, 0.0);
        if self.smooth_reflects() {
            let mut fs = self.diffuse * FRAC_1_PI;
            let mut ps = (1.0 - self.p_glossy) * ci * FRAC_1_PI;
            if self.glossy != Vec3::ZERO {
                let (ch, oh) = half();
                let lobe = highlight(ch, self.exponent);
                fs += self.glossy * (self.norm * lobe);
                ps += self.p_glossy * lobe_pdf(self.exponent, lobe, oh);
            }
            f = self.smooth * fs;
            p = self.smooth * ps;
        }
        if self.rough_mirror() {
            let (ch, oh) = half();
            let lobe = highlight(ch, self.mirror_exponent);
            f += self.tint * (self.mirror * self.mirror_norm * lobe);
            p += self.mirror * lobe_pdf(self.mirror_exponent, lobe, oh);
        }
        (f, p)
    }

    /// A direction for `wo` from `u_lobe` (which lobe, and inside the dielectric which way) and
    /// `u` (where in the lobe); `None` where the path is absorbed.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if u_lobe < self.mirror {
            if self.mirror_exponent.is_finite() {
                let h = local_to_world(self.n, blinn_phong_half_vector(self.mirror_exponent, u));
                return self.scattered(wo, 2.0 * wo.dot(h) * h - wo);
            }
            return Some(BsdfSample {
                dir: reflect(-wo, self.ng).normalize(),
                weight: self.tint,
                pdf: 0.0,
                delta: true,
            });
        }
        if u_lobe < self.mirror + self.glass {
            let v = (u_lobe - self.mirror) / self.glass;
            let f = fresnel_dielectric(wo.dot(self.ng), self.eta);
            if v < f {
                return Some(BsdfSample {
                    dir: reflect(-wo, self.ng).normalize(),
                    weight: Vec3::ONE,
                    pdf: 0.0,
                    delta: true,
                });
            }
            // Radiance is squeezed into a narrower cone entering a denser medium: it scales by
            // (η_i/η_t)² along the path (pbrt-v4 §9.5.2, non-symmetric scattering).
            let dir = refract(-wo, self.ng, self.eta)?;
            return Some(BsdfSample {
                dir,
                weight: self.transmit * (self.eta * self.eta),
                pdf: 0.0,
                delta: true,
            });
        }
        if !self.smooth_reflects() {
            return None;
        }
        let v = ((u_lobe - self.mirror - self.glass) / self.smooth).clamp(0.0, 1.0);
        if v < self.p_glossy {
            let h = local_to_world(self.n, blinn_phong_half_vector(self.exponent, u));
            return self.scattered(wo, 2.0 * wo.dot(h) * h - wo);
        }
        // Cosine-weighted hemisphere (Malley's method).
        let d = crate::sampling::concentric_disk(u);
        let z = (1.0 - d.length_squared()).max(0.0).sqrt();
        let wi = local_to_world(self.n, Vec3::new(d.x, d.y, z));
        if self.p_glossy > 0.0 || self.rough_mirror() {
            return self.scattered(wo, wi);
        }
        // Diffuse is the only lobe that is not a delta: its density is the cosine's, and
        // f·cos/pdf is its albedo (what `scattered` would find, without the evaluation).
        let ci = self.reflected_cosine(wo, wi)?;
        Some(BsdfSample {
            dir: wi,
            weight: self.diffuse,
            pdf: self.smooth * (ci * FRAC_1_PI),
            delta: false,
        })
    }

    /// `cos θi` against the shading normal where `wo` and `wi` both lie on the side the ray came
    /// from, for the geometric and the shading normal alike (only there do the lobes that are
    /// not deltas reflect); `None` elsewhere.
    #[inline]
    fn reflected_cosine(&self, wo: Vec3, wi: Vec3) -> Option<f32> {
        if wi.dot(self.ng) <= 0.0 || wo.dot(self.ng) <= 0.0 {
            return None;
        }
        let (co, ci) = (self.n.dot(wo), self.n.dot(wi));
        (co > 0.0 && ci > 0.0).then_some(ci)
    }

    /// The sample for a direction `wi` drawn from a lobe that is not a delta: weighted by the
    /// density of all such lobes together; `None` where no lobe reflects that way.
    fn scattered(&self, wo: Vec3, wi: Vec3) -> Option<BsdfSample> {
        let (f, pdf) = self.eval_pdf(wo, wi);
        if pdf <= 0.0 || !pdf.is_finite() {
            return None;
        }
        Some(BsdfSample {
            dir: wi,
            weight: f * (self.n.dot(wi) / pdf),
            pdf,
            delta: false,
        })
    }

    /// The cosine factor of light arriving from `wi` (against the shading normal).
    #[inline]
    pub fn cos(&self, wi: Vec3) -> f32 {
        self.n.dot(wi).max(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn material(kd: f32, ks: f32, e: f32) -> Material {
        Material {
            kd,
            ks,
            exponent: e,
            diffuse: Vec3::ONE,
            specular: Vec3::ONE,
            ..Material::default()
        }
    }

    fn dir(theta: f32, phi: f32) -> Vec3 {
        Vec3::new(
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        )
    }

    /// `∫ f(wo, wi) cos θi dωi` by the midpoint rule over the hemisphere.
    fn albedo(b: &Bsdf, wo: Vec3, n: usize) -> f64 {
        let mut sum = 0.0f64;
        let (dt, dp) = (0.5 * PI / n as f32, 2.0 * PI / (2 * n) as f32);
        for i in 0..n {
            let theta = (i as f32 + 0.5) * dt;
            for j in 0..2 * n {
                let wi = dir(theta, (j as f32 + 0.5) * dp);
                let f = b.eval(wo, wi).x as f64;
                sum += f * (theta.cos() * theta.sin() * dt * dp) as f64;
            }
        }
        sum
    }

    /// The normalised glossy lobe reflects all it receives at normal incidence and less at any
    /// other angle, for exponents from Lambertian (0) to mirror-like.
    #[test]
    fn glossy_albedo_is_one_at_normal_incidence_and_never_more() {
        for e in [0.0f32, 1.0, 5.0, 20.0, 100.0] {
            let b = Bsdf::new(&material(0.0, 1.0, e), Vec3::ONE, Vec3::Z, Vec3::Z, true);
            let n = if e > 50.0 { 600 } else { 200 };
            let at_normal = albedo(&b, Vec3::Z, n);
            assert!((at_normal - 1.0).abs() < 0.01, "e {e}: {at_normal}");
            for theta in [0.3f32, 0.7, 1.1, 1.4] {
                let a = albedo(&b, dir(theta, 0.4), n);
                assert!(a <= 1.0 + 2e-3, "e {e}, θ {theta}: {a}");
            }
        }
    }

    /// Diffuse plus glossy weights above one are scaled down together: the albedo stays ≤ 1.
    #[test]
    fn diffuse_and_glossy_together_never_exceed_one() {
        let b = Bsdf::new(&material(0.9, 0.6, 10.0), Vec3::ONE, Vec3::Z, Vec3::Z, true);
        for theta in [0.0f32, 0.5, 1.0, 1.4] {
            let a = albedo(&b, dir(theta, 1.0), 200);
            assert!(a <= 1.0 + 2e-3, "θ {theta}: {a}");
        }
        assert!(albedo(&b, Vec3::Z, 200) > 0.98);
    }

    /// Each smooth lobe is reciprocal: f(wo, wi) = f(wi, wo).
    #[test]
    fn smooth_lobes_are_reciprocal() {
        let n = Vec3::new(0.2, 0.3, 0.93).normalize();
        for m in [
            material(0.7, 0.0, 1.0),
            material(0.0, 0.8, 30.0),
            material(0.5, 0.4, 7.0),
            Material {
                kr: 0.4,
                mirror_exponent: 40.0,
                mirror: Vec3::new(0.9, 0.8, 0.3),
                ..material(0.5, 0.2, 3.0)
            },
        ] {
            let b = Bsdf::new(&m, Vec3::new(0.9, 0.5, 0.2), n, n, true);
            for i in 0..50 {
                let a = dir(0.03 * i as f32, 0.7 * i as f32);
                let c = dir(1.5 - 0.02 * i as f32, 2.0 + 0.3 * i as f32);
                let (x, y) = (b.eval(a, c), b.eval(c, a));
                assert!(
                    (x - y).abs().max_element() <= 1e-6 * x.max_element().max(1e-3),
                    "{x} vs {y}"
                );
            }
        }
    }

    /// The sampler draws from the density `pdf` reports: the mean of `weight` is the albedo, and
    /// `pdf` integrates to the share of samples that leave in a lobe that is not a delta; with a
    /// perfect mirror and with a rough one.
    #[test]
    fn samples_follow_the_reported_density() {
        for (m, delta_share) in [
            (
                Material {
                    kr: 0.25,
                    ..material(0.5, 0.4, 12.0)
                },
                0.25,
            ),
            (
                Material {
                    kr: 0.5,
                    mirror_exponent: 60.0,
                    ..material(0.5, 0.4, 12.0)
                },
                0.0,
            ),
            // Diffuse alone beside a mirror: the sampler's shortcut for it.
            (
                Material {
                    kr: 0.3,
                    ..material(0.7, 0.0, 1.0)
                },
                0.3,
            ),
        ] {
            let b = Bsdf::new(&m, Vec3::ONE, Vec3::Z, Vec3::Z, true);
            let wo = dir(0.6, 0.0);
            let k = 256u32;
            let (mut mean, mut delta, mut smooth) = (0.0f64, 0, 0);
            for i in 0..k {
                for j in 0..k {
                    let u = Vec2::new((i as f32 + 0.5) / k as f32, (j as f32 + 0.5) / k as f32);
                    let u_lobe = ((i * 7919 + j * 104729) % 65536) as f32 / 65536.0;
                    if let Some(s) = b.sample(wo, u_lobe, u) {
                        if s.delta {
                            delta += 1;
                        } else {
                            assert!((s.pdf - b.pdf(wo, s.dir)).abs() <= 1e-4 * s.pdf);
                            mean += s.weight.x as f64;
                            smooth += 1;
                        }
                    }
                }
            }
            let n = (k * k) as f64;
            let expected = albedo(&b, wo, 400);
            assert!(
                (mean / n - expected).abs() < 0.01,
                "{} vs {expected}",
                mean / n
            );
            assert!((delta as f64 / n - delta_share).abs() < 0.01);
            let mut integral = 0.0f64;
            let steps = 300;
            let (dt, dp) = (0.5 * PI / steps as f32, 2.0 * PI / (2 * steps) as f32);
            for i in 0..steps {
                let theta = (i as f32 + 0.5) * dt;
                for j in 0..2 * steps {
                    let p = b.pdf(wo, dir(theta, (j as f32 + 0.5) * dp)) as f64;
                    integral += p * (theta.sin() * dt * dp) as f64;
                }
            }
            // Half vectors that would send the direction below the surface give no sample: the
            // density covers just the samples taken (all of them for diffuse alone).
            assert!(integral < 1.0 - delta_share + 2e-3, "{integral}");
            assert!(
                (integral - smooth as f64 / n).abs() < 0.01,
                "{integral} vs {}",
                smooth as f64 / n
            );
        }
    }

    /// A rough mirror of exponent `e` reflects as the glossy lobe of that exponent does (so it
    /// shares that lobe's albedo bound), tinted by its colour; without roughness it is a delta.
    #[test]
    fn rough_mirror_is_the_normalised_lobe_of_its_exponent() {
        let tint = Vec3::new(0.9, 0.7, 0.2);
        let mirror = |e: f32| Material {
            kd: 0.0,
            kr: 1.0,
            mirror: tint,
            mirror_exponent: e,
            ..Material::default()
        };
        for e in [2.0f32, 50.0, 2000.0] {
            let rough = Bsdf::new(&mirror(e), Vec3::ONE, Vec3::Z, Vec3::Z, true);
            let glossy = Bsdf::new(&material(0.0, 1.0, e), Vec3::ONE, Vec3::Z, Vec3::Z, true);
            assert!(rough.has_non_delta());
            for i in 0..40 {
                let (wo, wi) = (dir(0.02 * i as f32, 0.3), dir(0.03 * i as f32, 3.0));
                let (fr, pr) = rough.eval_pdf(wo, wi);
                let (fg, pg) = glossy.eval_pdf(wo, wi);
                assert!((fr - tint * fg.x).abs().max_element() <= 1e-6 * fg.x.max(1.0));
                assert!((pr - pg).abs() <= 1e-6 * pg.max(1.0), "{pr} vs {pg}");
            }
        }
        let perfect = Bsdf::new(&mirror(f32::INFINITY), Vec3::ONE, Vec3::Z, Vec3::Z, true);
        assert!(!perfect.has_non_delta());
        let s = perfect
            .sample(dir(0.4, 1.0), 0.5, Vec2::splat(0.3))
            .unwrap();
        assert!(s.delta && s.weight == tint);
    }

    /// A glass lobe splits by Fresnel and refracts by Snell's law; inside, past the critical
    /// angle, it only reflects.
    #[test]
    fn dielectric_reflects_by_fresnel_and_refracts_by_snell() {
        let glass = Material {
            kd: 0.0,
            kt: 1.0,
            eta: 1.5,
            ..Material::default()
        };
        let b = Bsdf::new(&glass, Vec3::ONE, Vec3::Z, Vec3::Z, true);
        let wo = dir(0.5, 0.0);
        let f = fresnel_dielectric(0.5f32.cos(), 1.0 / 1.5);
        let reflected = b.sample(wo, f * 0.5, Vec2::ZERO).unwrap();
        assert!(reflected.delta && reflected.dir.z > 0.0);
        let t = b.sample(wo, f + (1.0 - f) * 0.5, Vec2::ZERO).unwrap();
        assert!(t.dir.z < 0.0);
        let sin_t = (t.dir.x * t.dir.x + t.dir.y * t.dir.y).sqrt();
        assert!((sin_t - 0.5f32.sin() / 1.5).abs() < 1e-5);
        assert!((t.weight.x - 1.0 / 2.25).abs() < 1e-6);
        let inside = Bsdf::new(&glass, Vec3::ONE, Vec3::Z, Vec3::Z, false);
        for u in [0.0, 0.5, 0.999] {
            let s = inside.sample(dir(1.0, 0.0), u, Vec2::ZERO).unwrap();
            assert!(s.dir.z > 0.0, "total internal reflection");
        }
    }
}
