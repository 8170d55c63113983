//! RODAS4: a stiffly accurate, L-stable Rosenbrock method of order 4 with an embedded 3rd-order
//! error estimate and a 3rd-order dense output (Hairer & Wanner, *Solving ODEs II*, §IV.7 and
//! §VI.4; coefficients and algorithm of their code `RODAS`, `METH = 1`).
//!
//! For stiff phases of a mechanism: a lubricated joint whose film squeeze term grows without
//! bound as ε → 1 (low viscosity, small clearance), high contact stiffness, or a journal resting
//! in the film-to-contact transition. Each step solves six linear systems with the same matrix
//! `E = I/(hγ) − J`, where `J = ∂f/∂y` is a forward-difference Jacobian (one `f` per state
//! component, recomputed after every accepted step and kept on rejections) and `∂f/∂t` a forward
//! difference in `t`. `E` is factorised by [`Lu`] (`lu.rs`); the whole workspace is allocated
//! once per run. A mechanism hands its Jacobian over in lifted sparse form instead (`lifted.rs`:
//! `A₀` and the derivatives `K` of its KKT right-hand side, differenced by the mechanism in a few
//! groups of bodies), and `E` is solved through it, in time and storage linear in the
//! mechanism's size; `J` stays the whole derivative (a Rosenbrock method's order needs the exact
//! Jacobian). It is taken at every size: on one cycle of the fixtures it costs 46 % fewer
//! instructions on the lubricated nine-bar and 63 % fewer on the lubricated slider-crank (whose
//! differenced `f` gave a Jacobian poor enough for 627 rejected steps against 33), and it costs
//! `6·g + 2` residuals (`g`: groups of bodies, 3–5 for a chain) instead of `n + 1` right-hand sides.
//! Oil temperatures after (q, v) (heated joints) border the lifted `E` as they border RADAU5's
//! (`border.rs`: a Schur complement on the temperatures around the lifted solves, their rows and
//! columns from [`OdeSystem::border_jacobian`]).
//!
//! In the transformed form (Hairer–Wanner IV.7.25) with `u_i` the stage increments,
//! `(I/(hγ) − J) u_i = f(t + c_i h, y + Σ_{j<i} a_ij u_j) + Σ_{j<i} (c_ij/h) u_j + h d_i f_t`;
//! the method is stiffly accurate, so `y1 = y + a_51..a_54 u + u_5 + u_6` and `u_6` is the error.
//! Dense output: `y(θ) = (1−θ) y0 + θ (y1 + (1−θ)(r2 + θ r3))`, `r2 = Σ d2j u_j`, `r3 = Σ d3j u_j`.
//!
//! Cost per step: `n + 7` evaluations of `f` (Jacobian, `f_t`, the initial `f` and five stages)
//! and one LU of an `n × n` matrix (lifted: `6·g + 9` evaluations and one sparse LU): much more
//! than an explicit step, worth it when an explicit method is held to tiny steps by stability
//! rather than accuracy.

use faer::Mat;

use super::border::Border;
use super::controller::{Decision, Predictive};
use super::driver::{non_finite, Stepper, Trial};
use super::lifted::Lifted;
use super::lu::Lu;
use super::method::{Settings, Stats};
use super::ode::{DenseOutput, OdeSystem};
use crate::error::Error;

/// Coefficients of RODAS4 (Hairer's `ROCOE`, `METH = 1`).
#[allow(clippy::excessive_precision)]
mod coefficients {
    pub const GAMMA: f64 = 0.25;
    pub const C2: f64 = 0.386;
    pub const C3: f64 = 0.21;
    pub const C4: f64 = 0.63;
    /// `γ_i` multiplying `h f_t` in stages 1–4 (stages 5–6: 0).
    pub const D: [f64; 4] = [0.25, -0.1043, 0.1035, -0.03620000000000023];
    pub const A21: f64 = 1.544;
    pub const A31: f64 = 0.9466785280815826;
    pub const A32: f64 = 0.2557011698983284;
    pub const A41: f64 = 3.314825187068521;
    pub const A42: f64 = 2.896124015972201;
    pub const A43: f64 = 0.9986419139977817;
    pub const A51: f64 = 1.221224509226641;
    pub const A52: f64 = 6.019134481288629;
    pub const A53: f64 = 12.53708332932087;
    pub const A54: f64 = -0.687886036105895;
    pub const C21: f64 = -5.6688;
    pub const C31: f64 = -2.430093356833875;
    pub const C32: f64 = -0.2063599157091915;
    pub const C41: f64 = -0.1073529058151375;
    pub const C42: f64 = -9.594562251023355;
    pub const C43: f64 = -20.47028614809616;
    pub const C51: f64 = 7.496443313967647;
    pub const C52: f64 = -10.24680431464352;
    pub const C53: f64 = -33.99990352819905;
    pub const C54: f64 = 11.7089089320616;
    pub const C61: f64 = 8.083246795921522;
    pub const C62: f64 = -7.981132988064893;
    pub const C63: f64 = -31.52159432874371;
    pub const C64: f64 = 16.31930543123136;
    pub const C65: f64 = -6.058818238834054;
    /// Dense output rows `r2`, `r3` (weights of `u_1..u_5`).
    pub const D2: [f64; 5] = [10.12623508344586, -7.487995877610167, -34.80091861555747, -7.992771707568823, 1.025137723295662];
    pub const D3: [f64; 5] = [-0.6762803392801253, 6.087714651680015, 16.43084320892478, 24.76722511418386, -6.594389125716872];
}

const UROUND: f64 = f64::EPSILON;

/// Dense output of one RODAS4 step.
struct RodasDense {
    t0: f64,
    t1: f64,
    y0: Vec<f64>,
    y1: Vec<f64>,
    r2: Vec<f64>,
    r3: Vec<f64>,
}

impl DenseOutput for RodasDense {
    fn interval(&self) -> (f64, f64) {
        (self.t0, self.t1)
    }
    #[inline]
    fn component(&self, s: f64, i: usize) -> f64 {
        let s1 = 1.0 - s;
        s1 * self.y0[i] + s * (self.y1[i] + s1 * (self.r2[i] + s * self.r3[i]))
    }
}

/// `out = y + Σ w_j u_j` (`u_j = u[j*n..]`).
fn lincomb(out: &mut [f64], y: &[f64], w: &[f64], u: &[f64]) {
    let n = out.len();
    out.copy_from_slice(y);
    for (j, &wj) in w.iter().enumerate() {
        for (o, v) in out.iter_mut().zip(&u[j * n..(j + 1) * n]) {
            *o += wj * v;
        }
    }
}

/// `out = Σ w_j u_j`.
fn weighted(out: &mut [f64], w: &[f64], u: &[f64]) {
    let n = out.len();
    out.fill(0.0);
    for (j, &wj) in w.iter().enumerate() {
        for (o, v) in out.iter_mut().zip(&u[j * n..(j + 1) * n]) {
            *o += wj * v;
        }
    }
}

/// `E = I/(hγ) − J`, factorised in dense or lifted form (the lifted one bordered by any oil
/// temperatures after (q, v): `border.rs`).
enum IterationMatrix<'a> {
    Dense(&'a mut Lu),
    Lifted(&'a mut Lifted, Option<&'a mut Border>),
}

impl IterationMatrix<'_> {
    /// `x ← E⁻¹ x`.
    fn solve(&mut self, x: &mut [f64]) {
        match self {
            IterationMatrix::Dense(lu) => lu.solve(x),
            IterationMatrix::Lifted(lifted, None) => lifted.solve_real(x),
            IterationMatrix::Lifted(lifted, Some(border)) => border.solve_real(x, |v| lifted.solve_real(v)),
        }
    }
}

/// The RODAS4 stepper (the step of Hairer's `ROSCOR`): `J` and `∂f/∂t` recomputed after every
/// accepted step and kept on rejections; a trial whose error is not finite (a singular or
/// hopeless iteration matrix) is retried with half the step, up to four times in a row.
pub(super) struct Rodas4 {
    f0: Vec<f64>,
    /// `∂f/∂t`.
    ft: Vec<f64>,
    dy: Vec<f64>,
    ysafe: Vec<f64>,
    /// Stage increments `u_1..u_6`.
    u: Vec<f64>,
    /// The dense `J` and the LU of `E` (sized in [`Stepper::start`]), or the lifted form.
    jac: Mat<f64>,
    lu: Lu,
    lifted: Option<Lifted>,
    /// With the lifted form, the rows and columns of the first-order states after (q, v)
    /// ([`OdeSystem::first_order_states`]: oil temperatures), their exact derivatives from
    /// [`OdeSystem::border_jacobian`].
    border: Option<Border>,
    dense: RodasDense,
    need_jac: bool,
    /// Step-size control of RODAS: Gustafsson's predictive controller after the first accepted step.
    ctrl: Predictive,
}

impl Rodas4 {
    pub(super) fn new(n: usize) -> Self {
        Rodas4 {
            f0: vec![0.0; n],
            ft: vec![0.0; n],
            dy: vec![0.0; n],
            ysafe: vec![0.0; n],
            u: vec![0.0; 6 * n],
            jac: Mat::zeros(0, 0),
            lu: Lu::new(0),
            lifted: None,
            border: None,
            dense: RodasDense { t0: 0.0, t1: 0.0, y0: vec![0.0; n], y1: vec![0.0; n], r2: vec![0.0; n], r3: vec![0.0; n] },
            need_jac: true,
            ctrl: Predictive::rodas(),
        }
    }

    /// `∂f/∂t` and `J = ∂f/∂y` at `(t, y)` by forward differences (RODAS's increments).
    fn jacobian<S: OdeSystem>(&mut self, sys: &mut S, stats: &mut Stats, t: f64, y: &[f64]) -> Result<(), Error> {
        let n = y.len();
        let (f0, ft, dy) = (&self.f0, &mut self.ft, &mut self.dy);
        let delt = (UROUND * t.abs().max(1e-5)).sqrt();
        sys.rhs(t + delt, y, ft)?;
        for i in 0..n {
            ft[i] = (ft[i] - f0[i]) / delt;
        }
        if let Some(lifted) = self.lifted.as_mut() {
            stats.rhs_evals += 1 + lifted.update(sys, t, y, true)?;
            if let Some(b) = self.border.as_mut() {
                sys.border_jacobian(t, y, &mut b.a_z, &mut b.g_y)?;
            }
            stats.jacobians += 1;
            return Ok(());
        }
        self.ysafe.copy_from_slice(y);
        for j in 0..n {
            self.ysafe[j] = y[j] + sys.difference_step(j, y);
            let delt = self.ysafe[j] - y[j]; // the step actually taken
            sys.rhs(t, &self.ysafe, dy)?;
            self.ysafe[j] = y[j];
            for i in 0..n {
                self.jac[(i, j)] = (dy[i] - f0[i]) / delt;
            }
        }
        stats.rhs_evals += n + 1;
        stats.jacobians += 1;
        Ok(())
    }
}

impl<S: OdeSystem> Stepper<S> for Rodas4 {
    fn order(&self) -> usize {
        4
    }
    fn max_trial_failures(&self) -> usize {
        4
    }
    fn f0(&mut self) -> &mut [f64] {
        &mut self.f0
    }
    fn start(&mut self, sys: &mut S, _t: f64, y: &[f64]) -> Result<(), Error> {
        let n = y.len();
        let extra = sys.first_order_states().min(n);
        match sys.lifted_pattern().filter(|p| 2 * p.coords + extra == n) {
            Some(pattern) => {
                self.border = (extra > 0).then(|| Border::new(pattern.coords, extra));
                self.lifted = Some(Lifted::new(pattern, false));
            }
            None => (self.jac, self.lu) = (Mat::zeros(n, n), Lu::new(n)),
        }
        Ok(())
    }
    fn attempt(&mut self, sys: &mut S, stats: &mut Stats, st: &Settings, t: f64, t1: f64, hs: f64, y: &[f64], ynew: &mut [f64]) -> Result<Trial, Error> {
        use coefficients::*;
        let n = y.len();
        if self.need_jac {
            self.jacobian(sys, stats, t, y)?;
            self.need_jac = false;
        }
        let (f0, ft, dy, u) = (&self.f0, &self.ft, &mut self.dy, &mut self.u);
        let fac = 1.0 / (hs * GAMMA);
        let mut lu = match self.lifted.as_mut() {
            Some(lifted) => {
                lifted.factor_real(fac);
                if let Some(border) = self.border.as_mut() {
                    border.factor_real(fac, |x| lifted.solve_real(x));
                }
                IterationMatrix::Lifted(lifted, self.border.as_mut())
            }
            None => {
                self.lu.factor(&self.jac, fac);
                IterationMatrix::Dense(&mut self.lu)
            }
        };
        let hd: [f64; 4] = [hs * D[0], hs * D[1], hs * D[2], hs * D[3]];
        // Stage 1.
        for i in 0..n {
            u[i] = f0[i] + hd[0] * ft[i];
        }
        lu.solve(&mut u[..n]);
        // Stages 2..6.
        let stage_a: [&[f64]; 4] = [&[A21], &[A31, A32], &[A41, A42, A43], &[A51, A52, A53, A54]];
        let stage_c: [&[f64]; 5] = [&[C21], &[C31, C32], &[C41, C42, C43], &[C51, C52, C53, C54], &[C61, C62, C63, C64, C65]];
        let stage_t = [t + C2 * hs, t + C3 * hs, t + C4 * hs, t1, t1];
        for s in 1..6 {
            if s < 5 {
                lincomb(ynew, y, stage_a[s - 1], u);
            } else {
                // Embedded solution y + Σ a5j u_j + u_5, already in ynew after stage 5.
                for i in 0..n {
                    ynew[i] += u[4 * n + i];
                }
            }
            sys.rhs(stage_t[s - 1], ynew, dy)?;
            stats.rhs_evals += 1;
            let (done, cur) = u.split_at_mut(s * n);
            let cur = &mut cur[..n];
            cur.copy_from_slice(dy);
            if s < 4 {
                let hds = hd[s];
                for i in 0..n {
                    cur[i] += hds * ft[i];
                }
            }
            for (j, &cij) in stage_c[s - 1].iter().enumerate() {
                let w = cij / hs;
                for (c, v) in cur.iter_mut().zip(&done[j * n..(j + 1) * n]) {
                    *c += w * v;
                }
            }
            lu.solve(cur);
        }
        for i in 0..n {
            ynew[i] += u[5 * n + i];
        }

        // Error estimate u_6, RMS norm scaled by atol + rtol·max(|y|, |y1|).
        let mut err = 0.0;
        for i in 0..n {
            let sk = st.atol + st.rtol * y[i].abs().max(ynew[i].abs());
            err += (u[5 * n + i] / sk) * (u[5 * n + i] / sk);
        }
        let err = (err / n.max(1) as f64).sqrt();
        if !err.is_finite() {
            // A singular or hopeless iteration matrix: halve the step (RODAS).
            self.ctrl.failed();
            return Ok(Trial::Failed { error: non_finite(t), h_next: 0.5 * hs });
        }
        if let Decision::Reject { h_next } = self.ctrl.decide(err, hs, self.ctrl.safety, stats.steps_accepted > 0) {
            return Ok(Trial::Rejected { h_next });
        }
        // Dense output of [t, t1].
        let dense = &mut self.dense;
        dense.t0 = t;
        dense.t1 = t1;
        dense.y0.copy_from_slice(y);
        dense.y1.copy_from_slice(ynew);
        weighted(&mut dense.r2, &D2, u);
        weighted(&mut dense.r3, &D3, u);
        Ok(Trial::Passed)
    }
    fn dense(&self) -> &dyn DenseOutput {
        &self.dense
    }
    fn accepted(&mut self, h: f64) -> f64 {
        self.need_jac = true;
        self.ctrl.size_after_accept(h)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::excessive_precision)] // literature values of the test problems
    use super::super::{integrate, DenseOutput, Method, OdeSystem, Settings, Stats};
    use crate::error::Error;

    type Rhs = fn(f64, &[f64], &mut [f64]) -> Result<(), Error>;

    struct Sys {
        dim: usize,
        f: Rhs,
        outputs: Vec<(f64, Vec<f64>)>,
        accepted: usize,
        /// Largest |dense(t) − exact(t)| at step midpoints, when `exact` is given.
        exact: Option<fn(f64) -> Vec<f64>>,
        dense_err: f64,
    }

    impl Sys {
        fn new(dim: usize, f: Rhs) -> Self {
            Sys { dim, f, outputs: vec![], accepted: 0, exact: None, dense_err: 0.0 }
        }
    }

    impl OdeSystem for Sys {
        fn dim(&self) -> usize {
            self.dim
        }
        fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
            (self.f)(t, y, dy)
        }
        fn step_accepted(&mut self, t0: f64, y0: &[f64], t1: f64, y1: &[f64], d: &dyn DenseOutput) -> Result<bool, Error> {
            assert_eq!(d.interval(), (t0, t1));
            let mut b = vec![0.0; self.dim];
            d.eval(t0, &mut b);
            assert!(b.iter().zip(y0).all(|(a, c)| (a - c).abs() <= 1e-14 * (1.0 + c.abs())));
            d.eval(t1, &mut b);
            assert!(b.iter().zip(y1).all(|(a, c)| (a - c).abs() <= 1e-14 * (1.0 + c.abs())));
            let tq = 0.3 * t0 + 0.7 * t1;
            d.eval(tq, &mut b);
            assert!(b.iter().enumerate().all(|(i, v)| d.eval_component(tq, i) == *v));
            if let Some(ex) = self.exact {
                let tm = 0.5 * (t0 + t1);
                d.eval(tm, &mut b);
                let e = ex(tm);
                // Local dense error relative to the step's own end-point error.
                let y1e = ex(t1);
                let end_err = y1.iter().zip(&y1e).map(|(a, c)| (a - c).abs()).fold(0.0, f64::max);
                let mid_err = b.iter().zip(&e).map(|(a, c)| (a - c).abs()).fold(0.0, f64::max);
                self.dense_err = self.dense_err.max(mid_err - end_err);
            }
            self.accepted += 1;
            Ok(false)
        }
        fn output(&mut self, t: f64, y: &[f64]) -> Result<(), Error> {
            self.outputs.push((t, y.to_vec()));
            Ok(())
        }
    }

    /// y' = −y + sin t·y₂ …: a smooth non-autonomous linear test with a known solution
    /// y = (cos t, sin t)·e^{−t/10}.
    fn spiral(_t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
        dy[0] = -0.1 * y[0] - y[1];
        dy[1] = y[0] - 0.1 * y[1];
        Ok(())
    }
    fn spiral_exact(t: f64) -> Vec<f64> {
        let d = (-0.1 * t).exp();
        vec![d * t.cos(), d * t.sin()]
    }
    /// Non-autonomous scalar: y' = −50 (y − cos t), exact solution from y(0) = 0.
    fn prothero(t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
        dy[0] = -50.0 * (y[0] - t.cos());
        Ok(())
    }
    fn prothero_exact(t: f64) -> f64 {
        // y = (2500 cos t + 50 sin t)/2501 − 2500/2501 e^{−50t}
        (2500.0 * t.cos() + 50.0 * t.sin()) / 2501.0 - 2500.0 / 2501.0 * (-50.0 * t).exp()
    }

    fn fixed(f: Rhs, y0: &[f64], t_end: f64, steps: usize) -> Vec<f64> {
        let h = t_end / steps as f64;
        let s = Settings { rtol: 1e6, atol: 1e6, h0: Some(h), h_max: h, ..Settings::default() };
        let mut sys = Sys::new(y0.len(), f);
        let st = integrate(&mut sys, Method::Rodas4, 0.0, y0, t_end, &[t_end], &s).unwrap();
        assert_eq!(st.steps_accepted, steps);
        assert_eq!(st.steps_rejected, 0);
        sys.outputs[0].1.clone()
    }

    fn dist(a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>().sqrt()
    }

    #[test]
    fn observed_order_is_four() {
        let ex = spiral_exact(4.0);
        let errs: Vec<f64> = [10, 20, 40].iter().map(|&n| dist(&fixed(spiral, &[1.0, 0.0], 4.0, n), &ex)).collect();
        for w in errs.windows(2) {
            let p = (w[0] / w[1]).log2();
            assert!((3.6..4.6).contains(&p), "observed order {p} from {errs:?}");
        }
        // Non-autonomous (∂f/∂t by differences), beyond the stiff transient.
        let ex = [prothero_exact(2.0)];
        let errs: Vec<f64> = [20, 40, 80].iter().map(|&n| dist(&fixed(prothero, &[0.0], 2.0, n), &ex)).collect();
        let p = (errs[1] / errs[2]).log2();
        assert!(p > 3.0, "observed order {p} from {errs:?}");
    }

    /// Van der Pol with μ = 1: nonlinear and non-stiff, so every order condition of the
    /// method shows (a linear test checks only a subset).
    pub(super) fn vdp1(_t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
        dy[0] = y[1];
        dy[1] = (1.0 - y[0] * y[0]) * y[1] - y[0];
        Ok(())
    }

    #[test]
    fn observed_order_is_four_on_a_nonlinear_problem() {
        let s = Settings { rtol: 1e-13, atol: 1e-13, ..Settings::default() };
        let mut sys = Sys::new(2, vdp1);
        integrate(&mut sys, Method::Dop853, 0.0, &[2.0, 0.0], 2.0, &[2.0], &s).unwrap();
        let ex = sys.outputs[0].1.clone();
        // Coarse steps: below ~1e-9 the forward-difference Jacobian's error (a W-method term,
        // O(h²·δ)) takes over.
        let errs: Vec<f64> = [10, 20, 40, 80].iter().map(|&n| dist(&fixed(vdp1, &[2.0, 0.0], 2.0, n), &ex)).collect();
        for w in errs.windows(2) {
            let p = (w[0] / w[1]).log2();
            assert!((3.6..5.5).contains(&p), "observed order {p} from {errs:?}");
        }
    }

    #[test]
    fn dense_output_is_accurate_between_steps() {
        let mut sys = Sys::new(2, spiral);
        sys.exact = Some(spiral_exact);
        let s = Settings { rtol: 1e-8, atol: 1e-10, ..Settings::default() };
        let ts: Vec<f64> = (0..=100).map(|k| 0.1 * k as f64).collect();
        let st = integrate(&mut sys, Method::Rodas4, 0.0, &[1.0, 0.0], 10.0, &ts, &s).unwrap();
        assert_eq!(sys.outputs.len(), 101);
        assert_eq!(sys.accepted, st.steps_accepted);
        assert!(sys.dense_err < 1e-6, "dense error {}", sys.dense_err);
        let worst = sys.outputs.iter().map(|(t, y)| dist(y, &spiral_exact(*t))).fold(0.0, f64::max);
        assert!(worst < 1e-6, "worst output error {worst}");
    }

    /// Robertson's chemical kinetics (Hairer–Wanner II, §IV.1), stiffness ~1e4.
    fn robertson(_t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
        dy[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
        dy[2] = 3e7 * y[1] * y[1];
        dy[1] = -dy[0] - dy[2];
        Ok(())
    }

    fn run(method: Method, f: Rhs, y0: &[f64], t_end: f64, rtol: f64, atol: f64) -> (Stats, Vec<f64>) {
        let s = Settings { rtol, atol, ..Settings::default() };
        let mut sys = Sys::new(y0.len(), f);
        let st = integrate(&mut sys, method, 0.0, y0, t_end, &[t_end], &s).unwrap();
        (st, sys.outputs[0].1.clone())
    }

    #[test]
    fn robertson_matches_reference_with_few_steps() {
        // Reference y(40) (Hairer–Wanner II, Table of the Robertson problem), and DOP853 at 1e-12.
        let lit = [0.7158270687193605, 9.185534764529569e-06, 0.2841637457458749];
        let (sd, yd) = run(Method::Dop853, robertson, &[1.0, 0.0, 0.0], 40.0, 1e-12, 1e-16);
        assert!((yd[0] - lit[0]).abs() < 1e-10 && (yd[1] / lit[1] - 1.0).abs() < 1e-7, "{yd:?}");
        let (sr, yr) = run(Method::Rodas4, robertson, &[1.0, 0.0, 0.0], 40.0, 1e-7, 1e-12);
        assert!((yr[0] - lit[0]).abs() < 1e-6, "{yr:?}");
        assert!((yr[1] / lit[1] - 1.0).abs() < 1e-4, "{yr:?}");
        assert!((yr[2] - lit[2]).abs() < 1e-6, "{yr:?}");
        assert!(sr.steps_accepted * 20 < sd.steps_accepted, "rodas {} vs dop853 {}", sr.steps_accepted, sd.steps_accepted);
    }

    /// Van der Pol, μ = 1000 (y₁'' − μ(1 − y₁²) y₁' + y₁ = 0).
    fn vdp(_t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
        dy[0] = y[1];
        dy[1] = 1000.0 * (1.0 - y[0] * y[0]) * y[1] - y[0];
        Ok(())
    }

    #[test]
    fn van_der_pol_mu_1000_matches_dop853_reference() {
        let t_end = 1500.0;
        let (sd, yd) = run(Method::Dop853, vdp, &[2.0, 0.0], t_end, 1e-11, 1e-11);
        let (sr, yr) = run(Method::Rodas4, vdp, &[2.0, 0.0], t_end, 1e-7, 1e-7);
        assert!((yr[0] - yd[0]).abs() < 1e-4 * yd[0].abs().max(1.0), "{yr:?} vs {yd:?}");
        assert!((yr[1] - yd[1]).abs() < 1e-3 * yd[1].abs().max(1e-3), "{yr:?} vs {yd:?}");
        assert!(sr.steps_accepted * 20 < sd.steps_accepted, "rodas {} vs dop853 {}", sr.steps_accepted, sd.steps_accepted);
    }

    fn nan_after_1(t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
        dy[0] = if t > 1.0 { f64::NAN } else { -y[0] };
        Ok(())
    }
    fn blow_up(_t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
        dy[0] = y[0] * y[0];
        Ok(())
    }

    #[test]
    fn errors_follow_the_contract() {
        let s = Settings::default();
        let mut sys = Sys::new(1, nan_after_1);
        let ts = [0.5, 0.9, 1.5];
        let (e, st) = integrate(&mut sys, Method::Rodas4, 0.0, &[1.0], 2.0, &ts, &s).unwrap_err();
        assert!(matches!(e, Error::NonFinite { t, .. } if t <= 1.0 + 1e-9), "{e:?}");
        assert_eq!(sys.outputs.len(), 2);
        assert!(st.t_reached <= 1.0);
        let mut sys = Sys::new(1, blow_up);
        let (e, _) = integrate(&mut sys, Method::Rodas4, 0.0, &[1.0], 2.0, &[], &s).unwrap_err();
        assert!(matches!(e, Error::StepSizeUnderflow { .. } | Error::NonFinite { .. }), "{e:?}");
        let mut sys = Sys::new(2, spiral);
        let s2 = Settings { max_steps: 5, ..s };
        let (e, st) = integrate(&mut sys, Method::Rodas4, 0.0, &[1.0, 0.0], 100.0, &[], &s2).unwrap_err();
        assert!(matches!(e, Error::TooManySteps { max_steps: 5, .. }), "{e:?}");
        assert_eq!(st.steps_accepted + st.steps_rejected, 5);
        let s3 = Settings { h_min: 1.0, h0: Some(1.0), ..s };
        let mut sys = Sys::new(1, blow_up);
        let (e, _) = integrate(&mut sys, Method::Rodas4, 0.0, &[1.0], 2.0, &[], &s3).unwrap_err();
        assert!(matches!(e, Error::StepSizeUnderflow { .. }), "{e:?}");
    }

    #[test]
    fn stats_and_outputs_are_consistent() {
        let s = Settings { rtol: 1e-6, atol: 1e-9, h_max: 0.3, ..Settings::default() };
        let mut sys = Sys::new(2, spiral);
        let ts = [0.0, 1.0, 5.0, 5.0 + 1e-9, 7.0];
        let st = integrate(&mut sys, Method::Rodas4, 0.0, &[1.0, 0.0], 7.0, &ts, &s).unwrap();
        assert_eq!(st.t_reached, 7.0);
        assert!(st.h_max_used <= 0.3 + 1e-15);
        assert_eq!(sys.outputs.len(), 5);
        assert_eq!(sys.outputs[0].1, vec![1.0, 0.0]);
        assert_eq!(sys.accepted, st.steps_accepted);
        // n + 7 evaluations per step plus the initial ones.
        assert!(st.rhs_evals >= st.steps_accepted * 9);
    }
}
