//! [`SampleKey`]: the random-number source of one camera sample of one pixel.

use crate::math::Vec2;

use super::*;

/// The random-number source of one camera sample of one pixel. Values are pure functions of
/// `(pixel, sample, dimension, index, seed)`; `stream` derives an independent source for a part of
/// the ray tree (a bounce, a light) so that dimensions never need to be counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SampleKey {
    pub(super) key: u64,
    /// Index of this camera sample in the pixel, `0..spp`.
    pub sample: u32,
    /// Samples per pixel.
    pub spp: u32,
    /// The hash state after the pixel's key `hash(&[x, y, seed])`: every per-pixel hash continues
    /// from it.
    pub(super) pixel_state: u64,
    /// Dimensions 2 and 3 of this camera sample's Sobol point where the camera has no lens to
    /// take them ([`SampleKey::pinhole_pattern`]): the point the area lights' cells share over the
    /// pixel ([`SampleKey::light_set`]), stratified against the film point. Derived streams keep
    /// it.
    pub(super) light_point: SobolPair,
}

/// A point whose two coordinates are Sobol coordinates (multiples of 2⁻²³ in [0, 1), as the
/// Sobol points here are made), or none, in 8 bytes: the 23 bits of each and a flag. A
/// [`SampleKey`] is copied into every branch of a ray tree, and this keeps it at 32 bytes where
/// an `Option<Vec2>` would make it 40.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct SobolPair(u64);

impl SobolPair {
    pub(super) const NONE: SobolPair = SobolPair(0);
    const SET: u64 = 1 << 63;

    /// `p`, whose coordinates are Sobol coordinates.
    pub(super) fn new(p: Vec2) -> SobolPair {
        let bits = |v: f32| u64::from(sobol_bits(v));
        SobolPair(Self::SET | bits(p.x) << 23 | bits(p.y))
    }

    /// The point, exactly as it was given; `None` for [`SobolPair::NONE`].
    pub(super) fn get(self) -> Option<Vec2> {
        let coordinate = |bits: u64| from_sobol_bits(bits as u32);
        (self.0 & Self::SET != 0).then(|| Vec2::new(coordinate(self.0 >> 23), coordinate(self.0)))
    }
}

/// 2²³: a Sobol coordinate here times this is a whole number below it.
pub(super) const SOBOL_ONE: f32 = (1u32 << 23) as f32;

/// The 23 bits of `u`, a Sobol coordinate: `u · 2²³`, exactly.
#[inline]
pub(super) fn sobol_bits(u: f32) -> u32 {
    (u * SOBOL_ONE) as u32
}

/// The Sobol coordinate of the low 23 bits of `bits` ([`sobol_bits`]'s inverse), exactly.
#[inline]
pub(super) fn from_sobol_bits(bits: u32) -> f32 {
    (bits & 0x7f_ffff) as f32 / SOBOL_ONE
}

impl SampleKey {
    /// A key for camera sample `sample` of `spp` that holds no hash: for a sample whose tracer
    /// reads no key ([`crate::integrator::Tracer::reads_keys`]) and whose film and lens points
    /// are fixed (one sample through the pixel's centre, a pinhole camera). It saves the pixel's
    /// two hashes where nothing would read them.
    pub fn unread(sample: u32, spp: u32) -> SampleKey {
        SampleKey {
            key: 0,
            sample,
            spp,
            pixel_state: 0,
            light_point: SobolPair::NONE,
        }
    }

    /// The source for camera sample `sample` of `spp` at pixel `(x, y)` under `seed`.
    pub fn new(x: u32, y: u32, sample: u32, spp: u32, seed: u64) -> SampleKey {
        let pixel_state = hash(&[hash(&[x as u64, y as u64, seed])]);
        SampleKey {
            key: hash_on(pixel_state, &[sample as u64]),
            sample,
            spp,
            pixel_state,
            light_point: SobolPair::NONE,
        }
    }

    /// A derived source for a sub-stream (e.g. a bounce or a light), independent of this one.
    #[inline]
    pub fn stream(&self, id: u64) -> SampleKey {
        let pixel_key = self.pixel_hash(&[id]);
        SampleKey {
            key: hash(&[self.key, id]),
            pixel_state: hash(&[pixel_key]),
            ..*self
        }
    }

    /// `hash` of the pixel key followed by `words`.
    #[inline]
    pub(super) fn pixel_hash(&self, words: &[u64]) -> u64 {
        hash_on(self.pixel_state, words)
    }

    /// A uniform value in `[0, 1)` for `dimension`.
    #[inline]
    pub fn uniform(&self, dimension: u64) -> f32 {
        to_unit(hash(&[self.key, dimension]))
    }

    /// Two uniform values for dimensions `2·dimension` and `2·dimension + 1`.
    #[inline]
    pub fn uniform2(&self, dimension: u64) -> Vec2 {
        Vec2::new(self.uniform(2 * dimension), self.uniform(2 * dimension + 1))
    }

    /// This camera sample's point in the unit square for a per-pixel pattern of `spp` points,
    /// placed with `method`. Jittered patterns for different `dimension`s are decorrelated by a
    /// per-pixel shuffle of the strata; Sobol patterns only by their scrambles, which leaves them
    /// paired within a pixel: [`SampleKey::camera_pattern`] gives the film and lens points.
    pub fn pixel_pattern(&self, method: Method, dimension: u64) -> Vec2 {
        match method {
            Method::Random => self.pattern_jitter(dimension),
            Method::Jittered => {
                let (stratum, key) = self.jittered_stratum(dimension);
                self.jittered_point(dimension, stratum, key)
            }
            Method::Sobol => sobol2(self.sample, self.pattern_seed(dimension)),
        }
    }

    /// This camera sample's uniform point for the pixel pattern of `dimension`: the whole point
    /// of a random pattern, the offset inside its stratum of a jittered one.
    #[inline]
    fn pattern_jitter(&self, dimension: u64) -> Vec2 {
        let h = self.pixel_hash(&[dimension, self.sample as u64]);
        Vec2::new(to_unit(h), to_unit(mix64(h)))
    }

    /// The stratum of this camera sample in the pixel's jittered pattern for `dimension`, and
    /// the key of the pattern's per-pixel shuffle.
    #[inline]
    fn jittered_stratum(&self, dimension: u64) -> (u32, u32) {
        let key = (self.pixel_hash(&[dimension]) & 0xffff_ffff) as u32;
        (permute(self.sample, self.spp, key), key)
    }

    /// This camera sample's point in `stratum` of the pixel's jittered pattern for `dimension`;
    /// `key` shuffles the columns of a count that is not a square.
    #[inline]
    fn jittered_point(&self, dimension: u64, stratum: u32, key: u32) -> Vec2 {
        let spp = self.spp.max(1);
        let u = self.pattern_jitter(dimension);
        stratum_point(stratum, spp, square_side(spp), u, key.rotate_left(16))
    }

    /// The scramble of the pixel's Sobol pattern for `dimension` ([`SampleKey::pixel_pattern`]).
    #[inline]
    fn pattern_seed(&self, dimension: u64) -> u32 {
        (self.pixel_hash(&[dimension, 0x50b0]) >> 32) as u32
    }

    /// This camera sample's film and lens points (pixel anti-aliasing and depth of field),
    /// placed with `method`: [`SampleKey::pixel_pattern`] of dimensions 0 and 1, except that
    /// Sobol points come from one four-dimensional point, the film from its dimensions 0 and 1
    /// (dimension 0's pattern, bit for bit) and the lens from 2 and 3, and that jittered lens
    /// cells are paired with the film cells by an orthogonal array where one is built
    /// (`lens_stratum`).
    ///
    /// Two 2D Sobol patterns scrambled apart pair their points at random, so film and lens
    /// together would be sampled no better than independently; dimensions 2 and 3 of one
    /// sequence are stratified against 0 and 1 (Joe and Kuo 2008), and every power-of-two prefix
    /// of each coordinate stays stratified, as adaptive rounds need. The gain is measured in
    /// `docs/adaptive.md`.
    #[inline]
    pub fn camera_pattern(&self, method: Method) -> (Vec2, Vec2) {
        match method {
            Method::Sobol => {
                let [fx, fy, lx, ly] = sobol4(self.sample, self.pattern_seed(0));
                (Vec2::new(fx, fy), Vec2::new(lx, ly))
            }
            Method::Jittered => {
                let (stratum, key) = self.jittered_stratum(0);
                let film = self.jittered_point(0, stratum, key);
                let lens = match lens_stratum(self, stratum) {
                    // A square count: its grid has no column shuffle.
                    Some(lens) => self.jittered_point(1, lens, 0),
                    None => self.pixel_pattern(method, 1),
                };
                (film, lens)
            }
            Method::Random => (self.pixel_pattern(method, 0), self.pixel_pattern(method, 1)),
        }
    }

    /// This camera sample's film point for a camera without a lens, placed with `method`:
    /// [`SampleKey::pixel_pattern`] of dimension 0, bit for bit. With Sobol points the key then
    /// keeps the same point's dimensions 2 and 3, which a lens would have taken
    /// ([`SampleKey::camera_pattern`]), for the area lights to spread their cells' points over
    /// the pixel with ([`SampleKey::light_set`]): the film and the lights are then stratified
    /// against each other, where two patterns scrambled apart pair at random: a penumbra seen
    /// through a pixel depends on both at once. Both come from one point, so the lights' pattern
    /// costs nothing more.
    #[inline]
    pub fn pinhole_pattern(&mut self, method: Method) -> Vec2 {
        match method {
            Method::Sobol => {
                let (film, spare) = self.camera_pattern(method);
                self.light_point = SobolPair::new(spare);
                film
            }
            Method::Random | Method::Jittered => self.pixel_pattern(method, 0),
        }
    }

    /// Point `index` of the `count` points this camera sample owns in the pixel's padded 2D
    /// set for `dimension`, placed with `method`: the set is one pattern over all the pixel's
    /// `spp · count` points (camera sample `s` takes points `s·count .. s·count + count`), so a
    /// dimension is stratified across the whole pixel, not only within one camera sample. The path
    /// tracer gives each bounce and each light dimensions of their own ("padding", as pbrt-v4's
    /// `PaddedSobolSampler` and `StratifiedSampler` do). `random`: independent points; `jittered`:
    /// one point in each of the `spp · count` strata (a grid when that is a square, else N-rooks),
    /// shuffled per pixel and dimension; `sobol`: Owen-scrambled Sobol points.
    #[inline]
    pub fn padded(&self, method: Method, dimension: u64, index: u32, count: u32) -> Vec2 {
        let count = count.max(1);
        let (i, key) = self.padded_point(dimension, index, count);
        match method {
            Method::Sobol => sobol2(i, (key >> 32) as u32),
            Method::Random | Method::Jittered => {
                let h = mix64(key ^ (i as u64).wrapping_add(0x9e37_79b9_7f4a_7c15));
                let u = Vec2::new(to_unit(h), to_unit(mix64(h)));
                if method == Method::Random {
                    return u;
                }
                let total = self.spp.max(1).saturating_mul(count);
                let shuffle = key as u32;
                let stratum = permute(i % total, total, shuffle);
                stratum_point(
                    stratum,
                    total,
                    square_side(total),
                    u,
                    shuffle.rotate_left(16),
                )
            }
        }
    }

    /// [`SampleKey::padded`] in four dimensions: dimension sets `2·dimension` and
    /// `2·dimension + 1`, each a padded 2D set; for Sobol, dimensions 0 to 3 of one Owen-scrambled
    /// sequence, computed at once (the first two are the best stratified).
    #[inline]
    pub fn padded4(&self, method: Method, dimension: u64, index: u32, count: u32) -> [f32; 4] {
        match method {
            Method::Sobol => {
                let (i, key) = self.padded_point(dimension, index, count.max(1));
                sobol4(i, (key >> 32) as u32)
            }
            Method::Random | Method::Jittered => {
                let a = self.padded(method, 2 * dimension + (1 << 40), index, count);
                let b = self.padded(method, 2 * dimension + 1 + (1 << 40), index, count);
                [a.x, a.y, b.x, b.y]
            }
        }
    }

    /// Where point `index` of this camera sample's `count` (≥ 1) lies in the pixel's padded set for
    /// `dimension`, and the set's per-pixel key.
    #[inline]
    fn padded_point(&self, dimension: u64, index: u32, count: u32) -> (u32, u64) {
        let i = self.sample.wrapping_mul(count).wrapping_add(index);
        (i, self.pixel_hash(&[dimension, 0x9a7b_50b0]))
    }

    /// The `count` points this camera sample takes at one shading point (the shadow rays towards
    /// one area light), placed with `method`, on their own: a set per camera sample, as if the
    /// pixel had no other. `dimension` separates different sets at the same point.
    #[inline]
    pub fn point_set(&self, method: Method, dimension: u64, count: u32) -> PointSet {
        let count = count.max(1);
        PointSet {
            method,
            count,
            // `hash(&[key, dimension, index])` is this state mixed with the index; its low 32
            // bits are the N-rooks shuffle.
            prefix: hash(&[self.key, dimension]),
            side: square_side(count),
            sobol_seed: match method {
                Method::Sobol => (hash(&[self.key, dimension, 0x50b0]) >> 32) as u32,
                Method::Random | Method::Jittered => 0,
            },
            first: 0,
            shared_cells: None,
        }
    }

    /// The `count` points this camera sample takes at one shading point (the shadow rays towards
    /// one area light), placed with `method` as one part of a set spread over all the pixel's
    /// camera samples, so that the light is stratified over the whole pixel and not only within
    /// each camera sample (a penumbra's noise then falls faster than one over the samples):
    /// - `random`: independent points, as [`SampleKey::point_set`];
    /// - `jittered` with a square count `k²`: one point in each cell of a `k×k` grid over the
    ///   light, as the light asks of each camera sample; in each cell the pixel's `spp` camera
    ///   samples place their points with a pattern of `camera.method`, the pixel sampler
    ///   (jittered: one point in each part of the cell cut into the squarest grid of `spp` parts;
    ///   sobol: Owen-scrambled Sobol points, whose every power-of-two prefix is stratified,
    ///   dimensions 2 and 3 of the camera sample's own point where it has them, which stratifies
    ///   the film and the light against each other ([`SampleKey::pinhole_pattern`]);
    ///   random leaves the cells' points independent), each cell's pattern turned by an offset
    ///   of its own;
    /// - `jittered` with another count: the N-rooks set of this camera sample alone;
    /// - `sobol`: points `s·count .. s·count + count` of the pixel's Owen-scrambled Sobol set
    ///   (camera sample `s`), so every camera sample's points and every power-of-two prefix of
    ///   the pixel's are stratified.
    ///
    /// With one camera sample a pixel has nothing to spread over, and this is
    /// [`SampleKey::point_set`] bit for bit.
    #[inline]
    pub fn light_set(
        &self,
        method: Method,
        camera: &CameraSamples,
        dimension: u64,
        count: u32,
    ) -> PointSet {
        let mut set = self.point_set(method, dimension, count);
        if self.spp <= 1 {
            return set;
        }
        match method {
            Method::Random => {}
            Method::Jittered => {
                if set.side > 0 && camera.method != Method::Random {
                    let key = self.pixel_hash(&[dimension, 0x9a7b_ce11]);
                    let columns = if camera.spp == self.spp {
                        camera.columns
                    } else {
                        grid_columns(self.spp)
                    };
                    set.shared_cells = Some(SharedCells::new(camera.method, key, self, columns));
                }
            }
            Method::Sobol => {
                let (first, key) = self.padded_point(dimension, 0, set.count);
                set.first = first;
                set.sobol_seed = (key >> 32) as u32;
            }
        }
        set
    }
}
