//! The border of the implicit methods' Newton matrices for a second-order system with a few
//! first-order states after (q, v) — y = (q, v, z), the oil temperatures of heated joints
//! (docs/physics.md §4, *Heat*) — solved by a Schur complement on z, around any solve of the
//! (q, v) core (`radau_newton.rs`' structured one; a sparse one fits the same way).
//!
//! With the Jacobian's rows `q̇ = v`, `v̇ = a(q, v, z)`, `ż = g(q, v, z)`, the system
//! `(σI − J) (x, ζ) = (r, s)` is `[[K, B], [C, D]] (x, ζ) = (r, s)`, K = σI − J_core
//! (2m × 2m), B = −(0; ∂a/∂z) (2m × k), C = −∂g/∂(q, v) (k × 2m), D = σI − ∂g/∂z (k × k).
//! With Y = K⁻¹B (k core solves when the matrix is factorised) and the Schur complement
//! S = D − C Y (k × k, factorised with partial pivoting):
//! x₀ = K⁻¹ r, ζ = S⁻¹ (s − C x₀), x = x₀ − Y ζ. The same for the complex σ₂ = a + ib.
//! k is the number of heated joints (one or two): the border costs k core solves per
//! factorisation and one k × k solve per solve.

/// The border's blocks and their factorisations (module doc).
pub(super) struct Border {
    /// m = dim(q), k = dim(z).
    m: usize,
    k: usize,
    /// ∂a/∂z: m × k, column-major.
    pub(super) a_z: Vec<f64>,
    /// ∂g/∂y: k × (2m + k), row-major.
    pub(super) g_y: Vec<f64>,
    /// Y = K⁻¹B of the real system (2m × k, column-major), and of the complex one (real and
    /// imaginary parts).
    y_real: Vec<f64>,
    y_re: Vec<f64>,
    y_im: Vec<f64>,
    /// The Schur complements, factorised in place (k × k, row-major), with their pivots.
    s_real: Vec<f64>,
    s_re: Vec<f64>,
    s_im: Vec<f64>,
    piv_real: Vec<usize>,
    piv_complex: Vec<usize>,
    /// Scratch: a right-hand side for ζ (real, imaginary).
    zr: Vec<f64>,
    zi: Vec<f64>,
}

impl Border {
    pub(super) fn new(m: usize, k: usize) -> Self {
        let n = 2 * m + k;
        Border {
            m,
            k,
            a_z: vec![0.0; m * k],
            g_y: vec![0.0; k * n],
            y_real: vec![0.0; 2 * m * k],
            y_re: vec![0.0; 2 * m * k],
            y_im: vec![0.0; 2 * m * k],
            s_real: vec![0.0; k * k],
            s_re: vec![0.0; k * k],
            s_im: vec![0.0; k * k],
            piv_real: vec![0; k],
            piv_complex: vec![0; k],
            zr: vec![0.0; k],
            zi: vec![0.0; k],
        }
    }

    /// `out = B e_c`: column `c` of B = −(0; ∂a/∂z).
    fn b_column(&self, c: usize, out: &mut [f64]) {
        let m = self.m;
        out[..m].fill(0.0);
        for (o, v) in out[m..2 * m].iter_mut().zip(&self.a_z[c * m..(c + 1) * m]) {
            *o = -v;
        }
    }


    /// Factorise the real border for σ with the core's real solve `core` (x ← K⁻¹ x, 2m long).
    pub(super) fn factor_real(&mut self, sigma: f64, mut core: impl FnMut(&mut [f64])) {
        let (m, k) = (self.m, self.k);
        let mut col = std::mem::take(&mut self.y_real);
        for c in 0..k {
            self.b_column(c, &mut col[c * 2 * m..(c + 1) * 2 * m]);
            core(&mut col[c * 2 * m..(c + 1) * 2 * m]);
        }
        self.y_real = col;
        for r in 0..k {
            let (g_x, g_z) = g_rows(&self.g_y, m, k, r);
            for c in 0..k {
                // S = σI − ∂g/∂z + ∂g/∂(q, v) Y.
                let gy: f64 = g_x.iter().zip(&self.y_real[c * 2 * m..(c + 1) * 2 * m]).map(|(g, y)| g * y).sum();
                self.s_real[r * k + c] = if r == c { sigma } else { 0.0 } - g_z[c] + gy;
            }
        }
        factor_real(&mut self.s_real, k, &mut self.piv_real);
    }

    /// Factorise the complex border for σ₂ = a + ib with the core's complex solve `core`.
    pub(super) fn factor_complex(&mut self, a: f64, b: f64, mut core: impl FnMut(&mut [f64], &mut [f64])) {
        let (m, k) = (self.m, self.k);
        let (mut re, mut im) = (std::mem::take(&mut self.y_re), std::mem::take(&mut self.y_im));
        for c in 0..k {
            let s = c * 2 * m..(c + 1) * 2 * m;
            self.b_column(c, &mut re[s.clone()]);
            im[s.clone()].fill(0.0);
            core(&mut re[s.clone()], &mut im[s]);
        }
        (self.y_re, self.y_im) = (re, im);
        for r in 0..k {
            let (g_x, g_z) = g_rows(&self.g_y, m, k, r);
            for c in 0..k {
                let s = c * 2 * m..(c + 1) * 2 * m;
                let gr: f64 = g_x.iter().zip(&self.y_re[s.clone()]).map(|(g, y)| g * y).sum();
                let gi: f64 = g_x.iter().zip(&self.y_im[s]).map(|(g, y)| g * y).sum();
                self.s_re[r * k + c] = if r == c { a } else { 0.0 } - g_z[c] + gr;
                self.s_im[r * k + c] = if r == c { b } else { 0.0 } + gi;
            }
        }
        factor_complex(&mut self.s_re, &mut self.s_im, k, &mut self.piv_complex);
    }

    /// `x ← (σI − J)⁻¹ x` (x = (q, v, z) parts, 2m + k long) with the core's real solve.
    pub(super) fn solve_real(&mut self, x: &mut [f64], mut core: impl FnMut(&mut [f64])) {
        let (m, k) = (self.m, self.k);
        let (xc, xz) = x.split_at_mut(2 * m);
        core(xc);
        // ζ = S⁻¹ (s − C x₀), C = −∂g/∂(q, v).
        for r in 0..k {
            let (g_x, _) = g_rows(&self.g_y, m, k, r);
            self.zr[r] = xz[r] + g_x.iter().zip(xc.iter()).map(|(g, v)| g * v).sum::<f64>();
        }
        solve_real(&self.s_real, k, &self.piv_real, &mut self.zr);
        for c in 0..k {
            let z = self.zr[c];
            for (v, y) in xc.iter_mut().zip(&self.y_real[c * 2 * m..(c + 1) * 2 * m]) {
                *v -= y * z;
            }
        }
        xz.copy_from_slice(&self.zr);
    }

    /// `(xr + i xi) ← (σ₂I − J)⁻¹ (xr + i xi)` with the core's complex solve.
    pub(super) fn solve_complex(&mut self, xr: &mut [f64], xi: &mut [f64], mut core: impl FnMut(&mut [f64], &mut [f64])) {
        let (m, k) = (self.m, self.k);
        let (rc, rz) = xr.split_at_mut(2 * m);
        let (ic, iz) = xi.split_at_mut(2 * m);
        core(rc, ic);
        for r in 0..k {
            let (g_x, _) = g_rows(&self.g_y, m, k, r);
            self.zr[r] = rz[r] + g_x.iter().zip(rc.iter()).map(|(g, v)| g * v).sum::<f64>();
            self.zi[r] = iz[r] + g_x.iter().zip(ic.iter()).map(|(g, v)| g * v).sum::<f64>();
        }
        solve_complex(&self.s_re, &self.s_im, k, &self.piv_complex, &mut self.zr, &mut self.zi);
        for c in 0..k {
            let (zr, zi) = (self.zr[c], self.zi[c]);
            let s = c * 2 * m..(c + 1) * 2 * m;
            for ((vr, vi), (yr, yi)) in rc.iter_mut().zip(ic.iter_mut()).zip(self.y_re[s.clone()].iter().zip(&self.y_im[s])) {
                *vr -= yr * zr - yi * zi;
                *vi -= yr * zi + yi * zr;
            }
        }
        rz.copy_from_slice(&self.zr);
        iz.copy_from_slice(&self.zi);
    }
}

/// Row `r` of ∂g/∂(q, v) (2m long) and of ∂g/∂z (k long).
fn g_rows(g_y: &[f64], m: usize, k: usize, r: usize) -> (&[f64], &[f64]) {
    let n = 2 * m + k;
    g_y[r * n..(r + 1) * n].split_at(2 * m)
}

/// LU with partial pivoting of the k × k row-major `a`, in place (unit lower triangle below the
/// diagonal); `piv[i]` the row swapped into row i.
fn factor_real(a: &mut [f64], k: usize, piv: &mut [usize]) {
    for j in 0..k {
        let p = (j..k).max_by(|&r, &s| a[r * k + j].abs().total_cmp(&a[s * k + j].abs())).unwrap_or(j);
        piv[j] = p;
        if p != j {
            for c in 0..k {
                a.swap(j * k + c, p * k + c);
            }
        }
        let d = a[j * k + j];
        for r in j + 1..k {
            let l = a[r * k + j] / d;
            a[r * k + j] = l;
            for c in j + 1..k {
                a[r * k + c] -= l * a[j * k + c];
            }
        }
    }
}

fn solve_real(lu: &[f64], k: usize, piv: &[usize], x: &mut [f64]) {
    for j in 0..k {
        x.swap(j, piv[j]);
    }
    for r in 0..k {
        for c in 0..r {
            x[r] -= lu[r * k + c] * x[c];
        }
    }
    for r in (0..k).rev() {
        for c in r + 1..k {
            x[r] -= lu[r * k + c] * x[c];
        }
        x[r] /= lu[r * k + r];
    }
}

/// `factor_real` for the complex matrix `re + i im`.
fn factor_complex(re: &mut [f64], im: &mut [f64], k: usize, piv: &mut [usize]) {
    for j in 0..k {
        let p = (j..k).max_by(|&r, &s| re[r * k + j].hypot(im[r * k + j]).total_cmp(&re[s * k + j].hypot(im[s * k + j]))).unwrap_or(j);
        piv[j] = p;
        if p != j {
            for c in 0..k {
                re.swap(j * k + c, p * k + c);
                im.swap(j * k + c, p * k + c);
            }
        }
        let (dr, di) = (re[j * k + j], im[j * k + j]);
        let den = dr * dr + di * di;
        for r in j + 1..k {
            let (ar, ai) = (re[r * k + j], im[r * k + j]);
            let (lr, li) = ((ar * dr + ai * di) / den, (ai * dr - ar * di) / den);
            re[r * k + j] = lr;
            im[r * k + j] = li;
            for c in j + 1..k {
                let (ur, ui) = (re[j * k + c], im[j * k + c]);
                re[r * k + c] -= lr * ur - li * ui;
                im[r * k + c] -= lr * ui + li * ur;
            }
        }
    }
}

fn solve_complex(re: &[f64], im: &[f64], k: usize, piv: &[usize], xr: &mut [f64], xi: &mut [f64]) {
    for j in 0..k {
        xr.swap(j, piv[j]);
        xi.swap(j, piv[j]);
    }
    for r in 0..k {
        for c in 0..r {
            let (lr, li) = (re[r * k + c], im[r * k + c]);
            let (vr, vi) = (xr[c], xi[c]);
            xr[r] -= lr * vr - li * vi;
            xi[r] -= lr * vi + li * vr;
        }
    }
    for r in (0..k).rev() {
        for c in r + 1..k {
            let (ur, ui) = (re[r * k + c], im[r * k + c]);
            let (vr, vi) = (xr[c], xi[c]);
            xr[r] -= ur * vr - ui * vi;
            xi[r] -= ur * vi + ui * vr;
        }
        let (dr, di) = (re[r * k + r], im[r * k + r]);
        let den = dr * dr + di * di;
        let (vr, vi) = (xr[r], xi[r]);
        xr[r] = (vr * dr + vi * di) / den;
        xi[r] = (vi * dr - vr * di) / den;
    }
}

#[cfg(test)]
mod tests {
    use super::Border;

    /// The bordered solves against the full (2m + k)-square systems σI − J and σ₂I − J, built
    /// densely and checked by their residuals, with a dense core solve (Gaussian elimination on
    /// the 2m × 2m core written here).
    #[test]
    fn bordered_solves_satisfy_the_full_systems() {
        let (m, k) = (3usize, 2usize);
        let n = 2 * m + k;
        let mut seed = 11u64;
        let mut rnd = move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        // J = [[0, I, 0], [W_q, W_v, A_z], [G_q, G_v, G_z]], dense row-major.
        let mut jac = vec![0.0; n * n];
        for i in 0..m {
            jac[i * n + m + i] = 1.0;
            for j in 0..n {
                jac[(m + i) * n + j] = 30.0 * rnd();
            }
        }
        for r in 0..k {
            for j in 0..n {
                jac[(2 * m + r) * n + j] = 5.0 * rnd();
            }
        }
        let mut border = Border::new(m, k);
        for c in 0..k {
            for i in 0..m {
                border.a_z[c * m + i] = jac[(m + i) * n + 2 * m + c];
            }
        }
        for r in 0..k {
            border.g_y[r * n..(r + 1) * n].copy_from_slice(&jac[(2 * m + r) * n..(2 * m + r + 1) * n]);
        }
        // Complex Gaussian elimination on the core block (σ = sr + i si) for the core solves.
        let core = |sr: f64, si: f64, xr: &mut [f64], xi: &mut [f64]| {
            let c = 2 * m;
            let (mut ar, mut ai) = (vec![0.0; c * c], vec![0.0; c * c]);
            for i in 0..c {
                for j in 0..c {
                    ar[i * c + j] = -jac[i * n + j];
                }
                ar[i * c + i] += sr;
                ai[i * c + i] += si;
            }
            let mut piv = vec![0; c];
            super::factor_complex(&mut ar, &mut ai, c, &mut piv);
            super::solve_complex(&ar, &ai, c, &piv, xr, xi);
        };
        let (sigma, a, b) = (2.3, 1.7, 2.9);
        border.factor_real(sigma, |x| {
            let mut zero = vec![0.0; x.len()];
            core(sigma, 0.0, x, &mut zero);
        });
        border.factor_complex(a, b, |xr, xi| core(a, b, xr, xi));
        let r: Vec<f64> = (0..n).map(|_| rnd()).collect();
        let mut x = r.clone();
        border.solve_real(&mut x, |v| {
            let mut zero = vec![0.0; v.len()];
            core(sigma, 0.0, v, &mut zero);
        });
        for i in 0..n {
            let jx: f64 = (0..n).map(|j| jac[i * n + j] * x[j]).sum();
            assert!((sigma * x[i] - jx - r[i]).abs() < 1e-11, "real row {i}");
        }
        let (rr, ri): (Vec<f64>, Vec<f64>) = ((0..n).map(|_| rnd()).collect(), (0..n).map(|_| rnd()).collect());
        let (mut xr, mut xi) = (rr.clone(), ri.clone());
        border.solve_complex(&mut xr, &mut xi, |vr, vi| core(a, b, vr, vi));
        for i in 0..n {
            let (jr, ji): (f64, f64) = ((0..n).map(|j| jac[i * n + j] * xr[j]).sum(), (0..n).map(|j| jac[i * n + j] * xi[j]).sum());
            assert!((a * xr[i] - b * xi[i] - jr - rr[i]).abs() < 1e-11, "complex row {i} (real part)");
            assert!((a * xi[i] + b * xr[i] - ji - ri[i]).abs() < 1e-11, "complex row {i} (imaginary part)");
        }
    }
}
