//! The film content of the joints with mass-conserving cavitation along a run
//! (rust/clearance/cavitation.rs): given to their memory at the start, advanced after every
//! accepted step (from the film's state at the step's end). A run without such a joint does
//! nothing here.

use super::MechanismSystem;
use crate::clearance::cavitation::FilmContent;
use crate::laws::transition::film_eps;
use crate::laws::FilmState;

impl MechanismSystem<'_> {
    /// Flood the film of every mass-conserving joint (the run starts with a full bearing at `t0` \[s\]).
    pub fn cavitation_start(&mut self, t0: f64) {
        for j in 0..self.model.clearance.len() {
            let Some(film) = self.model.clearance[j].film.as_ref().filter(|f| f.mass_conserving) else { continue };
            let g = film.geometry;
            let mut content = FilmContent::flooded(2.0 * g.journal_radius / g.length);
            content.start_at(t0);
            self.memory[j].film = Some(content.shared());
            self.memory[j].film_generation = 0;
            // The first output (at t0) is evaluated with the step memory.
            self.step_memory[j] = self.memory[j].clone();
        }
    }

    /// Advance the content of every mass-conserving joint over the accepted step (t0, t1] (its
    /// film state at t1 from `y1`); `true` if any (f(t1, y1) is unchanged by it, but an explicit
    /// method's last stage was evaluated with the step's content).
    pub(super) fn cavitation_step(&mut self, t0: f64, t1: f64, y1: &[f64]) -> bool {
        let mut any = false;
        for j in 0..self.memory.len() {
            let Some(content) = self.memory[j].film.clone() else { continue };
            let Some(film) = self.model.clearance[j].film.as_ref() else { continue };
            let g = film.geometry_at(&self.memory[j]);
            let k = self.joint_kinematics(j, y1);
            let s = FilmState { eps: film_eps(k.eps, film.eps_max), eps_dot: k.eps_dot, wedge: k.wedge };
            let mut c = content.lock().unwrap_or_else(|e| e.into_inner());
            c.now = t1;
            c.advance(&g, t0, t1, s);
            self.memory[j].film_generation = c.generation;
            drop(c);
            any = true;
        }
        any
    }
}
