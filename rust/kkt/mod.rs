//! The Baumgarte-stabilised KKT solve of docs/physics.md §1 (P25–P26):
//!
//! ```text
//! [M  Φqᵀ] [q̈]   [g                ]
//! [Φq 0  ] [λ] = [γ − 2αΦ̇ − β²Φ     ]
//! ```
//!
//! `M` is diagonal, so the system is reduced to the Schur complement
//! `S λ = Φq M⁻¹ g − c` with `S = Φq M⁻¹ Φqᵀ` (symmetric positive definite for independent
//! constraints), factorised in place as `L D Lᵀ` (a sparse Cholesky without square roots), then
//! `q̈ = M⁻¹ (g − Φqᵀ λ)`.
//! `S` is assembled from the sparse rows ([`JacRow`]) body by body: only pairs of rows that share a
//! body contribute, and the rows are numbered in a minimum-degree order so that the factor has
//! little fill-in (nine-bar: 51 instead of 65 non-zeros below the diagonal). All storage (the matrix, the right-hand side and the scatter vector) is
//! allocated once in [`KktSolver::new`]; [`KktSolver::solve`] allocates nothing.
//! On a small mechanism the rows of L and the bodies' lists of entries hold two or three items,
//! so the numeric loops walk them with running indices and unchecked loads over index lists
//! that are fixed at construction (`at`): the slicing and bounds checks otherwise cost more
//! instructions than the arithmetic (nine-bar: −19 % of a dry cycle's instructions).
//!
//! The symbolic work (ordering, elimination tree, the pattern of L) is done once per model, in
//! time and memory proportional to the non-zeros; S and L live in compressed rows and are
//! factorised row by row over the structural non-zeros, so a chain of n bodies costs O(n) per
//! solve, from the slider-crank to a thousand links (`benches/chain.rs`, `docs/scaling.png`).
//!
//! `ordering.rs` is the symbolic half (elimination order, the pattern of L), `factor.rs` the
//! numeric one (LDLᵀ and its triangular solves); this file the solver over them: assembling S
//! and the right-hand side body by body, and q̈ from λ.

mod factor;
mod ordering;

use crate::constraints::JacRow;
use factor::{at, at_mut, SparseFactor};
use ordering::minimum_degree_order;
pub use ordering::LowerPattern;

/// Preallocated workspace and static sparsity structure of one model's KKT system.
pub struct KktSolver {
    rows: usize,
    /// 1/m, 1/m, 1/J per body.
    inv_mass: Vec<f64>,
    /// For each body, the (row, slot) pairs of Jacobian rows that touch it (CSR layout): the
    /// *entries* of Φq, body by body.
    body_start: Vec<usize>,
    body_rows: Vec<(u32, u8)>,
    /// Per entry: the row's three coefficients on that body, the same times M⁻¹, and the row's
    /// position in S, gathered by [`KktSolver::factor`] so that the assembly of S, the
    /// right-hand side `Φq M⁻¹ g` and `q̈ = M⁻¹ (g − Φqᵀ λ)` all run over contiguous memory,
    /// body by body.
    coef: Vec<[f64; 3]>,
    mcoef: Vec<[f64; 3]>,
    entry_pos: Vec<u32>,
    /// Per entry: its body's first coordinate (3 b).
    entry_body: Vec<u32>,
    /// For each body and each pair (p ≤ q) of its rows in `body_rows` order, where the product
    /// goes in the storage of S (`factor.vals`: an entry of L's pattern, or a diagonal).
    pair_slot: Vec<[u32; 3]>,
    /// Position of each constraint row in S (a minimum-degree order, less fill-in in L), and
    /// the row at each position.
    pos: Vec<u32>,
    row_at: Vec<u32>,
    factor: SparseFactor,
    rhs: Vec<f64>,
    pattern: LowerPattern,
    w: Vec<f64>,
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
        let mut adj: Vec<Vec<u32>> = vec![Vec::new(); rows];
        for b in 0..nb {
            let list = &body_rows[body_start[b]..body_start[b + 1]];
            for &(r1, _) in list {
                adj[r1 as usize].extend(list.iter().map(|&(r2, _)| r2));
            }
        }
        let row_at = minimum_degree_order(&adj);
        let mut pos = vec![0u32; rows];
        for (p, &r) in row_at.iter().enumerate() {
            pos[r as usize] = p as u32;
        }
        let lower: Vec<Vec<u32>> = (0..rows)
            .map(|i| {
                let mut l: Vec<u32> = adj[row_at[i] as usize].iter().map(|&r| pos[r as usize]).filter(|&j| (j as usize) < i).collect();
                l.sort_unstable();
                l.dedup();
                l
            })
            .collect();
        let pattern = LowerPattern::new(&lower);
        let mut pair_slot = Vec::new();
        for b in 0..nb {
            let list = &body_rows[body_start[b]..body_start[b + 1]];
            for (p, &(r1, _)) in list.iter().enumerate() {
                for (q, &(r2, _)) in list.iter().enumerate().skip(p) {
                    let (p1, p2) = (pos[r1 as usize], pos[r2 as usize]);
                    let (i, j) = if p1 >= p2 { (p1 as usize, p2 as usize) } else { (p2 as usize, p1 as usize) };
                    let slot = if i == j {
                        (pattern.len() + i) as u32
                    } else {
                        (pattern.start[i] + pattern.row(i).binary_search(&(j as u32)).expect("S's pattern is in L's")) as u32
                    };
                    let first = body_start[b] as u32;
                    pair_slot.push([first + p as u32, first + q as u32, slot]);
                }
            }
        }
        let factor = SparseFactor::new(&pattern, true);
        let entry_pos = body_rows.iter().map(|&(r, _)| pos[r as usize]).collect();
        let entry_body = (0..nb).flat_map(|b| std::iter::repeat_n(3 * b as u32, body_start[b + 1] - body_start[b])).collect();
        KktSolver {
            rows,
            pattern,
            pair_slot,
            pos,
            row_at,
            w: vec![0.0; inv_mass.len()],
            inv_mass,
            coef: vec![[0.0; 3]; body_rows.len()],
            mcoef: vec![[0.0; 3]; body_rows.len()],
            entry_pos,
            entry_body,
            body_start,
            body_rows,
            factor,
            rhs: vec![0.0; rows],
        }
    }

    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Structural non-zeros of the factor L below its diagonal.
    pub fn factor_nonzeros(&self) -> usize {
        self.pattern.len()
    }

    /// Solve for `qdd` (generalised accelerations) and `lambda` (multipliers) given the Jacobian
    /// rows, the generalised forces `force` and the constraint right-hand side `c`
    /// (= γ − 2αΦ̇ − β²Φ). Returns the constraint row of a non-positive pivot if `S` is singular.
    pub fn solve(&mut self, jac: &[JacRow], force: &[f64], c: &[f64], qdd: &mut [f64], lambda: &mut [f64]) -> Result<(), usize> {
        self.factor(jac)?;
        self.solve_factored(force, c, qdd, lambda);
        Ok(())
    }

    /// Assemble and factorise `S = Φq M⁻¹ Φqᵀ` for the Jacobian rows `jac` (their coefficients
    /// kept for [`KktSolver::solve_factored`]). Returns the constraint row of a non-positive pivot.
    pub fn factor(&mut self, jac: &[JacRow]) -> Result<(), usize> {
        let m = self.rows;
        if m == 0 {
            return Ok(());
        }
        let jac = &jac[..m];
        for (((&(r, k), &b), c), mc) in self.body_rows.iter().zip(&self.entry_body).zip(&mut self.coef).zip(&mut self.mcoef) {
            *c = at(&at(jac, r as usize).coef, k as usize);
            let b = b as usize;
            let im = [at(&self.inv_mass, b), at(&self.inv_mass, b + 1), at(&self.inv_mass, b + 2)];
            *mc = [c[0] * im[0], c[1] * im[1], c[2] * im[2]];
        }
        // Lower triangle of S = Φq M⁻¹ Φqᵀ, body by body: each pair of entries on one body.
        let f = &mut self.factor;
        f.vals.iter_mut().for_each(|v| *v = 0.0);
        for &[p, q, slot] in &self.pair_slot {
            let (m1, c2) = (at(&self.mcoef, p as usize), at(&self.coef, q as usize));
            *at_mut(&mut f.vals, slot as usize) += m1[0] * c2[0] + m1[1] * c2[1] + m1[2] * c2[2];
        }
        f.factor(&self.pattern).map_err(|p| self.row_at[p] as usize)
    }

    /// [`KktSolver::solve_factored`] for a unit generalised force on coordinate `k` and `c = 0`
    /// (a column of the constrained mobility, for RADAU5's Newton matrix): only the entries of
    /// Φq on k's body enter the right-hand side, so it skips the rest of `Φq M⁻¹ g`. The same
    /// numbers as the general solve (tested).
    pub fn unit_force_response(&mut self, k: usize, qdd: &mut [f64], lambda: &mut [f64]) {
        let n = self.inv_mass.len();
        let wk = self.inv_mass[k];
        if self.rows == 0 {
            qdd[..n].fill(0.0);
            qdd[k] = wk;
            return;
        }
        self.rhs.fill(0.0);
        let (b, axis) = (k / 3, k % 3);
        let range = self.body_start[b]..self.body_start[b + 1];
        for (c1, &p) in self.coef[range.clone()].iter().zip(&self.entry_pos[range]) {
            self.rhs[p as usize] += c1[axis] * wk;
        }
        self.factor.solve(&self.pattern, &mut self.rhs);
        for (l, &p) in lambda[..self.rows].iter_mut().zip(&self.pos) {
            *l = self.rhs[p as usize];
        }
        self.accelerations(qdd);
        qdd[k] += wk;
    }

    /// [`KktSolver::solve`] with the factor and the Jacobian of the last [`KktSolver::factor`].
    pub fn solve_factored(&mut self, force: &[f64], c: &[f64], qdd: &mut [f64], lambda: &mut [f64]) {
        let n = self.inv_mass.len();
        for i in 0..n {
            self.w[i] = self.inv_mass[i] * force[i];
        }
        if self.rows == 0 {
            qdd[..n].copy_from_slice(&self.w);
            return;
        }
        // Right-hand side Φq M⁻¹ g − c.
        for (r, &cr) in c[..self.rows].iter().enumerate() {
            self.rhs[self.pos[r] as usize] = -cr;
        }
        for ((c1, &p), &b) in self.coef.iter().zip(&self.entry_pos).zip(&self.entry_body) {
            let w = &self.w[b as usize..b as usize + 3];
            *at_mut(&mut self.rhs, p as usize) += c1[0] * w[0] + c1[1] * w[1] + c1[2] * w[2];
        }
        let m = self.rows;
        self.factor.solve(&self.pattern, &mut self.rhs);
        for (l, &p) in lambda[..m].iter_mut().zip(&self.pos) {
            *l = self.rhs[p as usize];
        }
        // q̈ = M⁻¹ (g − Φqᵀ λ).
        self.accelerations(qdd);
        for (a, w) in qdd[..n].iter_mut().zip(&self.w) {
            *a += w;
        }
    }

    /// Every index the unchecked loads (`at`, `at_mut`) follow is inside the array it indexes:
    /// the invariant that makes them sound, checked on any solver the tests build (in release
    /// builds too, where the `debug_assert!`s are gone).
    #[cfg(test)]
    fn assert_index_lists_in_bounds(&self) {
        let (m, entries, nb) = (self.rows, self.coef.len(), self.body_start.len() - 1);
        let f = &self.factor;
        let (nnz, slots) = (f.nnz, f.vals.len());
        assert_eq!((self.inv_mass.len(), self.mcoef.len(), self.entry_pos.len(), self.entry_body.len()), (3 * nb, entries, entries, entries));
        assert_eq!((self.body_start[nb], self.rhs.len(), f.inv_diag.len(), slots), (entries, m, m, nnz + m));
        assert!(self.body_start.windows(2).all(|w| w[0] <= w[1]));
        assert!(self.entry_pos.iter().all(|&p| (p as usize) < m));
        assert!(self.entry_body.iter().all(|&b| b as usize + 2 < 3 * nb));
        assert!(self.body_rows.iter().all(|&(r, k)| (r as usize) < m && k < 2));
        assert!(self.pair_slot.iter().all(|&[p, q, slot]| (p as usize) < entries && (q as usize) < entries && (slot as usize) < slots));
        let pattern = &self.pattern;
        assert_eq!((pattern.start.len(), pattern.start[m], pattern.cols.len()), (m + 1, nnz, nnz));
        assert!(pattern.start.windows(2).all(|w| w[0] <= w[1]));
        assert!(pattern.cols.iter().all(|&c| (c as usize) < m));
        if let Some(tape) = &f.tape {
            assert_eq!((tape.start.len(), tape.start[nnz] as usize), (nnz + 1, tape.pairs.len()));
            assert!(tape.start.windows(2).all(|w| w[0] <= w[1]));
            assert!(tape.pairs.iter().all(|&[a, b]| (a as usize) < nnz && (b as usize) < nnz));
        }
    }

    /// `q̈ = −M⁻¹ Φqᵀ λ`, body by body, with λ in `rhs` (factor order).
    fn accelerations(&self, qdd: &mut [f64]) {
        // The entries of a body follow each other: one running index, no per-body slicing.
        let mut e = 0;
        for (b, a) in qdd[..self.inv_mass.len()].chunks_exact_mut(3).enumerate() {
            let end = at(&self.body_start, b + 1);
            let mut acc = [0.0; 3];
            while e < end {
                let (mc, l) = (at(&self.mcoef, e), at(&self.rhs, at(&self.entry_pos, e) as usize));
                acc = [acc[0] + mc[0] * l, acc[1] + mc[1] * l, acc[2] + mc[2] * l];
                e += 1;
            }
            a.copy_from_slice(&[-acc[0], -acc[1], -acc[2]]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::dyn_stack::{MemBuffer, MemStack};
    use faer::linalg::cholesky::llt;
    use faer::{MatMut, MatRef, Par};

    /// A random generator for the tests (no dependency on the order of other tests).
    fn lcg(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        }
    }

    /// Random mechanisms' constraint rows: a tree of two-body joints (each body joined to an
    /// earlier one or to ground, like a chain, a fan or a branching linkage), a few joints that
    /// close loops, random coefficients; 2 rows per joint, as a revolute joint has.
    fn random_mechanism(seed: u64, nb: usize, loops: usize) -> (Vec<f64>, Vec<JacRow>) {
        let mut rnd = lcg(seed);
        let inv_mass: Vec<f64> = (0..3 * nb).map(|_| 1.0 / (0.6 + rnd())).collect();
        let mut rows = Vec::new();
        let mut joint = |a: Option<usize>, b: usize, rnd: &mut dyn FnMut() -> f64| {
            for _ in 0..2 {
                let cb = [rnd(), rnd(), rnd()];
                rows.push(match a {
                    Some(a) => JacRow { bodies: [b as u32, a as u32], count: 2, coef: [cb, [rnd(), rnd(), rnd()]] },
                    None => JacRow { bodies: [b as u32, 0], count: 1, coef: [cb, [0.0; 3]] },
                });
            }
        };
        for b in 0..nb {
            let parent = if b == 0 { None } else { Some(((rnd() + 0.5) * b as f64) as usize % b) };
            joint(parent, b, &mut rnd);
        }
        for _ in 0..loops {
            let a = ((rnd() + 0.5) * nb as f64) as usize % nb;
            let b = ((rnd() + 0.5) * nb as f64) as usize % nb;
            if a != b {
                // A loop-closing joint with one row (a distance constraint), so rows stay < 3 nb.
                rows.push(JacRow { bodies: [a as u32, b as u32], count: 2, coef: [[rnd(), rnd(), rnd()], [rnd(), rnd(), rnd()]] });
            }
        }
        (inv_mass, rows)
    }

    /// The sparse Schur-complement solve against the full KKT matrix `[M Φqᵀ; Φq 0]` solved
    /// densely by LU (nalgebra) on random mechanisms, from 3 to 90 bodies: the same q̈ and λ to
    /// round-off.
    #[test]
    fn sparse_solve_matches_a_dense_kkt_solve_on_random_mechanisms() {
        for (seed, nb, loops) in [(1, 3, 0), (2, 10, 2), (3, 25, 5), (4, 40, 0), (5, 60, 12), (6, 90, 20)] {
            let (inv_mass, rows) = random_mechanism(seed, nb, loops);
            let (n, m) = (inv_mass.len(), rows.len());
            let mut rnd = lcg(100 + seed);
            let force: Vec<f64> = (0..n).map(|_| rnd()).collect();
            let c: Vec<f64> = (0..m).map(|_| rnd()).collect();
            let mut kkt = KktSolver::new(inv_mass.clone(), &rows);
            kkt.assert_index_lists_in_bounds();
            let (mut qdd, mut lam) = (vec![0.0; n], vec![0.0; m]);
            kkt.solve(&rows, &force, &c, &mut qdd, &mut lam).unwrap();
            // The factorisation from its tape and by the scatter loop: the same to the last bit.
            let mut scatter = KktSolver::new(inv_mass.clone(), &rows);
            assert!(scatter.factor.tape.is_some());
            scatter.factor.tape = None;
            let (mut qdd2, mut lam2) = (vec![0.0; n], vec![0.0; m]);
            scatter.solve(&rows, &force, &c, &mut qdd2, &mut lam2).unwrap();
            assert_eq!((&qdd, &lam), (&qdd2, &lam2), "seed {seed}");
            let mut a = nalgebra::DMatrix::<f64>::zeros(n + m, n + m);
            let mut b = nalgebra::DVector::<f64>::zeros(n + m);
            for i in 0..n {
                a[(i, i)] = 1.0 / inv_mass[i];
                b[i] = force[i];
            }
            for (r, row) in rows.iter().enumerate() {
                for k in 0..row.count as usize {
                    for ax in 0..3 {
                        let col = 3 * row.bodies[k] as usize + ax;
                        a[(n + r, col)] += row.coef[k][ax];
                        a[(col, n + r)] += row.coef[k][ax];
                    }
                }
                b[n + r] = c[r];
            }
            let x = a.lu().solve(&b).expect("a regular KKT matrix");
            let scale = x.iter().fold(1.0f64, |s, v| s.max(v.abs()));
            for i in 0..n {
                assert!((qdd[i] - x[i]).abs() < 1e-10 * scale, "seed {seed}: q̈[{i}] {} vs {}", qdd[i], x[i]);
            }
            for r in 0..m {
                // The sign convention: M q̈ + Φqᵀ λ = g.
                assert!((lam[r] - x[n + r]).abs() < 1e-10 * scale, "seed {seed}: λ[{r}] {} vs {}", lam[r], x[n + r]);
            }
        }
    }

    /// The unit-force response (only k's body in the right-hand side) against the general solve
    /// with `g = e_k`, `c = 0`: the same numbers, for every coordinate of random mechanisms.
    #[test]
    fn unit_force_response_is_the_general_solve() {
        for (seed, nb, loops) in [(1, 3, 0), (3, 25, 5), (5, 60, 12)] {
            let (inv_mass, rows) = random_mechanism(seed, nb, loops);
            let (n, m) = (inv_mass.len(), rows.len());
            let mut kkt = KktSolver::new(inv_mass.clone(), &rows);
            kkt.factor(&rows).unwrap();
            let (mut a, mut la, mut b, mut lb) = (vec![0.0; n], vec![0.0; m], vec![0.0; n], vec![0.0; m]);
            for k in 0..n {
                let mut unit = vec![0.0; n];
                unit[k] = 1.0;
                kkt.solve_factored(&unit, &vec![0.0; m], &mut a, &mut la);
                kkt.unit_force_response(k, &mut b, &mut lb);
                assert_eq!((&a, &la), (&b, &lb), "seed {seed}, coordinate {k}");
                assert!(a.iter().any(|v| *v != 0.0));
            }
        }
    }

    /// The symbolic factorisation (elimination tree) gives exactly the fill-in of a dense
    /// elimination on the same pattern.
    #[test]
    fn elimination_tree_pattern_matches_dense_elimination() {
        let mut rnd = lcg(7);
        let n = 40;
        let mut p = vec![false; n * n];
        for i in 0..n {
            for j in 0..i {
                p[i * n + j] = rnd() > 0.42;
            }
        }
        let lower: Vec<Vec<u32>> = (0..n).map(|i| (0..i).filter(|&j| p[i * n + j]).map(|j| j as u32).collect()).collect();
        for j in 0..n {
            for k in 0..j {
                if p[j * n + k] {
                    for i in j + 1..n {
                        if p[i * n + k] {
                            p[i * n + j] = true;
                        }
                    }
                }
            }
        }
        let pattern = LowerPattern::new(&lower);
        for i in 0..n {
            let expect: Vec<u32> = (0..i).filter(|&j| p[i * n + j]).map(|j| j as u32).collect();
            assert_eq!(pattern.row(i), &expect[..], "row {i}");
        }
    }

    /// A chain's factor has O(n) non-zeros (no fill beyond a band).
    #[test]
    fn a_long_chain_factor_stays_linear() {
        let counts: Vec<usize> = [100, 1000]
            .iter()
            .map(|&nb| {
                let rows: Vec<JacRow> = (0..nb)
                    .flat_map(|b| {
                        let bodies = if b == 0 { [0, 0] } else { [b as u32, b as u32 - 1] };
                        let count = if b == 0 { 1 } else { 2 };
                        [JacRow { bodies, count, coef: [[1.0, 0.0, 0.3], [-1.0, 0.0, 0.2]] }, JacRow { bodies, count, coef: [[0.0, 1.0, -0.3], [0.0, -1.0, 0.1]] }]
                    })
                    .collect();
                KktSolver::new(vec![1.0; 3 * nb], &rows).factor_nonzeros()
            })
            .collect();
        assert!(counts[1] <= 11 * counts[0], "{counts:?}");
    }

    /// An arrow (node 0 joined to all others): eliminated first it fills the whole factor,
    /// minimum degree keeps it for last and the factor has no fill-in.
    #[test]
    fn minimum_degree_avoids_the_fill_of_an_arrow() {
        let n = 6;
        let arrow = |i: usize, j: usize| i == 0 || j == 0 || i == j;
        let lower_of = |perm: &dyn Fn(usize) -> usize| -> Vec<Vec<u32>> {
            (0..n).map(|i| (0..i).filter(|&j| arrow(perm(i), perm(j))).map(|j| j as u32).collect()).collect()
        };
        let natural = LowerPattern::new(&lower_of(&|i| i));
        assert_eq!(natural.cols.len(), n * (n - 1) / 2);
        let adj: Vec<Vec<u32>> = (0..n).map(|i| (0..n).filter(|&j| j != i && arrow(i, j)).map(|j| j as u32).collect()).collect();
        let order = minimum_degree_order(&adj);
        assert_eq!(order[..4], [1, 2, 3, 4]); // the leaves go first
        let reordered = LowerPattern::new(&lower_of(&|i| order[i] as usize));
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

    /// The sparse factor on a full pattern against faer's dense Cholesky on a random SPD matrix.
    #[test]
    fn sparse_cholesky_matches_faer() {
        let n = 30;
        let mut rnd = lcg(12345);
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
        let full = LowerPattern::new(&(0..n).map(|i| (0..i as u32).collect()).collect::<Vec<_>>());
        // The same factor with and without the tape.
        let mut factors = [SparseFactor::new(&full, true), SparseFactor::new(&full, false)];
        assert!(factors[0].tape.is_some() && factors[1].tape.is_none());
        for f in &mut factors {
            let lower = (0..n).flat_map(|i| full.row(i).iter().map(move |&k| (i, k as usize)));
            for (v, (i, k)) in f.vals.iter_mut().zip(lower) {
                *v = s[i + k * n];
            }
            for i in 0..n {
                f.vals[full.len() + i] = s[i + i * n];
            }
            f.factor(&full).unwrap();
        }
        assert_eq!(factors[0].vals, factors[1].vals, "the tape changes no rounding");
        let f = &factors[0];
        let mut x1 = b.clone();
        f.solve(&full, &mut x1);
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
