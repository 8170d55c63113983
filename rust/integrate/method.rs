//! What one integration is asked and what it reports: the [`Method`], its [`Settings`], the
//! span it covers (`Span`, checked here before the first step) and the counters of the run
//! ([`Stats`]).

use crate::error::Error;

/// Which method to integrate with; each variant is named as the Python API, the CLI and scene
/// files name it (`rk4`, `rk45`, `dop853`, `rodas4`, `radau`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// Classic 4th-order Runge–Kutta with a fixed step `step` \[s\]; cubic Hermite dense output.
    Rk4 { step: f64 },
    /// `rk45`: Dormand–Prince 5(4) with PI step control and 4th-order dense output (Hairer's
    /// DOPRI5).
    Rk45,
    /// Dormand–Prince 8(5,3) with 7th-order dense output (Hairer's DOP853).
    Dop853,
    /// RODAS4: L-stable, stiffly accurate Rosenbrock 4(3) with 3rd-order dense output and a
    /// finite-difference Jacobian (Hairer–Wanner's RODAS), for stiff phases (`rodas4.rs`).
    Rodas4,
    /// `radau`: RADAU5, the 3-stage Radau IIA of order 5 (L-stable, stiffly accurate) with
    /// simplified Newton iterations and the collocation polynomial as dense output (`radau.rs`).
    Radau,
}

impl Method {
    /// The method's name, as the Python API, the CLI and scene files write it (`"rk45"`, …).
    pub fn name(&self) -> &'static str {
        match self {
            Method::Rk4 { .. } => "rk4",
            Method::Rk45 => "rk45",
            Method::Dop853 => "dop853",
            Method::Rodas4 => "rodas4",
            Method::Radau => "radau",
        }
    }
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
    /// Steps redone to end on a switching point ([`OdeSystem::switching_point`](crate::integrate::OdeSystem::switching_point)).
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
    pub(super) fn validate(&self, n: usize, method: Method, s: &Settings) -> Result<(), Error> {
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
            Method::Rk45 | Method::Dop853 | Method::Rodas4 | Method::Radau => {
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
