//! Run settings: what one run is asked ([`RunSettings`]) and every check of them, in one place:
//! [`RunSettings::validate`] (once per run or batch, when the settings arrive) and
//! [`RunSettings::validate_for`] (the monitors against the compiled model, once per run). With
//! the `serde` feature also the settings as they arrive from Python (`RunSettingsDesc`: a plain
//! dict, through serde like the mechanism description, the keys `clearsim.Mechanism.run_settings`
//! writes; an unknown key is an error, not ignored) and their conversion.

use crate::compile::num;
use crate::error::{Error, Result};
use crate::integrate::{Method, Settings};
use crate::model::Model;
use crate::monitor::MonitorSpec;
use crate::record::Channels;

/// What to run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSettings {
    pub method: Method,
    pub ode: Settings,
    pub t0: f64,
    pub t_end: f64,
    /// Output times (sorted, within [t0, t_end]).
    pub t_out: Vec<f64>,
    pub channels: Channels,
    /// Wall-time budget of the run \[s\] (`None`: none); a run over it stops with
    /// [`Error::TimeBudget`] and keeps what it computed.
    pub max_wall_time: Option<f64>,
    /// Outputs tracked between the output samples ([`crate::monitor`]).
    pub monitors: Vec<MonitorSpec>,
    /// A time \[s\] in [t0, t_end] at which the wear books are also read
    /// ([`crate::clearance::wear::WearBook::at_mark`]): what wears after it is the difference.
    pub wear_mark: Option<f64>,
}

impl RunSettings {
    /// Output grid t0, t0 + dt, … up to t_end (inclusive when it lands on the grid).
    pub fn grid(t0: f64, t_end: f64, dt_out: f64) -> Vec<f64> {
        let n = ((t_end - t0) / dt_out * (1.0 + 1e-12)).floor() as usize;
        (0..=n).map(|k| t0 + k as f64 * dt_out).filter(|t| *t <= t_end * (1.0 + 1e-14) + 1e-300).collect()
    }

    /// Every check of the settings on their own (times, tolerances, step limits, output times,
    /// monitor specs): done once, by `RunSettingsDesc::into_settings` for what comes from Python;
    /// a Rust caller that builds [`RunSettings`] itself calls it before [`crate::simulate::simulate`].
    pub fn validate(&self) -> Result<()> {
        let fin = |f: &str, v: f64| if v.is_finite() { Ok(()) } else { Err(Error::invalid(f, num(v), "must be a finite number")) };
        fin("t0", self.t0)?;
        fin("t_end", self.t_end)?;
        if self.t_end <= self.t0 {
            return Err(Error::invalid("t_end", num(self.t_end), format!("must be greater than t0 = {}", num(self.t0))));
        }
        if !(self.ode.rtol > 0.0 && self.ode.rtol < 1.0) {
            return Err(Error::invalid("rtol", num(self.ode.rtol), "must lie in (0, 1)"));
        }
        if !(self.ode.atol > 0.0 && self.ode.atol.is_finite()) {
            return Err(Error::invalid("atol", num(self.ode.atol), "must be positive and finite"));
        }
        if let Some(b) = self.max_wall_time {
            if !(b > 0.0) {
                return Err(Error::invalid("max_seconds", num(b), "must be a positive number of seconds"));
            }
        }
        if let Some(m) = self.wear_mark {
            if !(m >= self.t0 && m <= self.t_end) {
                return Err(Error::invalid("wear_mark", num(m), format!("must lie in [t0, t_end] = [{}, {}]", num(self.t0), num(self.t_end))));
            }
        }
        if self.ode.max_steps == 0 {
            return Err(Error::invalid("max_steps", self.ode.max_steps, "must be a positive integer"));
        }
        // h_min = 0 would let a step halve without end at t = 0 (the floor is max(h_min, 1e-14 |t|)).
        if !(self.ode.h_min > 0.0 && self.ode.h_min.is_finite()) {
            return Err(Error::invalid("h_min", num(self.ode.h_min), "must be positive and finite"));
        }
        if !(self.ode.h_max > 0.0) {
            return Err(Error::invalid("h_max", num(self.ode.h_max), "must be positive"));
        }
        if let Method::Rk4 { step } = self.method {
            if !(step > 0.0 && step.is_finite()) {
                return Err(Error::invalid("step", num(step), "must be positive and finite"));
            }
        }
        for (k, w) in self.t_out.windows(2).enumerate() {
            if !(w[1] > w[0]) {
                return Err(Error::invalid(format!("t_out[{}]", k + 1), num(w[1]), "output times must increase strictly"));
            }
        }
        for (i, m) in self.monitors.iter().enumerate() {
            m.validate(i)?;
        }
        Ok(())
    }

    /// The monitors against the compiled model: each names a body coordinate (below 3 × bodies)
    /// or a clearance joint that exists (their own fields are checked by [`Self::validate`]).
    pub fn validate_for(&self, model: &Model) -> Result<()> {
        for spec in &self.monitors {
            if spec.quantity.of_joint() {
                if spec.coordinate >= model.clearance.len() {
                    let n = model.clearance.len();
                    return Err(Error::invalid("monitor.coordinate", spec.coordinate, format!("must be a clearance joint index below {n}")));
                }
            } else if spec.coordinate >= 3 * model.n_bodies() {
                return Err(Error::invalid("monitor.coordinate", spec.coordinate, format!("must be below 3 × bodies = {}", 3 * model.n_bodies())));
            }
        }
        Ok(())
    }
}

/// The integrator's name, as the Python API spells it (README "Choosing an integrator").
#[cfg(feature = "serde")]
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum IntegratorName {
    /// Dormand–Prince 5(4).
    Rk45,
    Dop853,
    Rodas4,
    Radau,
    /// Classic RK4 with the fixed `step`.
    Rk4,
}

/// One run's settings. Times in s; tolerances as in [`Settings`]; absent optional values take
/// [`Settings::default`]'s.
#[cfg(feature = "serde")]
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunSettingsDesc {
    pub integrator: IntegratorName,
    /// Fixed step of `rk4` \[s\].
    #[serde(default)]
    pub step: Option<f64>,
    #[serde(default)]
    pub rtol: Option<f64>,
    #[serde(default)]
    pub atol: Option<f64>,
    #[serde(default)]
    pub h0: Option<f64>,
    #[serde(default)]
    pub h_max: Option<f64>,
    #[serde(default)]
    pub h_min: Option<f64>,
    #[serde(default)]
    pub max_steps: Option<usize>,
    #[serde(default)]
    pub t0: f64,
    pub t_end: f64,
    /// Output times (increasing, within `[t0, t_end]`).
    #[serde(default)]
    pub t_out: Vec<f64>,
    /// Which outputs to store (`None`: [`Channels::default`]).
    #[serde(default)]
    pub outputs: Option<Channels>,
    /// Wall-time budget of the run \[s\].
    #[serde(default)]
    pub max_seconds: Option<f64>,
    #[serde(default)]
    pub monitors: Vec<MonitorSpec>,
    /// A time \[s\] at which the wear books are also read (the output's `*_at_mark`).
    #[serde(default)]
    pub wear_mark: Option<f64>,
}

#[cfg(feature = "serde")]
impl RunSettingsDesc {
    /// The settings the core runs with, validated ([`RunSettings::validate`]).
    pub fn into_settings(self) -> Result<RunSettings> {
        let method = match self.integrator {
            IntegratorName::Rk45 => Method::Rk45,
            IntegratorName::Dop853 => Method::Dop853,
            IntegratorName::Rodas4 => Method::Rodas4,
            IntegratorName::Radau => Method::Radau,
            IntegratorName::Rk4 => Method::Rk4 { step: self.step.ok_or_else(|| Error::invalid("step", "None", "the rk4 integrator needs a fixed step [s]"))? },
        };
        let base = Settings::default();
        let ode = Settings {
            rtol: self.rtol.unwrap_or(base.rtol),
            atol: self.atol.unwrap_or(base.atol),
            h0: self.h0,
            h_max: self.h_max.unwrap_or(base.h_max),
            h_min: self.h_min.unwrap_or(base.h_min),
            max_steps: self.max_steps.unwrap_or(base.max_steps),
        };
        let rs = RunSettings {
            method,
            ode,
            t0: self.t0,
            t_end: self.t_end,
            t_out: self.t_out,
            channels: self.outputs.unwrap_or_default(),
            max_wall_time: self.max_seconds,
            monitors: self.monitors,
            wear_mark: self.wear_mark,
        };
        rs.validate()?;
        Ok(rs)
    }
}

#[cfg(all(test, feature = "serde"))]
mod tests {
    use super::*;
    use crate::monitor::Quantity;

    fn read(v: serde_json::Value) -> Result<RunSettings> {
        let desc: RunSettingsDesc = serde_json::from_value(v).map_err(|e| Error::invalid("settings", "…", e.to_string()))?;
        desc.into_settings()
    }

    #[test]
    fn defaults_and_names() {
        let rs = read(serde_json::json!({"integrator": "radau", "t_end": 0.1})).unwrap();
        assert_eq!(rs.method, Method::Radau);
        assert_eq!(rs.ode, Settings::default());
        assert_eq!(rs.channels, Channels::default());
        let rs = read(serde_json::json!({"integrator": "rk4", "step": 1e-4, "t_end": 0.1, "outputs": {"energy": true},
            "monitors": [{"coordinate": 3, "quantity": "contact_force", "t_start": 0.0, "bin_width": 0.01}]}))
        .unwrap();
        assert_eq!(rs.method, Method::Rk4 { step: 1e-4 });
        assert!(rs.channels.energy && rs.channels.states, "unnamed outputs keep their defaults");
        assert_eq!(rs.monitors[0].quantity, Quantity::ContactForce);
        assert_eq!((rs.monitors[0].bins, rs.monitors[0].samples_per_step), (1, 8));
    }

    #[test]
    fn bad_settings_are_named() {
        let err = |v| read(v).unwrap_err().to_string();
        assert!(err(serde_json::json!({"integrator": "euler", "t_end": 0.1})).contains("unknown variant `euler`"));
        assert!(err(serde_json::json!({"integrator": "rk4", "t_end": 0.1})).contains("needs a fixed step"));
        assert!(err(serde_json::json!({"integrator": "rk45", "t_end": 0.1, "rtoll": 1e-3})).contains("unknown field `rtoll`"));
        let e = err(serde_json::json!({"integrator": "rk45", "t_end": 0.1, "monitors": [{"coordinate": 0, "quantity": "displacement",
            "t_start": 0.0, "bin_width": 0.01, "reference": {"t": [0.0, 1.0], "value": [0.0], "rate": [0.0, 0.0]}}]}));
        assert!(e.contains("monitors[0].reference") && e.contains("same length"), "{e}");
    }
}
