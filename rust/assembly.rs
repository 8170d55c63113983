//! Initial conditions (spec §1): Newton assembly of the ideal mechanism at t0 from the user's
//! approximate poses (clearance journals placed at their initial eccentricity), then the
//! consistent velocities Φq q̇ = −Φt. Both corrections are minimum-norm (unit weights).

use crate::constraints::Constraint;
use crate::error::{Error, Result};
use crate::model::Model;
use crate::system::Workspace;

const MAX_ITERATIONS: usize = 60;

/// The positions and velocities (q0, q̇0) of a consistent initial state.
pub fn assemble(model: &Model, t0: f64) -> Result<(Vec<f64>, Vec<f64>)> {
    // The clearance joints become revolute joints with the initial eccentricity as offset.
    let mut ideal = model.clone();
    for (c, e) in model.clearance.iter().zip(&model.initial_eccentricity) {
        ideal.constraints.push(Constraint::Revolute {
            a: c.journal,
            sa: c.journal_point,
            b: c.bearing,
            sb: c.bearing_point,
            offset: *e,
        });
        ideal.rows += 2;
    }
    ideal.clearance.clear();
    let n = 3 * model.n_bodies();
    if ideal.rows > n {
        return Err(Error::Assembly {
            t: t0,
            residual: f64::NAN,
            reason: format!("{} constraint equations for {} coordinates: the mechanism is over-constrained", ideal.rows, n),
        });
    }
    let mut ws = Workspace::with_weights(&ideal, vec![1.0; n]);
    let mut q = model.q_guess.clone();
    let zeros = vec![0.0; n];
    let mut dq = vec![0.0; n];
    let scale = 1.0 + q.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let tol = 1e-13 * scale;
    let mut residual = f64::INFINITY;
    for _ in 0..MAX_ITERATIONS {
        ws.eval_constraints(&ideal, t0, &q, &zeros);
        residual = ws.phi.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if !residual.is_finite() {
            break;
        }
        if residual <= tol {
            break;
        }
        // Minimum-norm Newton step: Δq = −Φqᵀ (Φq Φqᵀ)⁻¹ Φ.
        ws.force.iter_mut().for_each(|f| *f = 0.0);
        ws.c.copy_from_slice(&ws.phi);
        ws.solve_kkt(t0).map_err(|_| Error::Assembly {
            t: t0,
            residual,
            reason: "the constraint Jacobian is singular at the guessed pose (redundant joints or a toggle position)".into(),
        })?;
        // With zero force and c = Φ the solver returns q̈ = Φqᵀ (Φq Φqᵀ)⁻¹ Φ = −Δq.
        for i in 0..n {
            dq[i] = -ws.qdd[i];
            q[i] += dq[i];
        }
    }
    if !(residual <= tol) {
        return Err(Error::Assembly {
            t: t0,
            residual,
            reason: format!("Newton did not converge in {MAX_ITERATIONS} iterations; give body positions and angles closer to an assembled pose"),
        });
    }
    // Velocities: project the guess onto Φq q̇ = −Φt.
    ws.eval_constraints(&ideal, t0, &q, &zeros);
    ws.force.copy_from_slice(&model.qd_guess);
    for r in 0..ideal.rows {
        ws.c[r] = -ws.phi_t[r];
    }
    ws.solve_kkt(t0).map_err(|_| Error::Assembly { t: t0, residual, reason: "singular Jacobian in the velocity analysis".into() })?;
    let qd = ws.qdd.clone();
    Ok((q, qd))
}
