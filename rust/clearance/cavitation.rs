//! The film content of a lubricated joint with mass-conserving cavitation
//! (`Lubricated(film="finite", cavitation="jfo")`, docs/physics.md §4, *Mass-conserving
//! cavitation*; the law: [`crate::laws::bearing_jfo`]): where the oil is over the bearing, carried
//! from step to step, and the oil books (supplied, leaked) over the run.
//!
//! State layout: the content (720 values a joint) is not part of the integrator's state
//! (q, q̇): it is held per accepted step, with the time it was taken, and every evaluation inside
//! a step advances the partly filled nodes' oil from it to the evaluation's time by backward
//! Euler inside the film's complementarity problem ([`JfoFilm::solve`]): the film reforms
//! within the step as the gap closes on it, and its pressure grows from 0 there, so the force is
//! continuous in the state and in time. The step's end makes the next content from the same
//! solve ([`FilmContent::advance`]): what the last evaluation saw, so the force does not jump at
//! a step's start either. The implicit methods' Newton matrix sees the content at the step's
//! start (the film force's derivatives, rust/clearance/mod.rs `force_derivatives`, are taken at
//! the time of the evaluation before). A run without such a joint has no content and runs none
//! of this code (one `Option` check per joint and evaluation, [`set_time`]).
//!
//! The joint's [`super::ImpactMemory`] holds the state (shared, behind a mutex: the solver's
//! buffers are reused by every evaluation) and the generation of the content it was evaluated
//! with: the step's own, or, for the outputs inside an accepted step (sampled after the
//! content was advanced), the one before.

use crate::laws::bearing_jfo::{JfoFilm, JfoReading, JFO_THETA, JFO_ZETA};
use crate::laws::geometry::{BearingGeometry, FilmState};
use std::sync::{Arc, Mutex};

/// The film content of one joint over a run.
#[derive(Debug, Clone)]
pub struct FilmContent {
    pub film: JfoFilm,
    /// The fill θ_f ∈ [0, 1] of every node by generation parity: `content[g % 2]` is generation g,
    /// measured against the gaps H of the cells `gaps[g % 2]` (at the end of the step that made
    /// it; empty: against the gaps wherever it is evaluated) at the time `taken[g % 2]` \[s\] (NaN:
    /// unknown, evaluated as at that time).
    content: [Vec<f64>; 2],
    gaps: [Vec<f64>; 2],
    taken: [f64; 2],
    /// The time \[s\] of the evaluation under way (set by every evaluation of the mechanism,
    /// [`set_time`]).
    pub now: f64,
    /// The newest generation.
    pub generation: u64,
    /// Oil fed through the supply groove and leaked at the ends since the start \[m³\].
    pub supplied: f64,
    pub leaked: f64,
}

/// A joint's content as its memory holds it.
pub type SharedContent = Arc<Mutex<FilmContent>>;

impl FilmContent {
    /// A bearing of diameter-to-length ratio `k`, flooded (full everywhere).
    pub fn flooded(k: f64) -> Self {
        Self::with(k, vec![1.0; JFO_THETA * JFO_ZETA])
    }

    fn with(k: f64, m: Vec<f64>) -> Self {
        FilmContent { film: JfoFilm::new(k), content: [m.clone(), m], gaps: [Vec::new(), Vec::new()], taken: [f64::NAN; 2], now: f64::NAN, generation: 0, supplied: 0.0, leaked: 0.0 }
    }

    /// A bearing of diameter-to-length ratio `k` holding the content `m` (as recorded by a run's
    /// `film` channel), or `None` if `m` is not one.
    pub fn holding(k: f64, m: &[f64]) -> Option<Self> {
        (m.len() == JFO_THETA * JFO_ZETA && m.iter().all(|v| v.is_finite() && (0.0..=1.0).contains(v))).then(|| Self::with(k, m.to_vec()))
    }

    /// Shared, for a joint's memory.
    pub fn shared(self) -> SharedContent {
        Arc::new(Mutex::new(self))
    }

    /// The parity of `generation` if it is still held (the newest or the one before), else the newest's.
    fn slot(&self, generation: u64) -> usize {
        let k = if generation == self.generation || generation + 1 == self.generation { generation } else { self.generation };
        (k % 2) as usize
    }

    /// The content of the run's start at time `t0` \[s\].
    pub fn start_at(&mut self, t0: f64) {
        self.taken = [t0; 2];
    }

    /// Solve the film of `g` in the state `s` with the content of `generation` at the time
    /// [`Self::now`] (partly filled nodes advanced to it, [`JfoFilm::solve`]).
    pub fn evaluate(&mut self, generation: u64, g: &BearingGeometry, s: FilmState) -> JfoReading {
        let k = self.slot(generation);
        let since = self.now - self.taken[k];
        self.film.solve(&self.content[k], &self.gaps[k], since, s.clamped_eps(), s.eps_dot, s.wedge);
        self.film.reading(g.journal_radius, g.clearance, g.length, g.viscosity, s.eps_dot)
    }

    /// Advance the content over an accepted step (t0, t1] \[s\], the film in the state `s` at its
    /// end: backward Euler in the oil ([`JfoFilm::solve`] at t1, [`JfoFilm::step_fill`]), so the
    /// new content is the one the step's last evaluation saw and the force does not jump at the
    /// next step's start. Books the oil supplied and leaked (the end's flows over the step: the
    /// same Euler, so the books balance the oil in the gap).
    pub fn advance(&mut self, g: &BearingGeometry, t0: f64, t1: f64, s: FilmState) {
        let old = self.slot(self.generation);
        if self.taken[old].is_nan() {
            self.taken[old] = t0;
        }
        let dt = t1 - self.taken[old];
        self.film.solve(&self.content[old], &self.gaps[old], dt, s.clamped_eps(), s.eps_dot, s.wedge);
        let r = self.film.reading(g.journal_radius, g.clearance, g.length, g.viscosity, s.eps_dot);
        let (a, b) = self.content.split_at_mut(1);
        let (from, to) = if old == 0 { (&a[0], &mut b[0]) } else { (&b[0], &mut a[0]) };
        self.film.step_fill(from, dt, to);
        let new = 1 - old;
        self.gaps[new].clear();
        self.gaps[new].extend_from_slice(self.film.gaps());
        self.taken[new] = t1;
        self.supplied += dt * r.supply;
        self.leaked += dt * r.side_leakage;
        self.generation += 1;
    }

    /// The oil in the gap of the newest content \[m³\] for the geometry `g` (NaN before the first
    /// step: its gaps are not kept).
    pub fn oil(&self, g: &BearingGeometry) -> f64 {
        let k = self.slot(self.generation);
        let gaps = if self.gaps[k].is_empty() { return f64::NAN } else { &self.gaps[k] };
        g.clearance * g.journal_radius * g.length * JfoFilm::oil_of(&self.content[k], gaps)
    }

    /// The fill of every node that `generation` gives in the state `s` at [`Self::now`] (what the
    /// film is evaluated with there, [`JfoFilm::fill`]).
    pub fn fill_at(&mut self, generation: u64, g: &BearingGeometry, s: FilmState) -> &[f64] {
        self.evaluate(generation, g, s);
        self.film.fill()
    }
}

/// Tell the film content of a joint's memory (if any) the time \[s\] of the evaluation under way.
#[inline]
pub fn set_time(memory: &super::ImpactMemory, t: f64) {
    if let Some(c) = &memory.film {
        c.lock().unwrap_or_else(|e| e.into_inner()).now = t;
    }
}

impl PartialEq for FilmContent {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self, other)
    }
}

/// The film force `(F_ξ, F_η)` \[N\] of a mass-conserving film in the state `s` with the content
/// `memory` holds (its generation); a memory without content (outside a run: `CompiledModel.rhs`,
/// tests) sees a flooded film.
#[cold]
#[inline(never)]
pub fn film_force(g: &BearingGeometry, s: FilmState, memory: &super::ImpactMemory) -> (f64, f64) {
    match &memory.film {
        Some(content) => content.lock().unwrap_or_else(|e| e.into_inner()).evaluate(memory.film_generation, g, s).force,
        None => FilmContent::flooded(2.0 * g.journal_radius / g.length).evaluate(0, g, s).force,
    }
}

/// The flows, peak and pressure field of a mass-conserving film in the state `s` with the content
/// `memory` holds (flooded without one), the field mirrored over the whole width as
/// [`crate::laws::film_field::film_field`] gives it.
pub fn readings(g: &BearingGeometry, s: FilmState, memory: &super::ImpactMemory, field: bool) -> (JfoReading, Option<crate::laws::film_field::FilmField>) {
    let mut own;
    let mut guard;
    let content: &mut FilmContent = match &memory.film {
        Some(c) => {
            guard = c.lock().unwrap_or_else(|e| e.into_inner());
            &mut guard
        }
        None => {
            own = FilmContent::flooded(2.0 * g.journal_radius / g.length);
            &mut own
        }
    };
    let r = content.evaluate(memory.film_generation, g, s);
    if !field {
        return (r, None);
    }
    let (theta, zeta) = JfoFilm::grid();
    let nz = zeta.len();
    let p_scale = 6.0 * g.viscosity * g.journal_radius * g.journal_radius / (g.clearance * g.clearance);
    let half = 0.5 * g.length;
    let z: Vec<f64> = (0..=2 * nz).map(|j| half * (j as f64 - nz as f64) / nz as f64).collect();
    let mut pressure = Vec::with_capacity(theta.len() * z.len());
    for i in 0..theta.len() {
        let row = &content.film.pressure[i * nz..(i + 1) * nz];
        pressure.push(0.0);
        pressure.extend(row.iter().rev().map(|v| p_scale * v));
        pressure.extend(row[1..].iter().map(|v| p_scale * v));
        pressure.push(0.0);
    }
    (r, Some(crate::laws::film_field::FilmField { theta, z, pressure }))
}

/// The fill of the joint's content (as [`FilmContent::fill_at`]) in the state `k`, or `None`
/// for a joint without one: what the `film` channel records.
pub fn recorded_fill(joint: &super::ClearanceJoint, k: &super::JointKinematics, memory: &super::ImpactMemory) -> Option<Vec<f64>> {
    let (film, content) = (joint.film.as_ref()?, memory.film.as_ref()?);
    let s = FilmState { eps: crate::laws::transition::film_eps(k.eps, film.eps_max), eps_dot: k.eps_dot, wedge: k.wedge };
    Some(content.lock().unwrap_or_else(|e| e.into_inner()).fill_at(memory.film_generation, &film.geometry_at(memory), s).to_vec())
}

/// Copy the impact memory `from` into `to` with every film content copied too (not shared): for
/// a second integration of the same mechanism beside a run (a Lyapunov shadow), which advances
/// its own content.
pub fn copy_detached(to: &mut [super::ImpactMemory], from: &[super::ImpactMemory]) {
    to.clone_from_slice(from);
    for m in to.iter_mut() {
        if let Some(c) = m.film.take() {
            let own = c.lock().unwrap_or_else(|e| e.into_inner()).clone();
            m.film = Some(own.shared());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A journal squeezed sinusoidally along a fixed line while it turns (Brewe's case, his
    /// parameters not at hand: ε = 0.5 + 0.3 sin Ωt, Ω = ω = 100 rad/s, L/D = 1/2), its film
    /// advanced by `n` equal steps a period over two periods, as a run advances it between
    /// accepted steps (each step's end evaluated with the time since its start). Returns the
    /// oil's change in the gap and the books' supplied − leaked over the second period, the
    /// leaked oil \[m³\], the film force at the end \[N\] and whether it ruptured.
    fn squeezed(n: usize) -> (f64, f64, f64, (f64, f64), bool) {
        let g = BearingGeometry { viscosity: 0.01, journal_radius: 0.02, clearance: 4e-5, length: 0.02 };
        let omega = 100.0;
        let state = |t: f64| FilmState { eps: 0.5 + 0.3 * (omega * t).sin(), eps_dot: 0.3 * omega * (omega * t).cos(), wedge: omega };
        let mut c = FilmContent::flooded(2.0 * g.journal_radius / g.length);
        c.start_at(0.0);
        let period = std::f64::consts::TAU / omega;
        let h = period / n as f64;
        let (mut oil0, mut books0, mut leaked0, mut ruptured) = (f64::NAN, 0.0, 0.0, false);
        for k in 0..2 * n {
            let (t0, t1) = (k as f64 * h, (k + 1) as f64 * h);
            c.now = t1;
            c.advance(&g, t0, t1, state(t1));
            ruptured |= c.content[c.slot(c.generation)].iter().any(|v| *v < 0.9);
            if k + 1 == n {
                oil0 = c.oil(&g);
                books0 = c.supplied - c.leaked;
                leaked0 = c.leaked;
            }
        }
        let books = c.supplied - c.leaked - books0;
        let leaked_second = c.leaked - leaked0;
        c.now = 2.0 * period;
        let f = c.evaluate(c.generation, &g, state(2.0 * period)).force;
        (c.oil(&g) - oil0, books, leaked_second, f, ruptured)
    }

    #[test]
    fn a_squeezed_film_keeps_its_oil_books_and_converges_as_the_steps_shrink() {
        // Second method: the oil counted in the gap from the fill against the books of what the
        // groove fed less what the ends leaked; and the same film with halved steps.
        let runs: Vec<_> = [200, 400, 800].iter().map(|&n| squeezed(n)).collect();
        for (n, r) in [200, 400, 800].iter().zip(&runs) {
            eprintln!("n {n}: Δoil {:.4e}, books {:.4e}, leaked {:.4e}, F ({:.3}, {:.3}) N, ruptured {}", r.0, r.1, r.2, r.3 .0, r.3 .1, r.4);
            assert!(r.4, "the film ruptured");
        }
        let balance: Vec<f64> = runs.iter().map(|r| ((r.0 - r.1) / r.2).abs()).collect();
        let f_diff = |a: &(f64, f64, f64, (f64, f64), bool), b: &(f64, f64, f64, (f64, f64), bool)| (a.3 .0 - b.3 .0).hypot(a.3 .1 - b.3 .1);
        let (d1, d2) = (f_diff(&runs[0], &runs[1]), f_diff(&runs[1], &runs[2]));
        eprintln!("oil balance / leaked: {balance:?}; force change on halving: {d1:.4} N, {d2:.4} N (|F| {:.2} N)", runs[2].3 .0.hypot(runs[2].3 .1));
        // Measured: 1.6e-3, 7.8e-4, 3.8e-4 of the period's leak (first order in the step).
        assert!(balance[2] < 1e-3, "{balance:?}");
        assert!(balance[1] < 0.6 * balance[0] && balance[2] < 0.6 * balance[1], "the books close as the steps shrink: {balance:?}");
        assert!(d2 < 0.7 * d1, "first-order convergence of the force: {d1} then {d2}");
    }
}
