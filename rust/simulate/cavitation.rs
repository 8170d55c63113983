//! The film content of the joints with mass-conserving cavitation along a run
//! (rust/clearance/cavitation.rs): given to their memory at the start, advanced after every
//! accepted step. A run without such a joint does nothing here.

use super::MechanismSystem;
use crate::clearance::cavitation::FilmContent;
use crate::integrate::DenseOutput;
use crate::laws::transition::film_eps;
use crate::laws::FilmState;

impl MechanismSystem<'_> {
    /// Flood the film of every mass-conserving joint (the run starts with a full bearing).
    pub fn cavitation_start(&mut self) {
        for j in 0..self.model.clearance.len() {
            let Some(film) = self.model.clearance[j].film.as_ref().filter(|f| f.mass_conserving) else { continue };
            let g = film.geometry;
            self.memory[j].film = Some(FilmContent::flooded(2.0 * g.journal_radius / g.length).shared());
            self.memory[j].film_generation = 0;
            // The first output (at t0) is evaluated with the step memory.
            self.step_memory[j] = self.memory[j].clone();
        }
    }

    /// Advance the content of every mass-conserving joint over the accepted step (t0, t1]
    /// (its film states from the dense output); `true` if any (f(t1, y1) changed with it).
    pub(super) fn cavitation_step(&mut self, t0: f64, t1: f64, dense: &dyn DenseOutput) -> bool {
        let mut any = false;
        for j in 0..self.memory.len() {
            let Some(content) = self.memory[j].film.clone() else { continue };
            let Some(film) = self.model.clearance[j].film.as_ref() else { continue };
            let g = film.geometry_at(&self.memory[j]);
            let mut s = std::mem::take(&mut self.scratch);
            let nq = 3 * self.model.n_bodies();
            // How far the content moves against the line of centres: the mean surface speed's
            // travel (Simpson) less the line's turn over the step (from its two ends: exact, also
            // where it turns by π through the bearing's centre).
            let mut ends = [(0.0, 0.0); 3];
            for (k, f) in [0.0, 0.5, 1.0].into_iter().enumerate() {
                dense.eval(t0 + f * (t1 - t0), &mut s);
                let kin = self.joint_kinematics(j, &s);
                let (w_b, w_j) = crate::clearance::body_rates(&self.model.clearance[j], &s[nq..2 * nq]);
                ends[k] = (0.5 * (w_b + w_j), kin.e_vec.y.atan2(kin.e_vec.x));
            }
            let turn = (ends[2].1 - ends[0].1 + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
            let shift = (t1 - t0) * (ends[0].0 + 4.0 * ends[1].0 + ends[2].0) / 6.0 - turn;
            let mut state_at = |f: f64| {
                dense.eval(t0 + f * (t1 - t0), &mut s);
                let k = self.joint_kinematics(j, &s);
                FilmState { eps: film_eps(k.eps, film.eps_max), eps_dot: k.eps_dot, wedge: k.wedge }
            };
            let mut c = content.lock().unwrap_or_else(|e| e.into_inner());
            c.advance(&g, t1 - t0, shift, &mut state_at);
            self.memory[j].film_generation = c.generation;
            drop(c);
            self.scratch = s;
            any = true;
        }
        any
    }
}
