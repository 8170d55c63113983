//! Time integration: explicit Runge–Kutta methods, RODAS4 and RADAU5, with step control and
//! dense output. This file picks the stepper ([`integrate`]); every other file has one job and
//! imports only files below it:
//!
//! - `ode.rs`: the interface a system implements ([`OdeSystem`]) and a step's continuous
//!   extension ([`DenseOutput`]); `method.rs`: [`Method`], [`Settings`], the span's checks and
//!   [`Stats`].
//! - `driver.rs`: the one driver loop and the `Stepper` trait a method implements; it samples
//!   the solution on a user grid through the dense output, so output times never shorten a step.
//! - `explicit_rk.rs`: the RK4, DOPRI5 and DOP853 steppers, with `tableau.rs` (Butcher tableaus
//!   with their sources) and `dense.rs` (their continuous extensions).
//! - `rodas4.rs`: the RODAS4 stepper; `radau.rs`: the RADAU5 stepper, with `radau_newton.rs`
//!   (its two Newton matrices: build, factorise, solve) and `border.rs` (their rows and columns
//!   of first-order states after (q, v): a heated joint's oil temperature); `lu.rs`: the real and
//!   complex dense LU both use; `lifted.rs`: their sparse lifted form for large mechanisms, on
//!   `sparse_lu.rs`.
//! - `controller.rs`: error norms, step-size control (PI, predictive, the Newton limit) and the
//!   initial step.

use crate::error::Error;
use driver::drive;
use method::Span;

mod border;
pub mod controller;
pub mod dense;
mod driver;
mod explicit_rk;
mod lifted;
mod lu;
mod method;
mod ode;
mod radau;
mod radau_newton;
mod rodas4;
mod sparse_lu;
pub mod tableau;

pub use method::{Method, Settings, Stats};
pub use ode::{DenseOutput, LiftedPattern, OdeSystem};

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
        Method::Rk45 => drive(sys, &mut explicit_rk::ExplicitRk::new(n, false), span, settings, &mut stats),
        Method::Dop853 => drive(sys, &mut explicit_rk::ExplicitRk::new(n, true), span, settings, &mut stats),
        Method::Rodas4 => drive(sys, &mut rodas4::Rodas4::new(n), span, settings, &mut stats),
        Method::Radau => drive(sys, &mut radau::Radau5Stepper::new(n, settings), span, settings, &mut stats),
    });
    match res {
        Ok(()) => Ok(stats),
        Err(e) => Err((e, stats)),
    }
}
