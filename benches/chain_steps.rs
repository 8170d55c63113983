//! `cargo bench --bench chain_steps [-- radau|rodas4 [sizes…]]`: the implicit methods' cost per
//! step against mechanism size, on the pendulum chain of `tests/common/mod.rs` with a lubricated
//! clearance joint at every 4th joint (`common::lubricated_chain`), N = 20 … 320 links, 10 ms of
//! its fall at the benches' tolerances (rtol 1e-6, atol 1e-9). Prints per size the steps, the
//! right-hand sides and Newton matrices per step and the CPU time per step (this thread's, best of
//! three runs, one where a run takes over 2 s; `CHAIN_RUNS=1` for one run each, as for counting
//! instructions with `valgrind --tool=cachegrind --cache-sim=no`). The issue-37 target: N = 160 within 16×
//! the N = 20 cost.
//! Where the time goes: `perf record -F 5000 <binary> radau 160` and `perf report --no-children`.
//! An argument that is not a number is read as a mechanism description in JSON (the roller
//! chain: `python benches/roller_chain.py --json roller_chain.json`), run for 5 ms; its line
//! gives its number of bodies for N.

#[path = "../tests/common/mod.rs"]
mod common;

use clearsim::integrate::Method;
use clearsim::model::Model;
use clearsim::simulate::simulate;

/// Simulated time of each run [s].
const T_END: f64 = 0.02;

/// This thread's CPU time [s] (`CLOCK_THREAD_CPUTIME_ID`; on a shared machine wall time counts
/// the waits for a core).
#[cfg(target_os = "linux")]
fn cpu_time() -> f64 {
    #[repr(C)]
    struct Timespec {
        sec: i64,
        nsec: i64,
    }
    extern "C" {
        fn clock_gettime(clock: i32, ts: *mut Timespec) -> i32;
    }
    let mut ts = Timespec { sec: 0, nsec: 0 };
    // SAFETY: clock_gettime writes one timespec to the pointer given; 3 = CLOCK_THREAD_CPUTIME_ID.
    unsafe { clock_gettime(3, &mut ts) };
    ts.sec as f64 + ts.nsec as f64 * 1e-9
}

/// Elsewhere: the wall time since the first call.
#[cfg(not(target_os = "linux"))]
fn cpu_time() -> f64 {
    static START: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();
    START.get_or_init(std::time::Instant::now).elapsed().as_secs_f64()
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with("--")).collect();
    let (name, method) = match args.first().map_or("radau", String::as_str) {
        "radau" => ("radau", Method::Radau),
        "rodas4" => ("rodas4", Method::Rodas4),
        other => {
            eprintln!("unknown method {other:?}: radau or rodas4");
            std::process::exit(2);
        }
    };
    // Sizes of the chain, or a description in JSON (a scene's `m.description()`, as
    // `benches/roller_chain.py --json` writes it), run for 5 ms.
    let items: Vec<String> = if args.len() > 1 { args[1..].to_vec() } else { ["20", "40", "80", "160", "320"].map(String::from).to_vec() };
    // CHAIN_RUNS=1 for instruction counts (valgrind --tool=cachegrind): one run per size.
    let runs: usize = std::env::var("CHAIN_RUNS").ok().and_then(|v| v.parse().ok()).unwrap_or(3);
    println!("{name}, chain with a lubricated joint every 4th link, {} ms", T_END * 1e3);
    println!("{:>5} {:>7} {:>9} {:>10} {:>9} {:>12}", "N", "steps", "rejected", "rhs/step", "jac/step", "µs/step");
    let mut first = None;
    for item in items {
        let (n, model, rs) = match item.parse::<usize>() {
            Ok(n) => (n, Model::compile(&common::lubricated_chain(n, 4)).unwrap(), common::bench_run(method, T_END, 10)),
            Err(_) => {
                let text = std::fs::read_to_string(&item).unwrap_or_else(|e| panic!("{item}: {e}"));
                let model = Model::compile(&clearsim::description::from_json(&text).unwrap()).unwrap();
                (model.n_bodies(), model, common::bench_run(method, 0.005, 10))
            }
        };
        let mut best = f64::INFINITY;
        let mut stats = None;
        for _ in 0..runs {
            let t0 = cpu_time();
            let out = simulate(&model, &rs, None).expect("a valid run");
            let wall = cpu_time() - t0;
            if let Some(e) = &out.error {
                eprintln!("N = {n}: the run stopped: {e}");
                std::process::exit(1);
            }
            best = best.min(wall);
            stats = Some(out.stats);
            if wall > 2.0 {
                break;
            }
        }
        let s = stats.unwrap();
        let steps = (s.steps_accepted + s.steps_rejected) as f64;
        let per_step = best / steps * 1e6;
        let base = *first.get_or_insert((n, per_step));
        println!(
            "{n:>5} {:>7} {:>9} {:>10.1} {:>9.2} {:>12.1}   ({:.1}× N = {})",
            s.steps_accepted,
            s.steps_rejected,
            s.rhs_evals as f64 / steps,
            s.jacobians as f64 / steps,
            per_step,
            per_step / base.1,
            base.0
        );
    }
}
