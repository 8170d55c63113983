//! `cargo bench --bench chain`: one right-hand side of a pendulum chain of 8 to 1 024 links,
//! ideal and with two dry clearance joints (the first and the middle joint), to show how the
//! cost grows with size (`tests/common/mod.rs::chain`; plot: `python benches/scaling.py`).

#[path = "../tests/common/mod.rs"]
mod common;

use std::hint::black_box;
use std::time::Duration;

use clearsim::clearance::ImpactMemory;
use clearsim::model::Model;
use clearsim::system::Workspace;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};

pub const SIZES: [usize; 8] = [8, 16, 32, 64, 128, 256, 512, 1024];

fn bench_chain(c: &mut Criterion) {
    for (group, dry) in [("chain_ideal", false), ("chain_dry", true)] {
        let mut g = c.benchmark_group(group);
        g.warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(2)).sample_size(20);
        for n in SIZES {
            let clearance: Vec<usize> = if dry { vec![0, n / 2] } else { vec![] };
            let model = Model::compile(&common::chain(n, &clearance)).unwrap();
            let y = common::initial_state(&model);
            let memory = vec![ImpactMemory::default(); model.clearance.len()];
            let mut ws = Workspace::new(&model);
            g.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| b.iter(|| ws.evaluate(&model, &memory, 0.0, black_box(&y)).unwrap()));
        }
        g.finish();
    }
}

criterion_group!(benches, bench_chain);
criterion_main!(benches);
