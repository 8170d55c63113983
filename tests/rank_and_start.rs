//! The assembly at any t0 (following the drivers from the pose given at t = 0) against the
//! slider-crank's closed form, and the rank test of `rust/rank.rs` on the fixture models: sound
//! poses stay far above its lock-up threshold all along a cycle, a dead centre falls below it.

mod common;

use clearsim::assembly::assemble;
use clearsim::constraints::BodyKin;
use clearsim::integrate::Method;
use clearsim::model::Model;
use clearsim::rank::{analyse, DEPENDENT_RATIO};
use clearsim::simulate::simulate;
use clearsim::system::Workspace;

/// σ_min/σ_max of the model's scaled Φq at the pose q.
fn ratio(model: &Model, q: &[f64]) -> f64 {
    let mut ws = Workspace::new(model);
    ws.eval_constraints(model, 0.0, q, &vec![0.0; q.len()]);
    let kin: Vec<BodyKin> = (0..model.n_bodies()).map(|b| BodyKin::new(&q[3 * b..3 * b + 3], &[0.0; 3])).collect();
    analyse(model, &ws.jac, &kin).ratio
}

#[test]
fn the_slider_crank_assembled_at_any_t0_is_its_closed_form() {
    // Crank r = 0.05 m, rod l = 0.12 m, slider on the x axis, θ = ω t from the top dead centre:
    // x_slider = r cos θ + √(l² − r² sin² θ), on the branch of the pose given (slider to the right).
    let model = common::model("slider_crank_ideal");
    let (r, l, omega) = (0.05, 0.12, 5000.0 * 2.0 * std::f64::consts::PI / 60.0);
    for turns in [0.25, 0.4, 1.0, 1.7, 2.5, -0.3] {
        let t0 = turns * common::SLIDER_CRANK_CYCLE;
        let (q, qd) = assemble(&model, t0).unwrap();
        let th = omega * t0;
        let x = r * th.cos() + (l * l - r * r * th.sin() * th.sin()).sqrt();
        assert!((q[6] - x).abs() < 1e-12, "t0 = {turns} T: slider at {} m, closed form {x} m", q[6]);
        assert!((q[2] - th).abs() < 1e-12, "t0 = {turns} T: crank at {} rad, driver at {th} rad", q[2]);
        // ẋ = −r ω sin θ (1 + r cos θ / √(l² − r² sin² θ)).
        let v = -r * omega * th.sin() * (1.0 + r * th.cos() / (l * l - r * r * th.sin() * th.sin()).sqrt());
        assert!((qd[6] - v).abs() < 1e-9 * omega, "t0 = {turns} T: slider speed {} m/s, closed form {v} m/s", qd[6]);
    }
}

#[test]
fn sound_poses_of_the_fixtures_stay_far_from_the_lock_up_threshold() {
    // Along one cycle of every fixture (the Φq a run sees: clearance joints free), the scaled
    // Jacobian's σ_min/σ_max stays above 1e-2, ten times the threshold (measured: nine-bar
    // ≥ 0.0195, slider-crank ≥ 0.167).
    for name in ["slider_crank_ideal", "slider_crank_dry", "slider_crank_lubricated", "nine_bar_ideal", "nine_bar_dry", "nine_bar_lubricated"] {
        let model = common::model(name);
        let out = simulate(&model, &common::bench_run(Method::Rk45, common::cycle(name), 50), None).unwrap();
        assert!(out.error.is_none(), "{name}: {:?}", out.error);
        let n = 3 * model.n_bodies();
        let worst = out.recording.q.chunks(n).map(|q| ratio(&model, q)).fold(f64::INFINITY, f64::min);
        println!("{name}: σ_min/σ_max ≥ {worst:.3e} over a cycle");
        assert!(worst > 10.0 * DEPENDENT_RATIO, "{name}: σ_min/σ_max down to {worst:.2e}");
    }
}

#[test]
fn a_dead_centre_falls_below_the_threshold() {
    // The slider-crank at θ = 90° with a rod exactly as long as the crank's lift there: the rod
    // stands perpendicular to the guide, where its loop loses a rank.
    let model = common::model("slider_crank_ideal");
    let (r, l) = (0.05, 0.12);
    let mut q = vec![0.0; 9];
    // Crank straight up (θ = 90°), the slider right under the rod's end... a rod of length r
    // would stand vertical; with l > r the loop is sound: ratio above threshold.
    q[0] = 0.0;
    q[1] = r / 2.0;
    q[2] = std::f64::consts::FRAC_PI_2;
    let x = (l * l - r * r).sqrt();
    q[3] = x / 2.0;
    q[4] = r / 2.0;
    q[5] = (-r).atan2(x);
    q[6] = x;
    assert!(ratio(&model, &q) > DEPENDENT_RATIO);
    // The same bodies, the rod turned to stand perpendicular to the guide: Φq at this pose (its
    // joints need not close: Φq depends on the angles) has dependent rows.
    q[5] = -std::f64::consts::FRAC_PI_2;
    assert!(ratio(&model, &q) < 1e-12, "{:.2e}", ratio(&model, &q));
}
