//! SIMD kernels of the accelerators: one ray against four shapes at once, in `glam::Vec4` lanes.
//!
//! Each kernel has a scalar twin in [`crate::geometry`] ([`crate::geometry::Shape::intersect_prepared`])
//! and gives, lane for lane, the bits that twin gives: every step is an IEEE `f32` operation in
//! the twin's order (Rust never fuses them), and `min`/`max`, which differ from `f32::min`/`f32::max`
//! only for NaN, are reached only by values that cannot be NaN or are meant to ignore NaN as the
//! twin does. Whatever a kernel cannot settle that way it hands back to the twin
//! ([`Hits4::scalar`]). Each kernel's tests compare it with its twin bit for bit on adversarial
//! rays, so the BVHs built on them keep the contract of [`crate::accel`].

pub mod ray4;
pub mod sphere4;
pub mod triangle4;

pub use ray4::{Hits4, Ray4};
pub use sphere4::Sphere4;
pub use triangle4::Triangle4;
