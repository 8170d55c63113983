//! Kinematics of a journal inside its bearing (docs/physics.md §2, P7–P9).

use crate::constraints::{BodyKin, V2};

/// Eccentricity and the derived quantities every clearance law needs.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct JointKinematics {
    /// Eccentricity vector e = r_Pj − r_Pi \[m\] and its rate [m/s].
    pub e_vec: V2,
    pub e_dot: V2,
    /// |e| \[m\].
    pub e: f64,
    /// Unit eccentricity n (bearing → journal centre; +x when e = 0) and t = n turned +90°.
    pub n: V2,
    pub t: V2,
    /// ε = e / c and ε̇ [1/s].
    pub eps: f64,
    pub eps_dot: f64,
    /// Penetration δ = e − c \[m\] (contact when > 0) and its rate δ̇ = n·ė [m/s].
    pub delta: f64,
    pub delta_dot: f64,
    /// Slip of the journal's contact point relative to the bearing's, along t [m/s].
    pub slip: f64,
    /// γ̇ of the offset angle γ = atan2(e_y, e_x) [rad/s] (0 when e = 0).
    pub gamma_dot: f64,
    /// Wedge speed θ̇_j + θ̇_i − 2γ̇ [rad/s] (docs/physics.md §4).
    pub wedge: f64,
}

impl JointKinematics {
    /// A slider end in a guide (docs/physics.md §11): `e` is the end's lateral offset d n_g
    /// from the guide line (guide point `sg`, unit normal `normal_g` in the guide's frame), ė
    /// the end's velocity relative to the guide's material point under it, `half_gap` the
    /// free lateral travel; δ = |d| − half_gap, δ̇ = n·ė, slip = t·ė, no whirl or wedge.
    #[inline]
    pub fn in_guide(guide: &BodyKin, sg: V2, normal_g: V2, slider: &BodyKin, ss: V2, half_gap: f64) -> Self {
        let p = slider.point(ss);
        let n_g = guide.rot(normal_g);
        let d = n_g.dot(p.sub(guide.point(sg)));
        // Velocity of the guide's material point at p: v_g + θ̇_g (p − r_g)⊥.
        let e_dot = slider.point_velocity(ss).sub(guide.v().add(p.sub(guide.r()).perp().scale(guide.w)));
        let n = if d < 0.0 { n_g.scale(-1.0) } else { n_g };
        let t = n.perp();
        let delta_dot = n.dot(e_dot);
        JointKinematics {
            e_vec: n_g.scale(d),
            e_dot,
            e: d.abs(),
            n,
            t,
            eps: d.abs() / half_gap,
            eps_dot: delta_dot / half_gap,
            delta: d.abs() - half_gap,
            delta_dot,
            slip: t.dot(e_dot),
            gamma_dot: 0.0,
            wedge: 0.0,
        }
    }

    #[allow(clippy::too_many_arguments)]
    #[inline]
    pub fn new(bearing: &BodyKin, sb: V2, journal: &BodyKin, sj: V2, r_j: f64, r_b: f64, c: f64) -> Self {
        let e_vec = journal.point(sj).sub(bearing.point(sb));
        let e_dot = journal.point_velocity(sj).sub(bearing.point_velocity(sb));
        Self::relative(e_vec, e_dot, bearing.w, journal.w, r_j, r_b, c)
    }

    /// The same from the relative motion alone: eccentricity vector `e_vec` \[m\], its rate
    /// `e_dot` [m/s] and the angular speeds of bearing `w_b` and journal `w_j` [rad/s] (the
    /// variables the joint's force law depends on; its Newton-matrix derivatives are taken in
    /// them).
    #[inline]
    pub fn relative(e_vec: V2, e_dot: V2, w_b: f64, w_j: f64, r_j: f64, r_b: f64, c: f64) -> Self {
        let e = e_vec.norm();
        // n is formed as e/e, never 1/e (which overflows for subnormal e); γ̇ = (e × ė)/e² is
        // taken as 0 only where e² underflows. Near the centre γ̇ grows like 1/e but the film
        // sees ε·(θ̇_j + θ̇_b − 2γ̇) = ε(θ̇_j + θ̇_b) − 2 t·ė/c, which stays smooth through e = 0
        // (docs/physics.md §4); a cut-off at some e would make the film force jump there.
        let n = if e > 0.0 { V2::new(e_vec.x / e, e_vec.y / e) } else { V2::new(1.0, 0.0) };
        let n = if n.x.is_finite() && n.y.is_finite() { n } else { V2::new(1.0, 0.0) };
        let gamma_dot = if e * e > f64::MIN_POSITIVE { e_vec.cross(e_dot) / (e * e) } else { 0.0 };
        let t = n.perp();
        let delta_dot = n.dot(e_dot);
        // Contact-point velocities: material points of journal and bearing at Q_k = P_k + R_k n.
        let slip = t.dot(e_dot) + r_j * w_j - r_b * w_b;
        JointKinematics {
            e_vec,
            e_dot,
            e,
            n,
            t,
            eps: e / c,
            eps_dot: delta_dot / c,
            delta: e - c,
            delta_dot,
            slip,
            gamma_dot,
            wedge: w_j + w_b - 2.0 * gamma_dot,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, what: &str) {
        assert!((a - b).abs() <= 1e-12 * b.abs().max(1e-12), "{what}: {a} vs {b}");
    }

    #[test]
    fn a_whirling_journal_in_a_fixed_bearing() {
        // Hand-computed (docs/physics.md §2): ground bearing at the origin; the journal centre at
        // (1e-4, 0) m moving at (0, 2e-3) m/s and spinning at 10 rad/s. e = (1e-4, 0), n = x,
        // t = y; the line of centres turns at γ̇ = (e × ė)/e² = 20 rad/s; wedge = θ̇_j + θ̇_b −
        // 2γ̇ = −30 rad/s; δ = e − c, δ̇ = n·ė = 0; slip = t·ė + R_j θ̇_j − R_b θ̇_b = 0.102 m/s.
        let journal = BodyKin::new(&[1e-4, 0.0, 0.0], &[0.0, 2e-3, 10.0]);
        let k = JointKinematics::new(&BodyKin::GROUND, V2::new(0.0, 0.0), &journal, V2::new(0.0, 0.0), 0.01, 0.0105, 5e-4);
        close(k.e, 1e-4, "e");
        close(k.n.x, 1.0, "n.x");
        close(k.t.y, 1.0, "t.y");
        close(k.gamma_dot, 20.0, "γ̇");
        close(k.wedge, -30.0, "wedge");
        close(k.delta, -4e-4, "δ");
        assert_eq!(k.delta_dot, 0.0);
        assert_eq!(k.eps_dot, 0.0);
        close(k.eps, 0.2, "ε");
        close(k.slip, 0.102, "slip");
    }

    #[test]
    fn a_pin_on_a_turning_crank_in_a_sliding_bearing() {
        // Journal: a body at the origin turned by 90° at 5 rad/s, pin at s = (0.1, 0) → global
        // (0, 0.1), velocity 5·(A s)⊥ = (−0.5, 0). Bearing: a body at (0, 0.1 + 1e-4) sliding at
        // (0.2, 0), not turning, its point at its origin. e = (0, −1e-4), n = −y, t = n⊥ = x;
        // ė = (−0.7, 0); γ̇ = (e × ė)/e² = −7000 rad/s; wedge = 5 + 0 + 14000; δ̇ = n·ė = 0;
        // slip = t·ė + R_j·5 − R_b·0 = −0.7 + 0.05.
        let journal = BodyKin::new(&[0.0, 0.0, std::f64::consts::FRAC_PI_2], &[0.0, 0.0, 5.0]);
        let bearing = BodyKin::new(&[0.0, 0.1 + 1e-4, 0.0], &[0.2, 0.0, 0.0]);
        let k = JointKinematics::new(&bearing, V2::new(0.0, 0.0), &journal, V2::new(0.1, 0.0), 0.01, 0.0105, 5e-4);
        close(k.e_vec.y, -1e-4, "e_y");
        assert!(k.e_vec.x.abs() < 1e-17);
        close(k.n.y, -1.0, "n.y");
        close(k.t.x, 1.0, "t.x");
        close(k.e_dot.x, -0.7, "ė_x");
        close(k.gamma_dot, -7000.0, "γ̇");
        close(k.wedge, 14005.0, "wedge");
        assert!(k.delta_dot.abs() < 1e-12); // cos(π/2) rounds to 6e-17, not 0
        close(k.slip, -0.65, "slip");
    }

    #[test]
    fn relative_kinematics_are_those_of_the_bodies() {
        let journal = BodyKin::new(&[0.3, -0.2, 0.7], &[1.5, -0.4, 12.0]);
        let bearing = BodyKin::new(&[0.1, 0.4, -0.3], &[-0.6, 0.9, -4.0]);
        let (sb, sj) = (V2::new(0.25, -0.6), V2::new(-0.05, 0.01));
        let k = JointKinematics::new(&bearing, sb, &journal, sj, 0.01, 0.0105, 5e-4);
        let r = JointKinematics::relative(k.e_vec, k.e_dot, bearing.w, journal.w, 0.01, 0.0105, 5e-4);
        assert_eq!(k, r);
    }
}
