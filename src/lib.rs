//! `raytracer`: a Whitted/distribution ray tracer for the coursework JSON scene format.
//!
//! Data flows one way: JSON → [`scene::Scene`] → [`accel::Bvh`] → [`integrator`] → [`film::Film`] →
//! [`image_io`]. See `docs/ARCHITECTURE.md`.

pub mod accel;
pub mod batch;
pub mod bench;
pub mod camera;
pub mod cli;
pub mod files;
pub mod film;
pub mod geometry;
pub mod image_io;
pub mod integrator;
pub mod light;
pub mod material;
pub mod math;
pub mod memory;
pub mod metric;
pub mod parts;
pub mod ray;
pub mod render;
pub mod sampling;
pub mod scene;
pub mod study;
pub mod texture;
