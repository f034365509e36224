//! LU factorisation of one 6 × 6 block with partial pivoting, P A = L U (Golub & Van Loan,
//! "Matrix Computations", 4th ed., alg. 3.4.1), and its solves written out for the fixed
//! size: the block tree ([`super::block_tree`]) solves with every pivot block once per
//! GMRES iteration, where a generic dynamic-loop solve cost more than the arithmetic.

use nalgebra::{Matrix6, Vector6};

/// The factors of one block: `lu` holds L below the diagonal (unit diagonal implied) and
/// U on and above it, rows in pivoted order; row k of P A is row `row[k]` of A.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlockLu {
    lu: [[f64; 6]; 6],
    row: [usize; 6],
}

impl BlockLu {
    /// Factorises `a`; `None` when a pivot is exactly zero (the block is singular).
    pub fn new(a: &Matrix6<f64>) -> Option<Self> {
        let mut lu = [[0.0; 6]; 6];
        for (r, row) in lu.iter_mut().enumerate() {
            for (c, v) in row.iter_mut().enumerate() {
                *v = a[(r, c)];
            }
        }
        let mut row = [0, 1, 2, 3, 4, 5];
        for k in 0..6 {
            let mut p = k;
            for r in k + 1..6 {
                if lu[r][k].abs() > lu[p][k].abs() {
                    p = r;
                }
            }
            if lu[p][k] == 0.0 {
                return None;
            }
            lu.swap(k, p);
            row.swap(k, p);
            let pivot = lu[k][k];
            for r in k + 1..6 {
                let factor = lu[r][k] / pivot;
                lu[r][k] = factor;
                for c in k + 1..6 {
                    lu[r][c] -= factor * lu[k][c];
                }
            }
        }
        Some(Self { lu, row })
    }

    /// x = A⁻¹ b: forward substitution with L, back substitution with U, column by
    /// column (the updates of one column are independent, so they overlap in the
    /// pipeline rather than waiting on one sum).
    pub fn solve(&self, b: &Vector6<f64>) -> Vector6<f64> {
        let mut x = [0.0; 6];
        for (xk, &r) in x.iter_mut().zip(&self.row) {
            *xk = b[r];
        }
        for k in 0..6 {
            let xk = x[k];
            for j in k + 1..6 {
                x[j] -= self.lu[j][k] * xk;
            }
        }
        for k in (0..6).rev() {
            let xk = x[k] / self.lu[k][k];
            x[k] = xk;
            for j in 0..k {
                x[j] -= self.lu[j][k] * xk;
            }
        }
        Vector6::from(x)
    }

    /// X = A⁻¹ B, column by column.
    pub fn solve_matrix(&self, b: &Matrix6<f64>) -> Matrix6<f64> {
        let mut x = Matrix6::zeros();
        for c in 0..6 {
            let column = self.solve(&b.column(c).into_owned());
            x.set_column(c, &column);
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic non-symmetric block that needs pivoting (a zero leading entry)
    /// and spans six orders of magnitude, as a beam node's does (EA against EI).
    fn block() -> Matrix6<f64> {
        Matrix6::from_fn(|r, c| {
            let scale = [1e6, 1e3, 1.0, 1e2, 1e-1, 1e4][r];
            let v = ((r * 7 + c * 13) % 11) as f64 - 5.0 + if r == c { 12.0 } else { 0.0 };
            if r == 0 && c == 0 {
                0.0
            } else {
                scale * v
            }
        })
    }

    #[test]
    fn solves_like_nalgebras_lu_to_round_off() {
        let a = block();
        let b = Vector6::new(1.0, -2.0, 3.0, 0.5, -0.25, 4.0);
        let ours = BlockLu::new(&a).unwrap().solve(&b);
        let reference = a.lu().solve(&b).unwrap();
        assert!((ours - reference).norm() <= 1e-12 * reference.norm());
        // backward stable: the residual is at round-off of ‖A‖‖x‖
        assert!((a * ours - b).norm() <= 1e-14 * a.norm() * ours.norm());
        let m = Matrix6::from_fn(|r, c| (r as f64 - c as f64).sin());
        let x = BlockLu::new(&a).unwrap().solve_matrix(&m);
        assert!((a * x - m).norm() <= 1e-14 * a.norm() * x.norm());
    }

    #[test]
    fn a_singular_block_has_no_factors() {
        let mut a = block();
        let copy = a.row(2).into_owned();
        a.set_row(4, &copy);
        // rows 2 and 4 equal: both see the same operations until one is the pivot row,
        // which then zeroes the other exactly
        assert!(BlockLu::new(&a).is_none());
        assert!(BlockLu::new(&Matrix6::zeros()).is_none());
    }
}
