//! Maps from the unit square to disks, lobes and the sphere.

use crate::math::{Vec2, Vec3};

/// Maps a point of the unit square to the unit disk, preserving strata (Shirley and Chiu's
/// concentric mapping, "A Low Distortion Map Between Disk and Square", JGT 2(3), 1997).
pub fn concentric_disk(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    if o.x == 0.0 && o.y == 0.0 {
        return Vec2::ZERO;
    }
    let (r, theta) = if o.x.abs() > o.y.abs() {
        (o.x, std::f32::consts::FRAC_PI_4 * (o.y / o.x))
    } else {
        (
            o.y,
            std::f32::consts::FRAC_PI_2 - std::f32::consts::FRAC_PI_4 * (o.x / o.y),
        )
    };
    r * Vec2::new(theta.cos(), theta.sin())
}

/// A half vector about `+z` with density `(e+1)/(2π) · cos^e θ` over solid angle (a Blinn-Phong lobe
/// of exponent `e ≥ 0`): `cos θ = u.x^(1/(e+1))`. The sine comes from `1 − cos²θ` worked out as
/// `−expm1(2·ln u.x/(e+1))`, so that the small angles of a near-mirror lobe (exponents in the
/// thousands) keep their precision instead of rounding to steps of `√(2·2⁻²⁴)`.
pub fn blinn_phong_half_vector(e: f32, u: Vec2) -> Vec3 {
    let s = u.x.ln() / (e + 1.0);
    let cos = s.exp();
    let sin = (-(2.0 * s).exp_m1()).clamp(0.0, 1.0).sqrt();
    let phi = 2.0 * std::f32::consts::PI * u.y;
    Vec3::new(sin * phi.cos(), sin * phi.sin(), cos)
}

/// A uniformly distributed unit direction (used by tests and benchmarks).
pub fn uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * std::f32::consts::PI * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}
