//! How much memory a render may plan for, and what a mesh of a given size takes, so that a mesh
//! too large for the machine is refused with a message before anything is allocated for it,
//! rather than ending the process when an allocation fails.

/// Bytes a triangle of a mesh file takes at the peak of loading and tracing it: the reader's
/// index buffer, the mesh's own, the tree with its leaf blocks and the build's scratch. An upper
/// estimate: the measured growth of peak mapped memory per triangle, rounded up.
pub const BYTES_PER_TRIANGLE: u64 = 200;

/// Bytes a vertex of a mesh file takes at that peak: the reader's and the mesh's positions, and
/// room for a normal and texture coordinates in both.
pub const BYTES_PER_VERTEX: u64 = 64;

/// The memory a mesh of `vertices` and `triangles` needs to be loaded and traced.
pub fn mesh_bytes(vertices: u64, triangles: u64) -> u64 {
    vertices
        .saturating_mul(BYTES_PER_VERTEX)
        .saturating_add(triangles.saturating_mul(BYTES_PER_TRIANGLE))
}

/// The memory this process can still have, where the system says: the smaller of what the
/// system has available (free and reclaimable memory, and free swap) and what the process's
/// address-space limit (`ulimit -v`) leaves beyond what it already maps. `None` where neither
/// can be read.
pub fn available() -> Option<u64> {
    let system = system_available();
    let address_space = address_space_left();
    match (system, address_space) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// `MemAvailable` plus `SwapFree` from `/proc/meminfo`.
fn system_available() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    Some(kib_field(&text, "MemAvailable:")? + kib_field(&text, "SwapFree:").unwrap_or(0))
}

/// The bytes of a `NAME:  N kB` line of a `/proc` file's `text`.
fn kib_field(text: &str, name: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(name))?;
    let kib: u64 = line[name.len()..]
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .ok()?;
    Some(kib * 1024)
}

/// The soft `RLIMIT_AS` less the process's mapped size (`VmSize`), when there is a limit.
#[cfg(unix)]
// `rlim_t` is not `u64` on every Unix.
#[allow(clippy::unnecessary_cast)]
fn address_space_left() -> Option<u64> {
    let mut limit = libc::rlimit {
        rlim_cur: 0,
        rlim_max: 0,
    };
    // SAFETY: getrlimit writes one rlimit into the struct it is given, which lives on our stack.
    if unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut limit) } != 0
        || limit.rlim_cur == libc::RLIM_INFINITY
    {
        return None;
    }
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let mapped = kib_field(&status, "VmSize:")?;
    Some((limit.rlim_cur as u64).saturating_sub(mapped))
}

#[cfg(not(unix))]
fn address_space_left() -> Option<u64> {
    None
}

/// `bytes` in the largest binary unit that keeps a number of at least 1, with one decimal.
pub fn shown(bytes: u64) -> String {
    const UNITS: [&str; 5] = ["bytes", "KiB", "MiB", "GiB", "TiB"];
    let mut value = bytes as f64;
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < UNITS.len() {
        value /= 1024.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{bytes} bytes")
    } else {
        format!("{value:.1} {}", UNITS[unit])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mesh_takes_its_vertices_and_triangles() {
        assert_eq!(mesh_bytes(0, 0), 0);
        assert_eq!(mesh_bytes(3, 1), 3 * BYTES_PER_VERTEX + BYTES_PER_TRIANGLE);
        assert_eq!(mesh_bytes(u64::MAX, u64::MAX), u64::MAX);
    }

    #[test]
    fn sizes_are_shown_in_binary_units() {
        assert_eq!(shown(512), "512 bytes");
        assert_eq!(shown(1536), "1.5 KiB");
        assert_eq!(shown(3 << 30), "3.0 GiB");
    }

    #[test]
    fn proc_fields_are_read_in_bytes() {
        let text = "MemTotal:       24683800 kB\nMemAvailable:    1024 kB\nSwapFree: 0 kB\n";
        assert_eq!(kib_field(text, "MemAvailable:"), Some(1024 * 1024));
        assert_eq!(kib_field(text, "SwapFree:"), Some(0));
        assert_eq!(kib_field(text, "VmSize:"), None);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn linux_says_how_much_can_be_had() {
        let bytes = available().expect("/proc/meminfo is readable on Linux");
        assert!(bytes > 0);
    }
}
