//! Property tests of the maths helpers the robustness of the renderer rests on.

use proptest::prelude::*;
use raytracer::integrator::finite_radiance;
use raytracer::math::{fresnel_dielectric, orthonormal_basis, reflect, refract, Vec3};
use raytracer::ray::offset_ray_origin;

const SEED: u64 = 0x5eed_2026;

fn unit() -> impl Strategy<Value = Vec3> {
    (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0)
        .prop_filter("not too short", |(x, y, z)| x * x + y * y + z * z > 1e-3)
        .prop_map(|(x, y, z)| Vec3::new(x, y, z).normalize())
}

fn point() -> impl Strategy<Value = Vec3> {
    (-1e6f32..1e6, -1e6f32..1e6, -1e6f32..1e6).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

proptest! {
    // A fixed seed: CI runs the same 4,096 cases every time (change the seed to explore).
    #![proptest_config(ProptestConfig {
        cases: 4096,
        rng_seed: proptest::test_runner::RngSeed::Fixed(SEED),
        failure_persistence: None,
        max_global_rejects: 1 << 20,
        ..ProptestConfig::default()
    })]

    #[test]
    fn basis_is_orthonormal_and_right_handed(n in unit()) {
        let (t, b) = orthonormal_basis(n);
        prop_assert!((t.length() - 1.0).abs() < 1e-5 && (b.length() - 1.0).abs() < 1e-5);
        prop_assert!(t.dot(n).abs() < 1e-5 && b.dot(n).abs() < 1e-5 && t.dot(b).abs() < 1e-5);
        prop_assert!(t.cross(b).distance(n) < 1e-5);
    }

    #[test]
    fn reflection_keeps_length_and_mirrors_the_normal_component(d in unit(), n in unit()) {
        let r = reflect(d, n);
        prop_assert!((r.length() - 1.0).abs() < 1e-5);
        prop_assert!((r.dot(n) + d.dot(n)).abs() < 1e-5);
        // The tangential part is unchanged.
        prop_assert!(((r - r.dot(n) * n) - (d - d.dot(n) * n)).length() < 1e-5);
    }

    /// Snell's law, unit length, and the Fresnel reflectance in [0, 1], equal from both sides of
    /// the interface (reciprocity), 1 exactly when refraction is impossible.
    #[test]
    fn refraction_obeys_snell_and_fresnel_is_reciprocal(d in unit(), n in unit(), eta in 0.2f32..3.0) {
        let d = if d.dot(n) > 0.0 { -d } else { d };
        prop_assume!(d.dot(n) < -1e-3);
        let cos_i = -d.dot(n);
        let f = fresnel_dielectric(cos_i, eta);
        prop_assert!((0.0..=1.0).contains(&f));
        match refract(d, n, eta) {
            None => prop_assert_eq!(f, 1.0),
            Some(t) => {
                prop_assert!((t.length() - 1.0).abs() < 1e-4);
                let sin_i = (1.0 - cos_i * cos_i).max(0.0).sqrt();
                let cos_t = -t.dot(n);
                prop_assert!(cos_t > 0.0);
                let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
                prop_assert!((eta * sin_i - sin_t).abs() < 2e-3, "{} vs {}", eta * sin_i, sin_t);
                prop_assert!(f < 1.0);
                // Reciprocity, away from grazing angles on either side (and so from the critical
                // angle), where R's slope is unbounded and f32 rounding of the cosines dominates.
                prop_assume!(cos_t > 0.1 && cos_i > 0.1);
                let back = fresnel_dielectric(cos_t, 1.0 / eta);
                prop_assert!((f - back).abs() < 2e-3, "{} vs {}", f, back);
            }
        }
    }

    /// The spawned origin leaves the error box on the side the new ray goes to.
    #[test]
    fn offset_origin_clears_the_error_box(p in point(), n in unit(), w in unit(), e in 0.0f32..1.0, scale in -8i32..4) {
        prop_assume!(w.dot(n).abs() > 1e-4);
        let error = p.abs() * (e * f32::EPSILON) + Vec3::splat(10f32.powi(scale) * e);
        let o = offset_ray_origin(p, error, n, w);
        let along = (o.as_dvec3() - p.as_dvec3()).dot(n.as_dvec3());
        let needed = n.abs().dot(error) as f64;
        prop_assert!(along.signum() == (w.dot(n) as f64).signum() || needed == 0.0);
        prop_assert!(along.abs() >= needed * (1.0 - 1e-6), "moved {} of {}", along, needed);
    }

    #[test]
    fn film_values_are_always_finite(x in any::<f32>(), y in any::<f32>(), z in any::<f32>()) {
        let c = finite_radiance(Vec3::new(x, y, z));
        prop_assert!(c.is_finite() && c.min_element() >= 0.0);
        if x.is_finite() && x >= 0.0 {
            prop_assert_eq!(c.x, x);
        }
    }
}
