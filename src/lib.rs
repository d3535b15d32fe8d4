//! `raytracer`: a Whitted/distribution ray tracer and path tracer for the coursework JSON scene
//! format.
//!
//! Data flows one way: JSON → [`scene::Scene`] ([`scene::load()`]) → [`accel::Accel`] →
//! [`integrator`] → [`film::Film`] ([`render::render`]) → a file ([`image_io::write_image`]); a
//! render split into tiles or sample ranges is written and merged by [`parts`]. The command line
//! and its tools (`bench`, `study`, `batch`, `compare`) are the binary's, in `src/cli/`. See
//! `docs/ARCHITECTURE.md`.

pub mod accel;
pub mod camera;
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
pub mod texture;
