//! The solve with a 6 × 6 pivot block's LU factors (partial pivoting, P A = L U): the
//! right-hand side's rows permuted, forward substitution with the unit lower factor, back
//! substitution with the upper one (Golub & Van Loan, "Matrix Computations", 4th ed.,
//! §3.1 and §3.4.4) — column-oriented, in the order of nalgebra's `LU::solve`, so every
//! operation and its rounding are the same and the result is the same to the bit; only
//! the generic strided loops (the back-substitutions of the block tree's solves) are gone.

use nalgebra::{Const, Matrix6, Vector6, LU};

/// LU factors of a 6 × 6 block.
pub type BlockLu = LU<f64, Const<6>, Const<6>>;

/// x with A x = b from A's factors; `None` where U has a zero pivot (as `LU::solve`).
#[inline]
pub fn solve(lu: &BlockLu, b: &Vector6<f64>) -> Option<Vector6<f64>> {
    let mut x = *b;
    lu.p().permute_rows(&mut x);
    let m = lu.lu_internal();
    // L y = P b, L unit lower triangular: y_r −= y_i l_ri, column by column
    for i in 0..5 {
        let c = x[i];
        for r in i + 1..6 {
            x[r] += -c * m[(r, i)]; // y + a·x as nalgebra's axpy (addition commutes exactly)
        }
    }
    // U x = y from the last row up: x_r −= x_i u_ri, column by column
    for i in (0..6).rev() {
        let d = m[(i, i)];
        if d == 0.0 {
            return None;
        }
        let c = x[i] / d;
        x[i] = c;
        for r in 0..i {
            x[r] += -c * m[(r, i)]; // y + a·x as nalgebra's axpy (addition commutes exactly)
        }
    }
    Some(x)
}

/// X with A X = B, column by column ([`solve`]).
pub fn solve_matrix(lu: &BlockLu, b: &Matrix6<f64>) -> Option<Matrix6<f64>> {
    let mut x = Matrix6::zeros();
    for k in 0..6 {
        x.set_column(k, &solve(lu, &b.column(k).into_owned())?);
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn random_matrix(seed: &mut u64) -> Matrix6<f64> {
        Matrix6::from_fn(|_, _| {
            *seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((*seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        })
    }

    /// The same bits as nalgebra's solve, on matrices whose pivoting swaps rows.
    #[test]
    fn same_bits_as_nalgebra() {
        let mut seed = 7u64;
        for _ in 0..200 {
            let a = random_matrix(&mut seed);
            let b = random_matrix(&mut seed);
            let lu = a.lu();
            let expected = lu.solve(&b).expect("regular");
            let got = solve_matrix(&lu, &b).expect("regular");
            for (g, e) in got.iter().zip(expected.iter()) {
                assert_eq!(g.to_bits(), e.to_bits());
            }
            let v = b.column(0).into_owned();
            let expected = lu.solve(&v).expect("regular");
            let got = solve(&lu, &v).expect("regular");
            for (g, e) in got.iter().zip(expected.iter()) {
                assert_eq!(g.to_bits(), e.to_bits());
            }
        }
    }

    /// A singular block (a zero row) has no solve, as with nalgebra.
    #[test]
    fn singular_block_has_no_solve() {
        let mut seed = 11u64;
        let mut a = random_matrix(&mut seed);
        a.set_row(3, &nalgebra::RowVector6::zeros());
        let lu = a.lu();
        let b = Vector6::repeat(1.0);
        assert!(lu.solve(&b).is_none());
        assert!(solve(&lu, &b).is_none());
    }
}
