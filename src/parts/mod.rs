//! A render cut into parts and put back together: each part is a rectangle of pixels and a
//! range of their samples ([`crate::render::RenderOptions::crop`] and `samples`), written as an
//! EXR tile ([`exr`]) holding the exact sums of its samples ([`crate::film::PixelSum`]);
//! [`merge`] adds tiles up into the whole image, bit for bit the image a single render makes.
//!
//! Every tile carries a fingerprint of what made its pixels (the scene and asset files' bytes
//! and the options that change a pixel's value), so tiles of different scenes or options are
//! refused, not blended.

pub mod exr;
pub mod merge;

use std::ops::Range;
use std::path::Path;

use crate::film::{PixelRect, PixelSum, ToneMap};
use crate::render::{RenderOptions, RenderOutput};
use crate::scene::Scene;

/// One part of a render: the exact sample sums of a rectangle of pixels over a range of their
/// samples, and what is needed to check it against other parts.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// Width and height of the whole image.
    pub full: (u32, u32),
    /// The pixels this part holds.
    pub window: PixelRect,
    /// The samples of each pixel it holds.
    pub samples: Range<u32>,
    /// Samples per pixel of the whole render.
    pub spp: u32,
    /// What made the pixels: see [`fingerprint`].
    pub fingerprint: u64,
    /// The scene's display exposure for each tone map, in [`ToneMap::ALL`]'s order (see
    /// [`Scene::display_exposure`]): a merge maps tones as the render would.
    pub exposure: [f32; ToneMap::ALL.len()],
    /// The tone map the scene asks for ([`Scene::tone_map`]).
    pub tone_map: Option<ToneMap>,
    /// The sums, row-major over `window`.
    pub sums: Vec<PixelSum>,
    /// The samples summed in each pixel, row-major over `window`: all of `samples`, or for an
    /// adaptive render as many as the pixel took (at least one).
    pub counts: Vec<u32>,
    /// The noise threshold of an adaptive render.
    pub adaptive: Option<f32>,
}

impl Part {
    /// The part that a render of `scene` with `options` (and [`RenderOptions::keep_sums`])
    /// produced, with the `fingerprint` of both, taking the sums out of `out`; `None` when the
    /// render kept no sums.
    pub fn of_render(
        scene: &Scene,
        options: &RenderOptions,
        fingerprint: u64,
        out: &mut RenderOutput,
    ) -> Option<Part> {
        let sums = out.sums.take()?;
        let samples = options.sample_range();
        let counts = out
            .sample_counts
            .clone()
            .unwrap_or_else(|| vec![samples.len() as u32; sums.len()]);
        Some(Part {
            full: (scene.camera.width, scene.camera.height),
            window: out.window,
            samples,
            spp: options.spp.max(1),
            fingerprint,
            exposure: display_exposures(scene),
            tone_map: scene.tone_map,
            sums,
            counts,
            adaptive: options.adaptive.map(|a| a.threshold),
        })
    }

    /// The scene's display exposure for `map`.
    pub fn display_exposure(&self, map: ToneMap) -> f32 {
        let i = ToneMap::ALL.iter().position(|&m| m == map).unwrap_or(0);
        self.exposure[i]
    }
}

/// The display exposure of `scene` for each tone map, in [`ToneMap::ALL`]'s order.
pub fn display_exposures(scene: &Scene) -> [f32; ToneMap::ALL.len()] {
    ToneMap::ALL.map(|m| scene.display_exposure(m))
}

/// 64-bit FNV-1a (Fowler, Noll and Vo; the parameters of the IETF draft
/// draft-eastlake-fnv): a stable hash to tell inputs apart, not a cryptographic one.
#[derive(Debug, Clone, Copy)]
struct Fnv(u64);

impl Fnv {
    const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;

    fn new() -> Fnv {
        Fnv(Fnv::OFFSET)
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(Fnv::PRIME);
        }
    }

    /// Writes `bytes` with its length first, so that no two sequences of fields hash alike by
    /// moving bytes from one field to the next.
    fn field(&mut self, bytes: &[u8]) {
        self.write(&(bytes.len() as u64).to_le_bytes());
        self.write(bytes);
    }
}

/// A hash of everything that decides a render's pixel values: this program's version, the bytes
/// of the scene file and of every texture and mesh it reads, the image size, the samples per
/// pixel, the samplers, the seed, the depth cap and the light-sampling options. Not in it: the
/// crop and sample range (they say which values, not what they are), the accelerator and thread
/// count (they never change a value), and the tone map and exposure (applied when merging).
pub fn fingerprint(scene: &Scene, options: &RenderOptions) -> std::io::Result<u64> {
    let mut h = Fnv::new();
    h.field(env!("CARGO_PKG_VERSION").as_bytes());
    for input in &scene.inputs {
        h.field(&read_input(input)?);
    }
    let settings = format!(
        "{}x{} spp={} pixel={:?} seed={} max_depth={} trace={:?} adaptive={:?} integrator={}",
        scene.camera.width,
        scene.camera.height,
        options.spp.max(1),
        options.pixel_method,
        options.seed,
        options.max_depth,
        options.trace,
        options.adaptive,
        crate::integrator::IntegratorKind::chosen(options.integrator, scene)
    );
    h.field(settings.as_bytes());
    Ok(h.0)
}

fn read_input(path: &Path) -> std::io::Result<Vec<u8>> {
    std::fs::read(path)
        .map_err(|e| std::io::Error::new(e.kind(), format!("{}: {e}", crate::files::shown(path))))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv_matches_its_published_test_values() {
        // From the FNV test suite: FNV-1a 64 of "" and of "a".
        assert_eq!(Fnv::new().0, 0xcbf2_9ce4_8422_2325);
        let mut h = Fnv::new();
        h.write(b"a");
        assert_eq!(h.0, 0xaf63_dc4c_8601_ec8c);
        let mut h = Fnv::new();
        h.write(b"foobar");
        assert_eq!(h.0, 0x8594_4171_f739_67e8);
    }

    #[test]
    fn fields_are_delimited() {
        let (mut a, mut b) = (Fnv::new(), Fnv::new());
        a.field(b"ab");
        a.field(b"c");
        b.field(b"a");
        b.field(b"bc");
        assert_ne!(a.0, b.0);
    }
}
