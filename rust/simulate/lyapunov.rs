//! The largest Lyapunov exponent of a run by two nearby trajectories (Benettin, Galgani,
//! Giorgilli & Strelcyn 1980), valid through impacts and friction switches because each
//! trajectory is integrated as it is, contacts located on its own dense output.
//!
//! From [`LyapunovSpec::start`] a shadow run starts a distance d0 from the run (a fixed
//! pseudo-random direction, projected onto the constraints), is integrated alongside it and,
//! every `interval` τ, its distance d from the run is measured at the exact time t_k on the run's
//! dense output: ln(d/d_start) is booked and the shadow is put back at distance d0 along the same
//! direction. λ = Σ ln(d/d_start) / (Σ τ). The run itself is not touched (its steps, outputs
//! and sections are those of a run without a shadow). The distance is
//! √(Σ δq² + Σ (δq̇/Ω)²) over the bodies' coordinates, the 6 · bodies components of (q, q̇)
//! (m, rad; Ω = `velocity_scale`). Oil temperatures after them in the state (heated joints) are
//! not perturbed and not measured: the shadow takes the run's at each start of an interval and
//! carries its own through it, so they follow the mechanism's motion as the run's do. A perturbed
//! state is made consistent with the ideal joints and drivers (position: δq projected onto the
//! null space of Φq; velocity: Φq q̇ + Φt = 0 at the perturbed pose, both by the model's KKT
//! solve), so the Baumgarte terms do not decay a violation into the measurement.

use super::MechanismSystem;
use crate::error::{Error, Result};
use crate::integrate::{integrate, DenseOutput, Method, Settings};
use crate::model::Model;
use crate::record::Channels;
use crate::settings::LyapunovSpec;
use crate::system::Workspace;

/// What the shadow found: one entry per completed interval.
#[derive(Debug, Clone, Default)]
pub struct LyapunovBook {
    /// End of each interval \[s\].
    pub t: Vec<f64>,
    /// ln(d/d_start) over each interval.
    pub log_growth: Vec<f64>,
    /// Why the shadow stopped early (the run may have gone on), if it did.
    pub error: Option<Error>,
    /// The shadow's accepted steps and right-hand sides, all intervals together.
    pub steps: usize,
    pub rhs_evals: usize,
}

/// The shadow run beside a [`MechanismSystem`].
pub struct Shadow<'a> {
    pub sys: MechanismSystem<'a>,
    spec: LyapunovSpec,
    method: Method,
    ode: Settings,
    /// The shadow's time and state (the start of the interval under way).
    t: f64,
    y: Vec<f64>,
    /// Its distance from the run at `t`.
    d_start: f64,
    /// The run's state at the end of the interval (scratch).
    y_ref: Vec<f64>,
    started: bool,
    stopped: bool,
    /// Intervals completed.
    k: u64,
    pub book: LyapunovBook,
}

impl<'a> Shadow<'a> {
    pub fn new(model: &'a Model, spec: LyapunovSpec, method: Method, ode: Settings) -> Self {
        let none = Channels { states: false, accelerations: false, reactions: false, joints: false, violation: false, energy: false, film: false };
        let n = model.state_dim();
        Shadow {
            sys: MechanismSystem::new(model, none, 0, None),
            spec,
            method,
            ode,
            t: spec.start,
            y: vec![0.0; n],
            d_start: 0.0,
            y_ref: vec![0.0; n],
            started: false,
            stopped: false,
            k: 0,
            book: LyapunovBook::default(),
        }
    }

    /// The end of the interval under way \[s\] (from the start, no drift).
    fn next(&self) -> f64 {
        self.spec.start + (self.k + 1) as f64 * self.spec.interval
    }

    /// The weighted distance of `delta` (q then q̇; any oil temperatures after them left out).
    fn norm(&self, delta: &[f64]) -> f64 {
        let n = 3 * self.sys.model.n_bodies();
        let w = 1.0 / self.spec.velocity_scale;
        (delta[..n].iter().map(|d| d * d).sum::<f64>() + delta[n..2 * n].iter().map(|d| (d * w) * (d * w)).sum::<f64>()).sqrt()
    }

    /// Put the shadow at `y_ref + delta · d0/|delta|` in (q, q̇), made consistent with the
    /// constraints at time `t`, with the oil temperatures of `y_ref`; its distance from `y_ref`
    /// into `d_start`.
    fn place(&mut self, t: f64, y_ref: &[f64], delta: &mut [f64]) -> Result<()> {
        let scale = self.spec.d0 / self.norm(delta);
        if !scale.is_finite() {
            return Err(Error::NonFinite { t, detail: "; the Lyapunov shadow met the run exactly (distance 0)".into() });
        }
        delta.iter_mut().for_each(|d| *d *= scale);
        let model = self.sys.model;
        let n = 3 * model.n_bodies();
        project(model, &mut self.sys.ws, t, y_ref, delta)?;
        for i in 0..2 * n {
            self.y[i] = y_ref[i] + delta[i];
        }
        self.y[2 * n..].copy_from_slice(&y_ref[2 * n..]);
        self.d_start = self.norm(delta);
        self.t = t;
        Ok(())
    }

    /// Start the shadow at the run's start `t` (state `y`, impact memory `memory`).
    pub fn start_at(&mut self, t: f64, y: &[f64], memory: &[crate::clearance::ImpactMemory]) {
        crate::clearance::cavitation::copy_detached(&mut self.sys.memory, memory);
        let mut delta = first_direction(y.len());
        match self.place(t, y, &mut delta) {
            Ok(()) => self.started = true,
            Err(e) => {
                self.book.error = Some(e);
                self.stopped = true;
            }
        }
    }

    /// Follow the run over its accepted step [t0, t1] (`dense`, impact memory `memory`): start
    /// the shadow when the step passes `start`, then integrate it to the end of each interval
    /// inside the step, book its growth and put it back. A failure of the shadow stops it alone.
    pub fn follow(&mut self, t0: f64, t1: f64, dense: &dyn DenseOutput, memory: &[crate::clearance::ImpactMemory]) {
        if self.stopped {
            return;
        }
        if let Err(e) = self.advance(t0, t1, dense, memory) {
            self.book.error = Some(e);
            self.stopped = true;
        }
    }

    fn advance(&mut self, t0: f64, t1: f64, dense: &dyn DenseOutput, memory: &[crate::clearance::ImpactMemory]) -> Result<()> {
        let mut y_ref = std::mem::take(&mut self.y_ref);
        let res = (|| {
            if !self.started {
                let start = self.spec.start;
                if !(start >= t0 && start <= t1) {
                    return Ok(());
                }
                dense.eval(start, &mut y_ref);
                crate::clearance::cavitation::copy_detached(&mut self.sys.memory, memory);
                let mut delta = first_direction(y_ref.len());
                self.place(start, &y_ref, &mut delta)?;
                self.started = true;
            }
            loop {
                let t_next = self.next();
                if t_next > t1 {
                    return Ok(());
                }
                dense.eval(t_next, &mut y_ref);
                let y = std::mem::take(&mut self.y);
                let ran = integrate(&mut self.sys, self.method, self.t, &y, t_next, &[], &self.ode);
                self.y = y;
                let stats = match ran {
                    Ok(s) => s,
                    Err((e, s)) => {
                        self.book.steps += s.steps_accepted;
                        self.book.rhs_evals += s.rhs_evals;
                        return Err(e);
                    }
                };
                self.book.steps += stats.steps_accepted;
                self.book.rhs_evals += stats.rhs_evals;
                // The last accepted step ends on t_next exactly: its end state is the shadow's.
                let mut delta: Vec<f64> = self.sys.last_y.iter().zip(&y_ref).map(|(a, b)| a - b).collect();
                let d = self.norm(&delta);
                self.book.t.push(t_next);
                self.book.log_growth.push((d / self.d_start).ln());
                self.k += 1;
                self.place(t_next, &y_ref, &mut delta)?;
            }
        })();
        self.y_ref = y_ref;
        res
    }
}

/// A fixed pseudo-random direction (xorshift, components in [−1, 1]): no special alignment with
/// any mechanism's coordinates, the same in every run.
fn first_direction(n: usize) -> Vec<f64> {
    let mut s = 0x2545_f491_4f6c_dd1du64;
    (0..n)
        .map(|_| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            2.0 * ((s >> 11) as f64 / (1u64 << 53) as f64) - 1.0
        })
        .collect()
}

/// Make the perturbation `delta` of the state `y_ref` consistent with the constraints at `t`:
/// δq ← δq − M⁻¹Φqᵀ(Φq M⁻¹ Φqᵀ)⁻¹ Φq δq at q_ref (Φ stays 0 to second order), then the perturbed
/// velocity corrected the same way so that Φq q̇ + Φt = 0 at the perturbed pose.
fn project(model: &Model, ws: &mut Workspace, t: f64, y_ref: &[f64], delta: &mut [f64]) -> Result<()> {
    let n = 3 * model.n_bodies();
    if model.rows == 0 {
        return Ok(());
    }
    let (q, qd) = (&y_ref[..n], &y_ref[n..2 * n]);
    ws.eval_constraints(model, t, q, qd);
    ws.force.iter_mut().for_each(|f| *f = 0.0);
    for r in 0..model.rows {
        ws.c[r] = ws.jac[r].dot(&delta[..n]);
    }
    ws.solve_kkt(t)?;
    for i in 0..n {
        delta[i] -= ws.qdd[i];
    }
    let q1: Vec<f64> = (0..n).map(|i| q[i] + delta[i]).collect();
    let qd1: Vec<f64> = (0..n).map(|i| qd[i] + delta[n + i]).collect();
    ws.eval_constraints(model, t, &q1, &qd1);
    ws.force.iter_mut().for_each(|f| *f = 0.0);
    ws.c.copy_from_slice(&ws.phi_dot);
    ws.solve_kkt(t)?;
    for i in 0..n {
        delta[n + i] -= ws.qdd[i];
    }
    Ok(())
}

impl MechanismSystem<'_> {
    /// Let the shadow follow the accepted step [t0, t1] (no shadow: nothing).
    pub(super) fn follow_shadow(&mut self, t0: f64, t1: f64, dense: &dyn DenseOutput) {
        if let Some(mut sh) = self.shadow.take() {
            // Inside the step the run had the memory it was integrated with; at its end the new one.
            let memory = if sh.spec.start < t1 { &self.step_memory } else { &self.memory };
            sh.follow(t0, t1, dense, memory);
            self.shadow = Some(sh);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::description::{BodyDesc, ForceDesc, Harmonic, JointDesc, MechanismDesc, Profile};

    /// A pendulum (pivot at the origin, centroid 0.5 m below, J_pivot = 1 kg m², m g l = 1 N m)
    /// under a harmonic torque with damping 1/q: θ'' + θ'/q + sin θ = g cos(2t/3).
    fn pendulum(g: f64) -> MechanismDesc {
        let mut d = MechanismDesc { gravity: [0.0, -2.0], baumgarte: [5.0, 5.0], ..MechanismDesc::default() };
        d.bodies.push(BodyDesc { name: "bob".into(), mass: 1.0, inertia: 0.75, position: [0.5 * 0.2f64.sin(), -0.5 * 0.2f64.cos()], angle: 0.2, velocity: [0.0; 3] });
        d.joints.push(JointDesc::Revolute { name: "pivot".into(), body_a: None, point_a: [0.0, 0.0], body_b: Some(0), point_b: [0.0, 0.5] });
        d.forces.push(ForceDesc::RotationalSpringDamper { name: "damper".into(), body_a: None, body_b: Some(0), stiffness: 0.0, damping: 0.5, angle0: Some(0.0) });
        d.forces.push(ForceDesc::Torque { name: "drive".into(), body: 0, reaction: None, magnitude: Profile::Harmonic(Harmonic { amplitude: g, omega: 2.0 / 3.0, phase: 0.0, offset: 0.0 }) });
        d
    }

    #[test]
    fn a_periodic_pendulum_has_a_negative_exponent_and_a_chaotic_one_a_positive_one() {
        let period = 3.0 * std::f64::consts::PI;
        for (g, positive) in [(0.9, false), (1.5, true)] {
            let model = Model::compile(&pendulum(g)).unwrap();
            let ode = Settings { rtol: 1e-10, atol: 1e-12, ..Settings::default() };
            let spec = LyapunovSpec { start: 30.0 * period, interval: period, d0: 1e-8, velocity_scale: 2.0 / 3.0 };
            let rs = crate::settings::RunSettings { lyapunov: Some(spec), ..crate::settings::RunSettings::plain(Some(Method::Dop853), ode, 0.0, 130.0 * period, vec![]) };
            let out = super::super::simulate(&model, &rs, None).unwrap();
            let book = out.lyapunov.unwrap();
            assert!(book.error.is_none(), "{:?}", book.error);
            assert_eq!(book.t.len(), 100);
            let lambda = book.log_growth.iter().sum::<f64>() / (100.0 * period);
            if positive {
                assert!(lambda > 0.05, "g = {g}: λ = {lambda}");
            } else {
                // The linearised pendulum's exponents at a stable orbit: −1/(2q) = −0.25 1/s.
                assert!((lambda + 0.25).abs() < 0.02, "g = {g}: λ = {lambda}");
            }
        }
    }
}
