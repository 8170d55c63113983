//! Ideal joints as holonomic constraints Φ(q, t) = 0 (docs/physics.md §1): revolute, prismatic and driving
//! constraints. Each row's Jacobian touches at most two bodies and is stored sparsely
//! ([`JacRow`]); the acceleration right-hand side γ = −(Φq q̇)_q q̇ − 2Φqt q̇ − Φtt (P24) is
//! evaluated in closed form per primitive.

pub mod angle_law;
pub mod kinematics;

pub use angle_law::CompiledAngleLaw;
pub use kinematics::{BodyKin, V2};

/// The Jacobian row of one constraint equation: coefficients for (x, y, θ) of up to two bodies.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct JacRow {
    pub bodies: [u32; 2],
    pub count: u8,
    pub coef: [[f64; 3]; 2],
}

impl JacRow {
    #[inline]
    fn clear(&mut self) {
        self.count = 0;
    }
    #[inline]
    fn push(&mut self, body: Option<u32>, c: [f64; 3]) {
        if let Some(b) = body {
            let k = self.count as usize;
            self.bodies[k] = b;
            self.coef[k] = c;
            self.count += 1;
        }
    }
    /// Φq row · v for a generalised velocity (or acceleration) vector `v` (3 per body).
    #[inline]
    pub fn dot(&self, v: &[f64]) -> f64 {
        let mut s = 0.0;
        for k in 0..self.count as usize {
            let o = 3 * self.bodies[k] as usize;
            let c = &self.coef[k];
            s += c[0] * v[o] + c[1] * v[o + 1] + c[2] * v[o + 2];
        }
        s
    }
}

/// A compiled ideal joint or driver. Body indices are `None` for the ground.
#[derive(Debug, Clone, PartialEq)]
pub enum Constraint {
    /// r_a + A_a s_a − r_b − A_b s_b − offset = 0 (2 rows). `offset` (global frame) is zero for
    /// a joint; the kinematic assembly uses it to place a clearance journal at its initial
    /// eccentricity.
    Revolute { a: Option<u32>, sa: V2, b: Option<u32>, sb: V2, offset: V2 },
    /// Prismatic: (A_a u⊥)·d = 0 with d = r_b + A_b s_b − r_a − A_a s_a, and θ_b − θ_a − θ0 = 0
    /// (2 rows). `u_perp` is the unit normal of the guide in body a's frame.
    Prismatic { a: Option<u32>, sa: V2, u_perp: V2, b: u32, sb: V2, theta0: f64 },
    /// θ_b − f(t) = 0 (1 row).
    Driver { b: u32, law: CompiledAngleLaw },
}

impl Constraint {
    /// Number of scalar equations.
    pub fn rows(&self) -> usize {
        match self {
            Constraint::Revolute { .. } | Constraint::Prismatic { .. } => 2,
            Constraint::Driver { .. } => 1,
        }
    }

    /// Evaluate Φ, Φt, γ and the Jacobian rows of this constraint, writing `self.rows()` entries
    /// starting at each slice's beginning.
    #[inline]
    pub fn eval(&self, t: f64, kin: &[BodyKin], phi: &mut [f64], phi_t: &mut [f64], gamma: &mut [f64], jac: &mut [JacRow]) {
        let get = |b: Option<u32>| -> BodyKin { b.map_or(BodyKin::GROUND, |i| kin[i as usize]) };
        match self {
            Constraint::Revolute { a, sa, b, sb, offset } => {
                let (ka, kb) = (get(*a), get(*b));
                let (asa, asb) = (ka.rot(*sa), kb.rot(*sb));
                let (bsa, bsb) = (asa.perp(), asb.perp()); // B s = A s turned +90°
                let d = ka.r().add(asa).sub(kb.r()).sub(asb).sub(*offset);
                phi[0] = d.x;
                phi[1] = d.y;
                phi_t[0] = 0.0;
                phi_t[1] = 0.0;
                // γ = A_a s_a θ̇_a² − A_b s_b θ̇_b²
                gamma[0] = asa.x * ka.w * ka.w - asb.x * kb.w * kb.w;
                gamma[1] = asa.y * ka.w * ka.w - asb.y * kb.w * kb.w;
                jac[0].clear();
                jac[1].clear();
                jac[0].push(*a, [1.0, 0.0, bsa.x]);
                jac[1].push(*a, [0.0, 1.0, bsa.y]);
                jac[0].push(*b, [-1.0, 0.0, -bsb.x]);
                jac[1].push(*b, [0.0, -1.0, -bsb.y]);
            }
            Constraint::Prismatic { a, sa, u_perp, b, sb, theta0 } => {
                let (ka, kb) = (get(*a), kin[*b as usize]);
                let (asa, asb) = (ka.rot(*sa), kb.rot(*sb));
                let v = ka.rot(*u_perp); // guide normal, global
                let bv = v.perp();
                let d = kb.r().add(asb).sub(ka.r()).sub(asa);
                let ddot = kb.v().add(asb.perp().scale(kb.w)).sub(ka.v()).sub(asa.perp().scale(ka.w));
                phi[0] = v.dot(d);
                phi[1] = kb.th - ka.th - theta0;
                phi_t[0] = 0.0;
                phi_t[1] = 0.0;
                // Φ̈ = v̈·d + 2v̇·ḋ + v·d̈; γ collects the terms free of q̈.
                gamma[0] = v.dot(d) * ka.w * ka.w - 2.0 * ka.w * bv.dot(ddot)
                    + v.dot(asb) * kb.w * kb.w
                    - v.dot(asa) * ka.w * ka.w;
                gamma[1] = 0.0;
                jac[0].clear();
                jac[1].clear();
                jac[0].push(*a, [-v.x, -v.y, bv.dot(d) - v.dot(asa.perp())]);
                jac[0].push(Some(*b), [v.x, v.y, v.dot(asb.perp())]);
                jac[1].push(*a, [0.0, 0.0, -1.0]);
                jac[1].push(Some(*b), [0.0, 0.0, 1.0]);
            }
            Constraint::Driver { b, law } => {
                let kb = kin[*b as usize];
                let (f, df, ddf) = law.eval(t);
                phi[0] = kb.th - f;
                phi_t[0] = -df;
                gamma[0] = ddf;
                jac[0].clear();
                jac[0].push(Some(*b), [0.0, 0.0, 1.0]);
            }
        }
    }

    /// What this constraint exerts on its second body — body b of a joint (for an ideal joint
    /// made from a clearance joint: the journal), a driver's driven body — from its own
    /// multipliers `lambda` (its `rows()` entries of λ), in the global frame: `[fx, fy, torque]`,
    /// the force \[N\] through the joint's point on that body and a couple \[N m\],
    /// counter-clockwise positive (docs/physics.md §1, *Reactions*). Together they are the part
    /// of the constraint force −Φqᵀλ on that body; the first body (or the ground) takes the
    /// opposite force at the same place and the opposite couple.
    ///
    /// - revolute: F = (λ₀, λ₁) at s_b, no couple (Φ = r_a + A_a s_a − r_b − A_b s_b);
    /// - prismatic: F = −λ₀ n at s_b with n = A_a u⊥ the guide's unit normal (a force normal to
    ///   the guide) and the couple −λ₁ that keeps the relative angle;
    /// - driver: no force, the driving torque −λ₀ on its body.
    #[inline]
    pub fn reaction(&self, kin: &[BodyKin], lambda: &[f64]) -> [f64; 3] {
        match self {
            Constraint::Revolute { .. } => [lambda[0], lambda[1], 0.0],
            Constraint::Prismatic { a, u_perp, .. } => {
                let n = a.map_or(BodyKin::GROUND, |i| kin[i as usize]).rot(*u_perp);
                [-lambda[0] * n.x, -lambda[0] * n.y, -lambda[1]]
            }
            Constraint::Driver { .. } => [0.0, 0.0, -lambda[0]],
        }
    }

    /// The body [`Constraint::reaction`] acts on and its point there (body frame; `None`: the
    /// ground).
    pub fn second_body(&self) -> (Option<u32>, V2) {
        match self {
            Constraint::Revolute { b, sb, .. } => (*b, *sb),
            Constraint::Prismatic { b, sb, .. } => (Some(*b), *sb),
            Constraint::Driver { b, .. } => (Some(*b), V2::default()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::description::AngleLaw;

    /// The reaction on the second body equals the part of −Φqᵀλ on it (force, and moment about its
    /// centroid = (A_b s_b) × F + couple), and the first body takes the opposite force at the
    /// same global point and the opposite couple: a second method, from the Jacobian rows.
    #[test]
    fn reactions_are_the_constraint_force_on_the_second_body() {
        let kin = [BodyKin::new(&[0.3, -0.2, 0.7], &[1.0, 2.0, 3.0]), BodyKin::new(&[-0.1, 0.4, -1.2], &[0.5, -1.5, -2.0])];
        let law = CompiledAngleLaw::compile(&AngleLaw::ConstantSpeed { angle0: 0.1, omega: 2.0 }, "d").unwrap();
        let cases = [
            Constraint::Revolute { a: Some(0), sa: V2::new(0.2, 0.05), b: Some(1), sb: V2::new(-0.1, 0.03), offset: V2::default() },
            Constraint::Revolute { a: None, sa: V2::new(0.2, 0.05), b: Some(1), sb: V2::new(-0.1, 0.03), offset: V2::default() },
            Constraint::Prismatic { a: Some(0), sa: V2::new(0.1, -0.02), u_perp: V2::new(-0.6, 0.8), b: 1, sb: V2::new(0.04, 0.01), theta0: 0.3 },
            Constraint::Prismatic { a: None, sa: V2::new(0.1, -0.02), u_perp: V2::new(0.0, 1.0), b: 1, sb: V2::new(0.0, 0.0), theta0: 0.0 },
            Constraint::Driver { b: 1, law },
        ];
        let lambda = [2.5, -7.25];
        for con in &cases {
            let m = con.rows();
            let (mut phi, mut phi_t, mut gamma, mut jac) = ([0.0; 2], [0.0; 2], [0.0; 2], [JacRow::default(); 2]);
            con.eval(0.2, &kin, &mut phi[..m], &mut phi_t[..m], &mut gamma[..m], &mut jac[..m]);
            // −Φqᵀλ, body by body
            let mut g = [[0.0; 3]; 2];
            for (row, l) in jac[..m].iter().zip(&lambda[..m]) {
                for k in 0..row.count as usize {
                    for c in 0..3 {
                        g[row.bodies[k] as usize][c] -= row.coef[k][c] * l;
                    }
                }
            }
            let [fx, fy, tq] = con.reaction(&kin, &lambda[..m]);
            let f = V2::new(fx, fy);
            let (b, sb) = con.second_body();
            let b = b.unwrap() as usize;
            let arm = kin[b].rot(sb);
            let want = [fx, fy, arm.cross(f) + tq];
            for c in 0..3 {
                assert!((g[b][c] - want[c]).abs() < 1e-12, "{con:?}: body b, {c}: {} vs {}", g[b][c], want[c]);
            }
            // the first body (if any) takes −F and −couple: a revolute joint at its own point
            // (the two points coincide once assembled), a guide where the slider's point is
            let (a, at) = match con {
                Constraint::Revolute { a, sa, .. } => (*a, a.map(|a| kin[a as usize].rot(*sa))),
                Constraint::Prismatic { a, .. } => (*a, a.map(|a| kin[b].point(sb).sub(kin[a as usize].r()))),
                Constraint::Driver { .. } => (None, None),
            };
            if let (Some(a), Some(at)) = (a, at) {
                let a = a as usize;
                let want = [-fx, -fy, at.cross(f.scale(-1.0)) - tq];
                for c in 0..3 {
                    assert!((g[a][c] - want[c]).abs() < 1e-12, "{con:?}: body a, {c}: {} vs {}", g[a][c], want[c]);
                }
            }
        }
    }
}
