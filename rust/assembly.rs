//! Initial conditions (docs/physics.md §1): Newton assembly of the ideal mechanism at t0 from the user's
//! approximate poses (clearance journals placed at their initial eccentricity), then the
//! consistent velocities Φq q̇ = −Φt. Both corrections are minimum-norm (unit weights).

use crate::error::{Error, Result};
use crate::model::Model;
use crate::system::Workspace;

const MAX_ITERATIONS: usize = 60;

/// The positions and velocities (q0, q̇0) of a consistent initial state.
pub fn assemble(model: &Model, t0: f64) -> Result<(Vec<f64>, Vec<f64>)> {
    // Revolute clearance joints are held at their initial eccentricity, prismatic ones centred.
    let mut ideal = model.clone();
    for (name, c) in &model.assembly {
        ideal.constraint_names.push(name.clone());
        ideal.rows += c.rows();
        ideal.constraints.push(c.clone());
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
        ws.solve_kkt(t0).map_err(|e| Error::Assembly {
            t: t0,
            residual,
            reason: format!(
                "the constraint Jacobian became singular during assembly at {}: it is redundant with other joints, the pose is a toggle position, or the loop cannot close with these link lengths",
                singular_constraint(&ideal, &e)
            ),
        })?;
        // With zero force and c = Φ the solver returns q̈ = Φqᵀ (Φq Φqᵀ)⁻¹ Φ = −Δq.
        for i in 0..n {
            dq[i] = -ws.qdd[i];
            q[i] += dq[i];
        }
    }
    if !(residual <= tol) {
        // The equation that is furthest from closing names the joint to look at.
        let worst = ws.phi.iter().enumerate().fold((0, -1.0f64), |w, (r, v)| if !(v.abs() <= w.1) { (r, v.abs()) } else { w }).0;
        return Err(Error::Assembly {
            t: t0,
            residual,
            reason: format!(
                "Newton did not converge in {MAX_ITERATIONS} iterations; {} is furthest from closing (|Φ| = {:.3e}): check its points (body frame) and give body positions and angles closer to an assembled pose",
                ideal.constraint_of_row(worst),
                ws.phi[worst].abs()
            ),
        });
    }
    // Velocities: project the guess onto Φq q̇ = −Φt.
    ws.eval_constraints(&ideal, t0, &q, &zeros);
    ws.force.copy_from_slice(&model.qd_guess);
    for r in 0..ideal.rows {
        ws.c[r] = -ws.phi_t[r];
    }
    ws.solve_kkt(t0).map_err(|e| Error::Assembly {
        t: t0,
        residual,
        reason: format!(
            "the constraint Jacobian is singular at the assembled pose, at {}: it is redundant with other joints, or the pose is a toggle position",
            singular_constraint(&ideal, &e)
        ),
    })?;
    let qd = ws.qdd.clone();
    Ok((q, qd))
}

/// The constraint named by a singular-pivot error of the KKT solve.
fn singular_constraint(model: &Model, e: &Error) -> String {
    match e {
        Error::SingularJacobian { index, .. } => model.constraint_of_row(*index),
        _ => "a constraint".into(),
    }
}
