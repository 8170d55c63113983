//! Revolute clearance joints (docs/physics.md §2–§4): the journal's kinematics inside the bearing, the
//! force law (dry, or lubricated with the transition to dry), and its generalised forces.
//! The joint's two constraint equations are removed; the journal gains 2 DOF (docs/physics.md §2).

pub mod kinematics;
pub mod memory;

pub use kinematics::JointKinematics;
pub use memory::ImpactMemory;

use crate::constraints::{BodyKin, V2};
use crate::laws::contact::ContactLaw;
use crate::laws::film::{film_force, BearingGeometry, FilmModel, FilmState};
use crate::laws::friction::ModifiedCoulomb;
use crate::laws::transition::{film_eps, small_eccentricity_scale, transition_weights};

/// Parameters of the film part of a lubricated joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Film {
    pub model: FilmModel,
    /// The finite-length bearing's table (`FilmModel::Finite`), shared by joints of one L/D.
    pub table: Option<&'static crate::laws::bearing_finite::FiniteBearingTable>,
    pub geometry: BearingGeometry,
    pub eps0: f64,
    pub m: f64,
    pub e0: f64,
    pub eps_max: f64,
}

/// A compiled clearance joint. The dry law is always present: for a lubricated joint it acts
/// only beyond e = c (transition band and beyond, P18).
#[derive(Debug, Clone, PartialEq)]
pub struct ClearanceJoint {
    pub name: String,
    pub bearing: Option<u32>,
    pub bearing_point: V2,
    pub journal: Option<u32>,
    pub journal_point: V2,
    pub journal_radius: f64,
    pub bearing_radius: f64,
    pub clearance: f64,
    pub contact: ContactLaw,
    pub friction: ModifiedCoulomb,
    /// `None` for a dry joint: no film code runs.
    pub film: Option<Film>,
    /// A slider end in a guide (docs/physics.md §11): the guide's unit normal in the guide
    /// body's frame. The "bearing" is then the guide (its point on the guide line), the
    /// "journal" the slider (its end point), `clearance` half the lateral play and the radii 0.
    pub guide_normal: Option<V2>,
    /// Penetration [m] beyond which the run stops ([`crate::error::Error::PenetrationTooDeep`]).
    pub penetration_limit: f64,
    /// Archard wear, when asked for (docs/physics.md §12).
    pub wear: Option<crate::wear::Archard>,
}

/// What the joint's law produced at one instant.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct JointForce {
    /// Total force on the journal [N] (global); the bearing gets its opposite.
    pub total: V2,
    /// Dry normal force magnitude F_N [N] (before blending).
    pub normal: f64,
    /// Dry tangential (friction) force along t [N] (before blending).
    pub tangential: f64,
    /// Film force components along n and t [N] (before blending).
    pub film_xi: f64,
    pub film_eta: f64,
    /// Weight of the dry law (0 in the film, 1 in full contact).
    pub w_dry: f64,
    /// 0: free flight (dry) or film; 1: transition band; 2: contact (δ > 0, dry law in full).
    pub state: u8,
}

impl ClearanceJoint {
    /// Kinematics of the journal relative to the bearing (docs/physics.md §2).
    #[inline]
    pub fn kinematics(&self, kin: &[BodyKin]) -> JointKinematics {
        self.kinematics_with(|b| b.map_or(BodyKin::GROUND, |i| kin[i as usize]))
    }

    /// The same, with the bodies' kinematics supplied by `body` (`None` is the ground).
    #[inline]
    pub fn kinematics_with(&self, body: impl Fn(Option<u32>) -> BodyKin) -> JointKinematics {
        if let Some(normal) = self.guide_normal {
            return JointKinematics::in_guide(&body(self.bearing), self.bearing_point, normal, &body(self.journal), self.journal_point, self.clearance);
        }
        JointKinematics::new(
            &body(self.bearing),
            self.bearing_point,
            &body(self.journal),
            self.journal_point,
            self.journal_radius,
            self.bearing_radius,
            self.clearance,
        )
    }

    /// Evaluate the force law. `memory` supplies δ̇⁽⁻⁾ of the current impact.
    #[inline]
    pub fn force(&self, k: &JointKinematics, memory: &ImpactMemory) -> JointForce {
        let mut out = JointForce::default();
        // Penetration beyond the worn surfaces (the offset is 0 unless wear is fed back).
        let delta = k.delta - memory.wear_offset;
        let (w_film, w_dry) = match &self.film {
            None => (0.0, if delta > 0.0 { 1.0 } else { 0.0 }),
            Some(f) => transition_weights(k.e, self.clearance, f.e0),
        };
        if w_dry > 0.0 && delta > 0.0 {
            let impact_speed = memory.impact_speed_for(k.delta_dot);
            let f_n = self.contact.normal_force(delta, k.delta_dot, impact_speed);
            out.normal = f_n;
            out.tangential = self.friction.tangential_force(f_n, k.slip);
        }
        if let (Some(f), true) = (&self.film, w_film > 0.0) {
            let eps = film_eps(k.eps, f.eps_max);
            let s = FilmState { eps, eps_dot: k.eps_dot, wedge: k.wedge };
            let (xi, eta) = film_force(f.model, &f.geometry, s, f.table);
            let scale = small_eccentricity_scale(k.eps, f.eps0, f.m);
            out.film_xi = xi * scale;
            out.film_eta = eta * scale;
        }
        out.w_dry = w_dry;
        // On the journal: film F_ξ n + F_η t; dry −F_N n + F_t t (docs/physics.md §3, P17–P18).
        let f_n = w_film * out.film_xi - w_dry * out.normal;
        let f_t = w_film * out.film_eta + w_dry * out.tangential;
        out.total = k.n.scale(f_n).add(k.t.scale(f_t));
        out.state = if self.film.is_some() {
            if k.delta <= 0.0 { 0 } else if w_film > 0.0 { 1 } else { 2 }
        } else if delta > 0.0 {
            2
        } else {
            0
        };
        out
    }

    /// Add the joint's generalised forces (force and moment about each centroid) to `g`.
    /// Film forces act through the journal and bearing centres; the dry friction force acts at
    /// the contact points Q_k = P_k + R_k n and so adds the moments R_j F_t and −R_b F_t.
    #[inline]
    pub fn apply(&self, kin: &[BodyKin], k: &JointKinematics, f: &JointForce, g: &mut [f64]) {
        let friction = f.w_dry * f.tangential;
        if let Some(j) = self.journal {
            let kj = kin[j as usize];
            let arm = kj.rot(self.journal_point);
            let o = 3 * j as usize;
            g[o] += f.total.x;
            g[o + 1] += f.total.y;
            g[o + 2] += arm.cross(f.total) + self.journal_radius * friction;
        }
        if let Some(i) = self.bearing {
            let ki = kin[i as usize];
            // A guide takes the reaction where the slider end touches it, not at its point.
            let arm = match (self.guide_normal, self.journal) {
                (Some(_), Some(j)) => kin[j as usize].point(self.journal_point).sub(ki.r()),
                _ => ki.rot(self.bearing_point),
            };
            let o = 3 * i as usize;
            g[o] -= f.total.x;
            g[o + 1] -= f.total.y;
            g[o + 2] -= arm.cross(f.total) + self.bearing_radius * friction;
        }
        let _ = k;
    }
}
