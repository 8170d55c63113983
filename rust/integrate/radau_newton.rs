//! RADAU5's two Newton matrices `σ₁I − W` and `σ₂I − W` (Hairer–Wanner IV.8.16–19): `W` built
//! from the system's second-order hook [`OdeSystem::acceleration_jacobian`] or by forward
//! differences of `f`, both matrices factorised for a step size, and the solves with them, in
//! full form, in the half-size structured form of a second-order system, or — for a large
//! mechanism — in the sparse lifted form of `lifted.rs` ([`NewtonSystems`]); first-order states
//! after (q, v) border the structured and the lifted form alike (`border.rs`). The dense LU
//! factorisations are `lu.rs`'s; the iteration that uses the solves is `radau.rs`'s.

use faer::Mat;

use super::border::Border;
use super::lifted::Lifted;
use super::lu::{ComplexLu, Lu};
use super::method::Stats;
use super::ode::OdeSystem;
use crate::error::Error;

/// The two Newton matrices `σ₁I − W` (real `σ₁ = u1/h`) and `σ₂I − W` (complex
/// `σ₂ = (α + iβ)/h`), in full or structured (half-size) form.
///
/// In structured form only the columns of `W_q`, `W_v` that belong to coordinates of bodies
/// carrying a stiff force are non-zero (`active`; the nine-bar's two joints: 12 of 24). With
/// `G = W_v + W_q/σ`, the system `(σI − G) x = b` then splits: `(σI − G)_CC x_C = b_C` on the
/// active coordinates `C`, and `x_j = (b_j + Σ_c G_jc x_c)/σ` for the others, so only a
/// `|C| × |C|` matrix is factorised (and `2|C|` for the complex one).
///
/// That block is dense, and so is every column of the mobility that builds it: a mechanism with
/// more than [`LIFTED_ABOVE`] stiff coordinates (a chain with a clearance at every few joints)
/// takes the lifted form instead (`lifted.rs`), whose cost grows linearly with its size.
pub(super) struct NewtonSystems {
    /// The lifted form, when the system offers it and is large enough (`half` and the dense
    /// storage then unused).
    lifted: Option<Lifted>,
    /// `m = (n − k)/2` for a second-order system with the structured hook, else `None`.
    pub(super) half: Option<usize>,
    /// Structured form with `k` first-order states after (q, v)
    /// ([`OdeSystem::first_order_states`]): their rows and columns (`border.rs`).
    border: Option<Border>,
    jac: Mat<f64>,
    w_q: Vec<f64>,
    w_v: Vec<f64>,
    /// Structured form: the coordinates whose columns of `W_q` or `W_v` are non-zero, and the rest.
    active: Vec<usize>,
    rest: Vec<usize>,
    /// The reduced right-hand side or solution: `|C|` long, or its real and imaginary parts at
    /// 0 and `m`.
    reduced: Vec<f64>,
    real: Lu,
    complex: ComplexLu,
    sigma: f64,
    /// `σ₂ = a + ib` and `1/σ₂ = p + iq`.
    a: f64,
    b: f64,
    p: f64,
    q: f64,
    /// Scratch, `k` long (`k` = size of the real system).
    tmp: Vec<f64>,
    gq: Vec<f64>,
    probe: Vec<f64>,
    df: Vec<f64>,
}

/// Stiff coordinates (columns of `W` the structured form factorises) above which the lifted form
/// is taken, when the system offers it. Measured (instructions, `benches/one_cycle.rs`,
/// `benches/chain_steps.rs`): the lifted form costs 10 % more on the lubricated nine-bar (12
/// stiff coordinates) and 18 % more on the slider-crank (6); 5 % more on the 8-link chain of
/// `chain_steps` (9), 12 % less on its 12-link one (15), 33 % less at 20 links (27).
pub(super) const LIFTED_ABOVE: usize = 12;

impl NewtonSystems {
    /// Whether `W` comes from the system's structured hook or lifted form (not differenced).
    pub(super) fn structured(&self) -> bool {
        self.half.is_some() || self.lifted.is_some()
    }

    pub(super) fn new<S: OdeSystem>(sys: &mut S, t: f64, y: &[f64]) -> Result<Self, Error> {
        let n = y.len();
        let extra = sys.first_order_states().min(n);
        let m = (n - extra) / 2;
        if let Some(pattern) = sys.lifted_pattern().filter(|p| p.stiff_coords > LIFTED_ABOVE && 2 * p.coords + extra == n) {
            let mut ns = Self::with_matrices(0, 0, false, Vec::new(), Vec::new());
            ns.lifted = Some(Lifted::new(pattern, true));
            if extra > 0 {
                // The oil temperatures border the lifted core as they border the dense one.
                let mut border = Border::new(m, extra);
                sys.border_jacobian(t, y, &mut border.a_z, &mut border.g_y)?;
                ns.border = Some(border);
            }
            return Ok(ns);
        }
        let mut w_q = vec![0.0; m * m];
        let mut w_v = vec![0.0; m * m];
        let structured = (n - extra).is_multiple_of(2) && m > 0 && sys.acceleration_jacobian(t, y, &mut w_q, &mut w_v)?;
        let mut ns = Self::with_matrices(n, extra, structured, w_q, w_v);
        if let Some(b) = ns.border.as_mut() {
            sys.border_jacobian(t, y, &mut b.a_z, &mut b.g_y)?;
        }
        Ok(ns)
    }

    /// The storage for a state of size `n` with `extra` first-order states after (q, v), in
    /// structured form with `W_q`, `W_v` (`m × m`, column-major, `m = (n − extra)/2`) or in full
    /// form.
    fn with_matrices(n: usize, extra: usize, structured: bool, w_q: Vec<f64>, w_v: Vec<f64>) -> Self {
        let m = (n - extra) / 2;
        let k = if structured { m } else { n };
        let mut ns = NewtonSystems {
            lifted: None,
            half: structured.then_some(m),
            border: (structured && extra > 0).then(|| Border::new(m, extra)),
            jac: if structured { Mat::zeros(0, 0) } else { Mat::zeros(n, n) },
            w_q,
            w_v,
            active: Vec::with_capacity(m),
            rest: Vec::with_capacity(m),
            reduced: vec![0.0; 2 * m],
            real: Lu::new(k),
            complex: ComplexLu::new(k),
            sigma: 0.0,
            a: 0.0,
            b: 0.0,
            p: 0.0,
            q: 0.0,
            tmp: vec![0.0; k],
            gq: vec![0.0; 2 * m],
            probe: vec![0.0; n],
            df: vec![0.0; n],
        };
        ns.find_active();
        ns
    }

    /// Recompute `W` at `(t, y)`; `f0 = f(t, y)`. In structured form `W_q`, `W_v` come from the
    /// system's hook, or with `differenced` from forward differences of the whole `f` (`n`
    /// right-hand sides: every term of `∂q̈/∂(q, q̇)`, not only the clearance forces').
    pub(super) fn update<S: OdeSystem>(&mut self, sys: &mut S, stats: &mut Stats, t: f64, y: &[f64], f0: &[f64], differenced: bool) -> Result<(), Error> {
        stats.jacobians += 1;
        if let Some(lifted) = self.lifted.as_mut() {
            // Differenced: the whole K (constraint curvature, Baumgarte terms) in place of its
            // stiff part, still sparse.
            stats.rhs_evals += lifted.update(sys, t, y, differenced)?;
            if let Some(b) = self.border.as_mut() {
                sys.border_jacobian(t, y, &mut b.a_z, &mut b.g_y)?;
            }
            return Ok(());
        }
        if self.half.is_some() && !differenced {
            sys.acceleration_jacobian(t, y, &mut self.w_q, &mut self.w_v)?;
            if let Some(b) = self.border.as_mut() {
                sys.border_jacobian(t, y, &mut b.a_z, &mut b.g_y)?;
            }
            self.find_active();
            return Ok(());
        }
        let n = y.len();
        self.probe.copy_from_slice(y);
        for j in 0..n {
            self.probe[j] = y[j] + sys.difference_step(j, y);
            let delta = self.probe[j] - y[j]; // the step actually taken
            sys.rhs(t, &self.probe, &mut self.df)?;
            self.probe[j] = y[j];
            match self.half {
                None => {
                    for i in 0..n {
                        self.jac[(i, j)] = (self.df[i] - f0[i]) / delta;
                    }
                }
                Some(m) => {
                    // Rows m..2m of column j: ∂q̈/∂q_j (j < m), ∂q̈/∂q̇_{j−m} (j < 2m) or, in
                    // the border, ∂q̈/∂z_{j−2m}; and the border's rows ∂ż/∂y_j.
                    let col = if j < m {
                        &mut self.w_q[j * m..(j + 1) * m]
                    } else if j < 2 * m {
                        &mut self.w_v[(j - m) * m..(j - m + 1) * m]
                    } else if let Some(b) = self.border.as_mut() {
                        &mut b.a_z[(j - 2 * m) * m..(j - 2 * m + 1) * m]
                    } else {
                        &mut []
                    };
                    for (i, c) in col.iter_mut().enumerate() {
                        *c = (self.df[m + i] - f0[m + i]) / delta;
                    }
                    if let Some(b) = self.border.as_mut() {
                        for (r, i) in (2 * m..n).enumerate() {
                            b.g_y[r * n + j] = (self.df[i] - f0[i]) / delta;
                        }
                    }
                }
            }
        }
        stats.rhs_evals += n;
        self.find_active();
        Ok(())
    }

    /// Structured form: sort the coordinates into those with a non-zero column in `W_q` or
    /// `W_v` and the rest (within the capacity reserved in `new`: no allocation).
    fn find_active(&mut self) {
        let Some(m) = self.half else { return };
        self.active.clear();
        self.rest.clear();
        for j in 0..m {
            let cols = self.w_q[j * m..(j + 1) * m].iter().chain(&self.w_v[j * m..(j + 1) * m]);
            if cols.into_iter().any(|&v| v != 0.0) {
                self.active.push(j);
            } else {
                self.rest.push(j);
            }
        }
    }

    /// Factorise both systems for `σ₁ = sigma` and `σ₂ = a + ib`.
    pub(super) fn factor(&mut self, sigma: f64, a: f64, b: f64) {
        self.factor_core(sigma, a, b);
        if let Some(mut border) = self.border.take() {
            border.factor_real(sigma, |x| self.solve_real_core(x));
            border.factor_complex(a, b, |xr, xi| self.solve_complex_core(xr, xi));
            self.border = Some(border);
        }
    }

    /// `x ← (σ₁ I − W)⁻¹ x`.
    pub(super) fn solve_real(&mut self, x: &mut [f64]) {
        match self.border.take() {
            None => self.solve_real_core(x),
            Some(mut border) => {
                border.solve_real(x, |v| self.solve_real_core(v));
                self.border = Some(border);
            }
        }
    }

    /// `(xr + i xi) ← (σ₂ I − W)⁻¹ (xr + i xi)`.
    pub(super) fn solve_complex(&mut self, xr: &mut [f64], xi: &mut [f64]) {
        match self.border.take() {
            None => self.solve_complex_core(xr, xi),
            Some(mut border) => {
                border.solve_complex(xr, xi, |vr, vi| self.solve_complex_core(vr, vi));
                self.border = Some(border);
            }
        }
    }

    /// [`Self::factor`] without the border: the full matrix, or the (q, v) core.
    fn factor_core(&mut self, sigma: f64, a: f64, b: f64) {
        if let Some(lifted) = self.lifted.as_mut() {
            lifted.factor_real(sigma);
            lifted.factor_complex(a, b);
            return;
        }
        let den = a * a + b * b;
        (self.sigma, self.a, self.b, self.p, self.q) = (sigma, a, b, a / den, -b / den);
        let (p, q) = (self.p, self.q);
        match self.half {
            None => {
                let jac = &self.jac;
                let n = jac.nrows();
                self.real.factor(jac, sigma);
                self.complex.factor_with(n, |mut re, mut im| {
                    for j in 0..n {
                        for i in 0..n {
                            re[(i, j)] = -jac[(i, j)];
                            im[(i, j)] = 0.0;
                        }
                        re[(j, j)] += a;
                        im[(j, j)] = b;
                    }
                });
            }
            Some(m) => {
                let (w_q, w_v, act) = (&self.w_q, &self.w_v, &self.active);
                let kc = act.len();
                // Real: (σ I − W_v − W_q/σ)_CC.
                self.real.factor_with(kc, |mut e| {
                    for (cj, &j) in act.iter().enumerate() {
                        for (ci, &i) in act.iter().enumerate() {
                            e[(ci, cj)] = -w_v[i + j * m] - w_q[i + j * m] / sigma;
                        }
                        e[(cj, cj)] += sigma;
                    }
                });
                // Complex: M = (a I − W_v − p W_q) + i (b I − q W_q), its CC block.
                self.complex.factor_with(kc, |mut re, mut im| {
                    for (cj, &j) in act.iter().enumerate() {
                        for (ci, &i) in act.iter().enumerate() {
                            re[(ci, cj)] = -w_v[i + j * m] - p * w_q[i + j * m];
                            im[(ci, cj)] = -q * w_q[i + j * m];
                        }
                        re[(cj, cj)] += a;
                        im[(cj, cj)] += b;
                    }
                });
            }
        }
    }

    /// [`Self::solve_real`] on the full state, or on the (q, v) core (`x` 2m long).
    fn solve_real_core(&mut self, x: &mut [f64]) {
        if let Some(lifted) = self.lifted.as_mut() {
            lifted.solve_real(x);
            return;
        }
        let Some(m) = self.half else {
            self.real.solve(x);
            return;
        };
        // x_v = (σI − G)⁻¹ b with G = W_v + W_q/σ, b = r_v + W_q r_q/σ; x_q = (r_q + x_v)/σ.
        let s = self.sigma;
        let (w_q, w_v) = (&self.w_q, &self.w_v);
        let (xq, xv) = x.split_at_mut(m);
        let kc = self.active.len();
        let b = &mut self.tmp;
        b.copy_from_slice(xv);
        for &j in &self.active {
            let r = xq[j] / s;
            if r != 0.0 {
                for (t, w) in b.iter_mut().zip(&w_q[j * m..(j + 1) * m]) {
                    *t += r * w;
                }
            }
        }
        let red = &mut self.reduced[..kc];
        for (ci, &c) in self.active.iter().enumerate() {
            red[ci] = b[c];
        }
        if kc > 0 {
            self.real.solve(red);
        }
        xv.copy_from_slice(b);
        for (ci, &c) in self.active.iter().enumerate() {
            xv[c] = red[ci];
            let (gv, gq) = (&w_v[c * m..(c + 1) * m], &w_q[c * m..(c + 1) * m]);
            for &j in &self.rest {
                xv[j] += (gv[j] + gq[j] / s) * red[ci];
            }
        }
        for &j in &self.rest {
            xv[j] /= s;
        }
        for (q, v) in xq.iter_mut().zip(xv.iter()) {
            *q = (*q + v) / s;
        }
    }

    /// [`Self::solve_complex`] on the full state, or on the (q, v) core (2m long).
    fn solve_complex_core(&mut self, xr: &mut [f64], xi: &mut [f64]) {
        if let Some(lifted) = self.lifted.as_mut() {
            lifted.solve_complex(xr, xi);
            return;
        }
        let Some(m) = self.half else {
            self.complex.solve(xr, xi);
            return;
        };
        let (p, q) = (self.p, self.q);
        let (w_q, w_v) = (&self.w_q, &self.w_v);
        let kc = self.active.len();
        let (rq, rv) = xr.split_at_mut(m);
        let (iq, iv) = xi.split_at_mut(m);
        // b = r_v + (p + iq) W_q r_q (complex), into (rv, iv).
        let (gr, gi) = self.gq.split_at_mut(m);
        gr.fill(0.0);
        gi.fill(0.0);
        for &j in &self.active {
            let col = &w_q[j * m..(j + 1) * m];
            let (a, b) = (rq[j], iq[j]);
            if a != 0.0 || b != 0.0 {
                for i in 0..m {
                    gr[i] += col[i] * a;
                    gi[i] += col[i] * b;
                }
            }
        }
        for i in 0..m {
            let (a, b) = (gr[i], gi[i]);
            rv[i] += p * a - q * b;
            iv[i] += q * a + p * b;
        }
        // The active block: M_CC x_C = b_C.
        let (red_r, red_i) = self.reduced.split_at_mut(m);
        let (red_r, red_i) = (&mut red_r[..kc], &mut red_i[..kc]);
        for (ci, &c) in self.active.iter().enumerate() {
            red_r[ci] = rv[c];
            red_i[ci] = iv[c];
        }
        if kc > 0 {
            self.complex.solve(red_r, red_i);
        }
        // The others: x_j = (p + iq)(b_j + Σ_c G_jc x_c), G = W_v + (p + iq) W_q.
        for (ci, &c) in self.active.iter().enumerate() {
            let (xr_c, xi_c) = (red_r[ci], red_i[ci]);
            rv[c] = xr_c;
            iv[c] = xi_c;
            let (gv, gq) = (&w_v[c * m..(c + 1) * m], &w_q[c * m..(c + 1) * m]);
            for &j in &self.rest {
                let (g_re, g_im) = (gv[j] + p * gq[j], q * gq[j]);
                rv[j] += g_re * xr_c - g_im * xi_c;
                iv[j] += g_re * xi_c + g_im * xr_c;
            }
        }
        for &j in &self.rest {
            let (a, b) = (rv[j], iv[j]);
            rv[j] = p * a - q * b;
            iv[j] = q * a + p * b;
        }
        // x_q = (p + iq)(r_q + x_v).
        for i in 0..m {
            let (a, b) = (rq[i] + rv[i], iq[i] + iv[i]);
            rq[i] = p * a - q * b;
            iq[i] = q * a + p * b;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::NewtonSystems;

    /// The structured solves factorise only the active block of `σI − W` (columns of `W_q`,
    /// `W_v` that are not zero) and fill in the other coordinates; checked against the full
    /// `2m × 2m` matrix `W = [[0, I], [W_q, W_v]]` by its residual, for the real and the
    /// complex system, with two, all and no columns active.
    #[test]
    fn reduced_newton_solves_satisfy_the_full_systems() {
        let m = 6;
        let mut seed = 7u64;
        let mut rnd = move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        for zero_cols in [vec![1usize, 4], vec![], (0..m).collect()] {
            let mut w_q: Vec<f64> = (0..m * m).map(|_| 50.0 * rnd()).collect();
            let mut w_v: Vec<f64> = (0..m * m).map(|_| 5.0 * rnd()).collect();
            for &c in &zero_cols {
                w_q[c * m..(c + 1) * m].fill(0.0);
                w_v[c * m..(c + 1) * m].fill(0.0);
            }
            let mut ns = NewtonSystems::with_matrices(2 * m, 0, true, w_q.clone(), w_v.clone());
            assert_eq!(ns.active.len(), m - zero_cols.len());
            let n = 2 * m;
            // W x for the full matrix.
            let w_times = |x: &[f64]| -> Vec<f64> {
                let mut out = vec![0.0; n];
                for i in 0..m {
                    out[i] = x[m + i];
                    for j in 0..m {
                        out[m + i] += w_q[i + j * m] * x[j] + w_v[i + j * m] * x[m + j];
                    }
                }
                out
            };
            let (sigma, a, b) = (3.7, 2.9, 1.8);
            ns.factor(sigma, a, b);
            let r: Vec<f64> = (0..n).map(|_| rnd()).collect();
            let mut x = r.clone();
            ns.solve_real(&mut x);
            let wx = w_times(&x);
            for i in 0..n {
                assert!((sigma * x[i] - wx[i] - r[i]).abs() < 1e-12, "real row {i}");
            }
            let (rr, ri): (Vec<f64>, Vec<f64>) = ((0..n).map(|_| rnd()).collect(), (0..n).map(|_| rnd()).collect());
            let (mut xr, mut xi) = (rr.clone(), ri.clone());
            ns.solve_complex(&mut xr, &mut xi);
            let (wr, wi) = (w_times(&xr), w_times(&xi));
            for i in 0..n {
                assert!((a * xr[i] - b * xi[i] - wr[i] - rr[i]).abs() < 1e-12, "complex row {i} (real part)");
                assert!((a * xi[i] + b * xr[i] - wi[i] - ri[i]).abs() < 1e-12, "complex row {i} (imaginary part)");
            }
        }
    }
}
