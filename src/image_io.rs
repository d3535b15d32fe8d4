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
//! linear output, so renders and references can be compared directly. Decoding uses the
//! `image` crate's default resource limits, and every failure is an [`ImageError`] naming the
//! file; malformed input never panics.

use std::io::{self, BufReader};
use std::path::{Path, PathBuf};

use glam::Vec3;
use image::codecs::openexr::OpenExrEncoder;
use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder, ImageReader};

use crate::files::output::{write_atomic, OutputError};
use crate::files::{input, shown};
use crate::film::{to_rgb8, Film, ToneMap};

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
    /// The file is not a supported image, is malformed, or exceeds the decoder's limits.
    #[error("cannot read image '{}': {source}", shown(path))]
    Decode {
        /// The input path.
        path: PathBuf,
        /// The underlying error.
        source: image::ImageError,
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
            let floats: Vec<u8> = film
                .pixels
                .iter()
                .flat_map(|&p| (p * exposure).to_array())
                .flat_map(f32::to_ne_bytes)
                .collect();
            OpenExrEncoder::new(io::Cursor::new(&mut out))
                .write_image(&floats, width, height, ExtendedColorType::Rgb32F)
                .map_err(encode_err)?;
        }
    }
    Ok(out)
}

/// Reads PNG, JPEG, PPM (P3 ascii and P6 binary) or EXR into a linear Film:
/// 8-bit formats as value/255 (no gamma decoding: this renderer's default output is linear ×255),
/// 16-bit as value/65535, EXR as its float values (alpha is dropped). The format is detected
/// from the file's contents, falling back to its extension. Used to compare renders with references.
pub fn read_image(path: &Path) -> Result<Film, ImageError> {
    let open_err = |source: io::Error| ImageError::Open {
        path: path.to_path_buf(),
        source,
    };
    let file = input::open(path).map_err(open_err)?;
    // The format from the contents, else from the extension (as `ImageReader::open` does).
    let mut reader = ImageReader::new(BufReader::new(file))
        .with_guessed_format()
        .map_err(open_err)?;
    if reader.format().is_none() {
        if let Ok(format) = image::ImageFormat::from_path(path) {
            reader.set_format(format);
        }
    }
    let image = reader.decode().map_err(|source| ImageError::Decode {
        path: path.to_path_buf(),
        source,
    })?;
    let rgb = image.to_rgb32f();
    let (width, height) = rgb.dimensions();
    let pixels = rgb
        .as_raw()
        .chunks_exact(3)
        .map(|c| Vec3::new(c[0], c[1], c[2]))
        .collect();
    Ok(Film::from_pixels(width, height, pixels))
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
}
