//! Arithmetic of four f64 lanes as a trait ([`Lane4`]), for code written once and
//! compiled two ways: over the portable [`F4`] ([`crate::rod::lanes`], loops that the
//! compiler may or may not turn into vector instructions), and over [`Avx4`], a 256-bit
//! AVX register whose every operation is one instruction, for code compiled for AVX2
//! (chosen at run time). Large kernels need the latter: over `F4` the compiler splits
//! long chains of lane operations into scalar instructions (the
//! tangent kernel, [`crate::rod::tangent_kernel`], would run several scalar instructions
//! per operation).
//!
//! Only `+ − × ÷ √`, the fused multiply–add and lane selection, each correctly rounded,
//! so both give the same bits; and moving four consecutive 3-vectors or quaternions
//! between memory and lanes (one lane per vector).

use crate::rod::lanes::{F4, M4};
use glam::{DQuat, DVec3};
use std::ops::{Add, Div, Mul, Neg, Sub};

// The loads and stores read glam's vectors as consecutive f64 (`#[repr(C)]` x, y, z (, w)).
const _: () = assert!(std::mem::size_of::<[DVec3; 4]>() == 12 * 8);
const _: () = assert!(std::mem::size_of::<[DQuat; 4]>() == 16 * 8);

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
    /// self · a + b, correctly rounded (one rounding).
    fn mul_add(self, a: Self, b: Self) -> Self;
    /// The x, y and z of four vectors, vector k in lane k.
    fn load_vectors(a: &[DVec3; 4]) -> [Self; 3];
    /// Lane k of x, y and z to vector k.
    fn store_vectors(v: [Self; 3], a: &mut [DVec3; 4]);
    /// The x, y, z and w of four quaternions, quaternion k in lane k.
    fn load_quats(a: &[DQuat; 4]) -> [Self; 4];
    /// Lane k of x, y, z and w to quaternion k.
    fn store_quats(q: [Self; 4], a: &mut [DQuat; 4]);
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
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        F4::mul_add(self, a, b)
    }
    #[inline(always)]
    fn load_vectors(a: &[DVec3; 4]) -> [Self; 3] {
        [F4(a.map(|p| p.x)), F4(a.map(|p| p.y)), F4(a.map(|p| p.z))]
    }
    #[inline(always)]
    fn store_vectors(v: [Self; 3], a: &mut [DVec3; 4]) {
        for (k, p) in a.iter_mut().enumerate() {
            *p = DVec3::new(v[0].0[k], v[1].0[k], v[2].0[k]);
        }
    }
    #[inline(always)]
    fn load_quats(a: &[DQuat; 4]) -> [Self; 4] {
        [
            F4(a.map(|p| p.x)),
            F4(a.map(|p| p.y)),
            F4(a.map(|p| p.z)),
            F4(a.map(|p| p.w)),
        ]
    }
    #[inline(always)]
    fn store_quats(q: [Self; 4], a: &mut [DQuat; 4]) {
        for (k, p) in a.iter_mut().enumerate() {
            *p = DQuat::from_xyzw(q[0].0[k], q[1].0[k], q[2].0[k], q[3].0[k]);
        }
    }
}

#[cfg(target_arch = "x86_64")]
pub use avx::Avx4;

#[cfg(target_arch = "x86_64")]
mod avx {
    use super::{Lane4, F4, M4};
    use glam::{DQuat, DVec3};
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
        #[inline(always)]
        fn mul_add(self, a: Self, b: Self) -> Self {
            // SAFETY: as above (AVX2 code runs only where the CPU has FMA too).
            Avx4(unsafe { _mm256_fmadd_pd(self.0, a.0, b.0) })
        }
        #[inline(always)]
        fn load_vectors(a: &[DVec3; 4]) -> [Self; 3] {
            // SAFETY: as above; `a` is 12 consecutive f64 (checked at the top).
            unsafe {
                let p = a.as_ptr() as *const f64;
                // x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3
                let (a0, a1, a2) = (
                    _mm256_loadu_pd(p),
                    _mm256_loadu_pd(p.add(4)),
                    _mm256_loadu_pd(p.add(8)),
                );
                let xy02 = _mm256_blend_pd(a0, a1, 0b1100); // x0 y0 x2 y2
                let yz13 = _mm256_blend_pd(a1, a2, 0b1100); // y1 z1 y3 z3
                let zx = _mm256_blend_pd(a2, a0, 0b1100); // z2 x3 z0 x1
                let zx = _mm256_permute2f128_pd(zx, zx, 1); // z0 x1 z2 x3
                [
                    Avx4(_mm256_shuffle_pd(xy02, zx, 0b1010)),
                    Avx4(_mm256_shuffle_pd(xy02, yz13, 0b0101)),
                    Avx4(_mm256_shuffle_pd(zx, yz13, 0b1010)),
                ]
            }
        }
        #[inline(always)]
        fn store_vectors(v: [Self; 3], a: &mut [DVec3; 4]) {
            // SAFETY: as above; `a` is 12 consecutive f64 (checked at the top).
            unsafe {
                let [x, y, z] = v.map(|l| l.0);
                let xy02 = _mm256_shuffle_pd(x, y, 0b0000); // x0 y0 x2 y2
                let yz13 = _mm256_shuffle_pd(y, z, 0b1111); // y1 z1 y3 z3
                let zx = _mm256_shuffle_pd(z, x, 0b1010); // z0 x1 z2 x3
                let zx = _mm256_permute2f128_pd(zx, zx, 1); // z2 x3 z0 x1
                let p = a.as_mut_ptr() as *mut f64;
                _mm256_storeu_pd(p, _mm256_blend_pd(xy02, zx, 0b1100));
                _mm256_storeu_pd(p.add(4), _mm256_blend_pd(yz13, xy02, 0b1100));
                _mm256_storeu_pd(p.add(8), _mm256_blend_pd(zx, yz13, 0b1100));
            }
        }
        #[inline(always)]
        fn load_quats(a: &[DQuat; 4]) -> [Self; 4] {
            // SAFETY: as above; `a` is 16 consecutive f64 (checked at the top).
            unsafe {
                let p = a.as_ptr() as *const f64;
                let q = [0, 4, 8, 12].map(|k| _mm256_loadu_pd(p.add(k)));
                transpose(q).map(Avx4)
            }
        }
        #[inline(always)]
        fn store_quats(q: [Self; 4], a: &mut [DQuat; 4]) {
            // SAFETY: as above; `a` is 16 consecutive f64 (checked at the top).
            unsafe {
                let p = a.as_mut_ptr() as *mut f64;
                let t = transpose(q.map(|l| l.0));
                for (k, r) in t.into_iter().enumerate() {
                    _mm256_storeu_pd(p.add(4 * k), r);
                }
            }
        }
    }

    /// The 4 × 4 transpose of four rows.
    #[inline(always)]
    unsafe fn transpose(r: [__m256d; 4]) -> [__m256d; 4] {
        let t0 = _mm256_unpacklo_pd(r[0], r[1]); // a0 b0 a2 b2
        let t1 = _mm256_unpackhi_pd(r[0], r[1]); // a1 b1 a3 b3
        let t2 = _mm256_unpacklo_pd(r[2], r[3]); // c0 d0 c2 d2
        let t3 = _mm256_unpackhi_pd(r[2], r[3]); // c1 d1 c3 d3
        [
            _mm256_permute2f128_pd(t0, t2, 0x20),
            _mm256_permute2f128_pd(t1, t3, 0x20),
            _mm256_permute2f128_pd(t0, t2, 0x31),
            _mm256_permute2f128_pd(t1, t3, 0x31),
        ]
    }
}
