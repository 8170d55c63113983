//! Run settings: what one run is asked ([`RunSettings`]) and every check of them, in one place:
//! [`RunSettings::validate`] (once per run or batch, when the settings arrive) and
//! [`RunSettings::validate_for`] (the monitors against the compiled model, once per run); the
//! policies that complete them: the output grid from a spacing ([`RunSettings::grid`]) and the
//! integrator `auto` picks for a model ([`default_method`]). With
//! the `serde` feature also the settings as they arrive from Python (`RunSettingsDesc`: a plain
//! dict, through serde like the mechanism description, the keys `clearsim.Mechanism.run_settings`
//! writes; an unknown key is an error, not ignored) and their conversion.

use crate::compile::num;
use crate::error::{Error, Result};
use crate::integrate::{Method, Settings};
use crate::model::Model;
use crate::monitor::{MonitorSpec, ReferenceGrid, Target};
use crate::record::Channels;

/// What to run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSettings {
    /// The integrator; `None` is `integrator = "auto"`, resolved per model by [`default_method`]
    /// when the run starts (so one batch of dry and lubricated mechanisms picks per mechanism).
    pub method: Option<Method>,
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
    /// The grid of the reference runs the monitors are measured against (needed when one is:
    /// [`crate::monitor::reference`]; the batch makes the runs, rust/batch.rs).
    pub reference: Option<ReferenceGrid>,
    /// A time \[s\] in [t0, t_end] at which the wear books are also read
    /// ([`crate::clearance::wear::WearBook::at_mark`]): what wears after it is the difference.
    pub wear_mark: Option<f64>,
    /// Track the bearing summary of every lubricated joint along the steps (minimum film,
    /// peak and mean power loss: [`crate::simulate::BearingSummary`]); off unless asked, as
    /// it costs a force evaluation per joint and step where the method has none to reuse.
    pub bearings: bool,
    /// The start \[s\] of the bearing summary's window, in [t0, t_end) (`None`: t0; the
    /// window ends at t_end): its books start at the state there, from the dense output of the
    /// step that holds it (`simulate(extremes_from=)`, the window of the extremes too).
    pub bearings_from: Option<f64>,
    /// Stroboscopic samples at exact times ([`SectionSpec`]; `None`: none recorded).
    pub sections: Option<SectionSpec>,
    /// A shadow trajectory for the largest Lyapunov exponent ([`LyapunovSpec`]; `None`: none).
    pub lyapunov: Option<LyapunovSpec>,
}

/// Poincaré (stroboscopic) sections: the run's channels recorded at the exact times
/// t_k = (k + phase/2π) · period (k integer, t_k in [t0, t_end]) from the dense output of the
/// step that holds them, whatever the output grid (`rust/simulate/sections.rs`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize), serde(deny_unknown_fields))]
pub struct SectionSpec {
    /// \[s\], > 0.
    pub period: f64,
    /// \[rad\] of the period, counted from t = 0.
    #[cfg_attr(feature = "serde", serde(default))]
    pub phase: f64,
}

impl SectionSpec {
    /// The section times in [t0, t_end] \[s\], as k runs: (k + phase/2π) · period; one that
    /// misses an end of the run by rounding alone (1e-12 of the times) is put on it.
    pub fn times(&self, t0: f64, t_end: f64) -> impl Iterator<Item = f64> {
        let (p, shift) = (self.period, self.phase / std::f64::consts::TAU);
        let tol = 1e-12 * t0.abs().max(t_end.abs()).max(p);
        let first = (((t0 - tol) / p - shift).ceil() - 1.0) as i64;
        (first..)
            .map(move |k| (k as f64 + shift) * p)
            .skip_while(move |t| *t < t0 - tol)
            .take_while(move |t| *t <= t_end + tol)
            .map(move |t| t.clamp(t0, t_end))
    }
}

/// The largest Lyapunov exponent by two nearby trajectories (Benettin et al. 1980): from
/// `start` a shadow run starts `d0` away from the run in a weighted norm and is brought back to
/// that distance every `interval`, the logarithm of its growth booked each time
/// (`rust/simulate/lyapunov.rs`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize), serde(deny_unknown_fields))]
pub struct LyapunovSpec {
    /// When the shadow starts \[s\] (after the transient), in [t0, t_end).
    pub start: f64,
    /// Renormalisation interval τ \[s\], > 0.
    pub interval: f64,
    /// Distance kept between the two runs, in the norm √(Σ δq² + Σ (δq̇/Ω)²) \[m, rad\], > 0.
    pub d0: f64,
    /// Ω \[rad/s\] of that norm, > 0.
    pub velocity_scale: f64,
}

/// Most output times a spacing `dt_out` may ask for (each holds every stored channel).
pub const MAX_OUTPUTS: f64 = 1e7;

/// The integrator `integrator = "auto"` picks for a model: `radau` when a clearance joint is
/// lubricated (the film makes the problem stiff: README, "Choosing an integrator"), else `rk45`.
pub fn default_method(model: &Model) -> Method {
    if model.clearance.iter().any(|c| c.film.is_some()) {
        Method::Radau
    } else {
        Method::Rk45
    }
}

/// t0 and t_end finite, t_end after t0: checked before anything is built from them.
fn check_times(t0: f64, t_end: f64) -> Result<()> {
    let fin = |f: &str, v: f64| if v.is_finite() { Ok(()) } else { Err(Error::invalid(f, num(v), "must be a finite number")) };
    fin("t0", t0)?;
    fin("t_end", t_end)?;
    if t_end <= t0 {
        return Err(Error::invalid("t_end", num(t_end), format!("must be greater than t0 = {}", num(t0))));
    }
    Ok(())
}

/// `v` as Python's `format(v, ".3g")` writes it (three significant digits), for messages.
fn g3(v: f64) -> String {
    if !v.is_finite() || v == 0.0 {
        return num(v);
    }
    let exp = v.abs().log10().floor() as i32;
    if (-4..3).contains(&exp) {
        let s = format!("{:.*}", (2 - exp).max(0) as usize, v);
        return if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s };
    }
    let s = format!("{v:.2e}");
    let (mantissa, e) = s.split_once('e').unwrap_or((&s, "0"));
    let mantissa = if mantissa.contains('.') { mantissa.trim_end_matches('0').trim_end_matches('.') } else { mantissa };
    let (sign, digits) = e.strip_prefix('-').map_or(("+", e), |d| ("-", d));
    format!("{mantissa}e{sign}{digits:0>2}")
}

impl RunSettings {
    /// A run of `method` (`None`: `auto`) with `ode` over [t0, t_end] \[s\], the default channels
    /// stored at `t_out`, and nothing more read: no budget, monitors, references, wear mark,
    /// bearing summary, sections or shadow. The one list of those fields' "off"; a run that asks
    /// for more says so and takes the rest from here (`..RunSettings::plain(…)`).
    pub fn plain(method: Option<Method>, ode: Settings, t0: f64, t_end: f64, t_out: Vec<f64>) -> Self {
        RunSettings {
            method,
            ode,
            t0,
            t_end,
            t_out,
            channels: Channels::default(),
            max_wall_time: None,
            monitors: Vec::new(),
            reference: None,
            wear_mark: None,
            bearings: false,
            bearings_from: None,
            sections: None,
            lyapunov: None,
        }
    }

    /// The integrator this run uses on `model`: the one named, or [`default_method`]'s.
    pub fn method_for(&self, model: &Model) -> Method {
        self.method.unwrap_or_else(|| default_method(model))
    }

    /// Output grid t0, t0 + dt_out, … up to t_end \[s\]: `t0 + k dt_out` for k = 0 … n, n =
    /// ⌊(t_end − t0)/dt_out · (1 + 1e-12)⌋ (t_end inclusive when it lands on the grid within
    /// rounding: a last point past t_end by rounding is put on t_end). `dt_out` must be
    /// positive and finite and give at most [`MAX_OUTPUTS`] outputs; t0 and t_end as in
    /// [`Self::validate`]. The one implementation: `clearsim.Mechanism.run_settings` sends
    /// `dt_out` and the grid is built here.
    pub fn grid(t0: f64, t_end: f64, dt_out: f64) -> Result<Vec<f64>> {
        check_times(t0, t_end)?;
        if !dt_out.is_finite() {
            return Err(Error::invalid("dt_out", num(dt_out), "must be a finite number"));
        }
        if dt_out <= 0.0 {
            return Err(Error::invalid("dt_out", num(dt_out), "must be positive"));
        }
        let count = (t_end - t0) / dt_out;
        if !(count <= MAX_OUTPUTS) {
            let why = format!("gives {} outputs over [{}, {}] s, more than {}; choose a coarser grid", g3(count), num(t0), num(t_end), g3(MAX_OUTPUTS));
            return Err(Error::invalid("dt_out", num(dt_out), why));
        }
        let n = (count * (1.0 + 1e-12)).floor() as usize;
        // The last point lies on t_end within rounding (0.1 × 3 = 0.30000000000000004 > 0.3):
        // it is t_end itself, so a run records its end (it used to drop it).
        Ok((0..=n).map(|k| if k == n { (t0 + k as f64 * dt_out).min(t_end) } else { t0 + k as f64 * dt_out }).collect())
    }

    /// Every check of the settings on their own (times, tolerances, step limits, output times,
    /// monitor specs): done once, by `RunSettingsDesc::into_settings` for what comes from Python;
    /// a Rust caller that builds [`RunSettings`] itself calls it before [`crate::simulate::simulate`].
    pub fn validate(&self) -> Result<()> {
        check_times(self.t0, self.t_end)?;
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
        if let Some(w) = self.bearings_from {
            if !(w >= self.t0 && w < self.t_end) {
                return Err(Error::invalid("bearings_from", num(w), format!("must lie in [t0, t_end) = [{}, {}) s", num(self.t0), num(self.t_end))));
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
        if let Some(Method::Rk4 { step }) = self.method {
            if !(step > 0.0 && step.is_finite()) {
                return Err(Error::invalid("step", num(step), "must be positive and finite"));
            }
        }
        for (k, w) in self.t_out.windows(2).enumerate() {
            if !(w[1] > w[0]) {
                return Err(Error::invalid(format!("t_out[{}]", k + 1), num(w[1]), "output times must increase strictly"));
            }
        }
        // Every output time inside the run (a time outside it was dropped without a word).
        if let (Some(&first), Some(&last)) = (self.t_out.first(), self.t_out.last()) {
            let window = format!("outside the run, which covers [t0, t_end] = [{}, {}] s", num(self.t0), num(self.t_end));
            if first < self.t0 {
                return Err(Error::invalid("t_out[0]", num(first), window));
            }
            if last > self.t_end {
                return Err(Error::invalid(format!("t_out[{}]", self.t_out.len() - 1), num(last), window));
            }
        }
        for (i, m) in self.monitors.iter().enumerate() {
            m.validate(i)?;
            if let (Some(of), None) = (m.reference, self.reference) {
                let why = "a monitor measured against a reference needs the settings' reference grid (reference = {t_start, t_end, intervals})";
                return Err(Error::invalid(format!("monitors[{i}].reference"), of.name(), why));
            }
        }
        if let Some(grid) = &self.reference {
            grid.validate()?;
            if grid.t_start < self.t0 {
                return Err(Error::invalid("reference.t_start", num(grid.t_start), format!("must not lie before the run's t0 = {}", num(self.t0))));
            }
        }
        if let Some(sec) = &self.sections {
            if !(sec.period > 0.0 && sec.period.is_finite()) {
                return Err(Error::invalid("sections.period", num(sec.period), "must be a positive, finite time [s]"));
            }
            if !sec.phase.is_finite() {
                return Err(Error::invalid("sections.phase", num(sec.phase), "must be a finite angle [rad]"));
            }
            let count = (self.t_end - self.t0) / sec.period;
            if !(count <= MAX_OUTPUTS) {
                return Err(Error::invalid("sections.period", num(sec.period), format!("gives {} sections, more than {}", g3(count), g3(MAX_OUTPUTS))));
            }
        }
        if let Some(ly) = &self.lyapunov {
            if !(ly.start >= self.t0 && ly.start < self.t_end) {
                return Err(Error::invalid("lyapunov.start", num(ly.start), format!("must lie in [t0, t_end) = [{}, {})", num(self.t0), num(self.t_end))));
            }
            for (field, v) in [("lyapunov.interval", ly.interval), ("lyapunov.d0", ly.d0), ("lyapunov.velocity_scale", ly.velocity_scale)] {
                if !(v > 0.0 && v.is_finite()) {
                    return Err(Error::invalid(field, num(v), "must be positive and finite"));
                }
            }
            if let Some(Method::Rk4 { .. }) = self.method {
                return Err(Error::invalid("integrator", "rk4", "a Lyapunov exponent needs an adaptive integrator (its runs restart every interval)"));
            }
        }
        Ok(())
    }

    /// The monitors against the compiled model: each names a body coordinate (below 3 × bodies),
    /// a body (for a point) or a clearance joint that exists (their own fields are checked by
    /// [`Self::validate`]).
    pub fn validate_for(&self, model: &Model) -> Result<()> {
        if self.lyapunov.is_some() {
            if let Some(c) = model.clearance.iter().find(|c| c.wear.is_some()) {
                let why = "a Lyapunov exponent follows the state of the run: this joint's wear changes its geometry outside it";
                return Err(Error::invalid(format!("clearance joint '{}'", c.name), "wear model", why));
            }
        }
        let nb = model.n_bodies();
        for (i, spec) in self.monitors.iter().enumerate() {
            match spec.target {
                Target::Joint(j) if j >= model.clearance.len() => {
                    let n = model.clearance.len();
                    return Err(Error::invalid(format!("monitors[{i}].coordinate"), j, format!("must be a clearance joint index below {n}")));
                }
                Target::Coordinate(c) if c >= 3 * nb => {
                    return Err(Error::invalid(format!("monitors[{i}].coordinate"), c, format!("must be below 3 × bodies = {}", 3 * nb)));
                }
                Target::Point { body, .. } if body >= nb => {
                    return Err(Error::invalid(format!("monitors[{i}].body"), body, format!("must be a body index below {nb}")));
                }
                Target::Reaction { constraint, .. } if constraint >= model.constraints.len() => {
                    let n = model.constraints.len();
                    return Err(Error::invalid(format!("monitors[{i}].constraint"), constraint, format!("must be an ideal joint or driver index below {n}")));
                }
                _ => {}
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
    /// The model's choice, [`default_method`] (resolved when the run starts).
    Auto,
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
    /// Output times \[s\] (increasing, within `[t0, t_end]`); absent: the grid of `dt_out`.
    #[serde(default)]
    pub t_out: Option<Vec<f64>>,
    /// Output spacing \[s\] ([`RunSettings::grid`]; default (t_end − t0)/1000), when `t_out`
    /// is absent.
    #[serde(default)]
    pub dt_out: Option<f64>,
    /// Which outputs to store (`None`: [`Channels::default`]).
    #[serde(default)]
    pub outputs: Option<Channels>,
    /// Wall-time budget of the run \[s\].
    #[serde(default)]
    pub max_seconds: Option<f64>,
    #[serde(default)]
    pub monitors: Vec<MonitorSpec>,
    /// The reference runs' grid ([`RunSettings::reference`]).
    #[serde(default)]
    pub reference: Option<ReferenceGrid>,
    /// A time \[s\] at which the wear books are also read (the output's `*_at_mark`).
    #[serde(default)]
    pub wear_mark: Option<f64>,
    /// [`RunSettings::bearings`].
    #[serde(default)]
    pub bearings: bool,
    /// [`RunSettings::bearings_from`] \[s\].
    #[serde(default)]
    pub bearings_from: Option<f64>,
    #[serde(default)]
    pub sections: Option<SectionSpec>,
    #[serde(default)]
    pub lyapunov: Option<LyapunovSpec>,
}

#[cfg(feature = "serde")]
impl RunSettingsDesc {
    /// The settings the core runs with, validated ([`RunSettings::validate`]).
    pub fn into_settings(self) -> Result<RunSettings> {
        let method = match self.integrator {
            IntegratorName::Auto => None,
            IntegratorName::Rk45 => Some(Method::Rk45),
            IntegratorName::Dop853 => Some(Method::Dop853),
            IntegratorName::Rodas4 => Some(Method::Rodas4),
            IntegratorName::Radau => Some(Method::Radau),
            IntegratorName::Rk4 => Some(Method::Rk4 { step: self.step.ok_or_else(|| Error::invalid("step", "None", "the rk4 integrator needs a fixed step [s]"))? }),
        };
        let t_out = match (self.t_out, self.dt_out) {
            (Some(_), Some(dt)) => return Err(Error::invalid("dt_out", num(dt), "give dt_out or t_out, not both")),
            (Some(t_out), None) => t_out,
            (None, dt) => RunSettings::grid(self.t0, self.t_end, dt.unwrap_or((self.t_end - self.t0) / 1000.0))?,
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
            t_out,
            channels: self.outputs.unwrap_or_default(),
            max_wall_time: self.max_seconds,
            monitors: self.monitors,
            reference: self.reference,
            wear_mark: self.wear_mark,
            bearings: self.bearings,
            bearings_from: self.bearings_from,
            sections: self.sections,
            lyapunov: self.lyapunov,
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
        assert_eq!(rs.method, Some(Method::Radau));
        assert_eq!(rs.ode, Settings::default());
        assert_eq!(rs.channels, Channels::default());
        let rs = read(serde_json::json!({"integrator": "rk4", "step": 1e-4, "t_end": 0.1, "outputs": {"energy": true},
            "monitors": [{"coordinate": 3, "quantity": "contact_force", "t_start": 0.0, "bin_width": 0.01}]}))
        .unwrap();
        assert_eq!(rs.method, Some(Method::Rk4 { step: 1e-4 }));
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
            "t_start": 0.0, "bin_width": 0.01, "reference": "own_ideal"}]}));
        assert!(e.contains("monitors[0].reference = own_ideal") && e.contains("reference grid"), "{e}");
        let e = err(serde_json::json!({"integrator": "rk45", "t_end": 0.1, "monitors": [{"body": 0, "point": [0.1, 0.0], "quantity": "displacement",
            "t_start": 0.0, "bin_width": 0.01}]}));
        assert!(e.contains("component"), "{e}");
    }

    /// The grid Python built before the core did (clearsim 0.x `Mechanism.run_settings`):
    /// `t0 + dt_out * numpy.arange(n + 1)`, n = floor((t_end − t0)/dt_out · (1 + 1e-12)), of which
    /// a run recorded the times t ≤ t_end (`simulate`'s filter).
    fn python_grid(t0: f64, t_end: f64, dt: f64) -> Vec<f64> {
        let count = (t_end - t0) / dt;
        let n = (count * (1.0 + 1e-12)).floor() as i64;
        // ... with the last point past t_end by rounding put on t_end (the old one dropped it).
        (0..=n).map(|k| if k == n { (t0 + dt * (k as f64)).min(t_end) } else { t0 + dt * (k as f64) }).collect()
    }

    #[test]
    fn grid_is_the_old_python_grid_bit_for_bit() {
        // Deterministic triples: round and awkward spacings, negative and large start times,
        // spacings that land on t_end within rounding (0.1 × 3 > 0.3) and ones that do not.
        let mut state = 0x9e3779b97f4a7c15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut triples = vec![(0.0, 0.3, 0.1), (0.0, 1.0, 0.001), (-2.0, -1.0, 0.1), (-1.0, 1e-3, 1e-4), (0.1, 0.7, 0.2), (1e3, 1e3 + 1.0, 1e-3), (0.0, 0.05, 0.05 / 1000.0)];
        for _ in 0..3000 {
            let t0 = [0.0, -10.0 * next(), 100.0 * next(), 1e-3 * next()][(next() * 4.0) as usize];
            let span = 10f64.powf(-4.0 + 6.0 * next());
            let count = [10.0, 7.0, 1000.0, 3.0 + 5000.0 * next(), 1.0 + 37.0 * next()][(next() * 5.0) as usize];
            let dt = if next() < 0.5 { span / count } else { (span / count * 1e4).round().max(1.0) / 1e4 };
            triples.push((t0, t0 + span, dt));
        }
        for (t0, t_end, dt) in triples {
            let ours = RunSettings::grid(t0, t_end, dt).unwrap();
            let old = python_grid(t0, t_end, dt);
            assert_eq!(ours.len(), old.len(), "({t0}, {t_end}, {dt})");
            assert!(ours.iter().zip(&old).all(|(a, b)| a.to_bits() == b.to_bits()), "({t0}, {t_end}, {dt})");
        }
    }

    #[test]
    fn section_times_are_exact_multiples_inside_the_run() {
        let sec = SectionSpec { period: 0.1, phase: std::f64::consts::PI };
        let t: Vec<f64> = sec.times(0.02, 0.4).collect();
        assert_eq!(t, vec![0.05, 1.5 * 0.1, 2.5 * 0.1, 3.5 * 0.1]);
        let sec = SectionSpec { period: 0.1, phase: 0.0 };
        assert_eq!(sec.times(0.0, 0.3).collect::<Vec<_>>(), vec![0.0, 0.1, 0.2, 0.3], "the last one lands on t_end by rounding");
        assert_eq!(sec.times(-0.25, -0.05).collect::<Vec<_>>(), vec![-0.2, -0.1]);
        let e = read(serde_json::json!({"integrator": "rk45", "t_end": 1.0, "sections": {"period": 0.0}})).unwrap_err().to_string();
        assert_eq!(e, "invalid sections.period = 0.0: must be a positive, finite time [s]");
        let e = read(serde_json::json!({"integrator": "rk45", "t_end": 1.0, "lyapunov": {"start": 1.0, "interval": 0.1, "d0": 1e-8, "velocity_scale": 1.0}})).unwrap_err().to_string();
        assert_eq!(e, "invalid lyapunov.start = 1.0: must lie in [t0, t_end) = [0.0, 1.0)");
    }

    #[test]
    fn a_grid_ends_on_t_end_when_it_lands_there_within_rounding() {
        assert_eq!(RunSettings::grid(0.0, 0.3, 0.1).unwrap(), vec![0.0, 0.1, 0.2, 0.3]);
        assert_eq!(RunSettings::grid(0.0, 0.35, 0.1).unwrap(), vec![0.0, 0.1, 0.2, 0.30000000000000004]);
    }

    #[test]
    fn bad_spacings_are_named() {
        let msg = |dt: f64| RunSettings::grid(0.0, 1.0, dt).unwrap_err().to_string();
        assert_eq!(msg(0.0), "invalid dt_out = 0.0: must be positive");
        assert_eq!(msg(-0.1), "invalid dt_out = -0.1: must be positive");
        assert_eq!(msg(f64::NAN), "invalid dt_out = nan: must be a finite number");
        assert_eq!(msg(1e-8), "invalid dt_out = 1e-08: gives 1e+08 outputs over [0.0, 1.0] s, more than 1e+07; choose a coarser grid");
        assert_eq!(msg(3e-8), "invalid dt_out = 3e-08: gives 3.33e+07 outputs over [0.0, 1.0] s, more than 1e+07; choose a coarser grid");
        assert_eq!(msg(5e-324), "invalid dt_out = 5e-324: gives inf outputs over [0.0, 1.0] s, more than 1e+07; choose a coarser grid");
        let read_err = |v| read(v).unwrap_err().to_string();
        assert!(read_err(serde_json::json!({"integrator": "auto", "t_end": 0.1, "dt_out": 0.01, "t_out": [0.0]})).contains("not both"));
        assert_eq!(
            read_err(serde_json::json!({"integrator": "auto", "t_end": 0.1, "t_out": [0.0, 0.2]})),
            "invalid t_out[1] = 0.2: outside the run, which covers [t0, t_end] = [0.0, 0.1] s"
        );
        assert!(read_err(serde_json::json!({"integrator": "auto", "t0": 0.05, "t_end": 0.1, "t_out": [0.0, 0.1]})).starts_with("invalid t_out[0] = 0.0: outside"));
        assert!(read_err(serde_json::json!({"integrator": "auto", "t_end": 0.1, "dt_out": -1.0})).starts_with("invalid dt_out = -1.0"));
        // No spacing and no times: (t_end − t0)/1000.
        let rs = read(serde_json::json!({"integrator": "auto", "t0": 0.5, "t_end": 1.5})).unwrap();
        assert_eq!((rs.method, rs.t_out.len(), rs.t_out[1]), (None, 1001, 0.5 + 1e-3));
    }
}
