//! Writing rendered films to image files, and reading images back as linear films.
//!
//! Output formats are chosen by file extension ([`OutputFormat`]): binary PPM (P6) and 8-bit
//! PNG are tone-mapped with [`crate::film::tonemap`]; OpenEXR keeps linear 32-bit floats
//! (scaled by the exposure only). Writes are atomic: the image goes to a temporary file in the
//! destination folder, which is renamed over the target only once complete, so a failed write
//! never leaves a partial file and never disturbs an existing one.
//!
//! Reading ([`read_image`]) accepts PNG, JPEG, PPM (ASCII P3 and binary P6) and EXR. 8-bit
//! values are returned as `byte / 255` with no gamma decoding, matching the renderer's default
//! linear output, so renders and references can be compared directly. Every failure is an
//! [`ImageError`] naming the file; malformed input never panics.
//!
//! Reading is bounded by [`ReadLimits`]: the size is read from the file's header and checked
//! against the pixel limit before anything is decoded, the `image` crate's own limits (width,
//! height, allocation) are set to match, and the decoded buffer and the float pixels are
//! allocated fallibly, so a small file that claims a huge image (a decompression bomb) is an
//! error, not an abort. A JPEG whose data ends before its end-of-image marker is an error too,
//! as a truncated PNG is.

use std::io::{self, BufRead, BufReader, Read, Seek};
use std::path::{Path, PathBuf};

use glam::Vec3;
use image::codecs::png::PngEncoder;
use image::{ColorType, ExtendedColorType, ImageDecoder, ImageEncoder, ImageReader, Limits};

use crate::files::input::{self, SizeLimit};
use crate::files::output::{write_atomic, OutputError};
use crate::files::{raise_hint, shown};
use crate::film::{to_rgb8, Film, ToneMap};

/// The extensions [`write_image`] accepts, as listed in error messages.
const SUPPORTED_EXTENSIONS: &str = ".ppm, .png, .exr";

/// Default cap on the pixels of an image [`read_image`] reads: 2^27 (about 134 megapixels), the
/// largest render the scene loader allows by default, so any render can be read back.
pub const DEFAULT_MAX_READ_PIXELS: u64 = 1 << 27;

/// Bytes of decoder working memory allowed beyond the decoded image itself.
const DECODER_HEADROOM: u64 = 64 << 20;

/// The largest decoded pixel the `image` crate produces: RGBA with 32-bit float channels.
const MAX_BYTES_PER_PIXEL: u64 = 16;

/// How large an image [`read_image_with`] accepts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReadLimits {
    /// Most pixels (`width × height`) the image may have. The decoder may allocate at most
    /// 16 bytes per allowed pixel (RGBA 32-bit float) plus 64 MiB of working memory.
    pub max_pixels: u64,
    /// The command-line flag that raises the limit, named in messages; `None` where there is none.
    pub flag: Option<&'static str>,
}

impl Default for ReadLimits {
    fn default() -> Self {
        ReadLimits {
            max_pixels: DEFAULT_MAX_READ_PIXELS,
            flag: None,
        }
    }
}

/// Most bytes an image file may hold per allowed pixel: an ASCII PPM spends up to 12 characters
/// per pixel on its values alone; this leaves room for generous whitespace and comments.
const MAX_FILE_BYTES_PER_PIXEL: u64 = 64;

impl ReadLimits {
    /// The file-size cap that goes with the pixel limit: no honest encoding of an allowed image
    /// is larger (decoders such as JPEG's read the whole file into memory first).
    fn file_limit(&self) -> SizeLimit {
        SizeLimit {
            bytes: self
                .max_pixels
                .saturating_mul(MAX_FILE_BYTES_PER_PIXEL)
                .saturating_add(DECODER_HEADROOM),
            flag: self.flag,
        }
    }

    /// The `image` crate's limits that match: no side longer than the pixel limit, and no more
    /// memory than the largest allowed image takes decoded, plus working memory.
    fn decoder_limits(&self) -> Limits {
        let side = u32::try_from(self.max_pixels).unwrap_or(u32::MAX);
        let mut limits = Limits::default();
        limits.max_image_width = Some(side);
        limits.max_image_height = Some(side);
        limits.max_alloc = Some(
            self.max_pixels
                .saturating_mul(MAX_BYTES_PER_PIXEL)
                .saturating_add(DECODER_HEADROOM),
        );
        limits
    }
}

/// An output image format, chosen by file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputFormat {
    /// Binary PPM (P6), 8-bit RGB, tone-mapped.
    Ppm,
    /// PNG, 8-bit RGB, tone-mapped.
    Png,
    /// OpenEXR, linear 32-bit float RGB.
    Exr,
}

impl OutputFormat {
    /// The format for `path`'s extension (`ppm`, `png` or `exr`, case-insensitive), if any.
    pub fn from_path(path: &Path) -> Option<OutputFormat> {
        let ext = path.extension()?.to_str()?;
        if ext.eq_ignore_ascii_case("ppm") {
            Some(OutputFormat::Ppm)
        } else if ext.eq_ignore_ascii_case("png") {
            Some(OutputFormat::Png)
        } else if ext.eq_ignore_ascii_case("exr") {
            Some(OutputFormat::Exr)
        } else {
            None
        }
    }
}

/// An error writing or reading an image file. Every message names the file.
#[derive(Debug, thiserror::Error)]
pub enum ImageError {
    /// The output path's extension is not a supported output format.
    #[error(
        "cannot write image '{}': unsupported extension {} (supported: {SUPPORTED_EXTENSIONS})",
        shown(path),
        describe_extension(path)
    )]
    UnsupportedFormat {
        /// The output path.
        path: PathBuf,
    },
    /// The film's pixel buffer does not match its size, or the size is zero.
    #[error("cannot write image '{}': film is {width}x{height} but holds {len} pixels (need a non-empty image with width*height pixels)", shown(path))]
    InvalidFilm {
        /// The output path.
        path: PathBuf,
        /// Film width.
        width: u32,
        /// Film height.
        height: u32,
        /// Number of pixels actually held.
        len: usize,
    },
    /// The output cannot be written (folder, permissions, disk, an input in the way).
    #[error(transparent)]
    Output(#[from] OutputError),
    /// The encoder rejected the image.
    #[error("cannot write image '{}': encoding failed: {source}", shown(path))]
    Encode {
        /// The output path.
        path: PathBuf,
        /// The underlying error.
        source: image::ImageError,
    },
    /// The file could not be opened or read.
    #[error("cannot read image '{}': {source}", shown(path))]
    Open {
        /// The input path.
        path: PathBuf,
        /// The underlying error.
        source: io::Error,
    },
    /// The file is not a supported image or is malformed.
    #[error("cannot read image '{}': {source}", shown(path))]
    Decode {
        /// The input path.
        path: PathBuf,
        /// The underlying error.
        source: image::ImageError,
    },
    /// The header gives more pixels than the limit allows; nothing was decoded.
    #[error(
        "cannot read image '{}': it is {width}×{height} = {} pixels, over the limit of {limit} \
         pixels{}",
        shown(path),
        u64::from(*width) * u64::from(*height),
        raise_hint(*flag)
    )]
    TooLarge {
        /// The input path.
        path: PathBuf,
        /// Width from the header.
        width: u32,
        /// Height from the header.
        height: u32,
        /// The pixel limit.
        limit: u64,
        /// The flag that raises the limit, if any.
        flag: Option<&'static str>,
    },
    /// The decoder refused the image under the limits derived from the pixel limit.
    #[error(
        "cannot read image '{}': {source}; the limit is {limit} pixels{}",
        shown(path),
        raise_hint(*flag)
    )]
    Limits {
        /// The input path.
        path: PathBuf,
        /// The decoder's error.
        source: image::ImageError,
        /// The pixel limit.
        limit: u64,
        /// The flag that raises the limit, if any.
        flag: Option<&'static str>,
    },
    /// The decoded image or its float pixels could not be allocated.
    #[error(
        "cannot read image '{}': not enough memory for its {width}×{height} pixels ({bytes} bytes)",
        shown(path)
    )]
    OutOfMemory {
        /// The input path.
        path: PathBuf,
        /// Image width.
        width: u32,
        /// Image height.
        height: u32,
        /// The allocation that failed, in bytes.
        bytes: u64,
    },
    /// A JPEG file ends before its end-of-image marker.
    #[error(
        "cannot read image '{}': the JPEG data ends before its end-of-image marker \
         (truncated file)",
        shown(path)
    )]
    Truncated {
        /// The input path.
        path: PathBuf,
    },
}

fn describe_extension(path: &Path) -> String {
    match path.extension() {
        Some(ext) => format!("'.{}'", ext.to_string_lossy()),
        None => "(none)".to_string(),
    }
}

/// Writes the film: PPM = binary P6 8-bit, PNG = 8-bit RGB, both tone-mapped with `map`/`exposure`;
/// EXR = linear 32-bit float RGB, scaled by `exposure` but not tone-mapped.
///
/// Atomic (see [`crate::files::output`]): a failure leaves no partial file and an existing file at
/// `path` untouched. Errors (never panics): unknown extension, missing or unwritable folder, a
/// film whose pixel count does not match its size, an empty film, a full disk.
pub fn write_image(
    path: &Path,
    film: &Film,
    map: ToneMap,
    exposure: f32,
) -> Result<(), ImageError> {
    let bytes = encode_image(path, film, map, exposure)?;
    write_atomic(path, &bytes)?;
    Ok(())
}

/// The bytes of the image file [`write_image`] writes, in the format of `path`'s extension.
/// Encoding into memory first means a failure to write (a full disk, a file-size limit) is
/// reported as the OS error it is, not as an encoder error.
pub fn encode_image(
    path: &Path,
    film: &Film,
    map: ToneMap,
    exposure: f32,
) -> Result<Vec<u8>, ImageError> {
    let format = OutputFormat::from_path(path).ok_or_else(|| ImageError::UnsupportedFormat {
        path: path.to_path_buf(),
    })?;
    let (width, height) = (film.width, film.height);
    if width == 0 || height == 0 || film.pixels.len() as u64 != u64::from(width) * u64::from(height)
    {
        return Err(ImageError::InvalidFilm {
            path: path.to_path_buf(),
            width,
            height,
            len: film.pixels.len(),
        });
    }
    let encode_err = |source| ImageError::Encode {
        path: path.to_path_buf(),
        source,
    };
    let mut out = Vec::new();
    match format {
        OutputFormat::Ppm => {
            let rgb = to_rgb8(film, map, exposure);
            out.extend_from_slice(format!("P6\n{width} {height}\n255\n").as_bytes());
            out.extend_from_slice(&rgb);
        }
        OutputFormat::Png => {
            let rgb = to_rgb8(film, map, exposure);
            PngEncoder::new(&mut out)
                .write_image(&rgb, width, height, ExtendedColorType::Rgb8)
                .map_err(encode_err)?;
        }
        OutputFormat::Exr => {
            // The samples are read from the film as the lines are compressed, not copied into
            // channels first (three more buffers the film's size).
            let w = width as usize;
            let rgb = exr::prelude::SpecificChannels::rgb(|at: exr::prelude::Vec2<usize>| {
                let p = film.pixels[at.y() * w + at.x()] * exposure;
                (p.x, p.y, p.z)
            });
            let layer = exr::prelude::Layer::new(
                (w, height as usize),
                exr::prelude::LayerAttributes::default(),
                exr_encoding(),
                rgb,
            );
            use exr::prelude::WritableImage;
            exr::prelude::Image::from_layer(layer)
                .write()
                .to_buffered(io::Cursor::new(&mut out))
                .map_err(|e| {
                    encode_err(image::ImageError::IoError(io::Error::other(e.to_string())))
                })?;
        }
    }
    Ok(out)
}

/// How EXR files are written: ZIP-compressed scan lines in increasing order, so the same pixels
/// always give the same bytes (blocks compressed in parallel are still written in order).
pub fn exr_encoding() -> exr::prelude::Encoding {
    exr::prelude::Encoding::SMALL_LOSSLESS
}

/// Reads PNG, JPEG, PPM (P3 ascii and P6 binary) or EXR into a linear Film:
/// 8-bit formats as value/255 (no gamma decoding: this renderer's default output is linear ×255),
/// 16-bit as value/65535, EXR as its float values (alpha is dropped). The format is detected
/// from the file's contents, falling back to its extension. Used to compare renders with references.
///
/// Images over [`DEFAULT_MAX_READ_PIXELS`] are refused; [`read_image_with`] takes other limits.
pub fn read_image(path: &Path) -> Result<Film, ImageError> {
    read_image_with(path, &ReadLimits::default())
}

/// [`read_image`] under `limits`: an image whose header gives more than `limits.max_pixels`
/// pixels is refused before it is decoded ([`ImageError::TooLarge`]).
pub fn read_image_with(path: &Path, limits: &ReadLimits) -> Result<Film, ImageError> {
    let decoded = decode_with(path, limits)?;
    decoded.into_film(path)
}

/// An image as a texture keeps it: 8-bit samples as their bytes, anything else as
/// [`read_image_with`]'s floats.
pub enum TextureImage {
    /// Colour (`gray: false`) or grey samples of 8 bits, three bytes a pixel (grey repeated),
    /// alpha dropped, row-major from the top. [`read_image_with`] gives such a byte `b` the
    /// value `b / 255` in colour and `b · (1/255)` in grey.
    Bytes {
        width: u32,
        height: u32,
        texels: Vec<[u8; 3]>,
        gray: bool,
    },
    /// Any other image, as [`read_image_with`] reads it.
    Floats(Film),
}

/// [`read_image_with`] for a texture: the same image, with 8-bit samples left as bytes (a
/// quarter of the floats' memory).
pub fn read_texture_with(path: &Path, limits: &ReadLimits) -> Result<TextureImage, ImageError> {
    let mut decoded = decode_with(path, limits)?;
    let (channels, gray) = match decoded.color {
        ColorType::Rgb8 => (3, false),
        ColorType::Rgba8 => (4, false),
        ColorType::L8 => (1, true),
        ColorType::La8 => (2, true),
        _ => return Ok(TextureImage::Floats(decoded.into_film(path)?)),
    };
    let raw = std::mem::take(&mut decoded.raw);
    let pixels = decoded.pixels();
    let reserved = || {
        let mut texels: Vec<[u8; 3]> = Vec::new();
        match texels.try_reserve_exact(pixels) {
            Ok(()) => Ok(texels),
            Err(_) => Err(decoded.out_of_memory(path, pixels as u64 * 3)),
        }
    };
    let texels = if channels == 3 {
        // Already in the texels' layout: the decoder's buffer is taken over as it is, where its
        // capacity is a whole number of texels (as an exact reservation makes it), else copied
        // once. (A copy is a second buffer of the texture's size: 0.8 MB and 192 page faults
        // for a 512² texture.)
        match bytemuck::allocation::try_cast_vec::<u8, [u8; 3]>(raw) {
            Ok(texels) => texels,
            Err((_, raw)) => {
                let mut texels = reserved()?;
                texels.extend_from_slice(bytemuck::cast_slice::<u8, [u8; 3]>(&raw));
                texels
            }
        }
    } else {
        let mut texels = reserved()?;
        let chunks = raw.chunks_exact(channels);
        if gray {
            texels.extend(chunks.map(|px| [px[0]; 3]));
        } else {
            texels.extend(chunks.map(|px| [px[0], px[1], px[2]]));
        }
        texels
    };
    Ok(TextureImage::Bytes {
        width: decoded.width,
        height: decoded.height,
        texels,
        gray,
    })
}

/// An image's decoded samples, as the decoder wrote them.
struct Decoded {
    width: u32,
    height: u32,
    color: ColorType,
    raw: Vec<u8>,
}

impl Decoded {
    fn pixels(&self) -> usize {
        self.width as usize * self.height as usize
    }

    fn out_of_memory(&self, path: &Path, bytes: u64) -> ImageError {
        ImageError::OutOfMemory {
            path: path.to_path_buf(),
            width: self.width,
            height: self.height,
            bytes,
        }
    }

    /// The samples as float RGB (see [`read_image`]).
    fn into_film(self, path: &Path) -> Result<Film, ImageError> {
        let color = self.color;
        let texels = to_rgb_f32(color, &self.raw, self.pixels()).map_err(|kind| match kind {
            Conversion::OutOfMemory => self.out_of_memory(path, self.pixels() as u64 * 12),
            Conversion::Unsupported => ImageError::Decode {
                path: path.to_path_buf(),
                source: image::ImageError::Unsupported(
                    image::error::UnsupportedError::from_format_and_kind(
                        image::error::ImageFormatHint::Unknown,
                        image::error::UnsupportedErrorKind::Color(color.into()),
                    ),
                ),
            },
        })?;
        Ok(Film::from_pixels(self.width, self.height, texels))
    }
}

/// Opens, checks and decodes an image under `limits` (the work of [`read_image_with`] up to the
/// conversion of its samples).
fn decode_with(path: &Path, limits: &ReadLimits) -> Result<Decoded, ImageError> {
    let open_err = |source: io::Error| ImageError::Open {
        path: path.to_path_buf(),
        source,
    };
    let decode_err = |source: image::ImageError| match source {
        image::ImageError::Limits(_) => ImageError::Limits {
            path: path.to_path_buf(),
            source,
            limit: limits.max_pixels,
            flag: limits.flag,
        },
        source => ImageError::Decode {
            path: path.to_path_buf(),
            source,
        },
    };
    let file = input::open(path).map_err(open_err)?;
    input::checked_size(&file, limits.file_limit()).map_err(open_err)?;
    // The format from the contents, else from the extension (as `ImageReader::open` does).
    let mut reader = ImageReader::new(BufReader::new(file))
        .with_guessed_format()
        .map_err(open_err)?;
    if reader.format().is_none() {
        if let Ok(format) = image::ImageFormat::from_path(path) {
            reader.set_format(format);
        }
    }
    if reader.format() == Some(image::ImageFormat::Jpeg) {
        // The JPEG decoder pads missing data silently; check that the data is complete first.
        let mut stream = reader.into_inner();
        let complete = jpeg_is_complete(&mut stream).map_err(open_err)?;
        if !complete {
            return Err(ImageError::Truncated {
                path: path.to_path_buf(),
            });
        }
        stream.rewind().map_err(open_err)?;
        reader = ImageReader::with_format(stream, image::ImageFormat::Jpeg);
    }
    reader.limits(limits.decoder_limits());
    // Only the header is read here; the size is checked before any pixel is decoded.
    let decoder = reader.into_decoder().map_err(decode_err)?;
    let (width, height) = decoder.dimensions();
    let pixels = u64::from(width) * u64::from(height);
    if pixels > limits.max_pixels {
        return Err(ImageError::TooLarge {
            path: path.to_path_buf(),
            width,
            height,
            limit: limits.max_pixels,
            flag: limits.flag,
        });
    }
    let out_of_memory = |bytes: u64| ImageError::OutOfMemory {
        path: path.to_path_buf(),
        width,
        height,
        bytes,
    };
    let color = decoder.color_type();
    let total = decoder.total_bytes();
    let mut raw = Vec::new();
    usize::try_from(total)
        .ok()
        .and_then(|n| raw.try_reserve_exact(n).ok().map(|()| n))
        .map(|n| raw.resize(n, 0u8))
        .ok_or_else(|| out_of_memory(total))?;
    decoder.read_image(&mut raw).map_err(decode_err)?;
    Ok(Decoded {
        width,
        height,
        color,
        raw,
    })
}

/// Why decoded samples could not become float RGB.
enum Conversion {
    OutOfMemory,
    Unsupported,
}

/// Decoded samples (native-endian, as [`ImageDecoder::read_image`] writes them) as float RGB,
/// exactly as the `image` crate's `to_rgb32f` converts them: integers scaled to \[0, 1\], gray
/// repeated in all three channels, alpha dropped. The output is reserved fallibly.
fn to_rgb_f32(color: ColorType, raw: &[u8], pixels: usize) -> Result<Vec<Vec3>, Conversion> {
    fn convert(
        raw: &[u8],
        pixels: usize,
        channels: usize,
        size: usize,
        sample: impl Fn(&[u8]) -> f32,
    ) -> Result<Vec<Vec3>, Conversion> {
        let mut out = Vec::new();
        out.try_reserve_exact(pixels)
            .map_err(|_| Conversion::OutOfMemory)?;
        let chunks = raw.chunks_exact(channels * size);
        if channels < 3 {
            out.extend(chunks.map(|px| Vec3::splat(sample(&px[..size]))));
        } else {
            out.extend(chunks.map(|px| {
                let (r, rest) = px.split_at(size);
                let (g, rest) = rest.split_at(size);
                Vec3::new(sample(r), sample(g), sample(&rest[..size]))
            }));
        }
        Ok(out)
    }
    // The `image` crate divides colour samples by the maximum but multiplies gray ones by its
    // reciprocal (which can differ in the last bit); both are kept so that results are unchanged.
    let u8_sample = |b: &[u8]| f32::from(b[0]) / 255.0;
    let u16_sample = |b: &[u8]| f32::from(u16::from_ne_bytes([b[0], b[1]])) / 65535.0;
    let u8_gray = |b: &[u8]| f32::from(b[0]) * (1.0 / 255.0);
    let u16_gray = |b: &[u8]| f32::from(u16::from_ne_bytes([b[0], b[1]])) * (1.0 / 65535.0);
    let f32_sample = |b: &[u8]| f32::from_ne_bytes([b[0], b[1], b[2], b[3]]);
    match color {
        ColorType::L8 => convert(raw, pixels, 1, 1, u8_gray),
        ColorType::La8 => convert(raw, pixels, 2, 1, u8_gray),
        ColorType::Rgb8 => convert(raw, pixels, 3, 1, u8_sample),
        ColorType::Rgba8 => convert(raw, pixels, 4, 1, u8_sample),
        ColorType::L16 => convert(raw, pixels, 1, 2, u16_gray),
        ColorType::La16 => convert(raw, pixels, 2, 2, u16_gray),
        ColorType::Rgb16 => convert(raw, pixels, 3, 2, u16_sample),
        ColorType::Rgba16 => convert(raw, pixels, 4, 2, u16_sample),
        ColorType::Rgb32F => convert(raw, pixels, 3, 4, f32_sample),
        ColorType::Rgba32F => convert(raw, pixels, 4, 4, f32_sample),
        _ => Err(Conversion::Unsupported),
    }
}

/// Whether the JPEG stream reaches its end-of-image marker (FF D9), walking the marker segments
/// (skipped by their lengths, so markers inside embedded thumbnails are not mistaken for it) and
/// scanning entropy-coded data for the next marker. A stream that does not start with the
/// start-of-image marker is left to the decoder to reject. Bytes after the end marker are allowed.
fn jpeg_is_complete(r: &mut impl BufRead) -> io::Result<bool> {
    let mut start = [0u8; 2];
    if r.read_exact(&mut start).is_err() || start != [0xFF, 0xD8] {
        return Ok(true);
    }
    // The marker found by the last entropy-data scan, if any.
    let mut pending = None;
    loop {
        let marker = match pending.take() {
            Some(m) => m,
            None => match next_marker(r)? {
                Some(m) => m,
                None => return Ok(false),
            },
        };
        match marker {
            0xD9 => return Ok(true),
            // Markers without a length.
            0x01 | 0xD0..=0xD8 => {}
            _ => {
                let mut len = [0u8; 2];
                if r.read_exact(&mut len).is_err() {
                    return Ok(false);
                }
                let body = u64::from(u16::from_be_bytes(len)).saturating_sub(2);
                if io::copy(&mut Read::take(&mut *r, body), &mut io::sink())? < body {
                    return Ok(false);
                }
                if marker == 0xDA {
                    // Start of scan: entropy-coded data follows, up to the next marker.
                    match scan_entropy_data(r)? {
                        Some(m) => pending = Some(m),
                        None => return Ok(false),
                    }
                }
            }
        }
    }
}

/// Reads up to the next marker (skipping stray bytes and fill bytes) and returns its code, or
/// `None` at the end of the stream.
fn next_marker(r: &mut impl BufRead) -> io::Result<Option<u8>> {
    let mut seen_ff = false;
    let mut byte = [0u8; 1];
    loop {
        if r.read(&mut byte)? == 0 {
            return Ok(None);
        }
        match (seen_ff, byte[0]) {
            (_, 0xFF) => seen_ff = true,
            (true, 0x00) => seen_ff = false,
            (true, m) => return Ok(Some(m)),
            (false, _) => {}
        }
    }
}

/// Skips entropy-coded data (where FF 00 is a data byte and FF D0–D7 restart markers belong to
/// the scan) and returns the marker that ends it, or `None` at the end of the stream.
fn scan_entropy_data(r: &mut impl BufRead) -> io::Result<Option<u8>> {
    let mut seen_ff = false;
    loop {
        let buf = r.fill_buf()?;
        if buf.is_empty() {
            return Ok(None);
        }
        let mut used = 0;
        for &b in buf {
            used += 1;
            if seen_ff {
                match b {
                    0xFF => continue,
                    0x00 | 0xD0..=0xD7 => seen_ff = false,
                    m => {
                        r.consume(used);
                        return Ok(Some(m));
                    }
                }
            } else if b == 0xFF {
                seen_ff = true;
            }
        }
        r.consume(used);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    fn sample_film() -> Film {
        Film::from_pixels(
            3,
            2,
            vec![
                Vec3::new(0.0, 0.5, 1.0),
                Vec3::new(0.25, 0.75, 2.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(0.1, 0.2, 0.3),
                Vec3::new(-1.0, f32::NAN, 0.9),
                Vec3::splat(0.6),
            ],
        )
    }

    fn dir_entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn output_format_from_extension() {
        assert_eq!(
            OutputFormat::from_path(Path::new("a/b.ppm")),
            Some(OutputFormat::Ppm)
        );
        assert_eq!(
            OutputFormat::from_path(Path::new("x.PNG")),
            Some(OutputFormat::Png)
        );
        assert_eq!(
            OutputFormat::from_path(Path::new("x.Exr")),
            Some(OutputFormat::Exr)
        );
        assert_eq!(OutputFormat::from_path(Path::new("x.jpg")), None);
        assert_eq!(OutputFormat::from_path(Path::new("png")), None);
        assert_eq!(OutputFormat::from_path(Path::new("x")), None);
    }

    #[test]
    fn ppm_bytes_are_exact() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.ppm");
        let film = Film::from_pixels(
            2,
            1,
            vec![Vec3::new(1.0, 0.5, 0.0), Vec3::new(0.2, 3.0, -1.0)],
        );
        write_image(&path, &film, ToneMap::Linear, 1.0).unwrap();
        let mut expected = b"P6\n2 1\n255\n".to_vec();
        expected.extend_from_slice(&[255, 127, 0, 51, 255, 0]);
        assert_eq!(fs::read(&path).unwrap(), expected);
        // Only the output remains: the temporary file was renamed, not copied.
        assert_eq!(dir_entries(dir.path()), vec!["out.ppm".to_string()]);
    }

    #[test]
    fn ppm_round_trip_and_exposure() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.ppm");
        let film = sample_film();
        write_image(&path, &film, ToneMap::Linear, 0.5).unwrap();
        let back = read_image(&path).unwrap();
        let expected: Vec<f32> = to_rgb8(&film, ToneMap::Linear, 0.5)
            .into_iter()
            .map(|b| f32::from(b) / 255.0)
            .collect();
        let got: Vec<f32> = back.pixels.iter().flat_map(|p| p.to_array()).collect();
        assert_eq!(got, expected);
        assert_eq!(back.get(2, 0), Vec3::new(127.0 / 255.0, 0.0, 0.0));
    }

    #[test]
    fn png_round_trip_matches_to_rgb8() {
        let dir = tempfile::tempdir().unwrap();
        let film = sample_film();
        for map in ToneMap::ALL {
            let path = dir.path().join(format!("out-{map}.png"));
            write_image(&path, &film, map, 1.0).unwrap();
            let back = read_image(&path).unwrap();
            assert_eq!((back.width, back.height), (3, 2));
            let expected: Vec<f32> = to_rgb8(&film, map, 1.0)
                .into_iter()
                .map(|b| f32::from(b) / 255.0)
                .collect();
            let got: Vec<f32> = back.pixels.iter().flat_map(|p| p.to_array()).collect();
            assert_eq!(got, expected, "{map}");
        }
    }

    #[test]
    fn exr_round_trip_keeps_floats() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.exr");
        let film = Film::from_pixels(
            2,
            2,
            vec![
                Vec3::new(3.5, 0.0, 1e-3),
                Vec3::new(100.25, 0.5, 7.0),
                Vec3::new(0.1, 0.2, 0.3),
                Vec3::new(65504.0, 1.0, 2.0),
            ],
        );
        write_image(&path, &film, ToneMap::Srgb, 1.0).unwrap();
        assert_eq!(read_image(&path).unwrap(), film);

        // Exposure scales EXR output but no tone curve is applied.
        write_image(&path, &film, ToneMap::Reinhard, 2.0).unwrap();
        let back = read_image(&path).unwrap();
        assert_eq!(back.get(0, 0), Vec3::new(7.0, 0.0, 2e-3));
        assert_eq!(back.get(1, 0), Vec3::new(200.5, 1.0, 14.0));
    }

    #[test]
    fn missing_folder_is_an_error_and_writes_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("no-such-folder").join("out.png");
        let err = write_image(&path, &sample_film(), ToneMap::Linear, 1.0).unwrap_err();
        assert!(
            matches!(err, ImageError::Output(OutputError::MissingFolder { .. })),
            "{err:?}"
        );
        let msg = err.to_string();
        assert!(
            msg.contains("out.png") && msg.contains("no-such-folder"),
            "{msg}"
        );
        assert!(!path.exists());
        assert!(dir_entries(dir.path()).is_empty());
    }

    #[test]
    fn parent_that_is_a_file_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("plain");
        fs::write(&file, b"x").unwrap();
        let err =
            write_image(&file.join("out.ppm"), &sample_film(), ToneMap::Linear, 1.0).unwrap_err();
        assert!(
            matches!(err, ImageError::Output(OutputError::MissingFolder { .. })),
            "{err:?}"
        );
        assert_eq!(fs::read(&file).unwrap(), b"x");
    }

    #[cfg(unix)]
    #[test]
    fn unwritable_folder_is_an_error() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let locked = dir.path().join("locked");
        fs::create_dir(&locked).unwrap();
        fs::set_permissions(&locked, fs::Permissions::from_mode(0o555)).unwrap();
        // Privileged users (root) can write anyway; only check where permissions apply.
        let probe = locked.join("probe");
        let enforced = fs::write(&probe, b"").is_err();
        let _ = fs::remove_file(&probe);
        let result = write_image(
            &locked.join("out.png"),
            &sample_film(),
            ToneMap::Linear,
            1.0,
        );
        fs::set_permissions(&locked, fs::Permissions::from_mode(0o755)).unwrap();
        if enforced {
            let err = result.unwrap_err();
            assert!(
                matches!(err, ImageError::Output(OutputError::Write { .. })),
                "{err:?}"
            );
            assert!(err.to_string().contains("out.png"), "{err}");
            assert!(dir_entries(&locked).is_empty());
        } else {
            result.unwrap();
        }
    }

    #[test]
    fn unknown_extension_is_an_error_and_names_supported_ones() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.tga");
        let err = write_image(&path, &sample_film(), ToneMap::Linear, 1.0).unwrap_err();
        assert!(
            matches!(err, ImageError::UnsupportedFormat { .. }),
            "{err:?}"
        );
        let msg = err.to_string();
        for part in ["out.tga", ".tga", ".ppm", ".png", ".exr"] {
            assert!(msg.contains(part), "{msg} lacks {part}");
        }
        assert!(!path.exists());

        let err = write_image(
            &dir.path().join("noext"),
            &sample_film(),
            ToneMap::Linear,
            1.0,
        )
        .unwrap_err();
        assert!(
            matches!(err, ImageError::UnsupportedFormat { .. }),
            "{err:?}"
        );
        assert!(dir_entries(dir.path()).is_empty());
    }

    #[test]
    fn invalid_film_is_an_error_not_a_panic() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.png");
        let bad = Film {
            width: 4,
            height: 4,
            pixels: vec![Vec3::ONE; 3],
        };
        let err = write_image(&path, &bad, ToneMap::Linear, 1.0).unwrap_err();
        assert!(
            matches!(err, ImageError::InvalidFilm { len: 3, .. }),
            "{err:?}"
        );
        let err = write_image(&path, &Film::new(0, 5), ToneMap::Linear, 1.0).unwrap_err();
        assert!(matches!(err, ImageError::InvalidFilm { .. }), "{err:?}");
        assert!(dir_entries(dir.path()).is_empty());
    }

    #[test]
    fn existing_file_survives_failed_writes() {
        let dir = tempfile::tempdir().unwrap();
        let old = b"previous render".to_vec();

        // Rejected before anything is written.
        let path = dir.path().join("keep.txt");
        fs::write(&path, &old).unwrap();
        assert!(write_image(&path, &sample_film(), ToneMap::Linear, 1.0).is_err());
        assert_eq!(fs::read(&path).unwrap(), old);

        let path = dir.path().join("keep.png");
        fs::write(&path, &old).unwrap();
        let bad = Film {
            width: 2,
            height: 2,
            pixels: vec![],
        };
        assert!(write_image(&path, &bad, ToneMap::Linear, 1.0).is_err());
        assert_eq!(fs::read(&path).unwrap(), old);

        // A successful write replaces it.
        write_image(&path, &sample_film(), ToneMap::Linear, 1.0).unwrap();
        assert_eq!(read_image(&path).unwrap().width, 3);
        assert_eq!(
            dir_entries(dir.path()),
            vec!["keep.png".to_string(), "keep.txt".to_string()]
        );
    }

    #[test]
    fn truncated_png_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("full.png");
        let film = Film::from_pixels(16, 16, vec![Vec3::new(0.3, 0.6, 0.9); 256]);
        write_image(&path, &film, ToneMap::Linear, 1.0).unwrap();
        let bytes = fs::read(&path).unwrap();
        for cut in [8, 20, 40, bytes.len() / 2, bytes.len() - 12] {
            let short = dir.path().join(format!("cut{cut}.png"));
            fs::write(&short, &bytes[..cut]).unwrap();
            let err = read_image(&short).unwrap_err();
            assert!(err.to_string().contains(&format!("cut{cut}.png")), "{err}");
        }
    }

    #[test]
    fn text_file_and_missing_file_are_errors() {
        let dir = tempfile::tempdir().unwrap();
        for name in ["notes.txt", "fake.png", "fake.jpg", "fake.ppm", "fake.exr"] {
            let path = dir.path().join(name);
            fs::write(&path, "this is not an image\n").unwrap();
            let err = read_image(&path).unwrap_err();
            assert!(matches!(err, ImageError::Decode { .. }), "{name}: {err:?}");
            assert!(err.to_string().contains(name), "{err}");
        }
        let missing = dir.path().join("missing.png");
        let err = read_image(&missing).unwrap_err();
        assert!(matches!(err, ImageError::Open { .. }), "{err:?}");
        assert!(err.to_string().contains("missing.png"), "{err}");
    }

    #[test]
    fn reads_ascii_p3_ppm() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("ascii.ppm");
        fs::write(&path, "P3\n# comment\n2 1\n255\n255 0 51\n0 128 255\n").unwrap();
        let film = read_image(&path).unwrap();
        assert_eq!((film.width, film.height), (2, 1));
        assert_eq!(film.get(0, 0), Vec3::new(1.0, 0.0, 0.2));
        assert_eq!(film.get(1, 0), Vec3::new(0.0, 128.0 / 255.0, 1.0));
    }

    /// A small JPEG (RGB, or gray when `gray`), as the `image` crate encodes it.
    fn jpeg_bytes(width: u32, height: u32, gray: bool) -> Vec<u8> {
        let mut out = Vec::new();
        let encoder = image::codecs::jpeg::JpegEncoder::new_with_quality(&mut out, 90);
        let (channels, color) = if gray {
            (1, ExtendedColorType::L8)
        } else {
            (3, ExtendedColorType::Rgb8)
        };
        let data: Vec<u8> = (0..width * height * channels)
            .map(|i| (i * 37 % 251) as u8)
            .collect();
        encoder.write_image(&data, width, height, color).unwrap();
        out
    }

    /// Rewrites the size in a JPEG's baseline start-of-frame header.
    fn patch_jpeg_size(bytes: &mut [u8], width: u16, height: u16) {
        let sof = bytes
            .windows(2)
            .position(|w| w == [0xFF, 0xC0])
            .expect("baseline JPEG");
        bytes[sof + 5..sof + 7].copy_from_slice(&height.to_be_bytes());
        bytes[sof + 7..sof + 9].copy_from_slice(&width.to_be_bytes());
    }

    #[test]
    fn conversion_matches_to_rgb32f_for_every_color_type() {
        use image::DynamicImage;
        let (w, h) = (5u32, 3u32);
        let mut seed = 7u32;
        let mut next = move || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            seed >> 8
        };
        let u8s = |n: u32, next: &mut dyn FnMut() -> u32| -> Vec<u8> {
            (0..n).map(|_| next() as u8).collect()
        };
        let u16s = |n: u32, next: &mut dyn FnMut() -> u32| -> Vec<u16> {
            (0..n).map(|_| next() as u16).collect()
        };
        let f32s = |n: u32, next: &mut dyn FnMut() -> u32| -> Vec<f32> {
            (0..n).map(|_| next() as f32 / 1000.0 - 3.0).collect()
        };
        let n = w * h;
        let images = vec![
            DynamicImage::ImageLuma8(
                image::ImageBuffer::from_raw(w, h, u8s(n, &mut next)).unwrap(),
            ),
            DynamicImage::ImageLumaA8(
                image::ImageBuffer::from_raw(w, h, u8s(2 * n, &mut next)).unwrap(),
            ),
            DynamicImage::ImageRgb8(
                image::ImageBuffer::from_raw(w, h, u8s(3 * n, &mut next)).unwrap(),
            ),
            DynamicImage::ImageRgba8(
                image::ImageBuffer::from_raw(w, h, u8s(4 * n, &mut next)).unwrap(),
            ),
            DynamicImage::ImageLuma16(
                image::ImageBuffer::from_raw(w, h, u16s(n, &mut next)).unwrap(),
            ),
            DynamicImage::ImageLumaA16(
                image::ImageBuffer::from_raw(w, h, u16s(2 * n, &mut next)).unwrap(),
            ),
            DynamicImage::ImageRgb16(
                image::ImageBuffer::from_raw(w, h, u16s(3 * n, &mut next)).unwrap(),
            ),
            DynamicImage::ImageRgba16(
                image::ImageBuffer::from_raw(w, h, u16s(4 * n, &mut next)).unwrap(),
            ),
            DynamicImage::ImageRgb32F(
                image::ImageBuffer::from_raw(w, h, f32s(3 * n, &mut next)).unwrap(),
            ),
            DynamicImage::ImageRgba32F(
                image::ImageBuffer::from_raw(w, h, f32s(4 * n, &mut next)).unwrap(),
            ),
        ];
        for img in images {
            let expected: Vec<f32> = img.to_rgb32f().into_raw();
            let Ok(got) = to_rgb_f32(img.color(), img.as_bytes(), n as usize) else {
                panic!("{:?} not converted", img.color());
            };
            let got: Vec<f32> = got.iter().flat_map(|p| p.to_array()).collect();
            assert_eq!(got, expected, "{:?}", img.color());
        }
    }

    #[test]
    fn image_over_the_pixel_limit_is_refused_from_its_header() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("wide.png");
        let film = Film::from_pixels(4, 3, vec![Vec3::splat(0.5); 12]);
        write_image(&path, &film, ToneMap::Linear, 1.0).unwrap();
        let limits = |max_pixels| ReadLimits {
            max_pixels,
            flag: Some("--max-test-pixels"),
        };
        assert_eq!(
            read_image_with(&path, &limits(12)).unwrap(),
            read_image(&path).unwrap()
        );
        let err = read_image_with(&path, &limits(11)).unwrap_err();
        assert!(matches!(err, ImageError::TooLarge { .. }), "{err:?}");
        let msg = err.to_string();
        for part in [
            "wide.png",
            "4×3 = 12 pixels",
            "limit of 11 pixels",
            "--max-test-pixels",
        ] {
            assert!(msg.contains(part), "{msg} lacks {part}");
        }
        // A side longer than the limit is caught by the decoder's own limits; the message still
        // gives the limit.
        let err = read_image_with(&path, &limits(3)).unwrap_err();
        let msg = err.to_string();
        assert!(
            msg.contains("wide.png")
                && msg.contains("3 pixels")
                && msg.contains("--max-test-pixels"),
            "{msg}"
        );
    }

    #[test]
    fn jpeg_bomb_is_refused_before_decoding() {
        let dir = tempfile::tempdir().unwrap();
        let mut bytes = jpeg_bytes(16, 16, true);
        patch_jpeg_size(&mut bytes, 23_000, 23_000);
        let path = dir.path().join("bomb.jpg");
        fs::write(&path, &bytes).unwrap();
        let err = read_image(&path).unwrap_err();
        assert!(
            matches!(err, ImageError::TooLarge { width: 23_000, .. }),
            "{err:?}"
        );
        assert!(err.to_string().contains("bomb.jpg"), "{err}");
    }

    #[test]
    fn truncated_jpeg_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let bytes = jpeg_bytes(32, 24, false);
        let path = dir.path().join("full.jpg");
        fs::write(&path, &bytes).unwrap();
        let full = read_image(&path).unwrap();
        assert_eq!((full.width, full.height), (32, 24));
        // Bytes after the end-of-image marker are allowed.
        let mut trailing = bytes.clone();
        trailing.extend_from_slice(b"trailing bytes \xFF\xD8");
        fs::write(&path, &trailing).unwrap();
        assert_eq!(read_image(&path).unwrap(), full);
        for cut in [2, 3, 30, bytes.len() / 2, bytes.len() - 2, bytes.len() - 1] {
            let short = dir.path().join(format!("cut{cut}.jpg"));
            fs::write(&short, &bytes[..cut]).unwrap();
            let err = read_image(&short).unwrap_err();
            assert!(err.to_string().contains(&format!("cut{cut}.jpg")), "{err}");
            if cut > 2 && cut < bytes.len() {
                assert!(
                    matches!(err, ImageError::Truncated { .. }),
                    "{cut}: {err:?}"
                );
            }
        }
    }

    #[test]
    fn jpeg_marker_walk_skips_segments_and_stuffed_bytes() {
        // SOI, an APP1 segment holding a complete embedded JPEG (its FF D9 must not count), SOS
        // with entropy data containing stuffed FF 00 and a restart marker, then EOI.
        let mut stream = vec![
            0xFF, 0xD8, 0xFF, 0xE1, 0x00, 0x08, 0xFF, 0xD8, 0xFF, 0xD9, 0x00, 0x00,
        ];
        stream.extend_from_slice(&[0xFF, 0xDA, 0x00, 0x04, 0x01, 0x02]);
        stream.extend_from_slice(&[0x12, 0xFF, 0x00, 0x34, 0xFF, 0xD0, 0x56, 0xFF, 0xFF]);
        let complete = |bytes: &[u8]| jpeg_is_complete(&mut io::Cursor::new(bytes)).unwrap();
        assert!(!complete(&stream));
        assert!(!complete(&stream[..10]));
        stream.push(0xD9);
        assert!(complete(&stream));
        // Not a JPEG at all: left to the decoder.
        assert!(complete(b"P6 1 1 255 abc"));
    }
}
