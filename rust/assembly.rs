//! Initial conditions (docs/physics.md §1): the pose given is the mechanism's pose at t = 0, the
//! drivers' reference time. Newton assembly of the ideal mechanism at t = 0 from it (clearance
//! journals placed at their initial eccentricity: [`pose_at_zero`], once per compiled model, kept
//! in [`Model::start`]), then, for a start t0 ≠ 0, the drivers followed from 0 to t0 by
//! continuation on the branch of that pose, and the consistent velocities Φq q̇ = −Φt at t0
//! ([`assemble`]). Corrections are minimum-norm (unit weights). A Jacobian that loses rank on
//! the way is named (joints, drivers, time) by [`crate::rank`].

use std::sync::atomic::{AtomicUsize, Ordering};

use crate::constraints::Constraint;
use crate::error::{Error, Result};
use crate::model::Model;
use crate::rank;
use crate::system::Workspace;

const MAX_ITERATIONS: usize = 60;
/// Newton iterations a continuation step may take before it is retried shorter.
const STEP_ITERATIONS: usize = 8;
/// Largest turn of any body \[rad\] (or move, over the mechanism's size) per continuation step.
const STEP_TURN: f64 = 0.05;
/// A continuation step's Newton correction may be at most this fraction of the step's motion:
/// a larger one could land on another branch.
const STEP_CORRECTION: f64 = 0.05;

/// Assemblies of a pose given ([`pose_at_zero`]) since the process started (for tests that
/// count them: one per compiled model).
static ASSEMBLIES: AtomicUsize = AtomicUsize::new(0);

/// How many poses given this process has assembled ([`pose_at_zero`]).
pub fn assembly_count() -> usize {
    ASSEMBLIES.load(Ordering::Relaxed)
}

/// The Newton tolerance on ‖Φ‖∞ of a model's assembly (from the size of the pose given).
fn tolerance(model: &Model) -> f64 {
    1e-13 * (1.0 + model.q_guess.iter().fold(0.0f64, |m, v| m.max(v.abs())))
}

/// The positions and velocities (q0, q̇0) of a consistent initial state at `t0`, from the pose
/// given assembled at t = 0 ([`Model::start`], or assembled now if the model holds none).
pub fn assemble(model: &Model, t0: f64) -> Result<(Vec<f64>, Vec<f64>)> {
    let mut q = match &model.start {
        Some(Ok(q)) => q.clone(),
        Some(Err(e)) => return Err(e.clone()),
        None => pose_at_zero(model)?,
    };
    let ideal = held(model);
    let n = 3 * model.n_bodies();
    let mut ws = Workspace::with_weights(&ideal, vec![1.0; n]);
    let tol = tolerance(model);
    if t0 != 0.0 && ideal.constraints.iter().any(|c| matches!(c, Constraint::Driver { .. })) {
        follow_drivers(&ideal, &mut ws, &mut q, t0, tol)?;
    }
    // Velocities: project the guess onto Φq q̇ = −Φt.
    let zeros = vec![0.0; n];
    ws.eval_constraints(&ideal, t0, &q, &zeros);
    ws.force.copy_from_slice(&model.qd_guess);
    for r in 0..ideal.rows {
        ws.c[r] = -ws.phi_t[r];
    }
    if let Err(e) = ws.solve_kkt(t0) {
        let report = analysed(&ideal, &mut ws, t0, &q);
        let reason = if redundant(&ideal, &mut ws, &q) {
            format!("the constraint Jacobian is singular at the assembled pose: {}", analysed(&ideal, &mut ws, t0, &q).over_constraint(&ideal))
        } else if report.deficient() {
            format!("the constraint Jacobian is singular at the assembled pose: {}", report.lock_up(&ideal, t0))
        } else {
            format!("the constraint Jacobian is singular at the assembled pose, at {}: it is redundant with other joints, or the pose is a toggle position", singular_constraint(&ideal, &e))
        };
        return Err(Error::Assembly { t: t0, residual: residual(&ws), reason });
    }
    let qd = ws.qdd.clone();
    Ok((q, qd))
}

/// The pose given (the pose at t = 0) assembled: the positions q closing every loop, by
/// minimum-norm Newton from `model.q_guess`. An error names what stops it: redundant joints, a
/// dead centre, or the joint whose points lie furthest apart at the pose given (a point given in
/// the global instead of the body frame, a wrong length).
pub fn pose_at_zero(model: &Model) -> Result<Vec<f64>> {
    ASSEMBLIES.fetch_add(1, Ordering::Relaxed);
    let ideal = held(model);
    let n = 3 * model.n_bodies();
    let mut ws = Workspace::with_weights(&ideal, vec![1.0; n]);
    let mut q = model.q_guess.clone();
    if ideal.rows > n {
        return Err(over_constrained(&ideal, &mut ws, &q));
    }
    let tol = tolerance(model);
    match newton(&ideal, &mut ws, 0.0, &mut q, tol, MAX_ITERATIONS) {
        Ok(_) => {}
        Err(Failure::Singular(e)) => {
            let at = singular_constraint(&ideal, &e);
            let report = analysed(&ideal, &mut ws, 0.0, &q);
            let reason = if redundant(&ideal, &mut ws, &q) {
                format!("the constraint Jacobian is singular (at {at}): {}", report.over_constraint(&ideal))
            } else if report.deficient() {
                format!("the constraint Jacobian is singular during assembly (at {at}): {}", report.lock_up(&ideal, 0.0))
            } else {
                format!("the constraint Jacobian became singular during assembly at {at}: it is redundant with other joints, the pose is a toggle position, or the loop cannot close with these link lengths")
            };
            return Err(Error::Assembly { t: 0.0, residual: residual(&ws), reason });
        }
        Err(Failure::NotConverged(residual)) => {
            // The equation that is furthest from closing names the joint to look at, unless one
            // joint's points lie far apart already at the pose given: that one is the suspect.
            let worst = ws.phi.iter().enumerate().fold((0, -1.0f64), |w, (r, v)| if !(v.abs() <= w.1) { (r, v.abs()) } else { w }).0;
            let furthest = (ideal.constraint_of_row(worst), ws.phi[worst].abs());
            let suspect = match widest_gap(&ideal, &mut ws, &model.q_guess) {
                Some((name, gap)) if gap > GAP_SUSPECT * span(&model.q_guess) => format!(
                    "{name} has its two points {} m apart at the pose given, the most of any joint (furthest from closing now: {}, |Φ| = {:.3e})",
                    crate::text::g(gap, 3),
                    furthest.0,
                    furthest.1
                ),
                _ => format!("{} is furthest from closing (|Φ| = {:.3e})", furthest.0, furthest.1),
            };
            return Err(Error::Assembly {
                t: 0.0,
                residual,
                reason: format!("Newton did not converge in {MAX_ITERATIONS} iterations; {suspect}: check its points (body frame, not global) and give body positions and angles closer to an assembled pose"),
            });
        }
    }
    Ok(q)
}

/// A joint whose two points lie further apart at the pose given than this fraction of the
/// mechanism's [`span`] is named as the likely cause of an assembly that does not converge.
const GAP_SUSPECT: f64 = 0.05;

/// The mechanism's span \[m\] at the coordinates `q` (3 per body): the x extent plus the y extent
/// of the bodies' centroids, at least 1 mm (docs/physics.md §1). The one definition of the word:
/// the continuation's step (`follow_drivers`), the pose check ([`crate::pose`]) and the
/// plausibility checks ([`crate::compile::plausibility`], over the joints' points: [`extent`]).
pub fn span(q: &[f64]) -> f64 {
    extent(q.chunks(3).map(|c| (c[0], c[1]))).max(1e-3)
}

/// The x extent plus the y extent of a set of points \[m\] (0 for none).
pub fn extent(points: impl Iterator<Item = (f64, f64)>) -> f64 {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for (x, y) in points {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    if x1 < x0 {
        0.0
    } else {
        (x1 - x0) + (y1 - y0)
    }
}

/// The revolute joint (ideal, or a clearance joint held at its initial eccentricity) whose two
/// points lie furthest apart at the positions `q`, and that distance \[m\].
fn widest_gap(ideal: &Model, ws: &mut Workspace, q: &[f64]) -> Option<(String, f64)> {
    let zeros = vec![0.0; q.len()];
    ws.eval_constraints(ideal, 0.0, q, &zeros);
    let mut row = 0;
    let mut best: Option<(usize, f64)> = None;
    for (k, c) in ideal.constraints.iter().enumerate() {
        if matches!(c, Constraint::Revolute { .. }) {
            let gap = ws.phi[row].hypot(ws.phi[row + 1]);
            if best.is_none_or(|(_, b)| gap > b) {
                best = Some((k, gap));
            }
        }
        row += c.rows();
    }
    best.map(|(k, gap)| (ideal.constraint_names[k].clone(), gap))
}

/// The ideal mechanism of the assembly: revolute clearance joints held at their initial
/// eccentricity, prismatic ones centred and aligned.
fn held(model: &Model) -> Model {
    let mut ideal = model.clone();
    for (name, c) in &model.assembly {
        ideal.constraint_names.push(name.clone());
        ideal.rows += c.rows();
        ideal.constraints.push(c.clone());
    }
    ideal.clearance.clear();
    ideal
}

/// Why a Newton iteration stopped short.
enum Failure {
    /// A singular pivot of the KKT solve.
    Singular(Error),
    /// The residual ‖Φ‖∞ left after the iterations (NaN if it stopped being finite).
    NotConverged(f64),
}

fn residual(ws: &Workspace) -> f64 {
    ws.phi.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// Minimum-norm Newton iteration Δq = −Φqᵀ (Φq Φqᵀ)⁻¹ Φ on Φ(q, t) = 0 from `q`, until
/// ‖Φ‖∞ ≤ `tol`. Returns the iterations taken.
fn newton(ideal: &Model, ws: &mut Workspace, t: f64, q: &mut [f64], tol: f64, max_iterations: usize) -> std::result::Result<usize, Failure> {
    let zeros = vec![0.0; q.len()];
    for k in 0..=max_iterations {
        ws.eval_constraints(ideal, t, q, &zeros);
        let r = residual(ws);
        if !r.is_finite() {
            return Err(Failure::NotConverged(f64::NAN));
        }
        if r <= tol {
            return Ok(k);
        }
        if k == max_iterations {
            return Err(Failure::NotConverged(r));
        }
        ws.force.iter_mut().for_each(|f| *f = 0.0);
        ws.c.copy_from_slice(&ws.phi);
        ws.solve_kkt(t).map_err(Failure::Singular)?;
        // With zero force and c = Φ the solver returns q̈ = Φqᵀ (Φq Φqᵀ)⁻¹ Φ = −Δq.
        for (qi, d) in q.iter_mut().zip(&ws.qdd) {
            *qi -= d;
        }
    }
    unreachable!("the loop returns")
}

/// The minimum-norm rates at the assembled pose (t, q): q̇ solving Φq q̇ = −Φt into `v`, and q̈
/// solving Φq q̈ = γ(q, q̇) into `a`.
fn rates(ideal: &Model, ws: &mut Workspace, t: f64, q: &[f64], v: &mut [f64], a: &mut [f64]) -> Result<()> {
    let zeros = vec![0.0; q.len()];
    ws.eval_constraints(ideal, t, q, &zeros);
    ws.force.iter_mut().for_each(|f| *f = 0.0);
    for r in 0..ideal.rows {
        ws.c[r] = -ws.phi_t[r];
    }
    ws.solve_kkt(t)?;
    v.copy_from_slice(&ws.qdd);
    ws.eval_constraints(ideal, t, q, v);
    ws.force.iter_mut().for_each(|f| *f = 0.0);
    ws.c.copy_from_slice(&ws.gamma);
    ws.solve_kkt(t)?;
    a.copy_from_slice(&ws.qdd);
    Ok(())
}

/// Follow the drivers from the pose assembled at t = 0 (in `q`) to `t0` by continuation: steps
/// in time, each a Newton correction of q + Δt q̇ + Δt²/2 q̈, short enough that no body turns by
/// more than [`STEP_TURN`] and the correction stays small against the motion (so it cannot jump
/// to another branch). A step that fails is retried shorter; a pose the drivers cannot be
/// followed past (a dead centre) is an `Assembly` error naming the dependent joints and drivers.
fn follow_drivers(ideal: &Model, ws: &mut Workspace, q: &mut Vec<f64>, t0: f64, tol: f64) -> Result<()> {
    let n = q.len();
    let size = span(q);
    let (mut v, mut a, mut trial) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let direction = t0.signum();
    let mut t = 0.0f64;
    let mut dt = f64::INFINITY;
    let floor = 1e-13 * t0.abs().max(1e-3);
    while t != t0 {
        if let Err(e) = rates(ideal, ws, t, q, &mut v, &mut a) {
            return Err(stuck(ideal, ws, t, q, t0, Some(e)));
        }
        // The fastest body sets the step: STEP_TURN rad, or that fraction of the size in m.
        let speed = (0..n).map(|i| if i % 3 == 2 { v[i].abs() } else { v[i].abs() / size }).fold(0.0f64, f64::max);
        let cap = if speed > 0.0 { STEP_TURN / speed } else { (t0 - t).abs() };
        dt = dt.min(cap).min((t0 - t).abs());
        loop {
            if dt < floor {
                return Err(stuck(ideal, ws, t, q, t0, None));
            }
            let h = direction * dt;
            let t1 = if (t0 - t).abs() <= dt { t0 } else { t + h };
            for i in 0..n {
                trial[i] = q[i] + h * v[i] + 0.5 * h * h * a[i];
            }
            let predicted = trial.clone();
            let motion = (0..n).map(|i| scaled(i, trial[i] - q[i], size)).fold(0.0f64, f64::max);
            if let Ok(iterations) = newton(ideal, ws, t1, &mut trial, tol, STEP_ITERATIONS) {
                let correction = (0..n).map(|i| scaled(i, trial[i] - predicted[i], size)).fold(0.0f64, f64::max);
                if correction <= STEP_CORRECTION * motion + 1e3 * tol {
                    q.copy_from_slice(&trial);
                    t = t1;
                    if iterations <= 3 {
                        dt *= 2.0;
                    }
                    break;
                }
            }
            dt *= 0.25;
        }
    }
    Ok(())
}

/// A coordinate change as a turn: angles as they are, positions over the mechanism's size.
fn scaled(i: usize, d: f64, size: f64) -> f64 {
    if i % 3 == 2 { d.abs() } else { d.abs() / size }
}

/// The error of a continuation that cannot go on at (t, q) towards t0.
fn stuck(ideal: &Model, ws: &mut Workspace, t: f64, q: &[f64], t0: f64, solve: Option<Error>) -> Error {
    let report = analysed(ideal, ws, t, q);
    let reason = if report.deficient() {
        format!("following the drivers from the pose given (t = 0) to t0 = {t0} s: {}", report.lock_up(ideal, t))
    } else {
        let what = solve.map_or_else(|| "the steps shrank to nothing".to_string(), |e| e.to_string());
        format!("following the drivers from the pose given (t = 0) to t0 = {t0} s stopped at t = {t:.9} s: {what}")
    };
    Error::Assembly { t, residual: residual(ws), reason }
}

/// [`rank::analyse`] of Φq at (t, q).
fn analysed(ideal: &Model, ws: &mut Workspace, t: f64, q: &[f64]) -> rank::RankReport {
    let zeros = vec![0.0; q.len()];
    ws.eval_constraints(ideal, t, q, &zeros);
    rank::analyse(ideal, &ws.jac, &ws.kin)
}

/// Whether Φq's rows are dependent at every pose near `q` (redundant joints or drivers), not
/// only at this one (a dead centre): the rank test repeated at a pose moved by ~1e-3 (rad, or
/// that fraction of the mechanism's size) in every coordinate, a fixed pseudo-random pattern.
fn redundant(ideal: &Model, ws: &mut Workspace, q: &[f64]) -> bool {
    let size = 1.0 + q.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let moved: Vec<f64> = q.iter().enumerate().map(|(i, v)| v + 1e-3 * (if i % 3 == 2 { 1.0 } else { size }) * ((i as f64 * 0.618_034).fract() - 0.5)).collect();
    let report = analysed(ideal, ws, 0.0, &moved);
    report.rows > report.coordinates || report.ratio <= 1e-9
}

/// The error of a mechanism with more constraint equations than coordinates.
fn over_constrained(ideal: &Model, ws: &mut Workspace, q: &[f64]) -> Error {
    let report = analysed(ideal, ws, 0.0, q);
    Error::Assembly { t: 0.0, residual: residual(ws), reason: report.over_constraint(ideal) }
}

/// The constraint named by a singular-pivot error of the KKT solve.
fn singular_constraint(model: &Model, e: &Error) -> String {
    match e {
        Error::SingularJacobian { index, .. } => model.constraint_of_row(*index),
        _ => "a constraint".into(),
    }
}
