//! Tiles as OpenEXR files: a [`Part`] in a file any EXR viewer opens, and that [`super::merge`]
//! reads back exactly.
//!
//! The file's display window is the whole image and its data window the part's pixels, so a
//! viewer shows the tile in its place. Its channels:
//!
//! | channel | type | holds |
//! |---|---|---|
//! | `R`, `G`, `B` | f32 | the mean of the part's samples (linear, before exposure): what a viewer shows |
//! | `sum.R.0` … `sum.R.3` (and `G`, `B`) | u32 | the exact sum ([`crate::film::sum`]): a 128-bit two's-complement integer in units of 2⁻⁴⁸, least significant word first |
//! | `sum.flags` | u32 | bits 0–2: NaN, +∞, −∞ seen in R; bits 3–5 in G; bits 6–8 in B |
//! | `sum.count` | u32 | the samples summed in the pixel |
//!
//! and its attributes (in the header): `raytracer.fingerprint` (16 hex digits, see
//! [`super::fingerprint`]), `raytracer.spp` (the whole render's samples per pixel),
//! `raytracer.samples` (`A..B`, the samples this part holds) and `raytracer.exposure` (the
//! scene's display exposure for each tone map, as
//! `linear=… srgb=… reinhard=… exposure=… cgr=… aces=…`); `raytracer.adaptive` (f32, only in
//! tiles of adaptive renders: the noise threshold; each pixel's `sum.count` is then the samples it
//! took, 1 to all); `raytracer.tonemap` (text, only when the scene asks for a tone map: its name,
//! which a merge then applies by default).

use std::collections::HashMap;
use std::io::Cursor;
use std::path::{Path, PathBuf};

use exr::meta::attribute::{AttributeValue, IntegerBounds, Text};
use exr::prelude::{
    AnyChannel, AnyChannels, FlatSamples, Image, ImageAttributes, Layer, LayerAttributes,
    ReadChannels, ReadLayers, Vec2, WritableImage,
};

use super::Part;
use crate::files::input::{self, SizeLimit};
use crate::files::shown;
use crate::film::sum::ChannelSum;
use crate::film::{PixelRect, PixelSum, ToneMap};

const FINGERPRINT: &str = "raytracer.fingerprint";
const SPP: &str = "raytracer.spp";
const SAMPLES: &str = "raytracer.samples";
const EXPOSURE: &str = "raytracer.exposure";
const ADAPTIVE: &str = "raytracer.adaptive";
const TONEMAP: &str = "raytracer.tonemap";
const COLOURS: [&str; 3] = ["R", "G", "B"];

/// Why a tile could not be read.
#[derive(Debug, thiserror::Error)]
pub enum TileError {
    #[error("{}: {message}", shown(path))]
    Read { path: PathBuf, message: String },
    #[error("{}: not an EXR image ({message})", shown(path))]
    NotExr { path: PathBuf, message: String },
    #[error(
        "{}: not a raytracer tile (no '{FINGERPRINT}' attribute): tiles are written by a render with --crop or --sample-range to an .exr file",
        shown(path)
    )]
    NotATile { path: PathBuf },
    #[error("{}: a damaged tile: {message}", shown(path))]
    Damaged { path: PathBuf, message: String },
    #[error(
        "{}: the tile claims {pixels} pixels, more than the limit of {limit} (--max-pixels)",
        shown(path)
    )]
    TooLarge {
        path: PathBuf,
        pixels: u64,
        limit: u64,
    },
}

/// The bytes of the EXR file that holds `part`.
pub fn encode(part: &Part) -> Result<Vec<u8>, String> {
    let (w, h) = (part.window.width() as usize, part.window.height() as usize);
    let n = w * h;
    if part.sums.len() != n || part.counts.len() != n {
        return Err(format!(
            "a part of {w}×{h} pixels holds {} sums and {} counts",
            part.sums.len(),
            part.counts.len()
        ));
    }
    let mut channels = Vec::with_capacity(3 + 3 * 4 + 2);
    for (c, name) in COLOURS.iter().enumerate() {
        let means = part
            .sums
            .iter()
            .zip(&part.counts)
            .map(|(s, &k)| s.0[c].mean(k))
            .collect();
        channels.push(AnyChannel::new(*name, FlatSamples::F32(means)));
        for word in 0..4 {
            let words = part
                .sums
                .iter()
                .map(|s| (s.0[c].fixed as u128 >> (32 * word)) as u32)
                .collect();
            channels.push(AnyChannel::new(
                format!("sum.{name}.{word}").as_str(),
                FlatSamples::U32(words),
            ));
        }
    }
    let flags = part.sums.iter().map(flags_of).collect();
    channels.push(AnyChannel::new("sum.flags", FlatSamples::U32(flags)));
    channels.push(AnyChannel::new(
        "sum.count",
        FlatSamples::U32(part.counts.clone()),
    ));

    let mut attributes = LayerAttributes {
        layer_position: Vec2(
            i32::try_from(part.window.x0).map_err(|e| e.to_string())?,
            i32::try_from(part.window.y0).map_err(|e| e.to_string())?,
        ),
        ..LayerAttributes::default()
    };
    let text = |s: &str| AttributeValue::Text(Text::from(s));
    let other: &mut HashMap<Text, AttributeValue> = &mut attributes.other;
    other.insert(
        Text::from(FINGERPRINT),
        text(&format!("{:016x}", part.fingerprint)),
    );
    other.insert(
        Text::from(SPP),
        AttributeValue::I32(i32::try_from(part.spp).map_err(|e| e.to_string())?),
    );
    other.insert(
        Text::from(SAMPLES),
        text(&format!("{}..{}", part.samples.start, part.samples.end)),
    );
    let exposure: Vec<String> = ToneMap::ALL
        .iter()
        .zip(part.exposure)
        .map(|(m, e)| format!("{m}={e:?}"))
        .collect();
    other.insert(Text::from(EXPOSURE), text(&exposure.join(" ")));
    if let Some(t) = part.adaptive {
        other.insert(Text::from(ADAPTIVE), AttributeValue::F32(t));
    }
    if let Some(m) = part.tone_map {
        other.insert(Text::from(TONEMAP), text(m.name()));
    }

    let layer = Layer::new(
        (w, h),
        attributes,
        crate::image_io::exr_encoding(),
        AnyChannels::sort(channels.into()),
    );
    let display = IntegerBounds::from_dimensions((part.full.0 as usize, part.full.1 as usize));
    let image = Image::new(ImageAttributes::new(display), layer);
    let mut bytes = Vec::new();
    image
        .write()
        .to_buffered(Cursor::new(&mut bytes))
        .map_err(|e| e.to_string())?;
    Ok(bytes)
}

fn flags_of(s: &PixelSum) -> u32 {
    s.0.iter().enumerate().fold(0, |bits, (c, ch)| {
        let b = u32::from(ch.nan) | u32::from(ch.pos_inf) << 1 | u32::from(ch.neg_inf) << 2;
        bits | b << (3 * c)
    })
}

/// Reads the tile at `path`, refusing one whose header claims more than `max_pixels` pixels
/// before it is decoded.
pub fn read(path: &Path, max_pixels: u64) -> Result<Part, TileError> {
    let read_err = |message: String| TileError::Read {
        path: path.to_path_buf(),
        message,
    };
    let limit = SizeLimit {
        bytes: max_pixels.saturating_mul(128).saturating_add(1 << 20),
        flag: Some("--max-pixels"),
    };
    let bytes = input::read(path, limit).map_err(|e| read_err(e.to_string()))?;
    decode(path, &bytes, max_pixels)
}

/// [`read`] from the file's bytes; `path` names it in errors.
pub fn decode(path: &Path, bytes: &[u8], max_pixels: u64) -> Result<Part, TileError> {
    let display = tile_header(path, bytes, max_pixels)?;
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(Cursor::new(bytes))
        .map_err(|e| damaged(path, e.to_string()))?;
    let tile = TileLayer {
        path,
        layer: &image.layer_data,
    };
    let fingerprint = tile.fingerprint()?;
    let spp = tile.spp()?;
    let samples = tile.samples(spp)?;
    let exposure = tile.exposure()?;
    let (full, window) = tile.window(display)?;
    let sums = tile.sums()?;
    let adaptive = tile.adaptive()?;
    let tone_map = tile.tone_map()?;
    let counts = tile.counts(&samples, adaptive)?;
    Ok(Part {
        full,
        window,
        samples,
        spp,
        fingerprint,
        exposure,
        tone_map,
        sums,
        counts,
        adaptive,
    })
}

/// The [`TileError::Damaged`] error for the file at `path`.
fn damaged(path: &Path, message: String) -> TileError {
    TileError::Damaged {
        path: path.to_path_buf(),
        message,
    }
}

/// Reads only the header: checks that `bytes` are an EXR image written as a tile and claim no more
/// than `max_pixels` pixels, and returns the display window.
fn tile_header(path: &Path, bytes: &[u8], max_pixels: u64) -> Result<IntegerBounds, TileError> {
    let path_buf = || path.to_path_buf();
    let meta = exr::meta::MetaData::read_from_buffered(Cursor::new(bytes), false).map_err(|e| {
        TileError::NotExr {
            path: path_buf(),
            message: e.to_string(),
        }
    })?;
    let header = meta.headers.first().ok_or_else(|| TileError::NotExr {
        path: path_buf(),
        message: "no image in it".into(),
    })?;
    if !header
        .own_attributes
        .other
        .contains_key(&Text::from(FINGERPRINT))
    {
        return Err(TileError::NotATile { path: path_buf() });
    }
    let display = header.shared_attributes.display_window;
    for pixels in [header.layer_size.area() as u64, display.size.area() as u64] {
        if pixels > max_pixels {
            return Err(TileError::TooLarge {
                path: path_buf(),
                pixels,
                limit: max_pixels,
            });
        }
    }
    Ok(display)
}

/// A decoded tile's layer, read field by field into a [`Part`]; every error names `path`.
struct TileLayer<'a> {
    path: &'a Path,
    layer: &'a Layer<AnyChannels<FlatSamples>>,
}

impl TileLayer<'_> {
    /// The [`TileError::Damaged`] error for this tile.
    fn damaged(&self, message: String) -> TileError {
        damaged(self.path, message)
    }

    /// The header attribute `key`, of any type.
    fn attribute(&self, key: &str) -> Option<&AttributeValue> {
        self.layer.attributes.other.get(&Text::from(key))
    }

    /// The text attribute `key`.
    fn text(&self, key: &str) -> Result<String, TileError> {
        match self.attribute(key) {
            Some(AttributeValue::Text(t)) => Ok(t.to_string()),
            _ => Err(self.damaged(format!("no text attribute '{key}'"))),
        }
    }

    /// The u32 channel `name`, one sample per pixel.
    fn channel(&self, name: &str) -> Result<&[u32], TileError> {
        let n = self.layer.size.area();
        let found = self
            .layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name == *name);
        match found.map(|c| &c.sample_data) {
            Some(FlatSamples::U32(v)) if v.len() == n => Ok(v),
            Some(_) => Err(self.damaged(format!("channel '{name}' is not {n} u32 samples"))),
            None => Err(self.damaged(format!("no channel '{name}'"))),
        }
    }

    /// What made the pixels ([`super::fingerprint`]), from 16 hex digits.
    fn fingerprint(&self) -> Result<u64, TileError> {
        u64::from_str_radix(&self.text(FINGERPRINT)?, 16)
            .map_err(|_| self.damaged(format!("'{FINGERPRINT}' is not 16 hex digits")))
    }

    /// The whole render's samples per pixel.
    fn spp(&self) -> Result<u32, TileError> {
        match self.attribute(SPP) {
            Some(AttributeValue::I32(n)) if *n > 0 => Ok(*n as u32),
            _ => Err(self.damaged(format!("no positive integer attribute '{SPP}'"))),
        }
    }

    /// The samples this part holds, a range within `0..spp`.
    fn samples(&self, spp: u32) -> Result<std::ops::Range<u32>, TileError> {
        parse_range(&self.text(SAMPLES)?)
            .filter(|r| r.start < r.end && r.end <= spp)
            .ok_or_else(|| self.damaged(format!("'{SAMPLES}' is not a range A..B within 0..{spp}")))
    }

    /// The scene's display exposure for each tone map, in [`ToneMap::ALL`]'s order.
    fn exposure(&self) -> Result<[f32; ToneMap::ALL.len()], TileError> {
        parse_exposure(&self.text(EXPOSURE)?)
            .ok_or_else(|| self.damaged(format!("'{EXPOSURE}' does not list every tone map")))
    }

    /// The whole image's size and the part's pixels in it, from the display and data windows.
    fn window(&self, display: IntegerBounds) -> Result<((u32, u32), PixelRect), TileError> {
        if display.position != Vec2(0, 0) {
            return Err(self.damaged("the display window does not start at 0,0".into()));
        }
        let (pos, size) = (self.layer.attributes.layer_position, self.layer.size);
        let window = match (u32::try_from(pos.0), u32::try_from(pos.1)) {
            (Ok(x0), Ok(y0)) => PixelRect {
                x0,
                y0,
                x1: x0 + size.0 as u32,
                y1: y0 + size.1 as u32,
            },
            _ => {
                return Err(self.damaged("the data window starts left of or above the image".into()))
            }
        };
        let full = (display.size.0 as u32, display.size.1 as u32);
        if !window.within(&PixelRect::full(full.0, full.1)) || window.is_empty() {
            return Err(self.damaged(format!(
                "the data window {window} is not inside the {}×{} display window",
                full.0, full.1
            )));
        }
        Ok((full, window))
    }

    /// The exact sums: each colour's four words, then the non-finite flags.
    fn sums(&self) -> Result<Vec<PixelSum>, TileError> {
        let mut sums = vec![PixelSum::default(); self.layer.size.area()];
        for (c, name) in COLOURS.iter().enumerate() {
            let words: Vec<&[u32]> = (0..4)
                .map(|w| self.channel(&format!("sum.{name}.{w}")))
                .collect::<Result<_, _>>()?;
            for (i, s) in sums.iter_mut().enumerate() {
                let bits = (0..4).fold(0u128, |acc, w| acc | u128::from(words[w][i]) << (32 * w));
                s.0[c].fixed = bits as i128;
            }
        }
        let flags = self.channel("sum.flags")?;
        for (s, &f) in sums.iter_mut().zip(flags) {
            if f >> 9 != 0 {
                return Err(self.damaged(format!("unknown bits in sum.flags: {f:#x}")));
            }
            for (c, ch) in s.0.iter_mut().enumerate() {
                let b = f >> (3 * c);
                *ch = ChannelSum {
                    nan: b & 1 != 0,
                    pos_inf: b & 2 != 0,
                    neg_inf: b & 4 != 0,
                    ..*ch
                };
            }
        }
        Ok(sums)
    }

    /// The noise threshold of an adaptive render's tile, `None` in other tiles.
    fn adaptive(&self) -> Result<Option<f32>, TileError> {
        match self.attribute(ADAPTIVE) {
            Some(AttributeValue::F32(t)) if *t > 0.0 => Ok(Some(*t)),
            Some(_) => Err(self.damaged(format!("'{ADAPTIVE}' is not a positive number"))),
            None => Ok(None),
        }
    }

    /// The tone map the scene asks for, `None` where it asks for none.
    fn tone_map(&self) -> Result<Option<ToneMap>, TileError> {
        match self.attribute(TONEMAP) {
            None => Ok(None),
            Some(_) => Ok(Some(
                self.text(TONEMAP)?
                    .parse::<ToneMap>()
                    .map_err(|e| self.damaged(format!("'{TONEMAP}': {e}")))?,
            )),
        }
    }

    /// Each pixel's sample count: all of `samples`, or 1 to all of them in an adaptive render.
    fn counts(
        &self,
        samples: &std::ops::Range<u32>,
        adaptive: Option<f32>,
    ) -> Result<Vec<u32>, TileError> {
        let counts = self.channel("sum.count")?.to_vec();
        let expected = samples.end - samples.start;
        let fits = |k: u32| match adaptive {
            Some(_) => (1..=expected).contains(&k),
            None => k == expected,
        };
        if let Some(k) = counts.iter().find(|&&k| !fits(k)) {
            return Err(self.damaged(format!(
                "a pixel holds {k} samples where '{SAMPLES}' says {expected}"
            )));
        }
        Ok(counts)
    }
}

fn parse_range(s: &str) -> Option<std::ops::Range<u32>> {
    let (a, b) = s.split_once("..")?;
    Some(a.trim().parse().ok()?..b.trim().parse().ok()?)
}

fn parse_exposure(s: &str) -> Option<[f32; ToneMap::ALL.len()]> {
    let mut out = [f32::NAN; ToneMap::ALL.len()];
    for item in s.split_whitespace() {
        let (name, value) = item.split_once('=')?;
        let map: ToneMap = name.parse().ok()?;
        let i = ToneMap::ALL.iter().position(|&m| m == map)?;
        out[i] = value.parse().ok()?;
    }
    out.iter().all(|e| e.is_finite()).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn part() -> Part {
        let window = PixelRect {
            x0: 3,
            y0: 1,
            x1: 6,
            y1: 3,
        };
        let mut sums = vec![PixelSum::default(); 6];
        for (i, s) in sums.iter_mut().enumerate() {
            s.add(Vec3::new(i as f32 * 0.1, -2.5, 1e-9));
            s.add(Vec3::new(1e6, 0.25, 3.0));
        }
        sums[4].add(Vec3::new(f32::NAN, f32::INFINITY, f32::NEG_INFINITY));
        Part {
            full: (8, 4),
            window,
            samples: 2..5,
            spp: 9,
            fingerprint: 0x0123_4567_89ab_cdef,
            exposure: [1.0, 1.0, 1.0, 0.5, 1.0, 1.0],
            tone_map: None,
            sums,
            counts: vec![3; 6],
            adaptive: None,
        }
    }

    #[test]
    fn a_part_survives_the_file_exactly() {
        let mut p = part();
        for tone_map in [None, Some(ToneMap::Reinhard)] {
            p.tone_map = tone_map;
            let bytes = encode(&p).unwrap();
            let back = decode(Path::new("t.exr"), &bytes, 1 << 20).unwrap();
            assert_eq!(back, p);
        }
    }

    #[test]
    fn other_files_and_damage_are_errors_naming_the_file() {
        let bytes = encode(&part()).unwrap();
        for cut in [10, bytes.len() / 2, bytes.len() - 1] {
            let e = decode(Path::new("cut.exr"), &bytes[..cut], 1 << 20).unwrap_err();
            assert!(e.to_string().contains("cut.exr"), "{e}");
        }
        let e = decode(Path::new("big.exr"), &bytes, 16).unwrap_err();
        assert!(matches!(e, TileError::TooLarge { .. }), "{e}");
        let e = decode(Path::new("x.exr"), b"not an image", 1 << 20).unwrap_err();
        assert!(matches!(e, TileError::NotExr { .. }), "{e}");
    }
}
