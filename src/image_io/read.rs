//! Reading image files as films or textures: the file is opened, its format identified, its
//! header checked against the [`ReadLimits`], and its samples decoded into a fallibly allocated
//! buffer before they become floats (or stay bytes, for 8-bit textures).

use std::fs::File;
use std::io::{self, BufReader, Seek};
use std::path::Path;

use image::{ColorType, ImageDecoder, ImageReader};

use super::jpeg::jpeg_is_complete;
use super::samples::{to_rgb_f32, Conversion};
use super::{ImageError, ReadLimits};
use crate::files::input;
use crate::film::Film;

/// Reads PNG, JPEG, PPM (P3 ascii and P6 binary) or EXR into a linear Film:
/// 8-bit formats as value/255 (no gamma decoding: this renderer's default output is linear ×255),
/// 16-bit as value/65535, EXR as its float values (alpha is dropped). The format is detected
/// from the file's contents, falling back to its extension. Used to compare renders with references.
///
/// Images over [`DEFAULT_MAX_READ_PIXELS`](super::DEFAULT_MAX_READ_PIXELS) are
/// refused; [`read_image_with`] takes other limits.
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
        // once (a copy is a second buffer of the texture's size).
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
    /// The number of pixels, `width × height`.
    fn pixels(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// The error for an allocation of `bytes` for this image that failed.
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
    let mut reader = open_reader(path, limits)?;
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

/// Opens the file within the size limit and identifies its format from its contents, else
/// from its extension (as `ImageReader::open` does); a JPEG is checked for completeness first.
fn open_reader(
    path: &Path,
    limits: &ReadLimits,
) -> Result<ImageReader<BufReader<File>>, ImageError> {
    let open_err = |source: io::Error| ImageError::Open {
        path: path.to_path_buf(),
        source,
    };
    let file = input::open(path).map_err(open_err)?;
    input::checked_size(&file, limits.file_limit()).map_err(open_err)?;
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
    Ok(reader)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::{Film, ToneMap};
    use crate::image_io::write_image;
    use glam::Vec3;
    use std::fs;

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
}
