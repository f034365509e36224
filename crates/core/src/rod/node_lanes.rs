//! A window of consecutive nodes' data stored as lanes — structure of arrays — for the
//! element kernel's chained blocks ([`crate::rod::element_block`]).
//!
//! The node arrays hold each node's position, frame, velocity and angular velocity
//! together (array of structures: x₀ y₀ z₀ x₁ …). A chained block of four elements reads
//! its five nodes twice, as the lanes of its ends a (nodes n … n + 3) and b (n + 1 …
//! n + 4); gathered from the node arrays, that takes a shuffle or an insert for most of
//! the 2 × 52 numbers, on the floating-point pipes the kernel's multiplies need. Here
//! the nodes of a window are transposed once (four nodes' vectors by three 256-bit loads
//! and seven shuffles, their frames by four loads and eight, [`Lane4::load_vectors`] and
//! [`Lane4::load_quats`]), each component stored as consecutive f64, and a
//! block's lanes are plain loads: x of nodes n … n + 3 is `x[n..n + 4]`, of n + 1 …
//! n + 4 is `x[n + 1..n + 5]`.
//!
//! The window is filled from the node arrays when a block needs nodes outside it (the
//! next [`WINDOW`] nodes from the block's first), so each node is transposed about
//! once per call; the values are copies, so the kernel's results are the same bits.

use crate::rod::lane_arith::Lane4;
use crate::rod::lanes::{F4, Q4, V4};
use crate::rod::node_view::NodeView;

/// Nodes a window holds.
pub const WINDOW: usize = 64;
/// Components per node: x (3), q (4), v (3), w (3).
const COMPONENTS: usize = 13;
/// The first component of each quantity.
const X: usize = 0;
const Q: usize = 3;
const V: usize = 7;
const W: usize = 10;

/// The data of the nodes `first..first + count` (indices of a [`NodeView`]'s arrays),
/// component c of node `first + i` at `data[c][i]`.
pub struct NodeLanes {
    first: usize,
    count: usize,
    data: [[f64; WINDOW]; COMPONENTS],
}

impl NodeLanes {
    /// An empty window.
    pub const EMPTY: NodeLanes = NodeLanes {
        first: 0,
        count: 0,
        data: [[0.0; WINDOW]; COMPONENTS],
    };

    /// Forgets the window (the node arrays are about to change, or another view is read).
    #[inline(always)]
    pub fn clear(&mut self) {
        self.count = 0;
    }

    /// Makes the window hold the nodes `n..n + len` of `c` (`len` ≤ [`WINDOW`]), filling
    /// it with the nodes from `n` on when it does not.
    #[inline(always)]
    pub fn hold<L: Lane4>(&mut self, c: &NodeView, n: usize, len: usize) {
        debug_assert!(len <= WINDOW);
        if n < self.first || n + len > self.first + self.count {
            self.fill::<L>(c, n);
        }
    }

    /// Fills the window with the nodes from `first` on (as many as the arrays and the
    /// window hold).
    #[inline(always)]
    fn fill<L: Lane4>(&mut self, c: &NodeView, first: usize) {
        let count = WINDOW.min(c.x.len() - first);
        let r = first..first + count;
        let (x, q, v, w) = (&c.x[r.clone()], &c.q[r.clone()], &c.v[r.clone()], &c.w[r]);
        let d = &mut self.data;
        let mut i = 0;
        while i + 4 <= count {
            let four = i..i + 4;
            let put = |d: &mut [[f64; WINDOW]; COMPONENTS], c0: usize, lanes: &[L]| {
                for (k, l) in lanes.iter().enumerate() {
                    d[c0 + k][i..i + 4].copy_from_slice(&l.to_f4().0);
                }
            };
            put(
                d,
                X,
                &L::load_vectors(x[four.clone()].try_into().expect("four")),
            );
            put(
                d,
                Q,
                &L::load_quats(q[four.clone()].try_into().expect("four")),
            );
            put(
                d,
                V,
                &L::load_vectors(v[four.clone()].try_into().expect("four")),
            );
            put(d, W, &L::load_vectors(w[four].try_into().expect("four")));
            i += 4;
        }
        for i in i..count {
            let vectors = [(X, x[i]), (V, v[i]), (W, w[i])];
            for (c0, p) in vectors {
                (d[c0][i], d[c0 + 1][i], d[c0 + 2][i]) = (p.x, p.y, p.z);
            }
            (d[Q][i], d[Q + 1][i], d[Q + 2][i], d[Q + 3][i]) = (q[i].x, q[i].y, q[i].z, q[i].w);
        }
        (self.first, self.count) = (first, count);
    }

    /// Component `c` of the nodes `n..n + 4` in lanes (the window holds them).
    #[inline(always)]
    fn lanes(&self, c: usize, n: usize) -> F4 {
        let i = n - self.first;
        F4(self.data[c][i..i + 4].try_into().expect("four nodes"))
    }

    #[inline(always)]
    fn vectors(&self, c: usize, n: usize) -> V4 {
        V4::new(self.lanes(c, n), self.lanes(c + 1, n), self.lanes(c + 2, n))
    }

    /// Positions of the nodes `n..n + 4`.
    #[inline(always)]
    pub fn x(&self, n: usize) -> V4 {
        self.vectors(X, n)
    }

    /// Frames of the nodes `n..n + 4`.
    #[inline(always)]
    pub fn q(&self, n: usize) -> Q4 {
        Q4 {
            x: self.lanes(Q, n),
            y: self.lanes(Q + 1, n),
            z: self.lanes(Q + 2, n),
            w: self.lanes(Q + 3, n),
        }
    }

    /// Velocities of the nodes `n..n + 4`.
    #[inline(always)]
    pub fn v(&self, n: usize) -> V4 {
        self.vectors(V, n)
    }

    /// Angular velocities of the nodes `n..n + 4`.
    #[inline(always)]
    pub fn w(&self, n: usize) -> V4 {
        self.vectors(W, n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rod::inelastic::HistoryView;
    use crate::rod::lanes::{gather3, gather4};
    use glam::{DQuat, DVec3};

    /// Every window (refilled as blocks move along, with a tail shorter than four nodes)
    /// gives the lanes the gathers give, bit for bit, on both lane types.
    #[test]
    fn window_lanes_are_the_gathered_ones() {
        let n = WINDOW + 23;
        let f = |i: usize, k: usize| (i * 13 + k) as f64 * 0.37 - 5.0;
        let x: Vec<DVec3> = (0..n)
            .map(|i| DVec3::new(f(i, 0), f(i, 1), f(i, 2)))
            .collect();
        let q: Vec<DQuat> = (0..n)
            .map(|i| DQuat::from_xyzw(f(i, 3), f(i, 4), f(i, 5), f(i, 6)))
            .collect();
        let v: Vec<DVec3> = (0..n)
            .map(|i| DVec3::new(f(i, 7), f(i, 8), f(i, 9)))
            .collect();
        let w: Vec<DVec3> = (0..n)
            .map(|i| DVec3::new(f(i, 10), f(i, 11), f(i, 12)))
            .collect();
        let c = NodeView {
            x: &x,
            q: &q,
            v: &v,
            w: &w,
            inelastic_history: HistoryView::NONE,
        };
        let same3 = |a: V4, b: V4| assert_eq!((a.x, a.y, a.z), (b.x, b.y, b.z));
        let check = |lanes: &NodeLanes, m: usize| {
            let idx = [m, m + 1, m + 2, m + 3];
            same3(lanes.x(m), gather3(&x, idx));
            same3(lanes.v(m), gather3(&v, idx));
            same3(lanes.w(m), gather3(&w, idx));
            let (a, b) = (lanes.q(m), gather4(&q, idx));
            assert_eq!((a.x, a.y, a.z, a.w), (b.x, b.y, b.z, b.w));
        };
        let mut portable = NodeLanes::EMPTY;
        #[cfg(target_arch = "x86_64")]
        let avx = std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma");
        for m in (0..n - 4).step_by(3) {
            portable.hold::<F4>(&c, m, 5.min(n - m));
            check(&portable, m);
            #[cfg(target_arch = "x86_64")]
            if avx {
                let mut fast = NodeLanes::EMPTY;
                // SAFETY: the CPU has AVX2 and FMA (checked above).
                unsafe { hold_avx(&mut fast, &c, m) };
                check(&fast, m);
            }
        }
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn hold_avx(lanes: &mut NodeLanes, c: &NodeView, m: usize) {
        lanes.hold::<crate::rod::lane_arith::Avx4>(c, m, 4);
    }
}
