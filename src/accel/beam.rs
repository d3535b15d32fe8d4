//! Beams: the shadow rays from one shading point towards one area light, bounded together by a
//! cone so that the primitives none of them can reach are set aside once per shading point
//! instead of being tested by every ray.
//!
//! A beam is the cone with its apex at the shading point that holds the light's bounding box,
//! cut off at the box's farthest corner. Every shadow ray of the set starts within `offset` of
//! the apex (the robust origin offset) and ends at a point of the box, so it lies within
//! `offset` of the cone. A primitive is set aside only when its bounding sphere, grown by
//! `offset` and by a slack far larger than any rounding in the ray and primitive tests, misses
//! the cut cone: then no ray of the set can hit it, and testing only the candidates answers every
//! any-hit query exactly as testing every primitive does (the property `tests/accel.rs` checks).
//! This is the idea of POV-Ray's light buffer (objects sorted per light direction once, not per
//! ray), cut to one cone per shading point.

use glam::Vec4;

use crate::accel::aabb::Aabb;
use crate::math::{dot4, splat4, sqrt4, Vec3};

/// Relative slack on every distance and cosine of the cone test: rounding in the shadow ray's
/// direction and in the primitive tests is a few units of 2⁻²⁴ (6·10⁻⁸); this is a thousand
/// times more, and costs a candidate only where a primitive grazes the cone.
const SLACK: f32 = 1e-4;

/// Widest cone worth testing: past this half-angle (cosine) nearly everything is a candidate,
/// and the cone test's margins grow; such beams are not made.
const MIN_COS_HALF_ANGLE: f32 = 0.1;

/// The cone holding every shadow ray from one point to one light (see the module docs).
#[derive(Debug, Clone, Copy)]
pub struct Beam {
    apex: Vec3,
    /// Unit axis, from the apex towards the light box's centre.
    axis: Vec3,
    cos_half: f32,
    sin_half: f32,
    /// Distance from the apex to the farthest point of the light box.
    length: f32,
    /// Added to every bounding radius: the origin offset and the absolute slack.
    grow: f32,
    /// The box the rays end in (the light's), grown by the absolute slack: every computed
    /// sample point of the light lies inside, with room to spare.
    ends: Aabb,
}

impl Beam {
    /// The beam from `apex` to every point of `target` for rays whose origins lie within
    /// `offset` of the apex; `None` where a cone does not help (the apex in or next to the box,
    /// or a box that fills more than a hemisphere around it).
    pub fn new(apex: Vec3, target: &Aabb, offset: f32) -> Option<Beam> {
        if !(apex.is_finite() && target.min.is_finite() && target.max.is_finite()) {
            return None;
        }
        let axis = (target.center() - apex).normalize_or_zero();
        if axis == Vec3::ZERO {
            return None;
        }
        let mut min_cos = 1.0f32;
        let mut length = 0.0f32;
        for i in 0..8 {
            let w = target.corner(i) - apex;
            let d = w.length();
            if d == 0.0 {
                return None;
            }
            min_cos = min_cos.min(w.dot(axis) / d);
            length = length.max(d);
        }
        // Widen the cone by the slack (in cosine) and lengthen it.
        let cos_half = min_cos - SLACK;
        if cos_half.is_nan() || cos_half < MIN_COS_HALF_ANGLE {
            return None;
        }
        let scale = apex.abs().max_element() + length;
        Some(Beam {
            apex,
            axis,
            cos_half,
            sin_half: (1.0 - cos_half * cos_half).max(0.0).sqrt(),
            length: length * (1.0 + SLACK),
            grow: offset + SLACK * scale,
            ends: Aabb::new(target.min - SLACK * scale, target.max + SLACK * scale),
        })
    }

    /// Whether no ray of the beam that starts at `origin` can meet the box `b` at any `t ≥ 0`,
    /// decided without rounding: on some axis `origin` lies strictly beyond one side of `b`
    /// and the whole light (grown by the slack) lies at least as far beyond it. Every such ray's
    /// direction then points away from `b` on that axis, or along it (the difference
    /// `target − origin` has the sign of its exact value), so both of the slab test's distances
    /// for that axis are negative ([`crate::accel::aabb::slab`]: a nonzero difference times a
    /// reciprocal of the other sign, or times ∞ for a zero direction component) and the test
    /// rejects `b`. A primitive whose bounds are `b` never reports a hit on such a ray
    /// ([`crate::geometry::Shape::intersect_prepared`] keeps only hits inside its bounds), so
    /// leaving it out changes no answer. This is what a floor's triangles, which hold the
    /// shading points above them in their bounding balls, get from it: every ray towards a light
    /// above them starts above them.
    #[inline]
    pub fn leaves_behind(&self, origin: Vec3, b: &Aabb) -> bool {
        let (lo, hi) = (self.ends.min, self.ends.max);
        (origin.cmpgt(b.max) & lo.cmpge(origin)).any()
            || (origin.cmplt(b.min) & hi.cmple(origin)).any()
    }

    /// Whether no ray of the beam that starts at `origin` can hit a triangle whose bounds are
    /// `b`, where the triangle lies in a plane of constant coordinate (`b` is flat on some
    /// axis) and `origin` lies in that plane or beyond it while the whole light lies strictly
    /// beyond `origin`. Every such ray then moves strictly away from the plane (the difference
    /// `target − origin` is positive), so it meets the plane at `t ≤ 0` exactly, and the
    /// triangle test accepts only a `t` it can prove positive
    /// ([`crate::geometry::Triangle::intersect`], the error bounds of pbrt-v4 §6.8.4). This is
    /// what a point of an axis-aligned floor needs, whose origins lie on the floor's plane
    /// when the hit point is exact: [`Beam::leaves_behind`] asks for them to lie strictly
    /// beyond it.
    #[inline]
    pub fn leaves_plane_behind(&self, origin: Vec3, b: &Aabb) -> bool {
        let (lo, hi) = (self.ends.min, self.ends.max);
        let flat = b.min.cmpeq(b.max);
        (flat & origin.cmpge(b.max) & lo.cmpgt(origin)).any()
            || (flat & origin.cmple(b.min) & hi.cmplt(origin)).any()
    }

    /// Whether some ray of the beam may meet the ball `(center, radius)`; `false` only where
    /// none can.
    #[inline]
    pub fn may_hit_ball(&self, center: Vec3, radius: f32) -> bool {
        let r = radius * (1.0 + SLACK) + self.grow;
        let v = center - self.apex;
        let d2 = v.length_squared();
        if d2.partial_cmp(&(r * r)) != Some(std::cmp::Ordering::Greater) {
            return true; // the apex is in the ball, or a value is NaN
        }
        let d = d2.sqrt();
        if d - r > self.length {
            return false; // beyond the farthest point of the light
        }
        // The ball is seen from the apex within angle β of its centre, sin β = r / d; it meets
        // the cone of half-angle α iff the angle θ between its centre and the axis is at most
        // α + β, i.e. cos θ ≥ cos(α + β).
        let sin_b = r / d;
        let cos_b = (1.0 - sin_b * sin_b).max(0.0).sqrt();
        let cos_sum = self.cos_half * cos_b - self.sin_half * sin_b;
        v.dot(self.axis) >= (cos_sum - SLACK) * d
    }

    /// Whether some ray of the beam may meet `b`, through the box's bounding ball.
    #[inline]
    pub fn may_hit_box(&self, b: &Aabb) -> bool {
        let (center, radius) = b.ball();
        self.may_hit_ball(center, radius)
    }

    /// [`Beam::may_hit_box`] of four boxes (per axis, one lane per box), lane by lane the same
    /// operations: bit `l` is set where box `l` may be met. For the children of a wide BVH node.
    #[inline(always)]
    pub fn may_hit_boxes4(&self, lo: [Vec4; 3], hi: [Vec4; 3]) -> u32 {
        let half = Vec4::splat(0.5);
        let center = [0, 1, 2].map(|a| half * (lo[a] + hi[a]));
        let e = [0, 1, 2].map(|a| hi[a] - lo[a]);
        self.may_hit_balls4(center, half * sqrt4(dot4(&e, &e)))
    }

    /// [`Beam::may_hit_ball`] of four balls (per axis, one lane per centre), lane by lane the
    /// same operations: bit `l` is set where ball `l` may be met.
    #[inline(always)]
    pub fn may_hit_balls4(&self, center: [Vec4; 3], radius: Vec4) -> u32 {
        let r = radius * Vec4::splat(1.0 + SLACK) + Vec4::splat(self.grow);
        let apex = self.apex.to_array();
        let v = [0, 1, 2].map(|a| center[a] - Vec4::splat(apex[a]));
        let d2 = dot4(&v, &v);
        // The apex in the ball, or a NaN: `d2 > r²` fails.
        let near = !d2.cmpgt(r * r).bitmask() & 0b1111;
        let d = sqrt4(d2);
        let within = !(d - r).cmpgt(Vec4::splat(self.length)).bitmask() & 0b1111;
        let sin_b = r / d;
        let cos_b = sqrt4((Vec4::ONE - sin_b * sin_b).max(Vec4::ZERO));
        let cos_sum = Vec4::splat(self.cos_half) * cos_b - Vec4::splat(self.sin_half) * sin_b;
        let along = dot4(&v, &splat4(self.axis));
        let in_cone = along.cmpge((cos_sum - Vec4::splat(SLACK)) * d).bitmask();
        near | (within & in_cone)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn light() -> Aabb {
        Aabb::new(Vec3::new(-1.0, 5.0, -1.0), Vec3::new(1.0, 5.0, 1.0))
    }

    #[test]
    fn balls_on_the_way_are_candidates_and_balls_aside_are_not() {
        let beam = Beam::new(Vec3::ZERO, &light(), 1e-6).unwrap();
        assert!(beam.may_hit_ball(Vec3::new(0.0, 2.5, 0.0), 0.1));
        // At height 2.5 the cone's radius is about 0.5: a ball just past it still touches.
        assert!(beam.may_hit_ball(Vec3::new(0.75, 2.5, 0.0), 0.3));
        assert!(!beam.may_hit_ball(Vec3::new(2.0, 2.5, 0.0), 0.3));
        // Behind the apex, and beyond the light.
        assert!(!beam.may_hit_ball(Vec3::new(0.0, -2.0, 0.0), 1.0));
        assert!(!beam.may_hit_ball(Vec3::new(0.0, 8.0, 0.0), 1.0));
        // Holding the apex.
        assert!(beam.may_hit_ball(Vec3::new(0.0, -0.5, 0.0), 1.0));
    }

    #[test]
    fn wide_or_degenerate_beams_are_not_made() {
        // The apex inside the light box, or level with a light that spans around it.
        assert!(Beam::new(Vec3::new(0.0, 5.0, 0.0), &light(), 0.0).is_none());
        let flat = Aabb::new(Vec3::new(-10.0, 0.0, -10.0), Vec3::new(10.0, 0.1, 10.0));
        assert!(Beam::new(Vec3::ZERO, &flat, 0.0).is_none());
        let nan = Aabb::new(Vec3::splat(f32::NAN), Vec3::ONE);
        assert!(Beam::new(Vec3::ZERO, &nan, 0.0).is_none());
    }

    /// Every ray from near the apex to a point of the light that meets a ball finds the ball
    /// among the candidates (a brute-force check of the cone test's conservatism).
    #[test]
    fn four_boxes_are_four_times_one() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32 * 8.0 - 4.0
        };
        let mut hits = 0;
        for i in 0..4000 {
            let apex = Vec3::new(next(), next(), next());
            let Some(beam) = Beam::new(apex, &light(), 1e-5 * (i % 3) as f32) else {
                continue;
            };
            let boxes: [Aabb; 4] = std::array::from_fn(|l| match (i + l) % 7 {
                0 => Aabb::EMPTY,
                1 => Aabb::new(Vec3::splat(f32::NAN), Vec3::ONE),
                _ => {
                    let c = Vec3::new(next(), next(), next());
                    let h = Vec3::new(next(), next(), next()).abs() * 0.3;
                    Aabb::new(c - h, c + h)
                }
            });
            let lo = [0, 1, 2].map(|a| Vec4::from_array(boxes.map(|b| b.min[a])));
            let hi = [0, 1, 2].map(|a| Vec4::from_array(boxes.map(|b| b.max[a])));
            let lanes = beam.may_hit_boxes4(lo, hi);
            for (l, b) in boxes.iter().enumerate() {
                assert_eq!(
                    lanes & (1 << l) != 0,
                    beam.may_hit_box(b),
                    "{b:?} from {apex}"
                );
            }
            hits += lanes.count_ones();
        }
        assert!(hits > 2000, "{hits}");
    }

    #[test]
    fn no_ball_that_a_ray_meets_is_set_aside() {
        let mut s = 0x9e37_79b9u32;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            s as f32 / u32::MAX as f32
        };
        let target = light();
        let mut checked = 0;
        for _ in 0..300 {
            let apex = Vec3::new(next() * 6.0 - 3.0, next() * 3.0 - 1.0, next() * 6.0 - 3.0);
            let Some(beam) = Beam::new(apex, &target, 1e-5) else {
                continue;
            };
            for _ in 0..50 {
                let center = Vec3::new(next() * 6.0 - 3.0, next() * 6.0 - 0.5, next() * 6.0 - 3.0);
                let radius = next() * 0.5;
                if beam.may_hit_ball(center, radius) {
                    continue;
                }
                for _ in 0..50 {
                    let q = Vec3::new(next() * 2.0 - 1.0, 5.0, next() * 2.0 - 1.0);
                    // The closest point of the segment apex → q to the centre.
                    let d = q - apex;
                    let s = ((center - apex).dot(d) / d.length_squared()).clamp(0.0, 1.0);
                    let gap = (apex + s * d - center).length() - radius;
                    assert!(gap > 0.0, "{apex} → {q} meets ball {center} r {radius}");
                    checked += 1;
                }
            }
        }
        assert!(checked > 10_000, "{checked}");
    }
}
