//! The one driver loop behind every integrator (docs: README "Choosing an integrator"), and
//! the step control it owns: planning the next trial step against `t_end`, the floor and the
//! step budget; retrying failed trial steps; redoing a step so that it ends on a switching
//! point; accepting a step (statistics, the system's memory, the outputs inside it). A method is
//! a [`Stepper`]: one trial step with its error test and dense output (`explicit_rk.rs`: RK4,
//! DOPRI5, DOP853 from their tableaus; `rodas4.rs`: RODAS4; `radau.rs`: RADAU5). Adding a method
//! means writing a stepper (and, for a Runge–Kutta method, a tableau); the loop is [`drive`].

use super::controller::initial_step;
use super::method::{Settings, Span, Stats};
use super::ode::{DenseOutput, OdeSystem};
use crate::error::Error;

/// Delivers the outputs at the times `t_out[*next..]` that are `≤ t1` from `dense`.
pub(super) fn emit<S: OdeSystem>(
    sys: &mut S,
    t_out: &[f64],
    next: &mut usize,
    t1: f64,
    dense: &dyn DenseOutput,
    buf: &mut [f64],
) -> Result<(), Error> {
    while let Some(&t) = t_out.get(*next) {
        if t > t1 {
            break;
        }
        dense.eval(t, buf);
        sys.output(t, buf)?;
        *next += 1;
    }
    Ok(())
}

/// Skips output times before `t0` and delivers those equal to `t0` from `y0`.
pub(super) fn emit_initial<S: OdeSystem>(sys: &mut S, t_out: &[f64], t0: f64, y0: &[f64]) -> Result<usize, Error> {
    let mut next = t_out.partition_point(|&t| t < t0);
    while t_out.get(next) == Some(&t0) {
        sys.output(t0, y0)?;
        next += 1;
    }
    Ok(next)
}

pub(super) fn all_finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

pub(super) fn non_finite(t: f64) -> Error {
    Error::NonFinite {
        t,
        detail: String::new(),
    }
}

fn record_accepted(stats: &mut Stats, h: f64, t1: f64) {
    stats.steps_accepted += 1;
    stats.h_min_used = stats.h_min_used.min(h);
    stats.h_max_used = stats.h_max_used.max(h);
    stats.t_reached = t1;
}

/// `out = f(t, y)`, counted, and checked to be finite.
pub(super) fn fresh_rhs<S: OdeSystem>(sys: &mut S, stats: &mut Stats, t: f64, y: &[f64], out: &mut [f64]) -> Result<(), Error> {
    sys.rhs(t, y, out)?;
    stats.rhs_evals += 1;
    if all_finite(out) {
        Ok(())
    } else {
        Err(non_finite(t))
    }
}

/// Everything a driver does once a step `[t, t1]` of size `h` is accepted, with its dense
/// output filled: count it, let the system update its memory, deliver the outputs inside the
/// step, and move `y1` into `y`. Returns whether the system asked for `f(t1, y1)` afresh.
#[allow(clippy::too_many_arguments)]
pub(super) fn accept_step<S: OdeSystem>(
    sys: &mut S,
    stats: &mut Stats,
    h: f64,
    t: f64,
    t1: f64,
    y: &mut Vec<f64>,
    y1: &mut Vec<f64>,
    dense: &dyn DenseOutput,
    t_out: &[f64],
    next_out: &mut usize,
    buf: &mut [f64],
) -> Result<bool, Error> {
    record_accepted(stats, h, t1);
    let refresh = sys.step_accepted(t, y, t1, y1, dense)?;
    emit(sys, t_out, next_out, t1, dense, buf)?;
    std::mem::swap(y, y1);
    Ok(refresh)
}

/// The next trial step `[t, t1]` from a proposed size `h` (clamped to `h_max`): lands exactly
/// on `t_end`, stretching by up to 1 % rather than leaving a sliver (Hairer), or splits the
/// remainder in two when `h_max` forbids the stretch. Errors: the step budget is spent
/// (`TooManySteps`), or the step fell below the floor `max(h_min, 1e-14·|t|)` — then the error of
/// the failed trial steps that shrank it, if `failed_trials` gives one, else `StepSizeUnderflow`.
/// Returns `(h_step, t1, last)`.
pub(super) fn plan_step(
    t: f64,
    h: f64,
    t_end: f64,
    st: &Settings,
    stats: &Stats,
    failed_trials: impl FnOnce() -> Option<Error>,
) -> Result<(f64, f64, bool), Error> {
    let h = h.min(st.h_max);
    let floor = st.h_min.max(1e-14 * t.abs());
    if !(h > 0.0 && h >= floor) {
        return Err(failed_trials().unwrap_or(Error::StepSizeUnderflow { t, h, detail: String::new() }));
    }
    if stats.steps_accepted + stats.steps_rejected + stats.steps_to_switch >= st.max_steps {
        return Err(Error::TooManySteps { t, max_steps: st.max_steps });
    }
    Ok(if t + 1.01 * h < t_end {
        (h, t + h, false)
    } else if t_end - t <= st.h_max * (1.0 + 1e-9) {
        (t_end - t, t_end, true)
    } else {
        let half = 0.5 * (t_end - t);
        (half, t + half, false)
    })
}

/// A switching point within this fraction of a step from either end is left inside the step:
/// redoing the step would not move it out.
const SWITCH_MARGIN: f64 = 0.02;

/// For a step `[t, t1]` that passed the error test (dense output filled): the size of the step
/// to take instead, ending on a switching point that the system reports well inside it (and
/// not below the step floor `h_min`: then the step stays as it is).
#[allow(clippy::too_many_arguments)]
pub(super) fn step_to_switch<S: OdeSystem>(
    sys: &mut S,
    st: &Settings,
    stats: &mut Stats,
    t: f64,
    y: &[f64],
    t1: f64,
    y1: &[f64],
    dense: &dyn DenseOutput,
) -> Result<Option<f64>, Error> {
    let margin = SWITCH_MARGIN * (t1 - t);
    let floor = st.h_min.max(1e-14 * t.abs());
    let inside = |ts: &f64| *ts - t > margin.max(floor) && t1 - *ts > margin;
    let h = sys.switching_point(t, y, t1, y1, dense)?.filter(inside).map(|ts| ts - t);
    if h.is_some() {
        stats.steps_to_switch += 1;
    }
    Ok(h)
}

/// What a trial step came to.
#[derive(Debug)]
pub(super) enum Trial {
    /// It passed the error test: the stepper's `y1` and dense output cover the step. The driver
    /// still decides whether it is accepted as it is or redone to end on a switching point.
    Passed,
    /// It failed the error test: try again with `h_next`.
    Rejected { h_next: f64 },
    /// It could not be completed (a stage left the domain of `f`, the Newton iteration
    /// diverged): try again with `h_next`; too many in a row end the run with `error`.
    Failed { error: Error, h_next: f64 },
}

/// One integration method as the driver sees it: a trial step with its error test and dense
/// output, plus the method's own step-size proposal. It owns its work vectors (allocated once
/// per run) and `f(t, y)` at the step's start.
pub(super) trait Stepper<S: OdeSystem> {
    /// Order of the solution, for the automatic initial step (Hairer I, §II.4).
    fn order(&self) -> usize;
    /// Consecutive failed trial steps ([`Trial::Failed`]) the run survives.
    fn max_trial_failures(&self) -> usize;
    /// `Some(step)` for a fixed-step method: the driver steps on the grid `t0 + i·step` and
    /// neither rejects steps nor moves them to switching points.
    fn fixed_step(&self) -> Option<f64> {
        None
    }
    /// Storage of `f(t, y)` at the current step's start.
    fn f0(&mut self) -> &mut [f64];
    /// Once, after `f0 = f(t0, y0)` and before the first step.
    fn start(&mut self, _sys: &mut S, _t: f64, _y: &[f64]) -> Result<(), Error> {
        Ok(())
    }
    /// One trial step `[t, t1]` of size `h` from `y`, the solution into `y1`; on
    /// [`Trial::Passed`] the dense output of the step is filled. A stage error that means "`f`
    /// is not defined there" (`NonFinite`, `SingularJacobian`) may be returned as an `Err`: the
    /// driver treats it as a failed trial and retries with a quarter of the step.
    #[allow(clippy::too_many_arguments)]
    fn attempt(&mut self, sys: &mut S, stats: &mut Stats, st: &Settings, t: f64, t1: f64, h: f64, y: &[f64], y1: &mut [f64]) -> Result<Trial, Error>;
    /// The continuous extension of the last step that passed.
    fn dense(&self) -> &dyn DenseOutput;
    /// The step of size `h` that passed is redone shorter, from the same start, to end on a
    /// switching point.
    fn redo(&mut self, _h: f64) {}
    /// The step of size `h` that passed was accepted: the size to try next.
    fn accepted(&mut self, h: f64) -> f64;
    /// `f0 = f(t, y)` for the next step; `refresh` says whether the system changed its memory
    /// at the step's end (so that a value carried over from the step, FSAL, is stale).
    fn next_f0(&mut self, sys: &mut S, stats: &mut Stats, _refresh: bool, t: f64, y: &[f64]) -> Result<(), Error> {
        fresh_rhs(sys, stats, t, y, self.f0())
    }
}

/// The next step `[t, t1]` of a fixed-step method: the grid `t0 + i·step` (no drift), a
/// remainder below `1e-10·step` merged into the last step. Returns `(h, t1, last)`.
fn plan_fixed(t0: f64, step: f64, i: u64, t: f64, t_end: f64, st: &Settings, stats: &Stats) -> Result<(f64, f64, bool), Error> {
    if stats.steps_accepted >= st.max_steps {
        return Err(Error::TooManySteps { t, max_steps: st.max_steps });
    }
    let t1 = t0 + i as f64 * step;
    let last = t1 >= t_end - 1e-10 * step;
    let t1 = if last { t_end } else { t1 };
    Ok((t1 - t, t1, last))
}

/// The driver loop (the structure of Hairer's codes): integrate `sys` over `span` with
/// `stepper`, delivering the outputs from the dense output, calling
/// [`OdeSystem::step_accepted`] after every accepted step, and stopping with
/// `StepSizeUnderflow` / `TooManySteps` / the error of the last failed trial step, or a
/// non-finite solution. The span and settings have been validated.
pub(super) fn drive<S: OdeSystem, M: Stepper<S>>(sys: &mut S, stepper: &mut M, span: Span<'_>, st: &Settings, stats: &mut Stats) -> Result<(), Error> {
    let Span { t0, y0, t_end, t_out } = span;
    let n = y0.len();
    let mut y = y0.to_vec();
    let mut y1 = vec![0.0; n];
    let mut buf = vec![0.0; n];

    let mut next_out = emit_initial(sys, t_out, t0, y0)?;
    if t_end == t0 {
        return Ok(());
    }
    let mut t = t0;
    fresh_rhs(sys, stats, t, &y, stepper.f0())?;
    stepper.start(sys, t, &y)?;
    let fixed = stepper.fixed_step();
    let mut h = match (fixed, st.h0) {
        (Some(step), _) => step,
        (None, Some(h0)) => h0,
        (None, None) => {
            let (order, h_lim) = (stepper.order(), st.h_max.min(t_end - t0));
            let h = initial_step(sys, t, &y, stepper.f0(), order as i32, h_lim, st.rtol, st.atol, &mut y1, &mut buf)?;
            stats.rhs_evals += 1;
            // A guess below the floor would fail at once: start at the floor instead.
            h.max(st.h_min)
        }
    };
    let mut grid_index: u64 = 0;
    let mut trial_failures = 0usize;
    let mut last_trial_error = non_finite(t);

    loop {
        let (h_step, t1, last) = match fixed {
            Some(step) => {
                grid_index += 1;
                plan_fixed(t0, step, grid_index, t, t_end, st, stats)?
            }
            None => plan_step(t, h, t_end, st, stats, || (trial_failures > 0).then(|| last_trial_error.clone()))?,
        };
        let trial = match stepper.attempt(sys, stats, st, t, t1, h_step, &y, &mut y1) {
            Ok(trial) => trial,
            Err(e @ (Error::NonFinite { .. } | Error::SingularJacobian { .. })) => Trial::Failed { error: e, h_next: 0.25 * h_step },
            Err(e) => return Err(e),
        };
        match trial {
            Trial::Failed { error, h_next } => {
                trial_failures += 1;
                if trial_failures > stepper.max_trial_failures() {
                    return Err(error);
                }
                last_trial_error = error;
                stats.steps_rejected += 1;
                h = h_next;
            }
            Trial::Rejected { h_next } => {
                trial_failures = 0;
                stats.steps_rejected += 1;
                h = h_next;
            }
            Trial::Passed => {
                trial_failures = 0;
                if !all_finite(&y1) {
                    return Err(non_finite(t));
                }
                if fixed.is_none() {
                    if let Some(h_switch) = step_to_switch(sys, st, stats, t, &y, t1, &y1, stepper.dense())? {
                        stepper.redo(h_step);
                        h = h_switch;
                        continue;
                    }
                }
                let refresh = accept_step(sys, stats, h_step, t, t1, &mut y, &mut y1, stepper.dense(), t_out, &mut next_out, &mut buf)?;
                t = t1;
                if last {
                    return Ok(());
                }
                stepper.next_f0(sys, stats, refresh, t, &y)?;
                h = stepper.accepted(h_step);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    //! The driver loop with a toy method written only for these tests — what adding a method
    //! takes — on `y' = −y`: it must reach `e^(−t)`, retry failed trials and stop after too many,
    //! and redo a step that straddles a switching point.
    use super::super::dense::ContinuousExtension;
    use super::super::{integrate, DenseOutput, Method, OdeSystem, Settings, Span, Stats};
    use super::{drive, Stepper, Trial};
    use crate::error::Error;

    /// Heun's method with an Euler error estimate (order 2(1)), I-controller, Hermite dense output.
    struct Heun {
        f0: Vec<f64>,
        f1: Vec<f64>,
        dense: ContinuousExtension,
        h_next: f64,
        /// The first `fail_first` trials fail.
        fail_first: usize,
        redone: Vec<f64>,
    }

    impl Heun {
        fn new(fail_first: usize) -> Self {
            Heun { f0: vec![0.0], f1: vec![0.0], dense: ContinuousExtension::new(1), h_next: 0.0, fail_first, redone: Vec::new() }
        }
    }

    impl<S: OdeSystem> Stepper<S> for Heun {
        fn order(&self) -> usize {
            2
        }
        fn max_trial_failures(&self) -> usize {
            3
        }
        fn f0(&mut self) -> &mut [f64] {
            &mut self.f0
        }
        fn attempt(&mut self, sys: &mut S, stats: &mut Stats, st: &Settings, t: f64, t1: f64, h: f64, y: &[f64], y1: &mut [f64]) -> Result<Trial, Error> {
            if self.fail_first > 0 {
                self.fail_first -= 1;
                return Ok(Trial::Failed { error: Error::NewtonFailure { t, h }, h_next: 0.5 * h });
            }
            let euler = y[0] + h * self.f0[0];
            sys.rhs(t1, &[euler], &mut self.f1)?;
            stats.rhs_evals += 1;
            y1[0] = y[0] + 0.5 * h * (self.f0[0] + self.f1[0]);
            let err = ((y1[0] - euler) / (st.atol + st.rtol * y[0].abs())).abs();
            let h_new = h * (0.9 / err.max(1e-10).sqrt()).clamp(0.2, 5.0);
            if err > 1.0 {
                return Ok(Trial::Rejected { h_next: h_new });
            }
            self.h_next = h_new;
            sys.rhs(t1, y1, &mut self.f1)?;
            stats.rhs_evals += 1;
            self.dense.fill_hermite(t, t1, y, y1, &self.f0, &self.f1);
            Ok(Trial::Passed)
        }
        fn dense(&self) -> &dyn DenseOutput {
            &self.dense
        }
        fn redo(&mut self, h: f64) {
            self.redone.push(h);
        }
        fn accepted(&mut self, _h: f64) -> f64 {
            self.h_next
        }
    }

    /// `y' = −y`, outputs recorded, with a switching point at `t_switch`.
    struct Decay {
        out: Vec<(f64, f64)>,
        t_switch: f64,
        steps: Vec<(f64, f64)>,
    }

    impl OdeSystem for Decay {
        fn dim(&self) -> usize {
            1
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error> {
            dy[0] = -y[0];
            Ok(())
        }
        fn switching_point(&mut self, t0: f64, _y0: &[f64], t1: f64, _y1: &[f64], _d: &dyn DenseOutput) -> Result<Option<f64>, Error> {
            Ok((t0 < self.t_switch && self.t_switch < t1).then_some(self.t_switch))
        }
        fn step_accepted(&mut self, t0: f64, _y0: &[f64], t1: f64, _y1: &[f64], _d: &dyn DenseOutput) -> Result<bool, Error> {
            self.steps.push((t0, t1));
            Ok(false)
        }
        fn output(&mut self, t: f64, y: &[f64]) -> Result<(), Error> {
            self.out.push((t, y[0]));
            Ok(())
        }
    }

    fn run(fail_first: usize, t_switch: f64) -> (Result<(), Error>, Stats, Decay, Heun) {
        let mut sys = Decay { out: Vec::new(), t_switch, steps: Vec::new() };
        let mut stepper = Heun::new(fail_first);
        let mut stats = Stats { h_min_used: f64::INFINITY, ..Stats::default() };
        let t_out = [0.0, 0.5, 1.0, 2.0];
        let st = Settings { rtol: 1e-6, atol: 1e-9, ..Settings::default() };
        let span = Span { t0: 0.0, y0: &[1.0], t_end: 2.0, t_out: &t_out };
        let res = drive(&mut sys, &mut stepper, span, &st, &mut stats);
        (res, stats, sys, stepper)
    }

    #[test]
    fn a_new_method_is_a_stepper_and_the_driver_does_the_rest() {
        let (res, stats, sys, stepper) = run(0, 0.7);
        res.unwrap();
        assert_eq!(sys.out.len(), 4);
        for &(t, y) in &sys.out {
            // Global error of a 2nd-order method at local tolerance 1e-6 (Hermite between steps).
            assert!((y - (-t).exp()).abs() < 2e-5, "t = {t}: {y} vs {}", (-t).exp());
        }
        // Steps tile [0, 2] and one ends on the switching point; the straddling one was redone.
        assert_eq!(sys.steps.first().unwrap().0, 0.0);
        assert_eq!(sys.steps.last().unwrap().1, 2.0);
        assert!(sys.steps.windows(2).all(|w| w[0].1 == w[1].0));
        assert!(sys.steps.iter().any(|s| s.1 == 0.7), "no step ends on the switching point");
        assert_eq!(stepper.redone.len(), 1);
        assert_eq!(stats.steps_to_switch, 1);
        assert_eq!(stats.steps_accepted, sys.steps.len());
        assert_eq!(stats.t_reached, 2.0);
    }

    #[test]
    fn failed_trials_are_retried_up_to_the_method_limit_then_reported() {
        // Three failures in a row: retried with half the step each time, then it runs through.
        let (res, stats, sys, _) = run(3, 10.0);
        res.unwrap();
        assert!(stats.steps_rejected >= 3, "{stats:?}");
        assert!(stats.h_min_used <= 0.125 * 1.01 * stats.h_max_used, "the failures halved the first step three times");
        assert!((sys.out[3].1 - (-2f64).exp()).abs() < 2e-5);
        // A fourth: the run stops with the stepper's own error at the start.
        let (res, stats, sys, _) = run(4, 10.0);
        assert!(matches!(res, Err(Error::NewtonFailure { t, .. }) if t == 0.0), "{res:?}");
        assert_eq!(stats.steps_accepted, 0);
        assert_eq!(sys.out, vec![(0.0, 1.0)], "the initial output is kept");
    }

    #[test]
    fn every_method_behind_integrate_uses_the_same_loop() {
        // Same contract for all: outputs at the requested times, the last step ends on t_end.
        for method in [Method::Rk4 { step: 0.01 }, Method::Rk45, Method::Dop853, Method::Rodas4, Method::Radau] {
            let mut sys = Decay { out: Vec::new(), t_switch: 0.7, steps: Vec::new() };
            let st = Settings { rtol: 1e-8, atol: 1e-10, ..Settings::default() };
            let stats = integrate(&mut sys, method, 0.0, &[1.0], 2.0, &[0.0, 0.5, 1.0, 2.0], &st).unwrap();
            assert_eq!(sys.out.len(), 4, "{method:?}");
            assert!(sys.out.iter().all(|&(t, y)| (y - (-t).exp()).abs() < 1e-6), "{method:?}: {:?}", sys.out);
            assert_eq!(sys.steps.last().unwrap().1, 2.0);
            // Fixed-step RK4 keeps its grid; adaptive methods end a step on the switching point,
            // unless it falls within SWITCH_MARGIN of a step's end (then redoing would not move it).
            let on_switch = sys.steps.iter().any(|s| s.1 == 0.7);
            if matches!(method, Method::Rk4 { .. }) {
                assert!(!on_switch);
            } else if !on_switch {
                let &(a, b) = sys.steps.iter().find(|s| s.0 < 0.7 && 0.7 < s.1).unwrap();
                assert!((0.7 - a).min(b - 0.7) <= super::SWITCH_MARGIN * (b - a), "{method:?}: the step [{a}, {b}] was not redone");
            }
            assert_eq!(stats.steps_accepted, sys.steps.len());
        }
    }
}
