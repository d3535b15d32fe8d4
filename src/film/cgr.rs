//! The CGR course's display transform, as its own renders of its test scenes show it
//! (`docs/scene-format.md`, "CGR conventions"): a logarithmic curve on luminance, with colour
//! carried over by the ratio of each channel to the luminance.
//!
//! ```text
//! Y   = 0.2126·R + 0.7152·G + 0.0722·B               (Rec. 709 luminance)
//! T   = ln(1 + k·Y) / ln(1 + k)                      (maps 0 to 0 and 1 to 1)
//! out = T · (C / Y)^s                                 per channel C, then clamped to [0, 1]
//! ```
//!
//! The second line is a logarithmic tone curve; the third is the colour correction of tone
//! mappers that work on luminance (Mantiuk, Mantiuk, Tomaszewska and Heidrich, "Color correction
//! for tone mapping", Computer Graphics Forum 28(2), 2009, eq. 2), whose exponent `s` above 1
//! makes colours more saturated than a plain scaling by `T / Y` would. Greys map to `T(Y)`.

use glam::Vec3;

/// Rec. 709 (sRGB) luminance weights.
const LUMINANCE: Vec3 = Vec3::new(0.2126, 0.7152, 0.0722);

/// `k` of the logarithmic curve, fitted to the course's renders: it is pinned by the
/// background 0.25 showing as 87 of 255 (1.33 ≤ k ≤ 1.42 give 87).
pub const CURVE: f32 = 1.4;

/// `s`, the colour exponent, fitted to the course's renders.
pub const SATURATION: f32 = 1.08;

/// The display value in [0, 1] of linear radiance `c`. Negative and NaN channels count as 0; a
/// pixel whose luminance is then zero or infinite is black.
pub fn display(c: Vec3) -> Vec3 {
    let c = c.max(Vec3::ZERO);
    let y = c.dot(LUMINANCE);
    if !(y > 0.0 && y < f32::INFINITY) {
        return Vec3::ZERO;
    }
    let t = (CURVE * y).ln_1p() / CURVE.ln_1p();
    let channel = |x: f32| (t * (x / y).powf(SATURATION)).clamp(0.0, 1.0);
    Vec3::new(channel(c.x), channel(c.y), channel(c.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn greys_follow_the_curve_and_the_ends_are_fixed() {
        assert_eq!(display(Vec3::ZERO), Vec3::ZERO);
        let one = display(Vec3::ONE);
        assert!((one - Vec3::ONE).abs().max_element() < 1e-6, "{one}");
        // The course's background, 0.25, shows as 87 of 255.
        let bg = display(Vec3::splat(0.25));
        assert_eq!((bg.x * 255.0 + 0.5) as u8, 87);
        assert_eq!(bg.x, bg.y);
        assert_eq!(bg.y, bg.z);
        // Monotonic in grey.
        let mut last = 0.0;
        for i in 1..=400 {
            let v = display(Vec3::splat(i as f32 / 100.0)).x;
            assert!(v >= last, "{i}");
            last = v;
        }
    }

    #[test]
    fn saturated_colours_gain_saturation_and_keep_their_hue_order() {
        let c = Vec3::new(0.4, 0.25, 0.25);
        let d = display(c);
        // Red above green and blue, which stay equal; the ratio grows past the radiance's.
        assert!(d.x > d.y && d.y == d.z, "{d}");
        assert!(d.x / d.y > c.x / c.y, "{d}");
        // Pure red stays pure red: the binary render mode's red on black is unchanged.
        assert_eq!(display(Vec3::X), Vec3::X);
    }

    #[test]
    fn bad_values_are_black_or_clamped() {
        assert_eq!(display(Vec3::splat(f32::NAN)), Vec3::ZERO);
        assert_eq!(display(Vec3::new(f32::INFINITY, 0.0, 0.0)), Vec3::ZERO);
        assert_eq!(display(Vec3::splat(-1.0)), Vec3::ZERO);
        assert_eq!(display(Vec3::splat(1e30)), Vec3::ONE);
        let d = display(Vec3::new(-1.0, 0.5, 0.5));
        assert_eq!(d.x, 0.0);
    }
}
