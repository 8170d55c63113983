//! Step-size control: error norms, the PI controller of the explicit methods, the predictive
//! controller and the Newton-failure limit of the implicit ones, and the automatic initial step
//! (Hairer I, §II.4 "Automatic Step Size Control" and "Starting Step Size"; the PI
//! "Lund-stabilization" of Gustafsson as implemented in Hairer's DOPRI5/DOP853 codes;
//! Gustafsson's predictive controller as in Hairer's RODAS and RADAU5, Hairer–Wanner IV.8).

use super::ode::OdeSystem;
use crate::error::Error;

/// Error scale of one component, `sc = atol + rtol·max(|y0|, |y1|)` (Hairer I, eq. II.4.10).
#[inline]
pub fn scale(atol: f64, rtol: f64, y0: f64, y1: f64) -> f64 {
    atol + rtol * y0.abs().max(y1.abs())
}

/// RMS norm of a local error estimate `err` (already multiplied by `h`):
/// `sqrt(1/n Σ (err_i / sc_i)²)` (Hairer I, eq. II.4.11). Zero for an empty state.
pub fn rms_error(err: &[f64], y0: &[f64], y1: &[f64], rtol: f64, atol: f64) -> f64 {
    if err.is_empty() {
        return 0.0;
    }
    let sum: f64 = err
        .iter()
        .zip(y0.iter().zip(y1))
        .map(|(e, (a, b))| {
            let r = e / scale(atol, rtol, *a, *b);
            r * r
        })
        .sum();
    (sum / err.len() as f64).sqrt()
}

/// Combined error norm of DOP853 (Hairer's `dop853.f`): with `E5 = Σ (e5_i/sc_i)²` and
/// `E3 = Σ (e3_i/sc_i)²` (both estimates already multiplied by `h`),
/// `err = E5 / sqrt(n (E5 + 0.01 E3))`. This behaves like a 5th-order estimate for small `h`
/// and like an 8th-order one when the 3rd-order estimate dominates.
pub fn dop853_error(e5: &[f64], e3: &[f64], y0: &[f64], y1: &[f64], rtol: f64, atol: f64) -> f64 {
    let (mut s5, mut s3) = (0.0, 0.0);
    for i in 0..e5.len() {
        let sc = scale(atol, rtol, y0[i], y1[i]);
        s5 += (e5[i] / sc) * (e5[i] / sc);
        s3 += (e3[i] / sc) * (e3[i] / sc);
    }
    let mut deno = s5 + 0.01 * s3;
    if deno <= 0.0 {
        deno = 1.0; // also covers n = 0 (then s5 = 0)
    }
    s5 / (e5.len() as f64 * deno).sqrt()
}

/// Outcome of one step-size decision.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Decision {
    /// The step is accepted; try `h_next` for the next one.
    Accept { h_next: f64 },
    /// The step is rejected; redo it with `h_next`.
    Reject { h_next: f64 },
}

/// PI step-size controller (Hairer I, §II.4, eq. 4.13 with the stabilization of §IV.2 as in the
/// DOPRI5/DOP853 codes): `h_new = h · clamp(safety · err^(−α) · err_old^β, fac_min, fac_max)`,
/// accepted iff `err ≤ 1`; after a rejection the next accepted step may not grow.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Controller {
    /// Safety factor (0.9).
    pub safety: f64,
    /// Smallest allowed ratio `h_new / h`.
    pub fac_min: f64,
    /// Largest allowed ratio `h_new / h`.
    pub fac_max: f64,
    /// Exponent `α` of the current error (`1/(q+1) − 0.75 β` for DOPRI5, `1/8 − 0.2 β` for DOP853).
    pub alpha: f64,
    /// Exponent `β` of the previous accepted error (PI term; 0 gives the classic I controller).
    pub beta: f64,
    err_old: f64,
    rejected: bool,
}

impl Controller {
    /// Settings of Hairer's DOPRI5: safety 0.9, ratios in [0.2, 10], β = 0.04, α = 0.2 − 0.75 β.
    pub fn dopri5() -> Self {
        let beta = 0.04;
        Self::new(0.9, 0.2, 10.0, 0.2 - 0.75 * beta, beta)
    }

    /// Settings of Hairer's DOP853: safety 0.9, ratios in [0.333, 6], β = 0, α = 1/8.
    pub fn dop853() -> Self {
        Self::new(0.9, 0.333, 6.0, 0.125, 0.0)
    }

    /// A controller with the given constants.
    pub fn new(safety: f64, fac_min: f64, fac_max: f64, alpha: f64, beta: f64) -> Self {
        Controller {
            safety,
            fac_min,
            fac_max,
            alpha,
            beta,
            err_old: 1e-4,
            rejected: false,
        }
    }

    /// Decide on a step of size `h` whose scaled error norm is `err` (finite, ≥ 0).
    pub fn decide(&mut self, err: f64, h: f64) -> Decision {
        let fac11 = err.powf(self.alpha);
        if err <= 1.0 {
            // fac = h / h_new, limited to [1/fac_max, 1/fac_min].
            let fac =
                (fac11 / self.err_old.powf(self.beta) / self.safety).clamp(1.0 / self.fac_max, 1.0 / self.fac_min);
            let mut h_next = h / fac;
            if self.rejected {
                h_next = h_next.min(h);
            }
            self.err_old = err.max(1e-4);
            self.rejected = false;
            Decision::Accept { h_next }
        } else {
            // No PI term on rejection (Hairer's codes).
            self.rejected = true;
            Decision::Reject {
                h_next: h / (fac11 / self.safety).min(1.0 / self.fac_min),
            }
        }
    }
}

/// Gustafsson's predictive step-size controller of the stiff codes (Hairer–Wanner IV.8,
/// eq. 8.25; as in Hairer's RODAS and RADAU5): `h_new = h / q` with
/// `q = clamp(err^(1/4)/safety, q_min, q_max)`, and after the first accepted step
/// `q = max(q, clamp((h_acc/h)(err²/err_acc)^(1/4)/safety, …))` from the last accepted step
/// `(h_acc, err_acc)`. A step that passes may still be redone (a switching point); the size
/// after a real acceptance is [`Predictive::size_after_accept`], which does not grow right after
/// a rejected or failed trial.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Predictive {
    /// Safety factor of the predictive term (0.9).
    pub safety: f64,
    /// Bounds of `q = h/h_new`: `h_new/h ∈ [1/q_max, 1/q_min]`.
    pub q_min: f64,
    pub q_max: f64,
    h_acc: f64,
    err_acc: f64,
    rejected: bool,
    quot: f64,
}

impl Predictive {
    /// RODAS: `h_new/h ∈ [1/5, 6]`.
    pub fn rodas() -> Self {
        Predictive::new(1.0 / 6.0, 5.0)
    }
    /// RADAU5: `h_new/h ∈ [1/5, 8]`.
    pub fn radau5() -> Self {
        Predictive::new(1.0 / 8.0, 5.0)
    }
    fn new(q_min: f64, q_max: f64) -> Self {
        Predictive { safety: 0.9, q_min, q_max, h_acc: 0.0, err_acc: 1.0, rejected: false, quot: 1.0 }
    }

    /// Decide on a trial of size `h` with error `err`; `safety` scales the error term of this
    /// step (RADAU5 lowers it when the Newton iteration needed many iterations) and `predict`
    /// turns the predictive term on (after the first accepted step). An accepted decision's
    /// `h_next` is the plain proposal; use [`Predictive::size_after_accept`] once the step is kept.
    pub fn decide(&mut self, err: f64, h: f64, safety: f64, predict: bool) -> Decision {
        let mut q = (err.powf(0.25) / safety).clamp(self.q_min, self.q_max);
        if err > 1.0 {
            self.rejected = true;
            return Decision::Reject { h_next: h / q };
        }
        if predict {
            let qg = ((self.h_acc / h) * (err * err / self.err_acc).powf(0.25) / self.safety).clamp(self.q_min, self.q_max);
            q = q.max(qg);
        }
        self.h_acc = h;
        self.err_acc = err.max(1e-2);
        self.quot = q;
        Decision::Accept { h_next: h / q }
    }

    /// A trial failed (not finite, Newton diverged): like a rejection, the next accepted step
    /// may not grow.
    pub fn failed(&mut self) {
        self.rejected = true;
    }

    /// The size after the step of size `h` that passed last was kept: `h/q`, but no growth
    /// right after a rejection.
    pub fn size_after_accept(&mut self, h: f64) -> f64 {
        let h_next = if self.rejected { (h / self.quot).min(h) } else { h / self.quot };
        self.rejected = false;
        h_next
    }
}

/// Memory of the step sizes at which an implicit method's Newton iteration failed. Where the
/// error estimate would let the step grow but the iteration cannot converge beyond some size
/// (a stiff force with kinks, a µm oil film), the error-based proposal runs into the same
/// failure again and again (grow eightfold, fail, halve, halve, halve). A failure at `h` counts
/// once a shorter step converges with the same Newton matrix (a failure cured by a better
/// matrix says nothing about the step: [`NewtonLimit::reset`]); from then on the proposals are
/// capped at `margin · h`, the cap relaxing by `relax` per accepted step, so a limit that has
/// gone is forgotten within a few steps (1.1: tenfold in 25 steps).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonLimit {
    cap: f64,
    /// The smallest failed size since the last accepted step.
    pending: f64,
    /// Fraction of the failed size the cap is set to.
    pub margin: f64,
    /// Growth of the cap per accepted step.
    pub relax: f64,
}

impl NewtonLimit {
    pub fn new(margin: f64, relax: f64) -> Self {
        NewtonLimit { cap: f64::INFINITY, pending: f64::INFINITY, margin, relax }
    }

    /// Forget the failures: the Newton matrix they were seen with has been replaced.
    pub fn reset(&mut self) {
        self.cap = f64::INFINITY;
        self.pending = f64::INFINITY;
    }

    /// The Newton iteration failed on a step of size `h`.
    pub fn failed(&mut self, h: f64) {
        self.pending = self.pending.min(h);
    }

    /// The size to try after an accepted step, given the error-based proposal `h_next`: the
    /// failures before it count if the step's Newton iteration was `trusted`; the cap then
    /// relaxes.
    pub fn after_accept(&mut self, h_next: f64, trusted: bool) -> f64 {
        if trusted {
            self.cap = self.cap.min(self.margin * self.pending);
        }
        self.pending = f64::INFINITY;
        let h = h_next.min(self.cap);
        self.cap *= self.relax;
        h
    }
}

/// Automatic initial step (Hairer I, §II.4 "Starting Step Size"; `HINIT` of DOPRI5/DOP853).
///
/// With `d0 = ‖y0‖`, `d1 = ‖f0‖` (RMS norms scaled by `atol + rtol |y0|`): `h0 = 0.01 d0/d1`
/// (or `1e-6` when either is tiny), one Euler step to estimate `d2 = ‖f(t0+h0, y0+h0 f0) − f0‖/h0`,
/// then `h = min(100 h0, (0.01/max(d1, d2))^(1/order), h_max)`.
/// `y1` and `f1` are work vectors of length `n`. Uses one evaluation of `f`.
#[allow(clippy::too_many_arguments)]
pub fn initial_step<S: OdeSystem + ?Sized>(
    sys: &mut S,
    t0: f64,
    y0: &[f64],
    f0: &[f64],
    order: i32,
    h_max: f64,
    rtol: f64,
    atol: f64,
    y1: &mut [f64],
    f1: &mut [f64],
) -> Result<f64, Error> {
    let n = y0.len().max(1) as f64;
    let (mut dnf, mut dny) = (0.0, 0.0);
    for i in 0..y0.len() {
        let sk = atol + rtol * y0[i].abs();
        dnf += (f0[i] / sk) * (f0[i] / sk);
        dny += (y0[i] / sk) * (y0[i] / sk);
    }
    let (d0, d1) = ((dny / n).sqrt(), (dnf / n).sqrt());
    let mut h = if d0 <= 1e-5 || d1 <= 1e-5 { 1e-6 } else { 0.01 * d0 / d1 };
    h = h.min(h_max);
    for i in 0..y0.len() {
        y1[i] = y0[i] + h * f0[i];
    }
    sys.rhs(t0 + h, y1, f1)?;
    let mut d2 = 0.0;
    for i in 0..y0.len() {
        let sk = atol + rtol * y0[i].abs();
        d2 += ((f1[i] - f0[i]) / sk) * ((f1[i] - f0[i]) / sk);
    }
    let d2 = (d2 / n).sqrt() / h;
    let d12 = d1.max(d2); // NaN in d2 is ignored by max
    let h1 = if d12 <= 1e-15 {
        1e-6_f64.max(h * 1e-3)
    } else {
        (0.01 / d12).powf(1.0 / order as f64)
    };
    let h_new = (100.0 * h).min(h1).min(h_max);
    Ok(if h_new.is_finite() && h_new > 0.0 { h_new } else { h })
}

#[cfg(test)]
mod tests {
    use super::*;

    impl NewtonLimit {
        fn after_accept_t(&mut self, h_next: f64) -> f64 {
            self.after_accept(h_next, true)
        }
    }

    #[test]
    fn accept_iff_error_at_most_one() {
        for mut c in [Controller::dopri5(), Controller::dop853()] {
            assert!(matches!(c.decide(0.5, 1.0), Decision::Accept { .. }));
            assert!(matches!(c.decide(1.0, 1.0), Decision::Accept { .. }));
            assert!(matches!(c.decide(1.0 + 1e-12, 1.0), Decision::Reject { .. }));
            assert!(matches!(c.decide(1e3, 1.0), Decision::Reject { .. }));
        }
    }

    #[test]
    fn step_ratio_is_bounded() {
        for proto in [Controller::dopri5(), Controller::dop853()] {
            for &err in &[0.0, 1e-300, 1e-12, 1e-3, 0.3, 0.99, 1.0, 1.5, 10.0, 1e6, 1e300] {
                let mut c = proto;
                let h = 0.01;
                let h_next = match c.decide(err, h) {
                    Decision::Accept { h_next } | Decision::Reject { h_next } => h_next,
                };
                let r = h_next / h;
                assert!(
                    r >= proto.fac_min * (1.0 - 1e-12) && r <= proto.fac_max * (1.0 + 1e-12),
                    "err {err}: ratio {r}"
                );
                if err > 1.0 {
                    assert!(r < 1.0, "a rejected step must shrink (err {err}, ratio {r})");
                }
            }
            // Zero error: maximal growth; huge error: maximal shrink.
            let mut c = proto;
            assert_eq!(c.decide(0.0, 1.0), Decision::Accept { h_next: proto.fac_max });
            let mut c = proto;
            assert_eq!(c.decide(1e300, 1.0), Decision::Reject { h_next: proto.fac_min });
        }
    }

    #[test]
    fn no_growth_right_after_rejection() {
        let mut c = Controller::dopri5();
        assert!(matches!(c.decide(4.0, 1.0), Decision::Reject { .. }));
        match c.decide(1e-10, 0.5) {
            Decision::Accept { h_next } => assert!(h_next <= 0.5),
            d => panic!("expected acceptance, got {d:?}"),
        }
        // …but the next acceptance may grow again.
        match c.decide(1e-10, 0.5) {
            Decision::Accept { h_next } => assert!(h_next > 0.5),
            d => panic!("expected acceptance, got {d:?}"),
        }
    }

    #[test]
    fn i_controller_follows_asymptotic_law() {
        // β = 0: h_new = 0.9 h err^(-1/8) inside the limits.
        let mut c = Controller::dop853();
        let err: f64 = 0.01;
        match c.decide(err, 1.0) {
            Decision::Accept { h_next } => assert!((h_next - 0.9 * err.powf(-0.125)).abs() < 1e-14),
            d => panic!("{d:?}"),
        }
        // PI: a larger previous error allows a larger step (β > 0).
        let (mut a, mut b) = (Controller::dopri5(), Controller::dopri5());
        a.decide(0.9, 1.0);
        b.decide(0.01, 1.0);
        let ha = match a.decide(0.1, 1.0) {
            Decision::Accept { h_next } => h_next,
            d => panic!("{d:?}"),
        };
        let hb = match b.decide(0.1, 1.0) {
            Decision::Accept { h_next } => h_next,
            d => panic!("{d:?}"),
        };
        assert!(ha > hb);
    }

    #[test]
    fn norms() {
        let y0 = [1.0, -2.0];
        let y1 = [3.0, 0.0];
        let e = [1e-6, 1e-6];
        // sc = 1e-6 + 1e-3·max = [3.001e-3, 2.001e-3]
        let expect = (((1e-6 / 3.001e-3_f64).powi(2) + (1e-6 / 2.001e-3_f64).powi(2)) / 2.0).sqrt();
        assert!((rms_error(&e, &y0, &y1, 1e-3, 1e-6) - expect).abs() < 1e-15);
        assert_eq!(rms_error(&[], &[], &[], 1e-3, 1e-6), 0.0);
        assert!(rms_error(&[f64::NAN, 0.0], &y0, &y1, 1e-3, 1e-6).is_nan());
        // DOP853 norm: equals the 5th-order RMS norm when the 3rd-order estimate is zero…
        let z = [0.0, 0.0];
        assert!((dop853_error(&e, &z, &y0, &y1, 1e-3, 1e-6) - expect).abs() < 1e-15);
        // …and is smaller when the 3rd-order estimate is large (err5²/sqrt(err5²+0.01 err3²)).
        assert!(dop853_error(&e, &[1.0, 1.0], &y0, &y1, 1e-3, 1e-6) < expect);
        assert_eq!(dop853_error(&z, &z, &y0, &y1, 1e-3, 1e-6), 0.0);
    }

    struct Decay(usize);
    impl OdeSystem for Decay {
        fn dim(&self) -> usize {
            1
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
            self.0 += 1;
            dy[0] = -50.0 * y[0];
            Ok(())
        }
        fn output(&mut self, _t: f64, _y: &[f64]) -> Result<(), Error> {
            Ok(())
        }
    }

    #[test]
    fn initial_step_is_sane() {
        let mut sys = Decay(0);
        let (mut y1, mut f1) = ([0.0], [0.0]);
        let y0 = [1.0];
        let f0 = [-50.0];
        let h = initial_step(&mut sys, 0.0, &y0, &f0, 5, f64::INFINITY, 1e-6, 1e-6, &mut y1, &mut f1).unwrap();
        assert_eq!(sys.0, 1);
        // The local error of order 5 of a step h on y' = −50y is ~ (50h)^6/720 ~ tolerance.
        assert!(h > 1e-4 && h < 0.02, "h = {h}");
        let h_capped = initial_step(&mut sys, 0.0, &y0, &f0, 5, 1e-5, 1e-6, 1e-6, &mut y1, &mut f1).unwrap();
        assert!(h_capped <= 1e-5);
        // Zero state and derivative: fall back to small positive steps.
        let h0 = initial_step(&mut sys, 0.0, &[0.0], &[0.0], 8, 1.0, 1e-6, 1e-6, &mut y1, &mut f1).unwrap();
        assert!(h0 > 0.0 && h0.is_finite());
    }

    #[test]
    fn predictive_controller_shrinks_on_rejection_and_does_not_grow_right_after() {
        let mut c = Predictive::rodas();
        // Rejected with err = 16: q = 2/0.9 → h/2.22.
        match c.decide(16.0, 1.0, 0.9, false) {
            Decision::Reject { h_next } => assert!((h_next - 0.45).abs() < 1e-12, "{h_next}"),
            d => panic!("{d:?}"),
        }
        // Passed with a tiny error: would grow 6×, but not right after the rejection.
        assert!(matches!(c.decide(1e-8, 0.45, 0.9, false), Decision::Accept { h_next } if (h_next - 0.45 * 6.0).abs() < 1e-12));
        assert_eq!(c.size_after_accept(0.45), 0.45);
        // Next one grows; the predictive term (err rising from 1e-2 to 0.5) holds it back.
        assert!(matches!(c.decide(1e-8, 0.45, 0.9, true), Decision::Accept { .. }));
        assert!((c.size_after_accept(0.45) - 2.7).abs() < 1e-12);
        c.decide(0.5, 1.0, 0.9, true);
        let plain = 1.0 / (0.5f64.powf(0.25) / 0.9);
        let h = c.size_after_accept(1.0);
        assert!(h < plain, "{h} vs {plain}");
        let q = (0.45 / 1.0) * (0.25f64 / 1e-2).powf(0.25) / 0.9;
        assert!((h - 1.0 / q).abs() < 1e-12, "{h} vs {}", 1.0 / q);
    }

    #[test]
    fn newton_limit_caps_after_a_failure_and_forgets_it() {
        let mut l = NewtonLimit::new(0.8, 1.1);
        // No failure yet: the proposal passes.
        assert_eq!(l.after_accept_t(3.0), 3.0);
        // Failures at 8 and then 2, then a step converges: the cap is 0.8 × the smallest.
        l.failed(8.0);
        l.failed(2.0);
        assert_eq!(l.after_accept_t(10.0), 1.6);
        // Failures cured by a new Newton matrix do not count.
        let mut m = NewtonLimit::new(0.8, 1.1);
        m.failed(4.0);
        m.reset();
        assert_eq!(m.after_accept_t(10.0), 10.0);
        // A proposal below the cap passes; the cap relaxes by 1.1 per accepted step.
        assert_eq!(l.after_accept_t(1.0), 1.0);
        let cap = l.after_accept_t(10.0);
        assert!((cap - 1.6 * 1.1 * 1.1).abs() < 1e-12, "{cap}");
        // Within ~25 accepted steps a tenfold proposal is back.
        let mut h = 0.0;
        for _ in 0..25 {
            h = l.after_accept_t(16.0);
        }
        assert_eq!(h, 16.0);
        // Failures cured only by a slow iteration (an untrusted step) do not count.
        let mut u = NewtonLimit::new(0.8, 1.1);
        u.failed(2.0);
        assert_eq!(u.after_accept(10.0, false), 10.0);
    }

    /// A toy "Newton" that converges only for h ≤ 1 while the error test would let every step
    /// grow eightfold: without the limit each accepted step costs three failures (8 → 4 → 2 → 1);
    /// with it, one failure per three accepted steps (the cap creeps back up by 1.1 per step and
    /// meets the sharp limit again: the price of forgetting a limit that has gone).
    #[test]
    fn newton_limit_removes_repeated_failures() {
        let run = |limit: bool| {
            let mut l = NewtonLimit::new(0.8, 1.1);
            let (mut h, mut failures, mut accepted) = (1.0f64, 0, 0);
            while accepted < 100 {
                if h > 1.0 {
                    failures += 1;
                    if limit {
                        l.failed(h);
                    }
                    h *= 0.5;
                } else {
                    accepted += 1;
                    let proposal = 8.0 * h; // the error estimate is tiny: grow
                    h = if limit { l.after_accept_t(proposal) } else { proposal };
                }
            }
            failures
        };
        let (plain, limited) = (run(false), run(true));
        assert!(plain >= 250, "{plain}");
        assert!(limited <= 40, "{limited}");
    }
}
