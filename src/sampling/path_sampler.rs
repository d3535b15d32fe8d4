//! [`PathSampler`]: the random numbers of one camera path, taken dimension by dimension.

use crate::math::Vec2;

use super::{Method, SampleKey};

/// Dimensions the camera owns before a path's own: the film point (0) and the lens point (1),
/// placed by [`SampleKey::camera_pattern`].
pub const CAMERA_DIMENSIONS: u64 = 2;

/// The random numbers of one camera path, as pbrt-v4's samplers give them: each request takes
/// the next dimension, so the integrator asks for what it needs in the order it needs it and
/// never numbers a dimension itself. Every value is still a pure function of (pixel, sample,
/// dimension, seed) ([`SampleKey::padded`]): a dimension is one padded set over the pixel's
/// camera samples, so two samples of one pixel stay stratified against each other only where
/// they ask for the same things in the same order. An integrator that may skip a request (no
/// light sample at a mirror) takes the dimension anyway ([`PathSampler::skip`]).
#[derive(Debug, Clone)]
pub struct PathSampler<'k> {
    key: &'k SampleKey,
    method: Method,
    next: u64,
}

/// One dimension taken for a set of points at one vertex: point `index` of `count`
/// ([`SampleKey::padded`]), e.g. one light's samples.
#[derive(Debug, Clone, Copy)]
pub struct PaddedDimension<'k> {
    key: &'k SampleKey,
    method: Method,
    dimension: u64,
}

impl<'k> PathSampler<'k> {
    /// The path's sampler for camera sample `key`, starting after the camera's dimensions.
    pub fn new(key: &'k SampleKey, method: Method) -> PathSampler<'k> {
        PathSampler {
            key,
            method,
            next: CAMERA_DIMENSIONS,
        }
    }

    /// The dimension the next request takes.
    pub fn dimension(&self) -> u64 {
        self.next
    }

    fn take(&mut self) -> u64 {
        let d = self.next;
        self.next += 1;
        d
    }

    /// A 4D point in the next dimension ([`SampleKey::padded4`]): its first two coordinates
    /// are the best stratified.
    #[inline]
    pub fn get4(&mut self) -> [f32; 4] {
        let d = self.take();
        self.key.padded4(self.method, d, 0, 1)
    }

    /// The next dimension, for a set of points taken by index.
    #[inline]
    pub fn get_set(&mut self) -> PaddedDimension<'k> {
        PaddedDimension {
            key: self.key,
            method: self.method,
            dimension: self.take(),
        }
    }

    /// Takes `n` dimensions without reading them, so that what follows keeps its dimensions.
    #[inline]
    pub fn skip(&mut self, n: u64) {
        self.next += n;
    }
}

impl PaddedDimension<'_> {
    /// Point `index` of `count` (≥ 1) in this dimension.
    #[inline]
    pub fn point(&self, index: u32, count: u32) -> Vec2 {
        self.key.padded(self.method, self.dimension, index, count)
    }
}
