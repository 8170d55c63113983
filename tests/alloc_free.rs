//! The hot path allocates nothing per step (rust/system.rs: the workspace is allocated once per
//! run; a step allocates nothing): a counting global allocator sees the same number of allocations
//! for N and 2N right-hand sides / steps of the nine-bar with dry and lubricated joints.

mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use clearsim::clearance::ImpactMemory;
use clearsim::integrate::{integrate, Method, Settings};
use clearsim::record::Channels;
use clearsim::simulate::MechanismSystem;
use clearsim::system::Workspace;

struct Counting;

thread_local! {
    /// Allocations made by this thread (the test harness allocates on other threads).
    static ALLOCS: Cell<usize> = const { Cell::new(0) };
}

fn bump() {
    ALLOCS.with(|c| c.set(c.get() + 1));
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        bump();
        unsafe { System.alloc(l) }
    }
    unsafe fn alloc_zeroed(&self, l: Layout) -> *mut u8 {
        bump();
        unsafe { System.alloc_zeroed(l) }
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, n: usize) -> *mut u8 {
        bump();
        unsafe { System.realloc(p, l, n) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        unsafe { System.dealloc(p, l) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn count<R>(f: impl FnOnce() -> R) -> (usize, R) {
    let before = ALLOCS.with(Cell::get);
    let r = f();
    (ALLOCS.with(Cell::get) - before, r)
}

const MODELS: [&str; 4] = ["nine_bar_dry", "nine_bar_lubricated", "nine_bar_lubricated_mu004", "slider_crank_lubricated"];

#[test]
fn right_hand_side_allocates_nothing() {
    for name in MODELS {
        let model = common::model(name);
        let y0 = common::initial_state(&model);
        let mut ws = Workspace::new(&model);
        let memory = vec![ImpactMemory::default(); model.clearance.len()];
        let calls = |k: usize, ws: &mut Workspace| {
            let mut y = y0.clone();
            count(|| {
                for i in 0..k {
                    // Vary the state so contact, film and transition branches are all visited.
                    for (j, q) in y.iter_mut().enumerate().take(3 * model.n_bodies()) {
                        *q = y0[j] + 1e-4 * ((i * 7 + j) as f64).sin();
                    }
                    ws.evaluate(&model, &memory, 1e-3 * i as f64, &y).unwrap();
                }
            })
            .0
        };
        let (a, b) = (calls(100, &mut ws), calls(200, &mut ws));
        assert_eq!(a, b, "{name}: 100 rhs → {a} allocations, 200 rhs → {b}");
        assert_eq!(a, 0, "{name}: the rhs allocates");
    }
}

/// The sparse (row-by-row) KKT factor of a large mechanism allocates nothing either.
#[test]
fn large_chain_right_hand_side_allocates_nothing() {
    let model = clearsim::model::Model::compile(&common::chain(300, &[0, 150])).unwrap();
    assert!(model.rows > 500, "a large system");
    let y = common::initial_state(&model);
    let mut ws = Workspace::new(&model);
    let memory = vec![ImpactMemory::default(); model.clearance.len()];
    ws.evaluate(&model, &memory, 0.0, &y).unwrap();
    let (a, _) = count(|| {
        for i in 0..50 {
            ws.evaluate(&model, &memory, 1e-3 * i as f64, &y).unwrap();
        }
    });
    assert_eq!(a, 0, "the large-chain rhs allocates");
}

/// Allocations of a whole run (workspace set-up included) of `steps` steps of `method`.
fn run_allocs(name: &str, method: Method, t_end: f64) -> (usize, usize) {
    run_model_allocs(&common::model(name), method, t_end)
}

fn run_model_allocs(model: &clearsim::model::Model, method: Method, t_end: f64) -> (usize, usize) {
    let y0 = common::initial_state(model);
    let s = Settings { rtol: 1e-6, atol: 1e-9, ..Settings::default() };
    let t_out = [t_end];
    let mut sys = MechanismSystem::new(model, Channels::default(), t_out.len(), None);
    let (n, st) = count(|| integrate(&mut sys, method, 0.0, &y0, t_end, &t_out, &s).unwrap());
    (n, st.steps_accepted + st.steps_rejected)
}

#[test]
fn integration_steps_allocate_nothing() {
    for name in MODELS {
        let cycle = if name.starts_with("nine") { common::NINE_BAR_CYCLE } else { common::SLIDER_CRANK_CYCLE };
        for (method, t) in [
            (Method::Rk4 { step: 2e-5 }, 0.02),
            (Method::Rk45, 0.1 * cycle),
            // (DOP853 fails with NonFinite on the dry nine-bar at t ≈ 0.028 s: stay before it.)
            (Method::Dop853, if name.starts_with("nine") { 0.03 } else { 0.2 } * cycle),
            (Method::Rodas4, 0.05 * cycle),
            (Method::Radau, 0.1 * cycle),
        ] {
            // Warm-up: one-time process-wide initialisations (e.g. faer's CPU-feature cache)
            // are not per-step allocations.
            run_allocs(name, method, t);
            let (a, sa) = run_allocs(name, method, t);
            let (b, sb) = run_allocs(name, method, 2.0 * t);
            assert!(sb > sa + 10, "{name} {method:?}: {sa} vs {sb} steps");
            assert_eq!(a, b, "{name} {method:?}: {sa} steps → {a} allocations, {sb} steps → {b}");
        }
    }
}

/// The implicit methods on a large mechanism take the lifted sparse Newton matrices
/// (rust/integrate/lifted.rs; a 40-link chain with a lubricated joint at every 4th): their
/// refactorisations allocate nothing per step either.
#[test]
fn large_chain_implicit_steps_allocate_nothing() {
    let model = clearsim::model::Model::compile(&common::lubricated_chain(40, 4)).unwrap();
    for (method, t) in [(Method::Radau, 0.004), (Method::Rodas4, 0.0005)] {
        run_model_allocs(&model, method, t);
        let (a, sa) = run_model_allocs(&model, method, t);
        let (b, sb) = run_model_allocs(&model, method, 2.0 * t);
        assert!(sb > sa + 10, "{method:?}: {sa} vs {sb} steps");
        assert_eq!(a, b, "{method:?}: {sa} steps → {a} allocations, {sb} steps → {b}");
    }
}
