//! Materials: Blinn-Phong surfaces that may also reflect like a mirror and transmit like glass.
//!
//! ```json
//! "material": { "ks": 0.6, "kd": 0.7, "specularexponent": 10, "diffusecolor": [1, 1, 1],
//!               "specularcolor": [1, 1, 1], "kr": 0.3, "kt": 0.0, "eta": 1.5,
//!               "tPath": "../textures/sicily.jpg", "tWidth": 600, "tHeight": 490 }
//! ```
//! The CGR spellings `isreflective`/`reflectivity` and `isrefractive`/`refractiveindex` map onto
//! `kr`, `kt` and `eta` (see `docs/scene-format.md`). A texture replaces the diffuse colour.
//! `ka` scales the scene's ambient light (CGR files have one; see [`Reflection`] for the other
//! way CGR files differ), and [`Shares`] keeps every combination of weights from making light.

use crate::math::Vec3;

#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Ambient weight: the surface adds `ka · ambient · base colour`.
    pub ka: f32,
    /// Diffuse weight.
    pub kd: f32,
    /// Specular weight.
    pub ks: f32,
    /// Blinn-Phong exponent.
    pub exponent: f32,
    pub diffuse: Vec3,
    pub specular: Vec3,
    /// Mirror reflectivity.
    pub kr: f32,
    /// Transmission: a fraction `kt` of the light goes through a dielectric interface, split
    /// between reflection and refraction by the Fresnel equations.
    pub kt: f32,
    /// Index of refraction of the inside.
    pub eta: f32,
    /// Index into the scene's textures.
    pub texture: Option<u32>,
    /// Colour of the mirror reflection (a metal's `albedo`; white otherwise). The path tracer
    /// tints by it; Whitted reflection is untinted.
    pub mirror: Vec3,
    /// Blinn-Phong exponent of the mirror's lobe: `INFINITY` for a perfect mirror, finite for a
    /// rough one (a CGR material's `roughness`, through [`roughness_exponent`]). The path tracer
    /// scatters into the lobe; Whitted reflection traces one ray per camera sample about a half
    /// vector drawn from it.
    pub mirror_exponent: f32,
    /// Colour of the light a transmissive material lets through (a glass's
    /// `transmittancecolor`); white otherwise.
    pub transmit: Vec3,
    /// Radiance the surface emits (`emittance`, or an `emissive` material's colour × intensity).
    /// A sphere, triangle or quad with an emitting material is an area light.
    pub emission: Vec3,
}

impl Default for Material {
    fn default() -> Material {
        Material {
            ka: 1.0,
            kd: 0.8,
            ks: 0.0,
            exponent: 1.0,
            diffuse: Vec3::splat(0.8),
            specular: Vec3::ONE,
            kr: 0.0,
            kt: 0.0,
            eta: 1.0,
            texture: None,
            mirror: Vec3::ONE,
            mirror_exponent: f32::INFINITY,
            transmit: Vec3::ONE,
            emission: Vec3::ZERO,
        }
    }
}

/// Largest whole exponent [`highlight`] raises by repeated multiplication; past it (or for a
/// fractional exponent) it calls `powf`.
const MAX_WHOLE_EXPONENT: f32 = 4096.0;

/// The Blinn-Phong highlight `cos^exponent` for `cos ∈ [0, 1]`. A whole exponent (every bundled
/// and corpus scene's) is raised by square-and-multiply, which is cheaper than `powf`; its
/// relative error is at most `2·exponent` units of 2⁻²⁴ (each squaring doubles the error carried
/// in), below 5·10⁻⁴ of the value up to the largest such exponent: under a quarter of an 8-bit
/// step (1/1020) for highlights up to 1 (the tests in this module check the bound).
#[inline]
pub fn highlight(cos: f32, exponent: f32) -> f32 {
    if is_whole_exponent(exponent) {
        whole_power(cos, exponent as u32, 1.0)
    } else {
        cos.powf(exponent)
    }
}

/// [`highlight`] of four cosines with one exponent, lane by lane the same bits: every lane takes
/// the same squarings and multiplications, in the same order (or `powf` lane by lane).
#[inline(always)]
pub fn highlight4(cos: glam::Vec4, exponent: f32) -> glam::Vec4 {
    if is_whole_exponent(exponent) {
        whole_power(cos, exponent as u32, glam::Vec4::ONE)
    } else {
        glam::Vec4::from_array(cos.to_array().map(|c| c.powf(exponent)))
    }
}

/// Whether [`highlight`] raises to `exponent` by square-and-multiply.
#[inline(always)]
fn is_whole_exponent(exponent: f32) -> bool {
    // In that range the conversion to an integer and back is exact for whole numbers only (and
    // costs no call to `truncf`, which `fract` makes on a baseline x86-64).
    (0.0..=MAX_WHOLE_EXPONENT).contains(&exponent) && (exponent as u32) as f32 == exponent
}

/// `base^n` by square-and-multiply, low bit first, from `one`: one sequence of products for a
/// number or for lanes of numbers.
#[inline(always)]
fn whole_power<T: Copy + std::ops::MulAssign>(mut base: T, mut n: u32, one: T) -> T {
    let mut result = one;
    while n > 0 {
        if n & 1 == 1 {
            result *= base;
        }
        n >>= 1;
        if n > 0 {
            base *= base;
        }
    }
    result
}

/// The Blinn-Phong exponent of a microfacet roughness `α` (a Beckmann slope deviation), `2/α² − 2`
/// (Walter et al., "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007, §5.2):
/// `INFINITY` at `α = 0` (a perfect mirror), `0` at `α ≥ 1`.
pub fn roughness_exponent(alpha: f32) -> f32 {
    (2.0 / (alpha * alpha) - 2.0).max(0.0)
}

/// How a material shares the light that reaches it between its mirror, its glass and its own
/// shading, so that together they never return more than arrives: the mirror takes `kr` (at most
/// all), the glass `kt` of what the mirror leaves, and the surface's own shading the rest
/// (`docs/scene-format.md`, "Energy"). Both integrators use these shares.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shares {
    /// Weight of the mirror reflection.
    pub mirror: f32,
    /// Weight of the dielectric interface, split by the Fresnel equations between reflection and
    /// refraction.
    pub glass: f32,
    /// What is left for the surface's own (ambient, diffuse and highlight) terms.
    pub own: f32,
}

/// The weights of a shading point's own diffuse terms, each reflecting at most a `budget` of
/// what arrives: the ambient term's `ka·c` and the diffuse term's `kd·c`, scaled down (keeping
/// their hue) to a largest channel of `budget`. The highlight is not among them: it stands for
/// the mirror image of a point light, which no reflected ray can see.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OwnTerms {
    /// `ka · c`, to multiply by the ambient light.
    pub ambient: Vec3,
    /// `kd · c`, to multiply by a light's diffuse power and `n · l`.
    pub diffuse: Vec3,
}

/// `v` scaled so that its largest channel is at most `budget` (zero for a budget of zero or less).
fn capped(v: Vec3, budget: f32) -> Vec3 {
    let largest = v.max_element();
    if largest <= budget {
        v
    } else if budget > 0.0 {
        v * (budget / largest)
    } else {
        Vec3::ZERO
    }
}

impl Material {
    /// The material's [`Shares`].
    pub fn shares(&self) -> Shares {
        let mirror = self.kr.clamp(0.0, 1.0);
        let glass = self.kt.clamp(0.0, 1.0 - mirror);
        Shares {
            mirror,
            glass,
            own: (1.0 - mirror - glass).max(0.0),
        }
    }

    /// The [`OwnTerms`] at a point of base colour `base` (texture or diffuse colour).
    pub fn own_terms(&self, base: Vec3, budget: f32) -> OwnTerms {
        OwnTerms {
            ambient: capped(self.ka * base, budget),
            diffuse: capped(self.kd * base, budget),
        }
    }

    /// Whether shadow rays pass (attenuated) through this material.
    pub fn is_transmissive(&self) -> bool {
        self.kt > 0.0
    }

    /// Whether the material has a mirror part, and it is rough.
    pub fn has_rough_mirror(&self) -> bool {
        self.kr > 0.0 && self.mirror_exponent.is_finite()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_highlights_are_four_times_the_one() {
        let cos = glam::Vec4::new(0.0, 0.37, 0.999_9, 1.0);
        for exponent in [
            0.0, 1.0, 2.0, 7.0, 10.0, 30.0, 200.0, 4096.0, 4097.0, 12.5, -1.0,
        ] {
            let lanes = highlight4(cos, exponent);
            for l in 0..4 {
                assert_eq!(
                    lanes[l].to_bits(),
                    highlight(cos[l], exponent).to_bits(),
                    "{exponent}"
                );
            }
        }
    }

    #[test]
    fn whole_exponents_are_the_whole_numbers_up_to_the_limit() {
        let by_fract = |e: f32| (0.0..=MAX_WHOLE_EXPONENT).contains(&e) && e.fract() == 0.0;
        let mut values = vec![0.0, -0.0, 1.0, 0.5, 1e-40, f32::NAN, f32::INFINITY, -1.0];
        for k in 0..=4100 {
            let e = k as f32;
            values.extend([e, e + 0.5, e - 0.25, f32::from_bits(e.to_bits() + 1)]);
        }
        for e in values {
            assert_eq!(is_whole_exponent(e), by_fract(e), "{e}");
        }
    }

    /// The whole-exponent highlight against a double-precision power, over the cosines and
    /// exponents scenes use.
    #[test]
    fn whole_exponent_highlight_is_within_its_bound() {
        for exponent in [
            0.0f32, 1.0, 2.0, 7.0, 10.0, 30.0, 64.0, 100.0, 200.0, 1000.0, 4096.0,
        ] {
            let bound = (2.0 * exponent as f64 + 1.0) * f32::EPSILON as f64 / 2.0;
            for i in 0..=20000 {
                let cos = 1.0 - (i as f32 / 20000.0).powi(3);
                let got = highlight(cos, exponent) as f64;
                let want = (cos as f64).powf(exponent as f64);
                if want < f32::MIN_POSITIVE as f64 {
                    assert!(got < 1e-30, "{cos}^{exponent}: {got}");
                    continue;
                }
                let rel = (got - want).abs() / want;
                assert!(rel <= bound, "{cos}^{exponent}: {got} vs {want} ({rel:e})");
            }
        }
        // Fractional and negative exponents keep powf.
        assert_eq!(highlight(0.5, 2.5), 0.5f32.powf(2.5));
        assert_eq!(highlight(0.0, 0.0), 1.0);
    }
}

/// How a mirror's and a glass's light combines with the light a surface shades itself (its
/// [`Shares`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Reflection {
    /// `own + mirror · reflected + …`, the own ambient and diffuse weights capped at the share
    /// the mirror and glass leave: what the official 2021–23 reference render shows (its walls
    /// keep their diffuse colour beside their reflection).
    #[default]
    Added,
    /// `own share · own + mirror · reflected + …`: a `reflectivity` 1 mirror shows only what it
    /// reflects, as the CGR course's renders of its test scenes show.
    Blended,
}
