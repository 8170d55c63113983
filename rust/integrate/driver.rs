//! What every integrator driver shares (docs: README "Choosing an integrator"): planning the
//! next trial step against `t_end`, the floor and the step budget; redoing a step so that it
//! ends on a switching point; accepting a step (statistics, the system's memory, the outputs
//! inside it); and the stiff drivers' end of step and post-accept step size. The explicit
//! (`explicit_rk.rs`), Rosenbrock (`stiff.rs`) and Radau (`radau.rs`) steppers call these, so
//! step control around a step is written once.

use super::{DenseOutput, OdeSystem, Settings, Stats};
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

/// The end of an accepted step of the stiff drivers, its dense output filled: accept it
/// ([`accept_step`]: memory, outputs), move `t` to `t1` and — unless it was the `last` — evaluate
/// `f0 = f(t1, y1)` afresh (the system may have changed its memory). Returns whether the run is
/// done. `step` is `(h, t, t1, last)`, `outputs` the output times and the next one to deliver.
#[allow(clippy::too_many_arguments)]
pub(super) fn finish_accepted<S: OdeSystem>(
    sys: &mut S,
    stats: &mut Stats,
    step: (f64, &mut f64, f64, bool),
    y: &mut Vec<f64>,
    ynew: &mut Vec<f64>,
    dense: &dyn DenseOutput,
    outputs: (&[f64], &mut usize),
    buf: &mut [f64],
    f0: &mut [f64],
) -> Result<bool, Error> {
    let (h, t, t1, last) = step;
    accept_step(sys, stats, h, *t, t1, y, ynew, dense, outputs.0, outputs.1, buf)?;
    *t = t1;
    if last {
        return Ok(true);
    }
    fresh_rhs(sys, stats, t1, y, f0)?;
    Ok(false)
}

/// The step size after an accepted step of the stiff drivers: `hs/quot`, but no growth right
/// after a rejection (Hairer's RODAS and RADAU5); clears `reject`.
pub(super) fn size_after_accept(hs: f64, quot: f64, reject: &mut bool) -> f64 {
    let h = if *reject { (hs / quot).min(hs) } else { hs / quot };
    *reject = false;
    h
}

