//! Arithmetic of four f64 lanes as a trait ([`Lane4`]), for code written once and
//! compiled two ways: over the portable [`F4`] ([`crate::rod::lanes`], loops that the
//! compiler may or may not turn into vector instructions), and over [`Avx4`], a 256-bit
//! AVX register whose every operation is one instruction, for code compiled for AVX2
//! (chosen at run time). Large kernels need the latter: over `F4` the compiler splits
//! long chains of lane operations into scalar instructions (the
//! tangent kernel, [`crate::rod::tangent_kernel`], would run several scalar instructions
//! per operation).
//!
//! Only `+ − × ÷ √` and lane selection, each correctly rounded, so both give the same
//! bits.

use crate::rod::lanes::{F4, M4};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Four f64 lanes.
pub trait Lane4:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    fn splat(v: f64) -> Self;
    fn from_f4(v: F4) -> Self;
    fn to_f4(self) -> F4;
    fn sqrt(self) -> Self;
    /// `a` in the lanes `mask` sets, `b` in the others.
    fn select(mask: M4, a: Self, b: Self) -> Self;
}

impl Lane4 for F4 {
    #[inline(always)]
    fn splat(v: f64) -> Self {
        F4::splat(v)
    }
    #[inline(always)]
    fn from_f4(v: F4) -> Self {
        v
    }
    #[inline(always)]
    fn to_f4(self) -> F4 {
        self
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        F4::sqrt(self)
    }
    #[inline(always)]
    fn select(mask: M4, a: Self, b: Self) -> Self {
        mask.select(a, b)
    }
}

#[cfg(target_arch = "x86_64")]
pub use avx::Avx4;

#[cfg(target_arch = "x86_64")]
mod avx {
    use super::{Lane4, F4, M4};
    use std::arch::x86_64::*;
    use std::ops::{Add, Div, Mul, Neg, Sub};

    /// Four f64 lanes in a 256-bit AVX register.
    ///
    /// Its operations are inline AVX instructions: use it only inside functions compiled
    /// with `#[target_feature(enable = "avx2")]` and called after checking that the CPU
    /// has AVX2 (as [`crate::rod::element_block::Kernel::detect`] does). Elsewhere its
    /// operations are calls to AVX code — invalid on CPUs without AVX.
    #[derive(Clone, Copy, Debug)]
    pub struct Avx4(__m256d);

    macro_rules! op {
        ($tr:ident, $f:ident, $intr:ident) => {
            impl $tr for Avx4 {
                type Output = Avx4;
                #[inline(always)]
                fn $f(self, o: Avx4) -> Avx4 {
                    // SAFETY: used only in code compiled for AVX2 on CPUs that have it
                    // (see the type's documentation).
                    Avx4(unsafe { $intr(self.0, o.0) })
                }
            }
        };
    }
    op!(Add, add, _mm256_add_pd);
    op!(Sub, sub, _mm256_sub_pd);
    op!(Mul, mul, _mm256_mul_pd);
    op!(Div, div, _mm256_div_pd);

    impl Neg for Avx4 {
        type Output = Avx4;
        #[inline(always)]
        fn neg(self) -> Avx4 {
            // SAFETY: as above.
            Avx4(unsafe { _mm256_xor_pd(self.0, _mm256_set1_pd(-0.0)) })
        }
    }

    impl Lane4 for Avx4 {
        #[inline(always)]
        fn splat(v: f64) -> Self {
            // SAFETY: as above.
            Avx4(unsafe { _mm256_set1_pd(v) })
        }
        #[inline(always)]
        fn from_f4(v: F4) -> Self {
            // SAFETY: as above; `v` is 4 f64s.
            Avx4(unsafe { _mm256_loadu_pd(v.0.as_ptr()) })
        }
        #[inline(always)]
        fn to_f4(self) -> F4 {
            let mut out = F4::ZERO;
            // SAFETY: as above; `out` holds 4 f64s.
            unsafe { _mm256_storeu_pd(out.0.as_mut_ptr(), self.0) };
            out
        }
        #[inline(always)]
        fn sqrt(self) -> Self {
            // SAFETY: as above.
            Avx4(unsafe { _mm256_sqrt_pd(self.0) })
        }
        #[inline(always)]
        fn select(mask: M4, a: Self, b: Self) -> Self {
            // SAFETY: as above; the mask is 4 u64s, all bits set or none.
            Avx4(unsafe {
                let m = _mm256_castsi256_pd(_mm256_loadu_si256(mask.0.as_ptr() as *const __m256i));
                _mm256_blendv_pd(b.0, a.0, m)
            })
        }
    }
}
