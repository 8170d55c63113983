//! One cycle of one model, once, for a deterministic A/B of a code change by instruction count
//! (wall time on a shared machine swings by ±20 %; the instructions executed do not):
//!
//! ```text
//! cargo bench --bench one_cycle --no-run          # prints the binary's path
//! valgrind --tool=cachegrind --cache-sim=no <binary> nine_bar_lubricated radau
//! ```
//!
//! Arguments: a model of `tests/data/*.json` (default `nine_bar_dry`), a method, `rk45`
//! (default), `dop853`, `radau` or `rodas4`, and optionally a mode: `bearings`, `film_monitors` or
//! `reactions` (below),
//! or `monitored`, what a Study sample carries: a monitor of the last body's x displacement
//! measured against the model's own ideal twin, made by the batch (rust/batch.rs), 8 points a
//! step (the reference run is then in the count: run `monitored-bare` for it alone, i.e. the
//! same reference without the monitor's sampling). Prints the statistics of the run and the wall time; divide
//! cachegrind's `I refs` by the right-hand sides for instructions per right-hand side. The
//! settings are the benches' (`common::bench_run`): rtol 1e-6, atol 1e-9, 1 000 outputs. A chaotic
//! model (the dry nine-bar) takes a different number of steps after any change of round-off:
//! compare instructions per right-hand side there, totals on the lubricated models.

#[path = "../tests/common/mod.rs"]
mod common;

use clearsim::batch::run_batch;
use clearsim::integrate::Method;
use clearsim::monitor::{MonitorSpec, Quantity, ReferenceGrid, ReferenceOf, Target};
use clearsim::simulate::simulate;

fn main() {
    // `cargo bench` passes `--bench`; keep only the positional arguments.
    let args: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with("--")).collect();
    let name = args.first().map_or("nine_bar_dry", String::as_str);
    let method = match args.get(1).map_or("rk45", String::as_str) {
        "rk45" => Method::Rk45,
        "dop853" => Method::Dop853,
        "radau" => Method::Radau,
        "rodas4" => Method::Rodas4,
        other => {
            eprintln!("unknown method {other:?}: rk45, dop853, radau or rodas4");
            std::process::exit(2);
        }
    };
    let model = common::model(name);
    let mut rs = common::bench_run(method, common::cycle(name), 1000);
    // A third argument adds what a run may ask for: `bearings` (the bearing summary, as
    // `simulate(..., bearings=True)` and `clearsim run` ask), `film_monitors` (exact monitors of
    // the film thickness and power loss, what every lubricated run paid for before issue 37),
    // `monitored` / `monitored-bare` (a Study sample's monitor and its reference run).
    let mode = args.get(2).map_or("", String::as_str);
    match mode {
        "" => {}
        "bearings" => rs.bearings = true,
        "film_monitors" => rs.monitors = common::film_monitors(&model, rs.t0, rs.t_end),
        // The peaks of every ideal joint's force and driver's torque, as `simulate(extremes=[...])`
        // tracks them (and `clearsim run` with `[outputs] reactions`).
        "reactions" => rs.monitors = common::reaction_monitors(&model, rs.t0, rs.t_end),
        "monitored" | "monitored-bare" => {
            let t_end = common::cycle(name);
            rs.reference = Some(ReferenceGrid { t_start: 0.0, t_end, intervals: 7200, record: false });
            rs.monitors.push(MonitorSpec {
                target: Target::Coordinate(3 * (model.n_bodies() - 1)),
                quantity: Quantity::Displacement,
                reference: Some(ReferenceOf::OwnIdeal),
                t_start: 0.0,
                bin_width: t_end / 20.0,
                bins: 20,
                limit: Some(1e-3),
                samples_per_step: if mode == "monitored-bare" { 1 } else { 8 },
                exact: false,
            });
        }
        other => {
            eprintln!("unknown mode {other:?}: bearings, film_monitors, reactions, monitored or monitored-bare");
            std::process::exit(2);
        }
    }
    let start = std::time::Instant::now();
    let out = if mode.starts_with("monitored") {
        run_batch(&[common::description(name)], std::slice::from_ref(&rs), None, 1, None).pop().unwrap().expect("a valid run")
    } else {
        simulate(&model, &rs, None).expect("a valid run")
    };
    let wall = start.elapsed();
    if let Some(e) = &out.error {
        eprintln!("the run stopped: {e}");
        std::process::exit(1);
    }
    let s = &out.stats;
    println!(
        "{name} {}: {:.1} ms, {} steps, {} rejected, {} right-hand sides, {} Jacobians",
        args.get(1).map_or("rk45", String::as_str),
        wall.as_secs_f64() * 1e3,
        s.steps_accepted,
        s.steps_rejected,
        s.rhs_evals,
        s.jacobians
    );
}
