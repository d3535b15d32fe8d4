//! Deterministic sampling. Every random number is a hash of (pixel, sample index, dimension,
//! seed), so an image is bit-identical whatever the thread count or tile order: no generator state
//! is carried between pixels or threads.
//!
//! Three sample-placement methods, chosen per use (pixel anti-aliasing, thin-lens aperture, each
//! area light):
//! - `random`: independent uniform samples;
//! - `jittered`: stratified. For `n` samples where `n` is a perfect square `k²`, one sample in each
//!   cell of a `k×k` grid; otherwise one sample in each row and each column of an `n×n` grid
//!   ("N-rooks", a Latin hypercube), with the column order shuffled per pixel.
//! - `sobol`: the first two dimensions of the Sobol sequence with hash-based Owen scrambling
//!   (Burley, "Practical Hash-based Owen Scrambling", JCGT 9(4), 2020), the points of the
//!   `sobol_burley` crate (its shuffle and scrambling, with the Sobol matrices applied from byte
//!   tables: [`sobol4`] is the crate's `sample_4d` bit for bit). Any
//!   power-of-two prefix of `2^m` points has one point in every elementary interval of area
//!   `2^-m` (a (0,m,2)-net), and the scrambling keeps that while randomising the points.
//!   Each 2D set (a pixel's anti-aliasing pattern, its lens pattern, the shadow rays towards one
//!   light at one shading point) gets its own seed from the same hash as the other methods, and
//!   the crate's seeded nested shuffle of the index makes sets with different seeds statistically
//!   independent ("padding", Burley §4; pbrt-v4's `PaddedSobolSampler` does the same with
//!   per-dimension hashes). Decorrelation therefore comes from the seeds rather than from higher
//!   Sobol dimensions, whose 2D projections are worse nets than dimensions 0 and 1.
//!
//! A pixel's camera samples each trace their own shadow rays towards an area light, and the
//! Whitted integrator spreads those sets over the pixel ([`SampleKey::light_set`]): each camera
//! sample's set is what the light asks for, and together the pixel's sets are stratified as one
//! finer set (pbrt-v4's samplers do the same for every dimension; `docs/study.md` measures it).

/// How a set of samples is placed in the unit square.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// Independent uniform samples.
    Random,
    /// One sample per stratum (see the module docs).
    #[default]
    Jittered,
    /// Owen-scrambled Sobol points (see the module docs).
    Sobol,
}

impl std::str::FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Method, String> {
        match s.to_ascii_lowercase().as_str() {
            "random" => Ok(Method::Random),
            "jittered" | "stratified" => Ok(Method::Jittered),
            "sobol" => Ok(Method::Sobol),
            other => Err(format!(
                "unknown sampling method '{other}' (expected random, jittered or sobol)"
            )),
        }
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Method::Random => "random",
            Method::Jittered => "jittered",
            Method::Sobol => "sobol",
        })
    }
}

mod hash;
mod key;
mod path_sampler;
mod sets;
mod sobol;
mod strata;
#[cfg(test)]
mod tests;
mod warp;

use hash::*;
use key::*;
use sets::*;
use strata::*;

pub use hash::{hash, mix64, to_unit};
pub use key::SampleKey;
pub use path_sampler::{PaddedDimension, PathSampler};
pub use sets::{CameraSamples, PointSet};
pub use sobol::{sobol2, sobol4};
pub use strata::permute;
pub use warp::{blinn_phong_half_vector, concentric_disk, uniform_sphere};
