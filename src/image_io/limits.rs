//! How large an image may be read: the pixel limit, and the file-size and decoder limits
//! derived from it.

use image::Limits;

use crate::files::input::SizeLimit;

/// Default cap on the pixels of an image [`read_image`](super::read_image) reads: 2^27 (about
/// 134 megapixels), the largest render the scene loader allows by default, so any render can be
/// read back.
pub const DEFAULT_MAX_READ_PIXELS: u64 = 1 << 27;

/// Bytes of decoder working memory allowed beyond the decoded image itself.
const DECODER_HEADROOM: u64 = 64 << 20;

/// The largest decoded pixel the `image` crate produces: RGBA with 32-bit float channels.
const MAX_BYTES_PER_PIXEL: u64 = 16;

/// How large an image [`read_image_with`](super::read_image_with) accepts.
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
    pub(super) fn file_limit(&self) -> SizeLimit {
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
    pub(super) fn decoder_limits(&self) -> Limits {
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
