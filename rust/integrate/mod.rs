//! Time integration: explicit Runge–Kutta methods, RODAS4 and RADAU5, with step control and
//! dense output.
//!
//! One concept per file: `tableau.rs` (Butcher tableaus with their sources), `explicit_rk.rs`
//! (the stepper), `controller.rs` (PI step-size control, initial step), `dense.rs` (continuous
//! extensions), `stiff.rs` (RODAS4), `radau.rs` (RADAU5). The driver [`integrate`] samples the
//! solution on a user grid through the dense output, so output times never shorten a step.

use crate::error::Error;

pub mod controller;
pub mod dense;
mod explicit_rk;
mod radau;
mod stiff;
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
}

/// Continuous extension of one accepted step.
pub trait DenseOutput {
    /// Interval `[t0, t1]` the extension covers.
    fn interval(&self) -> (f64, f64);
    /// State at `t` in `[t0, t1]`, written to `out` (length `dim`). Allocates nothing.
    fn eval(&self, t: f64, out: &mut [f64]);
}

/// Which method to integrate with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// Classic 4th-order Runge–Kutta with a fixed step `step` [s]; cubic Hermite dense output.
    Rk4 { step: f64 },
    /// Dormand–Prince 5(4) with PI step control and 4th-order dense output (Hairer's DOPRI5).
    Dopri5,
    /// Dormand–Prince 8(5,3) with 7th-order dense output (Hairer's DOP853).
    Dop853,
    /// RODAS4: L-stable, stiffly accurate Rosenbrock 4(3) with 3rd-order dense output and a
    /// finite-difference Jacobian (Hairer–Wanner's RODAS), for stiff phases (`stiff.rs`).
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
    /// Initial step [s]; `None` picks one automatically (Hairer's algorithm).
    pub h0: Option<f64>,
    /// Largest step [s]; `f64::INFINITY` for none.
    pub h_max: f64,
    /// Step-size floor [s]: a step this small that still fails is a
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
    pub rhs_evals: usize,
    /// Jacobian (or W-matrix) evaluations of the stiff methods.
    pub jacobians: usize,
    /// Smallest accepted step [s] (`f64::INFINITY` before the first).
    pub h_min_used: f64,
    /// Largest accepted step [s].
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
    explicit_rk::run(sys, method, t0, y0, t_end, t_out, settings)
}
