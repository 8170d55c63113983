//! A sparse LU of a square matrix whose pattern is fixed for a run (`lifted.rs`'s Newton
//! matrices), real or complex ([`SparseLu`]).
//!
//! Once per run: a fill-reducing column order (approximate minimum degree on the pattern of
//! `A + Aᵀ`; the lifted matrices are structurally symmetric). Per matrix, a *refactorisation*:
//! the values of `L` and `U` recomputed left-looking on the pattern and with the row pivots of the
//! last full factorisation — no graph search, no pivot search, no allocation — as KLU's
//! `klu_refactor` does for the matrices of a circuit simulator's Newton iterations. A pivot that
//! has become small against the column it divides (below [`PIVOT_TOLERANCE`] of its largest
//! entry) sends the matrix to a full factorisation, faer's left-looking (Gilbert–Peierls) LU
//! with partial pivoting, whose pivots and pattern the next refactorisations then follow. Only a
//! full factorisation can allocate, and only when its pivots need more fill than any before.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::perm::PermRef;
use faer::sparse::linalg::amd;
use faer::sparse::linalg::lu::simplicial::{factorize_simplicial_numeric_lu, factorize_simplicial_numeric_lu_scratch, SimplicialLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::traits::ComplexField;

/// A refactorised pivot smaller than this fraction of the largest entry below it in its column
/// sends the matrix to a full factorisation with partial pivoting (a growth of the factors by at
/// most 1/0.01 per elimination step, as threshold pivoting allows).
const PIVOT_TOLERANCE: f64 = 0.01;

/// The scalars the LU runs on: `f64` (RODAS4, RADAU5's real system) and `faer::c64` (RADAU5's
/// complex one).
pub(super) trait Scalar: ComplexField + Copy + std::ops::Mul<Output = Self> + std::ops::Sub<Output = Self> + std::ops::SubAssign + PartialEq {
    const ZERO: Self;
    fn magnitude(self) -> f64;
    fn inverse(self) -> Self;
}

impl Scalar for f64 {
    const ZERO: Self = 0.0;
    fn magnitude(self) -> f64 {
        self.abs()
    }
    fn inverse(self) -> Self {
        1.0 / self
    }
}

impl Scalar for faer::c64 {
    const ZERO: Self = faer::c64::new(0.0, 0.0);
    fn magnitude(self) -> f64 {
        self.re.abs() + self.im.abs()
    }
    fn inverse(self) -> Self {
        faer::c64::new(1.0, 0.0) / self
    }
}

/// The LU `P A Q = L U` of a sparse square matrix with a fixed pattern (column-compressed, row
/// indices ascending in each column): `Q` the column order, `P` the row pivots.
pub(super) struct SparseLu<T: Scalar> {
    n: usize,
    col_start: Vec<usize>,
    row: Vec<usize>,
    /// The column order (`col_perm[j]`: the column of A eliminated at step j) and its inverse.
    col_perm: Vec<usize>,
    col_perm_inv: Vec<usize>,
    /// The row pivots of the last full factorisation (`row_perm[k]`: the row of A eliminated at
    /// step k) and their inverse.
    row_perm: Vec<usize>,
    row_perm_inv: Vec<usize>,
    /// `L` below its unit diagonal and `U` above its diagonal, by columns, in step indices;
    /// `U`'s entries of a column in the order the elimination needs them (topological).
    l_start: Vec<usize>,
    l_row: Vec<usize>,
    l_val: Vec<T>,
    u_start: Vec<usize>,
    u_row: Vec<usize>,
    u_val: Vec<T>,
    /// `1/U[j, j]`.
    inv_diag: Vec<T>,
    /// Whether the factors above belong to the last matrix given.
    factored: bool,
    /// Full factorisations so far (the first included).
    pub(super) full: usize,
    /// Dense work vector (zero between uses).
    work: Vec<T>,
    faer_lu: SimplicialLu<usize, T>,
    faer_mem: MemBuffer,
}

impl<T: Scalar> SparseLu<T> {
    /// The column order for the `n × n` pattern (`col_start` of length `n + 1`, then the row
    /// indices of each column, ascending). Panics on a malformed pattern (a programming error of
    /// the caller, not of the user's model).
    pub(super) fn new(n: usize, col_start: Vec<usize>, row: Vec<usize>) -> Self {
        let pattern = SymbolicSparseColMatRef::new_checked(n, n, &col_start, None, &row);
        let (mut col_perm, mut col_perm_inv) = (vec![0usize; n], vec![0usize; n]);
        let mut mem = MemBuffer::new(amd::order_scratch::<usize>(n, row.len()));
        amd::order(&mut col_perm, &mut col_perm_inv, pattern, amd::Control::default(), MemStack::new(&mut mem)).expect("an ordering of a valid pattern");
        SparseLu {
            n,
            col_start,
            row,
            col_perm,
            col_perm_inv,
            row_perm: vec![0; n],
            row_perm_inv: vec![0; n],
            l_start: vec![0; n + 1],
            l_row: Vec::new(),
            l_val: Vec::new(),
            u_start: vec![0; n + 1],
            u_row: Vec::new(),
            u_val: Vec::new(),
            inv_diag: vec![T::ZERO; n],
            factored: false,
            full: 0,
            work: vec![T::ZERO; n],
            faer_lu: SimplicialLu::new(),
            faer_mem: MemBuffer::new(factorize_simplicial_numeric_lu_scratch::<usize, T>(n, n)),
        }
    }

    /// Factorise the matrix whose entries on the pattern are `values`: refactorised on the last
    /// pivots, or in full where they no longer hold. Returns `false` when it is structurally
    /// singular; a numerically singular one gives non-finite solves, which the steppers treat
    /// as a failed step.
    pub(super) fn factor(&mut self, values: &[T]) -> bool {
        if self.full > 0 && self.refactor(values) {
            self.factored = true;
            return true;
        }
        self.factored = self.factor_full(values);
        self.factored
    }

    /// The values of `L` and `U` on the pattern and pivots of the last full factorisation;
    /// `false` (factors unusable) when a pivot falls below the tolerance.
    fn refactor(&mut self, values: &[T]) -> bool {
        let x = &mut self.work;
        for j in 0..self.n {
            let c = self.col_perm[j];
            for k in self.col_start[c]..self.col_start[c + 1] {
                x[self.row_perm_inv[self.row[k]]] = values[k];
            }
            let (us, ue) = (self.u_start[j], self.u_start[j + 1]);
            for p in us..ue {
                let k = self.u_row[p];
                let xk = x[k];
                self.u_val[p] = xk;
                x[k] = T::ZERO;
                if xk != T::ZERO {
                    for q in self.l_start[k]..self.l_start[k + 1] {
                        let v = self.l_val[q] * xk;
                        x[self.l_row[q]] -= v;
                    }
                }
            }
            let pivot = x[j];
            x[j] = T::ZERO;
            let (ls, le) = (self.l_start[j], self.l_start[j + 1]);
            let largest = self.l_row[ls..le].iter().fold(0.0f64, |m, &r| m.max(x[r].magnitude()));
            if !(pivot.magnitude() >= PIVOT_TOLERANCE * largest) || pivot == T::ZERO {
                x.fill(T::ZERO); // clean for the next use
                return false;
            }
            let inv = pivot.inverse();
            self.inv_diag[j] = inv;
            for q in ls..le {
                let r = self.l_row[q];
                self.l_val[q] = x[r] * inv;
                x[r] = T::ZERO;
            }
        }
        true
    }

    /// faer's LU with partial pivoting, its factors copied into this one's storage.
    fn factor_full(&mut self, values: &[T]) -> bool {
        let n = self.n;
        let a = SparseColMatRef::new(SymbolicSparseColMatRef::new_checked(n, n, &self.col_start, None, &self.row), values);
        let col_perm = PermRef::new_checked(&self.col_perm, &self.col_perm_inv, n);
        let mut stack = MemStack::new(&mut self.faer_mem);
        if factorize_simplicial_numeric_lu(&mut self.row_perm, &mut self.row_perm_inv, &mut self.faer_lu, a, col_perm, &mut stack).is_err() {
            return false;
        }
        self.full += 1;
        // L: the unit diagonal is each column's first entry; U: the diagonal its last.
        let l = self.faer_lu.l_factor_unsorted();
        let u = self.faer_lu.u_factor_unsorted();
        self.l_row.clear();
        self.l_val.clear();
        self.u_row.clear();
        self.u_val.clear();
        for j in 0..n {
            let (rows, vals) = (l.row_idx_of_col_raw(j), l.val_of_col(j));
            self.l_row.extend_from_slice(&rows[1..]);
            self.l_val.extend_from_slice(&vals[1..]);
            self.l_start[j + 1] = self.l_row.len();
            let (rows, vals) = (u.row_idx_of_col_raw(j), u.val_of_col(j));
            let last = rows.len() - 1;
            self.u_row.extend_from_slice(&rows[..last]);
            self.u_val.extend_from_slice(&vals[..last]);
            self.u_start[j + 1] = self.u_row.len();
            self.inv_diag[j] = vals[last].inverse();
        }
        if self.full == 1 {
            // Room for twice the first fill: a later pivot order that needs more (rare) then
            // still allocates nothing here (faer's own storage grows by doubling, alike).
            self.l_row.reserve(self.l_row.len());
            self.l_val.reserve(self.l_val.len());
            self.u_row.reserve(self.u_row.len());
            self.u_val.reserve(self.u_val.len());
        }
        true
    }

    /// `x ← A⁻¹ x` with the last factors (`x` of length `n`); NaN everywhere if the last
    /// factorisation failed.
    pub(super) fn solve(&mut self, x: &mut [T]) {
        if !self.factored {
            x.fill(T::nan_impl());
            return;
        }
        let w = &mut self.work;
        for (k, &r) in self.row_perm.iter().enumerate() {
            w[k] = x[r];
        }
        for j in 0..self.n {
            let wj = w[j];
            if wj != T::ZERO {
                for q in self.l_start[j]..self.l_start[j + 1] {
                    let v = self.l_val[q] * wj;
                    w[self.l_row[q]] -= v;
                }
            }
        }
        for j in (0..self.n).rev() {
            let wj = w[j] * self.inv_diag[j];
            w[j] = wj;
            if wj != T::ZERO {
                for p in self.u_start[j]..self.u_start[j + 1] {
                    let v = self.u_val[p] * wj;
                    w[self.u_row[p]] -= v;
                }
            }
        }
        for (j, &c) in self.col_perm.iter().enumerate() {
            x[c] = w[j];
            w[j] = T::ZERO;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::SparseLu;
    use faer::c64;

    /// A random structurally symmetric pattern (a band and a few far entries, one structurally
    /// zero diagonal block as in a KKT matrix) with values `f(seed)`.
    fn matrix(n: usize, seed: u64) -> (Vec<usize>, Vec<usize>, Vec<f64>) {
        let mut s = seed;
        let mut rnd = move || {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        let (mut col_start, mut row, mut val) = (vec![0], vec![], vec![]);
        for j in 0..n {
            for i in 0..n {
                let near = i.abs_diff(j) <= 2 || (i + j) % 7 == 0;
                let zero_diag = i == j && j >= n - 3;
                if near && !zero_diag {
                    row.push(i);
                    val.push(if i == j { 4.0 + rnd() } else { rnd() });
                }
            }
            col_start.push(row.len());
        }
        (col_start, row, val)
    }

    fn residual<T: super::Scalar>(n: usize, col_start: &[usize], row: &[usize], val: &[T], x: &[T], b: &[T]) -> f64 {
        let mut r: Vec<T> = b.to_vec();
        for j in 0..n {
            for k in col_start[j]..col_start[j + 1] {
                r[row[k]] -= val[k] * x[j];
            }
        }
        r.iter().fold(0.0, |m, v| m.max(v.magnitude()))
    }

    /// Full factorisation, then refactorisations on its pivots for changed values, real and
    /// complex, solve to round-off; a refactorisation whose pivot collapses falls back to a
    /// full one (counted), and still solves.
    #[test]
    fn refactorisations_solve_and_fall_back_when_a_pivot_collapses() {
        let n = 40;
        let (col_start, row, val) = matrix(n, 5);
        let mut lu = SparseLu::<f64>::new(n, col_start.clone(), row.clone());
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
        for (step, scale) in [1.0, 1.1, 0.9, 1.3].iter().enumerate() {
            let v: Vec<f64> = val.iter().enumerate().map(|(k, x)| x * if k % 3 == 0 { *scale } else { 1.0 }).collect();
            assert!(lu.factor(&v));
            assert_eq!(lu.full, 1, "step {step}: refactorised");
            let mut x = b.clone();
            lu.solve(&mut x);
            assert!(residual(n, &col_start, &row, &v, &x, &b) < 1e-12, "step {step}");
        }
        // Zero the entry the first step pivoted on: the old pivot is gone.
        let (c0, p0) = (lu.col_perm[0], lu.row_perm[0]);
        let mut v = val.clone();
        for k in col_start[c0]..col_start[c0 + 1] {
            if row[k] == p0 {
                v[k] = 0.0;
            }
        }
        assert!(lu.factor(&v));
        assert_eq!(lu.full, 2, "a collapsed pivot is not refactorised");
        let mut x = b.clone();
        lu.solve(&mut x);
        assert!(residual(n, &col_start, &row, &v, &x, &b) < 1e-11);
        // Complex.
        let mut lu = SparseLu::<c64>::new(n, col_start.clone(), row.clone());
        let bc: Vec<c64> = b.iter().map(|&v| c64::new(v, -0.5 * v)).collect();
        for scale in [1.0, 0.8] {
            let v: Vec<c64> = val.iter().enumerate().map(|(k, &x)| c64::new(x * scale, if k % 2 == 0 { 0.3 } else { -0.2 })).collect();
            assert!(lu.factor(&v));
            let mut x = bc.clone();
            lu.solve(&mut x);
            assert!(residual(n, &col_start, &row, &v, &x, &bc) < 1e-12);
        }
        assert_eq!(lu.full, 1);
    }
}
