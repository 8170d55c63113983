//! The film content of the joints with mass-conserving cavitation along a run
//! (rust/clearance/cavitation.rs): given to their memory at the start, advanced after every
//! accepted step. A run without such a joint does nothing here.

use super::MechanismSystem;
use crate::clearance::cavitation::FilmContent;
use crate::integrate::DenseOutput;
use crate::laws::transition::film_eps;
use crate::laws::FilmState;

impl MechanismSystem<'_> {
    /// Flood the content of every mass-conserving joint at its eccentricity in `y0`.
    pub fn cavitation_start(&mut self, y0: &[f64]) {
        for j in 0..self.model.clearance.len() {
            let Some(film) = self.model.clearance[j].film.as_ref().filter(|f| f.mass_conserving) else { continue };
            let k = self.joint_kinematics(j, y0);
            let g = film.geometry;
            self.memory[j].film = Some(FilmContent::flooded(2.0 * g.journal_radius / g.length, film_eps(k.eps, film.eps_max)).shared());
            self.memory[j].film_generation = 0;
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
            let mut state_at = |f: f64| {
                dense.eval(t0 + f * (t1 - t0), &mut s);
                let k = self.joint_kinematics(j, &s);
                FilmState { eps: film_eps(k.eps, film.eps_max), eps_dot: k.eps_dot, wedge: k.wedge }
            };
            let mut c = content.lock().unwrap_or_else(|e| e.into_inner());
            c.advance(&g, t1 - t0, &mut state_at);
            self.memory[j].film_generation = c.generation;
            drop(c);
            self.scratch = s;
            any = true;
        }
        any
    }
}
