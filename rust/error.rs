//! The one error type of the crate, and the one warning type. `rust/python/mod.rs` maps each
//! error variant to a Python exception (its kind decides, never its text) and each [`Warning`] to
//! a `PlausibilityWarning`; nothing else in the crate knows about Python.

/// Everything that can go wrong while describing, assembling or simulating a mechanism.
#[derive(Debug, Clone, thiserror::Error, PartialEq)]
pub enum Error {
    /// A field of the user's description has a value it cannot take.
    #[error("invalid {field} = {value}: {reason}")]
    InvalidInput {
        field: String,
        value: String,
        reason: String,
    },
    /// A name (body, joint, driver) is unknown or used twice.
    #[error("{what} '{name}': {reason}")]
    Name {
        what: &'static str,
        name: String,
        reason: String,
    },
    /// Newton's method could not close the loops of the ideal mechanism.
    #[error("assembly failed at t = {t} s: {reason} (residual ‖Φ‖ = {residual:.3e})")]
    Assembly { t: f64, residual: f64, reason: String },
    /// The assembly of the pose given moved a body further than the mechanism's assembly
    /// tolerance ([`crate::pose`]): `body` moved by `moved` \[m\] and turned by `turned` \[rad\];
    /// `joint`, if named, has its points furthest apart at the pose given. `field` and `value`
    /// locate it (the joint and its gap \[m\], or the body's position and its move).
    #[error("{message}")]
    PoseMoved { body: String, joint: Option<String>, moved: f64, turned: f64, field: String, value: f64, message: String },
    /// The KKT (Schur complement) matrix is singular: redundant constraints or a singular pose.
    #[error("singular constraint Jacobian at t = {t} s (constraint {index}): redundant constraints or a singular configuration")]
    SingularJacobian { t: f64, index: usize },
    /// The constraint Jacobian lost rank during a run (a dead centre the drivers push into):
    /// `reason` names the joints and drivers whose rows became dependent ([`crate::rank`]).
    #[error("{reason}")]
    LockUp { t: f64, reason: String },
    /// The adaptive step size fell below its floor.
    #[error("step size underflow at t = {t} s: h = {h:.3e} s{detail}")]
    StepSizeUnderflow { t: f64, h: f64, detail: String },
    /// A state or derivative stopped being finite.
    #[error("non-finite state at t = {t} s{detail}")]
    NonFinite { t: f64, detail: String },
    /// The maximum number of steps was reached before t_end.
    #[error("maximum number of steps ({max_steps}) reached at t = {t} s")]
    TooManySteps { t: f64, max_steps: usize },
    /// A journal went deeper into its bearing than any contact law can mean
    /// ([`crate::clearance::max_penetration`], `ClearanceJoint::penetration_limit`): the mechanism locks up or is driven through a pose
    /// it cannot pass.
    #[error("clearance joint '{joint}' penetrated {penetration:.3e} m deep (journal into bearing, or slider end into guide) at t = {t} s (limit {limit:.3e} m): the mechanism is locked up, driven through a pose it cannot pass, or its contact law is far too soft")]
    PenetrationTooDeep { t: f64, joint: String, penetration: f64, limit: f64 },
    /// An implicit method's Newton iteration kept failing to converge, down to step `h`.
    #[error("Newton iteration does not converge at t = {t} s, even with h = {h:.3e} s")]
    NewtonFailure { t: f64, h: f64 },
    /// The run used up its wall-time budget (`max_seconds`).
    #[error("wall-time budget of {seconds} s used up at t = {t} s")]
    TimeBudget { t: f64, seconds: f64 },
    /// The user interrupted the run (Ctrl-C).
    #[error("interrupted at t = {t} s")]
    Interrupted { t: f64 },
    /// The reference run a sample is measured against failed (`what`: the mechanism run, e.g.
    /// "ideal mechanism"), so the sample was not run ([`crate::batch`]).
    #[error("{cause} ({what})")]
    Reference { what: &'static str, cause: Box<Error> },
}

impl Error {
    /// Shorthand for [`Error::InvalidInput`].
    pub fn invalid(field: impl Into<String>, value: impl std::fmt::Display, reason: impl Into<String>) -> Self {
        Error::InvalidInput { field: field.into(), value: value.to_string(), reason: reason.into() }
    }

    /// Time at which a simulation failure happened, if this is one.
    pub fn time(&self) -> Option<f64> {
        match self {
            Error::Assembly { t, .. }
            | Error::SingularJacobian { t, .. }
            | Error::LockUp { t, .. }
            | Error::StepSizeUnderflow { t, .. }
            | Error::NonFinite { t, .. }
            | Error::TooManySteps { t, .. }
            | Error::TimeBudget { t, .. }
            | Error::NewtonFailure { t, .. }
            | Error::PenetrationTooDeep { t, .. }
            | Error::Interrupted { t } => Some(*t),
            Error::PoseMoved { .. } => Some(0.0),
            Error::Reference { cause, .. } => cause.time(),
            _ => None,
        }
    }

    /// Whether the run stalled: it used up its budget (steps, wall time), its step fell to the
    /// floor, or the user stopped it. A stall is no fault of the model as such; where the film
    /// model sets the pace, [`crate::simulate::failure_hint`] says what to try.
    pub fn is_stall(&self) -> bool {
        matches!(self, Error::TimeBudget { .. } | Error::TooManySteps { .. } | Error::StepSizeUnderflow { .. } | Error::Interrupted { .. })
    }

    /// The error at the root of a chain of [`Error::Reference`] (what kind of failure it is).
    pub fn root(&self) -> &Error {
        match self {
            Error::Reference { cause, .. } => cause.root(),
            other => other,
        }
    }

    /// Append a diagnosis (e.g. "; joint B, ε = 1.07") to a simulation failure.
    pub fn with_detail(mut self, extra: &str) -> Self {
        if let Error::NewtonFailure { t, h } = self {
            // Reported as the step-size underflow it is, with the cause and the diagnosis.
            return Error::StepSizeUnderflow { t, h, detail: format!("; the Newton iteration does not converge{extra}") };
        }
        match &mut self {
            Error::StepSizeUnderflow { detail, .. } | Error::NonFinite { detail, .. } | Error::LockUp { reason: detail, .. } => detail.push_str(extra),
            _ => {}
        }
        self
    }
}

pub type Result<T> = std::result::Result<T, Error>;

/// A number as it appears in a message: as Python writes it (`repr`), which is how the user gave
/// it: `2.0`, `0.001`, `1e-06`, `1e+20`, `nan`, `-inf` (Rust's `Display` would print 1e-300 with
/// 300 digits). Run settings' messages ([`crate::settings`]) write their numbers the same way.
pub fn num(v: f64) -> String {
    let a = v.abs();
    if v.is_nan() {
        "nan".to_string()
    } else if a.is_infinite() {
        (if v > 0.0 { "inf" } else { "-inf" }).to_string()
    } else if a == 0.0 || (1e-4..1e16).contains(&a) {
        format!("{v:?}") // shortest round-trip digits, with ".0" on whole numbers
    } else {
        let s = format!("{v:e}"); // 1e-6, 1.5e20
        let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
        let (sign, digits) = exp.strip_prefix('-').map_or(("+", exp), |d| ("-", d));
        format!("{mantissa}e{sign}{digits:0>2}")
    }
}

/// A value that is valid but looks like a mistake (a unit slip, a joint point in the wrong
/// frame): the field that holds it (`clearance joint 'A'.journal_radius`; empty when it is no
/// single field) and the message, which names the element, the value and the unit clearsim
/// expected. The run goes on.
#[derive(Debug, Clone, PartialEq)]
pub struct Warning {
    pub field: String,
    pub message: String,
}
