//! SIMD kernels of the accelerators: one ray against four shapes at once, in `glam::Vec4` lanes
//! ([`Sphere4`], [`Triangle4`]), four rays against one shape ([`Rays4`], for the shadow rays
//! of an area light), and eight boxes against one ray in one AVX register ([`boxes8`], for the
//! eight-wide tree where the CPU has AVX2: [`Isa`]).
//!
//! Each kernel has a scalar twin in [`crate::geometry`]
//! ([`crate::geometry::Shape::intersect_prepared`]) and gives, lane for lane, the bits that twin
//! gives: every step is an IEEE `f32` operation in the twin's order (Rust never fuses them), and
//! `min`/`max`, which differ from `f32::min`/`f32::max` only for NaN, are reached only by values
//! that cannot be NaN or are meant to ignore NaN as the twin does. Whatever a kernel cannot settle that way it hands back to the twin
//! ([`Hits4::scalar`]). Each kernel's tests compare it with its twin bit for bit on adversarial
//! rays, so the BVHs built on them keep the contract of [`crate::accel`]. The twin of the box
//! kernel [`boxes8`] is the four-lane node test of the wide trees, which the slab test of
//! [`crate::accel::aabb`] is in turn the twin of.

pub mod boxes8;
pub mod isa;
pub mod ray4;
pub mod rays4;
pub mod sphere4;
pub mod triangle4;

pub use isa::Isa;
pub use ray4::{Hits4, Ray4};
pub use rays4::Rays4;
pub use sphere4::Sphere4;
pub use triangle4::Triangle4;

use glam::Vec4;

/// Nine rows of four lanes: what a leaf block stores for the kernel that tests it (a
/// [`Triangle4`]'s corners, a [`Sphere4`]'s centres and radii), so that blocks of either kind
/// have one size and need no tag of their own.
pub type Rows = [[Vec4; 3]; 3];

/// What the kernels' tests share (and other tests borrow the generator): a small generator, and
/// the comparison with the scalar twin.
#[cfg(test)]
pub(crate) mod twin {
    use super::Hits4;
    use crate::geometry::{Candidate, Shape};
    use crate::math::Vec3;
    use crate::ray::PreparedRay;

    /// Xorshift64: uniform `f32` in `[0, 1)`.
    pub struct Rng(pub u64);

    impl Rng {
        pub fn next(&mut self) -> f32 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 40) as f32 / (1u64 << 24) as f32
        }

        /// A point of the cube of side `s` centred on the origin.
        pub fn vec(&mut self, s: f32) -> Vec3 {
            Vec3::new(self.next() - 0.5, self.next() - 0.5, self.next() - 0.5) * s
        }
    }

    /// Asserts that every lane of `h` not left to the scalar test holds, bit for bit, what the
    /// scalar twin gives for `shapes[l]` under `t_max`.
    pub fn assert_twin(h: &Hits4, shapes: &[Shape; 4], pr: &PreparedRay, t_max: f32) {
        assert_eq!(h.hit & h.scalar, 0);
        let bits = |c: Option<Candidate>| c.map(|c| [c.t, c.aux[0], c.aux[1]].map(f32::to_bits));
        for (l, shape) in shapes.iter().enumerate() {
            if h.scalar & (1 << l) != 0 {
                continue;
            }
            let want = shape.intersect_prepared(pr, t_max);
            let got = (h.hit & (1 << l) != 0).then(|| Candidate {
                t: h.t[l],
                aux: [h.b1[l], h.b2[l]],
            });
            assert_eq!(
                bits(got),
                bits(want),
                "lane {l} of {shapes:?}, ray {:?}, t_max {t_max}",
                pr.ray
            );
        }
    }
}
