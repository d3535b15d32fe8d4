//! PLY reader: arbitrary bytes as a `.ply` file, through `read_ply` and `read_mesh`.
#![no_main]

mod common;

use libfuzzer_sys::fuzz_target;
use raytracer::scene::mesh_file::{read_mesh, read_ply};

fuzz_target!(|data: &[u8]| {
    let path = common::write_input("input.ply", data);
    let direct = read_ply(&path);
    // `read_mesh` dispatches on the extension; it must agree with the direct call.
    let dispatched = read_mesh(&path);
    match (&direct, &dispatched) {
        (Ok(a), Ok(b)) => assert_eq!(a, b),
        (Err(a), Err(b)) => {
            // Both name the file first.
            let name = path.display().to_string();
            assert!(a.to_string().starts_with(&name), "{a}");
            assert!(b.to_string().starts_with(&name), "{b}");
        }
        _ => panic!("read_ply and read_mesh disagree"),
    }
    if let Ok(mesh) = direct {
        check(&mesh);
    }
});

/// What a successful read promises: indices in range, finite data, matching buffer lengths.
fn check(mesh: &raytracer::scene::mesh_file::MeshData) {
    assert!(!mesh.faces.is_empty());
    let n = mesh.positions.len();
    assert!(mesh.faces.iter().flatten().all(|&i| (i as usize) < n));
    assert!(mesh.positions.iter().all(|p| p.is_finite()));
    if let Some(normals) = &mesh.normals {
        assert_eq!(normals.len(), n);
        assert!(normals.iter().all(|v| v.is_finite()));
    }
    if let Some(uvs) = &mesh.uvs {
        assert_eq!(uvs.len(), n);
        assert!(uvs.iter().all(|v| v.is_finite()));
    }
}
