//! Rectangles of pixels in an image: the part of the image a render traces (`--crop`) and the
//! place a tile holds in the whole.

use std::fmt;
use std::str::FromStr;

/// Columns `x0..x1` and rows `y0..y1` of an image (origin top left, ends excluded).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct PixelRect {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

impl PixelRect {
    /// The whole of a `width × height` image.
    pub fn full(width: u32, height: u32) -> PixelRect {
        PixelRect {
            x0: 0,
            y0: 0,
            x1: width,
            y1: height,
        }
    }

    /// Cell `(col, row)` of a `cols × rows` grid over a `width × height` image: columns
    /// `⌊col·width/cols⌋ .. ⌊(col+1)·width/cols⌋`, rows likewise, so the cells tile the image
    /// exactly and differ in size by at most one pixel. `None` when the cell is outside the grid
    /// or empty (more columns than pixels).
    pub fn grid_cell(
        (width, height): (u32, u32),
        (col, row): (u32, u32),
        (cols, rows): (u32, u32),
    ) -> Option<PixelRect> {
        if col >= cols || row >= rows {
            return None;
        }
        let cut = |i: u32, n: u32, len: u32| (u64::from(i) * u64::from(len) / u64::from(n)) as u32;
        let r = PixelRect {
            x0: cut(col, cols, width),
            y0: cut(row, rows, height),
            x1: cut(col + 1, cols, width),
            y1: cut(row + 1, rows, height),
        };
        (!r.is_empty()).then_some(r)
    }

    pub fn width(&self) -> u32 {
        self.x1.saturating_sub(self.x0)
    }

    pub fn height(&self) -> u32 {
        self.y1.saturating_sub(self.y0)
    }

    /// Pixels inside.
    pub fn area(&self) -> u64 {
        u64::from(self.width()) * u64::from(self.height())
    }

    pub fn is_empty(&self) -> bool {
        self.area() == 0
    }

    /// Whether every pixel of `self` lies in `outer`.
    pub fn within(&self, outer: &PixelRect) -> bool {
        self.x0 >= outer.x0 && self.y0 >= outer.y0 && self.x1 <= outer.x1 && self.y1 <= outer.y1
    }

    /// The pixels in both, if any.
    pub fn intersection(&self, other: &PixelRect) -> Option<PixelRect> {
        let r = PixelRect {
            x0: self.x0.max(other.x0),
            y0: self.y0.max(other.y0),
            x1: self.x1.min(other.x1),
            y1: self.y1.min(other.y1),
        };
        (r.x0 < r.x1 && r.y0 < r.y1).then_some(r)
    }
}

impl fmt::Display for PixelRect {
    /// `X0,Y0,X1,Y1`, as [`FromStr`] reads it.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{},{},{},{}", self.x0, self.y0, self.x1, self.y1)
    }
}

impl FromStr for PixelRect {
    type Err = String;

    /// `X0,Y0,X1,Y1` with X0 < X1 and Y0 < Y1.
    fn from_str(s: &str) -> Result<PixelRect, String> {
        let bad = || format!("'{s}' is not a rectangle X0,Y0,X1,Y1 of whole pixel numbers");
        let v: Vec<u32> = s
            .split(',')
            .map(|p| p.trim().parse::<u32>())
            .collect::<Result<_, _>>()
            .map_err(|_| bad())?;
        let [x0, y0, x1, y1] = v[..] else {
            return Err(bad());
        };
        if x0 >= x1 || y0 >= y1 {
            return Err(format!(
                "'{s}' is an empty rectangle: X0 < X1 and Y0 < Y1 are needed"
            ));
        }
        Ok(PixelRect { x0, y0, x1, y1 })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_prints_and_refuses_empty_or_malformed() {
        let r: PixelRect = "0, 16,32,48".parse().unwrap();
        assert_eq!(
            r,
            PixelRect {
                x0: 0,
                y0: 16,
                x1: 32,
                y1: 48
            }
        );
        assert_eq!(r.to_string().parse::<PixelRect>(), Ok(r));
        assert_eq!((r.width(), r.height(), r.area()), (32, 32, 1024));
        for bad in [
            "",
            "1,2,3",
            "1,2,3,4,5",
            "4,0,4,8",
            "0,8,4,2",
            "a,b,c,d",
            "-1,0,2,2",
        ] {
            assert!(bad.parse::<PixelRect>().is_err(), "{bad}");
        }
    }

    #[test]
    fn grid_cells_tile_the_image_exactly() {
        for (w, h, cols, rows) in [(37, 23, 3, 2), (16, 16, 4, 4), (5, 7, 5, 7), (100, 1, 7, 1)] {
            let mut covered = vec![0u32; (w * h) as usize];
            for row in 0..rows {
                for col in 0..cols {
                    let c = PixelRect::grid_cell((w, h), (col, row), (cols, rows)).unwrap();
                    assert!(c.width() >= w / cols && c.width() <= w / cols + 1);
                    for y in c.y0..c.y1 {
                        for x in c.x0..c.x1 {
                            covered[(y * w + x) as usize] += 1;
                        }
                    }
                }
            }
            assert!(covered.iter().all(|&k| k == 1), "{w}x{h} in {cols}x{rows}");
        }
        assert_eq!(PixelRect::grid_cell((4, 4), (4, 0), (4, 4)), None);
        assert_eq!(PixelRect::grid_cell((4, 4), (0, 0), (5, 1)), None);
    }

    #[test]
    fn within_and_intersection() {
        let full = PixelRect::full(10, 8);
        let a = PixelRect {
            x0: 2,
            y0: 2,
            x1: 6,
            y1: 5,
        };
        assert!(a.within(&full));
        assert!(!PixelRect { x1: 11, ..a }.within(&full));
        let b = PixelRect {
            x0: 5,
            y0: 4,
            x1: 9,
            y1: 8,
        };
        assert_eq!(
            a.intersection(&b),
            Some(PixelRect {
                x0: 5,
                y0: 4,
                x1: 6,
                y1: 5
            })
        );
        let c = PixelRect {
            x0: 6,
            y0: 0,
            x1: 9,
            y1: 2,
        };
        assert_eq!(a.intersection(&c), None);
    }
}
