//! Batches of independent runs (Monte Carlo samples, parameter sweeps) in parallel with rayon,
//! with the reference runs their monitors are measured against (rust/monitor/reference.rs): a
//! sample's settings name its reference (its own ideal twin, or the nominal design's ideal, the
//! batch's one `nominal` description) and its grid; the batch idealises each description
//! ([`MechanismDesc::idealized`]), runs each distinct ideal run once (structural equality of the
//! ideal description and of the run's settings, no text key) and shares it between the samples
//! measured against it. A reference is run when its first sample needs it and dropped when its
//! last is done, so a batch whose every sample has its own (a random drive speed) holds about
//! one per thread.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::hash::{Hash, Hasher};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use rayon::prelude::*;

use crate::description::MechanismDesc;
use crate::error::{Error, Result};
use crate::integrate::Settings;
use crate::model::Model;
use crate::monitor::reference::same_bodies;
use crate::monitor::{ReferenceGrid, ReferenceOf, ReferenceRun, References};
use crate::record::Channels;
use crate::simulate::{simulate, simulate_measured, RunOutput, RunSettings, StopCheck};

/// Compile and run every description, in parallel on `threads` threads (0: all cores), each
/// measured against the reference runs its settings' monitors name (`nominal`: the nominal
/// design's description, which the batch idealises, for monitors measured against it).
/// `settings` holds one entry per description, or a single entry shared by all.
/// Each entry of the result is the run's output or the error that prevented it (a sample whose
/// reference run failed: [`Error::Reference`], the sample not run).
///
/// Each call builds its own thread pool and drops it at the end, never rayon's global pool:
/// a process forked after a batch (a fork-based `ProcessPoolExecutor`) inherits the global
/// pool's bookkeeping but none of its threads, and its first parallel batch would wait for
/// them forever. A pool costs tens of microseconds to build, nothing next to a run.
pub fn run_batch(descs: &[MechanismDesc], settings: &[RunSettings], nominal: Option<&MechanismDesc>, threads: usize, stop: Option<StopCheck<'_>>) -> Vec<Result<RunOutput>> {
    let pick = |k: usize| if settings.len() == 1 { &settings[0] } else { &settings[k] };
    let plan = Plan::new(descs.len(), |k| (&descs[k], pick(k)), nominal);
    let one = |k: usize| {
        let out = plan.references(k, stop).and_then(|refs| Model::compile(&descs[k]).and_then(|m| simulate_measured(&m, pick(k), &refs, stop)));
        plan.release(k);
        (k, out)
    };
    let threads = if threads == 0 { std::thread::available_parallelism().map_or(1, |n| n.get()) } else { threads };
    let threads = threads.min(descs.len()).max(1);
    let pairs: Vec<(usize, Result<RunOutput>)> = if threads == 1 {
        plan.order.iter().map(|&k| one(k)).collect()
    } else {
        match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
            Ok(pool) => pool.install(|| plan.order.par_iter().map(|&k| one(k)).collect()),
            Err(_) => plan.order.iter().map(|&k| one(k)).collect(),
        }
    };
    let mut out: Vec<Option<Result<RunOutput>>> = (0..descs.len()).map(|_| None).collect();
    for (k, r) in pairs {
        out[k] = Some(r);
    }
    out.into_iter().map(|r| r.expect("every sample runs once")).collect()
}

/// Run one compiled model with `settings`, measured against the reference runs its monitors
/// name (made here from its description `desc` and `nominal`): [`run_batch`] for one run.
pub fn run_one(model: &Model, desc: &MechanismDesc, settings: &RunSettings, nominal: Option<&MechanismDesc>, stop: Option<StopCheck<'_>>) -> Result<RunOutput> {
    let plan = Plan::new(1, |_| (desc, settings), nominal);
    let refs = plan.references(0, stop)?;
    simulate_measured(model, settings, &refs, stop)
}

/// Run a compiled model with `settings` ([`run_one`], its description `desc`) and, beside it on
/// a second thread, its ideal twin `ideal` compiled here and run with `ideal_settings`: a run
/// and the twin it is compared with (`clearsim.Mechanism.simulate_with_ideal`), the model's
/// pose assembled once (when it was compiled) and the twin's once, the numbers those of
/// [`run_batch`] on the two descriptions.
pub fn run_with_twin(model: &Model, desc: &MechanismDesc, settings: &RunSettings, ideal: &MechanismDesc, ideal_settings: &RunSettings, stop: Option<StopCheck<'_>>) -> (Result<RunOutput>, Result<RunOutput>) {
    std::thread::scope(|scope| {
        let twin = scope.spawn(|| Model::compile(ideal).and_then(|m| simulate(&m, ideal_settings, stop)));
        let own = run_one(model, desc, settings, None, stop);
        (own, twin.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic)))
    })
}

/// How many reference runs [`run_batch`] makes for these runs: one per distinct ideal mechanism
/// and run settings.
pub fn reference_runs(descs: &[MechanismDesc], settings: &[RunSettings], nominal: Option<&MechanismDesc>) -> usize {
    let pick = |k: usize| if settings.len() == 1 { &settings[0] } else { &settings[k] };
    Plan::new(descs.len(), |k| (&descs[k], pick(k)), nominal).slots.len()
}

/// The settings of the reference run for a sample run with `rs`: the same integrator, start,
/// step limits and budgets at a tenth of its tolerances, to the grid's end, storing states and
/// accelerations on the grid, with no monitors of its own.
pub fn reference_settings(rs: &RunSettings, grid: &ReferenceGrid) -> RunSettings {
    let ode = Settings { rtol: rs.ode.rtol / 10.0, atol: rs.ode.atol / 10.0, ..rs.ode };
    RunSettings {
        channels: Channels { states: true, accelerations: true, reactions: false, joints: false, violation: false, energy: false, film: false },
        max_wall_time: rs.max_wall_time,
        ..RunSettings::plain(rs.method, ode, rs.t0, grid.t_end, grid.times())
    }
}

/// What a reference run's result depends on besides its mechanism (its grid is expanded only
/// when it runs).
#[derive(Debug, Clone, PartialEq)]
struct RunKey {
    settings: RunSettings,
    grid: ReferenceGrid,
}

/// One distinct reference run of the batch, run on first use and dropped after its last.
struct Slot {
    of: ReferenceOf,
    ideal: MechanismDesc,
    key: RunKey,
    state: Mutex<SlotState>,
    users: AtomicUsize,
}

enum SlotState {
    Pending,
    Ready(Result<Arc<ReferenceRun>>),
    Dropped,
}

/// The batch's distinct reference runs, which of them each sample needs, and an order of the
/// samples that keeps those sharing a reference together.
struct Plan {
    slots: Vec<Slot>,
    /// Per sample: its slots, or why it cannot have them.
    needs: Vec<Result<Vec<usize>>>,
    order: Vec<usize>,
}

impl Plan {
    fn new<'a>(n: usize, sample: impl Fn(usize) -> (&'a MechanismDesc, &'a RunSettings), nominal: Option<&MechanismDesc>) -> Plan {
        let nominal_ideal = nominal.map(MechanismDesc::idealized);
        let mut slots: Vec<Slot> = Vec::new();
        let mut index: HashMap<u64, Vec<usize>> = HashMap::new();
        let mut needs = Vec::with_capacity(n);
        for k in 0..n {
            let (desc, rs) = sample(k);
            let mut mine = Vec::new();
            let mut need = Ok(());
            for (i, spec) in rs.monitors.iter().enumerate() {
                let Some(of) = spec.reference else { continue };
                let Some(grid) = rs.reference else {
                    need = Err(Error::invalid(format!("monitors[{i}].reference"), of.name(), "the settings give no reference grid"));
                    break;
                };
                let ideal = match of {
                    ReferenceOf::OwnIdeal => desc.idealized(),
                    ReferenceOf::Nominal => match &nominal_ideal {
                        Some(d) => {
                            // Named before anything runs: the nominal's bodies must be the sample's.
                            if let Err(e) = same_bodies(of, &body_names(d), &body_names(desc)) {
                                need = Err(e);
                                break;
                            }
                            d.clone()
                        }
                        None => {
                            need = Err(Error::invalid(format!("monitors[{i}].reference"), of.name(), "the batch was given no nominal mechanism"));
                            break;
                        }
                    },
                };
                let key = RunKey { settings: reference_settings_key(rs), grid };
                let h = structural_hash(&ideal, &key);
                let bucket = index.entry(h).or_default();
                let found = bucket.iter().copied().find(|&s| slots[s].of == of && slots[s].key == key && slots[s].ideal == ideal);
                let s = found.unwrap_or_else(|| {
                    slots.push(Slot { of, ideal, key, state: Mutex::new(SlotState::Pending), users: AtomicUsize::new(0) });
                    bucket.push(slots.len() - 1);
                    slots.len() - 1
                });
                if !mine.contains(&s) {
                    mine.push(s);
                }
            }
            needs.push(need.map(|()| {
                for &s in &mine {
                    slots[s].users.fetch_add(1, Ordering::Relaxed);
                }
                mine
            }));
        }
        // Samples sharing a first reference next to each other (stable: the given order within).
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by_key(|&k| needs[k].as_ref().ok().and_then(|m| m.first().copied()).unwrap_or(usize::MAX));
        Plan { slots, needs, order }
    }

    /// Sample `k`'s reference runs, each run on first use.
    fn references(&self, k: usize, stop: Option<StopCheck<'_>>) -> Result<References> {
        let mut refs = References::default();
        for &s in self.needs[k].as_ref().map_err(Clone::clone)? {
            let slot = &self.slots[s];
            let mut state = slot.state.lock().unwrap_or_else(|p| p.into_inner());
            if let SlotState::Pending = *state {
                *state = SlotState::Ready(run_reference(slot, stop));
            }
            match &*state {
                SlotState::Ready(Ok(run)) => refs.set(Arc::clone(run)),
                SlotState::Ready(Err(e)) => return Err(e.clone()),
                _ => unreachable!("a reference is dropped only after its last sample"),
            }
        }
        Ok(refs)
    }

    /// Sample `k` is done: drop the references no other sample needs.
    fn release(&self, k: usize) {
        for &s in self.needs[k].as_ref().map_or(&[][..], |v| &v[..]) {
            let slot = &self.slots[s];
            if slot.users.fetch_sub(1, Ordering::AcqRel) == 1 {
                *slot.state.lock().unwrap_or_else(|p| p.into_inner()) = SlotState::Dropped;
            }
        }
    }
}

/// A description's body names in the model's order (its coordinates: 3 a body).
fn body_names(d: &MechanismDesc) -> Vec<String> {
    d.bodies.iter().map(|b| b.name.clone()).collect()
}

/// The settings of a sample that its reference run depends on ([`reference_settings`] without
/// the grid expanded).
fn reference_settings_key(rs: &RunSettings) -> RunSettings {
    RunSettings { max_wall_time: rs.max_wall_time, ..RunSettings::plain(rs.method, rs.ode, rs.t0, rs.t_end, Vec::new()) }
}

/// A hash of the structure and every value of an ideal description and its run: fed from their
/// derived `Debug` forms, which write every field and every float so that it reads back exactly
/// (equal values hash equal; `PartialEq` then confirms a match).
fn structural_hash(ideal: &MechanismDesc, key: &RunKey) -> u64 {
    struct Feed<'a>(&'a mut std::collections::hash_map::DefaultHasher);
    impl std::fmt::Write for Feed<'_> {
        fn write_str(&mut self, s: &str) -> std::fmt::Result {
            s.hash(self.0);
            Ok(())
        }
    }
    let mut h = std::collections::hash_map::DefaultHasher::new();
    let _ = write!(Feed(&mut h), "{ideal:?}{key:?}");
    h.finish()
}

/// Run a reference: its ideal mechanism with [`reference_settings`]; a failure (or a run that
/// stopped early) is the samples' [`Error::Reference`].
fn run_reference(slot: &Slot, stop: Option<StopCheck<'_>>) -> Result<Arc<ReferenceRun>> {
    let wrap = |e: Error| Error::Reference { what: slot.of.what(), cause: Box::new(e) };
    let model = Model::compile(&slot.ideal).map_err(wrap)?;
    let rs = reference_settings(&slot.key.settings, &slot.key.grid);
    let out = simulate(&model, &rs, stop).map_err(wrap)?;
    if let Some(e) = out.error {
        return Err(wrap(e));
    }
    let rec = out.recording;
    Ok(Arc::new(ReferenceRun::new(slot.of, model.body_names.clone(), rec.t, rec.q, rec.qd, rec.qdd)))
}
