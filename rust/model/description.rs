//! The plain-data description of a mechanism, as the Python layer or a scene file gives it.
//! Validated by [`super::Model::compile`]; nothing here is used in the hot path.

use crate::laws::contact::NormalLaw;
use crate::laws::film::FilmModel;

/// A rigid body: reference point at the centroid (spec §1, P19).
#[cfg_attr(feature = "serde", derive(serde::Deserialize))]
#[derive(Debug, Clone, PartialEq)]
pub struct BodyDesc {
    pub name: String,
    /// Mass [kg] (> 0).
    pub mass: f64,
    /// Moment of inertia about the centroid [kg m²] (> 0).
    pub inertia: f64,
    /// Approximate centroid position [m] at t0 (refined by the kinematic assembly).
    pub position: [f64; 2],
    /// Approximate angle [rad] at t0.
    #[cfg_attr(feature = "serde", serde(default))]
    pub angle: f64,
    /// Optional initial velocity guess (ẋ, ẏ, θ̇) [m/s, rad/s]; projected onto the constraints.
    #[cfg_attr(feature = "serde", serde(default))]
    pub velocity: [f64; 3],
}

/// `None` is the ground (the fixed frame); points on ground are global coordinates.
pub type BodyRef = Option<usize>;

/// An ideal joint: a set of holonomic constraints (spec §1).
#[cfg_attr(feature = "serde", derive(serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(tag = "kind", rename_all = "snake_case"))]
#[derive(Debug, Clone, PartialEq)]
pub enum JointDesc {
    /// Revolute joint: point `point_a` of body a coincides with `point_b` of body b (2 equations).
    Revolute { name: String, body_a: BodyRef, point_a: [f64; 2], body_b: BodyRef, point_b: [f64; 2] },
    /// Prismatic (translational) joint: point `point_b` of body b slides along the line through
    /// `point_a` of body a with direction `axis` (in body a's frame), and the relative angle stays
    /// at its initial value (2 equations).
    Prismatic { name: String, body_a: BodyRef, point_a: [f64; 2], axis: [f64; 2], body_b: usize, point_b: [f64; 2] },
}

/// A prescribed angle law θ(t) for a driving constraint `θ_body − f(t) = 0`.
#[cfg_attr(feature = "serde", derive(serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(tag = "kind", rename_all = "snake_case"))]
#[derive(Debug, Clone, PartialEq)]
pub enum AngleLaw {
    /// θ = angle0 + ω t.
    ConstantSpeed { angle0: f64, omega: f64 },
    /// θ = Σ c_k t^k (coefficients in increasing power).
    Polynomial { coefficients: Vec<f64> },
    /// θ given at sample times, interpolated by a natural cubic spline (C² so that θ̈ exists).
    Samples { times: Vec<f64>, angles: Vec<f64> },
}

/// A driving constraint on a body's angle.
#[cfg_attr(feature = "serde", derive(serde::Deserialize))]
#[derive(Debug, Clone, PartialEq)]
pub struct DriverDesc {
    pub name: String,
    pub body: usize,
    pub law: AngleLaw,
}

/// Parameters of a dry clearance joint (spec §3).
#[cfg_attr(feature = "serde", derive(serde::Deserialize))]
#[derive(Debug, Clone, PartialEq)]
pub struct DryDesc {
    pub normal_law: NormalLaw,
    /// Young's modulus of the bearing / journal [Pa].
    pub youngs_bearing: f64,
    pub youngs_journal: f64,
    /// Poisson's ratio of the bearing / journal [-].
    pub poisson_bearing: f64,
    pub poisson_journal: f64,
    /// Coefficient of restitution c_e in (0, 1].
    pub restitution: f64,
    /// Exponent n of δ^n (1.5 for Hertzian contact).
    pub exponent: f64,
    /// Contact stiffness K [N/m^n]; `None` computes it from the materials (P4, internal contact).
    pub stiffness: Option<f64>,
    /// Use the paper's printed stiffness (R_b + R_j in the denominator of P4) instead.
    pub stiffness_paper_printed: bool,
    /// Sliding friction coefficient c_f (≥ 0).
    pub friction: f64,
    /// Modified-Coulomb speed limits v0 < v1 [m/s].
    pub v0: f64,
    pub v1: f64,
    /// Floor for the impact speed δ̇⁽⁻⁾ [m/s] (guards resting contact).
    pub impact_speed_floor: f64,
}

/// Parameters of a lubricated clearance joint (spec §4).
#[cfg_attr(feature = "serde", derive(serde::Deserialize))]
#[derive(Debug, Clone, PartialEq)]
pub struct LubricatedDesc {
    pub film: FilmModel,
    /// Dynamic viscosity μ [Pa s].
    pub viscosity: f64,
    /// Bearing length L [m].
    pub length: f64,
    /// Small-eccentricity threshold ε0 and exponent m (P15–P16).
    pub eps0: f64,
    pub m: f64,
    /// Transition band width e0 [m] (P18).
    pub e0: f64,
    /// The film is evaluated at min(ε, ε_max) inside the transition band.
    pub eps_max: f64,
    /// The dry law used beyond e = c.
    pub dry: DryDesc,
}

#[cfg_attr(feature = "serde", derive(serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(tag = "kind", rename_all = "snake_case"))]
#[derive(Debug, Clone, PartialEq)]
pub enum ClearanceModelDesc {
    Dry(DryDesc),
    Lubricated(LubricatedDesc),
}

/// A revolute joint with radial clearance: bearing (hole) on one body, journal (pin) on another.
#[cfg_attr(feature = "serde", derive(serde::Deserialize))]
#[derive(Debug, Clone, PartialEq)]
pub struct ClearanceJointDesc {
    pub name: String,
    pub bearing_body: BodyRef,
    pub bearing_point: [f64; 2],
    pub journal_body: BodyRef,
    pub journal_point: [f64; 2],
    /// Journal radius R_j [m]; bearing radius R_b = R_j + clearance.
    pub journal_radius: f64,
    /// Radial clearance c = R_b − R_j [m].
    pub clearance: f64,
    pub model: ClearanceModelDesc,
    /// Initial eccentricity vector e = r_Pj − r_Pi [m] (global frame); zero is centred.
    #[cfg_attr(feature = "serde", serde(default))]
    pub initial_eccentricity: [f64; 2],
}

/// Everything needed to compile a model.
#[cfg_attr(feature = "serde", derive(serde::Deserialize))]
#[derive(Debug, Clone, PartialEq)]
pub struct MechanismDesc {
    pub bodies: Vec<BodyDesc>,
    pub joints: Vec<JointDesc>,
    pub drivers: Vec<DriverDesc>,
    pub clearance_joints: Vec<ClearanceJointDesc>,
    /// Gravity [m/s²].
    pub gravity: [f64; 2],
    /// Baumgarte coefficients α, β (P26); default 50, 50.
    pub baumgarte: [f64; 2],
}

impl Default for MechanismDesc {
    fn default() -> Self {
        MechanismDesc {
            bodies: vec![],
            joints: vec![],
            drivers: vec![],
            clearance_joints: vec![],
            gravity: [0.0, -9.81],
            baumgarte: [50.0, 50.0],
        }
    }
}

impl DryDesc {
    /// The spec's §7 steel-on-steel defaults (Lankarani–Nikravesh, c_e = 0.9, c_f = 0.1).
    pub fn steel() -> Self {
        DryDesc {
            normal_law: NormalLaw::LankaraniNikravesh,
            youngs_bearing: 207e9,
            youngs_journal: 207e9,
            poisson_bearing: 0.3,
            poisson_journal: 0.3,
            restitution: 0.9,
            exponent: 1.5,
            stiffness: None,
            stiffness_paper_printed: false,
            friction: 0.1,
            v0: 1e-4,
            v1: 1e-2,
            impact_speed_floor: 1e-3,
        }
    }
}
