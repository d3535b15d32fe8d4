//! Tests of the mesh readers: both formats, their errors and their limits.

use super::*;
use std::fs;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A unique scratch folder under the system temp dir, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let dir = std::env::temp_dir().join(format!(
            "raytracer_mesh_file_{}_{}_{}",
            std::process::id(),
            name,
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        fs::create_dir_all(&dir).expect("create temp dir");
        TempDir(dir)
    }

    fn write(&self, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
        let path = self.0.join(name);
        fs::write(&path, bytes).expect("write temp file");
        path
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

const CUBE_VERTICES: [[f32; 3]; 8] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [1.0, 1.0, 1.0],
    [0.0, 1.0, 1.0],
];
const CUBE_QUADS: [[u32; 4]; 6] = [
    [0, 3, 2, 1],
    [4, 5, 6, 7],
    [0, 1, 5, 4],
    [2, 3, 7, 6],
    [1, 2, 6, 5],
    [0, 4, 7, 3],
];

fn cube_header(format: &str) -> String {
    format!(
        "ply\nformat {format} 1.0\ncomment unit cube\nelement vertex 8\n\
         property float x\nproperty float y\nproperty float z\n\
         element face 6\nproperty list uchar int vertex_indices\nend_header\n"
    )
}

fn cube_ascii() -> String {
    let mut s = cube_header("ascii");
    for v in CUBE_VERTICES {
        s += &format!("{} {} {}\n", v[0], v[1], v[2]);
    }
    for q in CUBE_QUADS {
        s += &format!("4 {} {} {} {}\n", q[0], q[1], q[2], q[3]);
    }
    s
}

fn cube_binary(big_endian: bool) -> Vec<u8> {
    let format = if big_endian {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let mut out = cube_header(format).into_bytes();
    for v in CUBE_VERTICES {
        for c in v {
            out.extend(if big_endian {
                c.to_be_bytes()
            } else {
                c.to_le_bytes()
            });
        }
    }
    for q in CUBE_QUADS {
        out.push(4);
        for i in q {
            let i = i as i32;
            out.extend(if big_endian {
                i.to_be_bytes()
            } else {
                i.to_le_bytes()
            });
        }
    }
    out
}

fn expected_cube() -> MeshData {
    MeshData {
        positions: CUBE_VERTICES.iter().map(|v| Vec3::from_array(*v)).collect(),
        normals: None,
        uvs: None,
        faces: CUBE_QUADS
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect(),
    }
}

#[test]
fn ascii_ply_cube() {
    let dir = TempDir::new("ascii_cube");
    let mesh = read_mesh(&dir.write("cube.ply", cube_ascii())).unwrap();
    assert_eq!(mesh.positions.len(), 8);
    assert_eq!(mesh.faces.len(), 12);
    assert_eq!(mesh.faces[0], [0, 3, 2]);
    assert_eq!(mesh.faces[1], [0, 2, 1]);
    assert_eq!(mesh.faces[11], [0, 7, 3]);
    assert_eq!(mesh, expected_cube());
}

#[test]
fn binary_ply_cube_equals_ascii() {
    let dir = TempDir::new("binary_cube");
    let ascii = read_ply(&dir.write("a.ply", cube_ascii())).unwrap();
    let le = read_ply(&dir.write("le.ply", cube_binary(false))).unwrap();
    let be = read_mesh(&dir.write("be.PLY", cube_binary(true))).unwrap();
    assert_eq!(le, ascii);
    assert_eq!(be, ascii);
}

#[test]
fn ply_normals_and_uvs() {
    let dir = TempDir::new("normals_uvs");
    for (u, v) in [("u", "v"), ("s", "t"), ("texture_u", "texture_v")] {
        let text = format!(
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
             property float z\nproperty float nx\nproperty float ny\nproperty float nz\n\
             property float {u}\nproperty float {v}\nproperty uchar red\n\
             element face 1\nproperty list uchar uint vertex_indices\nend_header\n\
             0 0 0 0 0 1 0 0 255\n1 0 0 0 0 1 1 0 0\n0 1 0 0 0 1 0 1 7\n3 0 1 2\n"
        );
        let mesh = read_ply(&dir.write("nuv.ply", text)).unwrap();
        assert_eq!(mesh.faces, vec![[0, 1, 2]]);
        assert_eq!(mesh.normals, Some(vec![Vec3::Z; 3]));
        assert_eq!(
            mesh.uvs,
            Some(vec![Vec2::ZERO, Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0)])
        );
    }
    // Incomplete normals are not reported.
    let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                property float z\nproperty float nx\nproperty float u\n\
                element face 1\nproperty list uchar uint vertex_indices\nend_header\n\
                0 0 0 1 0\n1 0 0 1 0\n0 1 0 1 0\n3 0 1 2\n";
    let mesh = read_ply(&dir.write("partial.ply", text)).unwrap();
    assert_eq!(mesh.normals, None);
    assert_eq!(mesh.uvs, None);
}

#[test]
fn ply_various_types_and_vertex_index_name() {
    let dir = TempDir::new("types");
    let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\n\
        property double x\nproperty int y\nproperty uchar z\nelement edge 1\n\
        property list uchar float junk\nelement face 1\n\
        property list ushort short vertex_index\nproperty float area\nend_header\n"
        .to_vec();
    for (x, y, z) in [(0.5f64, 0i32, 0u8), (1.5, 2, 3), (-1.0, -4, 255)] {
        bytes.extend(x.to_le_bytes());
        bytes.extend(y.to_le_bytes());
        bytes.push(z);
    }
    bytes.push(2);
    bytes.extend(1.0f32.to_le_bytes());
    bytes.extend(2.0f32.to_le_bytes());
    bytes.extend(3u16.to_le_bytes());
    for i in [2i16, 1, 0] {
        bytes.extend(i.to_le_bytes());
    }
    bytes.extend(0.25f32.to_le_bytes());
    let mesh = read_ply(&dir.write("types.ply", bytes)).unwrap();
    assert_eq!(
        mesh.positions,
        vec![
            Vec3::new(0.5, 0.0, 0.0),
            Vec3::new(1.5, 2.0, 3.0),
            Vec3::new(-1.0, -4.0, 255.0)
        ]
    );
    assert_eq!(mesh.faces, vec![[2, 1, 0]]);
}

#[test]
fn ply_index_out_of_range() {
    let dir = TempDir::new("ply_range");
    let text = cube_ascii().replace("4 1 2 6 5\n", "4 1 2 9 5\n");
    let path = dir.write("bad.ply", text);
    let err = read_ply(&path).unwrap_err();
    let msg = err.to_string();
    assert!(
        matches!(
            err,
            MeshFileError::IndexOutOfRange {
                face: 4,
                index: 9,
                line: Some(23),
                ..
            }
        ),
        "{msg}"
    );
    assert!(msg.contains("face 4") && msg.contains("index 9"), "{msg}");
    assert!(msg.contains("bad.ply") && msg.contains("line 23"), "{msg}");

    let text = cube_ascii().replace("4 1 2 6 5\n", "4 1 -2 6 5\n");
    let err = read_ply(&dir.write("neg.ply", text)).unwrap_err();
    assert!(err.to_string().contains("index -2"), "{err}");

    let mut bytes = cube_binary(false);
    let last = bytes.len() - 4;
    bytes[last..].copy_from_slice(&100i32.to_le_bytes());
    let err = read_ply(&dir.write("bad_bin.ply", bytes)).unwrap_err();
    assert!(
        matches!(
            err,
            MeshFileError::IndexOutOfRange {
                face: 5,
                index: 100,
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn ply_small_face_and_non_finite() {
    let dir = TempDir::new("ply_small");
    let text = cube_ascii().replace("4 0 4 7 3\n", "2 0 4\n");
    let err = read_ply(&dir.write("small.ply", text)).unwrap_err();
    assert!(
        matches!(
            err,
            MeshFileError::FaceTooSmall {
                face: 5,
                count: 2,
                ..
            }
        ),
        "{err}"
    );
    assert!(err.to_string().contains("face 5"), "{err}");

    let text = cube_ascii().replacen("1 0 0\n", "1 1e39 0\n", 1);
    let err = read_ply(&dir.write("inf.ply", text)).unwrap_err();
    assert!(
        matches!(
            err,
            MeshFileError::NonFinite {
                vertex: 1,
                what: "position",
                line: Some(12),
                ..
            }
        ),
        "{err}"
    );
    assert!(err.to_string().contains("vertex 1"), "{err}");
    let mut bytes = cube_binary(false);
    let at = cube_header("binary_little_endian").len() + 12 * 3 + 4;
    bytes[at..at + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    let err = read_ply(&dir.write("nan.ply", bytes)).unwrap_err();
    assert!(
        matches!(
            err,
            MeshFileError::NonFinite {
                vertex: 3,
                line: None,
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn truncated_binary_ply_is_an_error() {
    let dir = TempDir::new("truncated");
    let full = cube_binary(false);
    let header_len = cube_header("binary_little_endian").len();
    for len in 0..full.len() {
        let path = dir.write("t.ply", &full[..len]);
        let result = read_ply(&path);
        assert!(result.is_err(), "length {len} should fail");
        if len > header_len {
            let msg = result.unwrap_err().to_string();
            assert!(msg.contains("t.ply"), "{msg}");
        }
    }
    // Removing a byte in the middle shifts everything: still an error, no panic.
    let mut shifted = full.clone();
    shifted.remove(header_len + 5);
    assert!(read_ply(&dir.write("s.ply", shifted)).is_err());
}

#[test]
fn lying_huge_counts_fail_fast() {
    // Each count is refused from the header, before anything is allocated for it (an
    // allocation of that size would abort the test process).
    let dir = TempDir::new("huge");
    for (format, count) in [
        ("binary_little_endian", "4000000000"),
        ("binary_big_endian", "18446744073709551615"),
        ("ascii", "4000000000"),
    ] {
        let mut bytes = format!(
            "ply\nformat {format} 1.0\nelement vertex {count}\nproperty float x\n\
             property float y\nproperty float z\nelement face 1\n\
             property list uchar int vertex_indices\nend_header\n"
        )
        .into_bytes();
        bytes.extend([0u8; 200]);
        let err = read_ply(&dir.write("huge.ply", bytes)).unwrap_err();
        assert!(matches!(err, MeshFileError::CountTooLarge { .. }), "{err}");
        assert!(err.to_string().contains("'vertex'"), "{err}");
    }
    // A huge face count, and a huge element without properties before them.
    let text = cube_ascii().replace("element face 6", "element face 3000000000");
    let err = read_ply(&dir.write("faces.ply", text)).unwrap_err();
    assert!(matches!(err, MeshFileError::CountTooLarge { .. }), "{err}");
    let mut bytes = cube_binary(false);
    let text = String::from_utf8_lossy(&bytes).into_owned();
    let at = text.find("element vertex").unwrap();
    bytes.splice(at..at, b"element nothing 4000000000000\n".iter().copied());
    let err = read_ply(&dir.write("empty_el.ply", bytes)).unwrap_err();
    assert!(matches!(err, MeshFileError::CountTooLarge { .. }), "{err}");
    // A huge list length inside the payload just runs out of data.
    let mut bytes = cube_header("binary_little_endian")
        .replace("list uchar int", "list uint int")
        .into_bytes();
    for v in CUBE_VERTICES {
        for c in v {
            bytes.extend(c.to_le_bytes());
        }
    }
    bytes.extend(u32::MAX.to_le_bytes());
    bytes.extend([0u8; 64]);
    let err = read_ply(&dir.write("list.ply", bytes)).unwrap_err();
    assert!(err.to_string().contains("face"), "{err}");
}

#[test]
fn ply_lying_small_counts_and_structure_errors() {
    let dir = TempDir::new("ply_structure");
    let cases = [
        cube_ascii().replace("element vertex 8", "element vertex 10"),
        cube_ascii().replace("element vertex 8", "element vertex 6"),
        cube_ascii().replace("element face 6", "element face 7"),
        cube_ascii().replace("property float z\n", ""),
        cube_ascii().replace("vertex_indices", "corners"),
        cube_ascii().replace("list uchar int", "list uchar float"),
        cube_ascii().replace("property float x", "property list uchar float x"),
        cube_ascii().replace("element vertex", "element point"),
        cube_ascii().replace("end_header\n", ""),
        cube_ascii().replace("ply\n", "plx\n"),
        cube_ascii().replace("4 0 3 2 1", "4 0 3 2"),
        cube_ascii().replace("4 0 3 2 1", "4 0 3 2 one"),
        "ply\nformat ascii 1.0\nend_header\n".to_owned(),
        "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n\
         property float z\nelement face 0\nproperty list uchar int vertex_indices\n\
         end_header\n"
            .to_owned(),
    ];
    for (i, text) in cases.iter().enumerate() {
        let result = read_ply(&dir.write("s.ply", text));
        let err = result.expect_err(&format!("case {i} should fail"));
        assert!(err.to_string().contains("s.ply"), "{err}");
    }
    let no_faces = cube_ascii().replace("element face 6", "element fac 6");
    let err = read_ply(&dir.write("nf.ply", no_faces)).unwrap_err();
    assert!(matches!(err, MeshFileError::NoTriangles { .. }), "{err}");
    assert!(err.to_string().contains("no triangles"), "{err}");
}

const OBJ_QUADS: &str = "# two quads\nmtllib missing.mtl\no quad\n\
    v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n\
    vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
    vn 0 0 1\n\
    usemtl red\n\
    f 1/1/1 2/2/1 3/3/1 4/4/1\n\
    g other\n\
    f 2/1/1 5/2/1 6/3/1 3/4/1\n";

#[test]
fn obj_quads_with_uvs_and_normals() {
    let dir = TempDir::new("obj_quads");
    let mesh = read_mesh(&dir.write("quads.OBJ", OBJ_QUADS)).unwrap();
    assert_eq!(mesh.faces.len(), 4);
    let uvs = mesh.uvs.as_ref().expect("uvs");
    let normals = mesh.normals.as_ref().expect("normals");
    assert_eq!(uvs.len(), mesh.positions.len());
    assert_eq!(normals.len(), mesh.positions.len());
    assert!(normals.iter().all(|n| *n == Vec3::Z));
    // Every triangle corner keeps its own position/uv pairing.
    let corners = |tri: [u32; 3]| tri.map(|k| (mesh.positions[k as usize], uvs[k as usize]));
    let first = corners(mesh.faces[0]);
    assert_eq!(first[0], (Vec3::ZERO, Vec2::ZERO));
    assert_eq!(first[1], (Vec3::X, Vec2::X));
    assert_eq!(first[2], (Vec3::new(1.0, 1.0, 0.0), Vec2::ONE));
    let second = corners(mesh.faces[1]);
    assert_eq!(second[0], (Vec3::ZERO, Vec2::ZERO));
    assert_eq!(second[2], (Vec3::Y, Vec2::Y));
    let third = corners(mesh.faces[2]);
    assert_eq!(third[0], (Vec3::X, Vec2::ZERO));
    for tri in &mesh.faces {
        assert!(tri.iter().all(|&k| (k as usize) < mesh.positions.len()));
    }
    // Negative (relative) indices work too; no vt/vn gives None.
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n";
    let mesh = read_obj(&dir.write("rel.obj", text)).unwrap();
    assert_eq!(mesh.positions.len(), 3);
    assert_eq!(mesh.faces.len(), 1);
    assert_eq!(mesh.uvs, None);
    assert_eq!(mesh.normals, None);
}

#[test]
fn obj_index_out_of_range() {
    let dir = TempDir::new("obj_range");
    let cases = [
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", 4, "vertex", 4),
        ("v 0 0 0\nv 1 0 0\nf 1 2 -3\nv 0 1 0\n", -3, "vertex", 3),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 0, "vertex", 4),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n",
            2,
            "texture coordinate",
            5,
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//-99999 3//1\n",
            -99999,
            "normal",
            5,
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//9223372036854775807 2 3\n",
            i64::MAX,
            "normal",
            4,
        ),
    ];
    for (text, index, kind, line) in cases {
        let err = read_obj(&dir.write("r.obj", text)).unwrap_err();
        match &err {
            MeshFileError::IndexOutOfRange {
                index: i,
                kind: k,
                line: l,
                face: 0,
                ..
            } => {
                assert_eq!((*i, *k, *l), (index, kind, Some(line)), "{err}");
            }
            other => panic!("unexpected error {other}"),
        }
        let msg = err.to_string();
        assert!(
            msg.contains("r.obj") && msg.contains(&format!("index {index}")),
            "{msg}"
        );
    }
}

#[test]
fn obj_other_errors() {
    let dir = TempDir::new("obj_errors");
    type Check = fn(&MeshFileError) -> bool;
    let cases: [(&str, Check); 7] = [
        ("v 0 0 0\nv 1 0 0\nf 1 2\n", |e| {
            matches!(
                e,
                MeshFileError::FaceTooSmall {
                    count: 2,
                    line: Some(3),
                    ..
                }
            )
        }),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\n", |e| {
            matches!(e, MeshFileError::NoTriangles { .. })
        }),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\np 3\n", |e| {
            matches!(e, MeshFileError::NoTriangles { .. })
        }),
        ("v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n", |e| {
            matches!(
                e,
                MeshFileError::NonFinite {
                    vertex: 1,
                    line: Some(2),
                    ..
                }
            )
        }),
        ("v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", |e| {
            matches!(e, MeshFileError::Malformed { line: Some(1), .. })
        }),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n", |e| {
            matches!(e, MeshFileError::Malformed { line: Some(4), .. })
        }),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0 1e-45\nf 1 2 3\n", |e| {
            matches!(e, MeshFileError::NonFinite { vertex: 2, .. })
        }),
    ];
    for (i, (text, check)) in cases.into_iter().enumerate() {
        let err = read_obj(&dir.write("e.obj", text)).unwrap_err();
        assert!(check(&err), "case {i}: {err}");
        assert!(err.to_string().contains("e.obj"), "{err}");
    }
    let err = read_obj(&dir.write("bin.obj", b"v 0 0 0\n\xff\xfe\n")).unwrap_err();
    assert!(err.to_string().contains("line 2"), "{err}");
}

#[test]
fn unsupported_extension_and_missing_file() {
    let dir = TempDir::new("ext");
    let path = dir.write("mesh.stl", "solid x\n");
    let msg = read_mesh(&path).unwrap_err().to_string();
    assert!(
        msg.contains("'.stl'") && msg.contains(".ply") && msg.contains(".obj"),
        "{msg}"
    );
    let path = dir.write("mesh", "ply\n");
    let err = read_mesh(&path).unwrap_err();
    assert!(matches!(
        err,
        MeshFileError::UnsupportedExtension {
            extension: None,
            ..
        }
    ));
    let err = read_mesh(&dir.0.join("absent.ply")).unwrap_err();
    assert!(matches!(err, MeshFileError::Io { .. }), "{err}");
    assert!(err.to_string().contains("absent.ply"), "{err}");
}

#[test]
fn empty_and_garbage_files() {
    let dir = TempDir::new("empty");
    for name in ["empty.ply", "empty.obj"] {
        let err = read_mesh(&dir.write(name, "")).unwrap_err();
        assert!(matches!(err, MeshFileError::Empty { .. }), "{err}");
        assert!(err.to_string().contains(name), "{err}");
    }
    let mut state = 0x1234_5678_9abc_def0u64;
    let garbage: Vec<u8> = (0..4096).map(|_| xorshift(&mut state) as u8).collect();
    assert!(read_mesh(&dir.write("g.ply", &garbage)).is_err());
    assert!(read_mesh(&dir.write("g.obj", &garbage)).is_err());
    assert!(read_mesh(&dir.write("ws.obj", "\n\n  \n")).is_err());
}

fn xorshift(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

/// Random corruption of valid files must give `Ok` or `Err`, never a panic.
#[test]
fn corrupted_inputs_never_panic() {
    let path = Path::new("fuzz.ply");
    let seeds: [Vec<u8>; 4] = [
        cube_ascii().into_bytes(),
        cube_binary(false),
        cube_binary(true),
        OBJ_QUADS.as_bytes().to_vec(),
    ];
    let interesting: &[&[u8]] = &[
        b"4294967295",
        b"-1",
        b"0",
        b"99999999999999999999",
        b"nan",
        b"list",
        b"/",
        b"-",
        b"\n",
        b" ",
        b"double",
        b"uint",
        b"\xff",
    ];
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    for (s, seed) in seeds.iter().enumerate() {
        for _ in 0..1500 {
            let mut data = seed.clone();
            for _ in 0..1 + xorshift(&mut state) % 4 {
                let at = (xorshift(&mut state) as usize) % (data.len() + 1);
                match xorshift(&mut state) % 5 {
                    0 if at < data.len() => data[at] = xorshift(&mut state) as u8,
                    1 => data.truncate(at),
                    2 if at < data.len() => {
                        data.remove(at);
                    }
                    _ => {
                        let pick = interesting[xorshift(&mut state) as usize % interesting.len()];
                        data.splice(at..at, pick.iter().copied());
                    }
                }
            }
            let result = if s == 3 {
                parse_obj(Path::new("fuzz.obj"), &data, &MeshLimits::default())
            } else {
                parse_ply(path, &data, &MeshLimits::default())
            };
            if let Ok(mesh) = result {
                assert!(!mesh.faces.is_empty());
                for tri in &mesh.faces {
                    assert!(tri.iter().all(|&k| (k as usize) < mesh.positions.len()));
                }
                assert!(mesh.positions.iter().all(|p| p.is_finite()));
            }
        }
    }
}

/// Every PLY/OBJ mesh in the coursework corpus either loads or fails cleanly.
#[test]
fn corpus_meshes_load_or_fail_cleanly() {
    let root = Path::new("/work/shared/coursework/corpus/assets");
    if !root.is_dir() {
        return;
    }
    let mut stack = vec![root.to_path_buf()];
    let mut files = Vec::new();
    while let Some(dir) = stack.pop() {
        let Ok(entries) = fs::read_dir(&dir) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if path
                .extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| e.eq_ignore_ascii_case("ply") || e.eq_ignore_ascii_case("obj"))
            {
                files.push(path);
            }
        }
    }
    files.sort();
    for path in &files {
        match read_mesh(path) {
            Ok(mesh) => {
                assert!(!mesh.faces.is_empty());
                let n = mesh.positions.len();
                assert!(mesh.faces.iter().flatten().all(|&k| (k as usize) < n));
                assert!(mesh.normals.as_ref().is_none_or(|v| v.len() == n));
                assert!(mesh.uvs.as_ref().is_none_or(|v| v.len() == n));
                println!(
                    "loaded {}: {} vertices, {} triangles, normals: {}, uvs: {}",
                    shown(path),
                    n,
                    mesh.faces.len(),
                    mesh.normals.is_some(),
                    mesh.uvs.is_some()
                );
            }
            Err(e) => println!("FAILED {e}"),
        }
    }
}

fn limits(max_triangles: usize, triangles_before: usize) -> MeshLimits {
    MeshLimits {
        max_triangles,
        triangles_before,
        ..MeshLimits::default()
    }
}

#[test]
fn obj_fan_over_the_triangle_limit_is_refused_from_the_text() {
    let dir = TempDir::new("obj_fan");
    // One polygon of 1002 corners: a fan of 1000 triangles.
    let mut text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf".to_owned();
    for _ in 0..334 {
        text.push_str(" 1 2 3");
    }
    text.push('\n');
    let path = dir.write("fan.obj", &text);
    assert_eq!(
        read_mesh_with(&path, &limits(1000, 0)).unwrap().faces.len(),
        1000
    );
    let err = read_mesh_with(&path, &limits(999, 0)).unwrap_err();
    assert!(
        matches!(err, MeshFileError::TooManyTriangles { line: Some(4), .. }),
        "{err:?}"
    );
    let msg = err.to_string();
    for part in [
        "fan.obj (line 4)",
        "1000 triangles",
        "limit of 999",
        "--max-triangles",
    ] {
        assert!(msg.contains(part), "{msg} lacks {part}");
    }
    // Triangles already in the scene count against the limit.
    let err = read_mesh_with(&path, &limits(1500, 600)).unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.contains("already has 600") && msg.contains("1500"),
        "{msg}"
    );
    assert!(read_mesh_with(&path, &limits(1500, 500)).is_ok());
}

#[test]
fn ply_faces_over_the_triangle_limit_are_refused() {
    let dir = TempDir::new("ply_limit");
    // Six quads: 12 triangles.
    let path = dir.write("cube.ply", cube_ascii());
    assert_eq!(
        read_mesh_with(&path, &limits(12, 0)).unwrap().faces.len(),
        12
    );
    // More faces than triangles left: refused from the header.
    let err = read_mesh_with(&path, &limits(5, 0)).unwrap_err();
    let msg = err.to_string();
    assert!(
        matches!(err, MeshFileError::TooManyTriangles { line: None, .. }),
        "{err:?}"
    );
    assert!(
        msg.contains("declares 6 faces") && msg.contains("--max-triangles"),
        "{msg}"
    );
    // Enough faces but too many triangles once the quads are split: refused while reading.
    let err = read_mesh_with(&path, &limits(11, 0)).unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.contains("face 5 make 12 triangles") && msg.contains("limit of 11"),
        "{msg}"
    );
    let path = dir.write("cube-bin.ply", cube_binary(true));
    assert!(read_mesh_with(&path, &limits(11, 0)).is_err());
    assert!(read_mesh_with(&path, &limits(12, 0)).is_ok());
}

#[test]
fn mesh_file_over_the_size_limit_is_refused() {
    let dir = TempDir::new("mesh_size");
    let path = dir.write("cube.ply", cube_ascii());
    let size = fs::metadata(&path).unwrap().len();
    let with_max = |max_bytes| MeshLimits {
        max_bytes,
        ..MeshLimits::default()
    };
    assert!(read_mesh_with(&path, &with_max(size)).is_ok());
    let err = read_mesh_with(&path, &with_max(size - 1)).unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.contains("cube.ply") && msg.contains("--max-mesh-bytes"),
        "{msg}"
    );
}

#[cfg(unix)]
#[test]
fn fifo_and_device_meshes_are_refused_without_blocking() {
    let dir = TempDir::new("mesh_fifo");
    let fifo = dir.0.join("pipe.obj");
    let status = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(status.success());
    let err = read_mesh(&fifo).unwrap_err();
    assert!(err.to_string().contains("FIFO"), "{err}");
    let zero = dir.0.join("zero.ply");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let err = read_mesh(&zero).unwrap_err();
    assert!(err.to_string().contains("character device"), "{err}");
}
