//! Time integration: explicit Runge–Kutta methods, RODAS4 and RADAU5, with step control and
//! dense output.
//!
//! One concept per file: `driver.rs` (the one driver loop and the `Stepper`
//! trait a method implements), `tableau.rs` (Butcher tableaus with their sources),
//! `explicit_rk.rs` (the RK4, DOPRI5 and DOP853 steppers), `rodas4.rs` (RODAS4), `radau.rs`
//! (RADAU5), `controller.rs` (PI step-size control, initial step), `dense.rs` (continuous
//! extensions). [`integrate`] picks the stepper; the driver samples the solution on a user grid
//! through the dense output, so output times never shorten a step.

use crate::error::Error;
use driver::drive;

pub mod controller;
pub mod dense;
mod driver;
mod explicit_rk;
mod lu;
mod radau;
mod radau_newton;
mod rodas4;
pub mod tableau;

/// A first-order ODE system `ẏ = f(t, y)` with hooks the mechanism needs.
pub trait OdeSystem {
    /// Length of the state vector.
    fn dim(&self) -> usize;
    /// `dy = f(t, y)`. Called for every stage, including stages of steps that get rejected,
    /// so it must not change any state that outlives the call.
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error>;
    /// Called once after every accepted step `[t0, t1]`, before the outputs inside it are
    /// sampled. `dense` evaluates the step's continuous extension on `[t0, t1]`.
    /// Returns `Ok(true)` when the system changed an internal memory (e.g. recorded the start of
    /// an impact) so that `f(t1, y1)` must be evaluated again (no FSAL reuse).
    fn step_accepted(
        &mut self,
        _t0: f64,
        _y0: &[f64],
        _t1: f64,
        _y1: &[f64],
        _dense: &dyn DenseOutput,
    ) -> Result<bool, Error> {
        Ok(false)
    }
    /// The earliest switching point inside a step `[t0, t1]` that passed the error test: a time
    /// at which `f` stops being smooth (a contact starting or ending, a friction law's corner),
    /// located on `dense`, or
    /// `None`. Called before [`OdeSystem::step_accepted`]; must not change any state. When the
    /// point lies well inside the step, the drivers redo the step so that it ends there, so that
    /// no step straddles it (the error estimates assume a smooth `f`). Default: none.
    fn switching_point(&mut self, _t0: f64, _y0: &[f64], _t1: f64, _y1: &[f64], _dense: &dyn DenseOutput) -> Result<Option<f64>, Error> {
        Ok(None)
    }
    /// Called at every requested output time with the (interpolated) state.
    fn output(&mut self, t: f64, y: &[f64]) -> Result<(), Error>;
    /// For a second-order system, `y = (q, v)` and `f = (v, a(t, q, v))` with `q`, `v` of length
    /// `m = dim/2`: write an approximation of `∂a/∂q` and `∂a/∂v` (each `m × m`, column-major)
    /// and return `Ok(true)`. Used for the Newton matrices of RADAU5, whose simplified Newton
    /// iteration converges with any good approximation of the stiff part. The default,
    /// `Ok(false)`, makes it difference the whole `f` instead.
    fn acceleration_jacobian(&mut self, _t: f64, _y: &[f64], _a_q: &mut [f64], _a_v: &mut [f64]) -> Result<bool, Error> {
        Ok(false)
    }
    /// Forward-difference step for component `j` of `y` when the implicit methods difference
    /// `f`. Default (Hairer): `√(ε_mach · max(1e-5, |y_j|))`. A system whose `f` varies on a
    /// scale much finer than `|y_j|` (a journal in a µm clearance) returns a smaller one.
    fn difference_step(&self, j: usize, y: &[f64]) -> f64 {
        (f64::EPSILON * 1e-5f64.max(y[j].abs())).sqrt()
    }
}

/// Continuous extension of one accepted step.
pub trait DenseOutput {
    /// Interval `[t0, t1]` the extension covers.
    fn interval(&self) -> (f64, f64);
    /// The variable the polynomial is written in, at `t`. Default: `θ = (t − t0)/(t1 − t0)`
    /// (0 for an empty interval).
    fn fraction(&self, t: f64) -> f64 {
        let (t0, t1) = self.interval();
        if t1 != t0 { (t - t0) / (t1 - t0) } else { 0.0 }
    }
    /// Component `i` of the polynomial at `s` = [`fraction`](DenseOutput::fraction)`(t)`.
    fn component(&self, s: f64, i: usize) -> f64;
    /// State at `t` in `[t0, t1]` (extrapolated outside), written to `out` (length `dim`).
    /// Allocates nothing.
    fn eval(&self, t: f64, out: &mut [f64]) {
        let s = self.fraction(t);
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.component(s, i);
        }
    }
    /// Component `i` of the state at `t` (what [`eval`](DenseOutput::eval) writes to
    /// `out[i]`), for a caller that needs one coordinate of a large state.
    fn eval_component(&self, t: f64, i: usize) -> f64 {
        self.component(self.fraction(t), i)
    }
    /// Components `idx` of the state at `t`, each into `out[i]` (the other entries of `out`
    /// untouched): [`eval_component`](DenseOutput::eval_component) for several coordinates
    /// with one call through the trait object and `θ` computed once.
    fn eval_components(&self, t: f64, idx: &[usize], out: &mut [f64]) {
        let s = self.fraction(t);
        for &i in idx {
            out[i] = self.component(s, i);
        }
    }
    /// `f(t1, y1)` at the step's end when the method computed it exactly (the explicit
    /// Runge–Kutta methods' FSAL stage, with the memory the step was integrated with), so that
    /// a system needing the rate there need not evaluate `f` again. Default: `None`.
    fn end_rate(&self) -> Option<&[f64]> {
        None
    }
}

/// Which method to integrate with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// Classic 4th-order Runge–Kutta with a fixed step `step` \[s\]; cubic Hermite dense output.
    Rk4 { step: f64 },
    /// Dormand–Prince 5(4) with PI step control and 4th-order dense output (Hairer's DOPRI5).
    Dopri5,
    /// Dormand–Prince 8(5,3) with 7th-order dense output (Hairer's DOP853).
    Dop853,
    /// RODAS4: L-stable, stiffly accurate Rosenbrock 4(3) with 3rd-order dense output and a
    /// finite-difference Jacobian (Hairer–Wanner's RODAS), for stiff phases (`rodas4.rs`).
    Rodas4,
    /// RADAU5: 3-stage Radau IIA of order 5 (L-stable, stiffly accurate) with simplified Newton
    /// iterations and the collocation polynomial as dense output (`radau.rs`).
    Radau5,
}

/// Tolerances and limits for adaptive methods (ignored by RK4 except `max_steps`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Relative tolerance (> 0).
    pub rtol: f64,
    /// Absolute tolerance (> 0), applied to every component.
    pub atol: f64,
    /// Initial step \[s\]; `None` picks one automatically (Hairer's algorithm).
    pub h0: Option<f64>,
    /// Largest step \[s\]; `f64::INFINITY` for none.
    pub h_max: f64,
    /// Step-size floor \[s\]: a step this small that still fails is a
    /// [`Error::StepSizeUnderflow`]. The effective floor is `max(h_min, 1e-14·|t|)`.
    pub h_min: f64,
    /// Stop with [`Error::TooManySteps`] after this many steps (accepted + rejected).
    pub max_steps: usize,
}

impl Default for Settings {
    fn default() -> Self {
        Settings { rtol: 1e-6, atol: 1e-9, h0: None, h_max: f64::INFINITY, h_min: 1e-14, max_steps: 50_000_000 }
    }
}

/// Counters of one integration.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Stats {
    pub steps_accepted: usize,
    pub steps_rejected: usize,
    /// Steps redone to end on a switching point ([`OdeSystem::switching_point`]).
    pub steps_to_switch: usize,
    pub rhs_evals: usize,
    /// Jacobian (or W-matrix) evaluations of the stiff methods.
    pub jacobians: usize,
    /// Smallest accepted step \[s\] (`f64::INFINITY` before the first).
    pub h_min_used: f64,
    /// Largest accepted step \[s\].
    pub h_max_used: f64,
    /// Time reached (the end of the last accepted step).
    pub t_reached: f64,
}

/// Integrate `sys` from `(t0, y0)` to `t_end`, calling `sys.output` at each time of `t_out`
/// (sorted, inside `[t0, t_end]`; a time equal to `t0` is output from `y0`).
///
/// On failure returns the error together with the stats so far; every output before the
/// failure has already been delivered to `sys.output`.
pub fn integrate<S: OdeSystem>(
    sys: &mut S,
    method: Method,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    t_out: &[f64],
    settings: &Settings,
) -> Result<Stats, (Error, Stats)> {
    let span = Span { t0, y0, t_end, t_out };
    let mut stats = Stats { h_min_used: f64::INFINITY, t_reached: t0, ..Stats::default() };
    let n = y0.len();
    let res = span.validate(sys.dim(), method, settings).and_then(|()| match method {
        Method::Rk4 { step } => drive(sys, &mut explicit_rk::Rk4::new(n, step), span, settings, &mut stats),
        Method::Dopri5 => drive(sys, &mut explicit_rk::ExplicitRk::new(n, false), span, settings, &mut stats),
        Method::Dop853 => drive(sys, &mut explicit_rk::ExplicitRk::new(n, true), span, settings, &mut stats),
        Method::Rodas4 => drive(sys, &mut rodas4::Rodas4::new(n), span, settings, &mut stats),
        Method::Radau5 => drive(sys, &mut radau::Radau5Stepper::new(n, settings), span, settings, &mut stats),
    });
    match res {
        Ok(()) => Ok(stats),
        Err(e) => Err((e, stats)),
    }
}

/// What one integration covers: from `(t0, y0)` to `t_end`, with outputs at `t_out`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Span<'a> {
    pub t0: f64,
    pub y0: &'a [f64],
    pub t_end: f64,
    pub t_out: &'a [f64],
}

impl Span<'_> {
    /// Checks the span, and the settings `method` uses, for a system of dimension `n`.
    fn validate(&self, n: usize, method: Method, s: &Settings) -> Result<(), Error> {
        let Span { t0, y0, t_end, t_out } = *self;
        if y0.len() != n {
            return Err(Error::invalid("y0", format!("length {}", y0.len()), format!("the system has dimension {n}")));
        }
        if !t0.is_finite() {
            return Err(Error::invalid("t0", t0, "must be finite"));
        }
        if !(t_end.is_finite() && t_end >= t0) {
            return Err(Error::invalid("t_end", t_end, "must be finite and ≥ t0 (forward integration only)"));
        }
        if t_out.iter().any(|t| !t.is_finite()) || t_out.windows(2).any(|w| w[1] < w[0]) {
            return Err(Error::invalid("t_out", "[…]", "output times must be finite and sorted"));
        }
        if !y0.iter().all(|v| v.is_finite()) {
            return Err(Error::NonFinite { t: t0, detail: String::new() });
        }
        match method {
            Method::Rk4 { step } => {
                if !(step.is_finite() && step > 0.0) {
                    return Err(Error::invalid("step", step, "must be finite and > 0"));
                }
            }
            Method::Dopri5 | Method::Dop853 | Method::Rodas4 | Method::Radau5 => {
                if !(s.rtol.is_finite() && s.rtol > 0.0) {
                    return Err(Error::invalid("rtol", s.rtol, "must be finite and > 0"));
                }
                if !(s.atol.is_finite() && s.atol > 0.0) {
                    return Err(Error::invalid("atol", s.atol, "must be finite and > 0"));
                }
                if let Some(h0) = s.h0 {
                    if !(h0.is_finite() && h0 > 0.0) {
                        return Err(Error::invalid("h0", h0, "must be finite and > 0"));
                    }
                }
                if s.h_max.is_nan() || s.h_max <= 0.0 {
                    return Err(Error::invalid("h_max", s.h_max, "must be > 0"));
                }
                if !(s.h_min.is_finite() && s.h_min >= 0.0) {
                    return Err(Error::invalid("h_min", s.h_min, "must be finite and ≥ 0"));
                }
                if s.h_min > s.h_max {
                    return Err(Error::invalid("h_min", s.h_min, format!("must not exceed h_max = {}", s.h_max)));
                }
            }
        }
        Ok(())
    }
}
