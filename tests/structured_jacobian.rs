//! The mechanism's structured Newton matrix for RADAU5 (`MechanismSystem::acceleration_jacobian`:
//! clearance-joint force derivatives mapped through the constrained mobility) against central
//! differences of the whole right-hand side, at states along the stiff hard case (μ = 0.04 Pa s,
//! film near ε → 1 and the film-to-contact band) and the dry nine-bar in contact. The parts it
//! leaves out (pose dependence of the mobility, γ and Baumgarte terms) are not stiff, so the two
//! must agree on the dominant entries: a relative Frobenius difference of a few per cent.

mod common;

use clearsim::integrate::{integrate, Method, OdeSystem, Settings};
use clearsim::record::Channels;
use clearsim::simulate::MechanismSystem;

fn frobenius(a: &[f64]) -> f64 {
    a.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// (‖W_q − J_q‖/‖J_q‖, ‖W_v − J_v‖/‖J_v‖, ‖J_v‖) at the state reached at `t`.
fn compare(name: &str, t: f64) -> (f64, f64, f64) {
    let model = common::model(name);
    let y0 = common::initial_state(&model);
    let mut sys = MechanismSystem::new(&model, Channels::default(), 0, None);
    let s = Settings { rtol: 1e-8, atol: 1e-11, ..Settings::default() };
    integrate(&mut sys, Method::Rk45, 0.0, &y0, t, &[], &s).unwrap();
    let y = sys.last_y.clone();
    let n = y.len();
    let m = n / 2;
    let (mut w_q, mut w_v) = (vec![0.0; m * m], vec![0.0; m * m]);
    assert!(sys.acceleration_jacobian(t, &y, &mut w_q, &mut w_v).unwrap());
    let (mut j_q, mut j_v) = (vec![0.0; m * m], vec![0.0; m * m]);
    let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
    let mut probe = y.clone();
    for col in 0..n {
        let delta = f64::EPSILON.sqrt() * y[col].abs().max(1.0);
        probe[col] = y[col] + delta;
        sys.rhs(t, &probe, &mut fp).unwrap();
        probe[col] = y[col] - delta;
        sys.rhs(t, &probe, &mut fm).unwrap();
        probe[col] = y[col];
        let target = if col < m { &mut j_q } else { &mut j_v };
        let c = col % m;
        for i in 0..m {
            target[i + c * m] = (fp[m + i] - fm[m + i]) / (2.0 * delta);
        }
    }
    let diff = |a: &[f64], b: &[f64]| frobenius(&a.iter().zip(b).map(|(x, y)| x - y).collect::<Vec<_>>()) / frobenius(b);
    (diff(&w_q, &j_q), diff(&w_v, &j_v), frobenius(&j_v))
}

#[test]
fn structured_newton_matrix_matches_the_full_jacobian() {
    for (name, t) in [
        ("nine_bar_lubricated_mu004", 0.02),
        ("nine_bar_lubricated_mu004", 0.13),
        ("nine_bar_lubricated_mu004", 0.37),
        ("nine_bar_lubricated", 0.2),
        ("slider_crank_lubricated", 0.006),
    ] {
        let (dq, dv, norm_v) = compare(name, t);
        eprintln!("{name} t = {t}: rel. diff W_q {dq:.2e}, W_v {dv:.2e} (‖J_v‖ = {norm_v:.3e})");
        assert!(dq < 0.05 && dv < 0.05, "{name} at t = {t}: {dq:.3e}, {dv:.3e}");
    }
}

/// With a 5 µm film the journal sits within nanometres of the bearing centre. Moving the journal
/// and its bearing together (rod and slider both by 1 m in x) leaves the eccentricity, and so
/// the film force, unchanged: the Newton matrix must give no stiffness against it. The law is
/// differenced in the joint's own variables with an exact chain rule, so the two columns cancel
/// to round-off; differencing in body coordinates (steps of ~1e-8 m, several times e) left a
/// spurious stiffness of ~1e-3 of the film's, which stopped Newton's iteration for steps above
/// ~1e-9 s.
#[test]
fn a_micrometre_film_has_no_stiffness_against_common_motion() {
    let mut desc = common::description("slider_crank_lubricated");
    desc.clearance_joints[0].clearance = 5e-6;
    let model = clearsim::model::Model::compile(&desc).unwrap();
    let y0 = common::initial_state(&model);
    let mut sys = MechanismSystem::new(&model, Channels::default(), 0, None);
    let t = 0.003;
    integrate(&mut sys, Method::Radau, 0.0, &y0, t, &[], &Settings::default()).unwrap();
    let y = sys.last_y.clone();
    let m = y.len() / 2;
    let (mut w_q, mut w_v) = (vec![0.0; m * m], vec![0.0; m * m]);
    assert!(sys.acceleration_jacobian(t, &y, &mut w_q, &mut w_v).unwrap());
    let names: Vec<&str> = desc.bodies.iter().map(|b| b.name.as_str()).collect();
    let (rod, slider) = (names.iter().position(|n| *n == "rod").unwrap(), names.iter().position(|n| *n == "slider").unwrap());
    for w in [&w_q, &w_v] {
        let col = |k: usize| &w[k * m..(k + 1) * m];
        let (a, b) = (col(3 * rod), col(3 * slider));
        let common = frobenius(&a.iter().zip(b).map(|(x, y)| x + y).collect::<Vec<_>>());
        let scale = frobenius(a).max(frobenius(b));
        eprintln!("common-motion stiffness / film stiffness = {:.2e} (film ‖column‖ = {scale:.3e})", common / scale);
        assert!(scale > 1e6, "the film should be stiff here: {scale:.3e}");
        assert!(common < 1e-9 * scale, "common motion of journal and bearing: {:.3e} of the film's stiffness", common / scale);
    }
}
