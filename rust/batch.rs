//! Batches of independent runs (Monte Carlo samples, parameter sweeps) in parallel with rayon.

use rayon::prelude::*;

use crate::error::Result;
use crate::description::MechanismDesc;
use crate::model::Model;
use crate::simulate::{simulate, RunOutput, RunSettings, StopCheck};

/// Compile and run every description, in parallel on `threads` threads (0: all cores).
/// `settings` holds one entry per description, or a single entry shared by all.
/// Each entry of the result is the run's output or the error that prevented it.
///
/// Each call builds its own thread pool and drops it at the end, never rayon's global pool:
/// a process forked after a batch (a fork-based `ProcessPoolExecutor`) inherits the global
/// pool's bookkeeping but none of its threads, and its first parallel batch would wait for
/// them forever. A pool costs tens of microseconds to build, nothing next to a run.
pub fn run_batch(descs: &[MechanismDesc], settings: &[RunSettings], threads: usize, stop: Option<StopCheck<'_>>) -> Vec<Result<RunOutput>> {
    let pick = |k: usize| if settings.len() == 1 { &settings[0] } else { &settings[k] };
    let one = |k: usize, d: &MechanismDesc| Model::compile(d).and_then(|m| simulate(&m, pick(k), stop));
    let threads = if threads == 0 { std::thread::available_parallelism().map_or(1, |n| n.get()) } else { threads };
    let threads = threads.min(descs.len()).max(1);
    if threads == 1 {
        return descs.iter().enumerate().map(|(k, d)| one(k, d)).collect();
    }
    match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
        Ok(pool) => pool.install(|| descs.par_iter().enumerate().map(|(k, d)| one(k, d)).collect()),
        Err(_) => descs.iter().enumerate().map(|(k, d)| one(k, d)).collect(),
    }
}
