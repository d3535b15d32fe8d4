//! Decoded samples as float RGB, converted exactly as the `image` crate's `to_rgb32f` does.

use glam::Vec3;
use image::ColorType;

/// Why decoded samples could not become float RGB.
pub(super) enum Conversion {
    /// The float pixels could not be allocated.
    OutOfMemory,
    /// The decoder's colour type is not one the conversion knows.
    Unsupported,
}

/// Decoded samples (native-endian, as [`ImageDecoder::read_image`] writes them) as float RGB,
/// exactly as the `image` crate's `to_rgb32f` converts them: integers scaled to \[0, 1\], gray
/// repeated in all three channels, alpha dropped. The output is reserved fallibly.
pub(super) fn to_rgb_f32(
    color: ColorType,
    raw: &[u8],
    pixels: usize,
) -> Result<Vec<Vec3>, Conversion> {
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
