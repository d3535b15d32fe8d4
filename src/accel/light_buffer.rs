//! Light buffers: per direction from a light, the primitives its shadow rays may meet, found once
//! for the whole render instead of by a tree walk at every shading point. This is the idea of
//! POV-Ray's light buffer (Haines and Greenberg, "The Light Buffer: A Shadow-Testing
//! Accelerator", IEEE CG&A 6(9), 1986): a cube around the light's centre, each face cut into
//! `RES × RES` cells, each cell holding the primitives some shadow ray from a point in its
//! directions may hit.
//!
//! Why a cell's list holds every such primitive: a shadow ray runs from an origin `O` (within
//! `offset` of a shading point `P`) to a point `Q` of the light (within `radius` of the centre
//! `C`). A point `s·O + (1 − s)·Q` of it lies within `(1 − s)·|Q − C| + s·|O − P| ≤ radius +
//! offset` of the point `s·P + (1 − s)·C` of the segment from `P` to `C`, which lies in the cone
//! of `P`'s cell (apex `C`). So every ray from `P`'s cell meets only primitives whose bounding
//! ball, grown by `radius + offset`, meets the cell's cone: the [`Beam`] test, with the beam's
//! slack for rounding. A buffer is built for origins up to [`LightBuffer::max_offset`] from
//! their points; a point whose origins lie farther is answered by the tree.
//!
//! The Whitted tracer asks a buffer in place of [`Accel::beam_candidates`]: the cell's list,
//! filtered by the shading point's own beam ([`LightBuffer::beam_candidates`]), holds every
//! primitive the tree's walk finds, so testing it answers every shadow ray as testing every
//! primitive does (`tests/accel.rs` checks it), for a few dozen ball tests instead of a walk.

use glam::Vec4;

use super::aabb::Aabb;
use super::leaves::lanes;
use super::{ball_of, Accel, Beam};
use crate::geometry::Primitives;
use crate::math::Vec3;

/// Cells along each edge of a cube face: 6 · 16² = 1,536 cells, each about 7° across.
const RES: usize = 16;

/// Longest list a cell keeps; past it (and where its cone could not be made) the cell keeps none
/// and its points walk the tree.
const CELL_LIMIT: usize = 48;

/// The count of a cell that keeps no list.
const FULL: u32 = u32::MAX;

/// How far from their shading point the ray origins a buffer serves may lie, relative to the
/// scene's reach from the light: the robust origin offsets are a few units of 2⁻²³ of the
/// coordinates, a hundredth of this.
const OFFSET_FRACTION: f32 = 1e-4;

/// Four primitives of a cell's list and the balls [`super::may_hit`] tests them by, one lane each
/// (an unbounded primitive's ball is infinite: every beam may hit it).
#[derive(Debug, Clone, Copy)]
struct Balls4 {
    center: [Vec4; 3],
    radius: Vec4,
    numbers: [u32; 4],
}

/// The primitives the shadow rays of one light may meet, per direction from its centre.
#[derive(Debug, Clone)]
pub struct LightBuffer {
    centre: Vec3,
    /// The largest origin offset the lists allow for.
    max_offset: f32,
    /// Per cell, the first of its blocks of `balls` and its number of primitives, or a count of
    /// [`FULL`].
    cells: Vec<(u32, u32)>,
    /// Each cell's list, four primitives a block (the last block of a cell padded).
    balls: Vec<Balls4>,
}

impl LightBuffer {
    /// The buffer of a light whose every sample point lies within `radius` of `centre`, over the
    /// primitives `prims`, gathered through `accel`; `bounds` holds every bounded primitive
    /// ([`Primitives::bounds`]).
    pub fn new(
        centre: Vec3,
        radius: f32,
        prims: &Primitives,
        accel: &Accel,
        bounds: &Aabb,
    ) -> LightBuffer {
        // Every cone reaches past every bounded primitive: each cell's square is set at the
        // distance of the bounds' farthest corner, and a cone is as long as its farthest corner.
        let reach = (0..8)
            .map(|i| bounds.corner(i).distance(centre))
            .fold(0.0f32, f32::max);
        let max_offset = OFFSET_FRACTION * (centre.abs().max_element() + reach);
        let mut balls = Vec::new();
        let mut cells = Vec::with_capacity(6 * RES * RES);
        let mut candidates = Vec::new();
        for cell in 0..6 * RES * RES {
            let listed = cell_square(centre, reach, cell)
                .and_then(|square| Beam::new(centre, &square, radius + max_offset))
                .is_some_and(|cone| {
                    accel.beam_candidates(prims, &cone, CELL_LIMIT, &mut candidates)
                });
            if listed {
                cells.push((balls.len() as u32, candidates.len() as u32));
                balls.extend(candidates.chunks(4).map(|four| block(prims, four)));
            } else {
                cells.push((0, FULL));
            }
        }
        LightBuffer {
            centre,
            max_offset,
            cells,
            balls,
        }
    }

    /// The largest distance from its shading point a ray origin may lie at for the buffer to
    /// serve it.
    pub fn max_offset(&self) -> f32 {
        self.max_offset
    }

    /// The blocks of the list of the cell of `point` and the number of primitives in them, for
    /// rays leaving from within `offset` of `point`; `None` where the tree must answer (a point
    /// at the centre, an offset past [`LightBuffer::max_offset`], or a cell that keeps no list).
    #[inline]
    fn list(&self, point: Vec3, offset: f32) -> Option<(&[Balls4], usize)> {
        if offset.is_nan() || offset > self.max_offset {
            return None;
        }
        let (start, count) = self.cells[cell_of(point - self.centre)?];
        if count == FULL {
            return None;
        }
        let blocks = start as usize..start as usize + (count as usize).div_ceil(4);
        Some((&self.balls[blocks], count as usize))
    }

    /// Every primitive a shadow ray of the light may meet when it leaves from within `offset` of
    /// `point`, in list order (for the tests); `None` where the tree must answer (as for
    /// [`LightBuffer::beam_candidates`]).
    #[cfg(test)]
    fn primitives(&self, point: Vec3, offset: f32) -> Option<Vec<u32>> {
        let (blocks, count) = self.list(point, offset)?;
        Some(blocks.iter().flat_map(|b| b.numbers).take(count).collect())
    }

    /// What [`Accel::beam_candidates`] gives for `beam`, the beam of the shading point `point`
    /// (rays leaving from within `offset` of it) to this light, from the list of the point's
    /// cell: those of its primitives the beam may hit ([`Beam::may_hit_ball`], four at a time), in
    /// `out`; `false` past `limit`, as there. `None` where the buffer has no list for the point (a
    /// point at the centre, an offset past [`LightBuffer::max_offset`], or a cell that keeps no
    /// list): then ask the accelerator.
    pub fn beam_candidates(
        &self,
        beam: &Beam,
        point: Vec3,
        offset: f32,
        limit: usize,
        out: &mut Vec<u32>,
    ) -> Option<bool> {
        let (blocks, count) = self.list(point, offset)?;
        out.clear();
        for (k, b) in blocks.iter().enumerate() {
            let used = (1u32 << (count - 4 * k).min(4)) - 1;
            for l in lanes(beam.may_hit_balls4(b.center, b.radius) & used) {
                if out.len() >= limit {
                    return Some(false);
                }
                out.push(b.numbers[l]);
            }
        }
        Some(true)
    }
}

/// The block of the primitives `four` (one to four), each with the ball [`ball_of`] gives it
/// (an infinite one for an unbounded shape); the lanes past them hold copies of the first.
fn block(prims: &Primitives, four: &[u32]) -> Balls4 {
    let lane = |l: usize| {
        let p = four[if l < four.len() { l } else { 0 }];
        let ball = ball_of(&prims.shape(p)).unwrap_or((Vec3::ZERO, f32::INFINITY));
        (p, ball)
    };
    let lanes: [(u32, (Vec3, f32)); 4] = std::array::from_fn(lane);
    Balls4 {
        center: [0, 1, 2].map(|a| Vec4::from_array(lanes.map(|(_, (c, _))| c[a]))),
        radius: Vec4::from_array(lanes.map(|(_, (_, r))| r)),
        numbers: lanes.map(|(p, _)| p),
    }
}

/// The face (0–5: +x, −x, +y, −y, +z, −z) of direction `d`, and its other two coordinates
/// divided by the largest (each in [−1, 1]).
#[inline]
fn face_of(d: Vec3) -> (usize, f32, f32) {
    let a = d.abs();
    let (axis, major, u, v) = if a.x >= a.y && a.x >= a.z {
        (0, d.x, d.y, d.z)
    } else if a.y >= a.z {
        (1, d.y, d.x, d.z)
    } else {
        (2, d.z, d.x, d.y)
    };
    let m = major.abs();
    (2 * axis + (major < 0.0) as usize, u / m, v / m)
}

/// The cell holding direction `d`; `None` for a zero or non-finite `d`.
#[inline]
fn cell_of(d: Vec3) -> Option<usize> {
    if !d.is_finite() || d == Vec3::ZERO {
        return None;
    }
    let (face, u, v) = face_of(d);
    // u, v ∈ [−1, 1]; the cell of 1 is the last one (cells are closed on both sides).
    let step = |w: f32| (((w + 1.0) * (0.5 * RES as f32)) as usize).min(RES - 1);
    Some((face * RES + step(u)) * RES + step(v))
}

/// The square of cell `cell`'s directions at distance `reach` from `apex`, as a flat box: the
/// directions from `apex` of its points are those of the cell.
fn cell_square(apex: Vec3, reach: f32, cell: usize) -> Option<Aabb> {
    if !(reach > 0.0 && reach.is_finite()) {
        return None;
    }
    let (face, i, j) = (cell / (RES * RES), cell / RES % RES, cell % RES);
    let (axis, sign) = (face / 2, if face % 2 == 0 { 1.0 } else { -1.0 });
    let others = match axis {
        0 => [1, 2],
        1 => [0, 2],
        _ => [0, 1],
    };
    let edge = |k: usize| 2.0 * k as f32 / RES as f32 - 1.0;
    let mut min = apex;
    let mut max = apex;
    min[axis] += sign * reach;
    max[axis] += sign * reach;
    for (other, k) in others.into_iter().zip([i, j]) {
        min[other] += edge(k) * reach;
        max[other] += edge(k + 1) * reach;
    }
    Some(Aabb::new(min, max))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::AccelKind;
    use crate::geometry::{Primitive, Shape, Sphere};

    #[test]
    fn every_direction_has_one_cell_and_its_square_holds_it() {
        let mut state = 7u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 40) as f32 / (1u64 << 23) as f32 - 1.0
        };
        for _ in 0..20_000 {
            let d = Vec3::new(next(), next(), next());
            let Some(cell) = cell_of(d) else { continue };
            let square = cell_square(Vec3::ZERO, 3.0, cell).unwrap();
            // The point of direction d on the cell's face, scaled as the square is.
            let axis = face_of(d).0 / 2;
            let p = d * (3.0 / d[axis].abs());
            let tol = 1e-5;
            assert!(
                (p.cmpge(square.min - tol) & p.cmple(square.max + tol)).all(),
                "{d} in cell {cell}"
            );
        }
        assert_eq!(cell_of(Vec3::ZERO), None);
        assert_eq!(cell_of(Vec3::new(f32::NAN, 0.0, 1.0)), None);
        // The cube's edges and corners, and the middles of faces, have a cell.
        for d in [
            Vec3::ONE,
            -Vec3::ONE,
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::X,
            -Vec3::Z,
        ] {
            assert!(cell_of(d).is_some_and(|c| c < 6 * RES * RES), "{d}");
        }
    }

    #[test]
    fn a_cell_past_the_limit_keeps_no_list() {
        // Many small spheres in one direction from the light: the cells towards them are full.
        let records = (0..64)
            .map(|i| Primitive {
                shape: Shape::Sphere(Sphere::new(
                    Vec3::new((i % 8) as f32 * 0.01, (i / 8) as f32 * 0.01, 5.0),
                    0.004,
                    Vec3::Y,
                    Vec3::X,
                )),
                material: 0,
            })
            .collect();
        let prims = Primitives::from_records(records, Vec::new());
        let accel = Accel::build(&prims, AccelKind::Sah4, 4);
        let buffer = LightBuffer::new(Vec3::ZERO, 0.1, &prims, &accel, &prims.bounds());
        assert_eq!(buffer.primitives(Vec3::new(0.0, 0.0, 10.0), 0.0), None);
        // Away from them, an empty list.
        let behind = Vec3::new(0.0, 0.0, -10.0);
        assert_eq!(buffer.primitives(behind, 0.0), Some(vec![]));
        // At the centre, or for origins too far from their point, none.
        assert_eq!(buffer.primitives(Vec3::ZERO, 0.0), None);
        let far = 2.0 * buffer.max_offset();
        assert_eq!(buffer.primitives(behind, far), None);
        assert_eq!(buffer.primitives(behind, f32::NAN), None);
        // Beside them, a list of some of them.
        let side = buffer.primitives(Vec3::new(0.0, 0.7, 5.0), 0.0).unwrap();
        assert!(side.len() < 64, "{side:?}");
    }
}
