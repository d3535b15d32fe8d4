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
//!   tables: [`sobol4`] is the crate's `sample_4d` bit for bit, in half the time). Any
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
//! finer set (pbrt-v4's samplers do the same for every dimension). On `scenes/penumbra.json` at 64
//! samples a pixel that takes the MSE against a converged render from 1.19·10⁻⁵ to 3.0·10⁻⁶, for
//! 3–9% more time (`docs/study.md`).

use crate::math::{Vec2, Vec3};

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

/// A 64-bit mixing function with full avalanche (the finaliser of SplitMix64, Steele et al.,
/// "Fast Splittable Pseudorandom Number Generators", OOPSLA 2014).
#[inline]
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Hashes a sequence of words into one.
#[inline]
pub fn hash(words: &[u64]) -> u64 {
    hash_on(0x9e37_79b9_7f4a_7c15, words)
}

/// [`hash`] continued from state `h`: `hash_on(hash(a), b)` is `hash` of `a` then `b`.
#[inline]
fn hash_on(mut h: u64, words: &[u64]) -> u64 {
    for &w in words {
        h = mix64(h ^ w.wrapping_add(0x9e37_79b9_7f4a_7c15));
    }
    h
}

/// A uniform `f32` in `[0, 1)` from the top 24 bits of a hash.
#[inline]
pub fn to_unit(h: u64) -> f32 {
    (h >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
}

/// The random-number source of one camera sample of one pixel. Values are pure functions of
/// `(pixel, sample, dimension, index, seed)`; `stream` derives an independent source for a part of
/// the ray tree (a bounce, a light) so that dimensions never need to be counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SampleKey {
    key: u64,
    /// Index of this camera sample in the pixel, `0..spp`.
    pub sample: u32,
    /// Samples per pixel.
    pub spp: u32,
    /// The hash state after the pixel's key `hash(&[x, y, seed])`: every per-pixel hash continues
    /// from it.
    pixel_state: u64,
    /// Dimensions 2 and 3 of this camera sample's Sobol point where the camera has no lens to
    /// take them ([`SampleKey::pinhole_pattern`]): the point the area lights' cells share over the
    /// pixel ([`SampleKey::light_set`]), stratified against the film point. Derived streams keep
    /// it.
    lights_across: SobolPair,
}

/// A point whose two coordinates are Sobol coordinates (multiples of 2⁻²³ in [0, 1), as the
/// Sobol points here are made), or none, in 8 bytes: the 23 bits of each and a flag. A
/// [`SampleKey`] is copied into every branch of a ray tree, and an `Option<Vec2>` there (12
/// bytes) made it 40 bytes where 32 hold this: 1.02× the time of the glass peer scene, which
/// draws no samples at all (41 alternating runs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct SobolPair(u64);

impl SobolPair {
    const NONE: SobolPair = SobolPair(0);
    const SET: u64 = 1 << 63;

    /// `p`, whose coordinates are Sobol coordinates.
    fn new(p: Vec2) -> SobolPair {
        let bits = |v: f32| u64::from(sobol_bits(v));
        SobolPair(Self::SET | bits(p.x) << 23 | bits(p.y))
    }

    /// The point, exactly as it was given; `None` for [`SobolPair::NONE`].
    fn get(self) -> Option<Vec2> {
        let coordinate = |bits: u64| from_sobol_bits(bits as u32);
        (self.0 & Self::SET != 0).then(|| Vec2::new(coordinate(self.0 >> 23), coordinate(self.0)))
    }
}

/// 2²³: a Sobol coordinate here times this is a whole number below it.
const SOBOL_ONE: f32 = (1u32 << 23) as f32;

/// The 23 bits of `u`, a Sobol coordinate: `u · 2²³`, exactly.
#[inline]
fn sobol_bits(u: f32) -> u32 {
    (u * SOBOL_ONE) as u32
}

/// The Sobol coordinate of the low 23 bits of `bits` ([`sobol_bits`]'s inverse), exactly.
#[inline]
fn from_sobol_bits(bits: u32) -> f32 {
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
            lights_across: SobolPair::NONE,
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
            lights_across: SobolPair::NONE,
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
    fn pixel_hash(&self, words: &[u64]) -> u64 {
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
    /// cells are paired with the film cells by an orthogonal array where one is built (see
    /// `lens_stratum` in this module: 1.15–1.8× lower MSE on `scenes/thinlens.json` from 9 to 256
    /// samples a pixel).
    ///
    /// Two 2D Sobol patterns under scrambles of their own are each stratified, but their points
    /// pair up at random: together, film and lens are sampled no better than independently (of a
    /// pixel's 64 samples, one film axis against one lens axis leaves about a third of the cells
    /// of an 8×8 grid empty, as random pairs do). Dimensions 2 and 3 of the sequence are
    /// stratified against 0 and 1 (Joe and Kuo 2008): from 8 samples each film axis against each
    /// lens axis fills the quarters evenly, and 64 samples put one point in every cell of that
    /// 8×8 grid. On `scenes/thinlens.json` the MSE at 256 samples a pixel falls 2.6× (MSE ∝
    /// n^−1.29 against n^−1.01; docs/adaptive.md). At 4 samples the lens points lie in two
    /// opposite quarters of the lens: two bits of a Sobol coordinate allow only two generator
    /// matrices, so dimensions 1 to 3 are tied that early (4 and 8 samples give about 1.15× the
    /// MSE of the independent pairing). Every power-of-two prefix of each coordinate stays
    /// stratified, as adaptive rounds need.
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
    /// against each other, where two patterns scrambled apart pair at random. A penumbra seen
    /// through a pixel depends on both at once: on `scenes/penumbra.json` the MSE of uniform
    /// renders falls 1.2× at 64 samples a pixel and 1.6× at 256 (docs/adaptive.md). Both come from
    /// one point, so the lights' pattern costs nothing more.
    #[inline]
    pub fn pinhole_pattern(&mut self, method: Method) -> Vec2 {
        match method {
            Method::Sobol => {
                let (film, spare) = self.camera_pattern(method);
                self.lights_across = SobolPair::new(spare);
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
            across: None,
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
                    set.across = Some(Across::new(camera.method, key, self, columns));
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

/// `count` sample points in the unit square for one shading point (see
/// [`SampleKey::point_set`] and [`SampleKey::light_set`]), with everything that does not depend
/// on the point's index worked out once.
#[derive(Debug, Clone, Copy)]
pub struct PointSet {
    method: Method,
    count: u32,
    prefix: u64,
    /// [`square_side`] of `count`.
    side: u32,
    sobol_seed: u32,
    /// Sobol: the index of point 0 in the seed's sequence.
    first: u32,
    /// Jittered cells: how the pixel's camera samples share each cell; `None`: each camera
    /// sample's point is anywhere in its cell.
    across: Option<Across>,
}

/// How one camera sample places its points in a light's jittered cells (see
/// [`SampleKey::light_set`]). Over the pixel's camera samples every cell is stratified, each cell
/// by the same pattern turned by an offset of its own, so that one camera sample's points lie at
/// unrelated places in their cells, as independent jitter would put them.
#[derive(Debug, Clone, Copy)]
struct Across {
    /// The pixel's key of the set: a cell's offset is a hash of it and the cell.
    key: u64,
    pattern: Pattern,
}

/// The pattern a light's cell is stratified with over a pixel's camera samples.
#[derive(Debug, Clone, Copy)]
enum Pattern {
    /// The cell cut into a grid of `spp` parts, `grid.0` wide and `grid.1` high: camera sample
    /// `s` takes part `part` of the grid, its place in a shuffle of the parts shared by the cells,
    /// turned by the cell's offset (a toroidal shift of the grid, a shuffle of its own per cell).
    Parts { part: (u32, u32), grid: (u32, u32) },
    /// Camera sample `s` takes point `s` of the pixel's Owen-scrambled Sobol set, shifted
    /// digitally by the cell's offset ([`digital_shift`], which keeps every power-of-two prefix
    /// a net): the camera sample's own point, dimensions 2 and 3, where a camera without a lens
    /// leaves them ([`SampleKey::pinhole_pattern`]), else a 2D set of the light's own.
    Sobol(Vec2),
}

impl Across {
    /// The pattern of `camera_sample`, its pixel's camera samples placed with `method`, under
    /// the set's pixel key `key`, with a grid of parts `columns` wide when they are jittered.
    fn new(method: Method, key: u64, camera_sample: &SampleKey, columns: u32) -> Across {
        let (sample, spp) = (camera_sample.sample, camera_sample.spp);
        let pattern = match method {
            Method::Sobol => Pattern::Sobol(
                camera_sample
                    .lights_across
                    .get()
                    .unwrap_or_else(|| sobol2(sample, (key >> 32) as u32)),
            ),
            Method::Random | Method::Jittered => {
                let part = permute(sample, spp, key as u32);
                Pattern::Parts {
                    part: (part % columns, part / columns),
                    grid: (columns, spp / columns),
                }
            }
        };
        Across { key, pattern }
    }

    /// The point in cell `(x, y)` of a `side × side` grid, with `u` the point's own random
    /// offset in its part.
    #[inline]
    fn point(&self, (x, y): (u32, u32), side: u32, u: Vec2) -> Vec2 {
        let offset = mix64(self.key ^ (y * side + x) as u64);
        let (fine_x, fine_y, per_cell) = match self.pattern {
            Pattern::Parts { part, grid } => {
                // The turn along each axis from 32 bits of the offset: a number in `0..n` by a
                // multiply and shift (Lemire, "Fast Random Integer Generation in an Interval",
                // ACM TOMACS 29(1), 2019), added modulo `n`.
                let turn = |bits: u64, at: u32, n: u32| {
                    let t = (((bits & 0xffff_ffff) * n as u64) >> 32) as u32;
                    if at + t >= n {
                        at + t - n
                    } else {
                        at + t
                    }
                };
                let px = turn(offset, part.0, grid.0);
                let py = turn(offset >> 32, part.1, grid.1);
                (
                    (x * grid.0 + px) as f32 + u.x,
                    (y * grid.1 + py) as f32 + u.y,
                    Vec2::new(grid.0 as f32, grid.1 as f32),
                )
            }
            Pattern::Sobol(p) => {
                let q = Vec2::new(
                    digital_shift(p.x, offset as u32),
                    digital_shift(p.y, (offset >> 32) as u32),
                );
                (x as f32 + q.x, y as f32 + q.y, Vec2::ONE)
            }
        };
        // Rounding may carry the last part's point up to 1: keep it inside.
        (Vec2::new(fine_x, fine_y) / (per_cell * side as f32))
            .min(Vec2::splat(1.0 - f32::EPSILON / 2.0))
    }
}

/// `u`, a Sobol coordinate (a multiple of 2⁻²³ in [0, 1), as the Sobol points here are made),
/// with its 23 bits XORed with the low bits of `shift`: a random digital shift (pbrt-v4's
/// `BinaryPermuteScrambler`, Pharr, Jakob and Humphreys, "Physically Based Rendering", 4th ed.,
/// §8.7, is the same map on 32 bits). It moves every point of
/// a net to a point of another net of the same quality, where adding a shift modulo 1 moves
/// points across the net's cells: a light's cells, each shifted by its own offset, keep their
/// points stratified over the pixel (on `scenes/penumbra.json` 1.3× lower MSE at 16 to 64 samples
/// a pixel than the shift modulo 1; docs/adaptive.md). Exact: the conversions only move bits.
#[inline]
fn digital_shift(u: f32, shift: u32) -> f32 {
    from_sobol_bits(sobol_bits(u) ^ shift)
}

/// How a render places each pixel's camera samples, as [`SampleKey::light_set`] needs it: the
/// pixel sampler, and for `spp` samples the grid of parts a light's cell is cut into (found once,
/// since the search for it takes up to `√spp` steps).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CameraSamples {
    pub method: Method,
    spp: u32,
    columns: u32,
}

impl CameraSamples {
    pub fn new(method: Method, spp: u32) -> CameraSamples {
        CameraSamples {
            method,
            spp,
            columns: grid_columns(spp),
        }
    }

    /// The samples per pixel this was made for.
    pub fn spp(&self) -> u32 {
        self.spp
    }
}

/// The columns of the most nearly square grid of `n` cells: the largest divisor of `n` that is
/// at most `√n` (1 for a prime).
fn grid_columns(n: u32) -> u32 {
    let root = (n as f64).sqrt() as u32;
    (1..=root.max(1))
        .rev()
        .find(|c| n.is_multiple_of(*c))
        .unwrap_or(1)
}

impl PointSet {
    /// Point `index` of the set.
    #[inline(always)]
    pub fn point(&self, index: u32) -> Vec2 {
        let h = mix64(self.prefix ^ (index as u64).wrapping_add(0x9e37_79b9_7f4a_7c15));
        let u = Vec2::new(to_unit(h), to_unit(mix64(h)));
        match self.method {
            Method::Random => u,
            Method::Jittered => match &self.across {
                None => stratum_point(index, self.count, self.side, u, self.prefix as u32),
                Some(a) => a.point((index % self.side, index / self.side), self.side, u),
            },
            Method::Sobol => sobol2(self.first.wrapping_add(index), self.sobol_seed),
        }
    }
}

/// Point `index` of the 2D Owen-scrambled Sobol set keyed by `seed`: dimensions 0 and 1 of the
/// sequence, both scrambled and shuffled with `seed` so that they stay paired. The crate supports
/// indices below 2^16; later points continue in a fresh, independently seeded copy of the sequence
/// (still well spread, though the set is then no longer one net).
#[inline]
pub fn sobol2(index: u32, seed: u32) -> Vec2 {
    let [x, y, _, _] = sobol4(index, seed);
    Vec2::new(x, y)
}

/// Point `index` of the 4D Owen-scrambled Sobol set keyed by `seed`: dimensions 0 to 3 of the
/// sequence, continued past 2^16 points as [`sobol2`] is (the crate computes the four at once, in
/// SIMD lanes where the CPU has them, with the same integer arithmetic as one at a time).
#[inline]
pub fn sobol4(index: u32, seed: u32) -> [f32; 4] {
    const LEN: u32 = 1 << 16;
    let (block, i) = (index / LEN, index % LEN);
    let seed = if block == 0 {
        seed
    } else {
        (hash(&[seed as u64, block as u64]) >> 32) as u32
    };
    sobol_set0(i, seed)
}

/// The first 16 direction numbers of Sobol dimensions 0 to 3 (Joe and Kuo, "Constructing Sobol
/// sequences with better two-dimensional projections", SIAM J. Sci. Comput. 30(5), 2008; their
/// `new-joe-kuo-6` set, which `sobol_burley` uses), one row per bit of the index from its most
/// significant, each number with its bits reversed as `sobol_burley` stores them. A test checks
/// them against the crate.
const SOBOL_REV_VECTORS: [[u32; 4]; 16] = [
    [0x0000_0001, 0x0000_0001, 0x0000_0001, 0x0000_0001],
    [0x0000_0002, 0x0000_0003, 0x0000_0003, 0x0000_0003],
    [0x0000_0004, 0x0000_0005, 0x0000_0006, 0x0000_0004],
    [0x0000_0008, 0x0000_000f, 0x0000_0009, 0x0000_000a],
    [0x0000_0010, 0x0000_0011, 0x0000_0017, 0x0000_001f],
    [0x0000_0020, 0x0000_0033, 0x0000_003a, 0x0000_002e],
    [0x0000_0040, 0x0000_0055, 0x0000_0071, 0x0000_0045],
    [0x0000_0080, 0x0000_00ff, 0x0000_00a3, 0x0000_00c9],
    [0x0000_0100, 0x0000_0101, 0x0000_0116, 0x0000_011b],
    [0x0000_0200, 0x0000_0303, 0x0000_0339, 0x0000_02a4],
    [0x0000_0400, 0x0000_0505, 0x0000_0677, 0x0000_079a],
    [0x0000_0800, 0x0000_0f0f, 0x0000_09aa, 0x0000_0b67],
    [0x0000_1000, 0x0000_1111, 0x0000_1601, 0x0000_101e],
    [0x0000_2000, 0x0000_3333, 0x0000_3903, 0x0000_302d],
    [0x0000_4000, 0x0000_5555, 0x0000_7706, 0x0000_4041],
    [0x0000_8000, 0x0000_ffff, 0x0000_aa09, 0x0000_a0c3],
];

/// The Sobol matrices of dimensions 0 to 3 applied to every value of one byte of the
/// bit-reversed index: entry `[k][b]` is the XOR of the direction numbers of the bits set in `b`
/// when `b` is byte `k` (0 the most significant) of the index's top 16 bits. The matrices are
/// linear over GF(2), so two lookups give what a walk over the index's set bits gives.
const SOBOL_BYTE_TABLES: [[[u32; 4]; 256]; 2] = {
    let mut tables = [[[0u32; 4]; 256]; 2];
    let mut k = 0;
    while k < 2 {
        let mut b = 0;
        while b < 256 {
            let mut bit = 0;
            while bit < 8 {
                if b & (0x80 >> bit) != 0 {
                    let row = SOBOL_REV_VECTORS[8 * k + bit];
                    let mut lane = 0;
                    while lane < 4 {
                        tables[k][b][lane] ^= row[lane];
                        lane += 1;
                    }
                }
                bit += 1;
            }
            b += 1;
        }
        k += 1;
    }
    tables
};

/// `sobol_burley::sample_4d(index, 0, seed)` bit for bit (`index` < 2^16), with the crate's
/// walk over the index's set bits (one data-dependent step per bit, about half the cost of a
/// point on x86-64's baseline instructions) replaced by two lookups in [`SOBOL_BYTE_TABLES`]; the
/// index shuffle and the Owen scrambling are the crate's own.
#[inline]
fn sobol_set0(index: u32, seed: u32) -> [f32; 4] {
    use sobol_burley::parts::{hash, hash_int4, owen_scramble_int4_rev, owen_scramble_rev, Int4};
    // Burley's nested uniform shuffle of the index, as the crate seeds it.
    let shuffled = owen_scramble_rev(index.reverse_bits(), hash(seed ^ 0x79c6_8e4a));
    let hi = SOBOL_BYTE_TABLES[0][(shuffled >> 24) as usize];
    let lo = SOBOL_BYTE_TABLES[1][((shuffled >> 16) & 0xff) as usize];
    let sobol = Int4::from([0, 1, 2, 3].map(|d| hi[d] ^ lo[d]));
    // The crate's per-dimension scramble keys for dimension set 0.
    let keys = Int4::from([seed.wrapping_mul(0x9c8f_2d3b); 4])
        ^ Int4::from([0x912f_69ba, 0x174f_18ab, 0x691e_72ca, 0xb40c_c1b8]);
    owen_scramble_int4_rev(sobol, hash_int4(keys))
        .reverse_bits()
        .to_f32_norm()
}

/// The lens stratum, on the `k×k` grid of a pixel of `k²` jittered samples, of the camera
/// sample `key` whose film stratum is `film`: the film cell `(i, j)` and the lens cell are one run of a strength-2
/// orthogonal array of four factors (Bose's construction; Jarosz et al., "Orthogonal Array
/// Sampling for Monte Carlo Rendering", EGSR 2019), `(i + j, i + 2j)` over the integers mod `k`
/// for odd `k` and `(i ⊕ j, i ⊕ x·j)` over polynomials mod `x^m + x + 1` for `k = 2^m ≥ 4`.
/// Each lens axis's levels are then shuffled per pixel. Every pair of the four coordinates (film
/// x, film y, lens x, lens y) then puts one sample in each cell of its `k×k` grid: the film
/// against the lens as the film against itself. Two forms `a·i + b·j` and `c·i + d·j` pair
/// that way when `ad − bc` is invertible, as every pair of `i`, `j`, `i + j` and `i + 2j` is
/// for odd `k` (and of `i`, `j`, `i ⊕ j`, `i ⊕ x·j`, where `x` and `x + 1` are invertible mod
/// `x^m + x + 1`, for `k = 2^m`). `None` where no such array is built here: a count that is
/// not a square, `k = 2`, or `k` twice an odd number (the lens then pairs with the film at
/// random, as it did).
fn lens_stratum(key: &SampleKey, film: u32) -> Option<u32> {
    let k = square_side(key.spp);
    if k < 3 {
        return None;
    }
    let (i, j) = (film % k, film / k);
    let (a, b) = if k % 2 == 1 {
        ((i + j) % k, (i + 2 * j) % k)
    } else if k.is_power_of_two() {
        // Multiplying by x mod x^m + x + 1: shift, and fold the overflow back in.
        let mut xj = j << 1;
        if xj >= k {
            xj ^= k | 0b11;
        }
        (i ^ j, i ^ xj)
    } else {
        return None;
    };
    let shuffle = (key.pixel_hash(&[1, 0x0a]) & 0xffff_ffff) as u32;
    // Stratum `x + k·y`, as `stratum_point` lays out a square grid.
    Some(permute(a, k, shuffle) + k * permute(b, k, shuffle.rotate_left(16)))
}

/// The side `k` of the `k×k` grid of strata when `count` is a perfect square, else 0.
fn square_side(count: u32) -> u32 {
    let k = (count as f64).sqrt() as u32;
    if k * k == count {
        k
    } else {
        0
    }
}

/// The point of stratum `index` out of `count` (at least 1), offset by `jitter ∈ [0,1)²` inside
/// its stratum. Perfect squares (`side` = [`square_side`] of `count`, nonzero) use a `k×k` grid;
/// other counts use N-rooks with columns shuffled by `shuffle`.
fn stratum_point(index: u32, count: u32, side: u32, jitter: Vec2, shuffle: u32) -> Vec2 {
    let k = side;
    if k > 0 {
        let (i, j) = (index % k, index / k);
        Vec2::new(
            (i as f32 + jitter.x) / k as f32,
            (j as f32 + jitter.y) / k as f32,
        )
    } else {
        let column = permute(index, count, shuffle);
        Vec2::new(
            (index as f32 + jitter.x) / count as f32,
            (column as f32 + jitter.y) / count as f32,
        )
        .min(Vec2::splat(1.0 - f32::EPSILON / 2.0))
    }
}

/// A pseudo-random permutation of `0..len` evaluated at `i`, keyed by `key`: Kensler's hash-based
/// permutation with cycle walking ("Correlated Multi-Jittered Sampling", Pixar Technical Memo
/// 13-01, 2013, listing 3).
pub fn permute(mut i: u32, len: u32, key: u32) -> u32 {
    if len <= 1 {
        return 0;
    }
    let mut w = len - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    loop {
        i ^= key;
        i = i.wrapping_mul(0xe170893d);
        i ^= key >> 16;
        i ^= (i & w) >> 4;
        i ^= key >> 8;
        i = i.wrapping_mul(0x0929eb3f);
        i ^= key >> 23;
        i ^= (i & w) >> 1;
        i = i.wrapping_mul(1 | key >> 27);
        i = i.wrapping_mul(0x6935fa69);
        i ^= (i & w) >> 11;
        i = i.wrapping_mul(0x74dcb303);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0x9e501cc3);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0xc860a3df);
        i &= w;
        i ^= i >> 5;
        if i < len {
            break;
        }
    }
    (i.wrapping_add(key)) % len
}

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

#[cfg(test)]
mod tests {

    /// A padded dimension is stratified over all of a pixel's points: with 4 camera samples of
    /// 4 points each, jittered puts one point in each cell of a 4×4 grid, and Sobol's 16 points
    /// form a (0,4,2)-net (one in each 1/4 × 1/4 cell too).
    #[test]
    fn padded_points_are_stratified_across_the_pixel() {
        for method in [Method::Jittered, Method::Sobol] {
            let mut cells = [0u32; 16];
            for s in 0..4 {
                let key = SampleKey::new(3, 5, s, 4, 9);
                for j in 0..4 {
                    let u = key.padded(method, 7, j, 4);
                    assert!((0.0..1.0).contains(&u.x) && (0.0..1.0).contains(&u.y));
                    cells[(u.x * 4.0) as usize + 4 * (u.y * 4.0) as usize] += 1;
                }
            }
            assert_eq!(cells, [1; 16], "{method}");
            // The 4D form's first two dimensions are the 2D point.
            let key = SampleKey::new(3, 5, 2, 4, 9);
            if method == Method::Sobol {
                let [a, b, _, _] = key.padded4(method, 7, 1, 4);
                assert_eq!(Vec2::new(a, b), key.padded(method, 7, 1, 4));
            }
        }
    }

    /// The point set's hoisted form against the per-point computation it replaces.
    #[test]
    fn point_set_equals_the_per_point_formula() {
        let reference = |key: &SampleKey, method, dim: u64, i: u32, count: u32| {
            let h = hash(&[key.key, dim, i as u64]);
            let u = Vec2::new(to_unit(h), to_unit(mix64(h)));
            match method {
                Method::Random => u,
                Method::Jittered => {
                    let shuffle = (hash(&[key.key, dim]) & 0xffff_ffff) as u32;
                    stratum_point(i, count, square_side(count), u, shuffle)
                }
                Method::Sobol => sobol2(i, (hash(&[key.key, dim, 0x50b0]) >> 32) as u32),
            }
        };
        let key = SampleKey::new(5, 9, 2, 4, 77).stream(3);
        for method in [Method::Random, Method::Jittered, Method::Sobol] {
            for count in [1, 2, 7, 16, 64, 100, 101] {
                for dim in [0, 3] {
                    let set = key.point_set(method, dim, count);
                    for i in 0..count {
                        let want = reference(&key, method, dim, i, count);
                        assert_eq!(set.point(i), want, "{method:?} {count} {dim} {i}");
                    }
                }
            }
        }
    }

    use super::*;

    /// A packed Sobol point gives back every point it can hold exactly, and keeps a sample key
    /// at 32 bytes.
    #[test]
    fn sobol_pairs_hold_sobol_points_exactly() {
        assert_eq!(SobolPair::NONE.get(), None);
        for seed in [0, 9, 0xfeed_f00d] {
            for i in (0..1u32 << 16).step_by(7).chain([0xffff]) {
                let [a, b, c, d] = sobol4(i, seed);
                for p in [Vec2::new(a, b), Vec2::new(c, d)] {
                    assert_eq!(SobolPair::new(p).get(), Some(p), "{i} {seed}");
                }
            }
        }
        let ends = [0.0, 1.0 - 1.0 / SOBOL_ONE];
        for (x, y) in ends.iter().flat_map(|&x| ends.map(|y| (x, y))) {
            let p = Vec2::new(x, y);
            assert_eq!(SobolPair::new(p).get(), Some(p));
        }
        assert_eq!(std::mem::size_of::<SampleKey>(), 32);
    }

    /// A digital shift is exact and its own inverse, and it maps a Sobol net to a net: the
    /// first 2ᵏ points of a pixel's pattern, shifted alike, still put one point in every
    /// elementary cell of their area.
    #[test]
    fn digital_shifts_keep_nets() {
        for seed in [0, 7, 0xdead_beef] {
            for shift in [
                0u64,
                1,
                0x7f_ffff,
                0x1234_5678_9abc_def0,
                mix64(seed as u64),
            ] {
                let (sx, sy) = (shift as u32, (shift >> 32) as u32);
                for n in [4, 16, 64, 256] {
                    let points: Vec<Vec2> = (0..n)
                        .map(|i| {
                            let p = sobol2(i, seed);
                            let q = Vec2::new(digital_shift(p.x, sx), digital_shift(p.y, sy));
                            assert!((0.0..1.0).contains(&q.x) && (0.0..1.0).contains(&q.y));
                            let back = Vec2::new(digital_shift(q.x, sx), digital_shift(q.y, sy));
                            assert_eq!(back, p);
                            q
                        })
                        .collect();
                    assert!(is_net(&points), "seed {seed}, shift {shift:x}, {n} points");
                }
            }
        }
    }

    /// The table-driven Sobol points against the crate they stand in for, over every index the
    /// crate supports and a spread of seeds.
    #[test]
    fn sobol_tables_reproduce_the_crate() {
        for (d, row) in SOBOL_REV_VECTORS.iter().enumerate() {
            let single = sobol_burley::parts::sobol_int4_rev(0x8000_0000 >> d, 0);
            assert_eq!(
                <[u32; 4]>::from(single),
                *row,
                "direction numbers of bit {d}"
            );
        }
        for seed in [0u32, 1, 0x9e37_79b9, 0xdead_beef, u32::MAX] {
            for index in 0..1u32 << 16 {
                let ours = sobol_set0(index, seed).map(f32::to_bits);
                let crate_point = sobol_burley::sample_4d(index, 0, seed).map(f32::to_bits);
                assert_eq!(ours, crate_point, "index {index}, seed {seed:#x}");
            }
        }
    }

    #[test]
    fn permute_is_a_bijection() {
        for len in [1u32, 2, 3, 7, 16, 100, 257] {
            for key in [0u32, 1, 0xdead_beef] {
                let mut seen = vec![false; len as usize];
                for i in 0..len {
                    let p = permute(i, len, key);
                    assert!(p < len);
                    assert!(!seen[p as usize], "len {len} key {key}: {p} twice");
                    seen[p as usize] = true;
                }
            }
        }
    }

    #[test]
    fn jittered_square_counts_fill_every_cell_once() {
        let key = SampleKey::new(3, 4, 0, 1, 7);
        let mut cells = [0u32; 16];
        for i in 0..16 {
            let p = key.point_set(Method::Jittered, 5, 16).point(i);
            assert!(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0);
            cells[(p.y * 4.0) as usize * 4 + (p.x * 4.0) as usize] += 1;
        }
        assert!(cells.iter().all(|&c| c == 1), "{cells:?}");
    }

    #[test]
    fn jittered_other_counts_are_latin_hypercubes() {
        let n = 12;
        let mut rows = vec![0u32; n];
        let mut cols = vec![0u32; n];
        for s in 0..n as u32 {
            let p = SampleKey::new(1, 2, s, n as u32, 9).pixel_pattern(Method::Jittered, 0);
            rows[(p.x * n as f32) as usize] += 1;
            cols[(p.y * n as f32) as usize] += 1;
        }
        assert!(rows.iter().all(|&c| c == 1) && cols.iter().all(|&c| c == 1));
    }

    /// Whether `points` has exactly one point in each cell of every `2^a × 2^b` grid with
    /// `a + b = log2(points.len())` (the (0,m,2)-net property).
    fn is_net(points: &[Vec2]) -> bool {
        let m = points.len().trailing_zeros();
        (0..=m).all(|a| {
            let (nx, ny) = (1usize << a, 1usize << (m - a));
            let mut cells = vec![0u32; points.len()];
            for p in points {
                cells[(p.y * ny as f32) as usize * nx + (p.x * nx as f32) as usize] += 1;
            }
            cells.iter().all(|&c| c == 1)
        })
    }

    /// Every point of a light set of pixel `(x, y)` under `seed`: `spp` camera samples of `count`
    /// points each, a camera sample's points together.
    fn light_points(
        method: Method,
        across: Method,
        (x, y, seed): (u32, u32, u64),
        spp: u32,
        count: u32,
    ) -> Vec<Vec<Vec2>> {
        (0..spp)
            .map(|s| {
                let set = SampleKey::new(x, y, s, spp, seed).stream(2).light_set(
                    method,
                    &CameraSamples::new(across, spp),
                    0,
                    count,
                );
                (0..count).map(|i| set.point(i)).collect()
            })
            .collect()
    }

    /// How many of `points` fall in each cell of a `columns × rows` grid, row by row.
    fn cell_counts(points: &[Vec2], columns: usize, rows: usize) -> Vec<u32> {
        let mut cells = vec![0u32; columns * rows];
        for p in points {
            assert!(
                (0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y),
                "{p}"
            );
            cells[(p.y * rows as f32) as usize * columns + (p.x * columns as f32) as usize] += 1;
        }
        cells
    }

    /// With one camera sample a light set is the camera sample's own point set, bit for bit.
    #[test]
    fn one_camera_sample_keeps_its_own_light_set() {
        let key = SampleKey::new(5, 9, 0, 1, 77).stream(3);
        for method in [Method::Random, Method::Jittered, Method::Sobol] {
            for across in [Method::Random, Method::Jittered, Method::Sobol] {
                for count in [1, 2, 7, 16, 64] {
                    let (ours, own) = (
                        key.light_set(method, &CameraSamples::new(across, 1), 4, count),
                        key.point_set(method, 4, count),
                    );
                    for i in 0..count {
                        assert_eq!(ours.point(i), own.point(i), "{method} {across} {count}");
                    }
                }
            }
        }
    }

    /// Each camera sample's points are what the light asks for (one in each of its `k×k` cells,
    /// or a Sobol net), and the pixel's points together are stratified finer: jittered cells cut
    /// into one part per camera sample (`√spp` square, else the squarest grid), each part holding
    /// one point, or, spread with Sobol points, each cell's points a net; Sobol, the pixel's
    /// points one net.
    #[test]
    fn light_sets_are_stratified_over_the_pixel() {
        for pixel in [(0, 0, 0), (3, 4, 7), (100, 7, 12345)] {
            for (spp, columns) in [(4, 2), (8, 2), (16, 4), (12, 3)] {
                let rows = spp as usize / columns;
                for across in [Method::Jittered, Method::Sobol] {
                    let sets = light_points(Method::Jittered, across, pixel, spp, 16);
                    for set in &sets {
                        assert_eq!(cell_counts(set, 4, 4), [1; 16], "{across} {spp}");
                    }
                    if across == Method::Jittered {
                        let all: Vec<Vec2> = sets.concat();
                        let cells = cell_counts(&all, 4 * columns, 4 * rows);
                        assert!(cells.iter().all(|&c| c == 1), "{spp}: {cells:?}");
                    } else if spp.is_power_of_two() {
                        // Each cell's points over the pixel, scaled to the unit square: a net.
                        for cell in 0..16 {
                            let corner = Vec2::new((cell % 4) as f32, (cell / 4) as f32);
                            let inside: Vec<Vec2> = sets
                                .iter()
                                .flatten()
                                .map(|p| *p * 4.0 - corner)
                                .filter(|q| q.cmpge(Vec2::ZERO).all() && q.cmplt(Vec2::ONE).all())
                                .collect();
                            assert_eq!(inside.len(), spp as usize);
                            assert!(is_net(&inside), "{spp} cell {cell}: {inside:?}");
                        }
                    }
                }
                // Random cells stay independent: some pixel's part holds two points.
                let all = light_points(Method::Jittered, Method::Random, pixel, spp, 16).concat();
                assert!(cell_counts(&all, 4 * columns, 4 * rows).contains(&0));
            }
            let sets = light_points(Method::Sobol, Method::Jittered, pixel, 8, 16);
            assert!(sets.iter().all(|set| is_net(set)));
            assert!(is_net(&sets.concat()));
        }
    }

    /// The variance of pixel estimates `values` of `truth`, after checking that their mean lies
    /// within four standard errors of it.
    fn unbiased_variance(values: &[f64], truth: f64) -> f64 {
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
        assert!(
            (mean - truth).abs() < 4.0 * (var / n).sqrt() + 1e-9,
            "{mean} against {truth}"
        );
        var
    }

    /// Under a pinhole camera the lights' Sobol pattern over the pixel is the camera sample's own
    /// point, dimensions 2 and 3, so a shadow edge that moves across the light as the point moves
    /// across the pixel is estimated with less variance than by a pattern scrambled apart from
    /// the film, and both estimates are unbiased.
    #[test]
    fn pinhole_film_and_light_points_are_stratified_together() {
        // Lit where the light point lies below a line that rises with the film point's x.
        let lit = |film: Vec2, p: Vec2| f64::from(u8::from(p.y < 0.1 + 0.8 * film.x));
        let truth = 0.5;
        let (spp, count, pixels) = (64, 16, 1000u32);
        let stats = |shared: bool| {
            let values: Vec<f64> = (0..pixels)
                .map(|x| {
                    let camera = CameraSamples::new(Method::Sobol, spp);
                    let mut sum = 0.0;
                    for s in 0..spp {
                        let mut key = SampleKey::new(x, 3, s, spp, 11);
                        let film = if shared {
                            key.pinhole_pattern(Method::Sobol)
                        } else {
                            key.pixel_pattern(Method::Sobol, 0)
                        };
                        let set = key.stream(0).light_set(Method::Jittered, &camera, 0, count);
                        sum += (0..count).map(|i| lit(film, set.point(i))).sum::<f64>();
                    }
                    sum / (spp * count) as f64
                })
                .collect();
            unbiased_variance(&values, truth)
        };
        let (shared, apart) = (stats(true), stats(false));
        // 2.3× less at these settings.
        assert!(shared * 1.5 < apart, "{shared} against {apart}");
    }

    /// The variance of a pixel's estimate of the lit part of a light, 16 camera samples of 16
    /// shadow rays, with a straight edge across the light: sets spread over the pixel cut it at
    /// least threefold against a set per camera sample, and both estimates are unbiased.
    #[test]
    fn light_sets_over_the_pixel_estimate_with_less_variance() {
        // The part of the unit square below the line y = 0.3 + 0.45·x.
        let lit = |p: Vec2| f64::from(u8::from(p.y < 0.3 + 0.45 * p.x));
        let truth = 0.3 + 0.45 / 2.0;
        let (spp, count, pixels) = (16, 16, 2000u32);
        let stats = |estimate: &dyn Fn(u32) -> f64| {
            let values: Vec<f64> = (0..pixels).map(estimate).collect();
            unbiased_variance(&values, truth)
        };
        for (method, across) in [
            (Method::Jittered, Method::Jittered),
            (Method::Jittered, Method::Sobol),
            (Method::Sobol, Method::Jittered),
        ] {
            let total = (spp * count) as f64;
            let own = stats(&|x| {
                (0..spp)
                    .map(|s| {
                        let set = SampleKey::new(x, 1, s, spp, 5).point_set(method, 0, count);
                        (0..count).map(|i| lit(set.point(i))).sum::<f64>()
                    })
                    .sum::<f64>()
                    / total
            });
            let spread = stats(&|x| {
                let sets = light_points(method, across, (x, 1, 5), spp, count);
                sets.concat().into_iter().map(lit).sum::<f64>() / total
            });
            assert!(
                spread * 3.0 < own,
                "{method} {across}: {spread} against {own}"
            );
        }
    }

    #[test]
    fn sobol_sets_are_stratified_nets_in_the_unit_square() {
        for (x, y, seed) in [(0, 0, 0), (3, 4, 7), (100, 7, 12345)] {
            let key = SampleKey::new(x, y, 0, 1, seed).stream(2);
            for m in 0..=8 {
                let n = 1u32 << m;
                let set: Vec<Vec2> = (0..n)
                    .map(|i| key.point_set(Method::Sobol, 0, n).point(i))
                    .collect();
                assert!(set
                    .iter()
                    .all(|p| (0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y)));
                assert!(is_net(&set), "{n} points at ({x}, {y}) seed {seed}");
            }
            // In particular, the first 16 points fill the 4×4 grid one per cell.
            let mut cells = [0u32; 16];
            for i in 0..16 {
                let p = key.point_set(Method::Sobol, 0, 16).point(i);
                cells[(p.y * 4.0) as usize * 4 + (p.x * 4.0) as usize] += 1;
            }
            assert!(cells.iter().all(|&c| c == 1), "{cells:?}");
        }
        // Per-pixel patterns too: the 64 camera samples of a pixel form a net.
        let pattern: Vec<Vec2> = (0..64)
            .map(|s| SampleKey::new(5, 9, s, 64, 3).pixel_pattern(Method::Sobol, 0))
            .collect();
        assert!(is_net(&pattern));
    }

    /// A pixel's film and lens points, camera sample by camera sample: with Sobol points the
    /// film is dimension 0's pattern, every power-of-two prefix of each lens coordinate is
    /// stratified, and film and lens are stratified against each other, where two 2D patterns
    /// scrambled apart pair their points at random.
    #[test]
    fn film_and_lens_points_are_stratified_against_each_other() {
        // Samples whose film coordinate `f` and lens coordinate `l` (0 = x, 1 = y) fall in each
        // cell of a `g×g` grid over the unit square they span.
        let cells = |pairs: &[(Vec2, Vec2)], f: usize, l: usize, g: usize| {
            let mut cells = vec![0u32; g * g];
            for (film, lens) in pairs {
                cells[(film[f] * g as f32) as usize * g + (lens[l] * g as f32) as usize] += 1;
            }
            cells
        };
        let axes = [(0, 0), (0, 1), (1, 0), (1, 1)];
        for (x, y, seed) in [(0, 0, 0), (3, 4, 7), (100, 7, 12345), (17, 90, 2)] {
            let key = |s: u32| SampleKey::new(x, y, s, 64, seed);
            let pairs: Vec<(Vec2, Vec2)> = (0..64)
                .map(|s| key(s).camera_pattern(Method::Sobol))
                .collect();
            for (s, (film, _)) in pairs.iter().enumerate() {
                assert_eq!(*film, key(s as u32).pixel_pattern(Method::Sobol, 0));
            }
            for n in [4, 8, 16, 32, 64] {
                let prefix = &pairs[..n];
                for axis in 0..2 {
                    let mut strata = vec![0u32; n];
                    for (_, lens) in prefix {
                        strata[(lens[axis] * n as f32) as usize] += 1;
                    }
                    assert!(
                        strata.iter().all(|&c| c == 1),
                        "lens axis {axis}, {n} samples"
                    );
                }
                // From 8 samples on: at 4, dimensions 1 to 3 are tied (see `camera_pattern`).
                for (f, l) in axes.into_iter().filter(|_| n >= 8) {
                    let quarters = cells(prefix, f, l, 2);
                    assert_eq!(
                        quarters,
                        [n as u32 / 4; 4],
                        "film {f} lens {l}, {n} samples"
                    );
                }
            }
            for (f, l) in axes {
                assert!(
                    cells(&pairs, f, l, 8).iter().all(|&c| c == 1),
                    "film {f} lens {l}"
                );
            }
            // Two patterns scrambled apart: random pairs, which leave about 64·(63/64)^64 ≈ 23
            // of the 64 cells empty.
            let apart: Vec<(Vec2, Vec2)> = (0..64)
                .map(|s| {
                    let k = key(s);
                    (
                        k.pixel_pattern(Method::Sobol, 0),
                        k.pixel_pattern(Method::Sobol, 1),
                    )
                })
                .collect();
            for (f, l) in axes {
                let empty = cells(&apart, f, l, 8).iter().filter(|&&c| c == 0).count();
                assert!(empty >= 12, "film {f} lens {l}: {empty} empty");
            }
        }
        // Random points are the two patterns they were.
        let key = SampleKey::new(5, 6, 3, 16, 9);
        let (film, lens) = key.camera_pattern(Method::Random);
        assert_eq!(film, key.pixel_pattern(Method::Random, 0));
        assert_eq!(lens, key.pixel_pattern(Method::Random, 1));
    }

    /// Jittered film and lens points of a pixel of `k²` samples, `k` odd or a power of two from
    /// 4: one sample in every cell of the `k×k` grid of each pair of their four coordinates, and
    /// the film the pattern it was. Other counts pair the lens with the film at random, as before.
    #[test]
    fn jittered_film_and_lens_points_form_an_orthogonal_array() {
        for (k, seed) in [
            (3, 0),
            (4, 1),
            (5, 2),
            (7, 3),
            (8, 4),
            (9, 5),
            (16, 6),
            (32, 7),
        ] {
            let n = k * k;
            for (x, y) in [(0, 0), (13, 7), (200, 91)] {
                let key = |s: u32| SampleKey::new(x, y, s, n, seed);
                let points: Vec<[f32; 4]> = (0..n)
                    .map(|s| {
                        let (film, lens) = key(s).camera_pattern(Method::Jittered);
                        assert_eq!(film, key(s).pixel_pattern(Method::Jittered, 0));
                        [film.x, film.y, lens.x, lens.y]
                    })
                    .collect();
                for a in 0..4 {
                    for b in a + 1..4 {
                        let mut cells = vec![0u32; n as usize];
                        for p in &points {
                            let (u, v) = ((p[a] * k as f32) as u32, (p[b] * k as f32) as u32);
                            cells[(u.min(k - 1) * k + v.min(k - 1)) as usize] += 1;
                        }
                        assert!(
                            cells.iter().all(|&c| c == 1),
                            "k = {k}, pixel ({x}, {y}), coordinates {a} and {b}"
                        );
                    }
                }
            }
        }
        for n in [4, 36, 100, 7, 1] {
            for s in 0..n {
                let key = SampleKey::new(5, 6, s, n, 9);
                assert_eq!(
                    key.camera_pattern(Method::Jittered).1,
                    key.pixel_pattern(Method::Jittered, 1),
                    "{n} samples"
                );
            }
        }
    }

    #[test]
    fn sobol_sets_are_deterministic_and_decorrelated() {
        let a = SampleKey::new(10, 20, 3, 8, 42);
        let b = SampleKey::new(10, 20, 3, 8, 42);
        for i in 0..8 {
            assert_eq!(
                a.point_set(Method::Sobol, 0, 8).point(i),
                b.point_set(Method::Sobol, 0, 8).point(i)
            );
            assert_eq!(
                a.pixel_pattern(Method::Sobol, 1),
                b.pixel_pattern(Method::Sobol, 1)
            );
        }
        // Different pixels, seeds, lights (streams) and set dimensions give different points.
        let p = a.point_set(Method::Sobol, 0, 8).point(0);
        assert_ne!(
            p,
            SampleKey::new(11, 20, 3, 8, 42)
                .point_set(Method::Sobol, 0, 8)
                .point(0)
        );
        assert_ne!(
            p,
            SampleKey::new(10, 20, 3, 8, 43)
                .point_set(Method::Sobol, 0, 8)
                .point(0)
        );
        assert_ne!(p, a.stream(1).point_set(Method::Sobol, 0, 8).point(0));
        assert_ne!(p, a.point_set(Method::Sobol, 1, 8).point(0));
        assert_ne!(
            a.pixel_pattern(Method::Sobol, 0),
            a.pixel_pattern(Method::Sobol, 1)
        );
        // Pixel (dimension 0) and lens (dimension 1) patterns are not paired up: over many
        // pixels, the correlation of their x coordinates is near zero.
        let n = 4096;
        let (mut sxy, mut sx, mut sy, mut sxx, mut syy) = (0.0f64, 0.0, 0.0, 0.0, 0.0);
        for k in 0..n {
            let key = SampleKey::new(k % 64, k / 64, k % 16, 16, 1);
            let (u, v) = (
                key.pixel_pattern(Method::Sobol, 0).x as f64,
                key.pixel_pattern(Method::Sobol, 1).x as f64,
            );
            (sx, sy, sxy, sxx, syy) = (sx + u, sy + v, sxy + u * v, sxx + u * u, syy + v * v);
        }
        let nf = n as f64;
        let cov = sxy / nf - sx * sy / nf / nf;
        let r = cov / ((sxx / nf - (sx / nf).powi(2)) * (syy / nf - (sy / nf).powi(2))).sqrt();
        assert!(r.abs() < 0.05, "correlation {r}");
        // Indices past the crate's 2^16 points still give valid, distinct points.
        let far = sobol2(70_000, 9);
        assert!((0.0..1.0).contains(&far.x) && far != sobol2(70_000 - (1 << 16), 9));
        assert_eq!("sobol".parse::<Method>(), Ok(Method::Sobol));
        assert_eq!(Method::Sobol.to_string(), "sobol");
    }

    #[test]
    fn values_depend_only_on_their_coordinates() {
        let a = SampleKey::new(10, 20, 3, 8, 42);
        let b = SampleKey::new(10, 20, 3, 8, 42);
        assert_eq!(a.uniform(5), b.uniform(5));
        assert_ne!(a.uniform(5), a.uniform(6));
        assert_ne!(a.uniform(5), SampleKey::new(10, 20, 3, 8, 43).uniform(5));
        assert_ne!(a.stream(1).uniform(0), a.stream(2).uniform(0));
    }

    #[test]
    fn uniform_values_have_the_right_mean() {
        let key = SampleKey::new(0, 0, 0, 1, 1);
        let n = 100_000;
        let mean: f64 = (0..n).map(|d| key.uniform(d) as f64).sum::<f64>() / n as f64;
        assert!((mean - 0.5).abs() < 0.005, "{mean}");
    }

    /// Half vectors are unit length, and their cosines follow the lobe's distribution: the share
    /// with `cos θ ≥ c` is `1 − c^(e+1)`; for a near-mirror exponent the angles stay resolved.
    #[test]
    fn blinn_phong_half_vectors_follow_the_lobe() {
        for e in [0.0f32, 10.0, 1000.0, 19998.0] {
            let c = 0.5f32.powf(1.0 / (e + 1.0)); // the median cosine
            let n = 4096;
            let mut above = 0;
            for i in 0..n {
                let u = Vec2::new((i as f32 + 0.5) / n as f32, (i * 37 % n) as f32 / n as f32);
                let h = blinn_phong_half_vector(e, u);
                assert!((h.length() - 1.0).abs() < 1e-5, "e {e}: {h}");
                above += (h.z >= c) as usize;
            }
            assert!(
                (above as f32 / n as f32 - 0.5).abs() < 0.01,
                "e {e}: {above}"
            );
        }
        // Near a mirror, neighbouring samples give distinct angles (no 3·10⁻⁴ steps).
        let a = blinn_phong_half_vector(19998.0, Vec2::new(0.5, 0.0)).x;
        let b = blinn_phong_half_vector(19998.0, Vec2::new(0.5001, 0.0)).x;
        assert!(a > 0.0 && a != b && (a - b).abs() < 1e-5, "{a} {b}");
    }

    #[test]
    fn concentric_disk_stays_inside() {
        for i in 0..100 {
            for j in 0..100 {
                let p = concentric_disk(Vec2::new(i as f32 / 99.0, j as f32 / 99.0));
                assert!(p.length() <= 1.0 + 1e-6);
            }
        }
        assert_eq!(concentric_disk(Vec2::splat(0.5)), Vec2::ZERO);
    }
}
