//! LU factorisation with partial pivoting of one 6 × 6 block, P A = L U (Golub & Van
//! Loan, "Matrix Computations", 4th ed., 2013, Alg. 3.4.1, "outer product" Gaussian
//! elimination with partial pivoting), and solves with it for one right-hand side
//! (Alg. 3.1.1/3.1.2, forward and back substitution) or six at once.
//!
//! It is what [`super::block_tree`] factorises each pivot block with: fixed-size arrays
//! held row by row, so that eliminating a row and solving for six right-hand sides are
//! straight loops over rows of six numbers that the compiler vectorises, with no
//! pivot-search or column-swap machinery of a general-size LU.

use nalgebra::{Matrix6, Vector6};

/// The factors of one 6 × 6 block: L (unit lower, below the diagonal) and U (on and
/// above it) in one array, row by row, and the row permutation P.
#[derive(Clone, Copy, Debug)]
pub struct BlockLu {
    /// `lu[r][c]`: L below the diagonal, U on and above it.
    lu: [[f64; 6]; 6],
    /// Row `r` of P A is row `perm[r]` of A.
    perm: [u8; 6],
    /// Some pivot (a diagonal entry of U) is exactly zero: no solve is possible.
    singular: bool,
}

impl BlockLu {
    /// Factorises `a`. A column with no nonzero pivot is left as it is and the factors
    /// are marked singular (the solves then return `None`), as a general LU does.
    #[inline]
    pub fn new(a: &Matrix6<f64>) -> Self {
        let mut lu = [[0.0; 6]; 6];
        for (r, row) in lu.iter_mut().enumerate() {
            for (c, v) in row.iter_mut().enumerate() {
                *v = a[(r, c)];
            }
        }
        let mut perm = [0u8, 1, 2, 3, 4, 5];
        let mut singular = false;
        for k in 0..6 {
            // the largest entry of column k on or below the diagonal
            let mut p = k;
            let mut largest = lu[k][k].abs();
            for (r, row) in lu.iter().enumerate().skip(k + 1) {
                if row[k].abs() > largest {
                    largest = row[k].abs();
                    p = r;
                }
            }
            if p != k {
                lu.swap(p, k);
                perm.swap(p, k);
            }
            let pivot = lu[k][k];
            if pivot == 0.0 {
                singular = true;
                continue;
            }
            let pivot_row = lu[k];
            for row in lu.iter_mut().skip(k + 1) {
                let l = row[k] / pivot;
                row[k] = l;
                for c in k + 1..6 {
                    row[c] -= l * pivot_row[c];
                }
            }
        }
        Self { lu, perm, singular }
    }

    /// Whether a pivot is zero (the block is singular).
    pub fn is_singular(&self) -> bool {
        self.singular
    }

    /// x with A x = b; `None` when the block is singular.
    #[inline]
    pub fn solve(&self, b: &Vector6<f64>) -> Option<Vector6<f64>> {
        if self.singular {
            return None;
        }
        let mut y = [0.0; 6];
        for r in 0..6 {
            let mut s = b[self.perm[r] as usize];
            for (c, yc) in y.iter().enumerate().take(r) {
                s -= self.lu[r][c] * yc;
            }
            y[r] = s;
        }
        for r in (0..6).rev() {
            let mut s = y[r];
            for c in r + 1..6 {
                s -= self.lu[r][c] * y[c];
            }
            y[r] = s / self.lu[r][r];
        }
        Some(Vector6::from(y))
    }

    /// X with A X = B for six right-hand sides at once (the columns of `b`); `None` when
    /// the block is singular.
    #[inline]
    pub fn solve_matrix(&self, b: &Matrix6<f64>) -> Option<Matrix6<f64>> {
        if self.singular {
            return None;
        }
        // rows of P B, eliminated row by row: each step is one row of six updated by a
        // multiple of another
        let mut x = [[0.0; 6]; 6];
        for (r, row) in x.iter_mut().enumerate() {
            let from = self.perm[r] as usize;
            for (c, v) in row.iter_mut().enumerate() {
                *v = b[(from, c)];
            }
        }
        for r in 1..6 {
            for c in 0..r {
                let l = self.lu[r][c];
                let above = x[c];
                for (v, a) in x[r].iter_mut().zip(above) {
                    *v -= l * a;
                }
            }
        }
        for r in (0..6).rev() {
            for c in r + 1..6 {
                let u = self.lu[r][c];
                let below = x[c];
                for (v, a) in x[r].iter_mut().zip(below) {
                    *v -= u * a;
                }
            }
            let d = self.lu[r][r];
            for v in &mut x[r] {
                *v /= d;
            }
        }
        Some(Matrix6::from_fn(|r, c| x[r][c]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn random(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((*seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    }

    /// Against nalgebra's LU on random blocks, some needing row exchanges (a small
    /// leading entry), for one and for six right-hand sides: A x = b to 1e-12 relative.
    #[test]
    fn solves_as_a_general_lu() {
        let mut seed = 7u64;
        for case in 0..200 {
            let mut a = Matrix6::from_fn(|_, _| random(&mut seed));
            if case % 2 == 0 {
                a[(0, 0)] = 1e-9 * random(&mut seed);
            } else {
                a += Matrix6::identity() * 3.0;
            }
            let b = Vector6::from_fn(|_, _| random(&mut seed));
            let bm = Matrix6::from_fn(|_, _| random(&mut seed));
            let f = BlockLu::new(&a);
            let reference = a.lu();
            let x = f.solve(&b).unwrap();
            let expected = reference.solve(&b).unwrap();
            let scale = expected.amax().max(1.0);
            assert!((x - expected).amax() <= 1e-10 * scale, "case {case}");
            assert!((a * x - b).amax() <= 1e-12 * (a.amax() * x.amax()).max(1.0));
            let xm = f.solve_matrix(&bm).unwrap();
            let expected = reference.solve(&bm).unwrap();
            let scale = expected.amax().max(1.0);
            assert!((xm - expected).amax() <= 1e-10 * scale, "case {case}");
        }
    }

    /// A block with a zero column is singular: no solve.
    #[test]
    fn a_singular_block_has_no_solve() {
        let mut a = Matrix6::<f64>::identity();
        a[(3, 3)] = 0.0;
        a[(1, 3)] = 2.0;
        let f = BlockLu::new(&a);
        assert!(f.is_singular());
        assert!(f.solve(&Vector6::repeat(1.0)).is_none());
        assert!(f.solve_matrix(&Matrix6::identity()).is_none());
        assert!(a.lu().solve(&Vector6::repeat(1.0)).is_none());
    }
}
