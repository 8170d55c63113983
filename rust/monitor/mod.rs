//! Running extremes of one output between the output samples, so that a reliability answer
//! does not depend on how densely the user stores results (docs/reliability: "continuous in
//! time"). The integrator hands every accepted step to the run's observers
//! (rust/simulate/observe.rs), which sample the step's dense output at a few interior points and
//! feed each monitor its error there; the monitor keeps, per time bin, the largest and smallest
//! |error| and the time integrals of |error| and error², plus the overall peak and the first time
//! |error| exceeds a limit.
//!
//! What is watched is the monitor's [`Target`] (target.rs: a body coordinate, a point on a body,
//! a clearance joint); its error is the target's displacement, velocity or acceleration minus the
//! same function of its reference's state (reference.rs: the ideal run of the sample's own
//! mechanism or of the nominal design), or the value itself when it has none.
//!
//! With [`MonitorSpec::exact`] the signed extremes are located on the quantity itself, not only
//! at the samples: every step whose samples come near the running maximum (or minimum) is
//! searched by golden section on the exact quantity (the dense output's state; accelerations
//! from a KKT solve there, as the stored outputs are), so the extremes are at least every value
//! the run could store at any output time, whatever the output grid (`Result.extremes`).

pub mod reference;
pub mod target;

use std::sync::Arc;

pub use reference::{ReferenceGrid, ReferenceOf, ReferenceRun, References};
pub use target::{Kinematics, PointComponent, Target};

/// What is monitored: a derivative of a body target (a coordinate or a point), or a quantity of
/// a clearance joint.
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
    /// The couple \[N m\] an ideal joint or driver exerts on its second body ([`Target::Reaction`]:
    /// a driver's torque, a prismatic joint's constraint couple).
    Torque,
}

impl Quantity {
    /// Whether the quantity is read from the whole state (a clearance joint's, or a reaction's)
    /// rather than from a body's coordinates.
    pub fn of_joint(self) -> bool {
        matches!(
            self,
            Quantity::Eccentricity
                | Quantity::Force
                | Quantity::ContactForce
                | Quantity::FilmForce
                | Quantity::FilmThickness
                | Quantity::FrictionTorque
                | Quantity::PowerLoss
                | Quantity::Torque
        )
    }
}

/// What to monitor (`RunSettings::monitors`).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize), serde(try_from = "MonitorSpecDesc"))]
pub struct MonitorSpec {
    /// What is watched: a body coordinate, a point on a body or a clearance joint.
    pub target: Target,
    pub quantity: Quantity,
    /// What the error is measured against (body targets only; `None`: the value itself).
    pub reference: Option<ReferenceOf>,
    /// Start of the analysed window \[s\] and the width \[s\] and number of its bins.
    pub t_start: f64,
    pub bin_width: f64,
    pub bins: usize,
    /// |error| above this is an exceedance (first passage); `None`: not tracked.
    pub limit: Option<f64>,
    /// Dense-output samples per accepted step (the step's end included; ≥ 1).
    pub samples_per_step: usize,
    /// Locate the signed extremes on the exact quantity between the samples (module doc).
    pub exact: bool,
}

/// A monitor as the settings give it: `coordinate` (a body coordinate, 3 per body: x, y, θ; or
/// a clearance joint's index for a joint quantity), `body` with `point` (body frame \[m\])
/// and `component` (x, y or magnitude), or `constraint` (an ideal joint's or driver's index,
/// model order) with quantity `force` and its `component` or quantity `torque`.
#[cfg(feature = "serde")]
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct MonitorSpecDesc {
    #[serde(default)]
    coordinate: Option<usize>,
    #[serde(default)]
    body: Option<usize>,
    #[serde(default)]
    point: Option<[f64; 2]>,
    #[serde(default)]
    component: Option<PointComponent>,
    #[serde(default)]
    constraint: Option<usize>,
    quantity: Quantity,
    #[serde(default)]
    reference: Option<ReferenceOf>,
    t_start: f64,
    bin_width: f64,
    #[serde(default = "one")]
    bins: usize,
    #[serde(default)]
    limit: Option<f64>,
    #[serde(default = "eight")]
    samples_per_step: usize,
    #[serde(default)]
    exact: bool,
}

#[cfg(feature = "serde")]
impl TryFrom<MonitorSpecDesc> for MonitorSpec {
    type Error = String;

    fn try_from(d: MonitorSpecDesc) -> Result<Self, String> {
        if let Some(constraint) = d.constraint {
            if d.coordinate.is_some() || d.body.is_some() || d.point.is_some() {
                return Err("a reaction names its constraint alone (no coordinate, body or point)".into());
            }
            let component = match (d.quantity, d.component) {
                (Quantity::Force, Some(c)) => c,
                (Quantity::Force, None) => return Err("a reaction's force needs its component: x, y or magnitude".into()),
                (Quantity::Torque, None) => PointComponent::Magnitude,
                (Quantity::Torque, Some(_)) => return Err("a reaction's torque has no component".into()),
                (q, _) => return Err(format!("a reaction's quantity is its force or torque, not {q:?}")),
            };
            let target = Target::Reaction { constraint, component };
            return Ok(MonitorSpec { target, ..MonitorSpec::of(d) });
        }
        let target = match (d.coordinate, d.body, d.point) {
            (Some(c), None, None) if d.component.is_none() && d.quantity != Quantity::Torque => {
                if d.quantity.of_joint() {
                    Target::Joint(c)
                } else {
                    Target::Coordinate(c)
                }
            }
            (None, Some(body), Some(at)) => {
                let Some(component) = d.component else { return Err("a point needs its component: x, y or magnitude".into()) };
                if d.quantity.of_joint() {
                    return Err(format!("a point's quantity is its displacement, velocity or acceleration, not {:?}", d.quantity));
                }
                Target::Point { body, at, component }
            }
            _ => return Err("give coordinate, body with point and component, or constraint".into()),
        };
        Ok(MonitorSpec { target, ..MonitorSpec::of(d) })
    }
}

#[cfg(feature = "serde")]
impl MonitorSpec {
    /// The spec of `d`'s window and sampling, its target still to be set.
    fn of(d: MonitorSpecDesc) -> Self {
        MonitorSpec {
            target: Target::Coordinate(0),
            quantity: d.quantity,
            reference: d.reference,
            t_start: d.t_start,
            bin_width: d.bin_width,
            bins: d.bins,
            limit: d.limit,
            samples_per_step: d.samples_per_step,
            exact: d.exact,
        }
    }
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
    /// Checks what serde cannot: a point's position is finite, a joint quantity has no reference,
    /// the window and bins make sense. Errors name `monitors[i].<field>`.
    pub fn validate(&self, i: usize) -> crate::error::Result<()> {
        use crate::error::Error;
        let field = |f: &str| format!("monitors[{i}].{f}");
        if let Target::Point { at, .. } = self.target {
            if !(at[0].is_finite() && at[1].is_finite()) {
                return Err(Error::invalid(field("point"), format!("({}, {})", at[0], at[1]), "must be finite [m, body frame]"));
            }
        }
        if let (Target::Joint(_), Some(of)) = (self.target, self.reference) {
            return Err(Error::invalid(field("reference"), of.name(), "a clearance joint's quantity is measured against no reference"));
        }
        if let (Target::Reaction { .. }, Some(of)) = (self.target, self.reference) {
            return Err(Error::invalid(field("reference"), of.name(), "a reaction is measured against no reference"));
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
/// How near (in bins) to a bin's edge a time's bin is found by division rather than by the
/// product with the inverse width (whose error is a few ulps of the bin number, ≤ 1e-9 below
/// 2^20 bins).
const BIN_EDGE: f64 = 1e-9;
/// Golden-section iterations: the bracket (one sample interval) shrinks to 0.618^40 ≈ 4e-9 of
/// itself, so the extremum's value is found to round-off (the quantity is flat there).
const GOLDEN_ITERATIONS: usize = 40;

/// The running state of a monitor during one run.
#[derive(Debug, Clone)]
pub struct Monitor {
    pub spec: MonitorSpec,
    /// The run its error is measured against (present exactly when the spec names one).
    reference: Option<Arc<ReferenceRun>>,
    pub result: MonitorResult,
    last: Option<(f64, f64)>,
    /// The bin of the last sample.
    last_bin: Option<usize>,
    /// 1 / bin width \[1/s\].
    per_width: f64,
    /// With [`MonitorSpec::exact`]: (t, signed error) of the current step's samples, the
    /// previous step's end first.
    step: Vec<(f64, f64)>,
}

impl Monitor {
    /// The monitor of `spec` (monitor number `i` of the run), with the reference run it names
    /// taken from `references`: a monitor measured against a reference it was not given is an
    /// error, so no monitor is ever measured against nothing by mistake.
    pub fn new(i: usize, spec: MonitorSpec, references: &References) -> crate::error::Result<Self> {
        let reference = match spec.reference {
            None => None,
            Some(of) => match references.get(of) {
                Some(run) => Some(Arc::clone(run)),
                None => {
                    let why = "the run was given no such reference run (runs measured against one go through the batch, rust/batch.rs, which makes it)";
                    return Err(crate::error::Error::invalid(format!("monitors[{i}].reference"), of.name(), why));
                }
            },
        };
        Ok(Self::with_reference(spec, reference))
    }

    /// The monitor of `spec` measured against `reference` (or nothing).
    fn with_reference(spec: MonitorSpec, reference: Option<Arc<ReferenceRun>>) -> Self {
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
        let per_width = 1.0 / spec.bin_width;
        Monitor { spec, reference, result, last: None, last_bin: None, per_width, step: Vec::new() }
    }

    fn bin(&self, t: f64) -> Option<usize> {
        // (t − t_start) × (1 / width) is within 3 ulps of the quotient: away from the bins' edges
        // its whole part is the quotient's (cheaper than the division, which decides at the edges).
        let y = (t - self.spec.t_start) * self.per_width;
        if y >= 0.0 && y < self.spec.bins as f64 && self.spec.bins <= 1 << 20 {
            let k = y as usize;
            let frac = y - k as f64;
            if frac > BIN_EDGE && frac < 1.0 - BIN_EDGE {
                return Some(k);
            }
        }
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

    /// The error of a body target at time `t` with the run's state `sample` (target.rs): against
    /// the reference's state at `t`, or the value itself without a reference.
    #[inline]
    pub fn error<S: Kinematics>(&self, t: f64, sample: &S) -> f64 {
        match &self.reference {
            Some(r) => self.spec.target.error(self.spec.quantity, sample, Some(&r.at(t))),
            None => self.spec.target.error::<S, S>(self.spec.quantity, sample, None),
        }
    }

    /// The error `e` at time `t` (samples come in increasing time).
    pub fn observe(&mut self, t: f64, e: f64) {
        let a = e.abs();
        let now = self.bin(t);
        // The bin of the segment's midpoint: the bin of both its ends when they share one (the
        // bin is monotone in time).
        let mid = match self.last {
            Some((t0, _)) if t0 >= self.spec.t_start => {
                if now.is_some() && self.last_bin == now {
                    now
                } else {
                    self.bin(0.5 * (t0 + t))
                }
            }
            _ => None,
        };
        self.last_bin = now;
        if let Some(k) = now {
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

    /// Whether the monitor's value at a state needs a KKT solve there beyond the accelerations:
    /// a reaction's (from λ).
    pub fn solves(&self) -> bool {
        matches!(self.spec.target, Target::Reaction { .. })
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
            target: Target::Coordinate(0),
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
        let mut m = Monitor::with_reference(spec(Some(0.5)), None);
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
        let mut m = Monitor::with_reference(MonitorSpec { exact: true, bins: 1, bin_width: 1.5, ..spec(None) }, None);
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

    /// The bins found by the product agree with those found by division, edges included.
    #[test]
    fn bins_by_product_are_the_quotients() {
        let m = Monitor::with_reference(MonitorSpec { t_start: 0.013, bin_width: 0.0006, bins: 20, ..spec(None) }, None);
        let exact = |t: f64| {
            let x = (t - 0.013) / 0.0006;
            (x >= 0.0).then(|| (x as usize).min(19)).filter(|_| x <= 20.0 * (1.0 + 1e-12))
        };
        for i in 0..200_000 {
            let t = 0.0129 + i as f64 * 1.3e-7;
            assert_eq!(m.bin(t), exact(t), "t = {t}");
        }
        for k in 0..=20 {
            let edge = 0.013 + k as f64 * 0.0006;
            for t in [edge, f64::from_bits(edge.to_bits() - 1), f64::from_bits(edge.to_bits() + 1)] {
                assert_eq!(m.bin(t), exact(t), "t = {t}");
            }
        }
    }

    /// A monitor that names a reference is built only with it.
    #[test]
    fn a_monitor_without_its_reference_is_refused() {
        let spec = MonitorSpec { reference: Some(ReferenceOf::OwnIdeal), ..spec(None) };
        let err = Monitor::new(3, spec, &References::default()).unwrap_err().to_string();
        assert!(err.starts_with("invalid monitors[3].reference = own_ideal"), "{err}");
    }
}
