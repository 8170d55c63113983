//! What a run observes along its accepted steps besides the recorded samples: the monitors'
//! extremes between the output times (rust/monitor/; an ideal joint's or driver's reaction from
//! a KKT solve at each of its points, only when a monitor watches one), the work integrals of the energy balance
//! (rust/energy.rs, docs/physics.md §10.5) and the wear books (rust/clearance/wear.rs, §12).
//! A joint's forces are evaluated at the state's oil temperature ([`ClearanceJoint::memory_at`]).

use super::MechanismSystem;
use crate::clearance::wear::WearRate;
use crate::energy::Powers;
use crate::error::Result;
use crate::integrate::DenseOutput;
use crate::monitor::target::State;
use crate::monitor::Monitor;
use crate::monitor::{golden_section, Kinematics, PointComponent, Quantity, Target};

/// The run's state inside an accepted step, read off its dense output at time `t`: positions
/// and velocities directly, accelerations as the time derivative of the dense velocity (central
/// difference over ±`d`).
struct DenseState<'a> {
    dense: &'a dyn DenseOutput,
    t: f64,
    d: f64,
    nq: usize,
}

impl Kinematics for DenseState<'_> {
    fn q(&self, c: usize) -> f64 {
        self.dense.eval_component(self.t, c)
    }
    fn qd(&self, c: usize) -> f64 {
        self.dense.eval_component(self.t, self.nq + c)
    }
    fn qdd(&self, c: usize) -> f64 {
        (self.dense.eval_component(self.t + self.d, self.nq + c) - self.dense.eval_component(self.t - self.d, self.nq + c)) / (2.0 * self.d)
    }
}

impl MechanismSystem<'_> {
    /// Feed every monitor its error at (t, y): from q, q̇, or q̈ and λ of the KKT solve (one
    /// solve for all monitors that need it).
    pub(super) fn observe(&mut self, t: f64, y: &[f64]) -> Result<()> {
        if self.monitors.iter().any(|m| m.spec.quantity == Quantity::Acceleration || m.solves()) {
            self.ws.evaluate(self.model, &self.memory, t, y)?;
        }
        for j in 0..self.monitors.len() {
            let e = self.monitored_error(j, t, y, &self.ws.qdd);
            self.monitors[j].observe(t, e);
        }
        Ok(())
    }

    /// Monitor `j`'s error at time `t` and state `y` with accelerations `qdd` (read only by
    /// acceleration monitors): a body target's against its reference (rust/monitor/target.rs), a
    /// joint's quantity itself, a reaction from the workspace (which must hold the KKT solve at
    /// (t, y)).
    pub(super) fn monitored_error(&self, j: usize, t: f64, y: &[f64], qdd: &[f64]) -> f64 {
        let m = &self.monitors[j];
        match m.spec.target {
            Target::Joint(c) => self.joint_value(c, m.spec.quantity, y),
            Target::Reaction { constraint, component } => self.reaction_value(constraint, component, m.spec.quantity),
            _ => m.error(t, &State { y, qdd, nq: 3 * self.model.n_bodies() }),
        }
    }

    /// What ideal joint or driver `k` exerts on its second body, from the workspace's last KKT
    /// solve: its force's `component` \[N\] or (`quantity` torque) its couple \[N m\]
    /// ([`crate::constraints::Constraint::reaction`]; the `reactions` output channel's values).
    fn reaction_value(&self, k: usize, component: PointComponent, quantity: Quantity) -> f64 {
        let cons = &self.model.constraints;
        let row: usize = cons[..k].iter().map(|c| c.rows()).sum();
        let [fx, fy, torque] = cons[k].reaction(&self.ws.kin, &self.ws.lambda[row..row + cons[k].rows()]);
        match (quantity, component) {
            (Quantity::Torque, _) => torque,
            (_, PointComponent::X) => fx,
            (_, PointComponent::Y) => fy,
            (_, PointComponent::Magnitude) => fx.hypot(fy),
        }
    }

    /// Clearance joint `c`'s `quantity` at state `y`.
    fn joint_value(&self, c: usize, quantity: Quantity, y: &[f64]) -> f64 {
        let nq = 3 * self.model.n_bodies();
        let k = self.joint_kinematics(c, y);
        if quantity == Quantity::Eccentricity {
            return k.eps;
        }
        let joint = &self.model.clearance[c];
        let memory = joint.memory_at(&self.memory[c], y);
        let f = joint.force(&k, &memory);
        match quantity {
            Quantity::Force => f.total.norm(),
            Quantity::ContactForce => f.normal,
            Quantity::FilmForce => f.film_xi.hypot(f.film_eta),
            _ => {
                let (w_b, w_j) = crate::clearance::body_rates(joint, &y[nq..2 * nq]);
                let r = joint.readings(&k, &f, &memory, w_b, w_j);
                match quantity {
                    Quantity::FilmThickness => r.film_thickness,
                    Quantity::FrictionTorque => r.torque_journal,
                    _ => r.power_loss,
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
        let p = book.powers(self.model, &self.ws, t, &y[n..2 * n]);
        self.energy = Some(book);
        Ok(p)
    }

    /// Joint `j`'s wear rate at state `y` (its law; no KKT solve).
    fn wear_rate(&self, j: usize, y: &[f64]) -> WearRate {
        let joint = &self.model.clearance[j];
        let Some(law) = joint.wear else { return WearRate::default() };
        let k = self.joint_kinematics(j, y);
        let f = joint.force(&k, &joint.memory_at(&self.memory[j], y));
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
        // The errors of the step's points, k × monitors (sized once per run).
        let mut errors = std::mem::take(&mut self.monitor_values);
        if errors.len() < k * nm {
            errors.resize(k * nm, 0.0);
        }
        let mut s = std::mem::take(&mut self.scratch);
        // The step's sample times, the last at t1.
        let mut times = std::mem::take(&mut self.monitor_times);
        times.clear();
        times.extend((0..k).map(|i| if i + 1 == k { t1 } else { t0 + h * (i + 1) as f64 / k as f64 }));
        let at = |i: usize| times[i];
        // A joint quantity needs the whole state; body targets only their own components; a
        // reaction a KKT solve at each point (one for all of them).
        let whole_state = self.monitors.iter().any(|m| m.spec.quantity.of_joint());
        let solves = self.monitors.iter().any(Monitor::solves);
        let d = 0.25 * h / k as f64;
        let mut result = Ok(());
        for i in 0..k - 1 {
            let t = at(i);
            if whole_state {
                dense.eval(t, &mut s);
            }
            if solves {
                if let Err(e) = self.ws.evaluate(self.model, &self.memory, t, &s) {
                    result = Err(e);
                    break;
                }
            }
            let state = DenseState { dense, t, d, nq };
            for j in 0..nm {
                let m = &self.monitors[j];
                errors[i * nm + j] = match m.spec.target {
                    Target::Joint(c) => self.joint_value(c, m.spec.quantity, &s),
                    Target::Reaction { constraint, component } => self.reaction_value(constraint, component, m.spec.quantity),
                    _ => m.error(t, &state),
                };
            }
        }
        // Refine the largest interior acceleration error of each monitor with a KKT solve. Each
        // monitor keeps only its own refined value, so what one output reports does not depend
        // on which other outputs are watched; monitors that pick the same point share one solve.
        let mut solved = usize::MAX;
        for j in 0..nm {
            if result.is_err() || self.monitors[j].spec.quantity != Quantity::Acceleration || self.monitors[j].spec.exact || k < 2 {
                continue;
            }
            let (imax, _) = (0..k - 1).fold((usize::MAX, -1.0f64), |best, i| {
                let e = errors[i * nm + j].abs();
                if e > best.1 { (i, e) } else { best }
            });
            if imax == usize::MAX {
                continue;
            }
            if imax != solved {
                dense.eval(at(imax), &mut s);
                if let Err(e) = self.ws.evaluate(self.model, &self.memory, at(imax), &s) {
                    result = Err(e);
                    break;
                }
                solved = imax;
            }
            errors[imax * nm + j] = self.monitored_error(j, at(imax), &s, &self.ws.qdd);
        }
        // The acceleration at t1: the explicit methods' last stage f(t1, y1) holds it (same
        // memory), otherwise one KKT solve — done last, so that the workspace still holds it
        // when the implicit methods ask for f(t1, y1) next (`Workspace::evaluate_and_keep`).
        let end_rate = if any_acc { dense.end_rate() } else { None };
        if (any_acc && end_rate.is_none()) || solves {
            result = result.and_then(|()| self.ws.evaluate_and_keep(self.model, &self.memory, t1, y1));
        }
        if result.is_ok() {
            let qdd = match end_rate {
                Some(f1) => &f1[nq..2 * nq],
                None => &self.ws.qdd[..],
            };
            for j in 0..nm {
                errors[(k - 1) * nm + j] = self.monitored_error(j, t1, y1, qdd);
            }
        }
        self.scratch = s;
        if let Err(e) = result {
            self.monitor_values = errors;
            self.monitor_times = times;
            return Err(e);
        }
        for i in 0..k {
            for j in 0..nm {
                self.monitors[j].observe(at(i), errors[i * nm + j]);
            }
        }
        self.monitor_values = errors;
        self.monitor_times = times;
        if self.monitors.iter().any(|m| m.spec.exact) {
            self.search_extremes(dense)?;
        }
        Ok(())
    }

    /// Locate the extremes of the exact monitors between the samples of the step just observed
    /// (rust/monitor: `Monitor::search_bracket`, `golden_section`).
    fn search_extremes(&mut self, dense: &dyn DenseOutput) -> Result<()> {
        let mut s = std::mem::take(&mut self.scratch);
        let mut result = Ok(());
        for j in 0..self.monitors.len() {
            for sign in [1.0, -1.0] {
                let Some((a, b)) = self.monitors[j].search_bracket(sign) else { continue };
                let found = golden_section(a, b, |t| {
                    dense.eval(t, &mut s);
                    if self.monitors[j].spec.quantity == Quantity::Acceleration || self.monitors[j].solves() {
                        self.ws.evaluate(self.model, &self.memory, t, &s)?;
                    }
                    Ok(sign * self.monitored_error(j, t, &s, &self.ws.qdd))
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

    /// Integrate the work and the wear over the accepted step (t0, t1] and feed the monitors its
    /// points, all with the impact memory the step was integrated with (§10.5, §12).
    pub(super) fn observe_accepted_step(&mut self, t0: f64, t1: f64, y1: &[f64], dense: &dyn DenseOutput) -> Result<()> {
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
        // The bearing summary when asked (bearings.rs): after the monitors, whose KKT solve at
        // t1 it may reuse.
        if !self.bearings.is_empty() {
            self.bearings_step(t1, y1, dense)?;
        }
        Ok(())
    }
}
