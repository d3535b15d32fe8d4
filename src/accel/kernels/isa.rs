//! Which instructions the ray queries of a wide tree run with, chosen when the tree is built.
//!
//! The release build targets the x86-64 baseline, so that the binary runs on every 64-bit x86
//! CPU: its SIMD is SSE2. Where the CPU has AVX2 ([`Isa::detect`]), the closest-hit and any-hit
//! loops of an eight-wide tree ([`crate::accel::Bvh8`]) run in a copy compiled for it
//! (`accel/wide.rs`), which tests a node's eight boxes in one AVX register instead of two SSE
//! ones ([`super::boxes8`]). The four-wide tree keeps the baseline, as its loops gain nothing from
//! the AVX2 copy (`docs/performance.md`), though [`crate::accel::Accel::with_isa`] can ask for it.
//!
//! Either way a query does the same IEEE `f32` operations on the same values in the same order
//! (Rust never fuses a multiply and an add, and the AVX forms of `min`, `max` and the compares
//! treat NaN as the SSE forms do), so it returns the same bits: the images are the same bytes on
//! every CPU. `tests/accel.rs` checks the queries of both against the plain list,
//! `tests/render.rs` renders every bundled scene with both, and the box kernel is checked against
//! the SSE pair lane for lane (`accel/wide.rs`).

/// The instruction set of a tree's queries. A value that says AVX2 exists only where the CPU
/// has it ([`Isa::detect`]), which is what makes running the AVX2 loops sound.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Isa(Level);

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Level {
    Baseline,
    Avx2,
}

impl Isa {
    /// What every CPU of the target has (SSE2 on x86-64).
    pub const BASELINE: Isa = Isa(Level::Baseline);

    /// AVX2 if this CPU has it, else the baseline.
    pub fn detect() -> Isa {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            return Isa(Level::Avx2);
        }
        Isa::BASELINE
    }

    /// Whether the queries may use AVX2 (and so AVX).
    #[inline(always)]
    pub fn avx2(self) -> bool {
        self.0 == Level::Avx2
    }

    /// `baseline` or `avx2`, as the `simd` column of `raytracer bench --rays` prints it.
    pub fn name(self) -> &'static str {
        match self.0 {
            Level::Baseline => "baseline",
            Level::Avx2 => "avx2",
        }
    }
}

/// Calls `query` with the AVX2 value, from code compiled for AVX2: `query` is inlined into it, so
/// that its loops take the AVX2 encodings and may call AVX kernels.
///
/// Each query passes a closure of its own, called here only. A helper that took one closure and
/// called it either here or on the baseline path leaves it out of line, compiled for the
/// baseline, and this wrapper shrinks to a jump to it: the AVX2 copy is lost.
///
/// # Safety
/// Only where the CPU has AVX2, as an [`Isa::detect`] value that says AVX2 shows.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub(in crate::accel) unsafe fn in_avx2<R>(query: impl FnOnce(Isa) -> R) -> R {
    query(Isa(Level::Avx2))
}

impl std::fmt::Display for Isa {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn detection_says_avx2_only_where_the_cpu_has_it() {
        #[cfg(target_arch = "x86_64")]
        assert_eq!(
            Isa::detect().avx2(),
            std::arch::is_x86_feature_detected!("avx2")
        );
        #[cfg(not(target_arch = "x86_64"))]
        assert_eq!(Isa::detect(), Isa::BASELINE);
        assert!(!Isa::BASELINE.avx2());
        assert_eq!(Isa::BASELINE.to_string(), "baseline");
    }
}
