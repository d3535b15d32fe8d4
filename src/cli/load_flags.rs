//! The flags that say how a scene is read: the image size, where assets are found, and the
//! limits that refuse a scene too large for this machine. Every command that loads scenes for a
//! render takes them (`raytracer SCENE OUT`, `batch`, `check`, `watch`).

use std::path::PathBuf;

use raytracer::scene::LoadOptions;

/// How a scene is read, from the command line.
#[derive(clap::Args, Debug)]
pub(crate) struct LoadFlags {
    /// Override the image width (keeps the aspect ratio unless --height is also given).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    width: Option<u32>,
    /// Override the image height.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    height: Option<u32>,
    /// Extra folder to resolve texture and mesh paths against (repeatable).
    #[arg(long = "asset-dir")]
    asset_dirs: Vec<PathBuf>,
    /// Refuse images with more pixels than this.
    #[arg(long, default_value_t = raytracer::scene::load::DEFAULT_MAX_PIXELS)]
    max_pixels: u64,
    /// Refuse scenes whose nbounces is larger than this.
    #[arg(long, default_value_t = raytracer::scene::load::DEFAULT_MAX_BOUNCES)]
    max_bounces: u32,
    /// Refuse scenes with more triangles than this.
    #[arg(long, default_value_t = raytracer::scene::load::DEFAULT_MAX_TRIANGLES)]
    max_triangles: usize,
    /// Refuse area lights that take more shadow rays per shading point than this.
    #[arg(long, default_value_t = raytracer::scene::load::DEFAULT_MAX_LIGHT_SAMPLES)]
    max_light_samples: u32,
    /// Refuse scenes that ask for more samples per pixel than this (`pixelsample` and its
    /// spellings; --spp is not limited by it).
    #[arg(long, default_value_t = raytracer::scene::load::DEFAULT_MAX_PIXEL_SAMPLES)]
    max_pixel_samples: u32,
    /// Refuse scene files larger than this many bytes (checked before reading; the parsed
    /// document takes about ten times the file's size).
    #[arg(long, default_value_t = raytracer::scene::load::DEFAULT_MAX_SCENE_BYTES)]
    max_scene_bytes: u64,
    /// Refuse textures with more texels (width × height) than this, read from the image's header
    /// before decoding (a texture takes 3 bytes a texel from an 8-bit image, 12 from a 16-bit or
    /// EXR one; the default is 8192², 192 or 768 MiB).
    #[arg(long, default_value_t = raytracer::scene::load::DEFAULT_MAX_TEXTURE_PIXELS)]
    max_texture_pixels: u64,
    /// Refuse mesh files (PLY, OBJ) larger than this many bytes; they are read whole.
    #[arg(long, default_value_t = raytracer::scene::load::DEFAULT_MAX_MESH_BYTES)]
    max_mesh_bytes: u64,
    /// Refuse mesh files whose triangles and vertices would need more than this many bytes to
    /// load and trace (about 200 a triangle), checked from their counts before they are read.
    /// Default: the memory the process can have (available memory and swap, within its
    /// address-space limit).
    #[arg(long, value_name = "BYTES")]
    max_memory: Option<u64>,
}

impl LoadFlags {
    /// The image size the flags ask for, each side if given.
    pub(crate) fn size(&self) -> (Option<u32>, Option<u32>) {
        (self.width, self.height)
    }

    /// The load options these flags ask for; the memory limit defaults to what the process can
    /// have.
    pub(crate) fn options(&self) -> LoadOptions {
        LoadOptions {
            width: self.width,
            height: self.height,
            asset_dirs: self.asset_dirs.clone(),
            max_pixels: self.max_pixels,
            max_bounces: self.max_bounces,
            max_triangles: self.max_triangles,
            max_light_samples: self.max_light_samples,
            max_pixel_samples: self.max_pixel_samples,
            max_scene_bytes: self.max_scene_bytes,
            max_texture_pixels: self.max_texture_pixels,
            max_mesh_bytes: self.max_mesh_bytes,
            max_memory: self.max_memory.or_else(raytracer::memory::available),
        }
    }
}
