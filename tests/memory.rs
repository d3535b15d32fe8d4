//! The heap a render and its image take, counted by this test binary's allocator: a render holds
//! one buffer the size of its film (tiles are traced into the film in place), and an EXR is
//! compressed from the film's pixels without copying them into channels first. Counted in
//! bytes, never timed.

use std::alloc::{GlobalAlloc, Layout, System};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use raytracer::film::ToneMap;
use raytracer::image_io::encode_image;
use raytracer::render::{render, RenderOptions};
use raytracer::scene::{load_str, LoadOptions};

/// The system allocator, keeping the bytes allocated now and the most allocated at once.
struct Counting;

static NOW: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

fn grew(by: usize) {
    let now = NOW.fetch_add(by, Ordering::Relaxed) + by;
    PEAK.fetch_max(now, Ordering::Relaxed);
}

// SAFETY: every call is passed to `System` unchanged; the counters only observe it.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            grew(layout.size());
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            grew(layout.size());
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        NOW.fetch_sub(layout.size(), Ordering::Relaxed);
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            if new_size >= layout.size() {
                grew(new_size - layout.size());
            } else {
                NOW.fetch_sub(layout.size() - new_size, Ordering::Relaxed);
            }
        }
        p
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The tests measure the whole process's heap, so they take turns.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

/// The most bytes `f` had allocated at once beyond what was allocated when it started.
fn peak_during<R>(f: impl FnOnce() -> R) -> (R, usize) {
    let start = NOW.load(Ordering::Relaxed);
    PEAK.store(start, Ordering::Relaxed);
    let r = f();
    (r, PEAK.load(Ordering::Relaxed) - start)
}

const WIDTH: u32 = 1024;
const HEIGHT: u32 = 768;
/// One `Vec3` of radiance a pixel.
const FILM_BYTES: usize = WIDTH as usize * HEIGHT as usize * 12;

fn film() -> raytracer::film::Film {
    let text = format!(
        r#"{{"nbounces": 2,
              "camera": {{"width": {WIDTH}, "height": {HEIGHT}, "fov": 45}},
              "scene": {{"lightsources": [{{"type": "pointlight", "position": [2, 3, 0], "intensity": [1, 1, 1]}}],
                         "shapes": [{{"type": "sphere", "center": [0, 0, -3], "radius": 1,
                                      "material": {{"kd": 0.7, "ks": 0.2, "specularexponent": 20,
                                                   "diffusecolor": [0.8, 0.3, 0.2]}}}}]}}}}"#
    );
    let scene = load_str(&text, Path::new("memory.json"), &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let options = RenderOptions {
        spp: 2,
        ..RenderOptions::default()
    };
    let (out, peak) = peak_during(|| render(&scene, &options).unwrap_or_else(|e| panic!("{e}")));
    // The film, and the tracers' and the thread pool's few kilobytes; a second buffer the
    // film's size (tiles traced apart, then copied in) would double it. (The lower bound is
    // loose: threads of an earlier test may still be freeing memory while this one counts.)
    assert!(
        peak > FILM_BYTES / 2 && peak < FILM_BYTES + FILM_BYTES / 4,
        "a {WIDTH}×{HEIGHT} render peaked at {peak} bytes beyond its start, its film is {FILM_BYTES}"
    );
    out.film
}

#[test]
fn a_render_holds_one_film() {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let film = film();
    assert_eq!(film.pixels.len() * 12, FILM_BYTES);
}

#[test]
fn an_exr_is_written_from_the_film_without_copies() {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let film = film();
    let (bytes, peak) = peak_during(|| {
        encode_image(Path::new("out.exr"), &film, ToneMap::Linear, 1.0)
            .unwrap_or_else(|e| panic!("{e}"))
    });
    // The file, growing by doubling, and the blocks being compressed (16 rows each, two more
    // than the machine's cores at a time: 3.6 MB on 16 cores); copies of the three channels
    // would add the film's size.
    assert!(
        peak < 2 * bytes.len() + FILM_BYTES / 2,
        "encoding a {}-byte EXR of a {FILM_BYTES}-byte film peaked at {peak} bytes",
        bytes.len()
    );
}
