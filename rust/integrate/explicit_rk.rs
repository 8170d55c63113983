//! Explicit Runge–Kutta steppers for the driver loop ([`drive`](super::driver::drive)): RK4 with
//! a fixed step, DOPRI5 and DOP853 with PI step control (Hairer I, §II.4–II.6; the steps of
//! Hairer's codes DOPRI5 and DOP853). A method is its tableau (`tableau.rs`) plus how its error
//! is formed here; its dense output is `dense.rs`'s, filled here after an accepted step.
//!
//! All work vectors are allocated once per run; a step allocates nothing.

use super::controller::{dop853_error, rms_error, Controller, Decision};
use super::dense::{combine, ContinuousExtension};
use super::driver::{all_finite, fresh_rhs, non_finite, Stepper, Trial};
use super::method::{Settings, Stats};
use super::ode::{DenseOutput, OdeSystem};
use super::tableau::{dop853, dopri5, rk4};
use crate::error::Error;

/// Stage time `t + c h`, exactly `t1` for `c = 1`.
#[inline]
fn stage_time(t: f64, t1: f64, c: f64, h: f64) -> f64 {
    if c == 1.0 {
        t1
    } else {
        t + c * h
    }
}

/// Evaluates stages `range` of an explicit tableau: `k_i = f(t + c_i h, y + h Σ_j a_ij k_j)`
/// (Hairer I, eq. II.1.8). Stage `i` is stored in `k[i*n..(i+1)*n]`; `ytmp` is a work vector.
#[allow(clippy::too_many_arguments)]
fn stages<S: OdeSystem>(
    sys: &mut S,
    c: &[f64],
    a: &[&[f64]],
    range: std::ops::Range<usize>,
    t: f64,
    t1: f64,
    h: f64,
    y: &[f64],
    k: &mut [f64],
    ytmp: &mut [f64],
    stats: &mut Stats,
) -> Result<(), Error> {
    let n = y.len();
    for i in range {
        let (done, rest) = k.split_at_mut(i * n);
        ytmp.copy_from_slice(y);
        for (j, &aij) in a[i].iter().enumerate() {
            if aij != 0.0 {
                let ha = h * aij;
                for (yt, kv) in ytmp.iter_mut().zip(&done[j * n..(j + 1) * n]) {
                    *yt += ha * kv;
                }
            }
        }
        sys.rhs(stage_time(t, t1, c[i], h), ytmp, &mut rest[..n])?;
        stats.rhs_evals += 1;
    }
    Ok(())
}

/// `out = y + h Σ_j b_j k_j`.
fn advance(y: &[f64], h: f64, b: &[f64], k: &[f64], out: &mut [f64]) {
    combine(h, b, k, out);
    for (o, yi) in out.iter_mut().zip(y) {
        *o += yi;
    }
}

/// The first stage of the next step in `k[..n]`: `f(t, y)` afresh when the system changed its
/// memory at the step's end, else the step's last stage `k[fsal]` (= f(t, y), FSAL).
fn first_stage<S: OdeSystem>(sys: &mut S, stats: &mut Stats, refresh: bool, t: f64, y: &[f64], k: &mut [f64], fsal: usize) -> Result<(), Error> {
    let n = y.len();
    if refresh {
        fresh_rhs(sys, stats, t, y, &mut k[..n])
    } else {
        k.copy_within(fsal * n..(fsal + 1) * n, 0);
        Ok(())
    }
}

/// DOPRI5 or DOP853 (Hairer's `DOPCOR` / `DP86CO` steps). A trial step whose error is not
/// finite is a failed trial, retried with a quarter of the step, up to 12 times in a row.
pub(super) struct ExplicitRk {
    /// DOP853 (else DOPRI5).
    dop: bool,
    /// Stages; `k[..n]` is `f(t, y)`, `k[fsal]` is `f(t1, y1)`.
    k: Vec<f64>,
    fsal: usize,
    ytmp: Vec<f64>,
    e5: Vec<f64>,
    e3: Vec<f64>,
    dense: ContinuousExtension,
    ctrl: Controller,
    h_next: f64,
}

impl ExplicitRk {
    pub(super) fn new(n: usize, dop: bool) -> Self {
        let n_stages = if dop { dop853::STAGES_DENSE } else { 7 };
        ExplicitRk {
            dop,
            k: vec![0.0; n_stages * n],
            fsal: if dop { dop853::STAGES } else { 6 },
            ytmp: vec![0.0; n],
            e5: vec![0.0; n],
            e3: vec![0.0; if dop { n } else { 0 }],
            dense: ContinuousExtension::new(n),
            ctrl: if dop { Controller::dop853() } else { Controller::dopri5() },
            h_next: 0.0,
        }
    }
}

impl<S: OdeSystem> Stepper<S> for ExplicitRk {
    fn order(&self) -> usize {
        if self.dop {
            8
        } else {
            5
        }
    }
    fn max_trial_failures(&self) -> usize {
        12
    }
    fn f0(&mut self) -> &mut [f64] {
        let n = self.ytmp.len();
        &mut self.k[..n]
    }
    fn attempt(&mut self, sys: &mut S, stats: &mut Stats, st: &Settings, t: f64, t1: f64, h: f64, y: &[f64], y1: &mut [f64]) -> Result<Trial, Error> {
        let n = y.len();
        let (dop, k, ytmp) = (self.dop, &mut self.k, &mut self.ytmp);
        let (c, a, last_stage) = if dop { (&dop853::C[..], &dop853::A[..], dop853::STAGES) } else { (&dopri5::C[..], &dopri5::A[..], 6) };
        stages(sys, c, a, 1..last_stage, t, t1, h, y, k, ytmp, stats)?;
        let err = if dop {
            advance(y, h, &dop853::B, k, y1);
            combine(h, &dop853::E5, k, &mut self.e5);
            combine(h, &dop853::E3, k, &mut self.e3);
            dop853_error(&self.e5, &self.e3, y, y1, st.rtol, st.atol)
        } else {
            advance(y, h, &dopri5::B, k, y1);
            // FSAL stage 6 = f(t1, y1), part of the error estimate.
            sys.rhs(t1, y1, &mut k[6 * n..7 * n])?;
            stats.rhs_evals += 1;
            combine(h, &dopri5::E, k, &mut self.e5);
            rms_error(&self.e5, y, y1, st.rtol, st.atol)
        };
        if !err.is_finite() {
            return Ok(Trial::Failed { error: non_finite(t), h_next: 0.25 * h });
        }
        match self.ctrl.decide(err, h) {
            Decision::Reject { h_next } => Ok(Trial::Rejected { h_next }),
            Decision::Accept { h_next } => {
                self.h_next = h_next;
                if dop {
                    // f(t1, y1), then the three extra stages of the dense output.
                    let fsal = self.fsal;
                    fresh_rhs(sys, stats, t1, y1, &mut k[fsal * n..(fsal + 1) * n])?;
                    stages(sys, &dop853::C, &dop853::A, 13..16, t, t1, h, y, k, ytmp, stats)?;
                    self.dense.fill_dop853(t, t1, h, y, y1, k);
                } else {
                    self.dense.fill_dopri5(t, t1, h, y, y1, k);
                }
                Ok(Trial::Passed)
            }
        }
    }
    fn dense(&self) -> &dyn DenseOutput {
        &self.dense
    }
    fn accepted(&mut self, _h: f64) -> f64 {
        self.h_next
    }
    fn next_f0(&mut self, sys: &mut S, stats: &mut Stats, refresh: bool, t: f64, y: &[f64]) -> Result<(), Error> {
        first_stage(sys, stats, refresh, t, y, &mut self.k, self.fsal)
    }
}

/// Classic RK4 with a fixed step and cubic Hermite dense output from `f` at both ends;
/// `f(t1, y1)` is reused as the next first stage.
pub(super) struct Rk4 {
    step: f64,
    /// Stages 0–3, and `f(t1, y1)` in slot 4 (the next step's first stage).
    k: Vec<f64>,
    ytmp: Vec<f64>,
    dense: ContinuousExtension,
}

impl Rk4 {
    pub(super) fn new(n: usize, step: f64) -> Self {
        Rk4 { step, k: vec![0.0; 5 * n], ytmp: vec![0.0; n], dense: ContinuousExtension::new(n) }
    }
}

impl<S: OdeSystem> Stepper<S> for Rk4 {
    fn order(&self) -> usize {
        4
    }
    fn max_trial_failures(&self) -> usize {
        0
    }
    fn fixed_step(&self) -> Option<f64> {
        Some(self.step)
    }
    fn f0(&mut self) -> &mut [f64] {
        let n = self.ytmp.len();
        &mut self.k[..n]
    }
    fn attempt(&mut self, sys: &mut S, stats: &mut Stats, _st: &Settings, t: f64, t1: f64, h: f64, y: &[f64], y1: &mut [f64]) -> Result<Trial, Error> {
        let n = y.len();
        stages(sys, &rk4::C, &rk4::A, 1..4, t, t1, h, y, &mut self.k, &mut self.ytmp, stats)?;
        advance(y, h, &rk4::B, &self.k, y1);
        if !all_finite(y1) {
            return Err(non_finite(t));
        }
        fresh_rhs(sys, stats, t1, y1, &mut self.k[4 * n..5 * n])?;
        self.dense.fill_hermite(t, t1, y, y1, &self.k[..n], &self.k[4 * n..5 * n]);
        Ok(Trial::Passed)
    }
    fn dense(&self) -> &dyn DenseOutput {
        &self.dense
    }
    fn accepted(&mut self, _h: f64) -> f64 {
        self.step
    }
    fn next_f0(&mut self, sys: &mut S, stats: &mut Stats, refresh: bool, t: f64, y: &[f64]) -> Result<(), Error> {
        first_stage(sys, stats, refresh, t, y, &mut self.k, 4)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::excessive_precision)] // literature values of the test problems
    use super::super::{integrate, DenseOutput, Method, OdeSystem, Settings, Stats};
    use crate::error::Error;

    type Rhs = fn(f64, &[f64], &mut [f64]) -> Result<(), Error>;

    /// A test system around a plain function, recording everything the driver does.
    struct Sys {
        dim: usize,
        f: Rhs,
        evals: usize,
        outputs: Vec<(f64, Vec<f64>)>,
        accepted: Vec<(f64, f64)>,
        /// `output` fails at the first time ≥ this.
        fail_output_at: Option<f64>,
        /// `step_accepted` fails on this call (1-based).
        fail_accept_call: Option<usize>,
        /// `step_accepted` always returns this.
        refresh: bool,
    }

    impl Sys {
        fn new(dim: usize, f: Rhs) -> Self {
            Sys {
                dim,
                f,
                evals: 0,
                outputs: Vec::new(),
                accepted: Vec::new(),
                fail_output_at: None,
                fail_accept_call: None,
                refresh: false,
            }
        }
    }

    impl OdeSystem for Sys {
        fn dim(&self) -> usize {
            self.dim
        }
        fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
            self.evals += 1;
            (self.f)(t, y, dy)
        }
        fn step_accepted(
            &mut self,
            t0: f64,
            _y0: &[f64],
            t1: f64,
            _y1: &[f64],
            d: &dyn DenseOutput,
        ) -> Result<bool, Error> {
            assert_eq!(d.interval(), (t0, t1));
            self.accepted.push((t0, t1));
            if self.fail_accept_call == Some(self.accepted.len()) {
                return Err(Error::invalid("probe", t1, "step_accepted failure"));
            }
            Ok(self.refresh)
        }
        fn output(&mut self, t: f64, y: &[f64]) -> Result<(), Error> {
            if self.fail_output_at.is_some_and(|tf| t >= tf) {
                return Err(Error::Interrupted { t });
            }
            self.outputs.push((t, y.to_vec()));
            Ok(())
        }
    }

    /// Kepler problem; with `KEPLER_Y0` (eccentricity 0.5) the orbit has period 2π.
    fn kepler(_t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
        let r3 = (y[0] * y[0] + y[1] * y[1]).powf(1.5);
        dy[0] = y[2];
        dy[1] = y[3];
        dy[2] = -y[0] / r3;
        dy[3] = -y[1] / r3;
        Ok(())
    }
    const KEPLER_Y0: [f64; 4] = [0.5, 0.0, 0.0, 1.7320508075688772]; // p = sqrt((1+e)/(1−e))
    const TWO_PI: f64 = 2.0 * std::f64::consts::PI;

    /// Restricted three-body problem with the Arenstorf orbit (Hairer I, §II.0, eq. 0.1).
    fn arenstorf(_t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
        const MU: f64 = 0.012277471;
        const MUP: f64 = 1.0 - MU;
        let d1 = ((y[0] + MU).powi(2) + y[1] * y[1]).powf(1.5);
        let d2 = ((y[0] - MUP).powi(2) + y[1] * y[1]).powf(1.5);
        dy[0] = y[2];
        dy[1] = y[3];
        dy[2] = y[0] + 2.0 * y[3] - MUP * (y[0] + MU) / d1 - MU * (y[0] - MUP) / d2;
        dy[3] = y[1] - 2.0 * y[2] - MUP * y[1] / d1 - MU * y[1] / d2;
        Ok(())
    }
    const ARENSTORF_Y0: [f64; 4] = [0.994, 0.0, 0.0, -2.00158510637908252240537862224];
    const ARENSTORF_T: f64 = 17.0652165601579625588917206249;

    /// `u' = −u + sin t`, harmonic oscillator `v'' = −v`.
    fn forced(t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
        dy[0] = -y[0] + t.sin();
        dy[1] = y[2];
        dy[2] = -y[1];
        Ok(())
    }
    fn forced_exact(t: f64) -> [f64; 3] {
        // u(0) = 1: u = 1.5 e^(−t) + (sin t − cos t)/2; v(0) = 1, v'(0) = 0.
        [1.5 * (-t).exp() + 0.5 * (t.sin() - t.cos()), t.cos(), -t.sin()]
    }

    fn dist(a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
    }

    /// Final state after integrating with `n` equal steps (adaptive methods forced to fixed
    /// steps by huge tolerances and `h0 = h_max = step`).
    fn fixed_step_end(method: Method, f: Rhs, y0: &[f64], t_end: f64, n: usize) -> Vec<f64> {
        let h = t_end / n as f64;
        let method = match method {
            Method::Rk4 { .. } => Method::Rk4 { step: h },
            m => m,
        };
        let s = Settings {
            rtol: 1e6,
            atol: 1e6,
            h0: Some(h),
            h_max: h,
            ..Settings::default()
        };
        let mut sys = Sys::new(y0.len(), f);
        let st = integrate(&mut sys, method, 0.0, y0, t_end, &[t_end], &s).unwrap();
        assert_eq!(st.steps_accepted, n, "{method:?}");
        assert_eq!(st.steps_rejected, 0);
        assert_eq!(st.t_reached, t_end);
        sys.outputs[0].1.clone()
    }

    #[test]
    fn observed_global_order_rk4_dopri5_dop853() {
        // Kepler orbit over one period returns to its initial point; error ~ C h^p. DOP853 uses
        // a milder orbit (e = 0.2) so that both runs are asymptotic yet above round-off
        // (observed 7.80 with n = 50; 7.6–7.8 for n = 30..60).
        const KEPLER_E02: [f64; 4] = [0.8, 0.0, 0.0, 1.224744871391589];
        for (method, p, n, y0) in [
            (Method::Rk4 { step: 0.0 }, 4.0, 400, KEPLER_Y0),
            (Method::Rk45, 5.0, 200, KEPLER_Y0),
            (Method::Dop853, 8.0, 50, KEPLER_E02),
        ] {
            let e1 = dist(&fixed_step_end(method, kepler, &y0, TWO_PI, n), &y0);
            let e2 = dist(&fixed_step_end(method, kepler, &y0, TWO_PI, 2 * n), &y0);
            let order = (e1 / e2).log2();
            assert!(
                (order - p).abs() < 0.35,
                "{method:?}: errors {e1:e}, {e2:e}, observed order {order}"
            );
        }
    }

    fn arenstorf_run(method: Method, tol: f64) -> (Stats, Vec<f64>) {
        let mut sys = Sys::new(4, arenstorf);
        let s = Settings {
            rtol: tol,
            atol: tol,
            ..Settings::default()
        };
        let st = integrate(&mut sys, method, 0.0, &ARENSTORF_Y0, ARENSTORF_T, &[ARENSTORF_T], &s).unwrap();
        assert_eq!(sys.evals, st.rhs_evals);
        (st, sys.outputs[0].1.clone())
    }

    #[test]
    fn arenstorf_orbit_closes_dop853() {
        let (st, y) = arenstorf_run(Method::Dop853, 1e-12);
        let pos_err = dist(&y[..2], &ARENSTORF_Y0[..2]);
        assert!(pos_err < 1e-6, "position error {pos_err:e}");
        assert!(dist(&y, &ARENSTORF_Y0) < 1e-4);
        // scipy's DOP853 (same tableau and I-controller) needs 298 steps and ~59 rejections.
        assert!((250..=350).contains(&st.steps_accepted), "{st:?}");
        assert!(st.steps_rejected < st.steps_accepted / 3, "{st:?}");
        assert_eq!(
            st.rhs_evals,
            2 + 11 * (st.steps_accepted + st.steps_rejected) + 4 * st.steps_accepted
        );
    }

    #[test]
    fn arenstorf_orbit_closes_dopri5() {
        let (st, y) = arenstorf_run(Method::Rk45, 1e-9);
        let pos_err = dist(&y[..2], &ARENSTORF_Y0[..2]);
        assert!(pos_err < 1e-4, "position error {pos_err:e}");
        // scipy's RK45 (same tableau, I-controller) needs 501 steps here.
        assert!((400..=700).contains(&st.steps_accepted), "{st:?}");
        assert!(st.steps_rejected < st.steps_accepted / 3, "{st:?}");
        assert_eq!(st.rhs_evals, 2 + 6 * (st.steps_accepted + st.steps_rejected));
        // Tightening the tolerance shrinks the error (error ∝ tol^(5/6) roughly).
        let (_, y_tight) = arenstorf_run(Method::Rk45, 1e-11);
        assert!(dist(&y_tight[..2], &ARENSTORF_Y0[..2]) < pos_err / 10.0);
    }

    #[test]
    fn dense_outputs_match_exact_and_do_not_change_steps() {
        let grid: Vec<f64> = (0..=200).map(|i| i as f64 * 0.05).collect(); // [0, 10]
        let y0 = forced_exact(0.0);
        for method in [Method::Rk4 { step: 0.01 }, Method::Rk45, Method::Dop853] {
            let s = Settings {
                rtol: 1e-8,
                atol: 1e-10,
                ..Settings::default()
            };
            let mut plain = Sys::new(3, forced);
            let st_plain = integrate(&mut plain, method, 0.0, &y0, 10.0, &[], &s).unwrap();
            let mut sampled = Sys::new(3, forced);
            let st = integrate(&mut sampled, method, 0.0, &y0, 10.0, &grid, &s).unwrap();
            assert_eq!(st, st_plain, "{method:?}: outputs changed the steps");
            assert_eq!(plain.accepted, sampled.accepted);
            assert_eq!(sampled.outputs.len(), grid.len());
            let mut worst: f64 = 0.0;
            for ((t, y), tg) in sampled.outputs.iter().zip(&grid) {
                assert_eq!(t, tg);
                worst = worst.max(dist(y, &forced_exact(*t)));
            }
            assert_eq!(sampled.outputs[0].1, y0.to_vec(), "t0 is output from y0 exactly");
            assert!(worst < 1e-6, "{method:?}: max output error {worst:e}");
            if method != (Method::Rk4 { step: 0.01 }) {
                assert!(worst > 1e-13, "{method:?}: suspiciously exact");
            }
            assert_eq!(st.t_reached, 10.0);
            assert_eq!(sampled.accepted.last().map(|a| a.1), Some(10.0));
            // Steps chain without gaps.
            for w in sampled.accepted.windows(2) {
                assert_eq!(w[0].1, w[1].0);
            }
        }
    }

    #[test]
    fn outputs_outside_range_are_skipped_and_t0_equals_t_end() {
        let y0 = forced_exact(0.0);
        let mut sys = Sys::new(3, forced);
        let st = integrate(
            &mut sys,
            Method::Rk45,
            0.0,
            &y0,
            1.0,
            &[-1.0, 0.0, 0.0, 0.5, 1.0, 2.0],
            &Settings::default(),
        )
        .unwrap();
        let ts: Vec<f64> = sys.outputs.iter().map(|o| o.0).collect();
        assert_eq!(ts, vec![0.0, 0.0, 0.5, 1.0]);
        assert!(st.steps_accepted > 0);
        let mut sys = Sys::new(3, forced);
        let st = integrate(&mut sys, Method::Dop853, 2.0, &y0, 2.0, &[2.0], &Settings::default()).unwrap();
        assert_eq!((st.steps_accepted, st.rhs_evals, st.t_reached), (0, 0, 2.0));
        assert_eq!(sys.outputs, vec![(2.0, y0.to_vec())]);
    }

    #[test]
    fn h_max_is_respected_and_stats_are_consistent() {
        for method in [Method::Rk45, Method::Dop853] {
            let mut sys = Sys::new(4, kepler);
            let s = Settings {
                h_max: 0.01,
                ..Settings::default()
            };
            let st = integrate(&mut sys, method, 0.0, &KEPLER_Y0, TWO_PI, &[], &s).unwrap();
            assert!(st.h_max_used <= 0.01 && st.h_min_used <= st.h_max_used);
            assert!(st.steps_accepted >= 629);
            assert_eq!(st.rhs_evals, sys.evals);
            let hs = sys.accepted.iter().map(|(a, b)| b - a);
            assert!(hs.clone().all(|h| h <= 0.01 * (1.0 + 1e-12)));
        }
    }

    #[test]
    fn rk4_counts_and_short_last_step() {
        let mut sys = Sys::new(3, forced);
        let st = integrate(
            &mut sys,
            Method::Rk4 { step: 0.3 },
            0.0,
            &forced_exact(0.0),
            1.0,
            &[],
            &Settings::default(),
        )
        .unwrap();
        assert_eq!(st.steps_accepted, 4); // 0.3, 0.6, 0.9, 1.0
        assert_eq!(st.rhs_evals, 1 + 4 * 4);
        assert_eq!(st.rhs_evals, sys.evals);
        assert!((st.h_min_used - 0.1).abs() < 1e-12 && (st.h_max_used - 0.3).abs() < 1e-12);
        let (ta, tb) = sys.accepted[3];
        assert!((ta - 0.9).abs() < 1e-15 && tb == 1.0, "last step [{ta}, {tb}]");
    }

    /// `y' = c` where `c` is a memory switched on by `step_accepted` once `t1 ≥ 1`.
    struct Switch {
        c: f64,
        t_switch: f64,
        evals: usize,
    }
    impl OdeSystem for Switch {
        fn dim(&self) -> usize {
            1
        }
        fn rhs(&mut self, _t: f64, _y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
            self.evals += 1;
            dy[0] = self.c;
            Ok(())
        }
        fn step_accepted(
            &mut self,
            _t0: f64,
            _y0: &[f64],
            t1: f64,
            _y1: &[f64],
            _d: &dyn DenseOutput,
        ) -> Result<bool, Error> {
            if self.c == 0.0 && t1 >= 1.0 {
                self.c = 1.0;
                self.t_switch = t1;
                return Ok(true);
            }
            Ok(false)
        }
        fn output(&mut self, _t: f64, _y: &[f64]) -> Result<(), Error> {
            Ok(())
        }
    }

    #[test]
    fn step_accepted_true_forces_reevaluation() {
        for method in [Method::Rk4 { step: 0.07 }, Method::Rk45, Method::Dop853] {
            let mut sys = Switch {
                c: 0.0,
                t_switch: f64::NAN,
                evals: 0,
            };
            let s = Settings {
                h_max: 0.1,
                ..Settings::default()
            };
            let st = integrate(&mut sys, method, 0.0, &[0.0], 3.0, &[], &s).unwrap();
            assert_eq!(st.rhs_evals, sys.evals);
            // With a stale (FSAL) first stage the result would miss part of the slope.
            let mut sys2 = Switch {
                c: 0.0,
                t_switch: f64::NAN,
                evals: 0,
            };
            let mut y_end = Vec::new();
            struct Last<'a>(&'a mut Switch, &'a mut Vec<f64>);
            impl OdeSystem for Last<'_> {
                fn dim(&self) -> usize {
                    1
                }
                fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
                    self.0.rhs(t, y, dy)
                }
                fn step_accepted(
                    &mut self,
                    t0: f64,
                    y0: &[f64],
                    t1: f64,
                    y1: &[f64],
                    d: &dyn DenseOutput,
                ) -> Result<bool, Error> {
                    self.0.step_accepted(t0, y0, t1, y1, d)
                }
                fn output(&mut self, _t: f64, y: &[f64]) -> Result<(), Error> {
                    *self.1 = y.to_vec();
                    Ok(())
                }
            }
            integrate(&mut Last(&mut sys2, &mut y_end), method, 0.0, &[0.0], 3.0, &[3.0], &s).unwrap();
            assert!(
                (y_end[0] - (3.0 - sys2.t_switch)).abs() < 1e-12,
                "{method:?}: {} vs {}",
                y_end[0],
                3.0 - sys2.t_switch
            );
        }
    }

    fn nan_after_1_5(t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
        forced(t, y, dy)?;
        if t >= 1.5 {
            dy[1] = f64::NAN;
        }
        Ok(())
    }

    #[test]
    fn nan_rhs_gives_non_finite_before_it() {
        for method in [Method::Rk4 { step: 0.01 }, Method::Rk45, Method::Dop853] {
            let mut sys = Sys::new(3, nan_after_1_5);
            let grid: Vec<f64> = (0..=30).map(|i| i as f64 * 0.1).collect();
            let (e, st) = integrate(
                &mut sys,
                method,
                0.0,
                &forced_exact(0.0),
                3.0,
                &grid,
                &Settings::default(),
            )
            .unwrap_err();
            assert!(
                matches!(e, Error::NonFinite { t, .. } if t < 1.5 && t == st.t_reached),
                "{method:?}: {e:?}"
            );
            assert!(st.t_reached < 1.5 && st.t_reached > 1.0, "{method:?}: {st:?}");
            assert!(sys
                .outputs
                .iter()
                .all(|(t, y)| *t <= st.t_reached && y.iter().all(|v| v.is_finite())));
            assert_eq!(st.rhs_evals, sys.evals);
        }
    }

    fn blow_up(_t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
        dy[0] = y[0] * y[0]; // y = 1/(1 − t)
        Ok(())
    }

    fn jump(t: f64, _y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
        dy[0] = if t < 1.0 { 0.0 } else { 1e8 };
        Ok(())
    }

    #[test]
    fn step_size_underflow_when_h_min_is_large() {
        for method in [Method::Rk45, Method::Dop853] {
            let s = Settings {
                h_min: 1e-4,
                ..Settings::default()
            };
            let mut sys = Sys::new(1, blow_up);
            let (e, st) = integrate(&mut sys, method, 0.0, &[1.0], 2.0, &[], &s).unwrap_err();
            match e {
                Error::StepSizeUnderflow { t, h, .. } => {
                    assert!(t < 1.0 && t > 0.99 && h < 1e-4, "{method:?}: t = {t}, h = {h}");
                    assert_eq!(t, st.t_reached);
                }
                e => panic!("{method:?}: {e:?}"),
            }
            let mut sys = Sys::new(1, jump);
            let s_jump = Settings {
                h_min: 1e-3,
                h0: Some(0.01),
                ..s
            };
            let (e, st) = integrate(&mut sys, method, 0.0, &[0.0], 2.0, &[], &s_jump).unwrap_err();
            assert!(
                matches!(e, Error::StepSizeUnderflow { t, .. } if t < 1.0),
                "{method:?}: {e:?}"
            );
            assert!(st.steps_rejected > 0);
        }
    }

    #[test]
    fn too_many_steps() {
        for method in [Method::Rk4 { step: 0.01 }, Method::Rk45, Method::Dop853] {
            let mut sys = Sys::new(4, kepler);
            let s = Settings {
                max_steps: 7,
                ..Settings::default()
            };
            let (e, st) = integrate(&mut sys, method, 0.0, &KEPLER_Y0, TWO_PI, &[], &s).unwrap_err();
            assert_eq!(
                e,
                Error::TooManySteps {
                    t: st.t_reached,
                    max_steps: 7
                },
                "{method:?}"
            );
            assert_eq!(st.steps_accepted + st.steps_rejected, 7);
        }
    }

    #[test]
    fn callback_errors_propagate_unchanged() {
        let grid: Vec<f64> = (0..=10).map(|i| i as f64 * 0.1).collect();
        for method in [Method::Rk4 { step: 0.05 }, Method::Rk45, Method::Dop853] {
            let run = |sys: &mut Sys| integrate(sys, method, 0.0, &forced_exact(0.0), 1.0, &grid, &Settings::default()).unwrap_err();
            // output
            let mut sys = Sys::new(3, forced);
            sys.fail_output_at = Some(0.45);
            let (e, st) = run(&mut sys);
            assert!(
                matches!(e, Error::Interrupted { t } if (t - 0.5).abs() < 1e-15),
                "{e:?}"
            );
            assert_eq!(sys.outputs.len(), 5, "outputs before the failure were delivered");
            assert!(st.t_reached >= 0.5);
            // step_accepted
            let mut sys = Sys::new(3, forced);
            sys.fail_accept_call = Some(3);
            let (e, st) = run(&mut sys);
            assert!(
                matches!(&e, Error::InvalidInput { field, .. } if field == "probe"),
                "{e:?}"
            );
            assert_eq!(st.steps_accepted, 3);
            assert!(sys.outputs.iter().all(|o| o.0 <= sys.accepted[1].1));
            // rhs
            let mut sys = Sys::new(1, |t, _y, dy| {
                dy[0] = 1.0;
                if t > 0.3 {
                    Err(Error::SingularJacobian { t, index: 7 })
                } else {
                    Ok(())
                }
            });
            let (e, st) = integrate(&mut sys, method, 0.0, &[0.0], 1.0, &[], &Settings::default()).unwrap_err();
            assert!(matches!(e, Error::SingularJacobian { t, index: 7 } if t > 0.3), "{e:?}");
            assert!(st.t_reached <= 0.3);
        }
    }

    /// A ball dropped from 0.1 m onto an elastic Hertz wall (`K = 1e8 N/m^1.5` per kg): `y = (x, v)`,
    /// `ẍ = −g + K max(−x, 0)^1.5`. The force is C¹ at the contact onset and separation.
    fn bouncing(_t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
        dy[0] = y[1];
        dy[1] = -9.81 + 1e8 * (-y[0]).max(0.0).powf(1.5);
        Ok(())
    }

    /// The energy of the elastic bounce is conserved exactly; steps that straddle the onset or
    /// separation escape the error estimate and lose it, steps that end there (the system
    /// reports the switching points) keep it to the tolerance.
    #[test]
    fn steps_end_on_reported_switching_points() {
        /// The test system, reporting the contact onsets and separations when `.1` is set.
        struct Bounce(Sys, bool);
        impl OdeSystem for Bounce {
            fn dim(&self) -> usize { 2 }
            fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> { self.0.rhs(t, y, dy) }
            fn switching_point(&mut self, t0: f64, y0: &[f64], t1: f64, y1: &[f64], d: &dyn DenseOutput) -> Result<Option<f64>, Error> {
                if !self.1 || (y0[0] < 0.0) == (y1[0] < 0.0) {
                    return Ok(None);
                }
                // Bisection on x(t) through the dense output.
                let (mut a, mut b, mut buf) = (t0, t1, [0.0; 2]);
                for _ in 0..100 {
                    let m = 0.5 * (a + b);
                    d.eval(m, &mut buf);
                    if (buf[0] < 0.0) == (y0[0] < 0.0) { a = m } else { b = m }
                }
                Ok(Some(0.5 * (a + b)))
            }
            fn output(&mut self, t: f64, y: &[f64]) -> Result<(), Error> { self.0.output(t, y) }
        }
        let energy = |y: &[f64]| 0.5 * y[1] * y[1] + 9.81 * y[0] + 1e8 * (-y[0]).max(0.0).powf(2.5) / 2.5;
        let e0 = energy(&[0.1, 0.0]);
        let t_out: Vec<f64> = (1..=40).map(|i| i as f64 * 0.05).collect(); // 2 s: ~7 bounces
        for method in [Method::Rk45, Method::Dop853, Method::Radau] {
            let s = Settings { rtol: 1e-10, atol: 1e-13, ..Settings::default() };
            let mut drift = [0.0; 2];
            for (i, hook) in [false, true].into_iter().enumerate() {
                let mut sys = Bounce(Sys::new(2, bouncing), hook);
                let st = integrate(&mut sys, method, 0.0, &[0.1, 0.0], 2.0, &t_out, &s).unwrap();
                drift[i] = sys.0.outputs.iter().map(|(_, y)| (energy(y) - e0).abs() / e0).fold(0.0, f64::max);
                assert_eq!(st.steps_to_switch > 0, hook, "{method:?}: {st:?}");
            }
            eprintln!("{method:?}: relative energy drift without / with switching points: {:.2e} / {:.2e}", drift[0], drift[1]);
            // Measured at rtol 1e-10: 5.5e-8 / 1.8e-8 (DOPRI5), 1.8e-7 / 3.1e-9 (DOP853), 2.9e-10 / 1.8e-10 (RADAU5).
            assert!(drift[1] < drift[0] && drift[1] < 1e-7, "{method:?}: {drift:?}");
            if method == Method::Dop853 {
                assert!(drift[1] < 0.1 * drift[0], "{drift:?}");
            }
        }
    }

    #[test]
    fn invalid_input_is_rejected() {
        let y0 = forced_exact(0.0);
        let s = Settings::default();
        let run = |method, y0: &[f64], t_end, t_out: &[f64], s: &Settings| {
            integrate(&mut Sys::new(3, forced), method, 0.0, y0, t_end, t_out, s)
        };
        let bad = |r: Result<Stats, (Error, Stats)>| matches!(r, Err((Error::InvalidInput { .. }, _)));
        assert!(bad(run(Method::Rk45, &y0[..2], 1.0, &[], &s)), "state of the wrong length");
        assert!(bad(run(Method::Rk45, &y0, -1.0, &[], &s)), "t_end before t0");
        assert!(bad(run(Method::Rk45, &y0, 1.0, &[0.5, 0.2], &s)), "decreasing outputs");
        assert!(bad(run(Method::Rk4 { step: 0.0 }, &y0, 1.0, &[], &s)), "zero RK4 step");
        assert!(bad(run(Method::Dop853, &y0, 1.0, &[], &Settings { rtol: -1.0, ..s })), "negative rtol");
        assert!(bad(run(Method::Dop853, &y0, 1.0, &[], &Settings { h0: Some(0.0), ..s })), "zero first step");
        let s_bad = Settings { h_min: 1.0, h_max: 0.1, ..s };
        assert!(bad(run(Method::Dop853, &y0, 1.0, &[], &s_bad)), "h_min above h_max");
        let r = run(Method::Rk45, &[f64::NAN, 0.0, 0.0], 1.0, &[], &s);
        assert!(matches!(r, Err((Error::NonFinite { .. }, _))));
    }
}
