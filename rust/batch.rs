//! Batches of independent runs (Monte Carlo samples, parameter sweeps) in parallel with rayon.

use rayon::prelude::*;

use crate::error::Result;
use crate::model::{MechanismDesc, Model};
use crate::simulate::{simulate, RunOutput, RunSettings, StopCheck};

/// Compile and run every description, in parallel on `threads` threads (0: all cores).
/// `settings` holds one entry per description, or a single entry shared by all.
/// Each entry of the result is the run's output or the error that prevented it.
pub fn run_batch(descs: &[MechanismDesc], settings: &[RunSettings], threads: usize, stop: Option<StopCheck<'_>>) -> Vec<Result<RunOutput>> {
    let pick = |k: usize| if settings.len() == 1 { &settings[0] } else { &settings[k] };
    let work = || {
        descs
            .par_iter()
            .enumerate()
            .map(|(k, d)| Model::compile(d).and_then(|m| simulate(&m, pick(k), stop)))
            .collect()
    };
    if threads == 0 {
        work()
    } else {
        match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
            Ok(pool) => pool.install(work),
            Err(_) => work(),
        }
    }
}
