//! Encoding films into image files: PPM and PNG tone-mapped to 8 bits, EXR as linear floats
//! (see `exr`), written atomically.

use std::path::Path;

use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder};

use super::{ImageError, OutputFormat};
use crate::files::output::write_atomic;
use crate::film::{to_rgb8, Film, ToneMap};

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
            super::exr::encode(film, exposure, &mut out).map_err(encode_err)?;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::files::output::OutputError;
    use crate::image_io::read_image;
    use glam::Vec3;
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
}
