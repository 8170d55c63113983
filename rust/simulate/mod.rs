//! One simulation run ([`simulate`]): assembly, integration of the mechanism as an
//! [`OdeSystem`] ([`MechanismSystem`]: right-hand side, outputs, the step bookkeeping), and
//! what a failed run keeps. The system's other roles live beside it: `observe.rs` (monitors,
//! energy, wear along the steps), `switching.rs` (contact and friction switches, impact memory),
//! `newton.rs` (the implicit methods' Jacobian), `heat.rs` (its rows and columns of the oil
//! temperatures), `lifted.rs` (the same in sparse lifted form, for large mechanisms),
//! `diagnosis.rs` (where a failed run stood), `sections.rs` (Poincaré sections at exact times),
//! `lyapunov.rs` (a shadow run for the largest Lyapunov exponent).

mod bearings;
mod cavitation;
mod diagnosis;
mod heat;
mod lifted;
pub mod lyapunov;
mod newton;
mod observe;
pub mod sections;
mod switching;

use std::time::Instant;

use crate::assembly::assemble;
use crate::clearance::wear::WearBook;
use crate::clearance::{ImpactMemory, JointKinematics};
use crate::constraints::BodyKin;
use crate::energy::EnergyBook;
use crate::error::{Error, Result};
use crate::integrate::{integrate, DenseOutput, LiftedPattern, Method, OdeSystem, Stats};
use crate::model::Model;
use crate::monitor::reference::ReferenceStates;
use crate::monitor::{Monitor, MonitorResult, References};
use crate::record::{Channels, Recording};
use crate::system::Workspace;
use lyapunov::{LyapunovBook, Shadow};
use sections::Sections;

pub use bearings::BearingSummary;
pub use crate::settings::RunSettings;
pub use diagnosis::{failure_hint, MICROMETRE_FILM_RATIO};

/// Polled between steps (about every 64 accepted steps) with the time reached \[s\]; returning
/// `true` interrupts the run ([`Error::Interrupted`]). The Python glue uses it for Ctrl-C and
/// progress bars.
pub type StopCheck<'a> = &'a (dyn Fn(f64) -> bool + Sync);

/// The result of a run, complete or partial.
#[derive(Debug, Clone)]
pub struct RunOutput {
    /// The integrator that ran ([`RunSettings::method_for`]: `auto` resolved for the model).
    pub method: Method,
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
    /// For a stalled lubricated run: what to try ([`failure_hint`]).
    pub hint: Option<String>,
    /// Wear per clearance joint (`None` where it is not modelled).
    pub wear: Vec<Option<WearBook>>,
    /// Evaluations of the clearance joints' force laws over the run, by every caller (a count
    /// of work for the performance fingerprint; [`crate::clearance::force_evaluations`]).
    pub force_evaluations: u64,
    /// The bearing summary per clearance joint when the run asked for it
    /// ([`RunSettings::bearings`]; `None` for a dry joint, or when the run stopped before the
    /// window's start [`RunSettings::bearings_from`]), else empty.
    pub bearings: Vec<Option<BearingSummary>>,
    /// The references the monitors were measured against, at the output times (only with
    /// [`crate::monitor::ReferenceGrid::record`]: for error traces).
    pub references: Vec<ReferenceStates>,
    /// The channels at the section times ([`RunSettings::sections`]), when asked for.
    pub sections: Option<Recording>,
    /// What the Lyapunov shadow found ([`RunSettings::lyapunov`]), when asked for.
    pub lyapunov: Option<LyapunovBook>,
}

/// The model as an [`OdeSystem`]. Its fields by the file that works them: this one (the
/// right-hand side, outputs, step bookkeeping), observe.rs, switching.rs, newton.rs.
pub struct MechanismSystem<'a> {
    pub model: &'a Model,
    pub ws: Workspace,
    /// The outputs' own workspace, so that evaluating them leaves `ws` holding what the steps
    /// evaluated last: an implicit method's f(t1, y1), kept by the observers that evaluate it
    /// first (`Workspace::evaluate_and_keep`), is then not computed twice. Built at the first
    /// output that needs it.
    output_ws: Option<Workspace>,
    pub memory: Vec<ImpactMemory>,
    /// The memory as it was during the step last accepted (what its outputs are evaluated with).
    pub(super) step_memory: Vec<ImpactMemory>,
    pub recording: Recording,
    stop: Option<StopCheck<'a>>,
    /// Start of the run and its wall-time budget \[s\] ([`RunSettings::max_wall_time`]).
    pub budget: Option<(Instant, f64)>,
    accepted: usize,
    /// A state buffer for the dense output's values (observe.rs, switching.rs).
    scratch: Vec<f64>,
    /// Last accepted state (for the diagnosis of a failure).
    pub last_t: f64,
    pub last_y: Vec<f64>,

    // observe.rs
    /// The running extremes of [`RunSettings::monitors`] and their values at the points of the
    /// current step (k × monitors).
    pub monitors: Vec<Monitor>,
    monitor_values: Vec<f64>,
    /// The sample times of the current step.
    monitor_times: Vec<f64>,
    /// Work integrals, when the `energy` channel is recorded.
    energy: Option<EnergyBook>,
    /// Wear of each clearance joint that models it.
    pub wear: Vec<Option<WearBook>>,
    /// [`RunSettings::wear_mark`].
    pub wear_mark: Option<f64>,

    // bearings.rs
    /// The bearing summary of each lubricated joint, when the run asks for it (else empty).
    bearings: Vec<Option<bearings::BearingBook>>,
    /// The start \[s\] of the bearing summary's window while its books wait for it (`None`
    /// once they started: [`RunSettings::bearings_from`]).
    bearings_from: Option<f64>,

    // switching.rs
    /// Each clearance joint's kinematics at the last and the next sample of a step
    /// ([`OdeSystem::switching_point`]).
    switch_prev: Vec<(f64, JointKinematics)>,
    switch_next: Vec<JointKinematics>,
    /// Each clearance joint's kinematics at the step's end.
    switch_end: Vec<JointKinematics>,
    /// The state components the clearance joints' kinematics read (q and q̇ of their bodies):
    /// all that the switch search takes from the dense output.
    switch_components: Vec<usize>,
    /// The state at a load table's corner inside the step.
    scratch2: Vec<f64>,
    /// Penetration \[m\] within which a contact onset or end is grazing and not located as a
    /// switching point ([`crate::clearance::grazing`]): the run's `atol` (0 outside a run).
    pub gap_resolution: f64,

    // sections.rs, lyapunov.rs
    pub sections: Option<Sections>,
    pub shadow: Option<Box<Shadow<'a>>>,

    // newton.rs
    /// Columns `S e_k` of the constrained mobility (m × m, column-major; only the columns of
    /// clearance-joint bodies are filled) and which are current.
    mobility: Vec<f64>,
    mobility_done: Vec<bool>,
    /// The generalised force of one stiff item at the pose and at a probed pose.
    g_base: Vec<f64>,
    g_probe: Vec<f64>,
    /// The state whose mobility columns `mobility` holds (heat.rs reuses them for the border).
    mobility_at: Vec<f64>,
    // lifted.rs
    /// The lifted pattern's layout, built when an implicit method asks for it.
    lifted: Option<Box<lifted::LiftedLayout>>,
}

impl<'a> MechanismSystem<'a> {
    pub fn new(model: &'a Model, channels: Channels, capacity: usize, stop: Option<StopCheck<'a>>) -> Self {
        MechanismSystem {
            model,
            ws: Workspace::new(model),
            output_ws: None,
            memory: vec![ImpactMemory::default(); model.clearance.len()],
            step_memory: vec![ImpactMemory::default(); model.clearance.len()],
            recording: Recording::new(channels, capacity, model),
            stop,
            budget: None,
            monitors: Vec::new(),
            monitor_values: Vec::new(),
            monitor_times: Vec::new(),
            scratch2: Vec::new(),
            energy: channels.energy.then(|| EnergyBook::new(model)),
            wear: model.clearance.iter().enumerate().map(|(j, c)| c.wear.map(|law| WearBook::new(law, c, &model.initial_wear[j]))).collect(),
            wear_mark: None,
            bearings: Vec::new(),
            bearings_from: None,
            accepted: 0,
            scratch: vec![0.0; model.state_dim()],
            switch_prev: vec![(0.0, JointKinematics::default()); model.clearance.len()],
            switch_next: vec![JointKinematics::default(); model.clearance.len()],
            switch_end: vec![JointKinematics::default(); model.clearance.len()],
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
            lifted: None,
            mobility_at: Vec::new(),
            last_t: 0.0,
            last_y: vec![0.0; model.state_dim()],
            gap_resolution: 0.0,
            sections: None,
            shadow: None,
        }
    }

    /// Clearance-joint kinematics of joint `j` at state `y`.
    pub(super) fn joint_kinematics(&self, j: usize, y: &[f64]) -> JointKinematics {
        let n = 3 * self.model.n_bodies();
        self.model.clearance[j].kinematics_with(|b| match b {
            None => BodyKin::GROUND,
            Some(i) => {
                let o = 3 * i as usize;
                BodyKin::new(&y[o..o + 3], &y[n + o..n + o + 3])
            }
        })
    }
}

impl OdeSystem for MechanismSystem<'_> {
    fn dim(&self) -> usize {
        self.model.state_dim()
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<()> {
        self.ws.evaluate(self.model, &self.memory, t, y)?;
        self.ws.derivative(y, dy);
        Ok(())
    }

    /// See switching.rs.
    fn switching_point(&mut self, t0: f64, y0: &[f64], t1: f64, y1: &[f64], dense: &dyn DenseOutput) -> Result<Option<f64>> {
        self.first_switch(t0, y0, t1, y1, dense)
    }

    /// Book the accepted step: work, wear and monitors over it (observe.rs), the impact memory
    /// after it (switching.rs, docs/physics.md §3, P3), the last state, the wall-time budget
    /// and the stop check.
    fn step_accepted(&mut self, t0: f64, y0: &[f64], t1: f64, y1: &[f64], dense: &dyn DenseOutput) -> Result<bool> {
        self.step_memory.clone_from_slice(&self.memory);
        self.observe_accepted_step(t0, t1, y1, dense)?;
        let changed = self.update_contacts(t0, y0, t1, y1, dense)?;
        // The film content of mass-conserving joints moves on (rust/simulate/cavitation.rs):
        // f(t1, y1) changed with it, an explicit method's last stage is stale.
        let moved = self.memory.iter().any(|m| m.film.is_some()) && self.cavitation_step(t0, t1, y1);
        if self.sections.is_some() {
            self.record_sections(t1, dense)?;
        }
        if self.shadow.is_some() {
            self.follow_shadow(t0, t1, dense);
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
        Ok(changed || moved)
    }

    /// See newton.rs.
    fn acceleration_jacobian(&mut self, t: f64, y: &[f64], a_q: &mut [f64], a_v: &mut [f64]) -> Result<bool> {
        let done = self.stiff_jacobian(t, y, a_q, a_v)?;
        if !self.ws.heat_rate.is_empty() {
            // The border (heat.rs) asked next at this state reuses the mobility columns.
            self.mobility_at.clear();
            self.mobility_at.extend_from_slice(y);
        }
        Ok(done)
    }

    fn first_order_states(&self) -> usize {
        self.ws.heat_rate.len()
    }

    /// See heat.rs.
    fn border_jacobian(&mut self, t: f64, y: &[f64], a_z: &mut [f64], z_y: &mut [f64]) -> Result<()> {
        self.heat_jacobian(t, y, a_z, z_y)
    }

    /// See lifted.rs.
    fn lifted_pattern(&mut self) -> Option<LiftedPattern> {
        self.lifted_pattern_of()
    }

    fn lifted_jacobian(&mut self, t: f64, y: &[f64], exact: bool, a0: &mut [f64], k_q: &mut [f64], k_v: &mut [f64]) -> Result<usize> {
        self.lifted_values(t, y, exact, a0, k_q, k_v)
    }

    fn difference_step(&self, j: usize, y: &[f64]) -> f64 {
        self.jacobian_difference_step(j, y)
    }

    fn output(&mut self, t: f64, y: &[f64]) -> Result<()> {
        let ws = self.output_ws.get_or_insert_with(|| Workspace::new(self.model));
        if self.recording.needs_evaluation() {
            // Outputs lie inside the step just accepted: the memory it was integrated with.
            ws.evaluate(self.model, &self.step_memory, t, y)?;
        }
        self.recording.push(t, y, ws, &self.step_memory);
        if !self.ws.heat_rate.is_empty() {
            let temps = self.model.clearance.iter().map(|c| c.heat().map_or(f64::NAN, |h| y[h.state]));
            self.recording.temperature.extend(temps);
        }
        if let Some(book) = &self.energy {
            let e = EnergyBook::stored(self.model, ws);
            self.recording.energy.extend_from_slice(&e);
            self.recording.energy.extend_from_slice(&book.work_at(t));
        }
        Ok(())
    }
}

/// Run a compiled model with validated settings ([`RunSettings::validate`]; a monitor that does
/// not fit the model is an `Err`); a run that fails part-way is an `Ok` whose
/// `error` says why, with everything recorded until then. Its monitors are measured against no
/// reference run (a monitor that names one is an `Err`: [`simulate_measured`]).
pub fn simulate(model: &Model, rs: &RunSettings, stop: Option<StopCheck<'_>>) -> Result<RunOutput> {
    simulate_measured(model, rs, &References::default(), stop)
}

/// [`simulate`] with the reference runs its monitors are measured against (rust/batch.rs makes
/// them): each must have the model's bodies, and a monitor that names a reference not given is
/// an `Err` before the run.
pub fn simulate_measured(model: &Model, rs: &RunSettings, references: &References, stop: Option<StopCheck<'_>>) -> Result<RunOutput> {
    rs.validate_for(model)?;
    let evaluations_before = crate::clearance::force_evaluations();
    for run in [&references.own_ideal, &references.nominal].into_iter().flatten() {
        crate::monitor::reference::check_bodies(run, &model.body_names)?;
    }
    let monitors = rs.monitors.iter().enumerate().map(|(i, spec)| Monitor::new(i, spec.clone(), references)).collect::<Result<Vec<_>>>()?;
    let method = rs.method_for(model);
    let start = Instant::now();
    let (q0, qd0) = match assemble(model, rs.t0) {
        Ok(v) => v,
        Err(e) => {
            return Ok(RunOutput {
                method,
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
                hint: None,
                force_evaluations: crate::clearance::force_evaluations() - evaluations_before,
                bearings: Vec::new(),
                references: Vec::new(),
                sections: None,
                lyapunov: None,
            })
        }
    };
    let y0 = model.initial_state(&q0, &qd0);
    let t_out: Vec<f64> = rs.t_out.iter().copied().filter(|t| *t >= rs.t0 && *t <= rs.t_end).collect();
    let mut sys = MechanismSystem::new(model, rs.channels, t_out.len(), stop);
    sys.budget = rs.max_wall_time.map(|b| (start, b));
    sys.gap_resolution = rs.ode.atol;
    sys.cavitation_start(rs.t0);
    sys.monitors = monitors;
    if !sys.monitors.is_empty() {
        sys.observe_start(rs.t0, &y0)?;
    }
    sys.energy_start(rs.t0, &y0)?;
    sys.wear_mark = rs.wear_mark;
    sys.wear_start(rs.t0, &y0);
    if rs.bearings {
        sys.bearings = vec![None; model.clearance.len()];
        match rs.bearings_from.filter(|w| *w > rs.t0) {
            Some(w) => sys.bearings_from = Some(w),
            None => sys.bearings_start(rs.t0, &y0),
        }
    }
    if let Some(spec) = &rs.sections {
        sys.sections = Some(Sections::new(spec, rs.t0, rs.t_end, rs.channels, model));
        sys.sections_start(rs.t0, &y0)?;
    }
    if let Some(spec) = rs.lyapunov {
        let mut shadow = Shadow::new(model, spec, method, rs.ode.clone());
        shadow.sys.gap_resolution = rs.ode.atol;
        if spec.start == rs.t0 {
            shadow.start_at(rs.t0, &y0, &sys.memory);
        }
        sys.shadow = Some(Box::new(shadow));
    }
    sys.last_t = rs.t0;
    sys.last_y.copy_from_slice(&y0);
    let (stats, error, failure_joint) = match integrate(&mut sys, method, rs.t0, &y0, rs.t_end, &t_out, &rs.ode) {
        Ok(s) => (s, None, None),
        Err((e, s)) => {
            let e = sys.lock_up(&e).unwrap_or(e);
            let detail = sys.diagnosis();
            let joint = sys.worst_joint().map(|(j, k)| (model.clearance[j].name.clone(), k.eps));
            (s, Some(e.with_detail(&detail)), joint)
        }
    };
    let hint = error.as_ref().and_then(|e| failure_hint(model, e, failure_joint.as_ref()));
    let mut max_violation = [0.0f64; 2];
    for v in sys.recording.violation.chunks(2) {
        max_violation[0] = max_violation[0].max(v[0]);
        max_violation[1] = max_violation[1].max(v[1]);
    }
    // The references at the output times, for error traces.
    let recorded = match rs.reference {
        Some(grid) if grid.record => [&references.own_ideal, &references.nominal].into_iter().flatten().map(|r| r.states_at(&sys.recording.t)).collect(),
        _ => Vec::new(),
    };
    Ok(RunOutput {
        method,
        references: recorded,
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
        hint,
        force_evaluations: crate::clearance::force_evaluations() - evaluations_before,
        bearings: sys.bearings.iter().map(|b| b.map(|b| b.summary)).collect(),
        sections: sys.sections.map(|s| s.recording),
        lyapunov: sys.shadow.map(|s| s.book),
    })
}
