//! Continuous extensions ("dense output") of one accepted step (Hairer I, §II.6).
//!
//! All three use the nested form of Hairer's codes (`CONTD5`, `CONTD8`): with
//! `θ = (t − t0)/(t1 − t0)`, `θ1 = 1 − θ`,
//!
//! `y(θ) = y0 + θ·Δ + θ θ1 (r3 + θ (r4 + θ1 (r5 + θ (r6 + θ1 (r7 + θ r8)))))`,
//!
//! `Δ = y1 − y0`, `r3 = h f0 − Δ`, `r4 = Δ − h f1 − r3`. Truncated after `r4` this is the cubic
//! Hermite interpolant (used for RK4); DOPRI5 adds `r5` (4th order, Shampine's coefficients), DOP853
//! adds `r5..r8` (7th order, needing three extra stages).
//! For `θ > 1/2` the linear part is evaluated as `y1 − θ1 Δ`, so `t1` reproduces `y1` exactly.

use super::tableau::{dop853, dopri5};
use super::ode::DenseOutput;

/// Dense output of one step in Hairer's nested form; storage is allocated once by [`new`]
/// and refilled for every accepted step.
///
/// [`new`]: ContinuousExtension::new
#[derive(Debug, Clone)]
pub struct ContinuousExtension {
    t0: f64,
    t1: f64,
    n: usize,
    /// Number of correction rows `r3..` in use (2 Hermite, 3 DOPRI5, 6 DOP853).
    rows: usize,
    y0: Vec<f64>,
    y1: Vec<f64>,
    diff: Vec<f64>,
    /// Rows `r3, r4, …` (row-major, `MAX_ROWS × n`).
    r: Vec<f64>,
    /// `f(t1, y1)`, the rate at the step's end that every fill receives.
    f1: Vec<f64>,
}

const MAX_ROWS: usize = 6;

impl ContinuousExtension {
    /// Storage for a state of length `n` (enough for any of the three extensions).
    pub fn new(n: usize) -> Self {
        ContinuousExtension {
            t0: 0.0,
            t1: 0.0,
            n,
            rows: 0,
            y0: vec![0.0; n],
            y1: vec![0.0; n],
            diff: vec![0.0; n],
            r: vec![0.0; MAX_ROWS * n],
            f1: vec![0.0; n],
        }
    }

    /// Common part: `y0, y1, Δ, r3 = h f0 − Δ, r4 = Δ − h f1 − r3`.
    #[allow(clippy::too_many_arguments)]
    fn fill_hermite_part(&mut self, t0: f64, t1: f64, h: f64, y0: &[f64], y1: &[f64], f0: &[f64], f1: &[f64]) {
        let n = self.n;
        self.t0 = t0;
        self.t1 = t1;
        self.y0.copy_from_slice(y0);
        self.y1.copy_from_slice(y1);
        self.f1.copy_from_slice(f1);
        let (r3, rest) = self.r.split_at_mut(n);
        for i in 0..n {
            let d = y1[i] - y0[i];
            self.diff[i] = d;
            r3[i] = h * f0[i] - d;
            rest[i] = d - h * f1[i] - r3[i];
        }
    }

    /// Cubic Hermite interpolant on `[t0, t1]` from the values and derivatives at both ends
    /// (3rd order; Hairer I, §II.6, eq. 6.7).
    pub fn fill_hermite(&mut self, t0: f64, t1: f64, y0: &[f64], y1: &[f64], f0: &[f64], f1: &[f64]) {
        self.fill_hermite_part(t0, t1, t1 - t0, y0, y1, f0, f1);
        self.rows = 2;
    }

    /// DOPRI5's 4th-order extension (Hairer I, §II.6, Shampine 1986; code `DOPRI5`).
    /// `k` holds the 7 stages of the step (`k[j*n..(j+1)*n]`, stage 6 = `f(t1, y1)`), `h` is the
    /// step size used to compute them.
    pub fn fill_dopri5(&mut self, t0: f64, t1: f64, h: f64, y0: &[f64], y1: &[f64], k: &[f64]) {
        let n = self.n;
        self.fill_hermite_part(t0, t1, h, y0, y1, &k[..n], &k[6 * n..7 * n]);
        combine(h, &dopri5::D, k, &mut self.r[2 * n..3 * n]);
        self.rows = 3;
    }

    /// DOP853's 7th-order extension (Hairer I, §II.6; code `DOP853`). `k` holds the 16 stages
    /// of the extended tableau (stage 12 = `f(t1, y1)`, stages 13..15 the extra ones).
    pub fn fill_dop853(&mut self, t0: f64, t1: f64, h: f64, y0: &[f64], y1: &[f64], k: &[f64]) {
        let n = self.n;
        self.fill_hermite_part(t0, t1, h, y0, y1, &k[..n], &k[12 * n..13 * n]);
        for (r, d) in dop853::D.iter().enumerate() {
            combine(h, d, k, &mut self.r[(2 + r) * n..(3 + r) * n]);
        }
        self.rows = 6;
    }
}

/// `out = h Σ_j w_j k_j` over the stages `k[j*n..(j+1)*n]` (zero weights skipped).
pub(crate) fn combine(h: f64, w: &[f64], k: &[f64], out: &mut [f64]) {
    let n = out.len();
    out.fill(0.0);
    for (j, &wj) in w.iter().enumerate() {
        if wj != 0.0 {
            let hw = h * wj;
            for (o, kv) in out.iter_mut().zip(&k[j * n..(j + 1) * n]) {
                *o += hw * kv;
            }
        }
    }
}

impl DenseOutput for ContinuousExtension {
    fn interval(&self) -> (f64, f64) {
        (self.t0, self.t1)
    }

    fn end_rate(&self) -> Option<&[f64]> {
        (self.rows > 0).then_some(&self.f1[..])
    }

    /// Component `i` of the nested form at `θ = s` (extrapolates outside `[t0, t1]`).
    #[inline]
    fn component(&self, s: f64, i: usize) -> f64 {
        let n = self.n;
        let s1 = 1.0 - s;
        // Innermost first: r_last, then r_{m} + w_m * acc with w = θ after odd rows
        // (r3, r5, r7) and θ1 after even rows (r4, r6).
        let mut acc = 0.0;
        for row in (0..self.rows).rev() {
            let w = if row % 2 == 0 { s } else { s1 };
            acc = self.r[row * n + i] + w * acc;
        }
        let lin = if s <= 0.5 { self.y0[i] + s * self.diff[i] } else { self.y1[i] - s1 * self.diff[i] };
        lin + s * s1 * acc
    }
}

#[cfg(test)]
mod tests {
    use super::super::tableau::trees::{all_trees, max_defect, weights};
    use super::super::tableau::{dop853, dopri5};
    use super::super::{integrate, Method, OdeSystem, Settings};
    use super::*;
    use crate::error::Error;

    /// Weights `b_i(θ)` of an extension, obtained by filling it with unit stage vectors
    /// (state dimension = number of stages, `h = 1`, `y0 = 0`): component `i` of `y(θ)` is `b_i(θ)`.
    fn dense_weights(kind: &str, theta: f64) -> Vec<f64> {
        let s = if kind == "dopri5" { 7 } else { 16 };
        let mut k = vec![0.0; s * s];
        for j in 0..s {
            k[j * s + j] = 1.0;
        }
        let y0 = vec![0.0; s];
        let mut y1 = vec![0.0; s];
        let mut ext = ContinuousExtension::new(s);
        if kind == "dopri5" {
            y1.copy_from_slice(&dopri5::B);
            ext.fill_dopri5(0.0, 1.0, 1.0, &y0, &y1, &k);
        } else {
            y1[..12].copy_from_slice(&dop853::B);
            ext.fill_dop853(0.0, 1.0, 1.0, &y0, &y1, &k);
        }
        let mut b = vec![0.0; s];
        ext.eval(theta, &mut b);
        b
    }

    #[test]
    fn dense_weights_satisfy_continuous_order_conditions() {
        // Σ b_i(θ) Φ_i(t) = θ^|t| / γ(t) for |t| ≤ p* (Hairer I, Theorem II.6.1).
        let trees = all_trees(8);
        let g5 = weights(&trees, &dopri5::A);
        let g8 = weights(&trees, &dop853::A);
        for &theta in &[0.1, 0.3, 0.5, 0.77, 0.95] {
            let b5 = dense_weights("dopri5", theta);
            assert!(max_defect(&trees, &g5, &b5, 4, theta) < 1e-14, "dopri5 θ={theta}");
            assert!(
                max_defect(&trees, &g5, &b5, 5, theta) > 1e-7,
                "dopri5 is not 5th order dense"
            );
            let b8 = dense_weights("dop853", theta);
            assert!(max_defect(&trees, &g8, &b8, 7, theta) < 1e-12, "dop853 θ={theta}");
            assert!(
                max_defect(&trees, &g8, &b8, 8, theta) > 1e-9,
                "dop853 is not 8th order dense"
            );
        }
    }

    #[test]
    fn hermite_matches_cubic() {
        // Exact for cubics: y = t³ − 2t on [1, 3].
        let y = |t: f64| t * t * t - 2.0 * t;
        let f = |t: f64| 3.0 * t * t - 2.0;
        let mut e = ContinuousExtension::new(1);
        e.fill_hermite(1.0, 3.0, &[y(1.0)], &[y(3.0)], &[f(1.0)], &[f(3.0)]);
        let mut out = [0.0];
        for &t in &[1.0, 1.3, 2.0, 2.9, 3.0] {
            e.eval(t, &mut out);
            assert!((out[0] - y(t)).abs() < 1e-13, "t = {t}");
        }
        assert_eq!(e.interval(), (1.0, 3.0));
    }

    /// Kepler problem, eccentricity 0.6 (non-linear, smooth).
    struct Kepler;
    impl OdeSystem for Kepler {
        fn dim(&self) -> usize {
            4
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
            let r3 = (y[0] * y[0] + y[1] * y[1]).powf(1.5);
            dy[0] = y[2];
            dy[1] = y[3];
            dy[2] = -y[0] / r3;
            dy[3] = -y[1] / r3;
            Ok(())
        }
        fn output(&mut self, _t: f64, _y: &[f64]) -> Result<(), Error> {
            Ok(())
        }
    }

    /// Records each step's extension and checks it at the ends; measures the error of the
    /// extension of the first step against a reference at interior points.
    struct Probe {
        reference: Vec<(f64, Vec<f64>)>,
        max_err: f64,
        ends_exact: bool,
    }
    impl OdeSystem for Probe {
        fn dim(&self) -> usize {
            4
        }
        fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
            Kepler.rhs(t, y, dy)
        }
        fn step_accepted(
            &mut self,
            t0: f64,
            y0: &[f64],
            t1: f64,
            y1: &[f64],
            d: &dyn DenseOutput,
        ) -> Result<bool, Error> {
            let mut out = [0.0; 4];
            d.eval(t0, &mut out);
            self.ends_exact &= out == y0;
            d.eval(t1, &mut out);
            self.ends_exact &= out == y1;
            assert_eq!(d.interval(), (t0, t1));
            // One component is what the whole evaluation writes there, and the end rate is
            // f(t1, y1) itself (every explicit method computes it).
            let tm = 0.37 * t0 + 0.63 * t1;
            d.eval(tm, &mut out);
            for (i, o) in out.iter().enumerate() {
                self.ends_exact &= d.eval_component(tm, i) == *o;
            }
            // Several components at once: the same numbers, the other entries untouched.
            let mut some = [f64::NAN; 4];
            d.eval_components(tm, &[3, 1], &mut some);
            self.ends_exact &= some[1] == out[1] && some[3] == out[3] && some[0].is_nan() && some[2].is_nan();
            let mut f1 = [0.0; 4];
            Kepler.rhs(t1, y1, &mut f1)?;
            self.ends_exact &= d.end_rate() == Some(&f1[..]);
            for (t, r) in &self.reference {
                if *t > t0 && *t < t1 {
                    d.eval(*t, &mut out);
                    for i in 0..4 {
                        self.max_err = self.max_err.max((out[i] - r[i]).abs());
                    }
                }
            }
            Ok(false)
        }
        fn output(&mut self, _t: f64, _y: &[f64]) -> Result<(), Error> {
            Ok(())
        }
    }

    const Y0: [f64; 4] = [0.4, 0.0, 0.0, 2.0]; // e = 0.6: q = (1−e, 0), p = (0, sqrt((1+e)/(1−e)))

    /// Accurate reference by DOP853 at tight tolerance, sampled at `ts`.
    fn reference(ts: &[f64]) -> Vec<(f64, Vec<f64>)> {
        struct Rec(Vec<(f64, Vec<f64>)>);
        impl OdeSystem for Rec {
            fn dim(&self) -> usize {
                4
            }
            fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
                Kepler.rhs(t, y, dy)
            }
            fn output(&mut self, t: f64, y: &[f64]) -> Result<(), Error> {
                self.0.push((t, y.to_vec()));
                Ok(())
            }
        }
        let mut rec = Rec(Vec::new());
        let s = Settings {
            rtol: 1e-14,
            atol: 1e-14,
            h_max: 0.002,
            ..Settings::default()
        };
        integrate(&mut rec, Method::Dop853, 0.0, &Y0, ts[ts.len() - 1], ts, &s).unwrap();
        rec.0
    }

    /// Max interpolation error of a single step of size `h` from the exact `Y0`.
    fn one_step_error(method: Method, h: f64) -> (f64, bool) {
        let ts: Vec<f64> = [0.13, 0.5, 0.71, 0.92, 1.0].iter().map(|f| f * h).collect();
        let mut p = Probe {
            reference: reference(&ts),
            max_err: 0.0,
            ends_exact: true,
        };
        let s = Settings {
            rtol: 1e6,
            atol: 1e6,
            h0: Some(h),
            h_max: h,
            ..Settings::default()
        };
        let m = match method {
            Method::Rk4 { .. } => Method::Rk4 { step: h },
            m => m,
        };
        let st = integrate(&mut p, m, 0.0, &Y0, h, &[], &s).unwrap();
        assert_eq!(st.steps_accepted, 1);
        (p.max_err, p.ends_exact)
    }

    #[test]
    fn interpolants_converge_at_their_order() {
        // Local interpolation error is O(h^(p*+1)): 4 for Hermite (p* = 3), 5 for DOPRI5,
        // 8 for DOP853 (Hairer I, §II.6).
        for (method, p, h) in [
            (Method::Rk4 { step: 0.0 }, 4.0, 0.04),
            (Method::Rk45, 5.0, 0.04),
            (Method::Dop853, 8.0, 0.08),
        ] {
            let (e1, x1) = one_step_error(method, h);
            let (e2, x2) = one_step_error(method, h / 2.0);
            assert!(x1 && x2, "{method:?}: ends, components or end rate not reproduced exactly");
            let order = (e1 / e2).log2();
            assert!(
                order > p - 0.4 && order < p + 0.8,
                "{method:?}: errors {e1:e} {e2:e}, order {order}"
            );
        }
    }
}
