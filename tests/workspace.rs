//! `Workspace::evaluate` returns at once when it holds the evaluation asked for from
//! `evaluate_and_keep` (same t, y and impact memory), and evaluates afresh after any change or
//! any other use of the workspace: checked against a fresh workspace on a dry nine-bar state in contact, where the
//! impact memory enters the force (P3's damping uses the recorded δ̇⁽⁻⁾).

mod common;

use clearsim::clearance::ImpactMemory;
use clearsim::system::Workspace;

/// q̈, Φ, λ and the joint forces' normal components of an evaluation.
fn results(ws: &Workspace) -> (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>) {
    let normal = ws.joint_force.iter().map(|f| f.normal).collect();
    (ws.qdd.clone(), ws.phi.clone(), ws.lambda.clone(), normal)
}

#[test]
fn a_repeated_evaluation_is_reused_and_any_change_evaluates_afresh() {
    let model = common::model("nine_bar_dry");
    let n = 3 * model.n_bodies();
    let mut y = common::initial_state(&model);
    // Push joint 0's journal 2 µm into the bearing wall, moving outwards.
    let joint = &model.clearance[0];
    let b = joint.journal.expect("a moving journal") as usize;
    y[3 * b] += joint.clearance + 2e-6;
    y[n + 3 * b] += 0.05;
    let nj = model.clearance.len();
    let slow = vec![ImpactMemory { in_contact: true, impact_speed: 0.1, ..Default::default() }; nj];
    let fast = vec![ImpactMemory { in_contact: true, impact_speed: 0.5, ..Default::default() }; nj];
    let fresh = |memory: &[ImpactMemory], t: f64, y: &[f64]| {
        let mut ws = Workspace::new(&model);
        ws.evaluate_and_keep(&model, memory, t, y).unwrap();
        results(&ws)
    };
    let t = 0.01;
    let mut ws = Workspace::new(&model);
    ws.evaluate_and_keep(&model, &slow, t, &y).unwrap();
    let first = results(&ws);
    assert_eq!(first, fresh(&slow, t, &y));
    assert!(first.3[0] > 0.0, "joint 0 is in contact");
    ws.evaluate(&model, &slow, t, &y).unwrap();
    assert_eq!(results(&ws), first, "the same evaluation again");

    // Another impact memory: the damping and so the contact force change.
    ws.evaluate_and_keep(&model, &fast, t, &y).unwrap();
    let other = results(&ws);
    assert_eq!(other, fresh(&fast, t, &y));
    assert_ne!(other.3[0], first.3[0], "the memory enters the force");

    // Another time, another state.
    ws.evaluate_and_keep(&model, &slow, t, &y).unwrap();
    assert_eq!(results(&ws), first);
    ws.evaluate(&model, &slow, 0.02, &y).unwrap();
    assert_eq!(results(&ws), fresh(&slow, 0.02, &y));
    assert_ne!(results(&ws).1, first.1, "the drivers' Φ moves with t");
    ws.evaluate(&model, &slow, t, &y).unwrap();
    assert_eq!(results(&ws), first, "a plain evaluation in between is not kept");
    let mut y2 = y.clone();
    y2[3 * b] += 1e-6;
    ws.evaluate_and_keep(&model, &slow, t, &y2).unwrap();
    assert_eq!(results(&ws), fresh(&slow, t, &y2));
    assert_ne!(results(&ws).3[0], first.3[0]);

    // Another use of the workspace in between (the Newton matrix's constraints and factor at
    // another pose) leaves Φ and the factor of that pose: evaluated afresh.
    ws.evaluate_and_keep(&model, &slow, t, &y).unwrap();
    ws.eval_constraints(&model, 0.3, &y2[..n], &y2[n..]);
    ws.factor_kkt(0.3).unwrap();
    ws.evaluate_and_keep(&model, &slow, t, &y).unwrap();
    assert_eq!(results(&ws), first, "after another use of the workspace");
}
