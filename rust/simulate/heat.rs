//! The oil temperatures' rows and columns of the implicit methods' Newton matrices
//! ([`OdeSystem::border_jacobian`](crate::integrate::OdeSystem::border_jacobian); docs/physics.md
//! §4, *Heat*): the film force's change with the temperature through μ(T), mapped to
//! accelerations by the constrained mobility, and the heat balance's change with the joint's
//! motion and temperature, both by forward differences joint by joint.

use super::newton::joint_generalised_force;
use super::MechanismSystem;
use crate::error::Result;

impl MechanismSystem<'_> {
    /// `a_z = ∂q̈/∂T` (m × k, column-major) and `z_y = ∂Ṫ/∂y` (k × dim, row-major) at `(t, y)`,
    /// for the k oil temperatures of the state (rust/clearance/thermal.rs). For each joint with a
    /// heat model: ∂q̈/∂T = S ∂g/∂T with S the constrained mobility of the pose (the columns
    /// `stiff_jacobian` computed at this state just before, else computed here) and g the joint's
    /// generalised force, whose temperature enters through μ(T) only (0 at a constant
    /// viscosity); ∂Ṫ/∂y from C Ṫ = P_loss − hA (T − T_ambient), P_loss differenced in the q, q̇ of
    /// the joint's two bodies (the steps of the joint's own Newton matrix) and in T.
    pub(super) fn heat_jacobian(&mut self, t: f64, y: &[f64], a_z: &mut [f64], z_y: &mut [f64]) -> Result<()> {
        let model = self.model;
        let m = 3 * model.n_bodies();
        let n = y.len();
        a_z.fill(0.0);
        z_y.fill(0.0);
        // Body kinematics at y, and the mobility of this pose.
        self.ws.eval_constraints(model, t, &y[..m], &y[m..2 * m]);
        if self.mobility_at != y {
            self.ws.factor_kkt(t)?;
            self.mobility.resize(m * m, 0.0);
            self.mobility_done.fill(false);
            self.mobility_at.clear();
            self.mobility_at.extend_from_slice(y);
        }
        let mut probe = std::mem::take(&mut self.scratch);
        probe.copy_from_slice(y);
        let mut row = 0;
        for (j, joint) in model.clearance.iter().enumerate() {
            let Some(heat) = joint.heat() else { continue };
            let temp = y[heat.state];
            let bodies = [joint.bearing, joint.journal];
            let dt = f64::EPSILON.sqrt() * temp.abs().max(1.0);
            // ∂q̈/∂T through the viscosity.
            if heat.vogel.is_some() {
                joint_generalised_force(joint, &self.ws.kin, &heat.memory_at(&self.memory[j], temp), &mut self.g_base);
                joint_generalised_force(joint, &self.ws.kin, &heat.memory_at(&self.memory[j], temp + dt), &mut self.g_probe);
                let col = &mut a_z[row * m..(row + 1) * m];
                for b in bodies.iter().flatten().map(|&b| b as usize) {
                    for o in 3 * b..3 * b + 3 {
                        let d = (self.g_probe[o] - self.g_base[o]) / dt;
                        if d == 0.0 {
                            continue;
                        }
                        if !self.mobility_done[o] {
                            self.ws.unit_force_response(o, &mut self.mobility[o * m..(o + 1) * m]);
                            self.mobility_done[o] = true;
                        }
                        for (c, s) in col.iter_mut().zip(&self.mobility[o * m..(o + 1) * m]) {
                            *c += d * s;
                        }
                    }
                }
            }
            // ∂Ṫ/∂y: the power loss differenced in the bodies' q, q̇ and in T.
            let z_row = &mut z_y[row * n..(row + 1) * n];
            let base = self.power_loss_at(j, &probe);
            let capacity = heat.thermal.heat_capacity;
            for b in bodies.iter().flatten().map(|&b| b as usize) {
                for idx in (3 * b..3 * b + 3).chain(m + 3 * b..m + 3 * b + 3) {
                    let keep = probe[idx];
                    probe[idx] = keep + self.jacobian_difference_step(idx, y);
                    let delta = probe[idx] - keep;
                    let p = self.power_loss_at(j, &probe);
                    probe[idx] = keep;
                    z_row[idx] = (p - base) / delta / capacity;
                }
            }
            probe[heat.state] = temp + dt;
            let p_t = (self.power_loss_at(j, &probe) - base) / dt;
            probe[heat.state] = temp;
            z_row[heat.state] = (p_t - heat.thermal.heat_transfer) / capacity;
            row += 1;
        }
        self.scratch = probe;
        // Columns computed from here on need the factor of their own pose.
        self.mobility_at.clear();
        Ok(())
    }

    /// Joint `j`'s power loss \[W\] at the state `y` (its kinematics, forces and readings at y's
    /// oil temperature; no KKT solve).
    fn power_loss_at(&self, j: usize, y: &[f64]) -> f64 {
        let joint = &self.model.clearance[j];
        let k = self.joint_kinematics(j, y);
        let memory = joint.memory_at(&self.memory[j], y);
        let f = joint.force(&k, &memory);
        let m = 3 * self.model.n_bodies();
        let (w_b, w_j) = crate::clearance::body_rates(joint, &y[m..2 * m]);
        joint.readings(&k, &f, &memory, w_b, w_j).power_loss
    }
}
