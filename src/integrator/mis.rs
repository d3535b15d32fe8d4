//! Multiple importance sampling weights (Veach, "Robust Monte Carlo Methods for Light Transport
//! Simulation", PhD thesis, Stanford 1997, §9.2).
//!
//! A path tracer with next-event estimation finds light along a path in two ways: by sampling a
//! point on a light (`n` samples per shading point) and by following the BSDF sample (one) until it
//! hits a light. Each estimate is weighted by the power heuristic with β = 2,
//! `w_i = (n_i p_i)² / Σ_k (n_k p_k)²`, where `p_i` is the solid-angle density with which technique
//! `i` picks the direction; the weights of the techniques that can pick a direction sum to one,
//! which keeps the sum of the two estimates unbiased.

/// The power-heuristic weight of a technique taking `nf` samples of density `pf`, against one
/// taking `ng` samples of density `pg`. A technique of infinite density (a delta) takes all the
/// weight; two of zero density share nothing (the weight is 0).
#[inline]
pub fn power_heuristic(nf: f32, pf: f32, ng: f32, pg: f32) -> f32 {
    let f = nf * pf;
    let g = ng * pg;
    if f.is_infinite() {
        return if g.is_infinite() { 0.5 } else { 1.0 };
    }
    let (f2, g2) = (f * f, g * g);
    if f2 + g2 > 0.0 {
        f2 / (f2 + g2)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// For every pair of densities and sample counts, the two techniques' weights sum to one.
    #[test]
    fn weights_of_two_techniques_sum_to_one() {
        let densities = [1e-6f32, 0.01, 0.3, 1.0, 2.5, 40.0, 1e4, 1e12];
        for &n in &[1.0f32, 4.0, 16.0] {
            for &a in &densities {
                for &b in &densities {
                    let sum = power_heuristic(n, a, 1.0, b) + power_heuristic(1.0, b, n, a);
                    assert!((sum - 1.0).abs() < 1e-6, "n {n}, {a} vs {b}: {sum}");
                }
            }
        }
        assert_eq!(power_heuristic(1.0, f32::INFINITY, 1.0, 3.0), 1.0);
        assert_eq!(power_heuristic(1.0, 3.0, 1.0, f32::INFINITY), 0.0);
        assert_eq!(power_heuristic(1.0, 0.0, 1.0, 0.0), 0.0);
    }

    /// The weight favours the technique of higher density, more so with more samples.
    #[test]
    fn weight_follows_the_density() {
        assert!(power_heuristic(1.0, 4.0, 1.0, 1.0) > 0.9);
        assert_eq!(power_heuristic(1.0, 2.0, 1.0, 2.0), 0.5);
        assert!(power_heuristic(4.0, 1.0, 1.0, 1.0) > power_heuristic(1.0, 1.0, 1.0, 1.0));
    }
}
