//! The Baumgarte-stabilised KKT solve of spec §1 (P25–P26):
//!
//! ```text
//! [M  Φqᵀ] [q̈]   [g                ]
//! [Φq 0  ] [λ] = [γ − 2αΦ̇ − β²Φ     ]
//! ```
//!
//! `M` is diagonal, so the system is reduced to the Schur complement
//! `S λ = Φq M⁻¹ g − c` with `S = Φq M⁻¹ Φqᵀ` (symmetric positive definite for independent
//! constraints), factorised in place by faer's Cholesky (LLᵀ), then `q̈ = M⁻¹ (g − Φqᵀ λ)`.
//! `S` is assembled from the sparse rows ([`JacRow`]) body by body: only pairs of rows that share a
//! body contribute, and the rows are numbered in a minimum-degree order so that the factor has
//! little fill-in (nine-bar: 51 instead of 65 non-zeros below the diagonal). All storage (the matrix, the right-hand side and faer's scratch stack) is
//! allocated once in [`KktSolver::new`]; [`KktSolver::solve`] allocates nothing.
//!
//! Mechanisms have a few dozen constraint rows; up to [`SMALL`] rows `S` is factorised by a
//! plain left-looking Cholesky on contiguous columns (at this size faer's blocked, SIMD-dispatched
//! kernel spends more time choosing than computing); larger systems use faer's LLᵀ.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt;
use faer::{MatMut, MatRef, Par};

use crate::constraints::JacRow;

/// Up to this many constraint rows the Schur complement is factorised by
/// [`cholesky_small`]; larger systems go to faer's blocked LLᵀ.
pub const SMALL: usize = 64;

/// The structurally non-zero entries of the Cholesky factor L of S (fill-in included), row by
/// row below the diagonal: fixed by which constraint rows share a body, so computed once.
#[derive(Debug, Clone, Default)]
pub struct LowerPattern {
    start: Vec<usize>,
    cols: Vec<u32>,
}

impl LowerPattern {
    /// Symbolic factorisation of an n×n pattern given by `nonzero(i, j)` for i > j.
    fn new(n: usize, nonzero: impl Fn(usize, usize) -> bool) -> Self {
        let mut p = vec![false; n * n]; // p[i * n + j], i > j
        for i in 0..n {
            for j in 0..i {
                p[i * n + j] = nonzero(i, j);
            }
        }
        for j in 0..n {
            for k in 0..j {
                if p[j * n + k] {
                    for i in j + 1..n {
                        if p[i * n + k] {
                            p[i * n + j] = true; // fill-in
                        }
                    }
                }
            }
        }
        let mut start = vec![0];
        let mut cols = Vec::new();
        for i in 0..n {
            cols.extend((0..i).filter(|&j| p[i * n + j]).map(|j| j as u32));
            start.push(cols.len());
        }
        LowerPattern { start, cols }
    }

    /// The columns k < i with L[i, k] ≠ 0.
    #[inline]
    fn row(&self, i: usize) -> &[u32] {
        &self.cols[self.start[i]..self.start[i + 1]]
    }
}

/// A greedy minimum-degree elimination order of the symmetric graph `adj` (`n × n`, row-major):
/// repeatedly eliminate the node with the fewest remaining neighbours (the first such node on a
/// tie) and join its neighbours into a clique (George & Liu, "The evolution of the minimum degree
/// ordering algorithm", SIAM Rev. 31, 1989). Returns the nodes in elimination order.
fn minimum_degree_order(n: usize, adj: &[bool]) -> Vec<u32> {
    fn neighbours<'a>(n: usize, a: &'a [bool], done: &'a [bool], v: usize) -> impl Iterator<Item = usize> + 'a {
        (0..n).filter(move |&u| u != v && !done[u] && a[v * n + u])
    }
    let mut a = adj.to_vec();
    let mut done = vec![false; n];
    let mut order = Vec::with_capacity(n);
    for _ in 0..n {
        let v = (0..n).filter(|&v| !done[v]).min_by_key(|&v| neighbours(n, &a, &done, v).count()).expect("a node is left");
        let nbrs: Vec<usize> = neighbours(n, &a, &done, v).collect();
        for &x in &nbrs {
            for &y in &nbrs {
                a[x * n + y] = true;
            }
        }
        done[v] = true;
        order.push(v as u32);
    }
    order
}

/// In-place Cholesky LLᵀ of the lower triangle of the column-major n×n matrix `s`
/// (left-looking, column by column, visiting only the structural non-zeros of `pattern`).
/// Returns the index of a non-positive pivot (singular or indefinite `S`).
fn cholesky_small(s: &mut [f64], n: usize, pattern: &LowerPattern) -> Result<(), usize> {
    for j in 0..n {
        // Column j below the diagonal: s[j.., j] −= L[j.., k] L[j, k] for the k < j with
        // L[j, k] structurally non-zero (no test on values in the loop).
        let (left, right) = s.split_at_mut(j * n);
        let col_j = &mut right[j..n];
        for &k in pattern.row(j) {
            let k = k as usize;
            let ljk = left[j + k * n];
            let col_k = &left[k * n + j..k * n + n];
            for (dst, src) in col_j.iter_mut().zip(col_k) {
                *dst -= ljk * src;
            }
        }
        let d = s[j + j * n];
        if !(d > 0.0) {
            return Err(j);
        }
        let d = d.sqrt();
        let inv = 1.0 / d;
        s[j + j * n] = d;
        for v in &mut s[j * n + j + 1..j * n + n] {
            *v *= inv;
        }
    }
    Ok(())
}

/// `L Lᵀ x = rhs` with the factor of [`cholesky_small`], by forward and backward substitution.
fn cholesky_solve_small(s: &[f64], rhs: &mut [f64], n: usize, pattern: &LowerPattern) {
    // L y = b, row by row over the structural non-zeros of each row of L.
    for i in 0..n {
        let mut v = rhs[i];
        for &k in pattern.row(i) {
            v -= s[i + k as usize * n] * rhs[k as usize];
        }
        rhs[i] = v / s[i + i * n];
    }
    // Lᵀ x = y: once x_i is known, remove its share from the unknowns of row i's columns.
    for i in (0..n).rev() {
        let xi = rhs[i] / s[i + i * n];
        rhs[i] = xi;
        for &k in pattern.row(i) {
            rhs[k as usize] -= s[i + k as usize * n] * xi;
        }
    }
}

/// Preallocated workspace and static sparsity structure of one model's KKT system.
pub struct KktSolver {
    rows: usize,
    /// 1/m, 1/m, 1/J per body.
    inv_mass: Vec<f64>,
    /// For each body, the (row, slot) pairs of Jacobian rows that touch it (CSR layout).
    body_start: Vec<usize>,
    body_rows: Vec<(u32, u8)>,
    /// Position of each constraint row in `s` (a minimum-degree order, less fill-in in L), and
    /// the row at each position.
    pos: Vec<u32>,
    row_at: Vec<u32>,
    /// S in that order, column-major (`s[i + j·rows]`); only the lower triangle is used.
    s: Vec<f64>,
    rhs: Vec<f64>,
    pattern: LowerPattern,
    w: Vec<f64>,
    mem: MemBuffer,
}

impl KktSolver {
    /// `inv_mass` holds 3 entries per body; `structure` is any evaluation of the Jacobian rows
    /// (their body lists never change during a run).
    pub fn new(inv_mass: Vec<f64>, structure: &[JacRow]) -> Self {
        let nb = inv_mass.len() / 3;
        let rows = structure.len();
        let mut per_body: Vec<Vec<(u32, u8)>> = vec![Vec::new(); nb];
        for (r, row) in structure.iter().enumerate() {
            for k in 0..row.count as usize {
                per_body[row.bodies[k] as usize].push((r as u32, k as u8));
            }
        }
        let mut body_start = vec![0];
        let mut body_rows = Vec::new();
        for list in per_body {
            body_rows.extend(list);
            body_start.push(body_rows.len());
        }
        // S[i, j] is non-zero where rows i and j share a body.
        let mut shared = vec![false; rows * rows];
        for b in 0..nb {
            let list = &body_rows[body_start[b]..body_start[b + 1]];
            for &(r1, _) in list {
                for &(r2, _) in list {
                    shared[r1 as usize * rows + r2 as usize] = true;
                }
            }
        }
        let row_at = minimum_degree_order(rows, &shared);
        let mut pos = vec![0u32; rows];
        for (p, &r) in row_at.iter().enumerate() {
            pos[r as usize] = p as u32;
        }
        let pattern = LowerPattern::new(rows, |i, j| shared[row_at[i] as usize * rows + row_at[j] as usize]);
        let req = llt::factor::cholesky_in_place_scratch::<f64>(rows, Par::Seq, Default::default())
            .or(llt::solve::solve_in_place_scratch::<f64>(rows, 1, Par::Seq));
        KktSolver {
            rows,
            pattern,
            pos,
            row_at,
            w: vec![0.0; inv_mass.len()],
            inv_mass,
            body_start,
            body_rows,
            s: vec![0.0; rows * rows],
            rhs: vec![0.0; rows],
            mem: MemBuffer::new(req),
        }
    }

    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Solve for `qdd` (generalised accelerations) and `lambda` (multipliers) given the Jacobian
    /// rows, the generalised forces `force` and the constraint right-hand side `c`
    /// (= γ − 2αΦ̇ − β²Φ). Returns the constraint row of a non-positive pivot if `S` is singular.
    pub fn solve(&mut self, jac: &[JacRow], force: &[f64], c: &[f64], qdd: &mut [f64], lambda: &mut [f64]) -> Result<(), usize> {
        self.factor(jac)?;
        self.solve_factored(jac, force, c, qdd, lambda);
        Ok(())
    }

    /// Assemble and factorise `S = Φq M⁻¹ Φqᵀ` for the Jacobian rows `jac` (kept for
    /// [`KktSolver::solve_factored`]). Returns the constraint row of a non-positive pivot.
    pub fn factor(&mut self, jac: &[JacRow]) -> Result<(), usize> {
        let m = self.rows;
        if m == 0 {
            return Ok(());
        }
        // Lower triangle of S = Φq M⁻¹ Φqᵀ.
        self.s.iter_mut().for_each(|v| *v = 0.0);
        let nb = self.body_start.len() - 1;
        for b in 0..nb {
            let im = &self.inv_mass[3 * b..3 * b + 3];
            let list = &self.body_rows[self.body_start[b]..self.body_start[b + 1]];
            for (p, &(r1, k1)) in list.iter().enumerate() {
                let c1 = &jac[r1 as usize].coef[k1 as usize];
                let m1 = [c1[0] * im[0], c1[1] * im[1], c1[2] * im[2]];
                for &(r2, k2) in &list[p..] {
                    let c2 = &jac[r2 as usize].coef[k2 as usize];
                    let v = m1[0] * c2[0] + m1[1] * c2[1] + m1[2] * c2[2];
                    let (p1, p2) = (self.pos[r1 as usize], self.pos[r2 as usize]);
                    let (i, j) = if p1 >= p2 { (p1, p2) } else { (p2, p1) };
                    self.s[i as usize + j as usize * m] += v;
                }
            }
        }
        let pivot = if m <= SMALL {
            cholesky_small(&mut self.s, m, &self.pattern)
        } else {
            let mut stack = MemStack::new(&mut self.mem);
            let s = MatMut::from_column_major_slice_mut(&mut self.s, m, m);
            llt::factor::cholesky_in_place(s, Default::default(), Par::Seq, &mut stack, Default::default())
                .map(|_| ())
                .map_err(|e| match e {
                    llt::factor::LltError::NonPositivePivot { index } => index,
                })
        };
        pivot.map_err(|p| self.row_at[p] as usize)
    }

    /// [`KktSolver::solve`] with the factor of the last [`KktSolver::factor`] (same `jac`).
    pub fn solve_factored(&mut self, jac: &[JacRow], force: &[f64], c: &[f64], qdd: &mut [f64], lambda: &mut [f64]) {
        let n = self.inv_mass.len();
        for i in 0..n {
            self.w[i] = self.inv_mass[i] * force[i];
        }
        if self.rows == 0 {
            qdd[..n].copy_from_slice(&self.w);
            return;
        }
        // Right-hand side Φq M⁻¹ g − c.
        for (r, row) in jac.iter().enumerate() {
            self.rhs[self.pos[r] as usize] = row.dot(&self.w) - c[r];
        }
        let m = self.rows;
        if m <= SMALL {
            cholesky_solve_small(&self.s, &mut self.rhs, m, &self.pattern);
        } else {
            let mut stack = MemStack::new(&mut self.mem);
            let l = MatRef::from_column_major_slice(&self.s, m, m);
            llt::solve::solve_in_place(l, MatMut::from_column_major_slice_mut(&mut self.rhs, m, 1), Par::Seq, &mut stack);
        }
        for (l, &p) in lambda[..m].iter_mut().zip(&self.pos) {
            *l = self.rhs[p as usize];
        }
        // q̈ = M⁻¹ (g − Φqᵀ λ).
        qdd[..n].copy_from_slice(&self.w);
        for (r, row) in jac.iter().enumerate() {
            let l = lambda[r];
            for k in 0..row.count as usize {
                let o = 3 * row.bodies[k] as usize;
                for a in 0..3 {
                    qdd[o + a] -= self.inv_mass[o + a] * row.coef[k][a] * l;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An arrow (node 0 joined to all others): eliminated first it fills the whole factor,
    /// minimum degree keeps it for last and the factor has no fill-in.
    #[test]
    fn minimum_degree_avoids_the_fill_of_an_arrow() {
        let n = 6;
        let arrow = |i: usize, j: usize| i == 0 || j == 0 || i == j;
        let adj: Vec<bool> = (0..n * n).map(|k| arrow(k / n, k % n)).collect();
        let natural = LowerPattern::new(n, |i, j| arrow(i, j));
        assert_eq!(natural.cols.len(), n * (n - 1) / 2);
        let order = minimum_degree_order(n, &adj);
        assert_eq!(order[..4], [1, 2, 3, 4]); // the leaves go first
        let reordered = LowerPattern::new(n, |i, j| arrow(order[i] as usize, order[j] as usize));
        assert_eq!(reordered.cols.len(), n - 1);
    }

    /// A duplicated constraint row makes S singular; the error names a row of the pair in the
    /// caller's numbering, whatever order the factor used.
    #[test]
    fn singular_pivot_is_reported_as_a_constraint_row() {
        let inv_mass = vec![1.0; 9];
        let rows = [
            JacRow { bodies: [0, 1], count: 2, coef: [[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]] },
            JacRow { bodies: [1, 2], count: 2, coef: [[0.0, 1.0, 0.5], [0.0, -1.0, 0.0]] },
            JacRow { bodies: [2, 0], count: 2, coef: [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0]] },
            JacRow { bodies: [1, 2], count: 2, coef: [[0.0, 1.0, 0.5], [0.0, -1.0, 0.0]] },
        ];
        let mut kkt = KktSolver::new(inv_mass, &rows);
        let row = kkt.factor(&rows).unwrap_err();
        assert!(row == 1 || row == 3, "{row}");
    }

    /// A point mass on a rod pinned at the origin (one revolute row pair on body 0 with a
    /// fixed x), checked against hand elimination.
    #[test]
    fn schur_solve_matches_dense_kkt() {
        // Two bodies, three rows mixing them.
        let inv_mass = vec![1.0 / 2.0, 1.0 / 2.0, 1.0 / 0.1, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 0.2];
        let rows = [
            JacRow { bodies: [0, 1], count: 2, coef: [[1.0, 0.0, 0.3], [-1.0, 0.0, 0.2]] },
            JacRow { bodies: [0, 1], count: 2, coef: [[0.0, 1.0, -0.4], [0.0, -1.0, 0.1]] },
            JacRow { bodies: [1, 0], count: 1, coef: [[0.0, 0.0, 1.0], [0.0; 3]] },
        ];
        let force = [1.0, -2.0, 0.5, 0.3, 4.0, -1.0];
        let c = [0.1, -0.2, 0.7];
        let mut kkt = KktSolver::new(inv_mass.clone(), &rows);
        let (mut qdd, mut lam) = ([0.0; 6], [0.0; 3]);
        kkt.solve(&rows, &force, &c, &mut qdd, &mut lam).unwrap();
        // Check both block equations of the KKT system directly.
        let mut jt_l = [0.0; 6];
        for (r, row) in rows.iter().enumerate() {
            for k in 0..row.count as usize {
                for a in 0..3 {
                    jt_l[3 * row.bodies[k] as usize + a] += row.coef[k][a] * lam[r];
                }
            }
        }
        for i in 0..6 {
            let resid = qdd[i] / inv_mass[i] + jt_l[i] - force[i];
            assert!(resid.abs() < 1e-12, "dynamics row {i}: {resid}");
        }
        for (r, row) in rows.iter().enumerate() {
            assert!((row.dot(&qdd) - c[r]).abs() < 1e-12, "constraint row {r}");
        }
    }

    /// The small-system Cholesky against faer's on a random SPD matrix.
    #[test]
    fn small_cholesky_matches_faer() {
        let n = 30;
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        let a: Vec<f64> = (0..n * n).map(|_| rnd()).collect();
        // S = A Aᵀ + n I (column-major).
        let mut s = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                let mut v = if i == j { n as f64 } else { 0.0 };
                for k in 0..n {
                    v += a[i + k * n] * a[j + k * n];
                }
                s[i + j * n] = v;
            }
        }
        let b: Vec<f64> = (0..n).map(|_| rnd()).collect();
        let (mut s1, mut x1) = (s.clone(), b.clone());
        let dense = LowerPattern::new(n, |_, _| true);
        cholesky_small(&mut s1, n, &dense).unwrap();
        cholesky_solve_small(&s1, &mut x1, n, &dense);
        let mut s2 = s.clone();
        let mut x2 = b.clone();
        let req = llt::factor::cholesky_in_place_scratch::<f64>(n, Par::Seq, Default::default());
        let mut mem = MemBuffer::new(req);
        let mut stack = MemStack::new(&mut mem);
        llt::factor::cholesky_in_place(MatMut::from_column_major_slice_mut(&mut s2, n, n), Default::default(), Par::Seq, &mut stack, Default::default()).unwrap();
        llt::solve::solve_in_place(MatRef::from_column_major_slice(&s2, n, n), MatMut::from_column_major_slice_mut(&mut x2, n, 1), Par::Seq, &mut stack);
        for i in 0..n {
            assert!((x1[i] - x2[i]).abs() < 1e-13 * (1.0 + x2[i].abs()), "x[{i}]: {} vs {}", x1[i], x2[i]);
            // Residual of the original system.
            let r: f64 = (0..n).map(|j| s[i + j * n] * x1[j]).sum::<f64>() - b[i];
            assert!(r.abs() < 1e-12);
        }
    }

    #[test]
    fn redundant_rows_are_reported() {
        let inv_mass = vec![1.0; 3];
        let rows = [
            JacRow { bodies: [0, 0], count: 1, coef: [[1.0, 0.0, 0.0], [0.0; 3]] },
            JacRow { bodies: [0, 0], count: 1, coef: [[2.0, 0.0, 0.0], [0.0; 3]] },
        ];
        let mut kkt = KktSolver::new(inv_mass, &rows);
        let (mut qdd, mut lam) = ([0.0; 3], [0.0; 2]);
        assert!(kkt.solve(&rows, &[0.0; 3], &[0.0; 2], &mut qdd, &mut lam).is_err());
    }
}
