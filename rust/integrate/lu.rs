//! Dense LU factorisation and solves for the implicit methods' iteration matrices, allocated
//! once per run: [`Lu`] for a real matrix (RODAS4's `I/(hγ) − J`, RADAU5's real Newton
//! matrix), [`ComplexLu`] for RADAU5's complex one. Up to [`SMALL_LU`] rows the factorisation is
//! this file's own right-looking elimination with partial pivoting (LAPACK's `getf2`; in complex
//! arithmetic, Hairer's `DECC`); larger matrices go to faer's blocked partial-pivoting LU.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::lu::partial_pivoting::{factor as lu_factor, solve as lu_solve};
use faer::perm::PermRef;
use faer::{Mat, MatMut, Par};

/// Largest matrix factorised by [`Lu`]'s own loops; larger ones go to faer's blocked LU. The
/// Newton matrices of a mechanism are small after the structured reduction (nine-bar: 12 rows, real and complex),
/// where a plain right-looking elimination beats a blocked one's set-up.
const SMALL_LU: usize = 64;

/// An LU-factorised real matrix (RODAS4's `E = I/(hγ) − J`, RADAU5's `σ₁I − W`) and its
/// preallocated storage.
pub(super) struct Lu {
    /// Matrices of size ≤ [`SMALL_LU`]: the factors in place, column-major `k × k`, the row
    /// swaps in order and `1/U[j, j]`.
    small: Option<Vec<f64>>,
    piv: Vec<usize>,
    inv_diag: Vec<f64>,
    /// Larger matrices: faer's storage.
    e: Mat<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    rhs: Mat<f64>,
    mem: MemBuffer,
}

impl Lu {
    pub(super) fn new(n: usize) -> Self {
        if n <= SMALL_LU {
            return Lu {
                small: Some(vec![0.0; n * n]),
                piv: vec![0; n],
                inv_diag: vec![0.0; n],
                e: Mat::zeros(0, 0),
                perm: Vec::new(),
                perm_inv: Vec::new(),
                rhs: Mat::zeros(0, 0),
                mem: MemBuffer::new(StackReq::EMPTY),
            };
        }
        let req = StackReq::any_of(&[
            lu_factor::lu_in_place_scratch::<usize, f64>(n, n, Par::Seq, Default::default()),
            lu_solve::solve_in_place_scratch::<usize, f64>(n, 1, Par::Seq),
        ]);
        Lu {
            small: None,
            piv: Vec::new(),
            inv_diag: Vec::new(),
            e: Mat::zeros(n, n),
            perm: vec![0; n],
            perm_inv: vec![0; n],
            rhs: Mat::zeros(n, 1),
            mem: MemBuffer::new(req),
        }
    }

    /// Factorise `fac·I − J` (`J` of the size given to [`Lu::new`]).
    pub(super) fn factor(&mut self, jac: &Mat<f64>, fac: f64) {
        let n = jac.nrows();
        self.factor_with(n, |mut e| {
            for j in 0..n {
                for i in 0..n {
                    e[(i, j)] = -jac[(i, j)];
                }
                e[(j, j)] += fac;
            }
        });
    }

    /// Factorise the leading `k × k` block (`k` ≤ the size given to [`Lu::new`]) that `fill`
    /// writes (every entry of it must be written); [`Lu::solve`] then takes vectors of length `k`.
    /// The storage of the full size covers any smaller `k`, so this allocates nothing.
    pub(super) fn factor_with(&mut self, k: usize, fill: impl FnOnce(MatMut<'_, f64>)) {
        if let Some(a) = self.small.as_mut() {
            let a = &mut a[..k * k];
            fill(MatMut::from_column_major_slice_mut(a, k, k));
            small_lu(a, k, &mut self.piv[..k], &mut self.inv_diag[..k]);
            return;
        }
        let mut e = self.e.as_mut().submatrix_mut(0, 0, k, k);
        fill(e.as_mut());
        let mut stack = MemStack::new(&mut self.mem);
        lu_factor::lu_in_place(e, &mut self.perm[..k], &mut self.perm_inv[..k], Par::Seq, &mut stack, Default::default());
    }

    /// `x ← E⁻¹ x` for the block last factorised (`x.len()` = its size).
    pub(super) fn solve(&mut self, x: &mut [f64]) {
        let n = x.len();
        if let Some(a) = self.small.as_ref() {
            small_lu_solve(&a[..n * n], &self.piv[..n], &self.inv_diag[..n], x);
            return;
        }
        for (i, v) in x.iter().enumerate() {
            self.rhs[(i, 0)] = *v;
        }
        let perm = PermRef::new_checked(&self.perm[..n], &self.perm_inv[..n], n);
        let mut stack = MemStack::new(&mut self.mem);
        let lu = self.e.as_ref().submatrix(0, 0, n, n);
        lu_solve::solve_in_place(lu, lu, perm, self.rhs.as_mut().subrows_mut(0, n), Par::Seq, &mut stack);
        for (i, v) in x.iter_mut().enumerate() {
            *v = self.rhs[(i, 0)];
        }
    }
}

/// The LU-factorised complex matrix `(a + ib) I − G` of RADAU5's second system, in complex
/// arithmetic (Hairer's `DECC`/`SOLC`) up to [`SMALL_LU`] rows: half the multiplications of the
/// `2k × 2k` real form `[[Re, −Im], [Im, Re]]`, which larger matrices keep for faer's blocked LU.
pub(super) struct ComplexLu {
    /// Up to [`SMALL_LU`]: the factors' real and imaginary parts in place (column-major `k × k`),
    /// the row swaps in order and `1/U[j, j]`.
    re: Vec<f64>,
    im: Vec<f64>,
    piv: Vec<usize>,
    inv_re: Vec<f64>,
    inv_im: Vec<f64>,
    /// Larger: the real form and a `2k` scratch vector.
    real_form: Option<(Lu, Vec<f64>)>,
}

impl ComplexLu {
    pub(super) fn new(n: usize) -> Self {
        if n <= SMALL_LU {
            return ComplexLu { re: vec![0.0; n * n], im: vec![0.0; n * n], piv: vec![0; n], inv_re: vec![0.0; n], inv_im: vec![0.0; n], real_form: None };
        }
        ComplexLu { re: Vec::new(), im: Vec::new(), piv: Vec::new(), inv_re: Vec::new(), inv_im: Vec::new(), real_form: Some((Lu::new(2 * n), vec![0.0; 2 * n])) }
    }

    /// Factorise the leading `k × k` block whose real and imaginary parts `fill` writes (every
    /// entry of both); [`ComplexLu::solve`] then takes vectors of length `k`. Allocates nothing.
    pub(super) fn factor_with(&mut self, k: usize, fill: impl FnOnce(MatMut<'_, f64>, MatMut<'_, f64>)) {
        if let Some((lu, _)) = self.real_form.as_mut() {
            lu.factor_with(2 * k, |e| {
                let (top, bottom) = e.split_at_row_mut(k);
                let (mut re, mut minus_im) = top.split_at_col_mut(k);
                let (mut im, mut re2) = bottom.split_at_col_mut(k);
                fill(re.as_mut(), im.as_mut());
                for j in 0..k {
                    for i in 0..k {
                        re2[(i, j)] = re[(i, j)];
                        minus_im[(i, j)] = -im[(i, j)];
                    }
                }
            });
            return;
        }
        let (re, im) = (&mut self.re[..k * k], &mut self.im[..k * k]);
        fill(MatMut::from_column_major_slice_mut(re, k, k), MatMut::from_column_major_slice_mut(im, k, k));
        small_complex_lu(re, im, k, &mut self.piv[..k], &mut self.inv_re[..k], &mut self.inv_im[..k]);
    }

    /// `(xr + i xi) ← E⁻¹ (xr + i xi)` for the block last factorised.
    pub(super) fn solve(&mut self, xr: &mut [f64], xi: &mut [f64]) {
        let k = xr.len();
        if let Some((lu, tmp)) = self.real_form.as_mut() {
            let tmp = &mut tmp[..2 * k];
            tmp[..k].copy_from_slice(xr);
            tmp[k..].copy_from_slice(xi);
            lu.solve(tmp);
            xr.copy_from_slice(&tmp[..k]);
            xi.copy_from_slice(&tmp[k..]);
            return;
        }
        let (re, im) = (&self.re[..k * k], &self.im[..k * k]);
        for (j, &p) in self.piv[..k].iter().enumerate() {
            if p != j {
                xr.swap(j, p);
                xi.swap(j, p);
            }
        }
        for j in 0..k {
            let (br, bi) = (xr[j], xi[j]);
            if br != 0.0 || bi != 0.0 {
                let col = j * k + j + 1..(j + 1) * k;
                for (((r, i), lr), li) in xr[j + 1..].iter_mut().zip(&mut xi[j + 1..]).zip(&re[col.clone()]).zip(&im[col]) {
                    *r -= lr * br - li * bi;
                    *i -= lr * bi + li * br;
                }
            }
        }
        for j in (0..k).rev() {
            let (ur, ui) = (self.inv_re[j], self.inv_im[j]);
            let (br, bi) = (xr[j], xi[j]);
            let (br, bi) = (ur * br - ui * bi, ur * bi + ui * br);
            (xr[j], xi[j]) = (br, bi);
            if br != 0.0 || bi != 0.0 {
                let col = j * k..j * k + j;
                for (((r, i), ar), ai) in xr[..j].iter_mut().zip(&mut xi[..j]).zip(&re[col.clone()]).zip(&im[col]) {
                    *r -= ar * br - ai * bi;
                    *i -= ar * bi + ai * br;
                }
            }
        }
    }
}

/// [`small_lu`] in complex arithmetic, real and imaginary parts in two arrays; the pivot is the
/// largest `|Re| + |Im|` of the column (Hairer's `DECC`). `1/U[j, j]` is non-finite for an exactly
/// singular pivot, so a solve gives non-finite values (a failed step).
fn small_complex_lu(re: &mut [f64], im: &mut [f64], k: usize, piv: &mut [usize], inv_re: &mut [f64], inv_im: &mut [f64]) {
    for j in 0..k {
        let col = j * k;
        let mut p = j;
        let mut best = re[col + j].abs() + im[col + j].abs();
        for i in j + 1..k {
            let v = re[col + i].abs() + im[col + i].abs();
            if v > best {
                (p, best) = (i, v);
            }
        }
        piv[j] = p;
        if p != j {
            for c in 0..k {
                re.swap(c * k + j, c * k + p);
                im.swap(c * k + j, c * k + p);
            }
        }
        let (ur, ui) = (re[col + j], im[col + j]);
        let den = ur * ur + ui * ui;
        let (vr, vi) = (ur / den, -ui / den);
        (inv_re[j], inv_im[j]) = (vr, vi);
        for i in j + 1..k {
            let (a, b) = (re[col + i], im[col + i]);
            (re[col + i], im[col + i]) = (a * vr - b * vi, a * vi + b * vr);
        }
        for c in j + 1..k {
            let t = c * k;
            let (fr, fi) = (re[t + j], im[t + j]);
            if fr != 0.0 || fi != 0.0 {
                for i in j + 1..k {
                    let (lr, li) = (re[col + i], im[col + i]);
                    re[t + i] -= lr * fr - li * fi;
                    im[t + i] -= lr * fi + li * fr;
                }
            }
        }
    }
}

/// `P A = L U` in place by right-looking elimination with partial pivoting (LAPACK's `getf2`):
/// `a` column-major `k × k`; `piv[j]` the row swapped with row j at step j; `inv_diag[j] = 1/U[j, j]`
/// (infinite for an exactly singular pivot, so a solve gives non-finite values, which the
/// steppers treat as a failed step).
fn small_lu(a: &mut [f64], k: usize, piv: &mut [usize], inv_diag: &mut [f64]) {
    for j in 0..k {
        let col = j * k;
        let mut p = j;
        for i in j + 1..k {
            if a[col + i].abs() > a[col + p].abs() {
                p = i;
            }
        }
        piv[j] = p;
        if p != j {
            for c in 0..k {
                a.swap(c * k + j, c * k + p);
            }
        }
        let inv = 1.0 / a[col + j];
        inv_diag[j] = inv;
        let (left, right) = a.split_at_mut(col + k);
        let lcol = &mut left[col + j + 1..col + k];
        for v in lcol.iter_mut() {
            *v *= inv;
        }
        for c in 0..k - j - 1 {
            let target = &mut right[c * k..(c + 1) * k];
            let f = target[j];
            if f != 0.0 {
                for (t, l) in target[j + 1..].iter_mut().zip(lcol.iter()) {
                    *t -= l * f;
                }
            }
        }
    }
}

/// `x ← A⁻¹ x` from the factors of [`small_lu`].
fn small_lu_solve(a: &[f64], piv: &[usize], inv_diag: &[f64], x: &mut [f64]) {
    let k = x.len();
    for (j, &p) in piv.iter().enumerate() {
        if p != j {
            x.swap(j, p);
        }
    }
    for j in 0..k {
        let xj = x[j];
        if xj != 0.0 {
            for (xi, l) in x[j + 1..].iter_mut().zip(&a[j * k + j + 1..(j + 1) * k]) {
                *xi -= l * xj;
            }
        }
    }
    for j in (0..k).rev() {
        x[j] *= inv_diag[j];
        let xj = x[j];
        if xj != 0.0 {
            for (xi, u) in x[..j].iter_mut().zip(&a[j * k..j * k + j]) {
                *xi -= u * xj;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    /// Uniform numbers in [−1, 1) from a 64-bit linear congruential generator (reproducible
    /// random matrices for the LU tests).
    fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        }
    }

    /// Both LU paths (own loops up to `SMALL_LU`, faer's above) solve `fac·I − J` to round-off,
    /// by residual, on random matrices and on one that needs row swaps (zero leading pivot), and
    /// a leading block of a larger storage solves as its own matrix.
    #[test]
    fn lu_solves_to_round_off_on_both_paths() {
        use super::{Lu, SMALL_LU};
        use faer::Mat;
        let mut rnd = uniform(11);
        for &(n, fac) in &[(1usize, 2.0), (5, 0.0), (12, 3.0), (48, 1.5), (SMALL_LU, 0.7), (SMALL_LU + 6, 0.7)] {
            let mut jac = Mat::<f64>::zeros(n, n);
            for j in 0..n {
                for i in 0..n {
                    jac[(i, j)] = rnd();
                }
            }
            if n == 5 {
                jac[(0, 0)] = 0.0; // fac = 0: the first pivot must come from another row
            }
            let mut lu = Lu::new(n);
            lu.factor(&jac, fac);
            let b: Vec<f64> = (0..n).map(|_| rnd()).collect();
            let mut x = b.clone();
            lu.solve(&mut x);
            for i in 0..n {
                let r: f64 = (0..n).map(|j| (if i == j { fac } else { 0.0 } - jac[(i, j)]) * x[j]).sum::<f64>() - b[i];
                assert!(r.abs() < 1e-11 * (1.0 + x.iter().fold(0.0f64, |m, v| m.max(v.abs()))), "n = {n}, row {i}: residual {r}");
            }
            // The leading 3 × 3 block of the same storage.
            if n >= 3 {
                lu.factor_with(3, |mut e| {
                    for j in 0..3 {
                        for i in 0..3 {
                            e[(i, j)] = if i == j { 4.0 } else { 1.0 };
                        }
                    }
                });
                let mut y = vec![6.0, 6.0, 6.0];
                lu.solve(&mut y);
                assert!(y.iter().all(|v| (v - 1.0).abs() < 1e-14), "{y:?}");
            }
        }
    }

    /// The complex LU on both paths (complex arithmetic up to `SMALL_LU`, the real form through
    /// faer above) solves `(a + ib) I − G` to round-off by residual, on random matrices, with a
    /// zero leading pivot (a row swap; removing the swap fails this) and as a leading block of a
    /// larger storage.
    #[test]
    fn complex_lu_solves_to_round_off_on_both_paths() {
        use super::{ComplexLu, SMALL_LU};
        let mut rnd = uniform(23);
        for &(n, k, a, b) in &[(1usize, 1usize, 2.0, 1.0), (5, 5, 0.0, 0.0), (12, 12, 3.0, -1.5), (24, 9, 1.5, 2.5), (SMALL_LU, SMALL_LU, 0.7, 0.3), (SMALL_LU + 6, SMALL_LU + 6, 0.7, 0.3), (SMALL_LU + 6, 10, 0.7, 0.3)] {
            let g: Vec<(f64, f64)> = (0..k * k).map(|_| (rnd(), rnd())).collect();
            let at = |i: usize, j: usize| -> (f64, f64) {
                let (gr, gi) = if n == 5 && i == 0 && j == 0 { (0.0, 0.0) } else { g[i + j * k] };
                if i == j { (a - gr, b - gi) } else { (-gr, -gi) }
            };
            let mut lu = ComplexLu::new(n);
            lu.factor_with(k, |mut re, mut im| {
                for j in 0..k {
                    for i in 0..k {
                        (re[(i, j)], im[(i, j)]) = at(i, j);
                    }
                }
            });
            let (br, bi): (Vec<f64>, Vec<f64>) = ((0..k).map(|_| rnd()).collect(), (0..k).map(|_| rnd()).collect());
            let (mut xr, mut xi) = (br.clone(), bi.clone());
            lu.solve(&mut xr, &mut xi);
            let size = xr.iter().chain(&xi).fold(1.0f64, |m, v| m.max(v.abs()));
            for i in 0..k {
                let (mut rr, mut ri) = (-br[i], -bi[i]);
                for j in 0..k {
                    let (er, ei) = at(i, j);
                    rr += er * xr[j] - ei * xi[j];
                    ri += er * xi[j] + ei * xr[j];
                }
                assert!(rr.abs() < 1e-11 * size && ri.abs() < 1e-11 * size, "n = {n}, k = {k}, row {i}: residual {rr} + {ri}i");
            }
        }
    }
}
