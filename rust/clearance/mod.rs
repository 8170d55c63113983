//! Clearance joints (docs/physics.md §2–§4, §11): a journal in its bearing, or a slider end in
//! its guide. This file: the compiled joint, its force law (dry, or lubricated with the
//! transition to dry), its generalised forces and how deep it may penetrate; `kinematics.rs`
//! the journal's motion inside the bearing, `memory.rs` the impact memory, `wear.rs` the wear
//! books. The joint's two constraint equations are removed; the journal gains 2 DOF.

pub mod kinematics;
pub mod memory;
pub mod mixed;
pub mod readings;
pub mod thermal;
pub mod wear;

pub use kinematics::JointKinematics;
pub use memory::ImpactMemory;
pub use readings::{body_rates, Readings, READING_COLUMNS};

use crate::constraints::{BodyKin, V2};
use crate::laws::contact::ContactLaw;
use crate::laws::film::{film_force, BearingGeometry, FilmModel, FilmState};
use crate::laws::friction::ModifiedCoulomb;
use crate::laws::transition::{film_eps, small_eccentricity_scale, transition_weights};

/// Eccentricity ratio below which a long-bearing film is blended into its centre limit
/// (docs/physics.md §4).
pub const CENTRE_BAND: f64 = 5e-2;

/// Weight of the long bearing's centre limit ([`crate::laws::long_bearing_centre_limit`]) at
/// eccentricity ratio `eps`: (1 − ε/ε_c)² below ε_c = [`CENTRE_BAND`], 0 above and for the
/// short and finite bearings.
///
/// The long bearing (Pinkus–Sternlicht) puts the ambient pressure at the thickest film, which
/// flips to the other side as the journal passes the centre; with the Gümbel condition a
/// squeeze toward the wall then carries load on one side of the centre and none on the other
/// (at ε → 0 the pressure is ∝ ε̇ (1 − cos θ), one-signed), so the force jumps at e = 0 and a
/// journal held near the centre by a µm film (ε ~ 1e-5) stalls the integrator. The centre
/// limit is linear in the journal's motion and continuous through e = 0.
#[inline]
pub fn centre_weight(model: FilmModel, eps: f64) -> f64 {
    match model {
        FilmModel::LongBearing | FilmModel::LongBearingPaperClosedForm if eps < CENTRE_BAND => {
            let x = 1.0 - eps.max(0.0) / CENTRE_BAND;
            x * x
        }
        _ => 0.0,
    }
}

/// Whether a contact onset or end (δ changing sign) between two samples `a`, `b` of a step is
/// grazing (docs/physics.md §3, "Grazing contacts"): at both samples the penetration (or gap)
/// is within `±gap_resolution` \[m\] (the run's position tolerance) and the approach speed
/// |δ̇| is at most the law's impact speed floor (below which the contact law treats a contact
/// as resting: δ̇⁽⁻⁾ is floored there). Such a crossing is not located as a switching point:
/// the force that a step straddling it misses is at most K·gap_resolutionⁿ·(1 + D), and near
/// a wall that the journal slides along (δ̇ ≈ 0) δ changes sign on round-off alone, where
/// locating it would redo steps without end.
#[inline]
pub fn grazing(a: &JointKinematics, b: &JointKinematics, gap_resolution: f64, speed_floor: f64) -> bool {
    a.delta.abs() <= gap_resolution && b.delta.abs() <= gap_resolution && a.delta_dot.abs() <= speed_floor && b.delta_dot.abs() <= speed_floor
}

/// The deepest penetration δ = e − c \[m\] a clearance joint may reach before the run stops:
/// the larger of the clearance and 5 % of the journal radius. Hertzian contact laws assume a
/// contact patch small against the radii; a journal driven deeper than this has left the
/// model (a locked-up mechanism, a pose it cannot pass, a far too soft law) and would otherwise
/// run on with meaningless forces (docs: "Failures").
pub fn max_penetration(clearance: f64, journal_radius: f64) -> f64 {
    clearance.max(0.05 * journal_radius)
}

thread_local! {
    /// Evaluations of [`ClearanceJoint::force`] on this thread ([`force_evaluations`]).
    static FORCE_EVALUATIONS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// How many times a clearance joint's force law ([`ClearanceJoint::force`]) has been evaluated
/// on this thread: a run's difference of it is its `force_evaluations`, a count of the work its
/// right-hand sides, Newton matrices, outputs and observers did (the performance fingerprint,
/// `benches/perf_fingerprint.py`, catches work added where no step or right-hand side shows it).
pub fn force_evaluations() -> u64 {
    FORCE_EVALUATIONS.with(std::cell::Cell::get)
}

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
    /// Rough surfaces (`Lubricated(roughness=σ)`): asperity load and boundary friction in
    /// place of the transition band ([`mixed`]); `None`: the band (P18).
    pub mixed: Option<mixed::Mixed>,
    /// The oil temperature's balance and viscosity law (`Lubricated(thermal=…)`,
    /// [`thermal`]); `None`: a constant viscosity and no temperature.
    pub heat: Option<thermal::Heat>,
}

impl Film {
    /// The bearing geometry with the viscosity the joint's `memory` holds (a temperature-
    /// dependent one, [`ImpactMemory::viscosity`]), else the film's constant one.
    #[inline]
    pub fn geometry_at(&self, memory: &ImpactMemory) -> BearingGeometry {
        if memory.viscosity > 0.0 {
            BearingGeometry { viscosity: memory.viscosity, ..self.geometry }
        } else {
            self.geometry
        }
    }
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
    /// Penetration \[m\] beyond which the run stops ([`crate::error::Error::PenetrationTooDeep`]).
    pub penetration_limit: f64,
    /// Archard wear, when asked for (docs/physics.md §12).
    pub wear: Option<crate::laws::wear::Archard>,
}

/// What the joint's law produced at one instant.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct JointForce {
    /// Total force on the journal \[N\] (global); the bearing gets its opposite.
    pub total: V2,
    /// Dry normal force magnitude F_N \[N\] (before blending).
    pub normal: f64,
    /// Dry tangential (friction) force along t \[N\] (before blending).
    pub tangential: f64,
    /// Film force components along n and t \[N\] (before blending).
    pub film_xi: f64,
    pub film_eta: f64,
    /// Weight of the dry law (0 in the film, 1 in full contact).
    pub w_dry: f64,
    /// 0: free flight (dry) or film; 1: transition band (with roughness: asperities touching);
    /// 2: contact (δ > 0, dry law in full).
    pub state: u8,
    /// Rough surfaces only ([`mixed`]): the asperities' load \[N\] (along −n) and its boundary
    /// friction along t \[N\].
    pub asperity: f64,
    pub asperity_tangential: f64,
}

impl JointForce {
    /// The friction force along t acting at the contact points \[N\]: the dry law's by its weight,
    /// plus the asperities' boundary friction on a rough joint.
    #[inline]
    pub fn friction(&self) -> f64 {
        let dry = self.w_dry * self.tangential;
        if self.asperity_tangential == 0.0 { dry } else { dry + self.asperity_tangential }
    }
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
        FORCE_EVALUATIONS.with(|c| c.set(c.get() + 1));
        let mut out = JointForce::default();
        // Penetration beyond the worn surfaces (the offset is 0 unless wear is fed back).
        let delta = k.delta - memory.wear_offset;
        let (w_film, w_dry) = match &self.film {
            None => (0.0, if delta > 0.0 { 1.0 } else { 0.0 }),
            // Rough surfaces: no band; the film everywhere, the dry law where the mean surfaces overlap.
            Some(Film { mixed: Some(_), .. }) => (1.0, if delta > 0.0 { 1.0 } else { 0.0 }),
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
            let (mut xi, mut eta) = film_force(f.model, &f.geometry_at(memory), s, f.table);
            let w = centre_weight(f.model, k.eps);
            if w > 0.0 {
                // Near the centre the long bearing's force depends on which side n points (its
                // ambient-pressure point flips there): blend into its smooth first-order limit.
                let (xc, ec) = crate::laws::long_bearing_centre_limit(&f.geometry_at(memory), s);
                xi = (1.0 - w) * xi + w * xc;
                eta = (1.0 - w) * eta + w * ec;
            }
            let scale = small_eccentricity_scale(k.eps, f.eps0, f.m);
            out.film_xi = xi * scale;
            out.film_eta = eta * scale;
        }
        out.w_dry = w_dry;
        // On the journal: film F_ξ n + F_η t; dry −F_N n + F_t t (docs/physics.md §3, P17–P18).
        let mut f_n = w_film * out.film_xi - w_dry * out.normal;
        let mut f_t = w_film * out.film_eta + w_dry * out.tangential;
        if let Some(Film { mixed: Some(m), geometry, .. }) = &self.film {
            (out.asperity, out.asperity_tangential) = m.force(geometry, k.eps, k.slip);
            f_n -= out.asperity;
            f_t += out.asperity_tangential;
        }
        out.total = k.n.scale(f_n).add(k.t.scale(f_t));
        out.state = if self.film.as_ref().is_some_and(|f| f.mixed.is_some()) {
            if delta > 0.0 { 2 } else if out.asperity > 0.0 { 1 } else { 0 }
        } else if self.film.is_some() {
            if k.delta <= 0.0 { 0 } else if w_film > 0.0 { 1 } else { 2 }
        } else if delta > 0.0 {
            2
        } else {
            0
        };
        out
    }

    /// Derivatives of the joint's generalised forces, for the implicit methods' Newton matrix
    /// (docs/physics.md §4): `d[r][c]` is ∂g_r/∂x_c, rows r = (bearing x, y, θ, journal x,
    /// y, θ) of `g`, columns c = (bearing x, y, θ, ẋ, ẏ, θ̇, journal x, y, θ, ẋ, ẏ, θ̇).
    /// `None` for a slider-in-guide joint (differenced in body coordinates by the caller).
    ///
    /// The law is differenced (central differences) in the variables it depends on — e, ė
    /// and the two angular speeds — with steps on the scale of the clearance, and the chain
    /// rule to body coordinates is exact. Differencing in body coordinates instead (steps of
    /// ~1e-8 m) crosses a µm bearing's centre, and its round-off gives the film a spurious
    /// stiffness against the two bodies' common motion of ~1e-3 of the film's own, which stops
    /// Newton's iteration for any step above ~1e-9 s.
    pub fn force_derivatives(&self, kin: &[BodyKin], memory: &ImpactMemory) -> Option<[[f64; 12]; 6]> {
        if self.guide_normal.is_some() {
            return None;
        }
        let body = |b: Option<u32>| b.map_or(BodyKin::GROUND, |i| kin[i as usize]);
        let (kb, kj) = (body(self.bearing), body(self.journal));
        let k0 = self.kinematics(kin);
        let (r_j, r_b, c) = (self.journal_radius, self.bearing_radius, self.clearance);
        // Force on the journal (x, y) and the friction force w_dry·F_t of the law at z =
        // (e_x, e_y, ė_x, ė_y, θ̇_b, θ̇_j).
        let law = |z: [f64; 6]| -> [f64; 3] {
            let k = JointKinematics::relative(V2::new(z[0], z[1]), V2::new(z[2], z[3]), z[4], z[5], r_j, r_b, c);
            let f = self.force(&k, memory);
            [f.total.x, f.total.y, f.friction()]
        };
        let z0 = [k0.e_vec.x, k0.e_vec.y, k0.e_dot.x, k0.e_dot.y, kb.w, kj.w];
        let cbrt = f64::EPSILON.cbrt();
        let e_scale = k0.e.min(c).max(1e-4 * c);
        let v_scale = k0.e_dot.norm().max(c * (kb.w.abs() + kj.w.abs())).max(c);
        let steps = [e_scale, e_scale, v_scale, v_scale, kb.w.abs().max(1.0), kj.w.abs().max(1.0)].map(|s| cbrt * s);
        // ∂(F_x, F_y, friction)/∂z: central differences in the position e; forward ones in the
        // velocities, in which a film force is linear while its pressure arc holds (docs/physics.md
        // §4: F = wedge·A(ε) + ε̇·B(ε)) and a contact's nearly so (four law evaluations fewer).
        let f0 = law(z0);
        let mut dlaw = [[0.0; 6]; 3];
        for (i, step) in steps.iter().enumerate() {
            let (mut zp, mut zm) = (z0, z0);
            zp[i] += step;
            let fp = law(zp);
            let fm = if i < 2 {
                zm[i] -= step;
                law(zm)
            } else {
                f0
            };
            let h = zp[i] - zm[i];
            for r in 0..3 {
                dlaw[r][i] = (fp[r] - fm[r]) / h;
            }
        }
        let force = V2::new(f0[0], f0[1]);
        let arms = [kb.rot(self.bearing_point), kj.rot(self.journal_point)];
        let (ws, radii, signs) = ([kb.w, kj.w], [r_b, r_j], [-1.0, 1.0]);
        // ∂z/∂(body coordinates): e = P_j − P_b, ė = Ṗ_j − Ṗ_b; P = r + A s, Ṗ = ṙ + θ̇ (A s)⊥.
        let mut dz = [[0.0; 12]; 6];
        for b in 0..2 {
            let (sg, arm, o) = (signs[b], arms[b], 6 * b);
            let p = arm.perp();
            dz[0][o] = sg; // e_x / x
            dz[1][o + 1] = sg; // e_y / y
            dz[0][o + 2] = sg * p.x; // e / θ
            dz[1][o + 2] = sg * p.y;
            dz[2][o + 2] = -sg * ws[b] * arm.x; // ė / θ
            dz[3][o + 2] = -sg * ws[b] * arm.y;
            dz[2][o + 3] = sg; // ė / ẋ, ẏ
            dz[3][o + 4] = sg;
            dz[2][o + 5] = sg * p.x; // ė / θ̇
            dz[3][o + 5] = sg * p.y;
            dz[4 + b][o + 5] = 1.0; // θ̇_b, θ̇_j
        }
        // ∂(F_x, F_y, friction)/∂(body coordinates).
        let mut dlf = [[0.0; 12]; 3];
        for r in 0..3 {
            for col in 0..12 {
                dlf[r][col] = (0..6).map(|i| dlaw[r][i] * dz[i][col]).sum();
            }
        }
        // g of body b: sign·(F_x, F_y, arm × F + R·friction).
        let mut d = [[0.0; 12]; 6];
        for b in 0..2 {
            let (sg, arm, radius) = (signs[b], arms[b], radii[b]);
            for col in 0..12 {
                d[3 * b][col] = sg * dlf[0][col];
                d[3 * b + 1][col] = sg * dlf[1][col];
                d[3 * b + 2][col] = sg * (arm.x * dlf[1][col] - arm.y * dlf[0][col] + radius * dlf[2][col]);
            }
            // The arm turns with its body: ∂(arm × F)/∂θ = (arm)⊥ × F.
            d[3 * b + 2][6 * b + 2] += sg * arm.perp().cross(force);
        }
        Some(d)
    }

    /// Add the joint's generalised forces (force and moment about each centroid) to `g`.
    /// Film forces act through the journal and bearing centres; the dry friction force acts at
    /// the contact points Q_k = P_k + R_k n and so adds the moments R_j F_t and −R_b F_t.
    #[inline]
    pub fn apply(&self, kin: &[BodyKin], k: &JointKinematics, f: &JointForce, g: &mut [f64]) {
        let friction = f.friction();
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::laws::contact::NormalLaw;

    fn joint(model: FilmModel) -> ClearanceJoint {
        let c = 5e-6;
        let geometry = BearingGeometry { viscosity: 0.4, journal_radius: 0.01, clearance: c, length: 0.025 };
        ClearanceJoint {
            name: "pin".into(),
            bearing: Some(0),
            bearing_point: V2::new(0.0, 0.0),
            journal: Some(1),
            journal_point: V2::new(0.0, 0.0),
            journal_radius: 0.01,
            bearing_radius: 0.01 + c,
            clearance: c,
            contact: ContactLaw { line: None, law: NormalLaw::LankaraniNikravesh, stiffness: 1e10, exponent: 1.5, restitution: 0.9, impact_speed_floor: 1e-4 },
            friction: ModifiedCoulomb { friction_coefficient: 0.1, v0: 1e-4, v1: 1e-3 },
            film: Some(Film { model, table: None, geometry, eps0: 2e-6, m: 0.5, e0: 0.05 * c, eps_max: 0.99, mixed: None, heat: None }),
            guide_normal: None,
            penetration_limit: c,
            wear: None,
        }
    }

    /// Film force on a journal at eccentricity vector `e` [m] moving at `e_dot` [m/s].
    fn force_at(j: &ClearanceJoint, e: V2, e_dot: V2) -> V2 {
        let k = JointKinematics::relative(e, e_dot, 0.0, 15.0, j.journal_radius, j.bearing_radius, j.clearance);
        j.force(&k, &ImpactMemory::default()).total
    }

    #[test]
    fn the_film_force_is_continuous_through_the_bearing_centre() {
        // A journal squeezed along (1, 0.3) passes the centre: the force just before and just
        // after must agree. The long bearing's ambient-pressure point (the thickest film) flips
        // there, and without the centre limit its force jumped from ~0 to the full squeeze
        // force (docs/physics.md §4).
        let dir = V2::new(1.0, 0.3);
        let e_dot = dir.scale(1e-7);
        for model in [FilmModel::LongBearing, FilmModel::ShortBearing, FilmModel::LongBearingPaperClosedForm] {
            let j = joint(model);
            let scale = force_at(&j, dir.scale(2e-3 * j.clearance), e_dot).norm();
            for s in [1e-5, 1e-6, 1e-7] {
                let before = force_at(&j, dir.scale(-s * j.clearance), e_dot);
                let after = force_at(&j, dir.scale(s * j.clearance), e_dot);
                let jump = before.sub(after).norm();
                // What is left of the long law near the centre, 1 − (1 − ε/ε_c)² ≈ 2ε/ε_c, makes
                // a difference ∝ ε: → 0 at the centre (without the centre limit it is ~100 %).
                assert!(jump < 1e3 * s * scale, "{model:?} at ε = {s:e}: {before:?} before, {after:?} after the centre");
            }
        }
    }

    #[test]
    fn the_centre_average_leaves_the_film_alone_above_its_band() {
        for eps in [CENTRE_BAND, 0.1, 0.5] {
            assert_eq!(centre_weight(FilmModel::LongBearing, eps), 0.0);
        }
        assert_eq!(centre_weight(FilmModel::ShortBearing, 0.0), 0.0);
        assert_eq!(centre_weight(FilmModel::Finite, 0.0), 0.0);
        assert_eq!(centre_weight(FilmModel::LongBearing, 0.0), 1.0);
    }
}

#[cfg(test)]
mod friction_moments {
    use super::*;
    use crate::laws::contact::NormalLaw;

    #[test]
    fn friction_acts_at_the_contact_point_of_each_surface() {
        // A dry pin pressed 1e-5 m into its bearing along n = x while slipping: the friction
        // force F_t t acts on the journal at Q = P_j + R_j n and its opposite on the bearing at
        // P_b + R_b n, so about the centroids (journal and bearing points at their origins) the
        // moments are R_j F_t and −R_b F_t (n × t = 1); the forces pass through no other arm.
        let (c, r_j) = (5e-4, 0.01);
        let joint = ClearanceJoint {
            name: "pin".into(),
            bearing: Some(0),
            bearing_point: V2::new(0.0, 0.0),
            journal: Some(1),
            journal_point: V2::new(0.0, 0.0),
            journal_radius: r_j,
            bearing_radius: r_j + c,
            clearance: c,
            contact: ContactLaw { line: None, law: NormalLaw::Hertz, stiffness: 1e10, exponent: 1.5, restitution: 1.0, impact_speed_floor: 1e-4 },
            friction: ModifiedCoulomb { friction_coefficient: 0.2, v0: 1e-4, v1: 1e-3 },
            film: None,
            guide_normal: None,
            penetration_limit: c,
            wear: None,
        };
        let kin = [BodyKin::new(&[0.0, 0.0, 0.0], &[0.0, 0.0, 0.0]), BodyKin::new(&[c + 1e-5, 0.0, 0.0], &[0.0, 0.0, 30.0])];
        let k = joint.kinematics(&kin);
        let f = joint.force(&k, &ImpactMemory::default());
        assert!(f.normal > 0.0 && f.tangential != 0.0);
        // Full Coulomb (slip 0.3 m/s ≫ v1), opposing the slip: F_t = −c_f F_N.
        assert!((f.tangential + 0.2 * f.normal).abs() < 1e-9 * f.normal);
        let mut g = [0.0; 6];
        joint.apply(&kin, &k, &f, &mut g);
        assert!((g[3] + f.normal).abs() < 1e-9 * f.normal && (g[4] - f.tangential).abs() < 1e-9 * f.normal);
        assert!((g[5] - r_j * f.tangential).abs() < 1e-12 * f.normal, "journal moment {}", g[5]);
        assert!((g[2] + (r_j + c) * f.tangential).abs() < 1e-12 * f.normal, "bearing moment {}", g[2]);
        assert!((g[0] + g[3]).abs() < 1e-12 * f.normal && (g[1] + g[4]).abs() < 1e-12 * f.normal);
    }
}

#[cfg(test)]
mod grazing_crossings {
    use super::*;

    /// A journal in a 0.5 mm clearance at `e` [m] along x moving at `ė` [m/s].
    fn at(e: f64, e_dot: V2) -> JointKinematics {
        JointKinematics::relative(V2::new(e, 0.0), e_dot, 0.0, 0.0, 0.01, 0.0105, 0.5e-3)
    }

    #[test]
    fn a_crossing_within_the_position_tolerance_at_resting_speed_is_grazing() {
        let c = 0.5e-3;
        let (atol, floor) = (1e-9, 1e-3);
        // Sliding along the wall: δ changes sign by 1e-19 m, δ̇ ≈ 0.
        assert!(grazing(&at(c, V2::new(0.0, 0.1)), &at(c + 1e-19, V2::new(1e-13, 0.1)), atol, floor));
        // The same δ at an approach speed of 0.1 m/s is an impact: located.
        assert!(!grazing(&at(c - 1e-10, V2::new(0.1, 0.0)), &at(c + 1e-10, V2::new(0.1, 0.0)), atol, floor));
        // Resting speed but a gap beyond the tolerance at one sample: located.
        assert!(!grazing(&at(c - 1e-8, V2::new(1e-4, 0.0)), &at(c + 1e-10, V2::new(1e-4, 0.0)), atol, floor));
        // Outside a run (gap resolution 0) nothing is grazing but an exact touch.
        assert!(!grazing(&at(c - 1e-19, V2::new(0.0, 0.0)), &at(c + 1e-19, V2::new(0.0, 0.0)), 0.0, floor));
    }
}
