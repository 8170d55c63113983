//! What a failed run says about where it stood: the clearance joint nearest contact, a lock-up
//! (a dead centre) when the constraint Jacobian has lost rank at the last accepted state, and
//! what to try when a lubricated run stalls ([`failure_hint`]).

use super::MechanismSystem;
use crate::clearance::JointKinematics;
use crate::error::Error;
use crate::laws::FilmModel;
use crate::model::Model;
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

/// R_j/c from which a lubricated joint counts as a µm film: a long-bearing film there can crawl
/// in a whirl near the centre, and a journal released at rest against the wall can stall at
/// once (measured at R_j = 9.5 mm: docs/hard_cases.md, *µm films*).
pub const MICROMETRE_FILM_RATIO: f64 = 4000.0;

/// What to try when a lubricated run stalls ([`Error::is_stall`]) where the film model, not the
/// solver, sets the pace (docs/hard_cases.md, after the table), chosen by the kind of failure and
/// the state of `failure` (the clearance joint nearest contact and its ε): a journal released at
/// rest against the wall that cannot leave it (any clearance), and in a µm film
/// (R/c ≥ [`MICROMETRE_FILM_RATIO`]) a half-speed whirl along the wall or the long film's whirl
/// near the centre. `None` when none of these fits.
pub fn failure_hint(model: &Model, error: &Error, failure: Option<&(String, f64)>) -> Option<String> {
    let (name, eps) = failure?;
    let joint = model.clearance.iter().find(|c| &c.name == name)?;
    let film = joint.film.as_ref()?;
    if !error.is_stall() {
        return None;
    }
    let (r, c) = (joint.journal_radius, joint.clearance);
    let ratio = r / c;
    let kind = match film.model {
        FilmModel::LongBearing => "long",
        FilmModel::ShortBearing => "short",
        FilmModel::LongBearingPaperClosedForm => "long_paper",
        FilmModel::Finite => "finite",
    };
    let at = format!("joint '{name}' has a {} µm '{kind}' film (R/c = {ratio:.0})", crate::text::g(c * 1e6, 3));
    if *eps >= 0.9 && error.time() == Some(0.0) {
        return Some(format!(
            "hint: {at} and its journal was released at rest against the wall with the drive already at speed: the film pushes with a force so large and so nonlinear that the first steps cannot converge: start it centred or off the wall (docs/hard_cases.md lists the clearances each film releases from)"
        ));
    }
    if ratio < MICROMETRE_FILM_RATIO {
        return None;
    }
    if *eps >= 0.9 {
        return Some(format!(
            "hint: {at} and its journal sits against the wall, likely whirling along it at half the shaft speed (wedge ≈ 0, no load capacity) where the squeeze film is as stiff as at contact: start it centred or off the wall (docs/hard_cases.md)"
        ));
    }
    if film.model == FilmModel::LongBearing && *eps < 0.5 {
        return Some(format!(
            "hint: {at}; a journal whirling near the centre of a µm long-bearing (half-Sommerfeld) film meets a negative squeeze damping and the run crawls: film='finite', supply='none' (the periodic film) damps it; the default supply line crawls like the long film (docs/hard_cases.md)"
        ));
    }
    None
}
