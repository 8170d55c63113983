//! `cargo bench --bench rhs`: one right-hand side, RK45 steps and one full cycle of the nine-bar
//! and the slider-crank, and for the lubricated ones a RADAU5 cycle and one Newton matrix (ideal, 2 dry, 2 lubricated joints; the models are the Python ones,
//! loaded from `tests/data/*.json`).
//!
//! The state of the RHS and step benches is taken a tenth of a cycle into a run, so that the
//! clearance joints sit where they spend the run (film at ε ≈ 0.9, contact, free flight), not at
//! the centred start.

#[path = "../tests/common/mod.rs"]
mod common;

use std::hint::black_box;
use std::time::Duration;

use clearsim::clearance::ImpactMemory;
use clearsim::integrate::{integrate, Method, OdeSystem, Settings};
use clearsim::record::Channels;
use clearsim::simulate::{simulate, MechanismSystem};
use clearsim::system::Workspace;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};

const MODELS: [&str; 7] = [
    "nine_bar_ideal",
    "nine_bar_dry",
    "nine_bar_lubricated",
    "nine_bar_lubricated_mu004",
    "slider_crank_ideal",
    "slider_crank_dry",
    "slider_crank_lubricated",
];

/// (t, y, impact memory, mean accepted step of RK45 at rtol 1e-6) a tenth of a cycle in.
fn mid_state(model: &clearsim::model::Model, name: &str) -> (f64, Vec<f64>, Vec<ImpactMemory>, f64) {
    let y0 = common::initial_state(model);
    let t = 0.1 * common::cycle(name);
    let mut sys = MechanismSystem::new(model, Channels::default(), 0, None);
    let s = Settings { rtol: 1e-6, atol: 1e-9, ..Settings::default() };
    let st = integrate(&mut sys, Method::Rk45, 0.0, &y0, t, &[], &s).unwrap();
    (t, sys.last_y.clone(), sys.memory.clone(), t / st.steps_accepted as f64)
}

fn bench_rhs(c: &mut Criterion) {
    let mut g = c.benchmark_group("rhs");
    for name in MODELS {
        let model = common::model(name);
        let (t, y, memory, _) = mid_state(&model, name);
        let mut ws = Workspace::new(&model);
        g.bench_function(name, |b| b.iter(|| ws.evaluate(&model, &memory, black_box(t), black_box(&y)).unwrap()));
    }
    g.finish();
}

/// 100 RK45 steps of the mean accepted size (fixed: no rejections, FSAL reused); the reported
/// time is per step.
fn bench_steps(c: &mut Criterion) {
    let mut g = c.benchmark_group("rk45_step");
    const STEPS: usize = 100;
    g.throughput(Throughput::Elements(STEPS as u64));
    for name in MODELS {
        let model = common::model(name);
        let (t, y, memory, h_mean) = mid_state(&model, name);
        // Fixed steps (every step accepted) of a tenth of the run's mean step: a step costs its
        // six right-hand sides whatever its size, and the mean step itself, forced through a
        // contact, can drive a journal through the wall (μ = 0.04: "penetration too deep").
        let h = 0.1 * h_mean;
        let s = Settings { rtol: 1e6, atol: 1e6, h0: Some(h), h_max: h, ..Settings::default() };
        let mut sys = MechanismSystem::new(&model, Channels::default(), 0, None);
        g.bench_function(name, |b| {
            b.iter(|| {
                sys.memory.clone_from(&memory);
                integrate(&mut sys, Method::Rk45, t, &y, t + STEPS as f64 * h * (1.0 - 1e-9), &[], &s).unwrap()
            })
        });
    }
    g.finish();
}

/// One full crank cycle of each model with `method` at rtol 1e-6, atol 1e-9 and 1000 outputs
/// (assembly and recording included), as `Mechanism.simulate` runs it.
fn bench_cycles(c: &mut Criterion, group: &str, method: Method, models: &[&str], seconds: u64) {
    let mut g = c.benchmark_group(group);
    g.sample_size(10).measurement_time(Duration::from_secs(seconds));
    for &name in models {
        let model = common::model(name);
        let rs = common::bench_run(method, common::cycle(name), 1000);
        g.bench_function(name, |b| {
            b.iter(|| {
                let out = simulate(&model, &rs, None).unwrap();
                assert!(out.error.is_none());
                out.stats
            })
        });
    }
    g.finish();
}

fn bench_cycle(c: &mut Criterion) {
    bench_cycles(c, "cycle_rk45", Method::Rk45, &MODELS, 8);
}

/// The lubricated models, whose film makes RADAU5 the method of choice: one cycle at rtol 1e-6
/// (as `bench_cycle`), and one structured Newton matrix (`acceleration_jacobian`: the clearance
/// joints' force derivatives and the mobility columns of their bodies).
fn bench_radau(c: &mut Criterion) {
    let lubricated = ["nine_bar_lubricated", "nine_bar_lubricated_mu004", "slider_crank_lubricated"];
    bench_cycles(c, "cycle_radau", Method::Radau, &lubricated, 5);
    let mut g = c.benchmark_group("newton_matrix");
    for name in lubricated {
        let model = common::model(name);
        let (t, y, memory, _) = mid_state(&model, name);
        let mut sys = MechanismSystem::new(&model, Channels::default(), 0, None);
        sys.memory = memory;
        let m = y.len() / 2;
        let (mut w_q, mut w_v) = (vec![0.0; m * m], vec![0.0; m * m]);
        g.bench_function(name, |b| b.iter(|| sys.acceleration_jacobian(black_box(t), black_box(&y), &mut w_q, &mut w_v).unwrap()));
    }
    g.finish();
}

criterion_group!(benches, bench_rhs, bench_steps, bench_cycle, bench_radau);
criterion_main!(benches);
