//! Kinematics of a journal inside its bearing (docs/physics.md §2, P7–P9).

use crate::constraints::{BodyKin, V2};

/// Eccentricity and the derived quantities every clearance law needs.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct JointKinematics {
    /// Eccentricity vector e = r_Pj − r_Pi [m] and its rate [m/s].
    pub e_vec: V2,
    pub e_dot: V2,
    /// |e| [m].
    pub e: f64,
    /// Unit eccentricity n (bearing → journal centre; +x when e = 0) and t = n turned +90°.
    pub n: V2,
    pub t: V2,
    /// ε = e / c and ε̇ [1/s].
    pub eps: f64,
    pub eps_dot: f64,
    /// Penetration δ = e − c [m] (contact when > 0) and its rate δ̇ = n·ė [m/s].
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

    /// The same from the relative motion alone: eccentricity vector `e_vec` [m], its rate
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
