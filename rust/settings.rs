//! Run settings as they arrive from Python (a plain dict, through serde like the mechanism
//! description), and their conversion to [`RunSettings`]. The keys are those
//! `clearsim.Mechanism.run_settings` writes; an unknown key is an error, not ignored.

use serde::Deserialize;

use crate::error::{Error, Result};
use crate::integrate::{Method, Settings};
use crate::monitor::MonitorSpec;
use crate::record::Channels;
use crate::simulate::RunSettings;

/// The integrator's name, as the Python API spells it (README "Choosing an integrator").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum IntegratorName {
    /// Dormand–Prince 5(4).
    #[serde(alias = "dopri5")]
    Rk45,
    Dop853,
    Rodas4,
    #[serde(alias = "radau5")]
    Radau,
    /// Classic RK4 with the fixed `step`.
    Rk4,
}

/// One run's settings. Times in s; tolerances as in [`Settings`]; absent optional values take
/// [`Settings::default`]'s.
#[derive(Debug, Clone, Deserialize)]
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

impl RunSettingsDesc {
    /// The settings the core runs with, validated ([`RunSettings::validate`]).
    pub fn into_settings(self) -> Result<RunSettings> {
        let method = match self.integrator {
            IntegratorName::Rk45 => Method::Dopri5,
            IntegratorName::Dop853 => Method::Dop853,
            IntegratorName::Rodas4 => Method::Rodas4,
            IntegratorName::Radau => Method::Radau5,
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

#[cfg(test)]
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
        assert_eq!(rs.method, Method::Radau5);
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
