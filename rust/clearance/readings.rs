//! What a bearing engineer reads off a clearance joint at one instant (docs/physics.md §4, "Film
//! thickness, friction and power"): the film thickness, the friction torques on journal and
//! bearing and the power the joint dissipates in friction. Outputs only: the friction torques are
//! not applied to the bodies (the film's force acts through the centres, §4). One implementation
//! for the recorded channels ([`crate::record`]) and the monitors ([`crate::monitor`]).

use super::{ClearanceJoint, ImpactMemory, JointForce, JointKinematics};
use crate::laws::film_field::{film_field, flow_and_peak, FilmField, FiniteScratch, FlowAndPeak};
use crate::laws::film_friction::{dry_friction_torque, film_friction};
use crate::laws::transition::film_eps;
use crate::laws::FilmState;

/// The joint columns [`Readings::columns`] adds to [`crate::record::JOINT_COLUMNS`].
pub const READING_COLUMNS: [&str; 7] =
    ["film_thickness", "friction_torque", "friction_torque_bearing", "couette_torque", "poiseuille_torque", "power_loss", "asperity_force"];

/// One instant's readings of a clearance joint.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Readings {
    /// Smallest gap h = c − |e| \[m\] (negative: penetration; per slider end for a guide).
    pub film_thickness: f64,
    /// Friction torque on the journal about its centre \[N m\], counter-clockwise positive:
    /// the film's (weighted by the film's share of the transition blend, P18) plus the dry
    /// friction's moment R_j F_t (weighted by the dry share).
    pub torque_journal: f64,
    /// The same on the bearing about its centre (dry moment −R_b F_t).
    pub torque_bearing: f64,
    /// The film's Couette part of the journal's torque (the bearing gets its negative), weighted.
    pub couette: f64,
    /// The film's Poiseuille part −e F_η/2 (on journal and bearing alike), weighted.
    pub poiseuille: f64,
    /// Power dissipated \[W\] (≥ 0): the film's shear and pressure flow plus the dry friction's
    /// −F_t · slip, each by its share of the blend.
    pub power_loss: f64,
    /// The load the asperities carry \[N\] (rough surfaces only, [`super::mixed`]; else 0).
    pub asperity_force: f64,
}

impl Readings {
    /// The values in the order of [`READING_COLUMNS`].
    pub fn columns(&self) -> [f64; 7] {
        [self.film_thickness, self.torque_journal, self.torque_bearing, self.couette, self.poiseuille, self.power_loss, self.asperity_force]
    }
}

/// The angular speeds (bearing, journal) [rad/s] of a joint's two bodies from the velocities `qd`
/// (3 per body; the ground is at rest).
pub fn body_rates(joint: &ClearanceJoint, qd: &[f64]) -> (f64, f64) {
    let w = |b: Option<u32>| b.map_or(0.0, |i| qd[3 * i as usize + 2]);
    (w(joint.bearing), w(joint.journal))
}

impl ClearanceJoint {
    /// The readings of the joint in the kinematic state `k` under the force `f` the law gave
    /// there ([`ClearanceJoint::force`]), its bearing and journal turning at `w_bearing`,
    /// `w_journal` [rad/s], with the viscosity the joint's `memory` holds ([`super::Film::geometry_at`]).
    /// The film's torques come from [`film_friction`] at the ε the film
    /// force was evaluated at (min(ε, ε_max)) with the film force as recorded (small-ε scale
    /// included); the dry friction's from [`dry_friction_torque`].
    pub fn readings(&self, k: &JointKinematics, f: &JointForce, memory: &ImpactMemory, w_bearing: f64, w_journal: f64) -> Readings {
        // The friction force at the contact points: the dry law's by its weight, plus the
        // asperities' boundary friction on a rough joint (which has no band: the film in full).
        let friction = f.friction();
        let w_film = match &self.film {
            Some(film) if film.mixed.is_some() => 1.0,
            _ => 1.0 - f.w_dry,
        };
        let (dry_j, dry_b) = dry_friction_torque(self.journal_radius, self.bearing_radius, friction);
        let mut out = Readings {
            film_thickness: self.clearance - k.e,
            torque_journal: dry_j,
            torque_bearing: dry_b,
            couette: 0.0,
            poiseuille: 0.0,
            // The dry friction force opposes the slip (P5): −F_t·slip ≥ 0.
            power_loss: -friction * k.slip,
            asperity_force: f.asperity,
        };
        if let (Some(film), true) = (&self.film, w_film > 0.0) {
            let s = FilmState { eps: film_eps(k.eps, film.eps_max), eps_dot: k.eps_dot, wedge: k.wedge };
            let t = film_friction(&film.geometry_at(memory), s, w_journal, w_bearing, (f.film_xi, f.film_eta));
            out.couette = w_film * t.couette;
            out.poiseuille = w_film * t.poiseuille;
            out.torque_journal += w_film * t.journal;
            out.torque_bearing += w_film * t.bearing;
            out.power_loss += w_film * t.power_loss;
        }
        out
    }
}

/// The film columns a run stores per clearance joint and output time when it asks for them
/// (`outputs=["film"]`, [`ClearanceJoint::flow_and_peak`]).
pub const FILM_COLUMNS: [&str; 4] = ["side_leakage", "supply_flow", "peak_pressure", "peak_pressure_angle"];

impl ClearanceJoint {
    /// The share of the film in the joint's force (1 − w_dry in the transition band, 1 with
    /// roughness, 0 for a dry joint) and the small-eccentricity scale it was applied with.
    fn film_share(&self, k: &JointKinematics, f: &JointForce) -> f64 {
        match &self.film {
            None => 0.0,
            Some(film) => {
                let w = if film.mixed.is_some() { 1.0 } else { 1.0 - f.w_dry };
                w * crate::laws::transition::small_eccentricity_scale(k.eps, film.eps0, film.m)
            }
        }
    }

    /// The film's state as its force law saw it (ε at min(ε, ε_max)).
    fn film_state(&self, k: &JointKinematics) -> Option<FilmState> {
        self.film.as_ref().map(|film| FilmState { eps: film_eps(k.eps, film.eps_max), eps_dot: k.eps_dot, wedge: k.wedge })
    }

    /// Oil flow and peak pressure of the film in the state `k` under the force `f` the law gave
    /// there (docs/physics.md §4, "Oil flow and pressure"; [`crate::laws::film_field`]), weighted
    /// like the force by the film's share of the transition blend and the small-ε scale; all 0
    /// (angle NaN) for a dry joint or a prismatic one. `scratch`: the finite film's solver.
    pub fn flow_and_peak(&self, k: &JointKinematics, f: &JointForce, memory: &ImpactMemory, scratch: Option<&mut FiniteScratch>) -> FlowAndPeak {
        let (Some(film), Some(s), None) = (&self.film, self.film_state(k), self.guide_normal) else {
            return FlowAndPeak { peak_angle: f64::NAN, ..FlowAndPeak::default() };
        };
        let w = self.film_share(k, f);
        if w <= 0.0 {
            return FlowAndPeak { peak_angle: f64::NAN, ..FlowAndPeak::default() };
        }
        let r = if film.mass_conserving {
            let (j, _) = super::cavitation::readings(&film.geometry_at(memory), s, memory, false);
            FlowAndPeak { side_leakage: j.side_leakage, supply: j.supply, peak_pressure: j.peak_pressure, peak_angle: j.peak_angle }
        } else {
            flow_and_peak(film.model, &film.geometry_at(memory), s, scratch)
        };
        FlowAndPeak { side_leakage: w * r.side_leakage, supply: w * r.supply, peak_pressure: w * r.peak_pressure, peak_angle: r.peak_angle }
    }

    /// The film's pressure field in the state `k` (weighted as [`Self::flow_and_peak`]); `None`
    /// for a dry or prismatic joint.
    pub fn film_field(&self, k: &JointKinematics, f: &JointForce, memory: &ImpactMemory, scratch: Option<&mut FiniteScratch>) -> Option<FilmField> {
        let (Some(film), Some(s), None) = (&self.film, self.film_state(k), self.guide_normal) else { return None };
        let w = self.film_share(k, f);
        let mut field = if film.mass_conserving {
            super::cavitation::readings(&film.geometry_at(memory), s, memory, true).1?
        } else {
            film_field(film.model, &film.geometry_at(memory), s, scratch)
        };
        field.pressure.iter_mut().for_each(|p| *p *= w);
        Some(field)
    }

    /// The finite film's solver for [`Self::flow_and_peak`] and [`Self::film_field`] (`None` for
    /// the other films, which need none).
    pub fn film_scratch(&self) -> Option<FiniteScratch> {
        let film = self.film.as_ref()?;
        (film.model == crate::laws::FilmModel::Finite && !film.mass_conserving).then(|| FiniteScratch::new(&film.geometry, film.table.map_or(crate::laws::FilmSupply::default(), |t| t.supply)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::clearance::Film;
    use crate::constraints::{BodyKin, V2};
    use crate::laws::contact::{ContactLaw, NormalLaw};
    use crate::laws::film::{BearingGeometry, FilmModel};
    use crate::laws::friction::ModifiedCoulomb;

    fn joint(film: Option<FilmModel>) -> ClearanceJoint {
        let (r, c, l) = (0.02, 4e-5, 0.04);
        ClearanceJoint {
            name: "pin".into(),
            bearing: None,
            bearing_point: V2::new(0.0, 0.0),
            journal: Some(0),
            journal_point: V2::new(0.0, 0.0),
            journal_radius: r,
            bearing_radius: r + c,
            clearance: c,
            contact: ContactLaw { line: None, law: NormalLaw::Hertz, stiffness: 1e10, exponent: 1.5, restitution: 1.0, impact_speed_floor: 1e-4 },
            friction: ModifiedCoulomb { friction_coefficient: 0.1, v0: 1e-4, v1: 1e-3 },
            film: film.map(|model| Film {
                model,
                table: None,
                geometry: BearingGeometry { viscosity: 0.05, journal_radius: r, clearance: c, length: l },
                eps0: 2e-6,
                m: 0.5,
                e0: 0.05 * c,
                eps_max: 0.99,
                mixed: None,
                heat: None,
                mass_conserving: false,
            }),
            guide_normal: None,
            penetration_limit: c,
            wear: None,
        }
    }

    /// A journal at `e` [m] along x spinning at ω in a fixed bearing.
    fn state(j: &ClearanceJoint, e: f64, omega: f64) -> (JointKinematics, JointForce) {
        let kin = [BodyKin::new(&[e, 0.0, 0.0], &[0.0, 0.0, omega])];
        let k = j.kinematics(&kin);
        (k, j.force(&k, &ImpactMemory::default()))
    }

    #[test]
    fn petroff_for_a_centred_journal_and_dry_moments_in_contact() {
        let omega = 100.0;
        for model in [FilmModel::LongBearing, FilmModel::ShortBearing, FilmModel::Finite] {
            let j = joint(Some(model));
            let (k, f) = state(&j, 0.0, omega);
            let r = j.readings(&k, &f, &ImpactMemory::default(), 0.0, omega);
            let g = j.film.unwrap().geometry;
            let petroff = crate::laws::film_friction::petroff_torque(&g, omega);
            assert!((r.torque_journal / -petroff - 1.0).abs() < 1e-12, "{model:?}: {} vs {petroff}", r.torque_journal);
            assert!((r.power_loss / (petroff * omega) - 1.0).abs() < 1e-12);
            assert_eq!(r.film_thickness, j.clearance);
        }
        // Beyond the band: the dry law alone, its moment R_j F_t and power −F_t·slip.
        let j = joint(Some(FilmModel::ShortBearing));
        let e = j.clearance * 1.1;
        let (k, f) = state(&j, e, omega);
        assert_eq!(f.w_dry, 1.0);
        let r = j.readings(&k, &f, &ImpactMemory::default(), 0.0, omega);
        assert!((r.torque_journal - j.journal_radius * f.tangential).abs() < 1e-12 * f.normal);
        assert!((r.torque_bearing + j.bearing_radius * f.tangential).abs() < 1e-12 * f.normal);
        assert!((r.power_loss + f.tangential * k.slip).abs() < 1e-12 * r.power_loss && r.power_loss > 0.0);
        assert!((r.film_thickness + 0.1 * j.clearance).abs() < 1e-18);
        // A dry joint in free flight reads its gap and no friction.
        let j = joint(None);
        let (k, f) = state(&j, 0.5 * j.clearance, omega);
        let r = j.readings(&k, &f, &ImpactMemory::default(), 0.0, omega);
        assert_eq!((r.torque_journal, r.power_loss), (0.0, 0.0));
        assert!((r.film_thickness - 0.5 * j.clearance).abs() < 1e-18);
    }
}
