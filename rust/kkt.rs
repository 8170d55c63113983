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
//! body contribute. All storage (the matrix, the right-hand side and faer's scratch stack) is
//! allocated once in [`KktSolver::new`]; [`KktSolver::solve`] allocates nothing.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt;
use faer::{Mat, Par};

use crate::constraints::JacRow;

/// Preallocated workspace and static sparsity structure of one model's KKT system.
pub struct KktSolver {
    rows: usize,
    /// 1/m, 1/m, 1/J per body.
    inv_mass: Vec<f64>,
    /// For each body, the (row, slot) pairs of Jacobian rows that touch it (CSR layout).
    body_start: Vec<usize>,
    body_rows: Vec<(u32, u8)>,
    s: Mat<f64>,
    rhs: Mat<f64>,
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
        let req = llt::factor::cholesky_in_place_scratch::<f64>(rows, Par::Seq, Default::default())
            .or(llt::solve::solve_in_place_scratch::<f64>(rows, 1, Par::Seq));
        KktSolver {
            rows,
            w: vec![0.0; inv_mass.len()],
            inv_mass,
            body_start,
            body_rows,
            s: Mat::zeros(rows, rows),
            rhs: Mat::zeros(rows, 1),
            mem: MemBuffer::new(req),
        }
    }

    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Solve for `qdd` (generalised accelerations) and `lambda` (multipliers) given the Jacobian
    /// rows, the generalised forces `force` and the constraint right-hand side `c`
    /// (= γ − 2αΦ̇ − β²Φ). Returns the index of a non-positive pivot if `S` is singular.
    pub fn solve(&mut self, jac: &[JacRow], force: &[f64], c: &[f64], qdd: &mut [f64], lambda: &mut [f64]) -> Result<(), usize> {
        let n = self.inv_mass.len();
        for i in 0..n {
            self.w[i] = self.inv_mass[i] * force[i];
        }
        if self.rows == 0 {
            qdd[..n].copy_from_slice(&self.w);
            return Ok(());
        }
        // Right-hand side Φq M⁻¹ g − c.
        for (r, row) in jac.iter().enumerate() {
            self.rhs[(r, 0)] = row.dot(&self.w) - c[r];
        }
        // Lower triangle of S = Φq M⁻¹ Φqᵀ.
        for j in 0..self.rows {
            for i in j..self.rows {
                self.s[(i, j)] = 0.0;
            }
        }
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
                    let (i, j) = if r1 >= r2 { (r1, r2) } else { (r2, r1) };
                    self.s[(i as usize, j as usize)] += v;
                }
            }
        }
        let mut stack = MemStack::new(&mut self.mem);
        llt::factor::cholesky_in_place(self.s.as_mut(), Default::default(), Par::Seq, &mut stack, Default::default())
            .map_err(|e| match e {
                llt::factor::LltError::NonPositivePivot { index } => index,
            })?;
        llt::solve::solve_in_place(self.s.as_ref(), self.rhs.as_mut(), Par::Seq, &mut stack);
        for r in 0..self.rows {
            lambda[r] = self.rhs[(r, 0)];
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
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
