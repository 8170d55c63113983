//! What a monitor is measured against: a reference run ([`ReferenceRun`]), the ideal motion of
//! the sample's own mechanism (its ideal twin, [`ReferenceOf::OwnIdeal`]: what do the clearances
//! add?) or of the nominal design ([`ReferenceOf::Nominal`]: how far from the nominal motion?),
//! recorded on a fine grid ([`ReferenceGrid`]) and read at any time by cubic Hermite
//! interpolation of its states: q with q̇ as rates, q̇ with q̈, q̈ with its numerical
//! derivative (numpy's `gradient`: second-order central differences, one-sided at the ends).
//! A monitor evaluates its target on this state as on the sample's (rust/monitor/target.rs).
//!
//! The runs are made, deduplicated and shared by the batch (rust/batch.rs); a monitor that names a
//! reference is built only with it ([`super::Monitor::new`]).

use std::sync::Arc;

use super::target::Kinematics;
use crate::error::{Error, Result};

/// Which mechanism's ideal motion a monitor is measured against.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize), serde(rename_all = "snake_case"))]
pub enum ReferenceOf {
    /// The sample's own mechanism with every clearance joint made ideal.
    OwnIdeal,
    /// The nominal design's mechanism, made ideal (one for the whole batch).
    Nominal,
}

impl ReferenceOf {
    pub fn name(self) -> &'static str {
        match self {
            ReferenceOf::OwnIdeal => "own_ideal",
            ReferenceOf::Nominal => "nominal",
        }
    }

    /// The mechanism run, as failures name it.
    pub fn what(self) -> &'static str {
        match self {
            ReferenceOf::OwnIdeal => "ideal mechanism",
            ReferenceOf::Nominal => "nominal ideal mechanism",
        }
    }
}

/// The grid a reference run records on: `intervals` equal intervals over [t_start, t_end] \[s\]
/// (numpy's `linspace(t_start, t_end, intervals + 1)`, point for point), and whether the run's
/// output also gives the reference at its output times (`record`, for error traces).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize), serde(deny_unknown_fields))]
pub struct ReferenceGrid {
    pub t_start: f64,
    pub t_end: f64,
    pub intervals: usize,
    #[cfg_attr(feature = "serde", serde(default))]
    pub record: bool,
}

impl ReferenceGrid {
    /// The grid's times: t_start + k · ((t_end − t_start) / intervals), the last one t_end.
    pub fn times(&self) -> Vec<f64> {
        let step = (self.t_end - self.t_start) / self.intervals as f64;
        let mut t: Vec<f64> = (0..=self.intervals).map(|k| k as f64 * step + self.t_start).collect();
        if let Some(last) = t.last_mut() {
            *last = self.t_end;
        }
        t
    }

    /// Finite times, t_end after t_start, at least one and at most `MAX_OUTPUTS` intervals.
    pub fn validate(&self) -> Result<()> {
        let field = |f: &str| format!("reference.{f}");
        for (f, v) in [("t_start", self.t_start), ("t_end", self.t_end)] {
            if !v.is_finite() {
                return Err(Error::invalid(field(f), v, "must be a finite number"));
            }
        }
        if !(self.t_end > self.t_start) {
            return Err(Error::invalid(field("t_end"), self.t_end, format!("must be greater than reference.t_start = {}", self.t_start)));
        }
        if self.intervals == 0 || self.intervals as f64 > crate::settings::MAX_OUTPUTS {
            return Err(Error::invalid(field("intervals"), self.intervals, format!("must lie in [1, {}]", crate::settings::MAX_OUTPUTS)));
        }
        Ok(())
    }
}

/// A reference run: the ideal mechanism's states on a grid, read at any time by cubic Hermite
/// interpolation (held at the ends outside the grid).
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceRun {
    pub of: ReferenceOf,
    /// Its bodies, in the model's order (a sample measured against it must have the same).
    pub bodies: Vec<String>,
    /// Coordinates a time (3 per body).
    pub n: usize,
    pub t: Vec<f64>,
    /// q, q̇, q̈ and dq̈/dt, time-major (`[k * n + c]`).
    pub q: Vec<f64>,
    pub qd: Vec<f64>,
    pub qdd: Vec<f64>,
    pub jerk: Vec<f64>,
    /// Intervals per second of the grid's mean spacing (to find an interval without a search).
    per_second: f64,
}

impl ReferenceRun {
    /// From a run's recording: times `t` (increasing), `n` coordinates a time.
    pub fn new(of: ReferenceOf, bodies: Vec<String>, t: Vec<f64>, q: Vec<f64>, qd: Vec<f64>, qdd: Vec<f64>) -> Self {
        let n = bodies.len() * 3;
        let jerk = gradient(&t, &qdd, n);
        let per_second = match (t.first(), t.last()) {
            (Some(&a), Some(&b)) if b > a => (t.len() - 1) as f64 / (b - a),
            _ => 0.0,
        };
        ReferenceRun { of, bodies, n, t, q, qd, qdd, jerk, per_second }
    }

    /// The reference at time `t` \[s\].
    #[inline]
    pub fn at(&self, t: f64) -> ReferenceAt<'_> {
        let n = self.t.len();
        if n == 0 || t <= self.t[0] {
            return ReferenceAt { run: self, k: 0, held: true, h: 0.0, s: 0.0, s2: 0.0, s3: 0.0 };
        }
        if t >= self.t[n - 1] {
            return ReferenceAt { run: self, k: n - 1, held: true, h: 0.0, s: 0.0, s2: 0.0, s3: 0.0 };
        }
        // The interval [t_k, t_k+1) holding t: guessed from the (nearly) uniform spacing, then
        // moved to the exact one (the largest k ≤ n − 2 with t_k ≤ t), without a search.
        let guess = (t - self.t[0]) * self.per_second;
        let mut k = if guess > 0.0 { (guess as usize).min(n - 2) } else { 0 };
        while k > 0 && self.t[k] > t {
            k -= 1;
        }
        while k + 2 < n && self.t[k + 1] <= t {
            k += 1;
        }
        let h = self.t[k + 1] - self.t[k];
        let s = (t - self.t[k]) / h;
        ReferenceAt { run: self, k, held: false, h, s, s2: s * s, s3: s * s * s }
    }

    /// q, q̇ and q̈ at the times `t` (time-major), for error traces.
    pub fn states_at(&self, t: &[f64]) -> ReferenceStates {
        let mut out = ReferenceStates { of: self.of, q: Vec::with_capacity(t.len() * self.n), qd: Vec::with_capacity(t.len() * self.n), qdd: Vec::with_capacity(t.len() * self.n) };
        for &ti in t {
            let r = self.at(ti);
            for c in 0..self.n {
                out.q.push(r.q(c));
                out.qd.push(r.qd(c));
                out.qdd.push(r.qdd(c));
            }
        }
        out
    }
}

/// A sample measured against `run` must have its bodies (the same names in the same order: its
/// coordinates are the sample's): an `Err` naming those missing from either.
pub fn check_bodies(run: &ReferenceRun, bodies: &[String]) -> Result<()> {
    same_bodies(run.of, &run.bodies, bodies)
}

/// The reference's bodies `reference` against the sample's `sample` (both in the model's order): an `Err` naming those only one of them has.
pub fn same_bodies(of: ReferenceOf, reference: &[String], sample: &[String]) -> Result<()> {
    if reference == sample {
        return Ok(());
    }
    let only = |a: &[String], b: &[String]| a.iter().filter(|x| !b.contains(x)).map(|x| format!("'{x}'")).collect::<Vec<_>>().join(", ");
    let (extra, missing) = (only(sample, reference), only(reference, sample));
    let mut why = format!("the {} has other bodies than the sample", of.what());
    if !missing.is_empty() {
        why += &format!(": {missing} only in the reference");
    }
    if !extra.is_empty() {
        why += &format!("{} {extra} only in the sample", if missing.is_empty() { ":" } else { ";" });
    }
    Err(Error::invalid("reference", of.name(), why))
}

/// A reference located at one time (its interval and the Hermite weights' argument).
pub struct ReferenceAt<'a> {
    run: &'a ReferenceRun,
    k: usize,
    /// Outside the grid: the value at knot k.
    held: bool,
    h: f64,
    s: f64,
    s2: f64,
    s3: f64,
}

impl ReferenceAt<'_> {
    #[inline]
    fn hermite(&self, value: &[f64], rate: &[f64], c: usize) -> f64 {
        let n = self.run.n;
        let (i, j) = (self.k * n + c, (self.k + 1) * n + c);
        if self.held {
            return value[i];
        }
        let (s, s2, s3, h) = (self.s, self.s2, self.s3, self.h);
        (2.0 * s3 - 3.0 * s2 + 1.0) * value[i] + (s3 - 2.0 * s2 + s) * h * rate[i] + (-2.0 * s3 + 3.0 * s2) * value[j] + (s3 - s2) * h * rate[j]
    }
}

impl Kinematics for ReferenceAt<'_> {
    fn q(&self, c: usize) -> f64 {
        self.hermite(&self.run.q, &self.run.qd, c)
    }
    fn qd(&self, c: usize) -> f64 {
        self.hermite(&self.run.qd, &self.run.qdd, c)
    }
    fn qdd(&self, c: usize) -> f64 {
        self.hermite(&self.run.qdd, &self.run.jerk, c)
    }
}

/// A reference's states at a run's output times (`RunOutput::references`, with
/// [`ReferenceGrid::record`]): time-major, 3 coordinates a body.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceStates {
    pub of: ReferenceOf,
    pub q: Vec<f64>,
    pub qd: Vec<f64>,
    pub qdd: Vec<f64>,
}

/// The reference runs one run's monitors may be measured against, shared between the runs of a
/// batch.
#[derive(Debug, Clone, Default)]
pub struct References {
    pub own_ideal: Option<Arc<ReferenceRun>>,
    pub nominal: Option<Arc<ReferenceRun>>,
}

impl References {
    pub fn get(&self, of: ReferenceOf) -> Option<&Arc<ReferenceRun>> {
        match of {
            ReferenceOf::OwnIdeal => self.own_ideal.as_ref(),
            ReferenceOf::Nominal => self.nominal.as_ref(),
        }
    }

    pub fn set(&mut self, run: Arc<ReferenceRun>) {
        match run.of {
            ReferenceOf::OwnIdeal => self.own_ideal = Some(run),
            ReferenceOf::Nominal => self.nominal = Some(run),
        }
    }
}

/// d`f`/dt of each of the `n` columns of `f` (time-major) on the times `t`, as numpy's
/// `gradient(f, t)` computes it, operation for operation: a uniform grid (all spacings equal)
/// by central differences (f[k+1] − f[k−1]) / (2 dt), else the second-order formula for
/// unequal spacings; first-order one-sided differences at the ends.
fn gradient(t: &[f64], f: &[f64], n: usize) -> Vec<f64> {
    let m = t.len();
    let mut out = vec![0.0; f.len()];
    if m < 2 || n == 0 {
        return out;
    }
    let dx: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
    let uniform = dx.iter().all(|&d| d == dx[0]);
    for c in 0..n {
        let at = |k: usize| f[k * n + c];
        for k in 1..m - 1 {
            out[k * n + c] = if uniform {
                (at(k + 1) - at(k - 1)) / (2.0 * dx[0])
            } else {
                let (dx1, dx2) = (dx[k - 1], dx[k]);
                let a = -dx2 / (dx1 * (dx1 + dx2));
                let b = (dx2 - dx1) / (dx1 * dx2);
                let cc = dx1 / (dx2 * (dx1 + dx2));
                a * at(k - 1) + b * at(k) + cc * at(k + 1)
            };
        }
        out[c] = (at(1) - at(0)) / dx[0];
        out[(m - 1) * n + c] = (at(m - 1) - at(m - 2)) / dx[m - 2];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run_of(t: Vec<f64>, f: impl Fn(f64) -> [f64; 3]) -> ReferenceRun {
        let (mut q, mut qd, mut qdd) = (vec![], vec![], vec![]);
        for &x in &t {
            let [a, b, c] = f(x);
            q.extend([a, 0.0, 0.0]);
            qd.extend([b, 0.0, 0.0]);
            qdd.extend([c, 0.0, 0.0]);
        }
        ReferenceRun::new(ReferenceOf::OwnIdeal, vec!["b".into()], t, q, qd, qdd)
    }

    /// The Hermite reference reproduces a cubic exactly (positions with their rates), and the
    /// grid is numpy's linspace.
    #[test]
    fn hermite_reference_is_exact_for_a_cubic() {
        let f = |t: f64| [2.0 * t * t * t - t * t + 3.0, 6.0 * t * t - 2.0 * t, 12.0 * t - 2.0];
        let r = run_of(vec![0.0, 0.3, 1.0, 1.7], f);
        for x in [0.05, 0.29, 0.31, 0.9, 1.5] {
            let at = r.at(x);
            assert!((at.q(0) - f(x)[0]).abs() < 1e-12);
            assert!((at.qd(0) - f(x)[1]).abs() < 1e-12, "q̇ is a quadratic: its Hermite with q̈ as rates is exact");
        }
        // Held outside the grid; exact at the knots.
        assert_eq!(r.at(-1.0).q(0), f(0.0)[0]);
        assert_eq!(r.at(9.0).q(0), f(1.7)[0]);
        assert_eq!(r.at(1.0).q(0), f(1.0)[0]);
        let g = ReferenceGrid { t_start: 0.1, t_end: 0.7, intervals: 3, record: false }.times();
        let step = (0.7 - 0.1) / 3.0;
        assert_eq!(g, vec![0.0 * step + 0.1, step + 0.1, 2.0 * step + 0.1, 0.7]);
    }

    /// The interval found without a search is the one a binary search finds, on uneven grids too.
    #[test]
    fn interval_lookup_agrees_with_a_search() {
        let t: Vec<f64> = (0..40).map(|k| (k as f64).powf(1.7) * 0.01).collect();
        let r = run_of(t.clone(), |x| [x, 1.0, 0.0]);
        for i in 0..4000 {
            let x = -0.1 + i as f64 * (t[39] + 0.2) / 4000.0;
            let at = r.at(x);
            if x > t[0] && x < t[39] {
                let k = t.partition_point(|&v| v <= x).clamp(1, 39) - 1;
                assert_eq!((at.k, at.held), (k, false), "t = {x}");
            } else {
                assert!(at.held);
            }
        }
        for &x in &t[1..39] {
            let k = t.partition_point(|&v| v <= x) - 1;
            assert_eq!(r.at(x).k, k);
        }
    }

    /// numpy.gradient on unequal spacings is second-order exact: a quadratic's derivative comes
    /// out exactly inside, the ends first order.
    #[test]
    fn gradient_of_a_quadratic() {
        let t = [0.0, 0.1, 0.25, 0.45, 0.7];
        let f: Vec<f64> = t.iter().map(|x| 3.0 * x * x + x).collect();
        let d = gradient(&t, &f, 1);
        for k in 1..4 {
            assert!((d[k] - (6.0 * t[k] + 1.0)).abs() < 1e-12, "{k}: {}", d[k]);
        }
        assert!((d[0] - (f[1] - f[0]) / 0.1).abs() < 1e-15);
    }
}
