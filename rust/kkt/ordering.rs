//! The symbolic half of the KKT solve (docs/physics.md §1): which constraint rows are
//! eliminated in which order (greedy minimum degree) and the non-zero pattern of the factor L
//! that order gives (elimination tree). Done once per model.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

const NONE: u32 = u32::MAX;

/// The structurally non-zero entries of the Cholesky factor L of S (fill-in included), row by
/// row below the diagonal, ascending: fixed by which constraint rows share a body, so computed
/// once.
#[derive(Debug, Clone, Default)]
pub struct LowerPattern {
    pub(super) start: Vec<usize>,
    pub(super) cols: Vec<u32>,
}

impl LowerPattern {
    /// Symbolic factorisation of the symmetric pattern `lower[i]` = the j < i with S[i, j] ≠ 0,
    /// in O(non-zeros of L): the elimination tree (parent of j = the first row i > j with
    /// L[i, j] ≠ 0) by Liu's algorithm with path compression, then each row of L as the union of
    /// the tree paths from the non-zeros of S's row up to the row itself (Liu, "The role of
    /// elimination trees in sparse factorization", SIAM J. Matrix Anal. Appl. 11, 1990).
    pub(super) fn new(lower: &[Vec<u32>]) -> Self {
        let n = lower.len();
        let mut parent = vec![NONE; n];
        let mut ancestor = vec![NONE; n];
        for (i, row) in lower.iter().enumerate() {
            for &j in row {
                let mut r = j as usize;
                while ancestor[r] != NONE && ancestor[r] as usize != i {
                    let next = ancestor[r] as usize;
                    ancestor[r] = i as u32;
                    r = next;
                }
                if ancestor[r] == NONE {
                    ancestor[r] = i as u32;
                    parent[r] = i as u32;
                }
            }
        }
        let mut mark = vec![NONE; n];
        let mut start = vec![0];
        let mut cols = Vec::new();
        for (i, row) in lower.iter().enumerate() {
            let first = cols.len();
            mark[i] = i as u32;
            for &j in row {
                let mut k = j as usize;
                while mark[k] != i as u32 {
                    mark[k] = i as u32;
                    cols.push(k as u32);
                    k = parent[k] as usize;
                }
            }
            cols[first..].sort_unstable();
            start.push(cols.len());
        }
        LowerPattern { start, cols }
    }

    /// The columns k < i with L[i, k] ≠ 0.
    #[inline]
    pub(super) fn row(&self, i: usize) -> &[u32] {
        &self.cols[self.start[i]..self.start[i + 1]]
    }

    /// Number of structural non-zeros below the diagonal.
    pub fn len(&self) -> usize {
        self.cols.len()
    }

    pub fn is_empty(&self) -> bool {
        self.cols.is_empty()
    }
}

/// A greedy minimum-degree elimination order of the symmetric graph `adj` (neighbour lists):
/// repeatedly eliminate the node with the fewest remaining neighbours (the lowest-numbered such
/// node on a tie) and join its neighbours into a clique (George & Liu, "The evolution of the
/// minimum degree ordering algorithm", SIAM Rev. 31, 1989). A heap with lazy deletion finds the
/// next node, so the cost grows with the edges of the filled graph, not with n². Returns the nodes
/// in elimination order.
pub(super) fn minimum_degree_order(adj: &[Vec<u32>]) -> Vec<u32> {
    let n = adj.len();
    let mut nbrs: Vec<Vec<u32>> = adj
        .iter()
        .enumerate()
        .map(|(v, a)| {
            let mut a: Vec<u32> = a.iter().copied().filter(|&u| u as usize != v).collect();
            a.sort_unstable();
            a.dedup();
            a
        })
        .collect();
    let mut done = vec![false; n];
    let mut heap: BinaryHeap<Reverse<(usize, u32)>> = (0..n).map(|v| Reverse((nbrs[v].len(), v as u32))).collect();
    let mut order = Vec::with_capacity(n);
    let mut merged = Vec::new();
    while let Some(Reverse((deg, v))) = heap.pop() {
        let v = v as usize;
        if done[v] || deg != nbrs[v].len() {
            continue; // a stale entry
        }
        done[v] = true;
        order.push(v as u32);
        let clique = std::mem::take(&mut nbrs[v]);
        for &x in &clique {
            // x loses v and gains the other members of the clique.
            let list = &nbrs[x as usize];
            merged.clear();
            let (mut a, mut b) = (0, 0);
            while a < list.len() || b < clique.len() {
                let next = match (list.get(a), clique.get(b)) {
                    (Some(&p), Some(&q)) if p == q => {
                        a += 1;
                        b += 1;
                        p
                    }
                    (Some(&p), Some(&q)) if p < q => {
                        a += 1;
                        p
                    }
                    (Some(_), Some(&q)) | (None, Some(&q)) => {
                        b += 1;
                        q
                    }
                    (Some(&p), None) => {
                        a += 1;
                        p
                    }
                    (None, None) => unreachable!(),
                };
                if next != x && next as usize != v {
                    merged.push(next);
                }
            }
            nbrs[x as usize].clone_from(&merged);
            heap.push(Reverse((merged.len(), x)));
        }
    }
    order
}
