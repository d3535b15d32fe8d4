//! OpenEXR output: linear 32-bit float RGB, scaled by the exposure only.

use std::io;

use crate::film::Film;

/// Encodes the film's pixels times `exposure` into `out` as an EXR file written with
/// [`exr_encoding`]; the EXR crate's error is passed on as an I/O error carrying its message.
pub(super) fn encode(
    film: &Film,
    exposure: f32,
    out: &mut Vec<u8>,
) -> Result<(), image::ImageError> {
    // The samples are read from the film as the lines are compressed, not copied into
    // channels first (three more buffers the film's size).
    let w = film.width as usize;
    let rgb = exr::prelude::SpecificChannels::rgb(|at: exr::prelude::Vec2<usize>| {
        let p = film.pixels[at.y() * w + at.x()] * exposure;
        (p.x, p.y, p.z)
    });
    let layer = exr::prelude::Layer::new(
        (w, film.height as usize),
        exr::prelude::LayerAttributes::default(),
        exr_encoding(),
        rgb,
    );
    use exr::prelude::WritableImage;
    exr::prelude::Image::from_layer(layer)
        .write()
        .to_buffered(io::Cursor::new(out))
        .map_err(|e| image::ImageError::IoError(io::Error::other(e.to_string())))
}

/// How EXR files are written: ZIP-compressed scan lines in increasing order, so the same pixels
/// always give the same bytes (blocks compressed in parallel are still written in order).
pub fn exr_encoding() -> exr::prelude::Encoding {
    exr::prelude::Encoding::SMALL_LOSSLESS
}

#[cfg(test)]
mod tests {
    use crate::film::{Film, ToneMap};
    use crate::image_io::{read_image, write_image};
    use glam::Vec3;

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
}
