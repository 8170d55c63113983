//! The right-hand side ẏ = f(t, y) of a compiled model (docs/physics.md §1): y = (q, q̇), q̈ from the
//! Baumgarte-stabilised KKT solve with gravity and clearance-joint forces; with heat models
//! y = (q, q̇, T…) and Ṫ from each joint's heat balance (rust/clearance/thermal.rs, §4).

use crate::clearance::{ImpactMemory, JointForce, JointKinematics};
use crate::constraints::{BodyKin, JacRow};
use crate::error::{Error, Result};
use crate::kkt::KktSolver;
use crate::model::Model;

/// Everything one right-hand side writes, allocated once per run.
pub struct Workspace {
    pub kin: Vec<BodyKin>,
    pub phi: Vec<f64>,
    pub phi_t: Vec<f64>,
    pub phi_dot: Vec<f64>,
    pub gamma: Vec<f64>,
    /// γ − 2αΦ̇ − β²Φ.
    pub c: Vec<f64>,
    pub jac: Vec<JacRow>,
    /// Generalised forces g (gravity + clearance joints).
    pub force: Vec<f64>,
    pub qdd: Vec<f64>,
    pub lambda: Vec<f64>,
    pub joint_kin: Vec<JointKinematics>,
    pub joint_force: Vec<JointForce>,
    /// dT/dt \[K/s\] of each oil temperature in the state (rust/clearance/thermal.rs); empty
    /// without heat models.
    pub heat_rate: Vec<f64>,
    kkt: KktSolver,
    /// Scratch of [`Workspace::unit_force_response`]: its multipliers.
    unit_lambda: Vec<f64>,
    /// The arguments of the last [`Workspace::evaluate_and_keep`] while everything above still
    /// holds its results (cleared by any other use of the workspace), so that the same
    /// evaluation asked for again is not redone: RADAU5 asks for f(t1, y1) right after the
    /// monitors have solved for the accelerations at t1.
    last: Evaluated,
}

/// The arguments of an evaluation whose results the workspace holds (none while `t` is NaN).
struct Evaluated {
    t: f64,
    y: Vec<f64>,
    memory: Vec<ImpactMemory>,
}

impl Workspace {
    pub fn new(model: &Model) -> Self {
        Self::with_weights(model, model.mass.iter().map(|m| 1.0 / m).collect())
    }

    /// A workspace whose KKT solver uses the given diagonal weights instead of M⁻¹
    /// (unit weights give the minimum-norm corrections of the kinematic assembly).
    pub fn with_weights(model: &Model, inv_weights: Vec<f64>) -> Self {
        let nb = model.n_bodies();
        let rows = model.rows;
        let mut ws = Workspace {
            kin: vec![BodyKin::default(); nb],
            phi: vec![0.0; rows],
            phi_t: vec![0.0; rows],
            phi_dot: vec![0.0; rows],
            gamma: vec![0.0; rows],
            c: vec![0.0; rows],
            jac: vec![JacRow::default(); rows],
            force: vec![0.0; 3 * nb],
            qdd: vec![0.0; 3 * nb],
            lambda: vec![0.0; rows],
            joint_kin: vec![JointKinematics::default(); model.clearance.len()],
            joint_force: vec![JointForce::default(); model.clearance.len()],
            heat_rate: vec![0.0; model.heat_states()],
            kkt: KktSolver::new(vec![1.0; 3 * nb], &[]),
            unit_lambda: vec![0.0; rows],
            last: Evaluated { t: f64::NAN, y: vec![0.0; model.state_dim()], memory: vec![ImpactMemory::default(); model.clearance.len()] },
        };
        // The Jacobian's sparsity (which bodies each row touches) is fixed: take it from any pose.
        let n = 3 * nb;
        let zeros = vec![0.0; n];
        ws.eval_constraints(model, 0.0, &model.q_guess, &zeros);
        ws.kkt = KktSolver::new(inv_weights, &ws.jac);
        ws
    }

    /// Body kinematics, Φ, Φt, γ and the Jacobian rows at (t, q, q̇).
    pub fn eval_constraints(&mut self, model: &Model, t: f64, q: &[f64], qd: &[f64]) {
        self.forget();
        for (b, k) in self.kin.iter_mut().enumerate() {
            *k = BodyKin::new(&q[3 * b..3 * b + 3], &qd[3 * b..3 * b + 3]);
        }
        let mut r = 0;
        for con in &model.constraints {
            let m = con.rows();
            con.eval(t, &self.kin, &mut self.phi[r..r + m], &mut self.phi_t[r..r + m], &mut self.gamma[r..r + m], &mut self.jac[r..r + m]);
            r += m;
        }
        for r in 0..model.rows {
            self.phi_dot[r] = self.jac[r].dot(qd) + self.phi_t[r];
        }
    }

    /// Solve the KKT system with the current `force` and `c`.
    pub fn solve_kkt(&mut self, t: f64) -> Result<()> {
        self.forget();
        self.kkt
            .solve(&self.jac, &self.force, &self.c, &mut self.qdd, &mut self.lambda)
            .map_err(|index| Error::SingularJacobian { t, index })
    }

    /// Factorise the KKT Schur complement at the pose of the last
    /// [`Workspace::eval_constraints`], for [`Workspace::unit_force_response`].
    pub fn factor_kkt(&mut self, t: f64) -> Result<()> {
        self.forget();
        self.kkt.factor(&self.jac).map_err(|index| Error::SingularJacobian { t, index })
    }

    /// `out = S e_k`: the constrained acceleration response to a unit generalised force on
    /// coordinate `k` (the KKT solve with `g = e_k`, `c = 0`, using the factor of
    /// [`Workspace::factor_kkt`]), with `S = M⁻¹ − M⁻¹Φqᵀ(Φq M⁻¹ Φqᵀ)⁻¹Φq M⁻¹`.
    pub fn unit_force_response(&mut self, k: usize, out: &mut [f64]) {
        self.kkt.unit_force_response(k, out, &mut self.unit_lambda);
    }

    /// The results of the last evaluation no longer stand.
    #[inline]
    fn forget(&mut self) {
        self.last.t = f64::NAN;
    }

    /// Full evaluation at y = (q, q̇, T…): constraints, forces, KKT, heat balances. Leaves q̈ in
    /// `qdd` and Ṫ in `heat_rate`. Returns at
    /// once if the workspace holds the same evaluation from [`Workspace::evaluate_and_keep`]
    /// (same t, y and impact memory: an evaluation is a function of these alone).
    pub fn evaluate(&mut self, model: &Model, memory: &[ImpactMemory], t: f64, y: &[f64]) -> Result<()> {
        let last = &self.last;
        if last.t == t && last.y == y && last.memory == memory {
            return Ok(());
        }
        self.evaluate_afresh(model, memory, t, y)
    }

    /// [`Workspace::evaluate`], remembering its arguments so that the same evaluation asked for
    /// next is not redone (the copy is the cost: only where a repeat is likely).
    pub fn evaluate_and_keep(&mut self, model: &Model, memory: &[ImpactMemory], t: f64, y: &[f64]) -> Result<()> {
        self.evaluate(model, memory, t, y)?;
        let last = &mut self.last;
        last.t = t;
        // Sized for (q, q̇) and the model's joints in `Workspace::new`: no allocation.
        last.y.clear();
        last.y.extend_from_slice(y);
        last.memory.clear();
        last.memory.extend_from_slice(memory);
        Ok(())
    }

    fn evaluate_afresh(&mut self, model: &Model, memory: &[ImpactMemory], t: f64, y: &[f64]) -> Result<()> {
        self.eval_loads(model, memory, t, y)?;
        if !self.heat_rate.is_empty() {
            self.heat_balances(model, memory, y);
        }
        self.solve_kkt(t)
    }

    /// The KKT system's parts at (t, q, q̇) without solving it: constraints and their Jacobian
    /// rows, `c` and the generalised forces `force` (what [`Workspace::evaluate`] solves for q̈;
    /// the implicit methods difference them for their Newton matrices).
    #[inline(always)] // into evaluate: outlined, a right-hand side took ~350 more instructions
    /// Fails where a heated joint's oil temperature leaves its viscosity law's range.
    pub fn eval_loads(&mut self, model: &Model, memory: &[ImpactMemory], t: f64, y: &[f64]) -> Result<()> {
        let n = 3 * model.n_bodies();
        let (q, qd) = (&y[..n], &y[n..2 * n]);
        self.eval_constraints(model, t, q, qd);
        let (a, b2) = (model.alpha, model.beta * model.beta);
        for r in 0..model.rows {
            self.c[r] = self.gamma[r] - 2.0 * a * self.phi_dot[r] - b2 * self.phi[r];
        }
        for b in 0..model.n_bodies() {
            let m = model.mass[3 * b];
            self.force[3 * b] = m * model.gravity.x;
            self.force[3 * b + 1] = m * model.gravity.y;
            self.force[3 * b + 2] = 0.0;
        }
        for f in &model.forces {
            f.apply(t, &self.kin, &mut self.force);
        }
        for (j, joint) in model.clearance.iter().enumerate() {
            let k = joint.kinematics(&self.kin);
            // A mass-conserving film advances its partly filled nodes to the evaluation's time.
            crate::clearance::cavitation::set_time(&memory[j], t);
            let f = match joint.heat() {
                None => joint.force(&k, &memory[j]),
                Some(h) => {
                    if !h.holds_at(y[h.state]) {
                        return Err(Error::NonFinite { t, detail: h.out_of_range(&joint.name, y[h.state]) });
                    }
                    joint.force(&k, &h.memory_at(&memory[j], y[h.state]))
                }
            };
            joint.apply(&self.kin, &k, &f, &mut self.force);
            self.joint_kin[j] = k;
            self.joint_force[j] = f;
        }
        Ok(())
    }

    /// Ṫ of every oil temperature from its joint's power loss at the forces just evaluated
    /// (rust/clearance/thermal.rs).
    fn heat_balances(&mut self, model: &Model, memory: &[ImpactMemory], y: &[f64]) {
        let n = 3 * model.n_bodies();
        let mut s = 0;
        for (j, joint) in model.clearance.iter().enumerate() {
            let Some(h) = joint.heat() else { continue };
            let temp = y[h.state];
            let (w_b, w_j) = crate::clearance::body_rates(joint, &y[n..2 * n]);
            let p = joint.readings(&self.joint_kin[j], &self.joint_force[j], &h.memory_at(&memory[j], temp), w_b, w_j).power_loss;
            self.heat_rate[s] = h.rate(temp, p);
            s += 1;
        }
    }

    /// ẏ of the last evaluation at `y`: (q̇, q̈, Ṫ…).
    pub fn derivative(&self, y: &[f64], dy: &mut [f64]) {
        let n = self.qdd.len();
        dy[..n].copy_from_slice(&y[n..2 * n]);
        dy[n..2 * n].copy_from_slice(&self.qdd);
        dy[2 * n..].copy_from_slice(&self.heat_rate);
    }

    /// ‖Φ‖₂ and ‖Φ̇‖₂ of the last evaluation.
    pub fn violation(&self) -> (f64, f64) {
        let n2 = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        (n2(&self.phi), n2(&self.phi_dot))
    }
}
