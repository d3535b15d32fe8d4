//! Textures: images with bilinear, wrapping lookup, and constant colours.
//!
//! Besides a path on a material (`"tPath": "../textures/sicily.jpg"`), a scene may define named
//! textures in a top-level (or `scene`-level) library that materials name:
//! ```json
//! "textures": [
//!   { "name": "tex1", "type": "constant", "colour": [0.04, 0.42, 0.01] },
//!   { "name": "ball1", "type": "image", "image": "Ball1.jpg", "offset_u": 0.4, "offset_v": 0.97 }
//! ],
//! "materials": [ { "name": "ball1", "kd": 0.8, "texture": "ball1" } ]
//! ```
//! A constant texture is a one-texel image: every lookup returns its colour. `offset_u` and
//! `offset_v` shift where the image lies on the surface ([`Texture::offset`]).
//!
//! A [`Texture`] stores RGB texels row-major with row 0 at the top of the image. Values loaded
//! from 8-bit images are `byte / 255` with no gamma decoding, the same convention as
//! [`crate::image_io::read_image`]. An 8-bit image keeps its bytes, looked up in a table of the
//! 256 values that reading gives them: the same values to the bit in a quarter of the memory of
//! three `f32`s (a 4096² image takes 48 MiB, not 192), and a quarter of the cache traffic per
//! lookup. Other images (16-bit, EXR) keep their `f32`s.
//!
//! Texture coordinates: `uv = (0, 0)` is the top-left corner of texel (0, 0) and `(1, 1)` the
//! bottom-right corner of the image; `u` runs along columns (rightwards), `v` along rows
//! (downwards). Texel `(i, j)` has its centre at `((i + 0.5) / width, (j + 0.5) / height)`.
//! Coordinates repeat outside [0, 1) and bilinear filtering wraps across the edges.

use std::path::Path;

use glam::{Vec2, Vec3};

use crate::image_io::{read_texture_with, ImageError, ReadLimits, TextureImage};
use crate::math::floor_f64;
use crate::scene::load::DEFAULT_MAX_TEXTURE_PIXELS;

/// An RGB image texture.
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// `width * height` texels, row-major, row 0 = top of the image.
    texels: Texels,
    /// Added to every lookup's uv before wrapping (zero unless a library entry gives
    /// `offset_u`/`offset_v`; the loader turns those into this frame).
    pub offset: Vec2,
    /// A procedural checkerboard, which takes the place of the texels.
    pub checker: Option<Checker>,
}

/// Squares of two colours: `scale` squares to a unit of the shape's uv, or of world space when
/// `solid` (cubes then, the same on every shape cut through them).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Checker {
    pub colours: [Vec3; 2],
    pub scale: f32,
    pub solid: bool,
}

impl Checker {
    /// The colour of the square or cube holding `p` (the first where the sum of the cell's
    /// coordinates is even).
    fn at(&self, p: &[f32]) -> Vec3 {
        let cells: f64 = p
            .iter()
            .map(|&x| floor_f64(f64::from(x) * f64::from(self.scale)))
            .sum();
        if cells.rem_euclid(2.0) == 0.0 {
            self.colours[0]
        } else {
            self.colours[1]
        }
    }
}

/// A texture's texels.
#[derive(Debug, Clone, PartialEq)]
enum Texels {
    /// 8-bit samples, and the value of each byte ([`COLOUR_VALUES`] or [`GREY_VALUES`]).
    Bytes(Vec<[u8; 3]>, &'static [f32; 256]),
    /// Any values.
    Floats(Vec<Vec3>),
}

/// `b / 255` for every byte `b`: what [`crate::image_io::read_image`] gives an 8-bit colour
/// sample.
static COLOUR_VALUES: [f32; 256] = byte_values(false);

/// `b · (1/255)`: what it gives an 8-bit grey sample (which can differ in the last bit).
static GREY_VALUES: [f32; 256] = byte_values(true);

const fn byte_values(grey: bool) -> [f32; 256] {
    let mut v = [0.0; 256];
    let mut b = 0;
    while b < 256 {
        v[b] = if grey {
            b as f32 * (1.0 / 255.0)
        } else {
            b as f32 / 255.0
        };
        b += 1;
    }
    v
}

impl Texels {
    fn len(&self) -> usize {
        match self {
            Texels::Bytes(b, _) => b.len(),
            Texels::Floats(f) => f.len(),
        }
    }

    #[inline]
    fn get(&self, i: usize) -> Option<Vec3> {
        match self {
            Texels::Bytes(b, values) => b.get(i).map(|&[r, g, b]| {
                Vec3::new(values[r as usize], values[g as usize], values[b as usize])
            }),
            Texels::Floats(f) => f.get(i).copied(),
        }
    }
}

impl Texture {
    /// Loads a PNG, JPEG or PPM image (anything [`crate::image_io::read_image`] reads) as a
    /// texture of at most [`DEFAULT_MAX_TEXTURE_PIXELS`] texels.
    pub fn load(path: &Path) -> Result<Texture, ImageError> {
        Texture::load_with(
            path,
            &ReadLimits {
                max_pixels: DEFAULT_MAX_TEXTURE_PIXELS,
                flag: None,
            },
        )
    }

    /// [`Texture::load`] under `limits`: an image whose header gives more texels than
    /// `limits.max_pixels` is refused before it is decoded.
    pub fn load_with(path: &Path, limits: &ReadLimits) -> Result<Texture, ImageError> {
        Ok(match read_texture_with(path, limits)? {
            TextureImage::Bytes {
                width,
                height,
                texels,
                gray,
            } => Texture {
                width,
                height,
                texels: Texels::Bytes(texels, if gray { &GREY_VALUES } else { &COLOUR_VALUES }),
                offset: Vec2::ZERO,
                checker: None,
            },
            TextureImage::Floats(film) => {
                Texture::from_texels(film.width, film.height, film.pixels)
            }
        })
    }

    /// A texture of one colour everywhere: a single texel, which bilinear lookup returns exactly.
    pub fn constant(colour: Vec3) -> Texture {
        Texture::from_texels(1, 1, vec![colour])
    }

    /// The same texture with its uv shifted by `offset` (see [`Texture::offset`]).
    pub fn with_offset(self, offset: Vec2) -> Texture {
        Texture { offset, ..self }
    }

    /// A texture from texels (row-major, row 0 at the top); `texels.len()` must be
    /// `width * height`.
    pub fn from_texels(width: u32, height: u32, texels: Vec<Vec3>) -> Texture {
        debug_assert_eq!(
            texels.len(),
            width as usize * height as usize,
            "texel count does not match {width}x{height}"
        );
        Texture {
            width,
            height,
            texels: Texels::Floats(texels),
            offset: Vec2::ZERO,
            checker: None,
        }
    }

    /// A procedural checkerboard.
    pub fn checker(checker: Checker) -> Texture {
        Texture {
            checker: Some(checker),
            ..Texture::constant(checker.colours[0])
        }
    }

    /// The colour at a surface point of texture coordinates `uv` and world position `point`:
    /// a solid checkerboard's cube there, otherwise [`Texture::sample`] at `uv`.
    pub fn sample_at(&self, uv: Vec2, point: Vec3) -> Vec3 {
        match &self.checker {
            Some(c) if c.solid => c.at(&point.to_array()),
            _ => self.sample(uv),
        }
    }

    /// Every texel's value, row-major from the top row.
    pub fn texels(&self) -> Vec<Vec3> {
        (0..self.texels.len())
            .filter_map(|i| self.texels.get(i))
            .collect()
    }

    /// Bytes held by the texels: 3 a texel read from an 8-bit image, 12 otherwise.
    pub fn texel_bytes(&self) -> usize {
        match &self.texels {
            Texels::Bytes(b, _) => b.len() * 3,
            Texels::Floats(f) => f.len() * std::mem::size_of::<Vec3>(),
        }
    }

    /// The texel in column `i`, row `j`; black if out of range (only possible for an
    /// inconsistent texture).
    fn texel(&self, i: u32, j: u32) -> Vec3 {
        self.texels
            .get(j as usize * self.width as usize + i as usize)
            .unwrap_or(Vec3::ZERO)
    }

    /// Bilinear lookup. uv = (0,0) is the top-left corner of texel (0,0); u grows to the right
    /// (columns), v grows downwards (rows); (1,1) is the bottom-right corner of the image. Texel
    /// centres sit at ((i+0.5)/width, (j+0.5)/height). Coordinates wrap (repeat) in both
    /// directions, so u = 1.25 equals u = 0.25; filtering wraps across the edges too.
    /// Non-finite uv returns texel (0,0). An empty texture returns black. [`Texture::offset`]
    /// is added to `uv` first.
    pub fn sample(&self, uv: Vec2) -> Vec3 {
        if let Some(c) = &self.checker {
            let uv = uv + self.offset;
            return c.at(&uv.to_array());
        }
        if self.width == 0 || self.height == 0 {
            return Vec3::ZERO;
        }
        if self.texels.len() == 1 {
            // A constant texture: its colour exactly (a blend of a texel with itself may round).
            return self.texel(0, 0);
        }
        let uv = uv + self.offset;
        if !uv.is_finite() {
            return self.texel(0, 0);
        }
        let (i0, i1, fx) = wrap_axis(uv.x, self.width);
        let (j0, j1, fy) = wrap_axis(uv.y, self.height);
        let top = self.texel(i0, j0).lerp(self.texel(i1, j0), fx);
        let bottom = self.texel(i0, j1).lerp(self.texel(i1, j1), fx);
        top.lerp(bottom, fy)
    }
}

/// Blend weights closer than this (in texels) to a texel centre snap to it, so that lookups at
/// centres given as f32 `(i + 0.5) / n` return the texel exactly despite rounding.
const CENTRE_SNAP: f64 = 1e-4;

/// For a coordinate `t` along an axis of `n` texels, the two neighbouring texel indices
/// (wrapped into `0..n`) and the blend weight of the second.
#[inline]
fn wrap_axis(t: f32, n: u32) -> (u32, u32, f32) {
    // Reduce to [0, 1] first, in f64 so large coordinates keep their fraction (a tiny negative
    // `t` rounds up to 1). Most coordinates are in [0, 1) already, where the floor is 0.
    let t = f64::from(t);
    let frac = if (0.0..1.0).contains(&t) {
        t
    } else {
        t - floor_f64(t)
    };
    let x = frac * f64::from(n) - 0.5;
    let (x0, w) = snapped_floor(x);
    // `x` is in [-0.5, n - 0.5], so `x0` is in [-1, n - 1] (a snap up stays below `n - 0.5`):
    // the wrap is one step at the low end, without an integer division.
    let i0 = if x0 < 0.0 { n - 1 } else { x0 as u32 };
    let i1 = if i0 + 1 == n { 0 } else { i0 + 1 };
    (i0, i1, w as f32)
}

/// `x` as a texel index and the blend weight towards the next, `(⌊x⌋, x − ⌊x⌋)`, with a weight
/// within [`CENTRE_SNAP`] of 0 or 1 snapped to the nearer texel.
#[inline]
fn snapped_floor(x: f64) -> (f64, f64) {
    let x0 = floor_f64(x);
    let w = x - x0;
    if w < CENTRE_SNAP {
        (x0, 0.0)
    } else if w > 1.0 - CENTRE_SNAP {
        (x0 + 1.0, 0.0)
    } else {
        (x0, w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    /// A 3x2 texture with distinct texels: value = (column, row, column + 10 * row).
    fn grid() -> Texture {
        let mut texels = Vec::new();
        for j in 0..2 {
            for i in 0..3 {
                texels.push(Vec3::new(i as f32, j as f32, (i + 10 * j) as f32));
            }
        }
        Texture::from_texels(3, 2, texels)
    }

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).abs().max_element() < 1e-5
    }

    fn centre(t: &Texture, i: u32, j: u32) -> Vec2 {
        Vec2::new(
            (i as f32 + 0.5) / t.width as f32,
            (j as f32 + 0.5) / t.height as f32,
        )
    }

    #[test]
    fn texel_centres_are_exact() {
        let t = grid();
        for j in 0..2 {
            for i in 0..3 {
                assert_eq!(t.sample(centre(&t, i, j)), t.texels()[(j * 3 + i) as usize]);
            }
        }
    }

    #[test]
    fn midway_between_texels_is_their_mean() {
        let t = grid();
        // Between columns 0 and 1 on row 0: u = 1/3, v = 1/4.
        let m = t.sample(Vec2::new(1.0 / 3.0, 0.25));
        assert!(close(m, (t.texel(0, 0) + t.texel(1, 0)) * 0.5), "{m}");
        // Between rows 0 and 1 in column 2: u = 5/6, v = 1/2.
        let m = t.sample(Vec2::new(5.0 / 6.0, 0.5));
        assert!(close(m, (t.texel(2, 0) + t.texel(2, 1)) * 0.5), "{m}");
        // Centre of four texels.
        let m = t.sample(Vec2::new(2.0 / 3.0, 0.5));
        let mean = (t.texel(1, 0) + t.texel(2, 0) + t.texel(1, 1) + t.texel(2, 1)) * 0.25;
        assert!(close(m, mean), "{m}");
    }

    /// The reference wrap for [`wrap_axis`]: reduction to `[0, 1)`, then remainders.
    fn wrap_axis_by_remainders(t: f32, n: u32) -> (u32, u32, f32) {
        let t = f64::from(t);
        let frac = t - floor_f64(t);
        let (x0, w) = snapped_floor(frac * f64::from(n) - 0.5);
        let n = i64::from(n);
        let i0 = (x0 as i64).rem_euclid(n);
        let i1 = (i0 + 1) % n;
        (i0 as u32, i1 as u32, w as f32)
    }

    /// The wrap without divisions gives the remainders' texels and weight, bit for bit: at
    /// texel centres and edges, in [0, 1] and far outside it, at tiny negative coordinates
    /// (whose fraction rounds to 1) and on a spread of float bit patterns, for sizes 1 to 4097.
    #[test]
    fn wrap_axis_agrees_with_the_remainders() {
        let mut ts: Vec<f32> = vec![0.0, -0.0, 1.0, -1.0, 0.5, 1e-30, -1e-30, -1e-8, 1e9, -1e9];
        ts.extend((0..40_000u32).map(|i| f32::from_bits(i.wrapping_mul(0x9e37_79b9) >> 1)));
        ts.extend((0..40_000u32).map(|i| -f32::from_bits(i.wrapping_mul(0x85eb_ca6b) >> 1)));
        for n in [1u32, 2, 3, 7, 64, 512, 1000, 4097] {
            let mut cases = ts.clone();
            for i in 0..=n {
                let c = i as f32 / n as f32;
                cases.extend([c, (i as f32 + 0.5) / n as f32, c - 1e-7, c + 1e-7, c + 3.0]);
            }
            for &t in cases.iter().filter(|t| t.is_finite()) {
                let (a0, a1, aw) = wrap_axis(t, n);
                let (b0, b1, bw) = wrap_axis_by_remainders(t, n);
                assert_eq!(
                    (a0, a1, aw.to_bits()),
                    (b0, b1, bw.to_bits()),
                    "t = {t:e}, n = {n}"
                );
            }
        }
    }

    #[test]
    fn wraps_across_edges() {
        let t = grid();
        // u = 0 lies midway between the last and the first column.
        let m = t.sample(Vec2::new(0.0, 0.25));
        assert!(close(m, (t.texel(2, 0) + t.texel(0, 0)) * 0.5), "{m}");
        // u = 1 is the same place.
        assert!(close(t.sample(Vec2::new(1.0, 0.25)), m));
        // v = 0 lies midway between the bottom and the top row.
        let m = t.sample(Vec2::new(0.5, 0.0));
        assert!(close(m, (t.texel(1, 1) + t.texel(1, 0)) * 0.5), "{m}");
        // Repeating coordinates, positive and negative.
        for uv in [
            Vec2::new(0.3, 0.6),
            Vec2::new(0.1, 0.9),
            Vec2::new(0.95, 0.05),
        ] {
            let s = t.sample(uv);
            for shift in [
                Vec2::new(1.0, 0.0),
                Vec2::new(-1.0, 2.0),
                Vec2::new(3.0, -5.0),
            ] {
                assert!(close(t.sample(uv + shift), s), "{uv} + {shift}");
            }
        }
        assert!(close(
            t.sample(Vec2::new(1.25, 0.25)),
            t.sample(Vec2::new(0.25, 0.25))
        ));
    }

    #[test]
    fn v_zero_row_is_the_top_row() {
        // 1x2 texture: top row red, bottom row blue.
        let t = Texture::from_texels(1, 2, vec![Vec3::X, Vec3::Z]);
        assert_eq!(t.sample(Vec2::new(0.5, 0.25)), Vec3::X);
        assert_eq!(t.sample(Vec2::new(0.5, 0.75)), Vec3::Z);
        // Just below the top edge is mostly the top row.
        let near_top = t.sample(Vec2::new(0.5, 0.2));
        assert!(near_top.x > near_top.z, "{near_top}");
    }

    #[test]
    fn constant_textures_and_offsets() {
        let c = Texture::constant(Vec3::new(0.04, 0.42, 0.01));
        for uv in [Vec2::ZERO, Vec2::new(0.3, 0.9), Vec2::new(-17.5, 1e6)] {
            assert_eq!(c.sample(uv), Vec3::new(0.04, 0.42, 0.01));
        }
        // An offset of one texel's width shows texel (1, 1) where texel (0, 1) was.
        let t = grid();
        let moved = t.clone().with_offset(Vec2::new(1.0 / 3.0, 0.0));
        assert!(close(moved.sample(centre(&t, 0, 1)), t.texel(1, 1)));
        assert!(!close(moved.sample(centre(&t, 0, 1)), t.texel(0, 1)));
    }

    #[test]
    fn non_finite_uv_returns_first_texel() {
        let t = grid();
        for uv in [
            Vec2::new(f32::NAN, 0.5),
            Vec2::new(0.5, f32::INFINITY),
            Vec2::new(f32::NEG_INFINITY, f32::NAN),
        ] {
            assert_eq!(t.sample(uv), t.texel(0, 0));
        }
        assert_eq!(
            Texture::from_texels(0, 0, vec![]).sample(Vec2::ZERO),
            Vec3::ZERO
        );
    }

    #[test]
    fn single_texel_is_constant() {
        let t = Texture::from_texels(1, 1, vec![Vec3::new(0.2, 0.4, 0.6)]);
        for uv in [Vec2::ZERO, Vec2::new(0.7, 0.3), Vec2::new(-3.2, 9.9)] {
            assert!(close(t.sample(uv), Vec3::new(0.2, 0.4, 0.6)));
        }
    }

    #[test]
    fn loads_ppm_texture() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("tex.ppm");
        let mut bytes = b"P6\n2 2\n255\n".to_vec();
        bytes.extend_from_slice(&[255, 0, 0, 0, 255, 0, 0, 0, 255, 51, 102, 153]);
        fs::write(&path, bytes).unwrap();
        let t = Texture::load(&path).unwrap();
        assert_eq!((t.width, t.height), (2, 2));
        assert_eq!(t.texels()[0], Vec3::X);
        assert_eq!(t.texels()[1], Vec3::Y);
        assert_eq!(t.texels()[2], Vec3::Z);
        assert_eq!(t.texels()[3], Vec3::new(0.2, 0.4, 0.6));
        assert_eq!(t.sample(Vec2::new(0.75, 0.25)), Vec3::Y);
    }

    #[test]
    fn eight_bit_images_keep_their_bytes_with_the_values_read_image_gives() {
        let dir = tempfile::tempdir().unwrap();
        let (w, h) = (64u32, 48u32);
        let kinds = [
            ("colour.png", image::ColorType::Rgb8),
            ("alpha.png", image::ColorType::Rgba8),
            ("grey.png", image::ColorType::L8),
            ("grey_alpha.png", image::ColorType::La8),
            ("deep.png", image::ColorType::Rgb16),
        ];
        for (name, kind) in kinds {
            let n = (w * h) as usize * kind.bytes_per_pixel() as usize;
            let data: Vec<u8> = (0..n).map(|i| (i * 7 % 251) as u8).collect();
            let path = dir.path().join(name);
            image::save_buffer(&path, &data, w, h, kind).unwrap();
            let t = Texture::load(&path).unwrap();
            let film = crate::image_io::read_image(&path).unwrap();
            let bytes = if kind == image::ColorType::Rgb16 {
                12
            } else {
                3
            };
            assert_eq!(t.texel_bytes(), bytes * film.pixels.len(), "{name}");
            let texels = t.texels();
            assert_eq!(texels.len(), film.pixels.len(), "{name}");
            for (a, b) in texels.iter().zip(&film.pixels) {
                assert_eq!(
                    a.to_array().map(f32::to_bits),
                    b.to_array().map(f32::to_bits)
                );
            }
            // Lookups agree with a texture of the same values as floats.
            let floats = Texture::from_texels(t.width, t.height, film.pixels.clone());
            for k in 0..500 {
                let uv = Vec2::new(k as f32 * 0.013_7 - 3.0, k as f32 * 0.029_1);
                assert_eq!(t.sample(uv), floats.sample(uv), "{name} {uv}");
            }
        }
        // Grey bytes are read as b·(1/255), which is not always b/255.
        assert!((0..256).any(|b| GREY_VALUES[b] != COLOUR_VALUES[b]));
    }

    #[test]
    fn load_errors_name_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("broken.png");
        fs::write(&path, b"\x89PNG\r\n\x1a\n").unwrap();
        let err = Texture::load(&path).unwrap_err();
        assert!(err.to_string().contains("broken.png"), "{err}");
    }

    #[test]
    fn loads_coursework_jpeg() {
        let path = Path::new("/work/shared/coursework/official/sicily.jpg");
        if !path.exists() {
            eprintln!("skipping: {} not present", path.display());
            return;
        }
        let t = Texture::load(path).unwrap();
        assert_eq!((t.width, t.height), (600, 494));
        assert_eq!(t.texels().len(), 600 * 494);
        assert!(t
            .texels()
            .iter()
            .all(|c| c.min_element() >= 0.0 && c.max_element() <= 1.0));
        // Not a blank image.
        let texels = t.texels();
        assert!(texels.iter().any(|c| *c != texels[0]));
        assert_eq!(
            t.texel_bytes(),
            3 * 600 * 494,
            "an 8-bit image keeps its bytes"
        );
    }
}
