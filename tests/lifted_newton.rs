//! The implicit methods' Newton matrices in lifted sparse form (rust/integrate/lifted.rs,
//! rust/simulate/lifted.rs) against what they replace, each computed a second way:
//!
//! - the stiff part, `[I 0] A₀⁻¹ K`, against the dense structured hook (`acceleration_jacobian`,
//!   columns of the constrained mobility), to round-off;
//! - the whole derivative (RODAS4's Jacobian, RADAU5's fallback; `K` differenced group by group of
//!   bodies) against central differences of the whole right-hand side, on chains and the
//!   fixtures (a wrong grouping of bodies mixes columns and fails this by orders of magnitude);
//! - a RADAU5 run on a lubricated chain through the lifted form against the same run through
//!   the dense form (the system's lifted form hidden), step for step; with oil temperatures as
//!   states, RADAU5 and RODAS4 alike (the temperatures border the lifted form);
//! - the work of a Jacobian no longer grows with the size: RODAS4's right-hand sides per step on
//!   an 80-link chain within 1.5× of a 20-link one's (on the dense form they grow 4×).

mod common;

use clearsim::integrate::{integrate, DenseOutput, Method, OdeSystem, Settings, Stats};
use clearsim::model::Model;
use clearsim::record::Channels;
use clearsim::simulate::MechanismSystem;
use nalgebra::DMatrix;

fn frobenius(a: &DMatrix<f64>) -> f64 {
    a.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// The state `model` reaches at `t` with RADAU5 (not a special pose).
fn state_at(model: &Model, t: f64) -> Vec<f64> {
    let y0 = common::initial_state(model);
    let mut sys = MechanismSystem::new(model, Channels::default(), 0, None);
    integrate(&mut sys, Method::Radau, 0.0, &y0, t, &[], &Settings::default()).unwrap();
    sys.last_y.clone()
}

/// `(W_q, W_v)` = `[I 0] A₀⁻¹ (K_q, K_v)` from the lifted form at `(t, y)`, dense `m × m`.
fn lifted_w(sys: &mut MechanismSystem, t: f64, y: &[f64], exact: bool) -> (DMatrix<f64>, DMatrix<f64>) {
    let p = sys.lifted_pattern().expect("a mechanism has a lifted form");
    let (m, dim) = (p.coords, p.dim);
    let nnz = p.row.len();
    let (mut a0, mut k_q, mut k_v) = (vec![0.0; nnz], vec![0.0; nnz], vec![0.0; nnz]);
    sys.lifted_jacobian(t, y, exact, &mut a0, &mut k_q, &mut k_v).unwrap();
    let dense = |v: &[f64], cols: usize| {
        let mut a = DMatrix::zeros(dim, cols);
        for j in 0..cols {
            for k in p.col_start[j]..p.col_start[j + 1] {
                a[(p.row[k], j)] = v[k];
            }
        }
        a
    };
    let lu = dense(&a0, dim).lu();
    let solve = |k: &[f64]| lu.solve(&dense(k, m)).expect("A₀ is regular").rows(0, m).into_owned();
    (solve(&k_q), solve(&k_v))
}

/// `(J_q, J_v)`: central differences of the accelerations of the whole right-hand side, with
/// steps 10⁴ times the forward steps of the implicit methods (`difference_step`: on the scale of
/// the clearance for a clearance joint's bodies, 1.5·10⁻⁴ c here), each column on its own.
fn central_differences(sys: &mut MechanismSystem, t: f64, y: &[f64]) -> (DMatrix<f64>, DMatrix<f64>) {
    let n = y.len();
    let m = n / 2;
    let (mut j_q, mut j_v) = (DMatrix::zeros(m, m), DMatrix::zeros(m, m));
    let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
    let mut probe = y.to_vec();
    for col in 0..n {
        let delta = 1e4 * sys.difference_step(col, y);
        probe[col] = y[col] + delta;
        sys.rhs(t, &probe, &mut fp).unwrap();
        probe[col] = y[col] - delta;
        sys.rhs(t, &probe, &mut fm).unwrap();
        probe[col] = y[col];
        let target = if col < m { &mut j_q } else { &mut j_v };
        for i in 0..m {
            target[(i, col % m)] = (fp[m + i] - fm[m + i]) / (2.0 * delta);
        }
    }
    (j_q, j_v)
}

#[test]
fn lifted_stiff_part_is_the_structured_hooks_matrix() {
    for (name, model, t) in [
        ("chain of 12, lubricated every 4th", Model::compile(&common::lubricated_chain(12, 4)).unwrap(), 0.004),
        ("chain of 9, dry at 0 and 5", Model::compile(&common::chain(9, &[0, 5])).unwrap(), 0.01),
        ("nine_bar_lubricated", common::model("nine_bar_lubricated"), 0.1),
        ("slider_crank_lubricated", common::model("slider_crank_lubricated"), 0.006),
    ] {
        let y = state_at(&model, t);
        let mut sys = MechanismSystem::new(&model, Channels::default(), 0, None);
        let m = y.len() / 2;
        let (mut w_q, mut w_v) = (vec![0.0; m * m], vec![0.0; m * m]);
        assert!(sys.acceleration_jacobian(t, &y, &mut w_q, &mut w_v).unwrap());
        let (l_q, l_v) = lifted_w(&mut sys, t, &y, false);
        for (dense, lifted, what) in [(w_q, l_q, "W_q"), (w_v, l_v, "W_v")] {
            let dense = DMatrix::from_column_slice(m, m, &dense);
            let diff = frobenius(&(&lifted - &dense));
            eprintln!("{name}: {what} lifted vs structured, difference {diff:.2e} (‖W‖ = {:.2e})", frobenius(&dense));
            assert!(diff <= 1e-10 * frobenius(&dense), "{name}: {what} differs by {diff:.3e}");
        }
    }
}

#[test]
fn lifted_whole_derivative_matches_central_differences() {
    for (name, model, t) in [
        ("chain of 12, lubricated every 4th", Model::compile(&common::lubricated_chain(12, 4)).unwrap(), 0.004),
        ("chain of 9, dry at 0 and 5", Model::compile(&common::chain(9, &[0, 5])).unwrap(), 0.01),
        ("nine_bar_lubricated", common::model("nine_bar_lubricated"), 0.1),
        ("nine_bar_ideal", common::model("nine_bar_ideal"), 0.1),
        ("slider_crank_lubricated", common::model("slider_crank_lubricated"), 0.006),
    ] {
        let y = state_at(&model, t);
        let mut sys = MechanismSystem::new(&model, Channels::default(), 0, None);
        let (j_q, j_v) = central_differences(&mut sys, t, &y);
        let (l_q, l_v) = lifted_w(&mut sys, t, &y, true);
        for (cd, lifted, what) in [(j_q, l_q, "J_q"), (j_v, l_v, "J_v")] {
            let rel = frobenius(&(&lifted - &cd)) / frobenius(&cd);
            eprintln!("{name}: {what} lifted (whole) vs central differences, rel. diff {rel:.2e} (‖J‖ = {:.2e})", frobenius(&cd));
            assert!(rel < 1e-4, "{name}: {what} differs by {rel:.3e}");
        }
    }
}

/// A [`MechanismSystem`] without its lifted form: the implicit methods take the dense forms.
struct DenseOnly<'s, 'm>(&'s mut MechanismSystem<'m>);

impl OdeSystem for DenseOnly<'_, '_> {
    fn dim(&self) -> usize {
        self.0.dim()
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> clearsim::error::Result<()> {
        self.0.rhs(t, y, dy)
    }
    fn step_accepted(&mut self, t0: f64, y0: &[f64], t1: f64, y1: &[f64], dense: &dyn DenseOutput) -> clearsim::error::Result<bool> {
        self.0.step_accepted(t0, y0, t1, y1, dense)
    }
    fn switching_point(&mut self, t0: f64, y0: &[f64], t1: f64, y1: &[f64], dense: &dyn DenseOutput) -> clearsim::error::Result<Option<f64>> {
        self.0.switching_point(t0, y0, t1, y1, dense)
    }
    fn output(&mut self, t: f64, y: &[f64]) -> clearsim::error::Result<()> {
        self.0.output(t, y)
    }
    fn acceleration_jacobian(&mut self, t: f64, y: &[f64], a_q: &mut [f64], a_v: &mut [f64]) -> clearsim::error::Result<bool> {
        self.0.acceleration_jacobian(t, y, a_q, a_v)
    }
    fn difference_step(&self, j: usize, y: &[f64]) -> f64 {
        self.0.difference_step(j, y)
    }
    fn first_order_states(&self) -> usize {
        self.0.first_order_states()
    }
    fn border_jacobian(&mut self, t: f64, y: &[f64], a_z: &mut [f64], z_y: &mut [f64]) -> clearsim::error::Result<()> {
        self.0.border_jacobian(t, y, a_z, z_y)
    }
}

/// RADAU5 on a 24-link chain with a lubricated joint at every 4th (27 stiff coordinates: the
/// lifted form) and the same run through the dense form: the same steps (the Newton matrices are
/// the same up to round-off, the iteration converges to the same stages) and the same end state
/// to far below the tolerance.
#[test]
fn radau5_through_the_lifted_form_runs_as_through_the_dense_form() {
    radau5_lifted_against_dense(Model::compile(&common::lubricated_chain(24, 4)).unwrap());
}

/// The same with the six films' oil temperatures as states (Vogel viscosity, a heat balance
/// each; `y = (q, q̇, T…)`): the temperatures border the lifted Newton matrices (`border.rs`'s
/// Schur complement around the lifted solves) as they border the dense ones.
#[test]
fn radau5_through_the_lifted_form_with_oil_temperatures_runs_as_through_the_dense_form() {
    let model = heated_chain(24);
    assert_eq!(model.state_dim(), 6 * 24 + 6);
    radau5_lifted_against_dense(model);
}

/// The chain of `n` links lubricated at every 4th joint with the films' oil temperatures as
/// states (Vogel viscosity, a heat balance each, starting 10 K above the ambient):
/// `y = (q, q̇, T…)`.
fn heated_chain(n: usize) -> Model {
    use clearsim::description::{ClearanceModelDesc, ThermalDesc, ViscosityDesc};
    let mut desc = common::lubricated_chain(n, 4);
    for cj in &mut desc.clearance_joints {
        if let ClearanceModelDesc::Lubricated(film) = &mut cj.model {
            film.viscosity = ViscosityDesc::Vogel { vogel: [6.4e-5, 900.0, 170.0] };
            film.thermal = Some(ThermalDesc { ambient: 300.0, heat_capacity: 1e-3, heat_transfer: 1e-3, initial: Some(310.0) });
        }
    }
    Model::compile(&desc).unwrap()
}

/// RODAS4 with oil temperatures as states takes the lifted form, bordered by the temperatures
/// (`border.rs` around the lifted solves), as it does without them. On a heated 12-link chain,
/// against the same run through the dense form (the whole `f` differenced, `n` right-hand sides a
/// Jacobian): under half the right-hand sides, no more steps (the differenced `f` is the poorer
/// Jacobian: 246 steps against 209, as 275 against 197 without heat), and both end states within
/// 3× the error allowance of a RADAU5 run at tolerances 10⁵ times tighter.
#[test]
fn rodas4_through_the_lifted_form_with_oil_temperatures_runs_as_through_the_dense_form() {
    let model = heated_chain(12);
    let (y0, (st_l, y_l), (st_d, y_d)) = lifted_and_dense(&model, Method::Rodas4);
    assert_eq!(y0.len(), 6 * 12 + 3);
    // The lifted form was taken: 6 g + 9 right-hand sides a step against n + 7 = 82.
    assert!(2 * st_l.rhs_evals < st_d.rhs_evals, "lifted {} vs dense {} right-hand sides", st_l.rhs_evals, st_d.rhs_evals);
    assert!(st_l.steps_accepted <= st_d.steps_accepted, "accepted steps: lifted {}, dense {}", st_l.steps_accepted, st_d.steps_accepted);
    let mut reference = MechanismSystem::new(&model, Channels::default(), 0, None);
    let tight = Settings { rtol: 1e-11, atol: 1e-14, ..Settings::default() };
    integrate(&mut reference, Method::Radau, 0.0, &y0, T_END, &[], &tight).unwrap();
    for (what, y) in [("lifted", &y_l), ("dense", &y_d)] {
        let worst = allowances(y, &reference.last_y);
        eprintln!("{what}: against the tight reference {worst:.2e} of the error allowance");
        assert!(worst < 3.0, "{what}: {worst:.3e}");
    }
    let m = 3 * model.n_bodies();
    assert!((y_l[2 * m] - y0[2 * m]).abs() > 1e-3, "the temperature moved ({} -> {})", y0[2 * m], y_l[2 * m]);
}

/// The span of the runs of [`lifted_and_dense`] \[s\].
const T_END: f64 = 0.01;

/// `model` run by `method` from its initial state over [`T_END`] at rtol 1e-6, atol 1e-9,
/// through the lifted form and through the dense form: `(y0, (stats, end state) lifted, (stats,
/// end state) dense)`.
fn lifted_and_dense(model: &Model, method: Method) -> (Vec<f64>, Run, Run) {
    let y = common::initial_state(model);
    let y0 = model.initial_state(&y[..y.len() / 2], &y[y.len() / 2..]); // (q, q̇) and any T
    let s = Settings { rtol: 1e-6, atol: 1e-9, ..Settings::default() };
    let mut lifted = MechanismSystem::new(model, Channels::default(), 0, None);
    let st_l = integrate(&mut lifted, method, 0.0, &y0, T_END, &[], &s).unwrap();
    let mut inner = MechanismSystem::new(model, Channels::default(), 0, None);
    let st_d = integrate(&mut DenseOnly(&mut inner), method, 0.0, &y0, T_END, &[], &s).unwrap();
    eprintln!("lifted {st_l:?}\ndense  {st_d:?}");
    (y0, (st_l, lifted.last_y.clone()), (st_d, inner.last_y.clone()))
}

/// A run's statistics and end state.
type Run = (Stats, Vec<f64>);

/// The largest difference of `y` from `reference`, in error allowances 1e-9 + 1e-6 |reference|.
fn allowances(y: &[f64], reference: &[f64]) -> f64 {
    y.iter().zip(reference).map(|(a, b)| (a - b).abs() / (1e-9 + 1e-6 * b.abs())).fold(0.0, f64::max)
}

fn radau5_lifted_against_dense(model: Model) {
    let (y0, (st_l, y_l), (st_d, y_d)) = lifted_and_dense(&model, Method::Radau);
    assert_eq!((st_l.steps_accepted, st_l.steps_rejected), (st_d.steps_accepted, st_d.steps_rejected));
    // The lifted form was taken: its differenced fallback Jacobians (after slow Newton
    // iterations, at the same steps in both runs) cost 6 g + 2 residuals, the dense one's n.
    assert!(2 * st_l.rhs_evals < st_d.rhs_evals, "lifted {} vs dense {} right-hand sides", st_l.rhs_evals, st_d.rhs_evals);
    let worst = allowances(&y_l, &y_d);
    eprintln!("largest end-state difference: {worst:.2e} of the error allowance");
    assert!(worst < 1e-3, "{worst:.3e}");
    let m = 3 * model.n_bodies();
    if model.heat_states() > 0 {
        let (t0, t1) = (y0[2 * m], y_l[2 * m]);
        eprintln!("first oil temperature: {t0} K -> {t1} K");
        assert!((t1 - t0).abs() > 1e-3, "the temperature moved ({t0} -> {t1})");
    }
}

/// RODAS4's Jacobian costs a fixed number of residuals whatever the size (groups of bodies ×
/// 6), where differencing the right-hand side costs one per state component: right-hand sides
/// per step at 80 links within 1.5× of those at 20.
#[test]
fn rodas4_work_per_step_does_not_grow_with_the_chain() {
    let per_step = |n: usize| {
        let model = Model::compile(&common::lubricated_chain(n, 4)).unwrap();
        let y0 = common::initial_state(&model);
        let mut sys = MechanismSystem::new(&model, Channels::default(), 0, None);
        let s = Settings { rtol: 1e-6, atol: 1e-9, ..Settings::default() };
        let st = integrate(&mut sys, Method::Rodas4, 0.0, &y0, 0.002, &[], &s).unwrap();
        st.rhs_evals as f64 / (st.steps_accepted + st.steps_rejected) as f64
    };
    let (small, large) = (per_step(20), per_step(80));
    eprintln!("RODAS4 right-hand sides per step: {small:.1} (20 links), {large:.1} (80 links)");
    assert!(large < 1.5 * small, "{small:.1} → {large:.1}");
}
