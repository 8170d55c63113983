//! The stiff part of the mechanism's Jacobian ∂q̈/∂(q, q̇) for the implicit methods' Newton
//! matrices (RADAU5, RODAS4): clearance-joint and spring forces differenced body by body and
//! mapped to accelerations through the constrained mobility of the current pose.

use super::MechanismSystem;
use crate::clearance::{ClearanceJoint, ImpactMemory};
use crate::constraints::BodyKin;
use crate::error::Result;

impl MechanismSystem<'_> {
    /// The stiff part of `∂q̈/∂(q, q̇)` for the implicit methods
    /// ([`OdeSystem::acceleration_jacobian`](crate::integrate::OdeSystem::acceleration_jacobian)):
    /// the clearance-joint forces `g_j` differenced in the 6 position and velocity components of each of their two bodies
    /// (forces, kinematics and moment arms recomputed, impact memory held), mapped to
    /// accelerations by the constrained mobility `S` of the current pose:
    /// `∂q̈/∂x ≈ S ∂g/∂x`. Left out, as not stiff: the pose dependence of `S`, of `γ` and of the
    /// Baumgarte terms (eigenvalues of order α, β).
    pub(super) fn stiff_jacobian(&mut self, t: f64, y: &[f64], a_q: &mut [f64], a_v: &mut [f64]) -> Result<bool> {
        let model = self.model;
        let m = 3 * model.n_bodies();
        a_q.fill(0.0);
        a_v.fill(0.0);
        if model.clearance.is_empty() && !model.forces.iter().any(|f| f.stiff_bodies().is_some()) {
            return Ok(true);
        }
        let items = stiff_items(model);
        self.ws.eval_constraints(model, t, &y[..m], &y[m..2 * m]);
        self.ws.factor_kkt(t)?;
        if self.mobility.len() != m * m {
            self.mobility.resize(m * m, 0.0); // once per run
        }
        self.mobility_done.fill(false);
        for item in items {
            let bodies = self.stiff_item_bodies(item);
            for &b in bodies.iter().flatten() {
                for k in 3 * b as usize..3 * b as usize + 3 {
                    if !self.mobility_done[k] {
                        self.ws.unit_force_response(k, &mut self.mobility[k * m..(k + 1) * m]);
                        self.mobility_done[k] = true;
                    }
                }
            }
            let d = self.stiff_block(item, t, y);
            for (slot, b) in bodies.iter().enumerate() {
                let Some(b) = b.map(|b| b as usize) else { continue };
                for comp in 0..6 {
                    let target = if comp < 3 { &mut *a_q } else { &mut *a_v };
                    let col = &mut target[(3 * b + comp % 3) * m..(3 * b + comp % 3 + 1) * m];
                    for (oslot, ob) in bodies.iter().enumerate() {
                        let Some(ob) = ob.map(|ob| ob as usize) else { continue };
                        for o in 0..3 {
                            let dv = d[3 * oslot + o][6 * slot + comp];
                            if dv != 0.0 {
                                for (c, s) in col.iter_mut().zip(&self.mobility[(3 * ob + o) * m..(3 * ob + o + 1) * m]) {
                                    *c += dv * s;
                                }
                            }
                        }
                    }
                }
            }
        }
        Ok(true)
    }

    /// The finite-difference step in component `j` of `y`
    /// ([`OdeSystem::difference_step`](crate::integrate::OdeSystem::difference_step)): the generic
    /// √ε_mach step, or smaller where a clearance joint of the body needs it.
    pub(super) fn jacobian_difference_step(&self, j: usize, y: &[f64]) -> f64 {
        let m = 3 * self.model.n_bodies();
        let b = Some(((j % m) / 3) as u32);
        let joints = self.model.clearance.iter().enumerate().filter(|(_, c)| c.bearing == b || c.journal == b).map(|(i, _)| i);
        self.difference_step_among(j, y, joints)
    }

    /// [`MechanismSystem::jacobian_difference_step`] with the clearance joints on component
    /// `j`'s body given (`joints`).
    pub(super) fn difference_step_among(&self, j: usize, y: &[f64], joints: impl Iterator<Item = usize>) -> f64 {
        let m = 3 * self.model.n_bodies();
        let generic = (f64::EPSILON * 1e-5f64.max(y[j].abs())).sqrt();
        if j >= 2 * m {
            return generic; // an oil temperature (heat.rs): no body's clearance scale
        }
        let (b, comp) = ((j % m) / 3, (j % m) % 3 + if j >= m { 3 } else { 0 });
        let x = [y[3 * b], y[3 * b + 1], y[3 * b + 2], y[m + 3 * b], y[m + 3 * b + 1], y[m + 3 * b + 2]];
        let mut step = generic;
        for i in joints {
            step = step.min(self.jacobian_steps(Stiff::Joint(i), b, &x)[comp]);
        }
        step
    }
}

/// A force whose derivatives enter the implicit methods' Newton matrix.
#[derive(Clone, Copy)]
pub(super) enum Stiff {
    Joint(usize),
    Force(usize),
}

/// The stiff forces of `model`, in order: clearance joints, and springs, rotational springs and
/// motors (their stiffness and damping); applied loads and torques depend on time only.
pub(super) fn stiff_items(model: &crate::model::Model) -> impl Iterator<Item = Stiff> + '_ {
    let springs = model.forces.iter().enumerate().filter(|(_, f)| f.stiff_bodies().is_some()).map(|(i, _)| Stiff::Force(i));
    (0..model.clearance.len()).map(Stiff::Joint).chain(springs) // no allocation
}

impl MechanismSystem<'_> {
    /// The two bodies of a stiff item (`None`: the ground).
    pub(super) fn stiff_item_bodies(&self, item: Stiff) -> [Option<u32>; 2] {
        match item {
            Stiff::Joint(j) => [self.model.clearance[j].bearing, self.model.clearance[j].journal],
            Stiff::Force(i) => self.model.forces[i].stiff_bodies().unwrap_or([None, None]),
        }
    }

    /// The derivatives of one stiff item's generalised forces on its two bodies at the pose of
    /// the workspace (`ws.kin`): `d[3·oslot + o][6·slot + comp]` = ∂g(body `oslot`, coordinate
    /// `o`)/∂(body `slot`'s x, y, θ, ẋ, ẏ, θ̇)`[comp]`, zero where a body is the ground. A
    /// clearance joint's law gives them with an exact chain rule where it can
    /// ([`ClearanceJoint::force_derivatives`]); otherwise the force is differenced body by body
    /// (forces, kinematics and moment arms recomputed, impact memory held).
    pub(super) fn stiff_block(&mut self, item: Stiff, t: f64, y: &[f64]) -> [[f64; 12]; 6] {
        if let Stiff::Joint(j) = item {
            if let Some(d) = self.model.clearance[j].force_derivatives(&self.ws.kin, &self.model.clearance[j].memory_at(&self.memory[j], y)) {
                return d;
            }
        }
        let bodies = self.stiff_item_bodies(item);
        let mut d = [[0.0; 12]; 6];
        self.stiff_force(item, t, y, &bodies, false);
        for (slot, b) in bodies.iter().enumerate() {
            let Some(b) = b.map(|b| b as usize) else { continue };
            let saved = self.ws.kin[b];
            let mut x = [saved.x, saved.y, saved.th, saved.vx, saved.vy, saved.w];
            let steps = self.jacobian_steps(item, b, &x);
            for comp in 0..6 {
                let keep = x[comp];
                x[comp] += steps[comp];
                let delta = x[comp] - keep; // the step actually taken (exact in floating point)
                self.ws.kin[b] = BodyKin::new(&x[..3], &x[3..]);
                x[comp] = keep;
                self.stiff_force(item, t, y, &bodies, true);
                self.ws.kin[b] = saved;
                for (oslot, ob) in bodies.iter().enumerate() {
                    let Some(ob) = ob.map(|ob| ob as usize) else { continue };
                    for o in 0..3 {
                        d[3 * oslot + o][6 * slot + comp] = (self.g_probe[3 * ob + o] - self.g_base[3 * ob + o]) / delta;
                    }
                }
            }
        }
        d
    }

    /// Finite-difference steps in body `b`'s (x, y, θ, ẋ, ẏ, θ̇) for the Newton matrix of `item`.
    /// A clearance joint's force varies on the scale of its clearance c, not of the body's
    /// coordinates: steps of √ε_mach·max(|x|, 1) m would move a µm journal by 1e-8 m, across
    /// the bearing centre (where it sits under a stiff film) and through its nonlinearity. So
    /// the positions are stepped by √ε_mach·c (θ by that over the joint point's arm) and the
    /// velocities by √ε_mach·c·max(|θ̇|, 1 rad/s).
    fn jacobian_steps(&self, item: Stiff, b: usize, x: &[f64; 6]) -> [f64; 6] {
        let root = f64::EPSILON.sqrt();
        let generic = |v: f64| root * v.abs().max(1.0);
        let mut steps = [0.0; 6];
        for (s, v) in steps.iter_mut().zip(x) {
            *s = generic(*v);
        }
        if let Stiff::Joint(j) = item {
            let joint = &self.model.clearance[j];
            let c = joint.clearance;
            let point = if joint.journal == Some(b as u32) { joint.journal_point } else { joint.bearing_point };
            let arm = point.norm().max(c);
            let rate = x[5].abs().max(1.0);
            steps = [root * c, root * c, (root * c / arm).min(generic(x[2])), root * c * rate, root * c * rate, (root * c * rate / arm).min(generic(x[5]))];
        }
        steps
    }

    /// The generalised force of one stiff item on its bodies (the state `y` giving a joint's oil
    /// temperature), into `g_probe` (`probe`) or `g_base`.
    fn stiff_force(&mut self, item: Stiff, t: f64, y: &[f64], bodies: &[Option<u32>; 2], probe: bool) {
        let g = if probe { &mut self.g_probe } else { &mut self.g_base };
        match item {
            Stiff::Joint(j) => {
                let joint = &self.model.clearance[j];
                joint_generalised_force(joint, &self.ws.kin, &joint.memory_at(&self.memory[j], y), g)
            }
            Stiff::Force(i) => {
                for &b in bodies.iter().flatten() {
                    g[3 * b as usize..3 * b as usize + 3].fill(0.0);
                }
                self.model.forces[i].apply(t, &self.ws.kin, g);
            }
        }
    }
}

/// The generalised forces of one clearance joint on its two bodies, written to their entries
/// of `g` (the other entries are left alone).
pub(super) fn joint_generalised_force(joint: &ClearanceJoint, kin: &[BodyKin], memory: &ImpactMemory, g: &mut [f64]) {
    for &b in [joint.bearing, joint.journal].iter().flatten() {
        g[3 * b as usize..3 * b as usize + 3].fill(0.0);
    }
    let k = joint.kinematics(kin);
    let f = joint.force(&k, memory);
    joint.apply(kin, &k, &f, g);
}
