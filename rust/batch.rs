//! Batches of independent runs (Monte Carlo samples, parameter sweeps) in parallel with rayon.

use rayon::prelude::*;

use crate::error::Result;
use crate::model::{MechanismDesc, Model};
use crate::simulate::{simulate, RunOutput, RunSettings};

/// Compile and run every description with the same settings, in parallel on `threads` threads
/// (0: all cores). Each entry is the run's output or the error that prevented it.
pub fn run_batch(descs: &[MechanismDesc], rs: &RunSettings, threads: usize, stop: Option<&(dyn Fn() -> bool + Sync)>) -> Vec<Result<RunOutput>> {
    let work = || descs.par_iter().map(|d| Model::compile(d).and_then(|m| simulate(&m, rs, stop))).collect();
    if threads == 0 {
        work()
    } else {
        match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
            Ok(pool) => pool.install(work),
            Err(_) => work(),
        }
    }
}
