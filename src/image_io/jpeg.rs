//! Checking that a JPEG stream is complete before it is decoded: the JPEG decoder pads missing
//! data silently, so a truncated file would otherwise read as an image.

use std::io::{self, BufRead, Read};

/// Whether the JPEG stream reaches its end-of-image marker (FF D9), walking the marker segments
/// (skipped by their lengths, so markers inside embedded thumbnails are not mistaken for it) and
/// scanning entropy-coded data for the next marker. A stream that does not start with the
/// start-of-image marker is left to the decoder to reject. Bytes after the end marker are allowed.
pub(super) fn jpeg_is_complete(r: &mut impl BufRead) -> io::Result<bool> {
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
    use crate::image_io::{read_image, ImageError};
    use image::{ExtendedColorType, ImageEncoder};
    use std::fs;

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
