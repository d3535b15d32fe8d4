//! The hand-made suite of broken inputs in `tests/bad_input/`: each is run through the command
//! line. Every one must exit with status 1 (not a panic), print a message that names the file, the
//! place (line:column or JSON path) and the rule broken, and leave the output path as it was: an
//! existing image there is neither replaced nor joined by stray files.

mod common;

use std::process::Command;

use common::repo;

/// (file, fragments its message must contain). The file name itself is always required too.
const CASES: &[(&str, &[&str])] = &[
    ("syntax-unclosed.json", &[":1:13:", "invalid JSON"]),
    (
        "syntax-trailing-garbage.json",
        &[":2:1:", "more than one JSON value"],
    ),
    ("syntax-missing-comma.json", &[":1:16:", "comma"]),
    ("syntax-single-quotes.json", &[":1:3:", "Single-quoted"]),
    ("empty.json", &[":1:1:", "empty"]),
    ("binary.json", &["not UTF-8"]),
    ("root-array.json", &["(root)", "JSON object"]),
    ("root-string.json", &["(root)", "JSON object"]),
    (
        "no-camera.json",
        &["(root)", "missing required key 'camera'"],
    ),
    ("camera-not-object.json", &["camera:", "expected an object"]),
    ("width-string.json", &["camera.width", "expected a number"]),
    ("width-zero.json", &["camera.width", "at least 1×1"]),
    ("height-negative.json", &["camera.height", "whole number"]),
    (
        "width-fraction.json",
        &["camera.width", "whole number", "8.5"],
    ),
    (
        "size-absurd.json",
        &["camera.width", "limit of 134217728 pixels", "--max-pixels"],
    ),
    (
        "fov-nan.json",
        &["camera.fov", "NaN is not a finite number"],
    ),
    ("fov-zero.json", &["camera.fov", "between 0 and 180"]),
    ("fov-180.json", &["camera.fov", "between 0 and 180"]),
    ("fov-missing.json", &["camera:", "'fov'"]),
    (
        "position-two-numbers.json",
        &["camera.position", "3 numbers", "2 elements"],
    ),
    (
        "position-string-element.json",
        &["camera.position[1]", "expected a number"],
    ),
    (
        "lookat-zero.json",
        &["camera.lookat", "viewing direction is zero"],
    ),
    ("nbounces-negative.json", &["nbounces", "whole number"]),
    (
        "nbounces-huge.json",
        &["nbounces", "limit of 64", "--max-bounces"],
    ),
    ("nbounces-string.json", &["nbounces", "expected a number"]),
    (
        "background-two-numbers.json",
        &["scene.backgroundcolor", "3 numbers"],
    ),
    (
        "shapes-not-array.json",
        &["scene.shapes", "expected an array"],
    ),
    (
        "shape-not-object.json",
        &["scene.shapes[0]", "a shape is an object"],
    ),
    ("shape-missing-type.json", &["scene.shapes[0]", "'type'"]),
    (
        "sphere-radius-negative.json",
        &["scene.shapes[0].radius", "> 0", "-1"],
    ),
    (
        "sphere-radius-zero.json",
        &["scene.shapes[0].radius", "> 0"],
    ),
    (
        "sphere-radius-infinity.json",
        &["scene.shapes[0].radius", "not a finite number"],
    ),
    (
        "sphere-radius-huge.json",
        &["scene.shapes[0].radius", "too large"],
    ),
    (
        "sphere-missing-center.json",
        &["scene.shapes[0]", "'center'"],
    ),
    ("triangle-missing-corner.json", &["scene.shapes[0]", "'v2'"]),
    ("triangle-zero-area.json", &["scene.shapes[0]", "zero area"]),
    ("quad-zero-area.json", &["scene.shapes[0]", "zero area"]),
    (
        "cylinder-axis-zero.json",
        &["scene.shapes[0].axis", "must not be zero"],
    ),
    (
        "cylinder-height-negative.json",
        &["scene.shapes[0].height", "> 0"],
    ),
    (
        "mesh-index-out-of-range.json",
        &[
            "scene.shapes[0].faces[0]",
            "index 3 is out of range",
            "3 vertices",
        ],
    ),
    (
        "mesh-index-negative.json",
        &["scene.shapes[0].faces[0]", "index -1 is out of range"],
    ),
    (
        "mesh-face-two-indices.json",
        &["scene.shapes[0].faces[0]", "at least 3"],
    ),
    ("mesh-no-faces.json", &["scene.shapes[0]", "no faces"]),
    (
        "mesh-file-missing.json",
        &[
            "scene.shapes[0].mPath",
            "not-there.ply",
            "not found",
            "tried",
        ],
    ),
    (
        "mesh-ply-lies-about-counts.json",
        &[
            "scene.shapes[0].mPath",
            "lying.ply",
            "1000000",
            "truncated or corrupt",
        ],
    ),
    (
        "mesh-ply-garbage.json",
        &["scene.shapes[0].mPath", "garbage.ply", "PLY header"],
    ),
    (
        "mesh-ply-bad-index.json",
        &[
            "scene.shapes[0].mPath",
            "bad-index.ply",
            "line 13",
            "out of range",
        ],
    ),
    (
        "mesh-obj-bad-index.json",
        &[
            "scene.shapes[0].mPath",
            "bad-index.obj",
            "line 4",
            "out of range",
        ],
    ),
    (
        "mesh-unknown-format.json",
        &["scene.shapes[0].mPath", ".stl", ".ply and .obj"],
    ),
    (
        "texture-missing.json",
        &["material.tPath", "none.png", "not found", "tried"],
    ),
    (
        "texture-truncated.json",
        &["material.tPath", "truncated.png", "cannot load the texture"],
    ),
    (
        "texture-not-an-image.json",
        &[
            "material.tPath",
            "not-an-image.png",
            "cannot load the texture",
        ],
    ),
    (
        "material-not-object.json",
        &["scene.shapes[0].material", "is an object"],
    ),
    (
        "material-unknown-name.json",
        &["scene.shapes[0].material", "no material named 'gold'"],
    ),
    ("kd-negative.json", &["material.kd", "≥ 0"]),
    ("eta-zero-glass.json", &["material.eta", "> 0"]),
    (
        "roughness-negative.json",
        &["material.roughness", "finite number ≥ 0", "-0.2"],
    ),
    (
        "specular-exponent-negative.json",
        &["scene.shapes[0].material", "exponent", "≥ 0"],
    ),
    (
        "light-missing-position.json",
        &["scene.lightsources[0]", "'position'"],
    ),
    (
        "light-not-object.json",
        &["scene.lightsources[0]", "a light is an object"],
    ),
    (
        "light-intensity-string.json",
        &["scene.lightsources[0].intensity", "found a string"],
    ),
    (
        "arealight-no-geometry.json",
        &["scene.lightsources[0]", "needs corners"],
    ),
    (
        "arealight-sphere-radius-zero.json",
        &["scene.lightsources[0].shape.radius", "> 0, found 0"],
    ),
    (
        "arealight-sphere-radius-negative.json",
        &["scene.lightsources[0].shape.radius", "> 0, found -0.5"],
    ),
    (
        "arealight-sphere-no-center.json",
        &[
            "scene.lightsources[0].shape:",
            "missing required key 'center'",
        ],
    ),
    (
        "arealight-shape-box.json",
        &[
            "scene.lightsources[0].shape.type",
            "a sphere, a triangle or a quad",
            "'box'",
        ],
    ),
    (
        "arealight-shapeid-unknown.json",
        &[
            "scene.lightsources[0].shapeid",
            "no shape has the id 'lamp'",
            "'ball', 'ceiling'",
        ],
    ),
    (
        "arealight-shapeid-mesh.json",
        &[
            "scene.lightsources[0].shapeid",
            "'lamp' (scene.shapes[1]) is a 'trimesh'",
            "only a sphere, a triangle or a quad",
        ],
    ),
    (
        "arealight-shapeid-cylinder.json",
        &[
            "scene.lightsources[0].shapeid",
            "is a 'cylinder'",
            "only a sphere, a triangle or a quad",
        ],
    ),
    (
        "arealight-shapeid-not-string.json",
        &["scene.lightsources[0].shapeid", "expected a string"],
    ),
    (
        "arealight-samples-absurd.json",
        &[
            "scene.lightsources[0].samples",
            "limit of 65536",
            "--max-light-samples",
        ],
    ),
    (
        "arealight-samples-negative.json",
        &["scene.lightsources[0].samples", "whole number"],
    ),
    ("thinlens-no-focus.json", &["camera:", "focus distance"]),
    (
        "thinlens-negative-aperture.json",
        &["camera:", "aperture", "≥ 0"],
    ),
    (
        "rendermode-number.json",
        &["rendermode", "expected a string"],
    ),
    ("exposure-negative.json", &["camera.exposure", "≥ 0"]),
    (
        "material-ka-negative.json",
        &["scene.shapes[0].material.ka", "ka must be ≥ 0"],
    ),
    (
        "light-attenuation-zero.json",
        &["scene.lightsources[0]", "zero at every distance"],
    ),
    (
        "light-attenuation-negative.json",
        &["scene.lightsources[0].kl", "kl must be ≥ 0"],
    ),
    (
        "ambient-negative.json",
        &["scene.ambientlight", "finite and ≥ 0"],
    ),
    (
        "ambient-light-no-intensity.json",
        &["scene.lightsources[0]", "missing required key 'intensity'"],
    ),
    (
        "plane-normal-zero.json",
        &["scene.shapes[0].normal", "normal must not be zero"],
    ),
    (
        "plane-distance-nan.json",
        &["scene.shapes[0].distance", "NaN is not a finite number"],
    ),
    (
        "texture-library-image-missing.json",
        &["scene.textures[0].image", "Ball1-nowhere.jpg", "not found"],
    ),
    (
        "texture-library-unknown-type.json",
        &["scene.textures[0].type", "unknown texture type 'perlin'"],
    ),
    (
        "box-euler-not-numbers.json",
        &["scene.shapes[0].rotation[1]", "expected a number"],
    ),
    (
        "mesh-euler-not-numbers.json",
        &["scene.shapes[0].euler", "found a string"],
    ),
    (
        "rectanglexy-zero-width.json",
        &["scene.shapes[0].x1", "no area"],
    ),
    (
        "pixelsample-negative.json",
        &[":1:18:", "pixelsample", "whole number", "-4"],
    ),
    (
        "pixelsample-fraction.json",
        &["pixelsample", "whole number", "2.5"],
    ),
    (
        "pixelsample-absurd.json",
        &[
            "pixel_sample_num",
            "1000000 samples per pixel",
            "limit of 65536",
            "--max-pixel-samples",
        ],
    ),
    (
        "lightsample-absurd.json",
        &["lightsample", "limit of 65536", "--max-light-samples"],
    ),
    (
        "no-scene.json",
        &[":1:1:", "(root)", "nothing to render", "'scene'"],
    ),
    (
        "arealight-shapeid-infinite-plane.json",
        &[
            "scene.lightsources[0].shapeid",
            "infinite plane",
            "no finite area",
        ],
    ),
];

#[test]
fn every_broken_input_fails_cleanly_and_touches_nothing() {
    let dir = repo().join("tests/bad_input");
    let on_disk: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".json") && !n.starts_with("fuzz-"))
        .collect();
    for name in &on_disk {
        assert!(
            CASES.iter().any(|(c, _)| c == name),
            "{name} has no expectation"
        );
    }
    assert!(CASES.len() >= 40);
    for (name, needles) in CASES {
        let scene = dir.join(name);
        assert!(scene.is_file(), "{name} missing");
        let out_dir = tempfile::tempdir().unwrap();
        let out = out_dir.path().join("render.png");
        std::fs::write(&out, b"an earlier render").unwrap();
        let o = Command::new(env!("CARGO_BIN_EXE_raytracer"))
            .arg(&scene)
            .arg(&out)
            .output()
            .unwrap();
        let msg = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{name}: {msg}");
        assert!(!msg.contains("panicked"), "{name}: {msg}");
        assert!(
            msg.contains(name),
            "{name}: the message does not name the file: {msg}"
        );
        for n in *needles {
            assert!(msg.contains(n), "{name}: the message lacks '{n}': {msg}");
        }
        assert_eq!(std::fs::read(&out).unwrap(), b"an earlier render", "{name}");
        assert_eq!(
            std::fs::read_dir(out_dir.path()).unwrap().count(),
            1,
            "{name}: stray files"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Generated cases: assets too large to keep in the repository, or that cannot be files in it
// (FIFOs, devices). Each is written into a temporary folder next to its scene.
// ---------------------------------------------------------------------------------------------

/// A scene with one textured sphere whose `tPath` is `texture`.
fn texture_scene(texture: &str) -> String {
    format!(
        r#"{{ "camera": {{ "type": "pinhole", "width": 8, "height": 6, "fov": 40,
              "position": [0, -4, 1], "lookat": [0, 1, 0], "up": [0, 0, 1] }},
             "scene": {{ "backgroundcolor": [0, 0, 0], "lightsources": [],
               "shapes": [{{ "type": "sphere", "center": [0, 0, 0], "radius": 1,
                 "material": {{ "kd": 0.8, "diffusecolor": [1, 1, 1], "tPath": "{texture}" }} }}] }} }}"#
    )
}

/// A scene with one mesh read from `mesh`.
fn mesh_scene(mesh: &str) -> String {
    format!(
        r#"{{ "camera": {{ "type": "pinhole", "width": 8, "height": 6, "fov": 40,
              "position": [0, -4, 1], "lookat": [0, 1, 0], "up": [0, 0, 1] }},
             "scene": {{ "backgroundcolor": [0, 0, 0], "lightsources": [],
               "shapes": [{{ "type": "mesh", "mPath": "{mesh}",
                 "material": {{ "kd": 0.8, "diffusecolor": [1, 1, 1] }} }}] }} }}"#
    )
}

/// Runs `raytracer <args…> <dir>/render.png` over an earlier render and returns its stderr after
/// checking that it exited with status 1 without a panic and left the earlier render alone.
fn fails_cleanly(dir: &std::path::Path, args: &[&std::ffi::OsStr]) -> String {
    let out = dir.join("render.png");
    std::fs::write(&out, b"an earlier render").unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .args(args)
        .arg(&out)
        .output()
        .unwrap();
    let msg = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(1), "{args:?}: {msg}");
    assert!(!msg.contains("panicked"), "{args:?}: {msg}");
    assert_eq!(std::fs::read(&out).unwrap(), b"an earlier render");
    msg
}

/// Writes `json` as `scene.json` in `dir`, renders it with `flags` and returns the message of
/// the clean failure, checked to contain every one of `needles`.
fn scene_fails(dir: &std::path::Path, json: &str, flags: &[&str], needles: &[&str]) -> String {
    let scene = dir.join("scene.json");
    std::fs::write(&scene, json).unwrap();
    let mut args: Vec<&std::ffi::OsStr> = vec![scene.as_os_str()];
    args.extend(flags.iter().map(std::ffi::OsStr::new));
    let msg = fails_cleanly(dir, &args);
    for n in needles {
        assert!(msg.contains(n), "the message lacks '{n}': {msg}");
    }
    msg
}

/// CRC-32 as PNG chunks use it.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// Deflate bits, least significant first.
#[derive(Default)]
struct Bits {
    bytes: Vec<u8>,
    used: u32,
}

impl Bits {
    fn put(&mut self, value: u32, count: u32) {
        for i in 0..count {
            if self.used.is_multiple_of(8) {
                self.bytes.push(0);
            }
            if value >> i & 1 != 0 {
                *self.bytes.last_mut().unwrap() |= 1 << (self.used % 8);
            }
            self.used += 1;
        }
    }

    /// A Huffman code, which deflate stores most significant bit first.
    fn code(&mut self, code: u32, count: u32) {
        self.put(code.reverse_bits() >> (32 - count), count);
    }
}

/// A zlib stream of `n` zero bytes: one fixed-Huffman block of a literal zero and copies of 258
/// bytes at distance 1 (13 bits each), so about 2500 times smaller than the data.
fn zlib_zeros(n: u64) -> Vec<u8> {
    let mut bits = Bits::default();
    bits.put(1, 1); // final block
    bits.put(1, 2); // fixed Huffman codes
    let literal_zero = |bits: &mut Bits| bits.code(0x30, 8);
    literal_zero(&mut bits);
    for _ in 0..(n - 1) / 258 {
        bits.code(0xC5, 8); // length 258 (code 285)
        bits.code(0, 5); // distance 1
    }
    for _ in 0..(n - 1) % 258 {
        literal_zero(&mut bits);
    }
    bits.code(0, 7); // end of block
    let mut out = vec![0x78, 0x01];
    out.extend(bits.bytes);
    // Adler-32 of zeros: a stays 1, b grows by 1 a byte.
    let adler = ((n % 65521) as u32) << 16 | 1;
    out.extend(adler.to_be_bytes());
    out
}

/// A black 1-bit grayscale PNG of `width × height`, compressed to a few hundred bytes per
/// megapixel.
fn black_png(width: u32, height: u32) -> Vec<u8> {
    let chunk = |out: &mut Vec<u8>, kind: &[u8], data: &[u8]| {
        out.extend((data.len() as u32).to_be_bytes());
        let start = out.len();
        out.extend(kind);
        out.extend(data);
        let crc = crc32(&out[start..]);
        out.extend(crc.to_be_bytes());
    };
    let mut ihdr = Vec::new();
    ihdr.extend(width.to_be_bytes());
    ihdr.extend(height.to_be_bytes());
    ihdr.extend([1, 0, 0, 0, 0]); // 1 bit, gray, deflate, adaptive filters, no interlace
                                  // Each row: a filter byte (0 = none) and the packed bits.
    let row = 1 + u64::from(width).div_ceil(8);
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    chunk(&mut png, b"IHDR", &ihdr);
    chunk(&mut png, b"IDAT", &zlib_zeros(row * u64::from(height)));
    chunk(&mut png, b"IEND", &[]);
    png
}

/// A small JPEG, gray or RGB, as the `image` crate encodes it.
fn small_jpeg(width: u32, height: u32, gray: bool) -> Vec<u8> {
    use image::ImageEncoder;
    let (channels, color) = if gray {
        (1, image::ExtendedColorType::L8)
    } else {
        (3, image::ExtendedColorType::Rgb8)
    };
    let data: Vec<u8> = (0..width * height * channels)
        .map(|i| (i * 7 % 256) as u8)
        .collect();
    let mut out = Vec::new();
    image::codecs::jpeg::JpegEncoder::new_with_quality(&mut out, 90)
        .write_image(&data, width, height, color)
        .unwrap();
    out
}

#[test]
fn the_bomb_generator_writes_a_real_png() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("black.png");
    std::fs::write(&path, black_png(1000, 300)).unwrap();
    let film = raytracer::image_io::read_image(&path).unwrap();
    assert_eq!((film.width, film.height), (1000, 300));
    assert!(film
        .pixels
        .iter()
        .all(|p| *p == raytracer::math::Vec3::ZERO));
}

#[test]
fn decompression_bombs_fail_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // 23000 × 23000 pixels: 66 MB as 1-bit rows, 6.3 GB as float RGB; about 420 KB on disk.
    let png = black_png(23_000, 23_000);
    assert!(png.len() < 1 << 20, "{} bytes", png.len());
    std::fs::write(d.join("bomb.png"), &png).unwrap();
    let needles = [
        "bomb.png",
        "scene.shapes[0].material.tPath",
        "23000×23000",
        "limit of 67108864 pixels",
        "--max-texture-pixels",
    ];
    scene_fails(d, &texture_scene("bomb.png"), &[], &needles);

    // A gray JPEG of 16 × 16 pixels whose header claims 23000 × 23000.
    let mut jpeg = small_jpeg(16, 16, true);
    let sof = jpeg.windows(2).position(|w| w == [0xFF, 0xC0]).unwrap();
    jpeg[sof + 5..sof + 9].copy_from_slice(&[0x59, 0xD8, 0x59, 0xD8]);
    std::fs::write(d.join("bomb.jpg"), &jpeg).unwrap();
    let needles = [
        "bomb.jpg",
        "scene.shapes[0].material.tPath",
        "23000×23000",
        "limit of 67108864 pixels",
        "--max-texture-pixels",
    ];
    scene_fails(d, &texture_scene("bomb.jpg"), &[], &needles);

    // The flag sets the limit.
    std::fs::write(d.join("wide.jpg"), small_jpeg(40, 30, false)).unwrap();
    let needles = ["wide.jpg", "40×30 = 1200 pixels", "limit of 1000 pixels"];
    scene_fails(
        d,
        &texture_scene("wide.jpg"),
        &["--max-texture-pixels", "1000"],
        &needles,
    );

    // Comparing against a bomb fails cleanly too.
    std::fs::write(d.join("small.png"), black_png(4, 4)).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .arg("compare")
        .arg(d.join("bomb.png"))
        .arg(d.join("small.png"))
        .output()
        .unwrap();
    let msg = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{msg}");
    assert!(!msg.contains("panicked"), "{msg}");
    assert!(
        msg.contains("bomb.png") && msg.contains("limit of 134217728 pixels"),
        "{msg}"
    );
}

#[test]
fn truncated_jpeg_texture_fails_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let jpeg = small_jpeg(64, 48, false);
    std::fs::write(dir.path().join("truncated.jpg"), &jpeg[..jpeg.len() / 2]).unwrap();
    let needles = [
        "truncated.jpg",
        "scene.shapes[0].material.tPath",
        "end-of-image marker",
    ];
    scene_fails(dir.path(), &texture_scene("truncated.jpg"), &[], &needles);
}

#[test]
fn mesh_blow_ups_fail_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // One polygon of 1.5 million corners (3 MB): a fan of about 1.5 million triangles.
    let mut obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf".to_vec();
    for _ in 0..500_000 {
        obj.extend_from_slice(b" 1 2 3");
    }
    obj.push(b'\n');
    std::fs::write(d.join("fan.obj"), &obj).unwrap();
    let needles = [
        "fan.obj (line 4)",
        "scene.shapes[0].mPath",
        "1499998 triangles",
        "limit of 1000000 triangles",
        "--max-triangles",
    ];
    scene_fails(
        d,
        &mesh_scene("fan.obj"),
        &["--max-triangles", "1000000"],
        &needles,
    );

    // A PLY header that claims far more faces than the file holds.
    let header = |faces: u64| {
        format!(
            "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n\
             property float y\nproperty float z\nelement face {faces}\n\
             property list uchar int vertex_indices\nend_header\n"
        )
        .into_bytes()
    };
    let mut ply = header(3_000_000_000);
    ply.extend([0u8; 36 + 13]);
    std::fs::write(d.join("huge.ply"), &ply).unwrap();
    let needles = [
        "huge.ply",
        "scene.shapes[0].mPath",
        "3000000000 'face' elements",
        "truncated or corrupt",
    ];
    scene_fails(d, &mesh_scene("huge.ply"), &[], &needles);

    // A PLY whose face count fits the file but not the triangle limit.
    let mut ply = header(2000);
    ply.extend([0u8; 36]);
    // Each face: three corners, vertices 0, 1 and 2.
    let face: Vec<u8> = std::iter::once(3u8)
        .chain((0i32..3).flat_map(i32::to_le_bytes))
        .collect();
    for _ in 0..2000 {
        ply.extend(&face);
    }
    std::fs::write(d.join("many.ply"), &ply).unwrap();
    let needles = [
        "many.ply",
        "declares 2000 faces",
        "limit of 1000 triangles",
        "--max-triangles",
    ];
    scene_fails(
        d,
        &mesh_scene("many.ply"),
        &["--max-triangles", "1000"],
        &needles,
    );

    // A mesh over the file size limit.
    let needles = [
        "many.ply",
        "over the limit of 1000 bytes",
        "--max-mesh-bytes",
    ];
    scene_fails(
        d,
        &mesh_scene("many.ply"),
        &["--max-mesh-bytes", "1000"],
        &needles,
    );

    // A mesh that would need more memory than the render may have, from its header's counts
    // (PLY) or its faces' corners (OBJ), before it is read.
    let needles = [
        "many.ply",
        "3 vertices and 2000 triangles",
        "can be had",
        "--max-memory",
    ];
    scene_fails(
        d,
        &mesh_scene("many.ply"),
        &["--max-memory", "100000"],
        &needles,
    );
    let obj = format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nf{}\n", " 1 2 3".repeat(700));
    std::fs::write(d.join("fan.obj"), obj).unwrap();
    let needles = ["fan.obj", "3 vertices and 2098 triangles", "--max-memory"];
    scene_fails(
        d,
        &mesh_scene("fan.obj"),
        &["--max-memory", "100000"],
        &needles,
    );
}

/// A one-line OBJ polygon of 24 million corners (under the triangle limit) in a process that may
/// map 4 GB (`ulimit -v`): its memory is estimated from the corners and refused with a message,
/// where it once ended the process on a failed allocation.
#[cfg(target_os = "linux")]
#[test]
fn a_mesh_too_large_for_the_address_space_is_refused_before_it_is_built() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut obj = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf");
    obj.push_str(&" 1 2 3 4".repeat(6_000_000));
    obj.push('\n');
    std::fs::write(d.join("fan.obj"), obj).unwrap();
    std::fs::write(d.join("scene.json"), mesh_scene("fan.obj")).unwrap();
    let o = Command::new("bash")
        .arg("-c")
        .arg(r#"ulimit -v 4000000 && exec "$0" "$1" "$2""#)
        .arg(env!("CARGO_BIN_EXE_raytracer"))
        .arg(d.join("scene.json"))
        .arg(d.join("out.png"))
        .output()
        .unwrap();
    let msg = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{msg}");
    for needle in [
        "fan.obj",
        "23999998 triangles",
        "can be had",
        "--max-memory",
    ] {
        assert!(msg.contains(needle), "the message lacks '{needle}': {msg}");
    }
    assert!(!d.join("out.png").exists());
}

#[cfg(unix)]
#[test]
fn fifos_and_devices_as_assets_fail_cleanly_without_blocking() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let status = Command::new("mkfifo")
        .arg(d.join("pipe.ply"))
        .status()
        .unwrap();
    assert!(status.success());
    let needles = ["pipe.ply", "scene.shapes[0].mPath", "FIFO"];
    scene_fails(d, &mesh_scene("pipe.ply"), &[], &needles);

    std::os::unix::fs::symlink("/dev/zero", d.join("zero.png")).unwrap();
    let needles = [
        "zero.png",
        "scene.shapes[0].material.tPath",
        "character device",
    ];
    scene_fails(d, &texture_scene("zero.png"), &[], &needles);
    let o = Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .arg("compare")
        .arg(d.join("zero.png"))
        .arg(d.join("zero.png"))
        .output()
        .unwrap();
    let msg = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{msg}");
    assert!(
        msg.contains("zero.png") && msg.contains("character device"),
        "{msg}"
    );

    // A texture named without an image extension is not read at all: a warning, and the render
    // goes ahead without it.
    let scene = d.join("plain.json");
    std::fs::write(&scene, texture_scene("/dev/zero")).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .arg(&scene)
        .arg(d.join("plain.png"))
        .output()
        .unwrap();
    let msg = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{msg}");
    assert!(msg.contains("not an image file"), "{msg}");
}
