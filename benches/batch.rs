//! `cargo bench --bench batch`: throughput of `run_batch` (rayon) on 1 and 2 threads: 8 runs of
//! a quarter cycle of the lubricated nine-bar (0.5 mm), viscosities spread ±10 % like a Monte
//! Carlo sample. Criterion reports runs per second; the scaling is the ratio of the two.

#[path = "../tests/common/mod.rs"]
mod common;

use std::time::Duration;

use clearsim::batch::run_batch;
use clearsim::integrate::Method;
use clearsim::description::{ClearanceModelDesc, ViscosityDesc};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};

const RUNS: usize = 8;

fn bench_batch(c: &mut Criterion) {
    let base = common::description("nine_bar_lubricated");
    let descs: Vec<_> = (0..RUNS)
        .map(|k| {
            let mut d = base.clone();
            for cj in &mut d.clearance_joints {
                if let ClearanceModelDesc::Lubricated(l) = &mut cj.model {
                    if let ViscosityDesc::Constant(mu) = &mut l.viscosity {
                        *mu *= 0.9 + 0.2 * k as f64 / (RUNS - 1) as f64;
                    }
                }
            }
            d
        })
        .collect();
    let t_end = 0.25 * common::NINE_BAR_CYCLE;
    let rs = common::bench_run(Method::Rk45, t_end, 250);
    let mut g = c.benchmark_group("batch_nine_bar_lubricated");
    g.sample_size(10).measurement_time(Duration::from_secs(10));
    g.throughput(Throughput::Elements(RUNS as u64));
    for threads in [1usize, 2] {
        g.bench_with_input(BenchmarkId::from_parameter(format!("{threads}_threads")), &threads, |b, &th| {
            b.iter(|| {
                let outs = run_batch(&descs, std::slice::from_ref(&rs), None, th, None);
                assert!(outs.iter().all(|o| o.as_ref().is_ok_and(|o| o.error.is_none())));
                outs.len()
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench_batch);
criterion_main!(benches);
