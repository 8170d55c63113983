//! The film content of a lubricated joint with mass-conserving cavitation
//! (`Lubricated(film="finite", cavitation="jfo")`, docs/physics.md §4, *Mass-conserving
//! cavitation*; the law: [`crate::laws::bearing_jfo`]): where the oil is over the bearing, carried
//! from step to step, and the oil books (supplied, leaked) over the run.
//!
//! State layout: the content (720 values a joint) is not part of the integrator's state
//! (q, q̇): like the oil temperature (rust/clearance/thermal.rs) and the wear books it is a
//! slow state, advanced once per accepted step from the step's start, middle and end (the
//! content moves with the mean surface speed, a cell in ms; a step is µs), and every evaluation
//! inside a step sees the content of the step's start. So the implicit methods' Newton matrix
//! does not see it: the film force's derivatives (rust/clearance/mod.rs,
//! `force_derivatives`) are taken at the step's content, which the step holds fixed. A run
//! without such a joint has no content and runs none of this code.
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
    /// The fill θ_f ∈ [0, 1] of every node by generation parity: `content[g % 2]` is generation g.
    content: [Vec<f64>; 2],
    /// The newest generation.
    pub generation: u64,
    /// Oil fed through the supply groove and leaked at the ends since the start \[m³\].
    pub supplied: f64,
    pub leaked: f64,
    /// Scratch: the rates of a step's three solves, their mean, the fill.
    rates: [Vec<f64>; 3],
    mean: Vec<f64>,
    scratch: Vec<f64>,
    h_start: Vec<f64>,
}

/// A joint's content as its memory holds it.
pub type SharedContent = Arc<Mutex<FilmContent>>;

impl FilmContent {
    /// A bearing of diameter-to-length ratio `k`, flooded (full everywhere).
    pub fn flooded(k: f64) -> Self {
        let film = JfoFilm::new(k);
        let m = vec![1.0; JFO_THETA * JFO_ZETA];
        FilmContent { film, content: [m.clone(), m], generation: 0, supplied: 0.0, leaked: 0.0, rates: [Vec::new(), Vec::new(), Vec::new()], mean: Vec::new(), scratch: Vec::new(), h_start: Vec::new() }
    }

    /// A bearing of diameter-to-length ratio `k` holding the content `m` (as recorded by a run's
    /// `film` channel), or `None` if `m` is not one.
    pub fn holding(k: f64, m: &[f64]) -> Option<Self> {
        (m.len() == JFO_THETA * JFO_ZETA && m.iter().all(|v| v.is_finite() && (0.0..=1.0).contains(v))).then(|| {
            let film = JfoFilm::new(k);
            FilmContent { film, content: [m.to_vec(), m.to_vec()], generation: 0, supplied: 0.0, leaked: 0.0, rates: [Vec::new(), Vec::new(), Vec::new()], mean: Vec::new(), scratch: Vec::new(), h_start: Vec::new() }
        })
    }

    /// Shared, for a joint's memory.
    pub fn shared(self) -> SharedContent {
        Arc::new(Mutex::new(self))
    }

    /// The content of `generation` (the newest or the one before; older ones are gone: the newest).
    pub fn content(&self, generation: u64) -> &[f64] {
        if generation == self.generation || generation + 1 == self.generation {
            &self.content[(generation % 2) as usize]
        } else {
            &self.content[(self.generation % 2) as usize]
        }
    }

    /// Solve the film of `g` in the state `s` with the content of `generation`.
    pub fn evaluate(&mut self, generation: u64, g: &BearingGeometry, s: FilmState) -> JfoReading {
        let k = if generation == self.generation || generation + 1 == self.generation { generation } else { self.generation };
        let m = &self.content[(k % 2) as usize];
        let eps = s.clamped_eps();
        self.film.solve(m, eps, s.eps_dot, s.wedge);
        self.film.reading(m, g.journal_radius, g.clearance, g.length, g.viscosity, s.eps_dot)
    }

    /// Advance the content over an accepted step of `dt` \[s\]: `states_at(f)` gives the film state
    /// at the fraction f ∈ [0, 1] of the step, `shift` \[rad\] how far the content moves relative to
    /// the line of centres over it (the mean surface speed's travel less the line of centres'
    /// turn). Sub-stepped so that the transport moves at most half a cell per sub-step; in each,
    /// the pressure part of the rate by Simpson's rule over its start, middle and end (solved at
    /// the sub-step's start content). Books the oil supplied and leaked.
    pub fn advance(&mut self, g: &BearingGeometry, dt: f64, shift: f64, states_at: &mut dyn FnMut(f64) -> FilmState) {
        let cell = std::f64::consts::TAU / JFO_THETA as f64;
        let n = (2.0 * shift.abs() / cell).ceil().clamp(1.0, 1e4) as usize;
        let old = (self.generation % 2) as usize;
        let (a, b) = self.content.split_at_mut(1);
        let (from, to) = if old == 0 { (&a[0], &mut b[0]) } else { (&b[0], &mut a[0]) };
        to.clone_from(from);
        let h = dt / n as f64;
        for r in self.rates.iter_mut() {
            r.resize(from.len(), 0.0);
        }
        let mut mean = std::mem::take(&mut self.mean);
        mean.resize(from.len(), 0.0);
        let mut h_start = std::mem::take(&mut self.h_start);
        for sub in 0..n {
            let mut flows = [(0.0, 0.0); 3];
            for k in 0..3 {
                let st = states_at((sub as f64 + 0.5 * k as f64) / n as f64);
                self.film.solve(to, st.clamped_eps(), st.eps_dot, st.wedge);
                let r = self.film.reading(to, g.journal_radius, g.clearance, g.length, g.viscosity, st.eps_dot);
                flows[k] = (r.supply, r.side_leakage);
                self.rates[k].copy_from_slice(&self.film.pressure_rate);
                if k == 0 {
                    h_start.clear();
                    h_start.extend_from_slice(self.film.gaps());
                }
            }
            for (i, v) in mean.iter_mut().enumerate() {
                *v = (self.rates[0][i] + 4.0 * self.rates[1][i] + self.rates[2][i]) / 6.0;
            }
            // The last solve was at the sub-step's end: its gap and its full nodes.
            self.film.apply(to, &h_start, &mean, h, shift / n as f64, &mut self.scratch);
            self.supplied += h * (flows[0].0 + 4.0 * flows[1].0 + flows[2].0) / 6.0;
            self.leaked += h * (flows[0].1 + 4.0 * flows[1].1 + flows[2].1) / 6.0;
        }
        self.mean = mean;
        self.h_start = h_start;
        self.generation += 1;
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
