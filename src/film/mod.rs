//! The linear image a render produces, and the tone mapping that turns it into display values.
//!
//! A [`Film`] holds linear RGB radiance per pixel, stored row-major with the first row at the
//! top of the image. Tone mapping ([`tonemap`], [`to_rgb8`]) first multiplies by an exposure
//! factor and then applies one of the [`ToneMap`] curves; the default, [`ToneMap::Linear`], is
//! the coursework's official mapping (value × 255, clamped, no gamma).

pub mod cgr;
pub mod rect;
pub mod sum;

use std::fmt;
use std::str::FromStr;

use glam::Vec3;

pub use rect::PixelRect;
pub use sum::PixelSum;

/// Linear RGB radiance, row-major, first row at the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Film {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height` pixels, row by row from the top, left to right within a row.
    pub pixels: Vec<Vec3>,
}

impl Film {
    /// A black film of the given size.
    pub fn new(width: u32, height: u32) -> Film {
        let len = width as usize * height as usize;
        Film {
            width,
            height,
            pixels: vec![Vec3::ZERO; len],
        }
    }

    /// A black film of the given size, or `None` when its pixels cannot be allocated (too many
    /// for the address space, or refused by the allocator).
    pub fn try_new(width: u32, height: u32) -> Option<Film> {
        let len = (width as usize).checked_mul(height as usize)?;
        let mut pixels = Vec::new();
        pixels.try_reserve_exact(len).ok()?;
        pixels.resize(len, Vec3::ZERO);
        Some(Film {
            width,
            height,
            pixels,
        })
    }

    /// A film from existing pixels (row-major, first row at the top);
    /// `pixels.len()` must be `width * height`.
    pub fn from_pixels(width: u32, height: u32, pixels: Vec<Vec3>) -> Film {
        debug_assert_eq!(
            pixels.len(),
            width as usize * height as usize,
            "pixel count does not match {width}x{height}"
        );
        Film {
            width,
            height,
            pixels,
        }
    }

    fn index(&self, x: u32, y: u32) -> usize {
        debug_assert!(
            x < self.width && y < self.height,
            "pixel ({x}, {y}) outside {}x{} film",
            self.width,
            self.height
        );
        y as usize * self.width as usize + x as usize
    }

    /// The pixel in column `x`, row `y` (row 0 is the top). Panics if out of range.
    pub fn get(&self, x: u32, y: u32) -> Vec3 {
        self.pixels[self.index(x, y)]
    }

    /// Sets the pixel in column `x`, row `y` (row 0 is the top). Panics if out of range.
    pub fn set(&mut self, x: u32, y: u32, c: Vec3) {
        let i = self.index(x, y);
        self.pixels[i] = c;
    }
}

/// How linear radiance is mapped to display values; see [`tonemap`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ToneMap {
    /// Clamp to [0, 1], no gamma: the coursework's official mapping.
    #[default]
    Linear,
    /// Clamp to [0, 1], then the sRGB transfer curve.
    Srgb,
    /// Reinhard `x / (1 + x)` per channel, then the sRGB transfer curve.
    Reinhard,
    /// `1 − exp(−x)` per channel, no gamma: the photographic exposure curve, which never clips.
    /// It is what a CGR camera's `exposure` feeds in the one coursework renderer whose code
    /// uses it (`docs/scene-format.md`, CGR conventions).
    Exposure,
    /// The CGR course's display transform ([`cgr::display`]): a logarithmic curve on
    /// luminance with colour carried by each channel's ratio to it. The default for CGR files.
    Cgr,
    /// Narkowicz's fit of the ACES filmic curve, `x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14)`
    /// per channel, no gamma ("ACES Filmic Tone Mapping Curve", 2016): what CGR files ask for
    /// with a camera's `"tone_mapping": "aces"`.
    Aces,
}

impl ToneMap {
    /// All tone maps, in the order they are listed in messages.
    pub const ALL: [ToneMap; 6] = [
        ToneMap::Linear,
        ToneMap::Srgb,
        ToneMap::Reinhard,
        ToneMap::Exposure,
        ToneMap::Cgr,
        ToneMap::Aces,
    ];

    /// The lower-case name used by [`FromStr`] and [`Display`](fmt::Display).
    pub fn name(self) -> &'static str {
        match self {
            ToneMap::Linear => "linear",
            ToneMap::Srgb => "srgb",
            ToneMap::Reinhard => "reinhard",
            ToneMap::Exposure => "exposure",
            ToneMap::Cgr => "cgr",
            ToneMap::Aces => "aces",
        }
    }

    /// `choice` (a command line's `--tonemap`), else what the scene asks for, else linear.
    pub fn chosen(choice: Option<ToneMap>, scene: Option<ToneMap>) -> ToneMap {
        choice.or(scene).unwrap_or(ToneMap::Linear)
    }
}

impl fmt::Display for ToneMap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Error from parsing a [`ToneMap`] name.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown tone map '{0}' (expected one of: linear, srgb, reinhard, exposure, cgr, aces)")]
pub struct ParseToneMapError(pub String);

impl FromStr for ToneMap {
    type Err = ParseToneMapError;

    /// Parses `linear`, `srgb`, `reinhard`, `exposure`, `cgr` or `aces` (ASCII case-insensitive,
    /// surrounding spaces ignored).
    fn from_str(s: &str) -> Result<ToneMap, ParseToneMapError> {
        let t = s.trim();
        ToneMap::ALL
            .into_iter()
            .find(|m| m.name().eq_ignore_ascii_case(t))
            .ok_or_else(|| ParseToneMapError(s.to_string()))
    }
}

/// The sRGB transfer curve (IEC 61966-2-1) of a value in [0, 1], evaluated in f64 so that
/// 1 maps to exactly 1.
fn srgb_encode(x: f32) -> f32 {
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        (1.055 * f64::from(x).powf(1.0 / 2.4) - 0.055) as f32
    }
}

#[inline(always)]
fn tonemap_channel(x: f32, map: ToneMap, exposure: f32) -> f32 {
    let x = x * exposure;
    // Not finite, or not positive (two comparisons, which NaN fails).
    if !(x > 0.0 && x < f32::INFINITY) {
        return 0.0;
    }
    match map {
        ToneMap::Linear => x.min(1.0),
        ToneMap::Srgb => srgb_encode(x.min(1.0)),
        ToneMap::Reinhard => srgb_encode(x / (1.0 + x)),
        ToneMap::Exposure => -(-x).exp_m1(),
        ToneMap::Aces => x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14),
        // A channel on its own is a grey; `tonemap` maps the pixel's channels together.
        ToneMap::Cgr => cgr::display(Vec3::splat(x)).x,
    }
    .clamp(0.0, 1.0)
}

/// Maps one linear radiance value to display \[0, 1\]: first multiplies by `exposure`, then
/// Linear: clamp(x,0,1) (the coursework's official mapping: value × 255, clamped, no gamma);
/// Srgb: the sRGB transfer curve (IEC 61966-2-1) of clamp(x,0,1);
/// Reinhard: x/(1+x) per channel, then the sRGB curve;
/// Exposure: 1 − exp(−x) per channel, no gamma;
/// Aces: Narkowicz's filmic curve per channel, no gamma;
/// Cgr: the course's transform of the whole pixel ([`cgr::display`]).
/// Non-finite or negative input maps to 0 (per channel, after the exposure scaling; for Cgr, an
/// infinite channel makes the pixel black).
pub fn tonemap(c: Vec3, map: ToneMap, exposure: f32) -> Vec3 {
    if map == ToneMap::Cgr {
        return cgr::display(c * exposure);
    }
    Vec3::new(
        tonemap_channel(c.x, map, exposure),
        tonemap_channel(c.y, map, exposure),
        tonemap_channel(c.z, map, exposure),
    )
}

/// A display value in [0, 1] as a byte. The coursework's linear mapping truncates (`⌊v·255⌋`:
/// the official render stores the background 0.01 as 2, not 3); the other maps round to nearest
/// (`⌊v·255 + 0.5⌋`). `v·255 + bias` is never negative, so the conversion's truncation is the
/// floor (and NaN, which `tonemap_channel` never returns, would give 0).
#[inline]
fn to_byte(v: f32, bias: f32) -> u8 {
    (v * 255.0 + bias).clamp(0.0, 255.0) as u8
}

/// The rounding bias of [`to_byte`] for `map`.
#[inline(always)]
fn byte_bias(map: ToneMap) -> f32 {
    if map == ToneMap::Linear {
        0.0
    } else {
        0.5
    }
}

/// 8-bit RGB bytes of the film (see `to_byte` for the quantisation):
/// `3 * width * height` bytes, row-major from the top row, R, G, B per pixel.
pub fn to_rgb8(film: &Film, map: ToneMap, exposure: f32) -> Vec<u8> {
    // One loop per map, each with its map fixed, rather than the map's choice in every channel.
    let channels = |m: ToneMap| {
        move |p: Vec3| {
            Vec3::new(
                tonemap_channel(p.x, m, exposure),
                tonemap_channel(p.y, m, exposure),
                tonemap_channel(p.z, m, exposure),
            )
        }
    };
    let bias = byte_bias(map);
    match map {
        ToneMap::Linear => bytes(film, channels(ToneMap::Linear), bias),
        ToneMap::Srgb => bytes(film, channels(ToneMap::Srgb), bias),
        ToneMap::Reinhard => bytes(film, channels(ToneMap::Reinhard), bias),
        ToneMap::Exposure => bytes(film, channels(ToneMap::Exposure), bias),
        ToneMap::Aces => bytes(film, channels(ToneMap::Aces), bias),
        ToneMap::Cgr => bytes(film, |p| cgr::display(p * exposure), bias),
    }
}

/// Each pixel of the film through `display` (to display values in [0, 1]), then as bytes with
/// rounding `bias`, R, G, B per pixel.
#[inline(always)]
fn bytes(film: &Film, display: impl Fn(Vec3) -> Vec3, bias: f32) -> Vec<u8> {
    let mut out = vec![0u8; film.pixels.len() * 3];
    for (rgb, &p) in out.chunks_exact_mut(3).zip(&film.pixels) {
        let d = display(p);
        rgb[0] = to_byte(d.x, bias);
        rgb[1] = to_byte(d.y, bias);
        rgb[2] = to_byte(d.z, bias);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f32, b: f32) -> bool {
        (a - b).abs() < 1e-6
    }

    fn mono(x: f32, map: ToneMap, exposure: f32) -> f32 {
        let v = tonemap(Vec3::splat(x), map, exposure);
        assert_eq!(v.x, v.y);
        assert_eq!(v.y, v.z);
        v.x
    }

    /// The byte conversion is the floor of `v·255 + bias`, clamped, for display values across
    /// [0, 1] (every 997th float there, and the ends).
    #[test]
    fn to_byte_is_the_floor_of_the_scaled_value() {
        let values = (0..=1.0f32.to_bits())
            .step_by(997)
            .map(f32::from_bits)
            .chain([0.0, 1.0, 0.01, 0.5 / 255.0, 254.5 / 255.0]);
        for v in values {
            for bias in [0.0, 0.5] {
                let want = crate::math::floor_f32(v * 255.0 + bias).clamp(0.0, 255.0) as u8;
                assert_eq!(to_byte(v, bias), want, "{v} + {bias}");
            }
        }
        assert_eq!(to_byte(1.0, 0.5), 255);
        assert_eq!(to_byte(0.01, 0.0), 2);
    }

    #[test]
    fn new_is_black_and_get_set_are_row_major() {
        let mut f = Film::new(3, 2);
        assert_eq!(f.pixels.len(), 6);
        assert!(f.pixels.iter().all(|&p| p == Vec3::ZERO));
        f.set(2, 1, Vec3::new(1.0, 2.0, 3.0));
        assert_eq!(f.get(2, 1), Vec3::new(1.0, 2.0, 3.0));
        assert_eq!(f.pixels[5], Vec3::new(1.0, 2.0, 3.0));
        f.set(1, 0, Vec3::X);
        assert_eq!(f.pixels[1], Vec3::X);
        let g = Film::from_pixels(3, 2, f.pixels.clone());
        assert_eq!(g, f);
    }

    #[test]
    fn linear_clamps_without_gamma() {
        assert_eq!(mono(0.5, ToneMap::Linear, 1.0), 0.5);
        assert_eq!(mono(0.25, ToneMap::Linear, 1.0), 0.25);
        assert_eq!(mono(2.0, ToneMap::Linear, 1.0), 1.0);
        assert_eq!(mono(1.0, ToneMap::Linear, 1.0), 1.0);
        assert_eq!(mono(0.0, ToneMap::Linear, 1.0), 0.0);
    }

    #[test]
    fn non_finite_and_negative_map_to_zero() {
        for map in ToneMap::ALL {
            assert_eq!(mono(f32::NAN, map, 1.0), 0.0, "{map}");
            assert_eq!(mono(f32::INFINITY, map, 1.0), 0.0, "{map}");
            assert_eq!(mono(f32::NEG_INFINITY, map, 1.0), 0.0, "{map}");
            assert_eq!(mono(-0.5, map, 1.0), 0.0, "{map}");
            assert_eq!(mono(0.5, map, f32::NAN), 0.0, "{map}");
        }
        // Channels are independent.
        let v = tonemap(Vec3::new(f32::NAN, 0.5, -1.0), ToneMap::Linear, 1.0);
        assert_eq!(v, Vec3::new(0.0, 0.5, 0.0));
    }

    #[test]
    fn srgb_curve_values() {
        // Linear segment up to and including the 0.0031308 boundary.
        assert!(close(mono(0.002, ToneMap::Srgb, 1.0), 0.002 * 12.92));
        assert!(close(mono(0.003_130_8, ToneMap::Srgb, 1.0), 0.040_449_936));
        // The two pieces meet (nearly) continuously at the boundary.
        let just_above = mono(0.003_131, ToneMap::Srgb, 1.0);
        assert!((just_above - 0.040_45).abs() < 1e-4, "{just_above}");
        // Power segment: 0.5 -> 0.735357, 0.2140 -> ~0.5 (mid-grey).
        assert!((mono(0.5, ToneMap::Srgb, 1.0) - 0.735_357).abs() < 1e-5);
        assert!((mono(0.214_041, ToneMap::Srgb, 1.0) - 0.5).abs() < 1e-5);
        assert_eq!(mono(1.0, ToneMap::Srgb, 1.0), 1.0);
        assert_eq!(mono(5.0, ToneMap::Srgb, 1.0), 1.0);
        assert_eq!(mono(0.0, ToneMap::Srgb, 1.0), 0.0);
    }

    #[test]
    fn reinhard_then_srgb() {
        // 1 -> 0.5 before gamma, then the sRGB curve of 0.5.
        let expected = 1.055 * 0.5f32.powf(1.0 / 2.4) - 0.055;
        assert!(close(mono(1.0, ToneMap::Reinhard, 1.0), expected));
        // 3 -> 0.75 before gamma.
        let expected = 1.055 * 0.75f32.powf(1.0 / 2.4) - 0.055;
        assert!(close(mono(3.0, ToneMap::Reinhard, 1.0), expected));
        // Large values approach but never exceed 1.
        let big = mono(1e6, ToneMap::Reinhard, 1.0);
        assert!(big > 0.999 && big <= 1.0);
    }

    #[test]
    fn exposure_scales_before_mapping() {
        assert_eq!(mono(0.25, ToneMap::Linear, 2.0), 0.5);
        assert_eq!(mono(0.75, ToneMap::Linear, 2.0), 1.0);
        assert!(close(
            mono(0.5, ToneMap::Reinhard, 2.0),
            mono(1.0, ToneMap::Reinhard, 1.0)
        ));
        assert!(close(
            mono(1.0, ToneMap::Srgb, 0.5),
            mono(0.5, ToneMap::Srgb, 1.0)
        ));
        assert_eq!(mono(1.0, ToneMap::Linear, 0.0), 0.0);
    }

    #[test]
    fn exposure_curve_is_one_minus_exp_and_never_clips() {
        assert!(close(
            mono(1.0, ToneMap::Exposure, 1.0),
            1.0 - (-1.0f32).exp()
        ));
        assert!(close(
            mono(0.25, ToneMap::Exposure, 2.0),
            1.0 - (-0.5f32).exp()
        ));
        // Large values approach 1 but stay ordered: no clipping plateau below 1.
        assert!(mono(5.0, ToneMap::Exposure, 1.0) < mono(6.0, ToneMap::Exposure, 1.0));
        assert_eq!(mono(f32::INFINITY, ToneMap::Exposure, 1.0), 0.0);
        assert_eq!(mono(-1.0, ToneMap::Exposure, 1.0), 0.0);
    }

    #[test]
    fn to_rgb8_truncates_linear_and_rounds_gamma_maps() {
        let film = Film::from_pixels(
            4,
            1,
            vec![
                Vec3::new(0.0, 0.5, 1.0),
                Vec3::new(2.0, -1.0, f32::NAN),
                Vec3::splat(1.4 / 255.0),
                Vec3::splat(1.6 / 255.0),
            ],
        );
        assert_eq!(
            to_rgb8(&film, ToneMap::Linear, 1.0),
            vec![0, 127, 255, 255, 0, 0, 1, 1, 1, 1, 1, 1]
        );
        let srgb = to_rgb8(
            &Film::from_pixels(1, 1, vec![Vec3::splat(0.5)]),
            ToneMap::Srgb,
            1.0,
        );
        assert_eq!(srgb, vec![188, 188, 188]);
    }

    #[test]
    fn tone_map_parse_and_display() {
        assert_eq!("linear".parse::<ToneMap>(), Ok(ToneMap::Linear));
        assert_eq!("srgb".parse::<ToneMap>(), Ok(ToneMap::Srgb));
        assert_eq!(" Reinhard ".parse::<ToneMap>(), Ok(ToneMap::Reinhard));
        let err = "gamma".parse::<ToneMap>().unwrap_err().to_string();
        assert!(err.contains("gamma"), "{err}");
        for name in ["linear", "srgb", "reinhard", "exposure"] {
            assert!(err.contains(name), "{err}");
        }
        for map in ToneMap::ALL {
            assert_eq!(map.to_string().parse::<ToneMap>(), Ok(map));
        }
        assert_eq!(ToneMap::default(), ToneMap::Linear);
    }
}
