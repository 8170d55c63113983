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
//!
//! With [`MonitorSpec::exact`] the signed extremes are located on the quantity itself, not only
//! at the samples: every step whose samples come near the running maximum (or minimum) is
//! searched by golden section on the exact quantity (the dense output's state; accelerations
//! from a KKT solve there, as the stored outputs are), so the extremes are at least every value
//! the run could store at any output time, whatever the output grid (`Result.extremes`).

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
    /// Film thickness h = c − |e| \[m\] ([`crate::clearance::Readings`]).
    FilmThickness,
    /// Friction torque on the journal \[N m\] ([`crate::clearance::Readings`]).
    FrictionTorque,
    /// Power dissipated in the joint \[W\] ([`crate::clearance::Readings`]).
    PowerLoss,
}

impl Quantity {
    /// Whether the quantity belongs to a clearance joint rather than a body coordinate.
    pub fn of_joint(self) -> bool {
        matches!(
            self,
            Quantity::Eccentricity | Quantity::Force | Quantity::ContactForce | Quantity::FilmForce | Quantity::FilmThickness | Quantity::FrictionTorque | Quantity::PowerLoss
        )
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
    /// Locate the signed extremes on the exact quantity between the samples (module doc).
    #[cfg_attr(feature = "serde", serde(default))]
    pub exact: bool,
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
    /// Largest and smallest signed error and their times \[s\] (−∞/+∞ and NaN before any
    /// sample); located between the samples with [`MonitorSpec::exact`].
    pub max: f64,
    pub t_max: f64,
    pub min: f64,
    pub t_min: f64,
}

/// Fraction of the range (max − min) seen so far within which a step's best sample makes the
/// step worth searching: the interior samples of an acceleration are differences of the dense
/// velocity, close to the KKT value but not equal to it.
const SEARCH_SLACK: f64 = 0.05;
/// Golden-section iterations: the bracket (one sample interval) shrinks to 0.618^40 ≈ 4e-9 of
/// itself, so the extremum's value is found to round-off (the quantity is flat there).
const GOLDEN_ITERATIONS: usize = 40;

/// The running state of a monitor during one run.
#[derive(Debug, Clone)]
pub struct Monitor {
    pub spec: MonitorSpec,
    pub result: MonitorResult,
    last: Option<(f64, f64)>,
    /// With [`MonitorSpec::exact`]: (t, signed error) of the current step's samples, the
    /// previous step's end first.
    step: Vec<(f64, f64)>,
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
            max: f64::NEG_INFINITY,
            t_max: f64::NAN,
            min: f64::INFINITY,
            t_min: f64::NAN,
        };
        Monitor { spec, result, last: None, step: Vec::new() }
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
            if self.spec.exact {
                self.step.push((t, e));
            }
            if e > r.max {
                (r.max, r.t_max) = (e, t);
            }
            if e < r.min {
                (r.min, r.t_min) = (e, t);
            }
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

    /// Where the current step may hold an extremum beyond its samples: for the maximum
    /// (`sign` = 1) or the minimum (−1), the sample interval(s) around the step's best sample
    /// when that sample comes within `SEARCH_SLACK` (5 %) of the range of the running extreme.
    /// A best sample at either end of the step is searched only if the parabola through it and
    /// its two neighbours still rises (for the maximum) towards the step's inside: else the
    /// extreme is that end, exact already.
    pub fn search_bracket(&self, sign: f64) -> Option<(f64, f64)> {
        let s = &self.step;
        let n = s.len();
        if !self.spec.exact || n < 2 {
            return None;
        }
        let r = &self.result;
        let (best, i) = s.iter().enumerate().map(|(i, &(_, e))| (sign * e, i)).fold((f64::NEG_INFINITY, 0), |a, b| if b.0 > a.0 { b } else { a });
        let record = if sign > 0.0 { r.max } else { -r.min };
        if !(best >= record - SEARCH_SLACK * (r.max - r.min)) {
            return None;
        }
        // Slope of the parabola through samples (a, b, c) at b's neighbour `at` ∈ {a, c}.
        let slope_at_end = |a: (f64, f64), b: (f64, f64), c: (f64, f64), at_start: bool| {
            let (d1, d2) = ((b.1 - a.1) / (b.0 - a.0), (c.1 - b.1) / (c.0 - b.0));
            let curv = (d2 - d1) / (c.0 - a.0);
            sign * if at_start { d1 - curv * (b.0 - a.0) } else { d2 + curv * (c.0 - b.0) }
        };
        if i == 0 {
            if n >= 3 && slope_at_end(s[0], s[1], s[2], true) <= 0.0 {
                return None;
            }
            Some((s[0].0, s[1].0))
        } else if i == n - 1 {
            if n >= 3 && slope_at_end(s[n - 3], s[n - 2], s[n - 1], false) >= 0.0 {
                return None;
            }
            Some((s[n - 2].0, s[n - 1].0))
        } else {
            Some((s[i - 1].0, s[i + 1].0))
        }
    }

    /// A value of the error found between the samples (by [`golden_section`]): kept if it
    /// beats the running extreme.
    pub fn record_extreme(&mut self, t: f64, e: f64) {
        let r = &mut self.result;
        if e > r.max {
            (r.max, r.t_max) = (e, t);
        }
        if e < r.min {
            (r.min, r.t_min) = (e, t);
        }
    }

    /// Forget the step's samples but its end (the next step's first sample).
    pub fn end_step(&mut self) {
        if let Some(&last) = self.step.last() {
            self.step.clear();
            self.step.push(last);
        }
    }
}

/// The largest value of `f` on `[a, b]` (assumed to have one peak there) and where, by golden
/// section: the ends are never evaluated (the caller has them), `GOLDEN_ITERATIONS` (40) evaluations.
pub fn golden_section<E>(a: f64, b: f64, mut f: impl FnMut(f64) -> Result<f64, E>) -> Result<(f64, f64), E> {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (a, b);
    let (mut x1, mut x2) = (b - g * (b - a), a + g * (b - a));
    let (mut f1, mut f2) = (f(x1)?, f(x2)?);
    let mut best = if f1 >= f2 { (x1, f1) } else { (x2, f2) };
    for _ in 2..GOLDEN_ITERATIONS {
        if f1 >= f2 {
            (b, x2, f2) = (x2, x1, f1);
            x1 = b - g * (b - a);
            f1 = f(x1)?;
            if f1 > best.1 {
                best = (x1, f1);
            }
        } else {
            (a, x1, f1) = (x1, x2, f2);
            x2 = a + g * (b - a);
            f2 = f(x2)?;
            if f2 > best.1 {
                best = (x2, f2);
            }
        }
    }
    Ok(best)
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
            exact: false,
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

    /// Golden section finds a smooth peak between samples to round-off in its value; an exact
    /// monitor fed a coarse sampling of cos(2πt) finds max 1 at t = 1 and min −1 at t = 1/2.
    #[test]
    fn exact_extremes_between_coarse_samples() {
        let (t, v) = golden_section(0.0, 1.0, |t: f64| Ok::<f64, ()>(1.0 - (t - 0.3).powi(2))).unwrap();
        assert!((t - 0.3).abs() < 1e-7 && (v - 1.0).abs() < 1e-14, "{t} {v}");
        let mut m = Monitor::new(MonitorSpec { exact: true, bins: 1, bin_width: 1.5, ..spec(None) });
        let f = |t: f64| (2.0 * std::f64::consts::PI * t).cos();
        m.observe(0.0, f(0.0));
        m.end_step();
        // Steps of 0.3 s sampled at their ends and midpoints: none at t = 1/2 or 1.
        for step in 0..5 {
            let t0 = 0.3 * step as f64;
            for t in [t0 + 0.15, t0 + 0.3] {
                m.observe(t, f(t));
            }
            for sign in [1.0, -1.0] {
                if let Some((a, b)) = m.search_bracket(sign) {
                    let (t, v) = golden_section(a, b, |t| Ok::<f64, ()>(sign * f(t))).unwrap();
                    m.record_extreme(t, sign * v);
                }
            }
            m.end_step();
        }
        let r = &m.result;
        assert!((r.min + 1.0).abs() < 1e-14 && (r.t_min - 0.5).abs() < 1e-7, "{} at {}", r.min, r.t_min);
        assert!((r.max - 1.0).abs() < 1e-14 && (r.t_max - 1.0).abs() < 1e-7 || r.t_max == 0.0, "{} at {}", r.max, r.t_max);
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
