//! The implicit methods' Newton matrices `σI − J` of a large constrained second-order system,
//! kept sparse by solving them in lifted form ([`Lifted`]; the system's side is
//! [`OdeSystem::lifted_pattern`] and [`OdeSystem::lifted_jacobian`]).
//!
//! With `y = (q, v)`, `J = [[0, I], [a_q, a_v]]` and `[a_q a_v] = [I 0] A₀⁻¹ [K_q K_v]` (a
//! mechanism: `A₀` its KKT matrix `[[M, Φqᵀ], [Φq, 0]]`, `K` the derivative of the KKT right-hand
//! side), the system `(σI − J) x = r` is, with `x_v = (r_v + δ)/σ`, `x_q = (r_q + x_v)/σ` and
//! `H = K_v/σ + K_q/σ²`,
//!
//! ```text
//! (A₀ − [H 0]) [δ; μ] = K_q r_q/σ + H r_v
//! ```
//!
//! a sparse `(m + c)`-square system with the pattern of `A₀` and `K`, whatever `σ`: one symbolic
//! analysis per run (`sparse_lu.rs`), one numeric LU per Newton matrix, in real arithmetic for
//! RODAS4's `I/(hγ) − J` and RADAU5's real system and in complex arithmetic for RADAU5's complex
//! one. The dense forms (`radau_newton.rs`, `lu.rs`) need `a_q`, `a_v` themselves — a column of
//! `A₀⁻¹` per stiff coordinate and a dense LU of all of them, cubic in the size of a mechanism
//! with a clearance at every few joints. Why a sparse LU of the lifted matrix and not a low-rank
//! update of the KKT factor: the stiff part is of low rank only while few joints carry it; a
//! roller chain has a clearance at every pin, and a rank-k update costs k³.
//!
//! Extra states beyond `(q, q̇)` (an oil temperature `z` per joint, `ż = h(q, q̇, z)`, whose
//! viscosity moves the forces) fit the same frame: they add unknowns `x_z` and rows
//! `(σ − h_z) x_z − (h_q/σ² + h_v/σ) δ = r_z + h_q (r_q/σ + r_v/σ²) + h_v r_v/σ` to the lifted
//! matrix (`x_q`, `x_v` being affine in `δ`), and a column `−K_z` to its first block rows: a
//! pattern one row and column per state larger, the same symbolic-once LU.

use faer::c64;

use super::ode::{LiftedPattern, OdeSystem};
use super::sparse_lu::SparseLu;
use crate::error::Error;

/// The Newton matrices `σI − J` of a second-order system in lifted form, for one real `σ` and
/// (RADAU5) one complex `σ₂`, and their solves. All storage is allocated in [`Lifted::new`].
pub(super) struct Lifted {
    /// `m`: coordinates (the state is `2m` long).
    m: usize,
    col_start: Vec<usize>,
    row: Vec<usize>,
    /// `A₀`, `K_q`, `K_v` on the pattern.
    a0: Vec<f64>,
    k_q: Vec<f64>,
    k_v: Vec<f64>,
    real: SparseLu<f64>,
    real_values: Vec<f64>,
    sigma: f64,
    rhs: Vec<f64>,
    /// The complex system (RADAU5 only): LU, values, right-hand side, `σ₂`.
    complex: Option<(SparseLu<c64>, Vec<c64>, Vec<c64>)>,
    sigma2: c64,
}

impl Lifted {
    /// The lifted storage for `pattern`, with the complex system if `complex`.
    pub(super) fn new(pattern: LiftedPattern, complex: bool) -> Self {
        let LiftedPattern { coords: m, dim, col_start, row, .. } = pattern;
        let nnz = row.len();
        let real = SparseLu::new(dim, col_start.clone(), row.clone());
        let complex = complex.then(|| (SparseLu::new(dim, col_start.clone(), row.clone()), vec![c64::new(0.0, 0.0); nnz], vec![c64::new(0.0, 0.0); dim]));
        Lifted {
            m,
            col_start,
            row,
            a0: vec![0.0; nnz],
            k_q: vec![0.0; nnz],
            k_v: vec![0.0; nnz],
            real,
            real_values: vec![0.0; nnz],
            sigma: 1.0,
            rhs: vec![0.0; dim],
            complex,
            sigma2: c64::new(1.0, 0.0),
        }
    }

    /// Recompute `A₀` and `K` at `(t, y)` (`exact`: the whole `K`, else its stiff part).
    /// Returns the right-hand sides the system evaluated for it.
    pub(super) fn update<S: OdeSystem>(&mut self, sys: &mut S, t: f64, y: &[f64], exact: bool) -> Result<usize, Error> {
        sys.lifted_jacobian(t, y, exact, &mut self.a0, &mut self.k_q, &mut self.k_v)
    }

    /// Factorise the real system for `σ` (`A₀ − K_v/σ − K_q/σ²`).
    pub(super) fn factor_real(&mut self, sigma: f64) {
        self.sigma = sigma;
        let (s1, s2) = (1.0 / sigma, 1.0 / (sigma * sigma));
        for (((v, a), kq), kv) in self.real_values.iter_mut().zip(&self.a0).zip(&self.k_q).zip(&self.k_v) {
            *v = a - (kv * s1 + kq * s2);
        }
        self.real.factor(&self.real_values);
    }

    /// Factorise the complex system for `σ₂ = a + ib`.
    pub(super) fn factor_complex(&mut self, a: f64, b: f64) {
        let sigma2 = c64::new(a, b);
        self.sigma2 = sigma2;
        let s1 = c64::new(1.0, 0.0) / sigma2;
        let s2 = s1 * s1;
        let Some((lu, values, _)) = self.complex.as_mut() else { return };
        for (((v, &a), &kq), &kv) in values.iter_mut().zip(&self.a0).zip(&self.k_q).zip(&self.k_v) {
            *v = c64::new(a - (kv * s1.re + kq * s2.re), -(kv * s1.im + kq * s2.im));
        }
        lu.factor(values);
    }

    /// `x ← (σI − J)⁻¹ x` for the `σ` of the last [`Lifted::factor_real`] (`x = (r_q, r_v)`).
    pub(super) fn solve_real(&mut self, x: &mut [f64]) {
        let (m, s) = (self.m, self.sigma);
        let (xq, xv) = x.split_at_mut(m);
        // K_q r_q/σ + H r_v = Σ_j K_q[:, j] (r_q/σ + r_v/σ²)_j + K_v[:, j] (r_v/σ)_j.
        self.rhs.fill(0.0);
        for j in 0..m {
            let (u, w) = (xq[j] / s + xv[j] / (s * s), xv[j] / s);
            if u == 0.0 && w == 0.0 {
                continue;
            }
            for k in self.col_start[j]..self.col_start[j + 1] {
                self.rhs[self.row[k]] += self.k_q[k] * u + self.k_v[k] * w;
            }
        }
        self.real.solve(&mut self.rhs);
        for ((q, v), d) in xq.iter_mut().zip(xv.iter_mut()).zip(&self.rhs[..m]) {
            *v = (*v + d) / s;
            *q = (*q + *v) / s;
        }
    }

    /// `(xr + i xi) ← (σ₂I − J)⁻¹ (xr + i xi)` for the `σ₂` of the last
    /// [`Lifted::factor_complex`].
    pub(super) fn solve_complex(&mut self, xr: &mut [f64], xi: &mut [f64]) {
        let (m, s) = (self.m, self.sigma2);
        let Some((lu, _, rhs)) = self.complex.as_mut() else { return };
        let s1 = c64::new(1.0, 0.0) / s;
        let s2 = s1 * s1;
        rhs.fill(c64::new(0.0, 0.0));
        for j in 0..m {
            let (rq, rv) = (c64::new(xr[j], xi[j]), c64::new(xr[m + j], xi[m + j]));
            let (u, w) = (rq * s1 + rv * s2, rv * s1);
            if u == c64::new(0.0, 0.0) && w == c64::new(0.0, 0.0) {
                continue;
            }
            for k in self.col_start[j]..self.col_start[j + 1] {
                rhs[self.row[k]] += u * self.k_q[k] + w * self.k_v[k];
            }
        }
        lu.solve(rhs);
        for j in 0..m {
            let v = (c64::new(xr[m + j], xi[m + j]) + rhs[j]) * s1;
            let q = (c64::new(xr[j], xi[j]) + v) * s1;
            (xr[j], xi[j], xr[m + j], xi[m + j]) = (q.re, q.im, v.re, v.im);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::ode::{LiftedPattern, OdeSystem};
    use super::Lifted;
    use crate::error::Error;

    /// A small "mechanism": m = 4 coordinates, c = 1 constraint coupling q0 and q2, `K` dense
    /// in the first 3 coordinates. Its `J` is formed densely from `A₀⁻¹` (Gauss–Jordan below)
    /// and the lifted solves are checked by their residual in the full `2m` system.
    struct Toy {
        a0: Vec<Vec<f64>>,
        k_q: Vec<Vec<f64>>,
        k_v: Vec<Vec<f64>>,
    }

    impl Toy {
        fn pattern(&self) -> LiftedPattern {
            let dim = self.a0.len();
            let (mut col_start, mut row) = (vec![0], vec![]);
            for j in 0..dim {
                for i in 0..dim {
                    if self.a0[i][j] != 0.0 || (j < 4 && (self.k_q[i][j] != 0.0 || self.k_v[i][j] != 0.0)) {
                        row.push(i);
                    }
                }
                col_start.push(row.len());
            }
            LiftedPattern { coords: 4, dim, col_start, row, stiff_coords: 3 }
        }
    }

    impl OdeSystem for Toy {
        fn dim(&self) -> usize {
            8
        }
        fn rhs(&mut self, _: f64, _: &[f64], _: &mut [f64]) -> Result<(), Error> {
            Ok(())
        }
        fn output(&mut self, _: f64, _: &[f64]) -> Result<(), Error> {
            Ok(())
        }
        fn lifted_jacobian(&mut self, _: f64, _: &[f64], _: bool, a0: &mut [f64], k_q: &mut [f64], k_v: &mut [f64]) -> Result<usize, Error> {
            let p = self.pattern();
            for j in 0..p.dim {
                for k in p.col_start[j]..p.col_start[j + 1] {
                    let i = p.row[k];
                    a0[k] = self.a0[i][j];
                    (k_q[k], k_v[k]) = if j < 4 { (self.k_q[i][j], self.k_v[i][j]) } else { (0.0, 0.0) };
                }
            }
            Ok(0)
        }
    }

    fn inverse(a: &[Vec<f64>]) -> Vec<Vec<f64>> {
        let n = a.len();
        let mut m: Vec<Vec<f64>> = a.iter().enumerate().map(|(i, r)| r.iter().copied().chain((0..n).map(|j| if i == j { 1.0 } else { 0.0 })).collect()).collect();
        for c in 0..n {
            let p = (c..n).max_by(|&x, &y| m[x][c].abs().total_cmp(&m[y][c].abs())).unwrap();
            m.swap(c, p);
            let d = m[c][c];
            m[c].iter_mut().for_each(|v| *v /= d);
            for r in 0..n {
                if r != c {
                    let f = m[r][c];
                    let pivot = m[c].clone();
                    m[r].iter_mut().zip(&pivot).for_each(|(v, p)| *v -= f * p);
                }
            }
        }
        m.into_iter().map(|r| r[n..].to_vec()).collect()
    }

    /// The lifted real and complex solves satisfy `(σI − J) x = r` for the dense
    /// `J = [[0, I], [a_q, a_v]]`, `[a_q a_v] = [I 0] A₀⁻¹ [K_q K_v]` (with constraint rows in `K`,
    /// as RODAS4's exact Jacobian has), to round-off.
    #[test]
    fn lifted_solves_satisfy_the_full_systems() {
        let mut a0 = vec![vec![0.0; 5]; 5];
        for (i, m) in [2.0, 2.0, 0.5, 1.5].iter().enumerate() {
            a0[i][i] = *m;
        }
        (a0[4][0], a0[4][2], a0[0][4], a0[2][4]) = (1.0, -0.7, 1.0, -0.7);
        let mut seed = 3u64;
        let mut rnd = move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        let k_q: Vec<Vec<f64>> = (0..5).map(|i| (0..4).map(|j| if j < 3 && i != 3 { 400.0 * rnd() } else { 0.0 }).collect()).collect();
        let k_v: Vec<Vec<f64>> = (0..5).map(|i| (0..4).map(|j| if j < 3 && i != 3 { 20.0 * rnd() } else { 0.0 }).collect()).collect();
        let mut toy = Toy { a0: a0.clone(), k_q: k_q.clone(), k_v: k_v.clone() };
        let inv = inverse(&a0);
        let (m, n) = (4, 8);
        let a_x = |k: &Vec<Vec<f64>>| -> Vec<Vec<f64>> { (0..m).map(|i| (0..m).map(|j| (0..5).map(|l| inv[i][l] * k[l][j]).sum()).collect()).collect() };
        let (a_q, a_v) = (a_x(&k_q), a_x(&k_v));
        let j_times = |x: &[f64]| -> Vec<f64> {
            let mut out = vec![0.0; n];
            for i in 0..m {
                out[i] = x[m + i];
                out[m + i] = (0..m).map(|j| a_q[i][j] * x[j] + a_v[i][j] * x[m + j]).sum();
            }
            out
        };
        let mut lifted = Lifted::new(toy.pattern(), true);
        lifted.update(&mut toy, 0.0, &[0.0; 8], true).unwrap();
        let (sigma, a, b) = (3.7, 2.9, 1.8);
        lifted.factor_real(sigma);
        lifted.factor_complex(a, b);
        let r: Vec<f64> = (0..n).map(|_| rnd()).collect();
        let mut x = r.clone();
        lifted.solve_real(&mut x);
        let jx = j_times(&x);
        for i in 0..n {
            assert!((sigma * x[i] - jx[i] - r[i]).abs() < 1e-12, "real row {i}: {}", sigma * x[i] - jx[i] - r[i]);
        }
        let (rr, ri): (Vec<f64>, Vec<f64>) = ((0..n).map(|_| rnd()).collect(), (0..n).map(|_| rnd()).collect());
        let (mut xr, mut xi) = (rr.clone(), ri.clone());
        lifted.solve_complex(&mut xr, &mut xi);
        let (jr, ji) = (j_times(&xr), j_times(&xi));
        for i in 0..n {
            assert!((a * xr[i] - b * xi[i] - jr[i] - rr[i]).abs() < 1e-12, "complex row {i} (real part)");
            assert!((a * xi[i] + b * xr[i] - ji[i] - ri[i]).abs() < 1e-12, "complex row {i} (imaginary part)");
        }
    }
}
