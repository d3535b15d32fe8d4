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
//!
//! The parts: `write` encodes films (PPM and PNG itself, EXR through `exr`); `read` opens,
//! checks and decodes files under the `limits`, checking JPEG completeness with `jpeg` and
//! turning decoded samples into floats with `samples`.

mod exr;
mod jpeg;
mod limits;
mod read;
mod samples;
mod write;

use std::io;
use std::path::{Path, PathBuf};

use crate::files::output::OutputError;
use crate::files::{raise_hint, shown};

pub use self::exr::exr_encoding;
pub use self::limits::{ReadLimits, DEFAULT_MAX_READ_PIXELS};
pub use self::read::{read_image, read_image_with, read_texture_with, TextureImage};
pub use self::write::{encode_image, write_image};

/// The extensions [`write_image`] accepts, as listed in error messages.
const SUPPORTED_EXTENSIONS: &str = ".ppm, .png, .exr";

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

/// How an output path's extension is named in [`ImageError::UnsupportedFormat`]'s message.
fn describe_extension(path: &Path) -> String {
    match path.extension() {
        Some(ext) => format!("'.{}'", ext.to_string_lossy()),
        None => "(none)".to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
