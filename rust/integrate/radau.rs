//! RADAU5: the 3-stage Radau IIA collocation method of order 5, L-stable and stiffly accurate,
//! with simplified Newton iterations, an embedded error estimate filtered through the iteration
//! matrix, Gustafsson's predictive step control and the collocation polynomial as dense output
//! (Hairer & Wanner, *Solving ODEs II*, §IV.8; the algorithm of their code `RADAU5`).
//!
//! Why a fully implicit method for the mechanism: the stiff forces of a clearance joint are
//! strongly nonlinear over one step (film damping ∝ (1 − ε²)^(−3/2), contact ∝ δ^1.5 with a
//! damping set by the impact speed), and a linearly implicit (Rosenbrock) step linearises them
//! once per step; the Newton iteration here solves the stage equations themselves, so the step
//! is limited by accuracy, not by how far the linearisation holds.
//!
//! The Newton matrices are `σI − W` for the eigenvalues `σ` of `(hA)⁻¹` (one real, one complex
//! pair: a real and a complex system per iteration, Hairer–Wanner IV.8.16–19). `W` comes from the
//! system's second-order hook [`OdeSystem::acceleration_jacobian`] when it has one — for a
//! mechanism, the clearance joints' force derivatives mapped through the constrained mobility,
//! a few KKT solves instead of `n` evaluations of `f`; the simplified Newton iteration converges
//! with an approximate `W` and the converged stages do not depend on it — and then, with
//! `W = [[0, I], [W_q, W_v]]`, each system shrinks to half size:
//! `x_q = (r_q + x_v)/σ`, `(σI − W_v − W_q/σ) x_v = r_v + W_q r_q/σ`.
//! Otherwise `W` is a forward-difference Jacobian of the whole `f`.
//! The complex system is factorised in complex arithmetic (`lu.rs`'s `ComplexLu`; in the real
//! form `[[Re, −Im], [Im, Re]]` above 64 rows). `radau_newton.rs` builds, factorises and solves
//! the two systems ([`NewtonSystems`]); this file is the stepper: the constants, the Newton
//! iteration on the stages, the error estimate, step control and dense output.
//!
//! Tolerances are used as given (no internal transformation as in Hairer's code; SciPy's
//! `Radau` does the same).

use super::controller::{Decision, NewtonLimit, Predictive};
use super::driver::{all_finite, non_finite, Stepper, Trial};
use super::method::{Settings, Stats};
use super::ode::{DenseOutput, OdeSystem};
use super::radau_newton::NewtonSystems;
use crate::error::Error;

/// The method's constants (Hairer's `RADCOR` / `ESTRAD`): nodes, the eigenvalues of `A⁻¹`
/// (`u1` real, `α ± iβ`), the transformation `T` with `T⁻¹ A⁻¹ T = [[u1, 0, 0], [0, α, −β], [0, β, α]]`,
/// and the error-estimate weights `d_i`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Radau5 {
    pub c: [f64; 3],
    pub u1: f64,
    pub alpha: f64,
    pub beta: f64,
    pub t: [[f64; 3]; 3],
    pub ti: [[f64; 3]; 3],
    pub d: [f64; 3],
}

#[allow(clippy::excessive_precision)]
impl Radau5 {
    pub(crate) fn new() -> Self {
        let sq6 = 6f64.sqrt();
        let (c81, c9) = (81f64.cbrt(), 9f64.cbrt());
        let u1 = 30.0 / (6.0 + c81 - c9);
        let (a, b) = ((12.0 - c81 + c9) / 60.0, (c81 + c9) * 3f64.sqrt() / 60.0);
        let cno = a * a + b * b;
        Radau5 {
            c: [(4.0 - sq6) / 10.0, (4.0 + sq6) / 10.0, 1.0],
            u1,
            alpha: a / cno,
            beta: b / cno,
            t: [
                [9.1232394870892942792e-02, -0.14125529502095420843, -3.0029194105147424492e-02],
                [0.24171793270710701896, 0.20412935229379993199, 0.38294211275726193779],
                [0.96604818261509293619, 1.0, 0.0],
            ],
            ti: [
                [4.3255798900631553510, 0.33919925181580986954, 0.54177053993587487119],
                [-4.1787185915519047273, -0.32768282076106238708, 0.47662355450055045196],
                [-0.50287263494578687595, 2.5719269498556054292, -0.59603920482822492497],
            ],
            d: [-(13.0 + 7.0 * sq6) / 3.0, (-13.0 + 7.0 * sq6) / 3.0, -1.0 / 3.0],
        }
    }

    /// The Radau IIA coefficient matrix (Hairer–Wanner IV.5, Table 5.6).
    #[cfg(test)]
    pub(crate) fn a() -> [[f64; 3]; 3] {
        let s = 6f64.sqrt();
        [
            [(88.0 - 7.0 * s) / 360.0, (296.0 - 169.0 * s) / 1800.0, (-2.0 + 3.0 * s) / 225.0],
            [(296.0 + 169.0 * s) / 1800.0, (88.0 + 7.0 * s) / 360.0, (-2.0 - 3.0 * s) / 225.0],
            [(16.0 - s) / 36.0, (16.0 + s) / 36.0, 1.0 / 9.0],
        ]
    }
}

/// The collocation polynomial of the last accepted step in Newton form in `s = (t − t1)/h`:
/// `y = c0 + s (c1 + (s − c2 + 1)(c2' + (s − c1 + 1) c3))` through `y0`, the stages and `y1`.
struct RadauDense {
    t0: f64,
    t1: f64,
    c1m1: f64,
    c2m1: f64,
    cont: Vec<f64>,
}

impl DenseOutput for RadauDense {
    fn interval(&self) -> (f64, f64) {
        (self.t0, self.t1)
    }
    /// `s = (t − t1)/h`.
    fn fraction(&self, t: f64) -> f64 {
        let h = self.t1 - self.t0;
        if h != 0.0 { (t - self.t1) / h } else { 0.0 }
    }
    #[inline]
    fn component(&self, s: f64, i: usize) -> f64 {
        let c = &self.cont;
        let n = c.len() / 4;
        c[i] + s * (c[n + i] + (s - self.c2m1) * (c[2 * n + i] + (s - self.c1m1) * c[3 * n + i]))
    }
}

/// Most Newton iterations per step (Hairer's `NIT`).
const NIT: usize = 7;

/// The Newton iteration's stopping tolerance κ (Hairer's `FNEWT`) for the relative tolerance
/// `rtol`: the iteration stops once its predicted remaining error is below κ in the norm of the
/// error test, so κ is the fraction of the local error allowance left to the iteration.
/// Hairer's code runs internally at `rtol' = 0.1·rtol^(2/3)` (its error estimate is of lower
/// order than the solution) and sets `κ = max(10·u/rtol', min(0.03, √rtol'))` from that. We test
/// the error against `rtol` as given but take κ from `rtol'`, so κ is the same fraction of the
/// allowance as in Hairer's code for the same user tolerance: rtol 1e-6 gives κ = 3.2e-3
/// (√rtol = 1e-3, the rule before, converged each step further than its error test can see:
/// 11–19 % more right-hand sides for the same error on the lubricated nine-bar and
/// slider-crank, docs/performance.md).
pub(super) fn newton_tolerance(rtol: f64) -> f64 {
    let rtol_internal = 0.1 * rtol.powf(2.0 / 3.0);
    (10.0 * f64::EPSILON / rtol_internal).max(0.03f64.min(rtol_internal.sqrt()))
}
/// Accepted steps that keep a differenced `W` after the hook's `W` failed (see [`Radau5Stepper`]).
const DIFFERENCED_SPELL: usize = 10;

/// The RADAU5 stepper (the step of Hairer's `RADCOR`). `W` is recomputed after every accepted
/// step (cheap with the structured hook) and kept on rejections, except that after three failed
/// trial steps a hook-supplied `W` is replaced by a differenced one, for that step and the next
/// [`DIFFERENCED_SPELL`] (the hook leaves out terms that can matter: constraint curvature,
/// Baumgarte terms). A trial whose stages leave the domain of `f` or whose Newton iteration
/// does not converge is retried with a smaller step, up to 30 times in a row.
pub(super) struct Radau5Stepper {
    k: Radau5,
    f0: Vec<f64>,
    /// Stage increments `Z_i = Y_i − y`.
    z: Vec<f64>,
    /// `T⁻¹ Z`.
    w: Vec<f64>,
    /// `f` at the stages, then the Newton corrections.
    fz: Vec<f64>,
    ytmp: Vec<f64>,
    scal: Vec<f64>,
    errv: Vec<f64>,
    e_comb: Vec<f64>,
    buf: Vec<f64>,
    dense: RadauDense,
    /// Built by [`Stepper::start`] (it asks the system whether it has the structured hook).
    newton: Option<NewtonSystems>,
    /// Newton stopping tolerance (Hairer's `FNEWT`).
    fnewt: f64,
    /// Gustafsson's predictive controller after the first accepted step.
    ctrl: Predictive,
    /// The last accepted step (for extrapolating the stages).
    h_old: f64,
    first: bool,
    /// Size of the step just abandoned to end on a switching point: the redone step starts from
    /// the same `t`, inside the abandoned step's collocation polynomial (in `dense`).
    redo_of: Option<f64>,
    /// The last trial was rejected or failed (then the error estimate is checked once more).
    reject: bool,
    need_w: bool,
    /// Failed trial steps since `W` was last built, and whether it came from the system's hook:
    /// after three failures it is rebuilt by differencing the whole right-hand side, and so are
    /// the next `DIFFERENCED_SPELL` steps' (where the hook fell short once it tends to again).
    fails_on_w: usize,
    w_from_hook: bool,
    differenced_left: usize,
    faccon: f64,
    /// Caps the step after Newton failures (µm films: the iteration, not the error, limits it).
    newton_limit: NewtonLimit,
    /// Newton iterations of the last accepted step.
    last_newt: usize,
}

impl Radau5Stepper {
    pub(super) fn new(n: usize, st: &Settings) -> Self {
        let k = Radau5::new();
        let (c1m1, c2m1) = (k.c[0] - 1.0, k.c[1] - 1.0);
        Radau5Stepper {
            k,
            f0: vec![0.0; n],
            z: vec![0.0; 3 * n],
            w: vec![0.0; 3 * n],
            fz: vec![0.0; 3 * n],
            ytmp: vec![0.0; n],
            scal: vec![0.0; n],
            errv: vec![0.0; n],
            e_comb: vec![0.0; n],
            buf: vec![0.0; n],
            dense: RadauDense { t0: 0.0, t1: 0.0, c1m1, c2m1, cont: vec![0.0; 4 * n] },
            newton: None,
            fnewt: newton_tolerance(st.rtol),
            ctrl: Predictive::radau5(),
            h_old: 0.0,
            first: true,
            redo_of: None,
            reject: false,
            need_w: true,
            fails_on_w: 0,
            w_from_hook: false,
            differenced_left: 0,
            faccon: 1.0,
            newton_limit: NewtonLimit::new(0.8, 1.1),
            last_newt: 0,
        }
    }

    /// Starting values of the stages: zero on the first step, else the last collocation
    /// polynomial `u(t_a + x h_a) − u(t_a) = x (a1 + (x − c2 + 1)(a2 + (x − c1 + 1) a3))`,
    /// anchored at the end `t_a` of the step of size `h_a` it came from: extrapolated past it
    /// after an accepted step (`x = c_i hs/h_old`), read inside it for a redone step
    /// (`x = c_i hs/h_a − 1`, less its value at `x = −1`, the common start).
    fn starting_values(&mut self, hs: f64) {
        let n = self.f0.len();
        if self.first {
            self.z.fill(0.0);
            self.w.fill(0.0);
            return;
        }
        let (c1, c2) = (self.k.c[0], self.k.c[1]);
        let (c1m1, c2m1) = (c1 - 1.0, c2 - 1.0);
        let (h_from, shift) = match self.redo_of.take() {
            Some(h_a) => (h_a, -1.0),
            None => (self.h_old, 0.0),
        };
        let c3q = hs / h_from;
        let cq = [c1 * c3q + shift, c2 * c3q + shift, c3q + shift];
        let poly = |x: f64, a1: f64, a2: f64, a3: f64| x * (a1 + (x - c2m1) * (a2 + (x - c1m1) * a3));
        let cont = &self.dense.cont;
        for i in 0..n {
            let (a1, a2, a3) = (cont[n + i], cont[2 * n + i], cont[3 * n + i]);
            let base = if shift == 0.0 { 0.0 } else { poly(shift, a1, a2, a3) };
            for (s, &x) in cq.iter().enumerate() {
                self.z[s * n + i] = poly(x, a1, a2, a3) - base;
            }
        }
        transform(&self.k.ti, &self.z, &mut self.w, n);
    }

    /// The simplified Newton iteration (Hairer–Wanner IV.8.19) for the stages of the step
    /// `[t, t1]` of size `hs`. Returns the number of iterations, or the failed trial (its error
    /// and the factor for the next step).
    #[allow(clippy::too_many_arguments)]
    fn newton<S: OdeSystem>(&mut self, sys: &mut S, stats: &mut Stats, t: f64, t1: f64, hs: f64, y: &[f64], fac: (f64, f64, f64)) -> Result<Result<usize, (Error, f64)>, Error> {
        let n = y.len();
        let (fac1, alphn, betan) = fac;
        let Some(newton) = self.newton.as_mut() else {
            return Err(Error::invalid("radau", "not started", "the stepper's start was not called"));
        };
        let (k, z, w, fz, ytmp, scal) = (&self.k, &mut self.z, &mut self.w, &mut self.fz, &mut self.ytmp, &self.scal);
        self.faccon = self.faccon.max(f64::EPSILON).powf(0.8);
        let (mut dyno_old, mut thq_old) = (1.0f64, 1.0f64);
        let mut newt = 0usize;
        loop {
            if newt >= NIT {
                return Ok(Err((Error::NewtonFailure { t, h: hs }, 0.5)));
            }
            let mut eval = || -> Result<(), Error> {
                for s in 0..3 {
                    // Zipped slices of length n: no bounds checks in RADAU5's innermost loops.
                    for ((yt, &yi), &zi) in ytmp[..n].iter_mut().zip(&y[..n]).zip(&z[s * n..(s + 1) * n]) {
                        *yt = yi + zi;
                    }
                    let ts = if s == 2 { t1 } else { t + k.c[s] * hs };
                    sys.rhs(ts, ytmp, &mut fz[s * n..(s + 1) * n])?;
                    stats.rhs_evals += 1;
                }
                Ok(())
            };
            match eval() {
                Ok(()) if all_finite(fz) => {}
                Ok(()) => return Ok(Err((non_finite(t), 0.25))),
                Err(e @ (Error::NonFinite { .. } | Error::SingularJacobian { .. })) => return Ok(Err((e, 0.25))),
                Err(e) => return Err(e),
            }
            // Right-hand sides in transformed variables, then the two solves.
            let mut dyno = 0.0;
            {
                let (r1, rest) = fz.split_at_mut(n);
                let (r2, r3) = rest.split_at_mut(n);
                let r3 = &mut r3[..n];
                let (wa, wb, wc) = (&w[..n], &w[n..2 * n], &w[2 * n..3 * n]);
                for (((((r1, r2), r3), &w1), &w2), &w3) in r1.iter_mut().zip(r2.iter_mut()).zip(r3.iter_mut()).zip(wa).zip(wb).zip(wc) {
                    let (f1, f2, f3) = (*r1, *r2, *r3);
                    let a1 = k.ti[0][0] * f1 + k.ti[0][1] * f2 + k.ti[0][2] * f3;
                    let a2 = k.ti[1][0] * f1 + k.ti[1][1] * f2 + k.ti[1][2] * f3;
                    let a3 = k.ti[2][0] * f1 + k.ti[2][1] * f2 + k.ti[2][2] * f3;
                    *r1 = a1 - fac1 * w1;
                    *r2 = a2 - alphn * w2 + betan * w3;
                    *r3 = a3 - alphn * w3 - betan * w2;
                }
                newton.solve_real(r1);
                newton.solve_complex(r2, r3);
                for (((&x1, &x2), &x3), &s) in r1.iter().zip(r2.iter()).zip(r3.iter()).zip(&scal[..n]) {
                    dyno += (x1 / s).powi(2) + (x2 / s).powi(2) + (x3 / s).powi(2);
                }
            }
            let dyno = (dyno / (3 * n).max(1) as f64).sqrt();
            if !dyno.is_finite() {
                // f was finite at the iterate: the Newton systems' solve overflowed (a matrix
                // σI − hJ close to singular), a failure of the iteration, not of the state.
                return Ok(Err((Error::NewtonFailure { t, h: hs }, 0.25)));
            }
            if newt >= 1 {
                let thq = dyno / dyno_old;
                let theta = if newt == 1 { thq } else { (thq * thq_old).sqrt() };
                thq_old = thq;
                if theta < 0.99 {
                    self.faccon = theta / (1.0 - theta);
                    let dyth = self.faccon * dyno * theta.powi((NIT - 1 - newt) as i32) / self.fnewt;
                    if dyth >= 1.0 {
                        // Convergence predicted too slow: a smaller step.
                        let qnewt = dyth.clamp(1e-4, 20.0);
                        return Ok(Err((Error::NewtonFailure { t, h: hs }, 0.8 * qnewt.powf(-1.0 / (4.0 + (NIT - 1 - newt) as f64)))));
                    }
                } else {
                    return Ok(Err((Error::NewtonFailure { t, h: hs }, 0.5)));
                }
            }
            dyno_old = dyno.max(f64::EPSILON);
            for (wi, d) in w.iter_mut().zip(fz.iter()) {
                *wi += d;
            }
            transform(&k.t, w, z, n);
            newt += 1;
            if self.faccon * dyno <= self.fnewt {
                return Ok(Ok(newt));
            }
        }
    }
}

impl<S: OdeSystem> Stepper<S> for Radau5Stepper {
    fn order(&self) -> usize {
        5
    }
    fn max_trial_failures(&self) -> usize {
        30
    }
    fn f0(&mut self) -> &mut [f64] {
        &mut self.f0
    }
    fn start(&mut self, sys: &mut S, t: f64, y: &[f64]) -> Result<(), Error> {
        self.newton = Some(NewtonSystems::new(sys, t, y)?);
        Ok(())
    }
    // Not inlined into the driver loop: inlined, the Newton iteration's loops lost their bounds
    // elision and cost 4 % more instructions on a lubricated cycle (codegen, measured).
    #[inline(never)]
    fn attempt(&mut self, sys: &mut S, stats: &mut Stats, st: &Settings, t: f64, t1: f64, hs: f64, y: &[f64], ynew: &mut [f64]) -> Result<Trial, Error> {
        let n = y.len();
        let Some(newton) = self.newton.as_mut() else {
            return Err(Error::invalid("radau", "not started", "the stepper's start was not called"));
        };
        if self.need_w {
            let differenced = self.differenced_left > 0;
            if self.differenced_left == 1 {
                // Back to the hook's matrix next: the failures seen with either say nothing
                // about the other.
                self.newton_limit.reset();
            }
            self.differenced_left = self.differenced_left.saturating_sub(1);
            newton.update(sys, stats, t, y, &self.f0, differenced)?;
            (self.need_w, self.fails_on_w, self.w_from_hook) = (false, 0, newton.structured() && !differenced);
        } else if self.fails_on_w >= 3 && self.w_from_hook {
            newton.update(sys, stats, t, y, &self.f0, true)?;
            (self.fails_on_w, self.w_from_hook, self.differenced_left) = (0, false, DIFFERENCED_SPELL);
            // Those failures were the hook matrix's, not the step size's.
            self.newton_limit.reset();
        }
        let k = &self.k;
        let (fac1, alphn, betan) = (k.u1 / hs, k.alpha / hs, k.beta / hs);
        newton.factor(fac1, alphn, betan);
        self.starting_values(hs);
        for i in 0..n {
            self.scal[i] = st.atol + st.rtol * y[i].abs();
        }
        let newt = match self.newton(sys, stats, t, t1, hs, y, (fac1, alphn, betan))? {
            Ok(newt) => newt,
            Err((error, fac)) => {
                self.fails_on_w += 1;
                self.reject = true;
                self.ctrl.failed();
                self.newton_limit.failed(hs);
                return Ok(Trial::Failed { error, h_next: hs * fac });
            }
        };

        // Error estimate (Hairer's ESTRAD): (σ₁I − W)⁻¹ (f0 + Σ d_i z_i / h), and once more
        // through f on the first or a rejected step when it is large.
        let Some(newton) = self.newton.as_mut() else {
            return Err(Error::invalid("radau", "not started", "the stepper's start was not called"));
        };
        let (k, z, f0, errv, e_comb, ytmp, buf, scal) = (&self.k, &self.z, &self.f0, &mut self.errv, &mut self.e_comb, &mut self.ytmp, &mut self.buf, &self.scal);
        for i in 0..n {
            e_comb[i] = (k.d[0] * z[i] + k.d[1] * z[n + i] + k.d[2] * z[2 * n + i]) / hs;
            errv[i] = f0[i] + e_comb[i];
        }
        newton.solve_real(errv);
        let mut err = rms(errv, scal);
        if err >= 1.0 && (self.first || self.reject) {
            for i in 0..n {
                ytmp[i] = y[i] + errv[i];
            }
            if sys.rhs(t, ytmp, buf).is_ok() && all_finite(buf) {
                stats.rhs_evals += 1;
                for i in 0..n {
                    errv[i] = buf[i] + e_comb[i];
                }
                newton.solve_real(errv);
                err = rms(errv, scal);
            }
        }
        if !err.is_finite() {
            self.reject = true;
            self.ctrl.failed();
            return Ok(Trial::Rejected { h_next: 0.25 * hs });
        }
        // Fewer Newton iterations, a bolder step (Hairer's FAC).
        let safety = self.ctrl.safety.min(self.ctrl.safety * (1 + 2 * NIT) as f64 / (newt + 2 * NIT) as f64);
        if let Decision::Reject { h_next } = self.ctrl.decide(err, hs, safety, !self.first) {
            self.reject = true;
            return Ok(Trial::Rejected { h_next: if self.first { 0.1 * hs } else { h_next } });
        }
        self.first = false;
        self.last_newt = newt;
        // y1 = y + Z3 (stiffly accurate); dense output through the stages.
        let (c1, c2) = (k.c[0], k.c[1]);
        let (c1m1, c2m1, c1mc2) = (c1 - 1.0, c2 - 1.0, c1 - c2);
        let cont = &mut self.dense.cont;
        for i in 0..n {
            let (z1, z2, z3) = (z[i], z[n + i], z[2 * n + i]);
            ynew[i] = y[i] + z3;
            cont[i] = ynew[i];
            cont[n + i] = (z2 - z3) / c2m1;
            let ak = (z1 - z2) / c1mc2;
            let acont3 = (ak - z1 / c1) / c2;
            cont[2 * n + i] = (ak - cont[n + i]) / c1m1;
            cont[3 * n + i] = cont[2 * n + i] - acont3;
        }
        self.dense.t0 = t;
        self.dense.t1 = t1;
        self.h_old = hs;
        Ok(Trial::Passed)
    }
    fn dense(&self) -> &dyn DenseOutput {
        &self.dense
    }
    fn redo(&mut self, h: f64) {
        self.redo_of = Some(h);
    }
    fn accepted(&mut self, h: f64) -> f64 {
        self.need_w = true;
        self.reject = false;
        let h_next = self.ctrl.size_after_accept(h);
        // The failures before this step count where it converged briskly (≤ 3 iterations): its
        // matrix is good, the size was the trouble. A slow one points at the matrix, which three
        // failures in a row replace (`fails_on_w`): a cap must not stand in their way.
        self.newton_limit.after_accept(h_next, self.last_newt <= 3)
    }
}

/// `out_s = Σ_j m_sj in_j` over the three stage blocks of length `n`.
fn transform(m: &[[f64; 3]; 3], input: &[f64], out: &mut [f64], n: usize) {
    for i in 0..n {
        let (a, b, c) = (input[i], input[n + i], input[2 * n + i]);
        for s in 0..3 {
            out[s * n + i] = m[s][0] * a + m[s][1] * b + m[s][2] * c;
        }
    }
}

/// RMS of `v / scal`.
fn rms(v: &[f64], scal: &[f64]) -> f64 {
    let s: f64 = v.iter().zip(scal).map(|(a, b)| (a / b) * (a / b)).sum();
    (s / v.len().max(1) as f64).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::{integrate, Method};

    fn mul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
        let mut c = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
            }
        }
        c
    }

    #[test]
    fn newton_tolerance_follows_hairers_rule_on_his_internal_tolerance() {
        // rtol 1e-6 → rtol' = 1e-5 → κ = √1e-5; loose tolerances cap at 0.03; a tolerance near
        // round-off is floored at 10 u / rtol'.
        assert!((newton_tolerance(1e-6) - 1e-5f64.sqrt()).abs() < 1e-12);
        assert_eq!(newton_tolerance(1e-2), 0.03);
        let rtol = 1e-14f64;
        let internal = 0.1 * rtol.powf(2.0 / 3.0);
        assert_eq!(newton_tolerance(rtol), 10.0 * f64::EPSILON / internal);
        // Monotone down to rtol ≈ 7e-14, where the round-off floor takes over: a tighter
        // tolerance never loosens the iteration.
        let grid: Vec<f64> = (0..60).map(|i| 10f64.powf(-1.0 - 0.2 * i as f64)).collect();
        assert!(grid.windows(2).all(|w| newton_tolerance(w[1]) <= newton_tolerance(w[0])));
    }

    /// `T⁻¹` is the inverse of `T`, and `T⁻¹ A⁻¹ T` is the block diagonal of the eigenvalues;
    /// the nodes are the rows sums of `A` and the zeros of the Radau polynomial.
    #[test]
    fn constants_are_consistent() {
        let k = Radau5::new();
        let a = Radau5::a();
        let id = mul(&k.ti, &k.t);
        for i in 0..3 {
            for j in 0..3 {
                assert!((id[i][j] - if i == j { 1.0 } else { 0.0 }).abs() < 1e-14, "{id:?}");
            }
            assert!((a[i].iter().sum::<f64>() - k.c[i]).abs() < 1e-15);
        }
        // T⁻¹ A⁻¹ T = D  ⇔  A T D = T.
        let d = [[k.u1, 0.0, 0.0], [0.0, k.alpha, -k.beta], [0.0, k.beta, k.alpha]];
        let atd = mul(&mul(&a, &k.t), &d);
        for i in 0..3 {
            for j in 0..3 {
                assert!((atd[i][j] - k.t[i][j]).abs() < 1e-13, "{atd:?} vs {:?}", k.t);
            }
        }
        // Radau IIA nodes: zeros of d²/dx² (x²(x − 1)³), i.e. 10x² − 8x + 1 = 0 besides x = 1.
        for c in &k.c[..2] {
            assert!((10.0 * c * c - 8.0 * c + 1.0).abs() < 1e-14);
        }
    }

    struct Sys {
        f: fn(f64, &[f64], &mut [f64]),
        outputs: Vec<(f64, Vec<f64>)>,
        w_scale: Option<f64>,
        jac: Option<fn(&[f64]) -> [[f64; 2]; 2]>,
    }

    impl OdeSystem for Sys {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
            (self.f)(t, y, dy);
            Ok(())
        }
        fn acceleration_jacobian(&mut self, _t: f64, y: &[f64], a_q: &mut [f64], a_v: &mut [f64]) -> Result<bool, Error> {
            let (Some(k), Some(jac)) = (self.w_scale, self.jac) else { return Ok(false) };
            let j = jac(y);
            a_q[0] = k * j[1][0];
            a_v[0] = k * j[1][1];
            Ok(true)
        }
        fn step_accepted(&mut self, t0: f64, y0: &[f64], t1: f64, y1: &[f64], d: &dyn DenseOutput) -> Result<bool, Error> {
            let mut b = [0.0; 2];
            d.eval(t0, &mut b);
            assert!(b.iter().zip(y0).all(|(a, c)| (a - c).abs() <= 1e-12 * (1.0 + c.abs())), "{b:?} vs {y0:?}");
            d.eval(t1, &mut b);
            assert!(b.iter().zip(y1).all(|(a, c)| (a - c).abs() <= 1e-14 * (1.0 + c.abs())));
            let tm = 0.3 * t0 + 0.7 * t1;
            d.eval(tm, &mut b);
            assert!(b.iter().enumerate().all(|(i, v)| d.eval_component(tm, i) == *v));
            Ok(false)
        }
        fn output(&mut self, t: f64, y: &[f64]) -> Result<(), Error> {
            self.outputs.push((t, y.to_vec()));
            Ok(())
        }
    }

    fn vdp(mu: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = mu * (1.0 - y[0] * y[0]) * y[1] - y[0];
    }
    fn vdp1(_t: f64, y: &[f64], dy: &mut [f64]) {
        vdp(1.0, y, dy)
    }
    fn vdp1_jac(y: &[f64]) -> [[f64; 2]; 2] {
        [[0.0, 1.0], [-2.0 * y[0] * y[1] - 1.0, 1.0 - y[0] * y[0]]]
    }
    fn vdp1000(_t: f64, y: &[f64], dy: &mut [f64]) {
        vdp(1000.0, y, dy)
    }
    fn vdp1000_jac(y: &[f64]) -> [[f64; 2]; 2] {
        [[0.0, 1.0], [-2000.0 * y[0] * y[1] - 1.0, 1000.0 * (1.0 - y[0] * y[0])]]
    }
    /// y'' = −y with y(0) = 1: exact cos t (for the dense output).
    fn oscillator(_t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = -y[0];
    }

    fn reference(f: fn(f64, &[f64], &mut [f64]), y0: &[f64], t_end: f64) -> Vec<f64> {
        let s = Settings { rtol: 1e-12, atol: 1e-12, ..Settings::default() };
        let mut sys = Sys { f, outputs: vec![], w_scale: None, jac: None };
        integrate(&mut sys, Method::Dop853, 0.0, y0, t_end, &[t_end], &s).unwrap();
        sys.outputs[0].1.clone()
    }

    /// A forced, damped oscillator (linear, non-autonomous): q̈ = −q − 0.1 q̇ + cos 2t.
    fn forced(t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = -y[0] - 0.1 * y[1] + (2.0 * t).cos();
    }
    fn forced_jac(_y: &[f64]) -> [[f64; 2]; 2] {
        [[0.0, 1.0], [-1.0, -0.1]]
    }

    /// Fixed steps: order 5 at the step ends. The problem is linear, so with the exact Newton
    /// matrix one iteration solves the stage equations whatever the (huge, rejection-free)
    /// tolerances; the finite-difference fallback needs a second.
    #[test]
    fn order_five_with_fixed_steps() {
        let ex = reference(forced, &[1.0, 0.0], 4.0);
        for (w, jac) in [(Some(1.0), Some(forced_jac as fn(&[f64]) -> [[f64; 2]; 2])), (None, None)] {
            let errs: Vec<f64> = [10, 20, 40]
                .iter()
                .map(|&steps| {
                    let h = 4.0 / steps as f64;
                    let s = Settings { rtol: 1e-3, atol: 1e6, h0: Some(h), h_max: h, ..Settings::default() };
                    let mut sys = Sys { f: forced, outputs: vec![], w_scale: w, jac };
                    let st = integrate(&mut sys, Method::Radau, 0.0, &[1.0, 0.0], 4.0, &[4.0], &s).unwrap();
                    assert_eq!(st.steps_accepted, steps);
                    let y = &sys.outputs[0].1;
                    ((y[0] - ex[0]).powi(2) + (y[1] - ex[1]).powi(2)).sqrt()
                })
                .collect();
            for p in errs.windows(2).map(|e| (e[0] / e[1]).log2()) {
                assert!((4.6..5.6).contains(&p), "W = {w:?}: observed order {p} from {errs:?}");
            }
        }
    }

    /// The converged stages do not depend on the Newton matrix: an exact, a halved and a
    /// differenced W give the reference solution of a nonlinear problem to the tolerance.
    #[test]
    fn any_newton_matrix_converges_to_the_solution() {
        let ex = reference(vdp1, &[2.0, 0.0], 3.0);
        for w in [Some(1.0), Some(0.5), None] {
            let s = Settings { rtol: 1e-9, atol: 1e-9, ..Settings::default() };
            let mut sys = Sys { f: vdp1, outputs: vec![], w_scale: w, jac: Some(vdp1_jac) };
            integrate(&mut sys, Method::Radau, 0.0, &[2.0, 0.0], 3.0, &[3.0], &s).unwrap();
            let y = &sys.outputs[0].1;
            assert!((y[0] - ex[0]).abs() < 1e-7 && (y[1] - ex[1]).abs() < 1e-7, "W = {w:?}: {y:?} vs {ex:?}");
        }
    }

    #[test]
    fn van_der_pol_mu_1000_is_solved_with_few_steps() {
        let t_end = 1500.0;
        let yd = reference(vdp1000, &[2.0, 0.0], t_end);
        let s = Settings { rtol: 1e-7, atol: 1e-7, ..Settings::default() };
        for (w, jac) in [(Some(1.0), Some(vdp1000_jac as fn(&[f64]) -> [[f64; 2]; 2])), (None, None)] {
            let mut sys = Sys { f: vdp1000, outputs: vec![], w_scale: w, jac };
            let st = integrate(&mut sys, Method::Radau, 0.0, &[2.0, 0.0], t_end, &[t_end], &s).unwrap();
            let yr = &sys.outputs[0].1;
            assert!((yr[0] - yd[0]).abs() < 1e-4 * yd[0].abs().max(1.0), "{yr:?} vs {yd:?}");
            // Hairer–Wanner report a few hundred steps for this problem; an explicit method
            // needs ~1e6.
            assert!(st.steps_accepted < 3000, "{st:?}");
        }
    }

    /// A hook that supplies a useless `W` (zero) on a stiff problem: after three failed trial
    /// steps the driver differences the whole right-hand side instead, so the run still takes
    /// steps of the stiff method's size (a zero `W` alone would be an explicit iteration).
    #[test]
    fn a_poor_hook_matrix_is_replaced_by_a_differenced_one() {
        let t_end = 1500.0;
        let yd = reference(vdp1000, &[2.0, 0.0], t_end);
        let s = Settings { rtol: 1e-7, atol: 1e-7, max_steps: 20_000, ..Settings::default() };
        let mut sys = Sys { f: vdp1000, outputs: vec![], w_scale: Some(0.0), jac: Some(vdp1000_jac) };
        let st = integrate(&mut sys, Method::Radau, 0.0, &[2.0, 0.0], t_end, &[t_end], &s).unwrap();
        let yr = &sys.outputs[0].1;
        assert!((yr[0] - yd[0]).abs() < 1e-4 * yd[0].abs().max(1.0), "{yr:?} vs {yd:?}");
        assert!(st.steps_accepted < 3000 && st.jacobians > st.steps_accepted, "{st:?}");
    }

    #[test]
    fn dense_output_is_accurate_between_steps() {
        let s = Settings { rtol: 1e-8, atol: 1e-10, ..Settings::default() };
        let mut sys = Sys { f: oscillator, outputs: vec![], w_scale: None, jac: None };
        let ts: Vec<f64> = (0..=200).map(|k| 0.05 * k as f64).collect();
        integrate(&mut sys, Method::Radau, 0.0, &[1.0, 0.0], 10.0, &ts, &s).unwrap();
        assert_eq!(sys.outputs.len(), ts.len());
        let worst = sys.outputs.iter().map(|(t, y)| (y[0] - t.cos()).abs().max((y[1] + t.sin()).abs())).fold(0.0, f64::max);
        assert!(worst < 1e-6, "worst dense error {worst}");
    }

    /// Robertson's chemical kinetics (Hairer–Wanner II, §IV.1; not second order: the
    /// finite-difference path with full-size systems), against the literature values at t = 40.
    struct Robertson(Vec<f64>);

    impl OdeSystem for Robertson {
        fn dim(&self) -> usize {
            3
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
            dy[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
            dy[2] = 3e7 * y[1] * y[1];
            dy[1] = -dy[0] - dy[2];
            Ok(())
        }
        fn output(&mut self, _t: f64, y: &[f64]) -> Result<(), Error> {
            self.0 = y.to_vec();
            Ok(())
        }
    }

    #[test]
    fn robertson_matches_the_literature_with_few_steps() {
        let lit = [0.7158270687193605, 9.185534764529569e-06, 0.2841637457458749];
        let s = Settings { rtol: 1e-7, atol: 1e-12, ..Settings::default() };
        let mut sys = Robertson(vec![]);
        let st = integrate(&mut sys, Method::Radau, 0.0, &[1.0, 0.0, 0.0], 40.0, &[40.0], &s).unwrap();
        let y = &sys.0;
        assert!((y[0] - lit[0]).abs() < 1e-6 && (y[2] - lit[2]).abs() < 1e-6, "{y:?}");
        assert!((y[1] / lit[1] - 1.0).abs() < 1e-4, "{y:?}");
        assert!(st.steps_accepted < 200, "{st:?}");
    }

    fn blow_up(_t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = y[0] * y[0] * y[0];
    }

    #[test]
    fn errors_follow_the_contract() {
        let mut sys = Sys { f: blow_up, outputs: vec![], w_scale: None, jac: None };
        let (e, _) = integrate(&mut sys, Method::Radau, 0.0, &[1.0, 1.0], 10.0, &[], &Settings::default()).unwrap_err();
        assert!(matches!(e, Error::StepSizeUnderflow { .. } | Error::NonFinite { .. }), "{e:?}");
        let mut sys = Sys { f: vdp1, outputs: vec![], w_scale: None, jac: None };
        let s = Settings { max_steps: 5, ..Settings::default() };
        let (e, st) = integrate(&mut sys, Method::Radau, 0.0, &[2.0, 0.0], 100.0, &[], &s).unwrap_err();
        assert!(matches!(e, Error::TooManySteps { max_steps: 5, .. }), "{e:?}");
        assert_eq!(st.steps_accepted + st.steps_rejected, 5);
    }
}
