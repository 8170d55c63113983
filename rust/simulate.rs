//! One simulation run: assembly, integration with impact-onset location, recording, and a
//! diagnosis when the run cannot go on (docs/physics.md §1, §3; issue: failures keep what was computed).

use std::time::Instant;

use crate::assembly::assemble;
use crate::clearance::{grazing, ClearanceJoint, ImpactMemory, JointKinematics};
use crate::constraints::BodyKin;
use crate::error::{Error, Result};
use crate::energy::{EnergyBook, Powers};
use crate::clearance::wear::{WearBook, WearRate};
use crate::integrate::{integrate, DenseOutput, Method, OdeSystem, Settings, Stats};
use crate::model::Model;
use crate::monitor::{golden_section, Monitor, MonitorResult, MonitorSpec, Quantity};
use crate::rank;
use crate::record::{Channels, Recording};
use crate::system::Workspace;

/// Polled between steps (about every 64 accepted steps) with the time reached \[s\]; returning
/// `true` interrupts the run ([`Error::Interrupted`]). The Python glue uses it for Ctrl-C and
/// progress bars.
pub type StopCheck<'a> = &'a (dyn Fn(f64) -> bool + Sync);


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

    pub fn validate(&self) -> Result<()> {
        let fin = |f: &str, v: f64| if v.is_finite() { Ok(()) } else { Err(Error::invalid(f, v, "must be a finite number")) };
        fin("t0", self.t0)?;
        fin("t_end", self.t_end)?;
        if self.t_end <= self.t0 {
            return Err(Error::invalid("t_end", self.t_end, format!("must be greater than t0 = {}", self.t0)));
        }
        if !(self.ode.rtol > 0.0 && self.ode.rtol < 1.0) {
            return Err(Error::invalid("rtol", self.ode.rtol, "must lie in (0, 1)"));
        }
        if !(self.ode.atol > 0.0 && self.ode.atol.is_finite()) {
            return Err(Error::invalid("atol", self.ode.atol, "must be positive and finite"));
        }
        if let Some(b) = self.max_wall_time {
            if !(b > 0.0) {
                return Err(Error::invalid("max_seconds", b, "must be a positive number of seconds"));
            }
        }
        if let Some(m) = self.wear_mark {
            if !(m >= self.t0 && m <= self.t_end) {
                return Err(Error::invalid("wear_mark", m, format!("must lie in [t0, t_end] = [{}, {}]", self.t0, self.t_end)));
            }
        }
        if self.ode.max_steps == 0 {
            return Err(Error::invalid("max_steps", self.ode.max_steps, "must be a positive integer"));
        }
        if !(self.ode.h_min >= 0.0 && self.ode.h_min.is_finite()) {
            return Err(Error::invalid("h_min", self.ode.h_min, "must be a finite number ≥ 0"));
        }
        if !(self.ode.h_max > 0.0) {
            return Err(Error::invalid("h_max", self.ode.h_max, "must be positive"));
        }
        if let Method::Rk4 { step } = self.method {
            if !(step > 0.0 && step.is_finite()) {
                return Err(Error::invalid("step", step, "must be positive and finite"));
            }
        }
        for (k, w) in self.t_out.windows(2).enumerate() {
            if !(w[1] > w[0]) {
                return Err(Error::invalid(format!("t_out[{}]", k + 1), w[1], "output times must increase strictly"));
            }
        }
        for (i, m) in self.monitors.iter().enumerate() {
            m.validate(i)?;
        }
        Ok(())
    }
}

/// The result of a run, complete or partial.
#[derive(Debug, Clone)]
pub struct RunOutput {
    pub recording: Recording,
    pub stats: Stats,
    /// Why the run stopped early, if it did; the recording holds everything before.
    pub error: Option<Error>,
    pub q0: Vec<f64>,
    pub qd0: Vec<f64>,
    /// Impacts located per clearance joint.
    pub impacts: Vec<u64>,
    /// Largest ‖Φ‖ and ‖Φ̇‖ over the outputs.
    pub max_violation: [f64; 2],
    pub wall_time: f64,
    /// For a failed run: the clearance joint nearest contact and its eccentricity ratio ε.
    pub failure_joint: Option<(String, f64)>,
    /// What each monitor found (over the part of the run completed).
    pub monitors: Vec<MonitorResult>,
    /// Wear per clearance joint (`None` where it is not modelled).
    pub wear: Vec<Option<WearBook>>,
}

/// The model as an [`OdeSystem`].
pub struct MechanismSystem<'a> {
    pub model: &'a Model,
    pub ws: Workspace,
    pub memory: Vec<ImpactMemory>,
    /// The memory as it was during the step last accepted (what its outputs are evaluated with).
    step_memory: Vec<ImpactMemory>,
    pub recording: Recording,
    stop: Option<StopCheck<'a>>,
    /// Start of the run and its wall-time budget \[s\] ([`RunSettings::max_wall_time`]).
    pub budget: Option<(Instant, f64)>,
    /// The running extremes of [`RunSettings::monitors`], their values at the points of the
    /// current step (k × monitors) and a second state buffer for the dense derivative.
    pub monitors: Vec<Monitor>,
    monitor_values: Vec<f64>,
    scratch2: Vec<f64>,
    /// Work integrals, when the `energy` channel is recorded.
    energy: Option<EnergyBook>,
    /// Wear of each clearance joint that models it.
    pub wear: Vec<Option<WearBook>>,
    /// [`RunSettings::wear_mark`].
    pub wear_mark: Option<f64>,
    accepted: usize,
    scratch: Vec<f64>,
    /// Each clearance joint's kinematics at the last and the next sample of a step
    /// ([`OdeSystem::switching_point`]).
    switch_prev: Vec<(f64, JointKinematics)>,
    switch_next: Vec<JointKinematics>,
    /// The state components the clearance joints' kinematics read (q and q̇ of their bodies):
    /// all that the switch search takes from the dense output.
    switch_components: Vec<usize>,
    /// Columns `S e_k` of the constrained mobility (m × m, column-major; only the columns of
    /// clearance-joint bodies are filled) and which are current.
    mobility: Vec<f64>,
    mobility_done: Vec<bool>,
    g_base: Vec<f64>,
    g_probe: Vec<f64>,
    /// Last accepted state (for the diagnosis of a failure).
    pub last_t: f64,
    pub last_y: Vec<f64>,
    /// Penetration \[m\] within which a contact onset or end is grazing and not located as a
    /// switching point ([`crate::clearance::grazing`]): the run's `atol` (0 outside a run).
    pub gap_resolution: f64,
}

impl<'a> MechanismSystem<'a> {
    pub fn new(model: &'a Model, channels: Channels, capacity: usize, stop: Option<StopCheck<'a>>) -> Self {
        MechanismSystem {
            model,
            ws: Workspace::new(model),
            memory: vec![ImpactMemory::default(); model.clearance.len()],
            step_memory: vec![ImpactMemory::default(); model.clearance.len()],
            recording: Recording::new(channels, capacity, model),
            stop,
            budget: None,
            monitors: Vec::new(),
            monitor_values: Vec::new(),
            scratch2: Vec::new(),
            energy: channels.energy.then(|| EnergyBook::new(model)),
            wear: model.clearance.iter().enumerate().map(|(j, c)| c.wear.map(|law| WearBook::new(law, c, &model.initial_wear[j]))).collect(),
            wear_mark: None,
            accepted: 0,
            scratch: vec![0.0; model.state_dim()],
            switch_prev: vec![(0.0, JointKinematics::default()); model.clearance.len()],
            switch_next: vec![JointKinematics::default(); model.clearance.len()],
            switch_components: {
                let n = 3 * model.n_bodies();
                let mut bodies: Vec<usize> = model.clearance.iter().flat_map(|c| [c.bearing, c.journal]).flatten().map(|b| b as usize).collect();
                bodies.sort_unstable();
                bodies.dedup();
                bodies.iter().flat_map(|&b| (3 * b..3 * b + 3).chain(n + 3 * b..n + 3 * b + 3)).collect()
            },
            // Sized on first use: only the stiff methods' Newton matrices need it (9 n² values).
            mobility: Vec::new(),
            mobility_done: vec![false; 3 * model.n_bodies()],
            g_base: vec![0.0; 3 * model.n_bodies()],
            g_probe: vec![0.0; 3 * model.n_bodies()],
            last_t: 0.0,
            last_y: vec![0.0; model.state_dim()],
            gap_resolution: 0.0,
        }
    }

    /// Clearance-joint kinematics of joint `j` at state `y`.
    fn joint_kinematics(&self, j: usize, y: &[f64]) -> JointKinematics {
        let n = 3 * self.model.n_bodies();
        self.model.clearance[j].kinematics_with(|b| match b {
            None => BodyKin::GROUND,
            Some(i) => {
                let o = 3 * i as usize;
                BodyKin::new(&y[o..o + 3], &y[n + o..n + o + 3])
            }
        })
    }

    /// The clearance joint closest to (or deepest in) contact at the last accepted state.
    /// Feed every monitor its quantity at (t, y): a coordinate of q or q̇, or of q̈ from the
    /// KKT solve (one solve for all monitors that need it).
    fn observe(&mut self, t: f64, y: &[f64]) -> Result<()> {
        if self.monitors.iter().any(|m| m.spec.quantity == Quantity::Acceleration) {
            self.ws.evaluate(self.model, &self.memory, t, y)?;
        }
        for j in 0..self.monitors.len() {
            let v = self.monitored_value(j, y);
            self.monitors[j].observe(t, v);
        }
        Ok(())
    }

    /// Monitor `j`'s quantity at state `y` (accelerations: from the last KKT solve).
    fn monitored_value(&self, j: usize, y: &[f64]) -> f64 {
        let spec = &self.monitors[j].spec;
        let c = spec.coordinate;
        let nq = 3 * self.model.n_bodies();
        match spec.quantity {
            Quantity::Displacement => y[c],
            Quantity::Velocity => y[nq + c],
            Quantity::Acceleration => self.ws.qdd[c],
            q => {
                let k = self.joint_kinematics(c, y);
                if q == Quantity::Eccentricity {
                    return k.eps;
                }
                let f = self.model.clearance[c].force(&k, &self.memory[c]);
                match q {
                    Quantity::Force => f.total.norm(),
                    Quantity::ContactForce => f.normal,
                    _ => f.film_xi.hypot(f.film_eta),
                }
            }
        }
    }

    /// Feed the monitors the initial state.
    pub fn observe_start(&mut self, t: f64, y: &[f64]) -> Result<()> {
        self.observe(t, y)
    }

    /// The powers of [`EnergyBook::powers`] at (t, y) (a full evaluation).
    fn powers(&mut self, t: f64, y: &[f64]) -> Result<Powers> {
        self.ws.evaluate(self.model, &self.memory, t, y)?;
        let n = 3 * self.model.n_bodies();
        let mut book = self.energy.take().unwrap_or_default();
        let p = book.powers(self.model, &self.ws, &self.memory, t, &y[n..2 * n]);
        self.energy = Some(book);
        Ok(p)
    }

    /// Joint `j`'s wear rate at state `y` (its law; no KKT solve).
    fn wear_rate(&self, j: usize, y: &[f64]) -> WearRate {
        let joint = &self.model.clearance[j];
        let Some(law) = joint.wear else { return WearRate::default() };
        let k = self.joint_kinematics(j, y);
        let f = joint.force(&k, &self.memory[j]);
        let th = |b: Option<u32>| b.map_or(0.0, |i| y[3 * i as usize + 2]);
        WearRate::new(&law, &k, &f, th(joint.bearing), th(joint.journal))
    }

    /// The worn depth at joint `j`'s current contact direction, for its contact law (only when
    /// its wear is fed back; the offset stays 0 otherwise).
    fn update_wear_offset(&mut self, j: usize, y: &[f64]) {
        let joint = &self.model.clearance[j];
        let (Some(book), Some(true)) = (self.wear[j].as_ref(), joint.wear.map(|w| w.feedback)) else { return };
        let k = self.joint_kinematics(j, y);
        let th = |b: Option<u32>| b.map_or(0.0, |i| y[3 * i as usize + 2]);
        self.memory[j].wear_offset = book.depth_at(k.n.y.atan2(k.n.x), th(joint.bearing), th(joint.journal));
    }

    /// Start the wear books at the initial state (a run that starts worn feeds its depth back
    /// from the first step).
    pub fn wear_start(&mut self, t: f64, y: &[f64]) {
        for j in 0..self.wear.len() {
            if self.wear[j].is_some() {
                self.update_wear_offset(j, y);
                let r = self.wear_rate(j, y);
                let mark = self.wear_mark.is_some_and(|m| m <= t);
                if let Some(w) = self.wear[j].as_mut() {
                    w.start(r);
                    if mark {
                        w.at_mark = Some(w.snapshot());
                    }
                }
            }
        }
    }

    /// Start the work integrals at the initial state.
    pub fn energy_start(&mut self, t: f64, y: &[f64]) -> Result<()> {
        if self.energy.is_some() {
            let p = self.powers(t, y)?;
            if let Some(b) = self.energy.as_mut() {
                b.start(t, p);
            }
        }
        Ok(())
    }

    /// Feed the monitors `samples_per_step` points of the accepted step (t0, t1], the last at
    /// t1. Positions and velocities are read off the dense output. Accelerations come from the
    /// step's own f(t1, y1) when the method has it (else a KKT solve at t1) and, inside the
    /// step, from the time derivative of the dense velocity (central difference over a quarter
    /// of the point spacing); the interior point where that estimate deviates most from the
    /// reference is then solved exactly, so a peak inside a step costs one KKT solve, not one
    /// per point.
    fn observe_step(&mut self, t0: f64, t1: f64, y1: &[f64], dense: &dyn DenseOutput) -> Result<()> {
        let nm = self.monitors.len();
        let k = self.monitors.iter().map(|m| m.spec.samples_per_step).max().unwrap_or(1).max(1);
        let nq = 3 * self.model.n_bodies();
        let h = t1 - t0;
        let any_acc = self.monitors.iter().any(|m| m.spec.quantity == Quantity::Acceleration);
        if self.monitor_values.len() < k * nm {
            self.monitor_values.resize(k * nm, 0.0); // once per run
        }
        let mut s = std::mem::take(&mut self.scratch);
        let at = |i: usize| if i + 1 == k { t1 } else { t0 + h * (i + 1) as f64 / k as f64 };
        // A joint quantity needs the whole state; body coordinates only their own component.
        let whole_state = self.monitors.iter().any(|m| m.spec.quantity.of_joint());
        let d = 0.25 * h / k as f64;
        for i in 0..k - 1 {
            let t = at(i);
            if whole_state {
                dense.eval(t, &mut s);
            }
            for j in 0..nm {
                let spec = &self.monitors[j].spec;
                let c = spec.coordinate;
                self.monitor_values[i * nm + j] = match spec.quantity {
                    Quantity::Displacement => dense.eval_component(t, c),
                    Quantity::Velocity => dense.eval_component(t, nq + c),
                    Quantity::Acceleration => (dense.eval_component(t + d, nq + c) - dense.eval_component(t - d, nq + c)) / (2.0 * d),
                    _ => self.monitored_value(j, &s),
                };
            }
        }
        // Refine the largest interior acceleration error of each monitor with a KKT solve.
        let mut result = Ok(());
        for j in 0..nm {
            if self.monitors[j].spec.quantity != Quantity::Acceleration || self.monitors[j].spec.exact || k < 2 {
                continue;
            }
            let m = &self.monitors[j];
            let (imax, _) = (0..k - 1).fold((usize::MAX, -1.0f64), |best, i| {
                let e = m.error(at(i), self.monitor_values[i * nm + j]).abs();
                if e > best.1 { (i, e) } else { best }
            });
            if imax == usize::MAX {
                continue;
            }
            dense.eval(at(imax), &mut s);
            if let Err(e) = self.ws.evaluate(self.model, &self.memory, at(imax), &s) {
                result = Err(e);
                break;
            }
            for (jj, mm) in self.monitors.iter().enumerate() {
                if mm.spec.quantity == Quantity::Acceleration {
                    self.monitor_values[imax * nm + jj] = self.ws.qdd[mm.spec.coordinate];
                }
            }
        }
        // The acceleration at t1: the explicit methods' last stage f(t1, y1) holds it (same
        // memory), otherwise one KKT solve — done last, so that the workspace still holds it
        // when the implicit methods ask for f(t1, y1) next (`Workspace::evaluate_and_keep`).
        let end_rate = if any_acc { dense.end_rate() } else { None };
        if any_acc && end_rate.is_none() {
            result = result.and_then(|()| self.ws.evaluate_and_keep(self.model, &self.memory, t1, y1));
        }
        for j in 0..nm {
            let m = &self.monitors[j].spec;
            self.monitor_values[(k - 1) * nm + j] = match end_rate {
                Some(f1) if m.quantity == Quantity::Acceleration => f1[nq + m.coordinate],
                _ => self.monitored_value(j, y1),
            };
        }
        self.scratch = s;
        result?;
        for i in 0..k {
            for j in 0..nm {
                let v = self.monitor_values[i * nm + j];
                self.monitors[j].observe(at(i), v);
            }
        }
        if self.monitors.iter().any(|m| m.spec.exact) {
            self.search_extremes(dense)?;
        }
        Ok(())
    }

    /// Locate the extremes of the exact monitors between the samples of the step just observed
    /// (rust/monitor.rs: `Monitor::search_bracket`, `golden_section`).
    fn search_extremes(&mut self, dense: &dyn DenseOutput) -> Result<()> {
        let mut s = std::mem::take(&mut self.scratch);
        let mut result = Ok(());
        for j in 0..self.monitors.len() {
            for sign in [1.0, -1.0] {
                let Some((a, b)) = self.monitors[j].search_bracket(sign) else { continue };
                let found = golden_section(a, b, |t| {
                    dense.eval(t, &mut s);
                    if self.monitors[j].spec.quantity == Quantity::Acceleration {
                        self.ws.evaluate(self.model, &self.memory, t, &s)?;
                    }
                    Ok(sign * self.monitors[j].error(t, self.monitored_value(j, &s)))
                });
                match found {
                    Ok((t, v)) => self.monitors[j].record_extreme(t, sign * v),
                    Err(e) => result = Err(e),
                }
            }
            self.monitors[j].end_step();
        }
        self.scratch = s;
        result
    }

    /// The first switch of a clearance joint in (t0, t1] (see [`OdeSystem::switching_point`]).
    fn joint_switch(&mut self, t0: f64, y0: &[f64], t1: f64, y1: &[f64], dense: &dyn DenseOutput) -> Result<Option<f64>> {
        let nj = self.memory.len();
        for j in 0..nj {
            self.switch_prev[j] = (t0, self.joint_kinematics(j, y0));
        }
        for i in 1..=SWITCH_SAMPLES {
            let tb = if i == SWITCH_SAMPLES { t1 } else { t0 + (t1 - t0) * i as f64 / SWITCH_SAMPLES as f64 };
            let mut s = std::mem::take(&mut self.scratch);
            let yb: &[f64] = if i == SWITCH_SAMPLES {
                y1
            } else {
                dense.eval_components(tb, &self.switch_components, &mut s);
                &s
            };
            for j in 0..nj {
                self.switch_next[j] = self.joint_kinematics(j, yb);
            }
            self.scratch = s;
            // Sub-intervals are visited in time order: the first with a switch holds the earliest.
            let mut first: Option<f64> = None;
            for j in 0..nj {
                let (a, b) = (self.switch_prev[j], (tb, self.switch_next[j]));
                if let Some(ts) = self.first_switch_between(j, a, b, dense) {
                    first = Some(first.map_or(ts, |f| f.min(ts)));
                }
                self.switch_prev[j] = b;
            }
            if first.is_some() {
                return Ok(first);
            }
        }
        Ok(None)
    }

    pub fn worst_joint(&self) -> Option<(usize, JointKinematics)> {
        let mut worst: Option<(usize, JointKinematics)> = None;
        for j in 0..self.model.clearance.len() {
            let k = self.joint_kinematics(j, &self.last_y);
            if worst.as_ref().is_none_or(|(_, w)| k.eps > w.eps || !k.eps.is_finite()) {
                worst = Some((j, k));
            }
        }
        worst
    }

    /// The time in `[ta, tb]` where the switching function `g` of joint `j`'s kinematics
    /// changes sign (`g` at the two ends of opposite signs), by Illinois (modified regula falsi)
    /// on g(t) through the dense output; `tol` is an absolute tolerance on g. Returns the time
    /// and the joint's kinematics there.
    fn locate_crossing(
        &mut self,
        j: usize,
        g: impl Fn(&JointKinematics) -> f64,
        tol: f64,
        (mut ta, ka): (f64, JointKinematics),
        (mut tb, kb): (f64, JointKinematics),
        dense: &dyn DenseOutput,
    ) -> (f64, JointKinematics) {
        // Orient so that g(ta) ≤ 0 < g(tb).
        let sign = if g(&kb) > 0.0 { 1.0 } else { -1.0 };
        let (mut fa, mut fb) = (sign * g(&ka), sign * g(&kb));
        let (t_lo, t_hi) = (ta, tb);
        let mut side = 0i8;
        let mut kin = kb;
        let mut tm = tb;
        for _ in 0..60 {
            tm = (ta * fb - tb * fa) / (fb - fa);
            if !(tm.is_finite() && tm > ta && tm < tb) {
                tm = 0.5 * (ta + tb);
            }
            let mut s = std::mem::take(&mut self.scratch);
            dense.eval(tm, &mut s);
            kin = self.joint_kinematics(j, &s);
            self.scratch = s;
            let fm = sign * g(&kin);
            if fm > 0.0 {
                tb = tm;
                fb = fm;
                if side == 1 {
                    fa *= 0.5;
                }
                side = 1;
            } else {
                ta = tm;
                fa = fm;
                if side == -1 {
                    fb *= 0.5;
                }
                side = -1;
            }
            if (tb - ta) <= 1e-14 * (1.0 + t_hi.abs()) || fm.abs() <= tol {
                break;
            }
        }
        (tm.clamp(t_lo, t_hi), kin)
    }

    /// Locate where contact starts or ends (δ changes sign) inside a step: time and kinematics.
    fn locate_contact_change(&mut self, j: usize, start: (f64, JointKinematics), end: (f64, JointKinematics), dense: &dyn DenseOutput) -> (f64, JointKinematics) {
        let tol = 1e-15 * self.model.clearance[j].clearance;
        self.locate_crossing(j, |k| k.delta, tol, start, end, dense)
    }

    /// The first switching point of joint `j` between two samples `a`, `b` of a step: contact
    /// starting or ending (δ changes sign), or, in contact at both, the slip crossing a corner
    /// of the friction ramp (±v0, ±v1, P5).
    fn first_switch_between(
        &mut self,
        j: usize,
        a: (f64, JointKinematics),
        b: (f64, JointKinematics),
        dense: &dyn DenseOutput,
    ) -> Option<f64> {
        let (ka, kb) = (&a.1, &b.1);
        if (ka.delta > 0.0) != (kb.delta > 0.0) {
            if grazing(ka, kb, self.gap_resolution, self.model.clearance[j].contact.impact_speed_floor) {
                return None;
            }
            return Some(self.locate_contact_change(j, a, b, dense).0);
        }
        let fr = self.model.clearance[j].friction;
        if ka.delta <= 0.0 || fr.friction_coefficient <= 0.0 {
            return None;
        }
        let mut first: Option<f64> = None;
        for v in [-fr.v1, -fr.v0, fr.v0, fr.v1] {
            if (ka.slip > v) != (kb.slip > v) {
                let tol = 1e-12 * fr.v1.abs().max(1e-12);
                let ts = self.locate_crossing(j, |k| k.slip - v, tol, a, b, dense).0;
                first = Some(first.map_or(ts, |f| f.min(ts)));
            }
        }
        first
    }

    /// For a run that stopped for want of step size (or a singular KKT matrix, a non-finite
    /// state): a [`Error::LockUp`] naming the joints and drivers when the constraint Jacobian at
    /// the last accepted state has lost rank ([`rank::analyse`]: a dead centre), else `None`.
    /// Only on this failure path: one dense SVD of Φq.
    pub fn lock_up(&mut self, e: &Error) -> Option<Error> {
        let how = match e {
            Error::StepSizeUnderflow { h, .. } => format!("the steps shrank to h = {h:.1e} s"),
            Error::NewtonFailure { h, .. } => format!("the Newton iteration failed down to h = {h:.1e} s"),
            Error::SingularJacobian { .. } => "the KKT matrix became singular".into(),
            Error::NonFinite { .. } => "the state stopped being finite".into(),
            _ => return None,
        };
        if self.model.rows == 0 {
            return None;
        }
        let n = 3 * self.model.n_bodies();
        let (q, qd) = self.last_y.split_at(n);
        self.ws.eval_constraints(self.model, self.last_t, q, qd);
        let report = rank::analyse(self.model, &self.ws.jac, &self.ws.kin);
        report.deficient().then(|| Error::LockUp { t: self.last_t, reason: format!("{} ({how})", report.lock_up(self.model, self.last_t)) })
    }

    /// Where a failed run stood, for the error message.
    pub fn diagnosis(&self) -> String {
        let mut out = String::new();
        if let Some((j, k)) = self.worst_joint() {
            let c = &self.model.clearance[j];
            let state = if k.delta > 0.0 { "in contact" } else if c.film.is_some() { "in the film" } else { "free" };
            out.push_str(&format!(
                "; last accepted t = {:.9} s; joint '{}' {} at eccentricity ε = {:.6} (δ = {:.3e} m, δ̇ = {:.3e} m/s)",
                self.last_t, c.name, state, k.eps, k.delta, k.delta_dot
            ));
        } else {
            out.push_str(&format!("; last accepted t = {:.9} s", self.last_t));
        }
        out
    }
}

/// Sub-intervals of a step in which [`OdeSystem::switching_point`] looks for switches.
const SWITCH_SAMPLES: usize = 4;

impl OdeSystem for MechanismSystem<'_> {
    fn dim(&self) -> usize {
        self.model.state_dim()
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<()> {
        let n = 3 * self.model.n_bodies();
        self.ws.evaluate(self.model, &self.memory, t, y)?;
        dy[..n].copy_from_slice(&y[n..2 * n]);
        dy[n..2 * n].copy_from_slice(&self.ws.qdd);
        Ok(())
    }

    /// The first switching point of any clearance joint inside the step: contact starting or
    /// ending, or the slip crossing a corner of the friction ramp — where the joint force stops
    /// being smooth.
    ///
    /// The switching functions are sampled at the step's ends and at `SWITCH_SAMPLES − 1`
    /// interior points of the dense output, so that a switch crossed twice inside one step (a
    /// whole short contact, a slip reversal through the friction ramp) is seen too; the first
    /// crossing is located in the first sub-interval that has one.
    fn switching_point(&mut self, t0: f64, y0: &[f64], t1: f64, y1: &[f64], dense: &dyn DenseOutput) -> Result<Option<f64>> {
        // Corners of time-tabulated loads (docs/physics.md §10.3) end a step like a switch.
        let t_break = self.model.forces.iter().filter_map(|f| f.time_break_in(t0, t1)).reduce(f64::min);
        let Some(tb) = t_break else {
            return self.joint_switch(t0, y0, t1, y1, dense);
        };
        let mut end = std::mem::take(&mut self.scratch2);
        end.resize(y0.len(), 0.0);
        dense.eval(tb, &mut end);
        let joint = self.joint_switch(t0, y0, tb, &end, dense);
        self.scratch2 = end;
        Ok(joint?.or(t_break))
    }

    /// Locate contact onsets inside the step and record δ̇⁽⁻⁾ there (docs/physics.md §3, P3); clear the
    /// memory at separation.
    fn step_accepted(&mut self, t0: f64, y0: &[f64], t1: f64, y1: &[f64], dense: &dyn DenseOutput) -> Result<bool> {
        self.step_memory.copy_from_slice(&self.memory);
        if self.energy.is_some() {
            // The step's powers with the impact memory it was integrated with (§10.5).
            let tm = 0.5 * (t0 + t1);
            let mut s = std::mem::take(&mut self.scratch);
            dense.eval(tm, &mut s);
            let pm = self.powers(tm, &s);
            self.scratch = s;
            let (pm, p1) = (pm?, self.powers(t1, y1)?);
            if let Some(b) = self.energy.as_mut() {
                b.step(t0, t1, pm, p1);
            }
        }
        if self.wear.iter().any(Option::is_some) {
            // Wear of the step, with the impact memory it was integrated with (§12).
            let mut s = std::mem::take(&mut self.scratch);
            dense.eval(0.5 * (t0 + t1), &mut s);
            for j in 0..self.wear.len() {
                if self.wear[j].is_some() {
                    let (mid, end) = (self.wear_rate(j, &s), self.wear_rate(j, y1));
                    let mark = self.wear_mark.filter(|m| *m > t0 && *m <= t1);
                    if let Some(w) = self.wear[j].as_mut() {
                        let before = mark.map(|_| w.snapshot());
                        w.step(t1 - t0, mid, end);
                        if let (Some(m), Some(b)) = (mark, before) {
                            // The books at the mark: linear in time within the step.
                            w.mark_between(b, (m - t0) / (t1 - t0));
                        }
                    }
                    self.update_wear_offset(j, y1);
                }
            }
            self.scratch = s;
        }
        // Monitors and outputs inside the step see the impact memory the step was integrated
        // with: a contact that ends at t1 still used its δ̇⁽⁻⁾ inside the step (P3).
        if !self.monitors.is_empty() {
            self.observe_step(t0, t1, y1, dense)?;
        }
        let mut changed = false;
        for j in 0..self.memory.len() {
            let k1 = self.joint_kinematics(j, y1);
            let cj = &self.model.clearance[j];
            let limit = cj.penetration_limit;
            if k1.delta > limit {
                // The diagnosis (worst joint, its ε) describes the state that went too deep.
                self.last_t = t1;
                self.last_y.copy_from_slice(y1);
                let cj = &self.model.clearance[j];
                return Err(Error::PenetrationTooDeep { t: t1, joint: cj.name.clone(), penetration: k1.delta, limit });
            }
            if k1.delta > 0.0 && !self.memory[j].in_contact {
                let k0 = self.joint_kinematics(j, y0);
                let speed = if k0.delta >= 0.0 { k0.delta_dot } else { self.locate_contact_change(j, (t0, k0), (t1, k1), dense).1.delta_dot };
                let m = &mut self.memory[j];
                m.in_contact = true;
                m.impact_speed = speed.abs();
                m.impacts += 1;
                changed = true;
            } else if k1.delta <= 0.0 && self.memory[j].in_contact {
                self.memory[j].in_contact = false;
            }
        }
        self.last_t = t1;
        self.last_y.copy_from_slice(y1);
        self.accepted += 1;
        // The wall-time budget every step (reading the clock costs tens of ns, a step µs to ms):
        // a run whose steps are slow stops within one step of its budget.
        if let Some((start, seconds)) = self.budget {
            if start.elapsed().as_secs_f64() > seconds {
                return Err(Error::TimeBudget { t: t1, seconds });
            }
        }
        if self.accepted % 64 == 0 {
            if let Some(stop) = self.stop {
                if stop(t1) {
                    return Err(Error::Interrupted { t: t1 });
                }
            }
        }
        Ok(changed)
    }

    /// The stiff part of `∂q̈/∂(q, q̇)` for the Rosenbrock-W method: the clearance-joint forces
    /// `g_j` differenced in the 6 position and velocity components of each of their two bodies
    /// (forces, kinematics and moment arms recomputed, impact memory held), mapped to
    /// accelerations by the constrained mobility `S` of the current pose:
    /// `∂q̈/∂x ≈ S ∂g/∂x`. Left out, as not stiff: the pose dependence of `S`, of `γ` and of the
    /// Baumgarte terms (eigenvalues of order α, β).
    fn acceleration_jacobian(&mut self, t: f64, y: &[f64], a_q: &mut [f64], a_v: &mut [f64]) -> Result<bool> {
        let model = self.model;
        let m = 3 * model.n_bodies();
        a_q.fill(0.0);
        a_v.fill(0.0);
        // The stiff forces: clearance joints, and springs, rotational springs and motors (their
        // stiffness and damping); applied loads and torques depend on time only.
        let springs = model.forces.iter().enumerate().filter(|(_, f)| f.stiff_bodies().is_some()).map(|(i, _)| Stiff::Force(i));
        let items = (0..model.clearance.len()).map(Stiff::Joint).chain(springs); // no allocation
        if model.clearance.is_empty() && !model.forces.iter().any(|f| f.stiff_bodies().is_some()) {
            return Ok(true);
        }
        self.ws.eval_constraints(model, t, &y[..m], &y[m..2 * m]);
        self.ws.factor_kkt(t)?;
        if self.mobility.len() != m * m {
            self.mobility.resize(m * m, 0.0); // once per run
        }
        self.mobility_done.fill(false);
        for item in items {
            let bodies = match item {
                Stiff::Joint(j) => [model.clearance[j].bearing, model.clearance[j].journal],
                Stiff::Force(i) => model.forces[i].stiff_bodies().unwrap_or([None, None]),
            };
            for &b in bodies.iter().flatten() {
                for k in 3 * b as usize..3 * b as usize + 3 {
                    if !self.mobility_done[k] {
                        self.ws.unit_force_response(k, &mut self.mobility[k * m..(k + 1) * m]);
                        self.mobility_done[k] = true;
                    }
                }
            }
            if let Stiff::Joint(j) = item {
                if let Some(d) = model.clearance[j].force_derivatives(&self.ws.kin, &self.memory[j]) {
                    for (slot, b) in bodies.iter().enumerate() {
                        let Some(b) = b.map(|b| b as usize) else { continue };
                        for comp in 0..6 {
                            let target = if comp < 3 { &mut *a_q } else { &mut *a_v };
                            let col = &mut target[(3 * b + comp % 3) * m..(3 * b + comp % 3 + 1) * m];
                            for (oslot, ob) in bodies.iter().enumerate() {
                                let Some(ob) = ob.map(|ob| ob as usize) else { continue };
                                for o in 0..3 {
                                    let dv = d[3 * oslot + o][6 * slot + comp];
                                    if dv != 0.0 {
                                        for (c, s) in col.iter_mut().zip(&self.mobility[(3 * ob + o) * m..(3 * ob + o + 1) * m]) {
                                            *c += dv * s;
                                        }
                                    }
                                }
                            }
                        }
                    }
                    continue;
                }
            }
            self.stiff_force(item, t, &bodies, false);
            for &b in bodies.iter().flatten() {
                let b = b as usize;
                let saved = self.ws.kin[b];
                let mut x = [saved.x, saved.y, saved.th, saved.vx, saved.vy, saved.w];
                let steps = self.jacobian_steps(item, b, &x);
                for comp in 0..6 {
                    let keep = x[comp];
                    x[comp] += steps[comp];
                    let delta = x[comp] - keep; // the step actually taken (exact in floating point)
                    self.ws.kin[b] = BodyKin::new(&x[..3], &x[3..]);
                    x[comp] = keep;
                    self.stiff_force(item, t, &bodies, true);
                    self.ws.kin[b] = saved;
                    let target = if comp < 3 { &mut *a_q } else { &mut *a_v };
                    let col = &mut target[(3 * b + comp % 3) * m..(3 * b + comp % 3 + 1) * m];
                    for &ob in bodies.iter().flatten() {
                        for o in 3 * ob as usize..3 * ob as usize + 3 {
                            let d = (self.g_probe[o] - self.g_base[o]) / delta;
                            if d != 0.0 {
                                for (c, s) in col.iter_mut().zip(&self.mobility[o * m..(o + 1) * m]) {
                                    *c += d * s;
                                }
                            }
                        }
                    }
                }
            }
        }
        Ok(true)
    }

    fn difference_step(&self, j: usize, y: &[f64]) -> f64 {
        let m = 3 * self.model.n_bodies();
        let generic = (f64::EPSILON * 1e-5f64.max(y[j].abs())).sqrt();
        let (b, comp) = ((j % m) / 3, (j % m) % 3 + if j >= m { 3 } else { 0 });
        let x = [y[3 * b], y[3 * b + 1], y[3 * b + 2], y[m + 3 * b], y[m + 3 * b + 1], y[m + 3 * b + 2]];
        let mut step = generic;
        for (i, joint) in self.model.clearance.iter().enumerate() {
            if joint.bearing == Some(b as u32) || joint.journal == Some(b as u32) {
                step = step.min(self.jacobian_steps(Stiff::Joint(i), b, &x)[comp]);
            }
        }
        step
    }

    fn output(&mut self, t: f64, y: &[f64]) -> Result<()> {
        if self.recording.needs_evaluation() {
            // Outputs lie inside the step just accepted: the memory it was integrated with.
            self.ws.evaluate(self.model, &self.step_memory, t, y)?;
        }
        self.recording.push(t, y, &self.ws);
        if let Some(book) = &self.energy {
            let e = EnergyBook::stored(self.model, &self.ws);
            self.recording.energy.extend_from_slice(&e);
            self.recording.energy.extend_from_slice(&book.work_at(t));
        }
        Ok(())
    }
}

/// The generalised forces of one clearance joint on its two bodies, written to their entries
/// of `g` (the other entries are left alone).
/// A force whose derivatives enter the implicit methods' Newton matrix.
#[derive(Clone, Copy)]
enum Stiff {
    Joint(usize),
    Force(usize),
}

impl MechanismSystem<'_> {
    /// Finite-difference steps in body `b`'s (x, y, θ, ẋ, ẏ, θ̇) for the Newton matrix of `item`.
    /// A clearance joint's force varies on the scale of its clearance c, not of the body's
    /// coordinates: steps of √ε_mach·max(|x|, 1) m would move a µm journal by 1e-8 m, across
    /// the bearing centre (where it sits under a stiff film) and through its nonlinearity. So
    /// the positions are stepped by √ε_mach·c (θ by that over the joint point's arm) and the
    /// velocities by √ε_mach·c·max(|θ̇|, 1 rad/s).
    fn jacobian_steps(&self, item: Stiff, b: usize, x: &[f64; 6]) -> [f64; 6] {
        let root = f64::EPSILON.sqrt();
        let generic = |v: f64| root * v.abs().max(1.0);
        let mut steps = [0.0; 6];
        for (s, v) in steps.iter_mut().zip(x) {
            *s = generic(*v);
        }
        if let Stiff::Joint(j) = item {
            let joint = &self.model.clearance[j];
            let c = joint.clearance;
            let point = if joint.journal == Some(b as u32) { joint.journal_point } else { joint.bearing_point };
            let arm = point.norm().max(c);
            let rate = x[5].abs().max(1.0);
            steps = [root * c, root * c, (root * c / arm).min(generic(x[2])), root * c * rate, root * c * rate, (root * c * rate / arm).min(generic(x[5]))];
        }
        steps
    }

    /// The generalised force of one stiff item on its bodies, into `g_probe` (`probe`) or `g_base`.
    fn stiff_force(&mut self, item: Stiff, t: f64, bodies: &[Option<u32>; 2], probe: bool) {
        let g = if probe { &mut self.g_probe } else { &mut self.g_base };
        match item {
            Stiff::Joint(j) => joint_generalised_force(&self.model.clearance[j], &self.ws.kin, &self.memory[j], g),
            Stiff::Force(i) => {
                for &b in bodies.iter().flatten() {
                    g[3 * b as usize..3 * b as usize + 3].fill(0.0);
                }
                self.model.forces[i].apply(t, &self.ws.kin, g);
            }
        }
    }
}

fn joint_generalised_force(joint: &ClearanceJoint, kin: &[BodyKin], memory: &ImpactMemory, g: &mut [f64]) {
    for &b in [joint.bearing, joint.journal].iter().flatten() {
        g[3 * b as usize..3 * b as usize + 3].fill(0.0);
    }
    let k = joint.kinematics(kin);
    let f = joint.force(&k, memory);
    joint.apply(kin, &k, &f, g);
}

/// Run a compiled model. Bad settings are an `Err`; a run that fails part-way is an `Ok` whose
/// `error` says why, with everything recorded until then.
pub fn simulate(model: &Model, rs: &RunSettings, stop: Option<StopCheck<'_>>) -> Result<RunOutput> {
    rs.validate()?;
    let start = Instant::now();
    let (q0, qd0) = match assemble(model, rs.t0) {
        Ok(v) => v,
        Err(e) => {
            return Ok(RunOutput {
                recording: Recording::new(rs.channels, 0, model),
                stats: Stats::default(),
                error: Some(e),
                q0: model.q_guess.clone(),
                qd0: model.qd_guess.clone(),
                impacts: vec![0; model.clearance.len()],
                max_violation: [0.0; 2],
                wall_time: start.elapsed().as_secs_f64(),
                failure_joint: None,
                monitors: Vec::new(),
                wear: Vec::new(),
            })
        }
    };
    let mut y0 = q0.clone();
    y0.extend_from_slice(&qd0);
    let t_out: Vec<f64> = rs.t_out.iter().copied().filter(|t| *t >= rs.t0 && *t <= rs.t_end).collect();
    let mut sys = MechanismSystem::new(model, rs.channels, t_out.len(), stop);
    sys.budget = rs.max_wall_time.map(|b| (start, b));
    sys.gap_resolution = rs.ode.atol;
    for spec in &rs.monitors {
        if spec.quantity.of_joint() {
            if spec.coordinate >= model.clearance.len() {
                let n = model.clearance.len();
                return Err(Error::invalid("monitor.coordinate", spec.coordinate, format!("must be a clearance joint index below {n}")));
            }
        } else if spec.coordinate >= 3 * model.n_bodies() {
            return Err(Error::invalid("monitor.coordinate", spec.coordinate, format!("must be below 3 × bodies = {}", 3 * model.n_bodies())));
        }
        if !(spec.bin_width > 0.0 && spec.bin_width.is_finite() && spec.t_start.is_finite()) {
            return Err(Error::invalid("monitor.bin_width", spec.bin_width, "must be a positive, finite time [s]"));
        }
        sys.monitors.push(Monitor::new(spec.clone()));
    }
    if !sys.monitors.is_empty() {
        sys.observe_start(rs.t0, &y0)?;
    }
    sys.energy_start(rs.t0, &y0)?;
    sys.wear_mark = rs.wear_mark;
    sys.wear_start(rs.t0, &y0);
    sys.last_t = rs.t0;
    sys.last_y.copy_from_slice(&y0);
    let (stats, error, failure_joint) = match integrate(&mut sys, rs.method, rs.t0, &y0, rs.t_end, &t_out, &rs.ode) {
        Ok(s) => (s, None, None),
        Err((e, s)) => {
            let e = sys.lock_up(&e).unwrap_or(e);
            let detail = sys.diagnosis();
            let joint = sys.worst_joint().map(|(j, k)| (model.clearance[j].name.clone(), k.eps));
            (s, Some(e.with_detail(&detail)), joint)
        }
    };
    let mut max_violation = [0.0f64; 2];
    for v in sys.recording.violation.chunks(2) {
        max_violation[0] = max_violation[0].max(v[0]);
        max_violation[1] = max_violation[1].max(v[1]);
    }
    Ok(RunOutput {
        impacts: sys.memory.iter().map(|m| m.impacts).collect(),
        recording: sys.recording,
        stats,
        error,
        q0,
        qd0,
        max_violation,
        wall_time: start.elapsed().as_secs_f64(),
        failure_joint,
        monitors: sys.monitors.into_iter().map(|m| m.result).collect(),
        wear: sys.wear,
    })
}
