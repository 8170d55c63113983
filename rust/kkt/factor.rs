//! The numeric half of the KKT solve (docs/physics.md §1): S = L D Lᵀ factorised in place over
//! the pattern of `ordering.rs` (by a tape of multiply-subtracts found once, or an up-looking
//! loop), and the triangular solves with it.

use super::ordering::LowerPattern;

/// `v[i]` without the bounds check, for the hot loops of the numeric factorisation and solves,
/// whose index lists are built once in [`super::KktSolver::new`] and [`SparseFactor::new`] from the
/// pattern and never change: every index is below the length of the array it indexes (checked
/// in debug builds, where the tests run every index list of random mechanisms). On the nine-bar
/// the bounds checks and the loop set-up of rows of two or three entries cost more than the
/// arithmetic.
#[inline(always)]
pub(super) fn at<T: Copy>(v: &[T], i: usize) -> T {
    debug_assert!(i < v.len());
    // SAFETY: `i < v.len()` (the index lists' invariant above).
    unsafe { *v.get_unchecked(i) }
}

/// A mutable reference to `v[i]`, as [`at`].
#[inline(always)]
pub(super) fn at_mut<T>(v: &mut [T], i: usize) -> &mut T {
    debug_assert!(i < v.len());
    // SAFETY: as `at`.
    unsafe { v.get_unchecked_mut(i) }
}

/// The numeric factorisation as a list of multiply-subtracts, found once from the pattern: for
/// each entry `(i, k)` of L, the pairs `(a, b)` of storage indices with `a = (i, t)`,
/// `b = (k, t)` over the columns `t < k` that rows i and k share (`y_ik = S_ik − Σ y_it L_kt`).
/// The factorisation then runs without the scatter vector and without the products with zeros
/// that the up-looking loop makes where row k has a column row i lacks. Its length is the
/// factorisation's multiply count (nine-bar: 42; a chain: O(n)).
#[derive(Debug, Clone, Default)]
pub(super) struct Tape {
    /// `pairs[start[s]..start[s + 1]]` belong to the entry at storage index s.
    pub(super) start: Vec<u32>,
    pub(super) pairs: Vec<[u32; 2]>,
}

/// For the entry at storage index `s` (row i, column k) of `pattern`: `emit(a, b)` for each
/// column t < k of both rows, `a` and `b` the storage indices of (i, t) and (k, t); both rows are
/// sorted ascending, so this is a merge.
fn shared_columns(pattern: &LowerPattern, i: usize, s: usize, mut emit: impl FnMut(u32, u32)) {
    let k = pattern.cols[s] as usize;
    let (mut a, mut b) = (pattern.start[i], pattern.start[k]);
    let b_end = pattern.start[k + 1];
    while a < s && b < b_end {
        match pattern.cols[a].cmp(&pattern.cols[b]) {
            std::cmp::Ordering::Less => a += 1,
            std::cmp::Ordering::Greater => b += 1,
            std::cmp::Ordering::Equal => {
                emit(a as u32, b as u32);
                a += 1;
                b += 1;
            }
        }
    }
}

/// Above this many multiply-subtracts (a mechanism whose S is nearly dense: 16 bytes each)
/// the factorisation keeps the up-looking loop, which needs no storage beyond L.
const TAPE_MAX: usize = 1 << 21;

impl Tape {
    /// The tape of `pattern`, or `None` if it would be longer than `TAPE_MAX`.
    fn new(pattern: &LowerPattern) -> Option<Self> {
        let n = pattern.start.len() - 1;
        let mut count = 0usize;
        for i in 0..n {
            for s in pattern.start[i]..pattern.start[i + 1] {
                shared_columns(pattern, i, s, |_, _| count += 1);
            }
            if count > TAPE_MAX {
                return None;
            }
        }
        let mut tape = Tape { start: Vec::with_capacity(pattern.len() + 1), pairs: Vec::with_capacity(count) };
        tape.start.push(0);
        for i in 0..n {
            for s in pattern.start[i]..pattern.start[i + 1] {
                let pairs = &mut tape.pairs;
                shared_columns(pattern, i, s, |a, b| pairs.push([a, b]));
                tape.start.push(tape.pairs.len() as u32);
            }
        }
        Some(tape)
    }
}

/// S and then its factors `S = L D Lᵀ` (L unit lower triangular), stored row by row:
/// `vals[pattern.start[i]..]` holds the entries of row i at the columns `pattern.row(i)`,
/// `vals[nnz + i]` the diagonal of S and then the pivot `D[i]` (one array, so that assembling S
/// needs no branch between diagonal and off-diagonal entries). Factorised up-looking (row i
/// solves `L₁₁ D₁ lᵢ = sᵢ` by sparse forward substitution), from the [`Tape`] where there is
/// one, else through a dense scatter vector that is kept zero between rows; a chain of n bodies
/// costs O(n) either way. LDLᵀ rather than LLᵀ: no square roots, and with `1/D` kept, one
/// division per row; the substitutions, a chain of dependent operations, only multiply and
/// subtract.
#[derive(Debug, Clone, Default)]
pub(super) struct SparseFactor {
    pub(super) vals: Vec<f64>,
    /// Structural non-zeros of L below the diagonal: where the diagonal starts in `vals`.
    pub(super) nnz: usize,
    /// `1/D[i]` once row i is factorised.
    pub(super) inv_diag: Vec<f64>,
    /// Scatter workspace, all zeros between calls (the loop without a tape).
    x: Vec<f64>,
    pub(super) tape: Option<Tape>,
}

impl SparseFactor {
    /// Storage for the factor of `pattern`, with a tape unless `with_tape` is false or it would be
    /// too long.
    pub(super) fn new(pattern: &LowerPattern, with_tape: bool) -> Self {
        let n = pattern.start.len() - 1;
        let tape = if with_tape { Tape::new(pattern) } else { None };
        SparseFactor { vals: vec![0.0; pattern.len() + n], nnz: pattern.len(), inv_diag: vec![0.0; n], x: vec![0.0; n], tape }
    }

    /// Factorise in place; `Err(i)` for a non-positive pivot at row i. (`#[inline]`: its one
    /// caller, `KktSolver::factor`, is hot; left to the codegen units' partition it was inlined or
    /// not as unrelated code changed, ±0.2 % of a lubricated cycle's instructions.)
    #[inline]
    pub(super) fn factor(&mut self, pattern: &LowerPattern) -> Result<(), usize> {
        if self.tape.is_some() {
            return self.factor_taped(pattern);
        }
        let n = self.inv_diag.len();
        let nnz = self.nnz;
        for i in 0..n {
            let range = pattern.start[i]..pattern.start[i + 1];
            // y_ik = D_k L_ik = S_ik − Σ_t L_kt y_it, then D_i = S_ii − Σ_k L_ik y_ik.
            let mut d = self.vals[nnz + i];
            for s in range.clone() {
                self.x[pattern.cols[s] as usize] = self.vals[s];
            }
            for s in range.clone() {
                let k = pattern.cols[s] as usize;
                let mut v = self.x[k];
                for t in pattern.start[k]..pattern.start[k + 1] {
                    v -= self.vals[t] * self.x[pattern.cols[t] as usize];
                }
                self.x[k] = v;
                d -= v * v * self.inv_diag[k];
            }
            for s in range {
                let k = pattern.cols[s] as usize;
                self.vals[s] = self.x[k] * self.inv_diag[k];
                self.x[k] = 0.0;
            }
            self.set_pivot(i, d)?;
        }
        Ok(())
    }

    /// [`SparseFactor::factor`] from the tape: the same operations in the same order, run with
    /// two running indices (the entries of L and the tape's pairs are stored in the order they
    /// are computed).
    fn factor_taped(&mut self, pattern: &LowerPattern) -> Result<(), usize> {
        let Some(tape) = &self.tape else { unreachable!("factor_taped without a tape") };
        let (n, nnz) = (self.inv_diag.len(), self.nnz);
        let vals = &mut self.vals[..];
        let (mut s, mut t) = (0, 0);
        for i in 0..n {
            let (first, end) = (s, at(&pattern.start, i + 1));
            // y_ik = D_k L_ik = S_ik − Σ_t L_kt y_it ...
            while s < end {
                let pairs_end = at(&tape.start, s + 1) as usize;
                let mut v = at(vals, s);
                while t < pairs_end {
                    let [a, b] = at(&tape.pairs, t);
                    v -= at(vals, a as usize) * at(vals, b as usize);
                    t += 1;
                }
                *at_mut(vals, s) = v;
                s += 1;
            }
            // ... then L_ik = y_ik / D_k and D_i = S_ii − Σ_k L_ik y_ik.
            let mut d = at(vals, nnz + i);
            for e in first..end {
                let dk = at(&self.inv_diag, at(&pattern.cols, e) as usize);
                let v = at_mut(vals, e);
                d -= *v * *v * dk;
                *v *= dk;
            }
            if !(d > 0.0) {
                return Err(i);
            }
            *at_mut(vals, nnz + i) = d;
            *at_mut(&mut self.inv_diag, i) = 1.0 / d;
        }
        Ok(())
    }

    /// Store the pivot `D[i] = d`, or `Err(i)` if it is not positive.
    fn set_pivot(&mut self, i: usize, d: f64) -> Result<(), usize> {
        if !(d > 0.0) {
            return Err(i);
        }
        self.vals[self.nnz + i] = d;
        self.inv_diag[i] = 1.0 / d;
        Ok(())
    }

    /// `L D Lᵀ x = rhs` in place, by forward and backward substitution over the non-zeros of L.
    pub(super) fn solve(&self, pattern: &LowerPattern, rhs: &mut [f64]) {
        let n = self.inv_diag.len();
        let rhs = &mut rhs[..n];
        let (l, cols) = (&self.vals[..self.nnz], &pattern.cols[..self.nnz]);
        // Rows of L follow each other in storage: one running index, no per-row slicing.
        let mut s = 0;
        for i in 0..n {
            let end = at(&pattern.start, i + 1);
            let mut v = rhs[i];
            while s < end {
                v -= at(l, s) * at(rhs, at(cols, s) as usize);
                s += 1;
            }
            rhs[i] = v;
        }
        for (r, d) in rhs.iter_mut().zip(&self.inv_diag) {
            *r *= d;
        }
        // Lᵀ x = D⁻¹ y: once x_i is known, remove its share from the unknowns of row i's columns.
        for i in (0..n).rev() {
            let start = at(&pattern.start, i);
            let xi = rhs[i];
            while s > start {
                s -= 1;
                *at_mut(rhs, at(cols, s) as usize) -= at(l, s) * xi;
            }
        }
    }
}
