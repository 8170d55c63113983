//! Running extremes of one output between the output samples, so that a reliability answer
//! does not depend on how densely the user stores results (docs/reliability: "continuous in
//! time"). The integrator hands every accepted step to [`Monitor::observe`] through
//! `MechanismSystem::step_accepted`; the monitor samples the step's dense output at a few interior
//! points and keeps, per time bin, the largest and smallest |error| and the time integrals of
//! |error| and error², plus the overall peak and the first time |error| exceeds a limit.
//!
//! The error is the monitored coordinate's displacement, velocity or acceleration minus a
//! reference (the ideal mechanism's response, a cubic Hermite curve through its values and rates
//! on a fine grid), or the raw value when there is no reference.

/// What is monitored: a derivative of a body coordinate, or a quantity of a clearance joint
/// (then [`MonitorSpec::coordinate`] is the joint's index).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize), serde(rename_all = "snake_case"))]
pub enum Quantity {
    Displacement,
    Velocity,
    Acceleration,
    /// Eccentricity ratio ε = e / c of a clearance joint.
    Eccentricity,
    /// Magnitude of the joint's total force on the journal \[N\] (dry and film, blended).
    Force,
    /// Dry normal force F_N \[N\] (before the transition blend).
    ContactForce,
    /// Film force magnitude \[N\] (before the transition blend).
    FilmForce,
}

impl Quantity {
    /// Whether the quantity belongs to a clearance joint rather than a body coordinate.
    pub fn of_joint(self) -> bool {
        matches!(self, Quantity::Eccentricity | Quantity::Force | Quantity::ContactForce | Quantity::FilmForce)
    }
}

/// A smooth reference curve: values and their time derivatives at increasing knots, evaluated by
/// cubic Hermite interpolation (held constant outside the knots).
#[derive(Debug, Clone, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize), serde(deny_unknown_fields))]
pub struct Reference {
    pub t: Vec<f64>,
    pub value: Vec<f64>,
    pub rate: Vec<f64>,
}

impl Reference {
    pub fn eval(&self, t: f64) -> f64 {
        let n = self.t.len();
        if n == 0 {
            return 0.0;
        }
        if t <= self.t[0] {
            return self.value[0];
        }
        if t >= self.t[n - 1] {
            return self.value[n - 1];
        }
        let k = self.t.partition_point(|&x| x <= t).clamp(1, n - 1) - 1;
        let h = self.t[k + 1] - self.t[k];
        let s = (t - self.t[k]) / h;
        let (s2, s3) = (s * s, s * s * s);
        (2.0 * s3 - 3.0 * s2 + 1.0) * self.value[k]
            + (s3 - 2.0 * s2 + s) * h * self.rate[k]
            + (-2.0 * s3 + 3.0 * s2) * self.value[k + 1]
            + (s3 - s2) * h * self.rate[k + 1]
    }
}

/// What to monitor (`RunSettings::monitor`).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize), serde(deny_unknown_fields))]
pub struct MonitorSpec {
    /// Index of the coordinate in q (3 per body: x, y, θ), or of the clearance joint for a
    /// joint quantity.
    pub coordinate: usize,
    pub quantity: Quantity,
    #[cfg_attr(feature = "serde", serde(default))]
    pub reference: Option<Reference>,
    /// Start of the analysed window \[s\] and the width \[s\] and number of its bins.
    pub t_start: f64,
    pub bin_width: f64,
    #[cfg_attr(feature = "serde", serde(default = "one"))]
    pub bins: usize,
    /// |error| above this is an exceedance (first passage); `None`: not tracked.
    #[cfg_attr(feature = "serde", serde(default))]
    pub limit: Option<f64>,
    /// Dense-output samples per accepted step (the step's end included; ≥ 1).
    #[cfg_attr(feature = "serde", serde(default = "eight"))]
    pub samples_per_step: usize,
}

#[cfg(feature = "serde")]
fn one() -> usize {
    1
}

#[cfg(feature = "serde")]
fn eight() -> usize {
    8
}

impl MonitorSpec {
    /// Checks what serde cannot: the reference's three columns agree and its knots increase,
    /// the window and bins make sense. Errors name `monitors[i].<field>`.
    pub fn validate(&self, i: usize) -> crate::error::Result<()> {
        use crate::error::Error;
        let field = |f: &str| format!("monitors[{i}].{f}");
        if let Some(r) = &self.reference {
            if r.value.len() != r.t.len() || r.rate.len() != r.t.len() {
                let lens = format!("t: {}, value: {}, rate: {}", r.t.len(), r.value.len(), r.rate.len());
                return Err(Error::invalid(field("reference"), lens, "t, value and rate must have the same length"));
            }
            if r.t.windows(2).any(|w| !(w[1] > w[0])) || r.t.iter().chain(&r.value).chain(&r.rate).any(|v| !v.is_finite()) {
                return Err(Error::invalid(field("reference.t"), "[…]", "must be finite and increase strictly"));
            }
        }
        if !self.t_start.is_finite() {
            return Err(Error::invalid(field("t_start"), self.t_start, "must be finite"));
        }
        if !(self.bin_width.is_finite() && self.bin_width > 0.0) {
            return Err(Error::invalid(field("bin_width"), self.bin_width, "must be finite and > 0"));
        }
        if self.bins == 0 {
            return Err(Error::invalid(field("bins"), 0, "must be ≥ 1"));
        }
        if self.samples_per_step == 0 {
            return Err(Error::invalid(field("samples_per_step"), 0, "must be ≥ 1"));
        }
        if self.limit.is_some_and(f64::is_nan) {
            return Err(Error::invalid(field("limit"), f64::NAN, "must be a number (∞ for none)"));
        }
        Ok(())
    }
}

/// What the monitor found over the analysed window.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MonitorResult {
    /// Largest |error| and its time \[s\].
    pub peak: f64,
    pub t_peak: f64,
    /// First time |error| exceeded the limit \[s\] (NaN: never).
    pub first_passage: f64,
    /// Per bin: largest and smallest |error|, ∫|error| dt, ∫error² dt and the time covered \[s\].
    pub bin_max: Vec<f64>,
    pub bin_min: Vec<f64>,
    pub bin_abs: Vec<f64>,
    pub bin_sq: Vec<f64>,
    pub bin_time: Vec<f64>,
}

/// The running state of a monitor during one run.
#[derive(Debug, Clone)]
pub struct Monitor {
    pub spec: MonitorSpec,
    pub result: MonitorResult,
    last: Option<(f64, f64)>,
}

impl Monitor {
    pub fn new(spec: MonitorSpec) -> Self {
        let b = spec.bins;
        let result = MonitorResult {
            peak: 0.0,
            t_peak: f64::NAN,
            first_passage: f64::NAN,
            bin_max: vec![0.0; b],
            bin_min: vec![f64::INFINITY; b],
            bin_abs: vec![0.0; b],
            bin_sq: vec![0.0; b],
            bin_time: vec![0.0; b],
        };
        Monitor { spec, result, last: None }
    }

    fn bin(&self, t: f64) -> Option<usize> {
        let x = (t - self.spec.t_start) / self.spec.bin_width;
        if x < 0.0 {
            return None;
        }
        let k = x as usize;
        // The window's end belongs to its last bin.
        if k < self.spec.bins {
            Some(k)
        } else if x <= self.spec.bins as f64 * (1.0 + 1e-12) && self.spec.bins > 0 {
            Some(self.spec.bins - 1)
        } else {
            None
        }
    }

    /// The error of a value of the monitored quantity at time `t` (value − reference).
    pub fn error(&self, t: f64, value: f64) -> f64 {
        value - self.spec.reference.as_ref().map_or(0.0, |r| r.eval(t))
    }

    /// The monitored quantity's value `value` at time `t` (samples come in increasing time).
    pub fn observe(&mut self, t: f64, value: f64) {
        let e = self.error(t, value);
        let a = e.abs();
        let mid = self.last.and_then(|(t0, _)| if t0 >= self.spec.t_start { self.bin(0.5 * (t0 + t)) } else { None });
        if let Some(k) = self.bin(t) {
            let r = &mut self.result;
            r.bin_max[k] = r.bin_max[k].max(a);
            r.bin_min[k] = r.bin_min[k].min(a);
            if a > r.peak {
                r.peak = a;
                r.t_peak = t;
            }
            if let Some(limit) = self.spec.limit {
                if a > limit && r.first_passage.is_nan() {
                    // Linear interpolation between the last sample and this one.
                    r.first_passage = match self.last {
                        Some((t0, a0)) if a0 <= limit && t0 >= self.spec.t_start => t0 + (t - t0) * (limit - a0) / (a - a0),
                        _ => t,
                    };
                }
            }
            // Trapezoids, each segment booked to the bin of its midpoint.
            if let (Some((t0, a0)), Some(m)) = (self.last, mid) {
                let dt = t - t0;
                r.bin_abs[m] += 0.5 * (a0 + a) * dt;
                r.bin_sq[m] += 0.5 * (a0 * a0 + a * a) * dt;
                r.bin_time[m] += dt;
            }
        }
        self.last = Some((t, a));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(limit: Option<f64>) -> MonitorSpec {
        MonitorSpec {
            coordinate: 0,
            quantity: Quantity::Displacement,
            reference: None,
            t_start: 0.0,
            bin_width: 0.25,
            bins: 4,
            limit,
            samples_per_step: 8,
        }
    }

    /// e(t) = sin(2πt) sampled finely: peak 1 at t = 0.25, first passage of 0.5 at t = 1/12,
    /// per-bin ∫|e| = 1/(2π) and ∫e² = 1/8.
    #[test]
    fn extremes_and_integrals_of_a_sine() {
        let mut m = Monitor::new(spec(Some(0.5)));
        let n = 20_000;
        for i in 0..=n {
            let t = i as f64 / n as f64;
            m.observe(t, (2.0 * std::f64::consts::PI * t).sin());
        }
        let r = &m.result;
        assert!((r.peak - 1.0).abs() < 1e-6 && (r.t_peak - 0.25).abs() < 1e-4);
        assert!((r.first_passage - 1.0 / 12.0).abs() < 1e-6, "{}", r.first_passage);
        for k in 0..4 {
            assert!((r.bin_abs[k] - 1.0 / (2.0 * std::f64::consts::PI)).abs() < 1e-6);
            assert!((r.bin_sq[k] - 0.125).abs() < 1e-6);
            assert!((r.bin_time[k] - 0.25).abs() < 1e-9);
            assert!((r.bin_max[k] - 1.0).abs() < 1e-6 && r.bin_min[k] < 1e-3);
        }
    }

    /// The Hermite reference reproduces a cubic exactly.
    #[test]
    fn hermite_reference_is_exact_for_a_cubic() {
        let f = |t: f64| 2.0 * t * t * t - t * t + 3.0;
        let df = |t: f64| 6.0 * t * t - 2.0 * t;
        let t: Vec<f64> = vec![0.0, 0.3, 1.0, 1.7];
        let r = Reference { value: t.iter().map(|&x| f(x)).collect(), rate: t.iter().map(|&x| df(x)).collect(), t };
        for x in [0.05, 0.29, 0.31, 0.9, 1.5] {
            assert!((r.eval(x) - f(x)).abs() < 1e-12);
        }
    }
}
