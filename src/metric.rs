//! Image error metrics, for `raytracer compare`, the golden-image tests and sampler studies.
//!
//! - **MSE**: mean squared error of linear RGB in [0, 1] over all channels (the coursework's
//!   definition: 8-bit images are value/255), and PSNR = 10·log10(1/MSE).
//! - **FLIP**: NVIDIA's perceptual difference (Andersson et al., "FLIP: A Difference Evaluator for
//!   Alternating Images", HPG 2020), through the `nv-flip` crate, at its default 67 pixels per
//!   degree. FLIP compares what is displayed, so both images are quantised to 8 bits first
//!   (linear, clamped: this renderer's default output).

use crate::film::Film;

/// A rectangle of pixels: columns `x..x + width`, rows `y..y + height`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Region {
    pub x: u32,
    pub y: u32,
    pub width: u32,
    pub height: u32,
}

impl Region {
    /// The whole of a `width × height` image.
    pub fn full(width: u32, height: u32) -> Region {
        Region {
            x: 0,
            y: 0,
            width,
            height,
        }
    }

    /// Whether the region is non-empty and lies inside a `width × height` image.
    pub fn fits(&self, width: u32, height: u32) -> bool {
        self.width > 0
            && self.height > 0
            && self.x as u64 + self.width as u64 <= width as u64
            && self.y as u64 + self.height as u64 <= height as u64
    }
}

impl std::str::FromStr for Region {
    type Err = String;
    /// `x,y,width,height`.
    fn from_str(s: &str) -> Result<Region, String> {
        let v: Vec<u32> = s
            .split(',')
            .map(|p| p.trim().parse::<u32>())
            .collect::<Result<_, _>>()
            .map_err(|_| format!("'{s}' is not a region x,y,width,height"))?;
        match v[..] {
            [x, y, width, height] => Ok(Region {
                x,
                y,
                width,
                height,
            }),
            _ => Err(format!("'{s}' is not a region x,y,width,height")),
        }
    }
}

/// Mean squared error over `region` of two images of the same size (panics otherwise: callers
/// check sizes and regions and report them as errors).
pub fn mse(reference: &Film, test: &Film, region: Region) -> f64 {
    assert_eq!(
        (reference.width, reference.height),
        (test.width, test.height)
    );
    assert!(region.fits(reference.width, reference.height));
    let mut sum = 0.0f64;
    for y in region.y..region.y + region.height {
        for x in region.x..region.x + region.width {
            let d = reference.get(x, y) - test.get(x, y);
            sum += (d.x as f64).powi(2) + (d.y as f64).powi(2) + (d.z as f64).powi(2);
        }
    }
    sum / (3 * region.width as u64 * region.height as u64) as f64
}

/// Peak signal-to-noise ratio in dB for a peak of 1 (∞ for identical images).
pub fn psnr(mse: f64) -> f64 {
    -10.0 * mse.log10()
}

fn to_flip_image(f: &Film) -> nv_flip::FlipImageRgb8 {
    let bytes: Vec<u8> = f
        .pixels
        .iter()
        .flat_map(|p| {
            p.to_array().map(|c| {
                if c.is_nan() {
                    0
                } else {
                    (c.clamp(0.0, 1.0) * 255.0).round() as u8
                }
            })
        })
        .collect();
    nv_flip::FlipImageRgb8::with_data(f.width, f.height, &bytes)
}

/// The FLIP error of every pixel, in [0, 1], row-major; NaN where either image holds NaN (a
/// pixel with no value has no error either, so every mean and threshold over it fails).
pub fn flip_map(reference: &Film, test: &Film) -> Vec<f32> {
    assert_eq!(
        (reference.width, reference.height),
        (test.width, test.height)
    );
    let map = nv_flip::flip(
        to_flip_image(reference),
        to_flip_image(test),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    );
    let mut map = map.to_vec();
    for (i, v) in map.iter_mut().enumerate() {
        if reference.pixels[i].is_nan() || test.pixels[i].is_nan() {
            *v = f32::NAN;
        }
    }
    map
}

/// Mean FLIP error over `region`.
pub fn mean_flip(reference: &Film, test: &Film, region: Region) -> f64 {
    let map = flip_map(reference, test);
    assert!(region.fits(reference.width, reference.height));
    let mut sum = 0.0f64;
    for y in region.y..region.y + region.height {
        for x in region.x..region.x + region.width {
            sum += map[(y * reference.width + x) as usize] as f64;
        }
    }
    sum / (region.width as u64 * region.height as u64) as f64
}

/// A heat map of a per-pixel error in [0, 1] (FLIP's "magma" colours), as a displayable film.
pub fn heat_map(width: u32, height: u32, error: &[f32]) -> Film {
    // A pixel without an error value (NaN) is shown as the largest error.
    let error: Vec<f32> = error
        .iter()
        .map(|&e| if e.is_nan() { 1.0 } else { e })
        .collect();
    let map = nv_flip::FlipImageFloat::with_data(width, height, &error);
    let rgb = map.apply_color_lut(&nv_flip::magma_lut()).to_vec();
    let pixels = rgb
        .chunks_exact(3)
        .map(|c| glam::Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32) / 255.0)
        .collect();
    Film::from_pixels(width, height, pixels)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn flat(w: u32, h: u32, c: f32) -> Film {
        Film::from_pixels(w, h, vec![Vec3::splat(c); (w * h) as usize])
    }

    #[test]
    fn a_nan_pixel_makes_both_metrics_nan() {
        let a = flat(8, 8, 0.5);
        let mut b = flat(8, 8, 0.5);
        b.pixels[9] = Vec3::new(0.5, f32::NAN, 0.5);
        assert!(mse(&a, &b, Region::full(8, 8)).is_nan());
        assert!(mean_flip(&a, &b, Region::full(8, 8)).is_nan());
        // Outside the NaN pixel's region both are defined.
        let corner = Region {
            x: 4,
            y: 4,
            width: 4,
            height: 4,
        };
        assert_eq!(mse(&a, &b, corner), 0.0);
        let heat = heat_map(8, 8, &flip_map(&a, &b));
        assert!(heat.pixels.iter().all(|p| p.is_finite()));
    }

    #[test]
    fn mse_and_psnr_of_known_differences() {
        let a = flat(4, 4, 0.5);
        let b = flat(4, 4, 0.6);
        let m = mse(&a, &b, Region::full(4, 4));
        assert!((m - 0.01).abs() < 1e-7);
        assert!((psnr(m) - 20.0).abs() < 1e-4);
        assert_eq!(mse(&a, &a, Region::full(4, 4)), 0.0);
        assert_eq!(psnr(0.0), f64::INFINITY);
        // Only the region counts.
        let mut c = a.clone();
        c.set(3, 3, Vec3::ONE);
        assert_eq!(
            mse(
                &a,
                &c,
                Region {
                    x: 0,
                    y: 0,
                    width: 3,
                    height: 3
                }
            ),
            0.0
        );
        assert!(mse(&a, &c, Region::full(4, 4)) > 0.0);
    }

    #[test]
    fn flip_is_zero_for_identical_images_and_grows_with_the_difference() {
        let a = flat(32, 32, 0.5);
        assert_eq!(mean_flip(&a, &a, Region::full(32, 32)), 0.0);
        let small = mean_flip(&a, &flat(32, 32, 0.52), Region::full(32, 32));
        let large = mean_flip(&a, &flat(32, 32, 0.9), Region::full(32, 32));
        assert!(small > 0.0 && large > small, "{small} {large}");
        let heat = heat_map(32, 32, &flip_map(&a, &flat(32, 32, 0.9)));
        assert_eq!((heat.width, heat.height), (32, 32));
    }

    #[test]
    fn regions_parse_and_check_bounds() {
        let r: Region = "1,2,3,4".parse().unwrap();
        assert_eq!(
            r,
            Region {
                x: 1,
                y: 2,
                width: 3,
                height: 4
            }
        );
        assert!("1,2,3".parse::<Region>().is_err());
        assert!("a,b,c,d".parse::<Region>().is_err());
        assert!(r.fits(4, 6) && !r.fits(3, 6) && !Region::full(0, 0).fits(1, 1));
    }
}
