//! Sets of sample points for one shading point, and the camera sample's film and lens points.

use crate::math::Vec2;

use super::*;

/// `count` sample points in the unit square for one shading point (see
/// [`SampleKey::point_set`] and [`SampleKey::light_set`]), with everything that does not depend
/// on the point's index worked out once.
#[derive(Debug, Clone, Copy)]
pub struct PointSet {
    pub(super) method: Method,
    pub(super) count: u32,
    pub(super) prefix: u64,
    /// [`square_side`] of `count`.
    pub(super) side: u32,
    pub(super) sobol_seed: u32,
    /// Sobol: the index of point 0 in the seed's sequence.
    pub(super) first: u32,
    /// Jittered cells: how the pixel's camera samples share each cell; `None`: each camera
    /// sample's point is anywhere in its cell.
    pub(super) shared_cells: Option<SharedCells>,
}

/// How one camera sample places its points in a light's jittered cells (see
/// [`SampleKey::light_set`]). Over the pixel's camera samples every cell is stratified, each cell
/// by the same pattern turned by an offset of its own, so that one camera sample's points lie at
/// unrelated places in their cells, as independent jitter would put them.
#[derive(Debug, Clone, Copy)]
pub(super) struct SharedCells {
    /// The pixel's key of the set: a cell's offset is a hash of it and the cell.
    pub(super) key: u64,
    pub(super) pattern: CellPattern,
}

/// The pattern a light's cell is stratified with over a pixel's camera samples.
#[derive(Debug, Clone, Copy)]
pub(super) enum CellPattern {
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

impl SharedCells {
    /// The pattern of `camera_sample`, its pixel's camera samples placed with `method`, under
    /// the set's pixel key `key`, with a grid of parts `columns` wide when they are jittered.
    pub(super) fn new(
        method: Method,
        key: u64,
        camera_sample: &SampleKey,
        columns: u32,
    ) -> SharedCells {
        let (sample, spp) = (camera_sample.sample, camera_sample.spp);
        let pattern = match method {
            Method::Sobol => CellPattern::Sobol(
                camera_sample
                    .light_point
                    .get()
                    .unwrap_or_else(|| sobol2(sample, (key >> 32) as u32)),
            ),
            Method::Random | Method::Jittered => {
                let part = permute(sample, spp, key as u32);
                CellPattern::Parts {
                    part: (part % columns, part / columns),
                    grid: (columns, spp / columns),
                }
            }
        };
        SharedCells { key, pattern }
    }

    /// The point in cell `(x, y)` of a `side × side` grid, with `u` the point's own random
    /// offset in its part.
    #[inline]
    fn point(&self, (x, y): (u32, u32), side: u32, u: Vec2) -> Vec2 {
        let offset = mix64(self.key ^ (y * side + x) as u64);
        let (fine_x, fine_y, per_cell) = match self.pattern {
            CellPattern::Parts { part, grid } => {
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
            CellPattern::Sobol(p) => {
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
/// points stratified over the pixel. Exact: the conversions only move bits.
#[inline]
pub(super) fn digital_shift(u: f32, shift: u32) -> f32 {
    from_sobol_bits(sobol_bits(u) ^ shift)
}

/// How a render places each pixel's camera samples, as [`SampleKey::light_set`] needs it: the
/// pixel sampler, and for `spp` samples the grid of parts a light's cell is cut into (found once,
/// since the search for it takes up to `√spp` steps).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CameraSamples {
    pub method: Method,
    pub(super) spp: u32,
    pub(super) columns: u32,
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
pub(super) fn grid_columns(n: u32) -> u32 {
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
            Method::Jittered => match &self.shared_cells {
                None => stratum_point(index, self.count, self.side, u, self.prefix as u32),
                Some(a) => a.point((index % self.side, index / self.side), self.side, u),
            },
            Method::Sobol => sobol2(self.first.wrapping_add(index), self.sobol_seed),
        }
    }
}
