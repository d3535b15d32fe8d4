//! Small maths helpers shared by the geometry, the cameras and the integrator: floating-point error
//! bounds, orthonormal bases, reflection, refraction and the Fresnel equations.
//!
//! Vectors are `glam::Vec3` (`f32`). Directions are unit length unless a name says otherwise.

pub use glam::{Vec2, Vec3};

/// Unit roundoff of `f32` (half the machine epsilon), the `u` of Higham's error analysis.
pub const MACHINE_EPSILON: f32 = f32::EPSILON * 0.5;

/// The bound `γ(n) = n·u / (1 − n·u)` on the relative error of `n` chained floating-point operations
/// (Higham, *Accuracy and Stability of Numerical Algorithms*, §3.1; pbrt-v4 §6.8.1).
#[inline]
pub fn gamma(n: u32) -> f32 {
    let nu = n as f32 * MACHINE_EPSILON;
    nu / (1.0 - nu)
}

/// `x.floor()`, the same value for every `x` (signed zeros, infinities and NaN included), without
/// the call to libm that a baseline x86-64 (no SSE4.1 `roundsd`) makes for `floor`: below 2⁵² a
/// truncation through `i64` is exact, and at or beyond it every double is whole already.
#[inline]
pub fn floor_f64(x: f64) -> f64 {
    const WHOLE: f64 = 4_503_599_627_370_496.0; // 2⁵²
    if x.abs() < WHOLE {
        let t = x as i64 as f64;
        // A nonzero floor has the sign of `x`, and the floor of ±0 and of (0, 1) is ±0.
        (if t > x { t - 1.0 } else { t }).copysign(x)
    } else {
        x
    }
}

/// [`floor_f64`] for `f32` (whole from 2²³ on).
#[inline]
pub fn floor_f32(x: f32) -> f32 {
    const WHOLE: f32 = 8_388_608.0; // 2²³
    if x.abs() < WHOLE {
        let t = x as i32 as f32;
        (if t > x { t - 1.0 } else { t }).copysign(x)
    } else {
        x
    }
}

/// The next representable `f32` above `x` (`+∞` stays put).
#[inline]
pub fn next_float_up(x: f32) -> f32 {
    if x.is_infinite() && x > 0.0 {
        return x;
    }
    let x = if x == -0.0 { 0.0 } else { x };
    let bits = x.to_bits();
    let bits = if x >= 0.0 { bits + 1 } else { bits - 1 };
    f32::from_bits(bits)
}

/// The next representable `f32` below `x` (`−∞` stays put).
#[inline]
pub fn next_float_down(x: f32) -> f32 {
    if x.is_infinite() && x < 0.0 {
        return x;
    }
    let x = if x == 0.0 { -0.0 } else { x };
    let bits = x.to_bits();
    let bits = if x > 0.0 { bits - 1 } else { bits + 1 };
    f32::from_bits(bits)
}

/// Two unit vectors `(t, b)` that, with the unit normal `n`, form a right-handed orthonormal basis
/// `t × b = n`. Branchless construction of Duff et al., "Building an Orthonormal Basis, Revisited",
/// JCGT 6(1), 2017.
#[inline]
pub fn orthonormal_basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let bt = Vec3::new(b, sign + n.y * n.y * a, -n.y);
    (t, bt)
}

/// `v`, given in the frame of [`orthonormal_basis`] of the unit normal `n` (with `n` its z
/// axis), in world space.
#[inline]
pub fn local_to_world(n: Vec3, v: Vec3) -> Vec3 {
    let (t, b) = orthonormal_basis(n);
    v.x * t + v.y * b + v.z * n
}

/// Mirror reflection of the incoming direction `d` (pointing towards the surface) about the unit
/// normal `n`; the result points away from the surface on the side `d` came from.
#[inline]
pub fn reflect(d: Vec3, n: Vec3) -> Vec3 {
    d - 2.0 * d.dot(n) * n
}

/// Refraction of the incoming unit direction `d` through a surface with unit normal `n` facing the
/// incoming side (`d·n ≤ 0`), where `eta = η_incident / η_transmitted`. `None` on total internal
/// reflection. Snell's law in vector form (pbrt-v4 §9.3.2).
#[inline]
pub fn refract(d: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_i = (-d.dot(n)).clamp(0.0, 1.0);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((eta * d + (eta * cos_i - cos_t) * n).normalize())
}

/// Fraction of unpolarised light reflected at a dielectric boundary (the exact Fresnel equations,
/// pbrt-v4 §9.3.5). `cos_i` is the cosine of the incident angle (≥ 0) and `eta` is
/// `η_incident / η_transmitted`. Returns 1 on total internal reflection.
#[inline]
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    // With η_t/η_i = 1/eta: r∥ = (η_t cos_i − η_i cos_t)/(η_t cos_i + η_i cos_t), likewise r⊥.
    let r_par = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let r_perp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    0.5 * (r_par * r_par + r_perp * r_perp)
}

/// Component-wise absolute value times `γ(n)`: the usual error bound of a point computed with `n`
/// rounding steps from coordinates of magnitude `|p|`.
#[inline]
pub fn error_bound(p: Vec3, n: u32) -> Vec3 {
    p.abs() * gamma(n)
}

/// Maximum component of a vector.
#[inline]
pub fn max_component(v: Vec3) -> f32 {
    v.x.max(v.y).max(v.z)
}

/// Index of the largest component of `v` (0, 1 or 2).
#[inline]
pub fn max_dimension(v: Vec3) -> usize {
    if v.x > v.y {
        if v.x > v.z {
            0
        } else {
            2
        }
    } else if v.y > v.z {
        1
    } else {
        2
    }
}

/// `a · b` for four vectors at once (per axis, one lane per vector), in [`Vec3::dot`]'s order
/// of operations: lane by lane the same bits.
#[inline(always)]
pub fn dot4(a: &[glam::Vec4; 3], b: &[glam::Vec4; 3]) -> glam::Vec4 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `v` in every lane, per axis: the form of [`dot4`]'s operands.
#[inline(always)]
pub fn splat4(v: Vec3) -> [glam::Vec4; 3] {
    v.to_array().map(glam::Vec4::splat)
}

/// The square root of each lane: IEEE `sqrt` is correctly rounded, so lane `l` holds the bits of
/// `v[l].sqrt()` whether the CPU takes one packed instruction or four scalar ones.
#[inline(always)]
pub fn sqrt4(v: glam::Vec4) -> glam::Vec4 {
    #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
    {
        // SAFETY: SSE2 is enabled for this target (checked at compile time above), and
        // `_mm_sqrt_ps` only reads its register operand.
        unsafe { glam::Vec4::from(std::arch::x86_64::_mm_sqrt_ps(v.into())) }
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
    {
        glam::Vec4::from_array(v.to_array().map(f32::sqrt))
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn floors_equal_the_standard_library_bit_for_bit() {
        let mut singles = vec![
            0.0f32,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            0.999_999_94,
            -0.999_999_94,
        ];
        singles.extend([
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::MIN_POSITIVE,
            -1e-45,
        ]);
        singles.extend([
            8_388_607.5,
            -8_388_607.5,
            8_388_608.0,
            -8_388_609.0,
            f32::MAX,
            f32::MIN,
        ]);
        let mut x = 0x1234_5678u32;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            singles.push(f32::from_bits(x));
            singles.push((x % 100_000) as f32 / 37.0 - 1000.0);
        }
        for v in singles {
            assert_eq!(floor_f32(v).to_bits(), v.floor().to_bits(), "{v}");
            let w = f64::from(v) * 1.000_000_1;
            assert_eq!(floor_f64(w).to_bits(), w.floor().to_bits(), "{w}");
        }
        for w in [
            4_503_599_627_370_495.5f64,
            -4_503_599_627_370_495.5,
            1e300,
            -1e-300,
            -0.0,
        ] {
            assert_eq!(floor_f64(w).to_bits(), w.floor().to_bits(), "{w}");
        }
    }

    use super::*;

    #[test]
    fn basis_is_orthonormal_and_right_handed() {
        for n in [
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            -Vec3::Z,
            Vec3::new(1.0, 2.0, -3.0).normalize(),
            Vec3::new(-1e-7, 0.0, -1.0).normalize(),
        ] {
            let (t, b) = orthonormal_basis(n);
            assert!((t.length() - 1.0).abs() < 1e-5);
            assert!((b.length() - 1.0).abs() < 1e-5);
            assert!(t.dot(n).abs() < 1e-5 && b.dot(n).abs() < 1e-5 && t.dot(b).abs() < 1e-5);
            assert!(t.cross(b).distance(n) < 1e-5);
        }
    }

    #[test]
    fn reflect_mirrors_about_the_normal() {
        let r = reflect(Vec3::new(1.0, -1.0, 0.0), Vec3::Y);
        assert_eq!(r, Vec3::new(1.0, 1.0, 0.0));
    }

    #[test]
    fn refract_with_equal_indices_passes_straight() {
        let d = Vec3::new(0.3, -1.0, 0.2).normalize();
        let t = refract(d, Vec3::Y, 1.0).unwrap();
        assert!(t.distance(d) < 1e-6);
        assert_eq!(fresnel_dielectric(-d.dot(Vec3::Y), 1.0), 0.0);
    }

    #[test]
    fn refract_obeys_snell_and_total_internal_reflection() {
        let d = Vec3::new(0.5f32.sqrt(), -(0.5f32.sqrt()), 0.0);
        let t = refract(d, Vec3::Y, 1.0 / 1.5).unwrap();
        let sin_t = t.x;
        assert!((sin_t * 1.5 - 0.5f32.sqrt()).abs() < 1e-5);
        // From glass to air at 45° exceeds the critical angle (41.8°).
        assert!(refract(d, Vec3::Y, 1.5).is_none());
        assert_eq!(fresnel_dielectric(0.5f32.sqrt(), 1.5), 1.0);
    }

    #[test]
    fn fresnel_at_normal_incidence_matches_schlick_r0() {
        let r0 = ((1.0f32 - 1.5) / (1.0 + 1.5)).powi(2);
        assert!((fresnel_dielectric(1.0, 1.0 / 1.5) - r0).abs() < 1e-6);
    }

    #[test]
    fn next_float_moves_one_ulp() {
        assert!(next_float_up(1.0) > 1.0);
        assert!(next_float_down(1.0) < 1.0);
        assert_eq!(next_float_up(0.0), f32::from_bits(1));
        assert_eq!(next_float_down(0.0), -f32::from_bits(1));
        assert_eq!(next_float_up(f32::INFINITY), f32::INFINITY);
    }
}
