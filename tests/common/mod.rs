//! Shared by the integration tests and the benches (`#[path = "../tests/common/mod.rs"]`):
//! the Python models loaded from the JSON fixtures `tests/data/*.json`, written by
//! `python benches/fixtures.py` and checked against the current models by
//! `tests/python/test_fixtures.py`.
#![allow(dead_code)]

use std::path::PathBuf;

use clearsim::assembly::assemble;
use clearsim::model::{MechanismDesc, Model};

/// One crank cycle of the nine-bar at ω = −5π rad/s [s].
pub const NINE_BAR_CYCLE: f64 = 0.4;
/// One crank cycle of the slider-crank at 5000 rpm [s].
pub const SLIDER_CRANK_CYCLE: f64 = 0.012;

/// The description in `tests/data/<name>.json`, with the defaults the Python glue fills in
/// (`e0 = 0.05 c` of a lubricated joint) applied.
pub fn description(name: &str) -> MechanismDesc {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(format!("{name}.json"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e} (run python benches/fixtures.py)", path.display()));
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    for cj in v["clearance_joints"].as_array_mut().unwrap() {
        let c = cj["clearance"].as_f64().unwrap();
        let model = cj["model"].as_object_mut().unwrap();
        if model["kind"] == "lubricated" && !model.contains_key("e0") {
            model.insert("e0".into(), (0.05 * c).into());
        }
    }
    serde_json::from_value(v).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
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
