//! What a failed run says about where it stood: the clearance joint nearest contact, and a
//! lock-up (a dead centre) when the constraint Jacobian has lost rank at the last accepted state.

use super::MechanismSystem;
use crate::clearance::JointKinematics;
use crate::error::Error;
use crate::rank;

impl MechanismSystem<'_> {
    /// The clearance joint closest to (or deepest in) contact at the last accepted state.
    pub fn worst_joint(&self) -> Option<(usize, JointKinematics)> {
        let mut worst: Option<(usize, JointKinematics)> = None;
        for j in 0..self.model.clearance.len() {
            let k = self.joint_kinematics(j, &self.last_y);
            if worst.as_ref().is_none_or(|(_, w)| k.eps > w.eps || !k.eps.is_finite()) {
                worst = Some((j, k));
            }
        }
        worst
    }

    /// For a run that stopped for want of step size (or a singular KKT matrix, a non-finite
    /// state): a [`Error::LockUp`] naming the joints and drivers when the constraint Jacobian at
    /// the last accepted state has lost rank ([`rank::analyse`]: a dead centre), else `None`.
    /// Only on this failure path: one dense SVD of Φq.
    pub fn lock_up(&mut self, e: &Error) -> Option<Error> {
        let how = match e {
            Error::StepSizeUnderflow { h, .. } => format!("the steps shrank to h = {h:.1e} s"),
            Error::NewtonFailure { h, .. } => format!("the Newton iteration failed down to h = {h:.1e} s"),
            Error::SingularJacobian { .. } => "the KKT matrix became singular".into(),
            Error::NonFinite { .. } => "the state stopped being finite".into(),
            _ => return None,
        };
        if self.model.rows == 0 {
            return None;
        }
        let n = 3 * self.model.n_bodies();
        let (q, qd) = self.last_y.split_at(n);
        self.ws.eval_constraints(self.model, self.last_t, q, qd);
        let report = rank::analyse(self.model, &self.ws.jac, &self.ws.kin);
        report.deficient().then(|| Error::LockUp { t: self.last_t, reason: format!("{} ({how})", report.lock_up(self.model, self.last_t)) })
    }

    /// Where a failed run stood, for the error message.
    pub fn diagnosis(&self) -> String {
        let mut out = String::new();
        if let Some((j, k)) = self.worst_joint() {
            let c = &self.model.clearance[j];
            let state = if k.delta > 0.0 { "in contact" } else if c.film.is_some() { "in the film" } else { "free" };
            out.push_str(&format!(
                "; last accepted t = {:.9} s; joint '{}' {} at eccentricity ε = {:.6} (δ = {:.3e} m, δ̇ = {:.3e} m/s)",
                self.last_t, c.name, state, k.eps, k.delta, k.delta_dot
            ));
        } else {
            out.push_str(&format!("; last accepted t = {:.9} s", self.last_t));
        }
        out
    }
}
