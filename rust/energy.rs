//! Energy bookkeeping (docs/physics.md §10.5): the energy stored in the mechanism (kinetic,
//! gravitational, elastic) and the work done on it by loads and motors, dampers, drivers and
//! clearance joints (contact, friction, film), so that a run can show
//! `E_kin + V_grav + V_elastic − ΣW = const`. Off unless the `energy` channel is asked for;
//! then the powers are integrated step by step (Simpson's rule on each accepted step, with the
//! step's midpoint from the dense output), not from the stored outputs, so the work does not
//! depend on the output grid.

use crate::model::Model;
use crate::system::Workspace;

/// Columns of the `energy` channel \[J\].
pub const ENERGY_COLUMNS: [&str; 9] = ["kinetic", "gravity", "spring", "load", "motor", "driver", "damper", "contact", "friction"];

/// How many of [`ENERGY_COLUMNS`] are stored energies; the rest are work done on the mechanism.
pub const STORED: usize = 3;

/// Powers \[W\] fed into the mechanism, in the order of the work columns.
pub type Powers = [f64; 6];

/// The work integrals of a run and the current step's quadrature data.
#[derive(Debug, Clone, Default)]
pub struct EnergyBook {
    /// Work done up to `t0` [J].
    w0: Powers,
    /// Powers at the start, middle and end of the last accepted step [t0, t0 + h].
    p0: Powers,
    pm: Powers,
    p1: Powers,
    t0: f64,
    h: f64,
    /// Scratch: one joint's generalised forces.
    g: Vec<f64>,
}

impl EnergyBook {
    pub fn new(model: &Model) -> Self {
        EnergyBook { g: vec![0.0; 3 * model.n_bodies()], ..Default::default() }
    }

    /// Start at `t` with the power `p` there (no work done yet).
    pub fn start(&mut self, t: f64, p: Powers) {
        *self = EnergyBook { g: std::mem::take(&mut self.g), t0: t, p0: p, pm: p, p1: p, ..Default::default() };
    }

    /// Close the accepted step [t0, t1] (which starts where the last one ended) with the
    /// powers at its middle and end.
    pub fn step(&mut self, t0: f64, t1: f64, pm: Powers, p1: Powers) {
        self.w0 = self.work_at(t0);
        self.p0 = self.p1;
        self.pm = pm;
        self.p1 = p1;
        self.t0 = t0;
        self.h = t1 - t0;
    }

    /// Work done up to `t` in the last accepted step: the exact integral of the quadratic
    /// through the powers at the step's start, middle and end (Simpson's rule at its end).
    pub fn work_at(&self, t: f64) -> Powers {
        if self.h <= 0.0 {
            return self.w0;
        }
        let s = ((t - self.t0) / self.h).clamp(0.0, 1.0);
        let mut w = self.w0;
        for k in 0..w.len() {
            let (a, m, b) = (self.p0[k], self.pm[k], self.p1[k]);
            let c1 = -3.0 * a + 4.0 * m - b;
            let c2 = 2.0 * a - 4.0 * m + 2.0 * b;
            w[k] += self.h * (a * s + c1 * s * s / 2.0 + c2 * s * s * s / 3.0);
        }
        w
    }

    /// The powers at the state of the last full evaluation of `ws` (constraints, forces,
    /// KKT): loads, motors, drivers (−λ Φq q̇ of each driving row), dampers, and the clearance
    /// joints (their generalised forces times q̇), split into friction (w_dry F_t times the
    /// slip speed) and the rest (normal contact and film).
    pub fn powers(&mut self, model: &Model, ws: &Workspace, t: f64, qd: &[f64]) -> Powers {
        let mut p = [0.0; 6];
        for f in &model.forces {
            p[f.work_column()] += f.power(t, &ws.kin);
        }
        let mut r = 0;
        for c in &model.constraints {
            let m = c.rows();
            if matches!(c, crate::constraints::Constraint::Driver { .. }) {
                p[2] -= ws.lambda[r] * ws.jac[r].dot(qd);
            }
            r += m;
        }
        for (j, joint) in model.clearance.iter().enumerate() {
            let f = ws.joint_force[j]; // as evaluated, at the state's oil temperature
            self.g.fill(0.0);
            joint.apply(&ws.kin, &ws.joint_kin[j], &f, &mut self.g);
            let total = self.g.iter().zip(qd).map(|(g, v)| g * v).sum::<f64>();
            let friction = f.friction() * ws.joint_kin[j].slip;
            p[4] += total - friction;
            p[5] += friction;
        }
        p
    }

    /// Kinetic, gravitational and elastic energy \[J\] at the state (q, q̇) whose body kinematics
    /// `ws.kin` holds.
    pub fn stored(model: &Model, ws: &Workspace) -> [f64; 3] {
        let mut e = [0.0; 3];
        for (b, k) in ws.kin.iter().enumerate() {
            let (m, j) = (model.mass[3 * b], model.mass[3 * b + 2]);
            e[0] += 0.5 * (m * (k.vx * k.vx + k.vy * k.vy) + j * k.w * k.w);
            e[1] -= m * (model.gravity.x * k.x + model.gravity.y * k.y);
        }
        e[2] = model.forces.iter().map(|f| f.potential(&ws.kin)).sum();
        e
    }
}
