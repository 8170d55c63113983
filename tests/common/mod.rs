//! Shared by the integration tests and the benches (`#[path = "../tests/common/mod.rs"]`):
//! the Python models loaded from the JSON fixtures `tests/data/*.json`, written by
//! `python benches/fixtures.py` and checked against the current models by
//! `tests/python/test_fixtures.py`.
#![allow(dead_code)]

use std::path::PathBuf;

use clearsim::assembly::assemble;
use clearsim::description::MechanismDesc;
use clearsim::model::Model;

/// One crank cycle of the nine-bar at ω = −5π rad/s [s].
pub const NINE_BAR_CYCLE: f64 = 0.4;
/// One crank cycle of the slider-crank at 5000 rpm [s].
pub const SLIDER_CRANK_CYCLE: f64 = 0.012;

/// One crank cycle of the fixture model `name` (a nine-bar or a slider-crank) [s].
pub fn cycle(name: &str) -> f64 {
    if name.starts_with("nine") {
        NINE_BAR_CYCLE
    } else {
        SLIDER_CRANK_CYCLE
    }
}

/// The benches' run: `method` from 0 to `t_end` [s] at rtol 1e-6, atol 1e-9, with `outputs`
/// evenly spaced output times, the default channels and no monitors.
pub fn bench_run(method: clearsim::integrate::Method, t_end: f64, outputs: usize) -> clearsim::simulate::RunSettings {
    let ode = clearsim::integrate::Settings { rtol: 1e-6, atol: 1e-9, ..Default::default() };
    let t_out = clearsim::simulate::RunSettings::grid(0.0, t_end, t_end / outputs as f64).unwrap();
    clearsim::simulate::RunSettings::plain(Some(method), ode, 0.0, t_end, t_out)
}

/// Exact monitors of the film thickness and power loss of every lubricated clearance joint over
/// [t0, t_end] (4 samples a step): what `clearsim` ran on every lubricated run before the bearing
/// summary was asked for (issue 37), kept to measure what exact monitors cost.
pub fn film_monitors(model: &Model, t0: f64, t_end: f64) -> Vec<clearsim::monitor::MonitorSpec> {
    use clearsim::monitor::{Quantity, Target};
    let lubricated = model.clearance.iter().enumerate().filter(|(_, c)| c.film.is_some()).map(|(j, _)| j);
    lubricated.flat_map(|j| [exact_monitor(Target::Joint(j), Quantity::FilmThickness, t0, t_end), exact_monitor(Target::Joint(j), Quantity::PowerLoss, t0, t_end)]).collect()
}

/// An exact monitor of `quantity` of `target` over [t0, t_end] in one bin, four points a step
/// (what `simulate(extremes=[...])` asks for).
#[allow(dead_code)]
pub fn exact_monitor(target: clearsim::monitor::Target, quantity: clearsim::monitor::Quantity, t0: f64, t_end: f64) -> clearsim::monitor::MonitorSpec {
    clearsim::monitor::MonitorSpec { target, quantity, reference: None, t_start: t0, bin_width: t_end - t0, bins: 1, limit: None, samples_per_step: 4, exact: true }
}

/// Exact monitors of every ideal joint's and driver's reaction, as `simulate(extremes=[...])`
/// makes them for its ideal joints and drivers (python/clearsim/joint_reactions.py): a revolute
/// joint's force x, y and magnitude, a prismatic joint's also its couple, a driver's torque.
#[allow(dead_code)]
pub fn reaction_monitors(model: &Model, t0: f64, t_end: f64) -> Vec<clearsim::monitor::MonitorSpec> {
    use clearsim::constraints::Constraint;
    use clearsim::monitor::{PointComponent, Quantity, Target};
    let spec = |constraint, quantity, component| exact_monitor(Target::Reaction { constraint, component }, quantity, t0, t_end);
    let force = |k| [PointComponent::X, PointComponent::Y, PointComponent::Magnitude].map(|c| spec(k, Quantity::Force, c));
    let mut out = Vec::new();
    for (k, c) in model.constraints.iter().enumerate() {
        match c {
            Constraint::Driver { .. } => out.push(spec(k, Quantity::Torque, PointComponent::Magnitude)),
            Constraint::Revolute { .. } => out.extend(force(k)),
            Constraint::Prismatic { .. } => {
                out.extend(force(k));
                out.push(spec(k, Quantity::Torque, PointComponent::Magnitude));
            }
        }
    }
    out
}

/// The description in `tests/data/<name>.json`, read the way the Python layer hands it over.
pub fn description(name: &str) -> MechanismDesc {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(format!("{name}.json"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e} (run python benches/fixtures.py)", path.display()));
    clearsim::description::from_json(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The compiled model of fixture `name`.
pub fn model(name: &str) -> Model {
    Model::compile(&description(name)).unwrap()
}

/// Consistent initial state y0 = (q0, q̇0) at t = 0.
pub fn initial_state(model: &Model) -> Vec<f64> {
    let (q, qd) = assemble(model, 0.0).unwrap();
    let mut y = q;
    y.extend_from_slice(&qd);
    y
}

/// A pendulum chain of `n` links (0.1 m, 1 kg, pinned end to end, the first to the ground,
/// hanging at 30° from the horizontal under gravity), with the joints at the listed link indices
/// given a dry clearance (0.1 mm on a 5 mm pin) instead of an ideal revolute: the scaling model of
/// `benches/chain.rs` (2 constraint rows per ideal joint).
pub fn chain(n: usize, clearance_at: &[usize]) -> MechanismDesc {
    use clearsim::description::{ClearanceModelDesc, DryDesc};
    chain_with(n, |i| clearance_at.contains(&i).then(|| ClearanceModelDesc::Dry(DryDesc::steel())))
}

/// The chain of [`chain`] with a lubricated clearance joint (long film, 0.1 mm on a 5 mm pin,
/// 10 mm long, μ = 0.1 Pa s) at every `every`-th joint, the first included: the model of the
/// implicit methods' per-step cost against size (`benches/chain_steps.rs`).
pub fn lubricated_chain(n: usize, every: usize) -> MechanismDesc {
    use clearsim::description::{ClearanceModelDesc, DryDesc, LubricatedDesc, ViscosityDesc};
    let film = LubricatedDesc {
        film: Default::default(),
        supply: Default::default(),
        viscosity: ViscosityDesc::Constant(0.1),
        length: 0.01,
        eps0: 2e-6,
        m: 0.5,
        e0: None,
        eps_max: 0.99,
        dry: DryDesc::steel(),
        roughness: None,
        boundary_friction: None,
        boundary_slip: None,
        cavitation: Default::default(),
        thermal: None,
    };
    chain_with(n, |i| i.is_multiple_of(every).then(|| ClearanceModelDesc::Lubricated(film.clone())))
}

/// The chain of [`chain`] with joint `i` a clearance joint of the model `clearance(i)` where it
/// gives one (0.1 mm on a 5 mm pin), else an ideal revolute.
pub fn chain_with(n: usize, clearance: impl Fn(usize) -> Option<clearsim::description::ClearanceModelDesc>) -> MechanismDesc {
    use clearsim::description::{BodyDesc, ClearanceJointDesc, JointDesc};
    let (l, angle) = (0.1, -std::f64::consts::FRAC_PI_6);
    let (dx, dy) = (l * angle.cos(), l * angle.sin());
    let bodies = (0..n)
        .map(|i| BodyDesc {
            name: format!("link{i}"),
            mass: 1.0,
            inertia: l * l / 12.0,
            position: [(i as f64 + 0.5) * dx, (i as f64 + 0.5) * dy],
            angle,
            velocity: [0.0; 3],
        })
        .collect();
    let mut joints = Vec::new();
    let mut clearance_joints = Vec::new();
    for i in 0..n {
        let (body_a, point_a) = if i == 0 { (None, [0.0, 0.0]) } else { (Some(i - 1), [l / 2.0, 0.0]) };
        let (body_b, point_b) = (Some(i), [-l / 2.0, 0.0]);
        if let Some(model) = clearance(i) {
            clearance_joints.push(ClearanceJointDesc {
                name: format!("c{i}"),
                bearing_body: body_a,
                bearing_point: point_a,
                journal_body: body_b,
                journal_point: point_b,
                journal_radius: 5e-3,
                clearance: 1e-4,
                model,
                initial_eccentricity: [0.0, 0.0],
            });
        } else {
            joints.push(JointDesc::Revolute { name: format!("j{i}"), body_a, point_a, body_b, point_b });
        }
    }
    MechanismDesc { bodies, joints, clearance_joints, ..MechanismDesc::default() }
}
