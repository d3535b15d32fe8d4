//! Putting tiles back together: crops and sample ranges, in any order and any mix, added into
//! the whole image. The result's pixels are bit for bit those of the render done whole, because
//! the tiles hold exact sums ([`crate::film::sum`]) and the mean is taken once, at the end.
//!
//! Before anything is added the tiles are checked against each other: the same fingerprint,
//! image size and samples per pixel; no two tiles hold the same sample of the same pixel; and,
//! once added, every pixel has all its samples. Each failure names the tiles or the pixel.

use std::path::{Path, PathBuf};

use crate::files::shown;
use crate::film::{Film, PixelRect, PixelSum};

use super::Part;

/// A tile and the file it came from.
#[derive(Debug, Clone)]
pub struct Tile {
    pub path: PathBuf,
    pub part: Part,
}

/// Why tiles do not make one image.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    #[error("no tiles to merge")]
    NoTiles,
    #[error(
        "{} and {} are parts of different renders (the scene, its assets or the render options differ)",
        shown(a),
        shown(b)
    )]
    Mismatch { a: PathBuf, b: PathBuf },
    #[error(
        "{} is a part of a {}×{} image at {} spp, {} of a {}×{} image at {} spp",
        shown(a), a_size.0, a_size.1, a_spp, shown(b), b_size.0, b_size.1, b_spp
    )]
    Size {
        a: PathBuf,
        a_size: (u32, u32),
        a_spp: u32,
        b: PathBuf,
        b_size: (u32, u32),
        b_spp: u32,
    },
    #[error(
        "{} and {} overlap: both hold samples {}..{} of the pixels {}",
        shown(a), shown(b), samples.0, samples.1, pixels
    )]
    Overlap {
        a: PathBuf,
        b: PathBuf,
        pixels: PixelRect,
        samples: (u32, u32),
    },
    #[error("a gap: no tile holds samples {}..{} of pixel ({x}, {y})", missing.0, missing.1)]
    Gap { x: u32, y: u32, missing: (u32, u32) },
    #[error("an image of {width}×{height} is too large to merge in memory")]
    TooLarge { width: u32, height: u32 },
}

/// The whole image from `tiles`: the mean of every pixel's samples.
pub fn assemble(tiles: &[Tile]) -> Result<Film, MergeError> {
    let first = tiles.first().ok_or(MergeError::NoTiles)?;
    let (full, spp) = (first.part.full, first.part.spp);
    for t in &tiles[1..] {
        let (a, b) = (&first.part, &t.part);
        if (a.full, a.spp) != (b.full, b.spp) {
            return Err(MergeError::Size {
                a: first.path.clone(),
                a_size: a.full,
                a_spp: a.spp,
                b: t.path.clone(),
                b_size: b.full,
                b_spp: b.spp,
            });
        }
        if a.fingerprint != b.fingerprint || a.exposure != b.exposure || a.adaptive != b.adaptive {
            return Err(MergeError::Mismatch {
                a: first.path.clone(),
                b: t.path.clone(),
            });
        }
    }
    check_overlaps(tiles)?;

    let (width, height) = full;
    let too_large = || MergeError::TooLarge { width, height };
    let n = width as usize * height as usize;
    let mut sums: Vec<PixelSum> = Vec::new();
    sums.try_reserve_exact(n).map_err(|_| too_large())?;
    sums.resize(n, PixelSum::default());
    let mut counts: Vec<u32> = Vec::new();
    counts.try_reserve_exact(n).map_err(|_| too_large())?;
    counts.resize(n, 0);
    // The samples the tiles cover, whether an adaptive pixel took them all or not.
    let mut covered: Vec<u32> = Vec::new();
    covered.try_reserve_exact(n).map_err(|_| too_large())?;
    covered.resize(n, 0);
    for t in tiles {
        let p = &t.part;
        let w = p.window.width() as usize;
        let range = p.samples.end - p.samples.start;
        for (row, y) in (p.window.y0..p.window.y1).enumerate() {
            let at = y as usize * width as usize + p.window.x0 as usize;
            let from = row * w;
            for i in 0..w {
                sums[at + i].merge(&p.sums[from + i]);
                counts[at + i] += p.counts[from + i];
                covered[at + i] += range;
            }
        }
    }
    // Tiles never overlap, so a pixel with all `spp` samples has each exactly once.
    if let Some(i) = covered.iter().position(|&k| k != spp) {
        let (x, y) = ((i % width as usize) as u32, (i / width as usize) as u32);
        return Err(MergeError::Gap {
            x,
            y,
            missing: first_missing(tiles, x, y, spp),
        });
    }
    let pixels = sums.iter().zip(&counts).map(|(s, &k)| s.mean(k)).collect();
    Ok(Film::from_pixels(width, height, pixels))
}

/// The first error of two tiles that hold the same samples of the same pixels.
fn check_overlaps(tiles: &[Tile]) -> Result<(), MergeError> {
    for (i, a) in tiles.iter().enumerate() {
        for b in &tiles[i + 1..] {
            let (pa, pb) = (&a.part, &b.part);
            let Some(pixels) = pa.window.intersection(&pb.window) else {
                continue;
            };
            let start = pa.samples.start.max(pb.samples.start);
            let end = pa.samples.end.min(pb.samples.end);
            if start < end {
                return Err(MergeError::Overlap {
                    a: a.path.clone(),
                    b: b.path.clone(),
                    pixels,
                    samples: (start, end),
                });
            }
        }
    }
    Ok(())
}

/// The first run of samples of pixel `(x, y)` that no tile holds.
fn first_missing(tiles: &[Tile], x: u32, y: u32, spp: u32) -> (u32, u32) {
    let pixel = PixelRect {
        x0: x,
        y0: y,
        x1: x + 1,
        y1: y + 1,
    };
    let mut held: Vec<(u32, u32)> = tiles
        .iter()
        .filter(|t| pixel.within(&t.part.window))
        .map(|t| (t.part.samples.start, t.part.samples.end))
        .collect();
    held.sort_unstable();
    let mut next = 0;
    for (a, b) in held {
        if a > next {
            return (next, a);
        }
        next = next.max(b);
    }
    (next, spp)
}

/// Reads every tile (see [`super::exr::read`]).
pub fn read_tiles(paths: &[impl AsRef<Path>], max_pixels: u64) -> Result<Vec<Tile>, String> {
    paths
        .iter()
        .map(|p| {
            let path = p.as_ref();
            super::exr::read(path, max_pixels)
                .map(|part| Tile {
                    path: path.to_path_buf(),
                    part,
                })
                .map_err(|e| e.to_string())
        })
        .collect()
}
