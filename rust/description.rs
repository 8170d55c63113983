//! The plain-data description of a mechanism, as the Python layer or a scene file gives it
//! (through serde), and its ideal counterpart ([`MechanismDesc::idealized`]). Checked and
//! compiled by [`crate::model::Model::compile`]; nothing here is used in the hot path.

use crate::laws::contact::NormalLaw;
use crate::laws::film::FilmModel;
use crate::laws::geometry::{FilmCavitation, FilmSupply};

/// A rigid body: reference point at the centroid (docs/physics.md §1, P19).
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[derive(Debug, Clone, PartialEq)]
pub struct BodyDesc {
    pub name: String,
    /// Mass \[kg\] (> 0).
    pub mass: f64,
    /// Moment of inertia about the centroid [kg m²] (> 0).
    pub inertia: f64,
    /// Approximate centroid position \[m\] at t = 0, the drivers' reference time (refined by the
    /// kinematic assembly; a run from t0 ≠ 0 follows the drivers on from there).
    pub position: [f64; 2],
    /// Approximate angle \[rad\] at t = 0.
    #[cfg_attr(feature = "serde", serde(default))]
    pub angle: f64,
    /// Optional initial velocity guess (ẋ, ẏ, θ̇) [m/s, rad/s]; projected onto the constraints.
    #[cfg_attr(feature = "serde", serde(default))]
    pub velocity: [f64; 3],
}

/// `None` is the ground (the fixed frame); points on ground are global coordinates.
pub type BodyRef = Option<usize>;

/// An ideal joint: a set of holonomic constraints (docs/physics.md §1).
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
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
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(tag = "kind", rename_all = "snake_case"))]
#[derive(Debug, Clone, PartialEq)]
pub enum AngleLaw {
    /// θ = angle0 + ω t.
    ConstantSpeed { angle0: f64, omega: f64 },
    /// θ = Σ c_k t^k (coefficients in increasing power).
    Polynomial { coefficients: Vec<f64> },
    /// θ given at sample times, interpolated by a natural cubic spline (C² so that θ̈ exists).
    Samples { times: Vec<f64>, angles: Vec<f64> },
    /// θ = offset + amplitude · cos(omega · t + phase) (\[rad\], ω \[rad/s\], phase \[rad\]).
    Harmonic(Harmonic),
}

/// offset + amplitude · cos(omega · t + phase): a smooth periodic load or motion
/// (`clearsim.Harmonic`), omega \[rad/s\] > 0, phase \[rad\], amplitude and offset in the
/// unit of what it gives (N, N m, rad).
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Harmonic {
    pub amplitude: f64,
    pub omega: f64,
    #[cfg_attr(feature = "serde", serde(default))]
    pub phase: f64,
    #[cfg_attr(feature = "serde", serde(default))]
    pub offset: f64,
}

impl Harmonic {
    /// (value, first, second time derivative) at t.
    #[inline]
    pub fn eval(&self, t: f64) -> (f64, f64, f64) {
        let (s, c) = (self.omega * t + self.phase).sin_cos();
        let a = self.amplitude;
        (self.offset + a * c, -a * self.omega * s, -a * self.omega * self.omega * c)
    }

    /// The value at t.
    #[inline]
    pub fn value(&self, t: f64) -> f64 {
        self.offset + self.amplitude * (self.omega * t + self.phase).cos()
    }
}

/// A driving constraint on a body's angle.
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[derive(Debug, Clone, PartialEq)]
pub struct DriverDesc {
    pub name: String,
    pub body: usize,
    pub law: AngleLaw,
}

/// Parameters of a dry clearance joint (docs/physics.md §3); a missing field takes [`DryDesc::steel`]'s value.
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(default))]
#[derive(Debug, Clone, PartialEq)]
pub struct DryDesc {
    pub normal_law: NormalLaw,
    /// Young's modulus E of the bearing \[Pa\] and Poisson's ratio ν [-] (the names of Python's
    /// `Dry`, as everywhere from Python to errors, paths and scenes).
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    /// The journal's E \[Pa\] and ν [-] (Python's `Dry` writes the bearing's unless given).
    pub journal_youngs_modulus: f64,
    pub journal_poisson_ratio: f64,
    /// Coefficient of restitution c_e in (0, 1].
    pub restitution: f64,
    /// Exponent n of δ^n (1.5 for Hertzian contact).
    pub exponent: f64,
    /// Contact stiffness K [N/m^n]; `None` computes it from the materials ([`StiffnessForm`]).
    pub stiffness: Option<f64>,
    /// How K follows from the materials when not given (docs/physics.md §3).
    pub stiffness_form: StiffnessForm,
    /// Pin length L \[m\] of `stiffness_form = "cylindrical"` (a line contact); `None` otherwise.
    pub length: Option<f64>,
    /// Sliding friction coefficient c_f (≥ 0).
    pub friction: f64,
    /// Modified-Coulomb speed limits v0 < v1 [m/s].
    pub v0: f64,
    pub v1: f64,
    /// Floor for the impact speed δ̇⁽⁻⁾ [m/s] (guards resting contact).
    pub impact_speed_floor: f64,
    /// Archard wear of the contact (docs/physics.md §12); `None`: no wear is computed.
    pub wear: Option<WearDesc>,
}

/// How a dry contact's stiffness follows from the materials (docs/physics.md §3).
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum StiffnessForm {
    /// A point contact of effective radius R_b R_j / (R_b − R_j), journal inside bearing (P4 with
    /// the erratum).
    #[default]
    Internal,
    /// The paper's printed P4 (R_b + R_j in the denominator).
    PaperPrinted,
    /// A pin of `length` L in its bore as a line contact (Johnson's law for cylinders).
    Cylindrical,
}

/// Archard's wear law: worn volume = coefficient × normal force × sliding distance / hardness.
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[derive(Debug, Clone, PartialEq)]
pub struct WearDesc {
    /// Dimensionless wear coefficient k.
    pub coefficient: f64,
    /// Hardness H of the softer surface \[Pa\].
    pub hardness: f64,
    /// Bearing (contact) length L \[m\] over which the volume spreads.
    pub length: f64,
    /// Feed the worn depth back into the contact geometry (default false).
    #[cfg_attr(feature = "serde", serde(default))]
    pub feedback: bool,
    /// Depth \[m\] already worn at the start of the run, in the 1° bins of
    /// [`crate::clearance::wear::WEAR_BINS`] around the bearing and around the journal (each body's frame);
    /// empty: unworn. Lets a run start from the worn state of an earlier one (reliability over life).
    #[cfg_attr(feature = "serde", serde(default))]
    pub initial_bearing: Vec<f64>,
    #[cfg_attr(feature = "serde", serde(default))]
    pub initial_journal: Vec<f64>,
}

/// Parameters of a lubricated clearance joint (docs/physics.md §4).
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[derive(Debug, Clone, PartialEq)]
pub struct LubricatedDesc {
    #[cfg_attr(feature = "serde", serde(default))]
    pub film: FilmModel,
    /// Where the finite film's pressure is ambient (`film = "finite"` only; docs/physics.md §4):
    /// on the line of the widest gap (default) or nowhere (a periodic film).
    #[cfg_attr(feature = "serde", serde(default))]
    pub supply: FilmSupply,
    /// How the finite film ruptures: the Reynolds condition (default, its tables) or
    /// mass-conserving (`"jfo"`, the film content carried from step to step; docs/physics.md §4).
    #[cfg_attr(feature = "serde", serde(default))]
    pub cavitation: FilmCavitation,
    /// Dynamic viscosity: a constant μ [Pa s] or Vogel's law of the oil temperature (with `thermal`).
    pub viscosity: ViscosityDesc,
    /// Bearing length L \[m\].
    pub length: f64,
    /// Small-eccentricity threshold ε0 and exponent m (P15–P16); default 2e-6 and 0.5.
    #[cfg_attr(feature = "serde", serde(default = "default_eps0"))]
    pub eps0: f64,
    #[cfg_attr(feature = "serde", serde(default = "default_m"))]
    pub m: f64,
    /// Transition band width e0 \[m\] (P18); `None`: 5 % of the clearance.
    #[cfg_attr(feature = "serde", serde(default))]
    pub e0: Option<f64>,
    /// The film is evaluated at min(ε, ε_max) inside the transition band; default 0.99.
    #[cfg_attr(feature = "serde", serde(default = "default_eps_max"))]
    pub eps_max: f64,
    /// The dry law used beyond e = c (default: [`DryDesc::steel`]).
    #[cfg_attr(feature = "serde", serde(default))]
    pub dry: DryDesc,
    /// Composite RMS roughness σ \[m\] of the two surfaces (docs/physics.md §4, roughness): the
    /// Greenwood–Tripp asperity load where the film is thinner than 4σ replaces the transition
    /// band; `None`: smooth surfaces and the band (P18).
    #[cfg_attr(feature = "serde", serde(default))]
    pub roughness: Option<f64>,
    /// Boundary friction coefficient μ_b on the asperity load (with `roughness`); `None`: the dry
    /// law's friction coefficient.
    #[cfg_attr(feature = "serde", serde(default))]
    pub boundary_friction: Option<f64>,
    /// Slip speed [m/s] over which the boundary friction ramps up from 0 to μ_b (with
    /// `roughness`; its own regularisation, not the dry law's v0, v1); `None`:
    /// [`crate::clearance::mixed::BOUNDARY_SLIP`].
    #[cfg_attr(feature = "serde", serde(default))]
    pub boundary_slip: Option<f64>,
    /// The oil temperature's heat balance (docs/physics.md §4, *Heat*); `None`: no temperature.
    #[cfg_attr(feature = "serde", serde(default))]
    pub thermal: Option<ThermalDesc>,
}

/// The viscosity of a lubricated joint: `0.4` or `{vogel = [a, b, c]}`.
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(untagged))]
#[derive(Debug, Clone, PartialEq)]
pub enum ViscosityDesc {
    /// μ [Pa s].
    Constant(f64),
    /// Vogel's law μ = a exp(b/(T − c)): a \[Pa s\], b and c \[K\] ([`crate::laws::viscosity::Vogel`]).
    Vogel { vogel: [f64; 3] },
}

/// The lumped heat balance C dT/dt = P_loss − hA (T − T_ambient) of a lubricated joint.
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThermalDesc {
    /// Ambient temperature \[K\].
    pub ambient: f64,
    /// Heat capacity C \[J/K\].
    pub heat_capacity: f64,
    /// Heat transfer hA \[W/K\].
    pub heat_transfer: f64,
    /// Oil temperature at the start \[K\]; `None`: the ambient.
    #[cfg_attr(feature = "serde", serde(default))]
    pub initial: Option<f64>,
}

#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(tag = "kind", rename_all = "snake_case"))]
#[derive(Debug, Clone, PartialEq)]
pub enum ClearanceModelDesc {
    Dry(DryDesc),
    Lubricated(LubricatedDesc),
}

/// A revolute joint with radial clearance: bearing (hole) on one body, journal (pin) on another.
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[derive(Debug, Clone, PartialEq)]
pub struct ClearanceJointDesc {
    pub name: String,
    pub bearing_body: BodyRef,
    pub bearing_point: [f64; 2],
    pub journal_body: BodyRef,
    pub journal_point: [f64; 2],
    /// Journal radius R_j \[m\]; bearing radius R_b = R_j + clearance.
    pub journal_radius: f64,
    /// Radial clearance c = R_b − R_j \[m\].
    pub clearance: f64,
    pub model: ClearanceModelDesc,
    /// Initial eccentricity vector e = r_Pj − r_Pi \[m\] (global frame); zero is centred.
    #[cfg_attr(feature = "serde", serde(default))]
    pub initial_eccentricity: [f64; 2],
}

/// A prismatic (translational) joint with clearance (docs/physics.md §11): a slider of length
/// `slider_length` centred on the slider body's centroid moves in a guide through `guide_point`
/// of the guide body along `axis` (guide frame), with a total lateral play `clearance`. Its two
/// ends (rounded with `corner_radius`) contact either guide surface with the dry law.
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[derive(Debug, Clone, PartialEq)]
pub struct PrismaticClearanceDesc {
    pub name: String,
    pub guide_body: BodyRef,
    pub guide_point: [f64; 2],
    pub slider_body: usize,
    pub axis: [f64; 2],
    /// Guide gap minus slider thickness \[m\] (the slider can move ±clearance/2 sideways).
    pub clearance: f64,
    /// Distance between the slider's two contact ends \[m\].
    pub slider_length: f64,
    /// Radius of the slider's rounded corners \[m\]: the Hertz sphere-on-plane contact stiffness
    /// uses it when the dry law gives no stiffness.
    #[cfg_attr(feature = "serde", serde(default = "default_corner_radius"))]
    pub corner_radius: f64,
    #[cfg_attr(feature = "serde", serde(default))]
    pub model: DryDesc,
}

#[cfg(feature = "serde")]
fn default_corner_radius() -> f64 {
    1e-3
}

/// What a [`Table`] is a function of.
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(tag = "kind", rename_all = "snake_case"))]
#[derive(Debug, Clone, PartialEq)]
pub enum TableArgument {
    /// Time t \[s\].
    Time,
    /// The absolute angle θ \[rad\] of a body (a driven crank: the driver's angle).
    Angle { body: usize },
}

/// A tabulated function y(x) (x strictly increasing), held at its end values outside
/// [x₀, x_last]; with a `period` the argument is first wrapped into [x₀, x₀ + period) and the
/// last point is joined to the first one period on (rust/table.rs).
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    #[cfg_attr(feature = "serde", serde(default))]
    pub period: Option<f64>,
    /// Between the points: straight lines (default) or a C² cubic spline.
    #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "Interpolation::is_linear"))]
    pub interpolation: Interpolation,
}

/// How a [`Table`] runs between its points (rust/table.rs).
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Interpolation {
    /// Straight lines: every point is a corner, and a time table's corners end integration steps.
    #[default]
    Linear,
    /// A C² cubic spline (not-a-knot; periodic with a period): no corners inside the table.
    Cubic,
}

impl Interpolation {
    pub fn is_linear(&self) -> bool {
        *self == Interpolation::Linear
    }
}

/// A scalar load: constant, or a table of time or of a body's angle.
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(tag = "kind", rename_all = "snake_case"))]
#[derive(Debug, Clone, PartialEq)]
pub enum Profile {
    Constant { value: f64 },
    Table { argument: TableArgument, table: Table },
    /// offset + amplitude · cos(omega · t + phase), in time.
    Harmonic(Harmonic),
}

/// The frame a force's direction is given in.
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Frame {
    #[default]
    Global,
    Body,
}

/// A force element or load (docs/physics.md §10). Body references: `None` is the ground.
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(tag = "kind", rename_all = "snake_case"))]
#[derive(Debug, Clone, PartialEq)]
pub enum ForceDesc {
    /// Translational spring-damper between two body points: tension
    /// F = k (ℓ − ℓ₀) + c ℓ̇, or F = table(ℓ − ℓ₀) + c ℓ̇ \[N\].
    SpringDamper {
        name: String,
        body_a: BodyRef,
        point_a: [f64; 2],
        body_b: BodyRef,
        point_b: [f64; 2],
        /// k [N/m].
        #[cfg_attr(feature = "serde", serde(default))]
        stiffness: f64,
        /// c [N s/m].
        #[cfg_attr(feature = "serde", serde(default))]
        damping: f64,
        /// ℓ₀ \[m\]; `None`: the assembled distance.
        #[cfg_attr(feature = "serde", serde(default))]
        free_length: Option<f64>,
        /// Force–deflection table (deflection \[m\] → tension \[N\]) used instead of k.
        #[cfg_attr(feature = "serde", serde(default))]
        force_table: Option<Table>,
    },
    /// Rotational spring-damper: torque on b (and −torque on a)
    /// T = −k (θ_b − θ_a − φ₀) − c (θ̇_b − θ̇_a) [N m].
    RotationalSpringDamper {
        name: String,
        body_a: BodyRef,
        body_b: BodyRef,
        /// k [N m/rad].
        #[cfg_attr(feature = "serde", serde(default))]
        stiffness: f64,
        /// c [N m s/rad].
        #[cfg_attr(feature = "serde", serde(default))]
        damping: f64,
        /// φ₀ \[rad\], the unloaded relative angle; `None`: the assembled one.
        #[cfg_attr(feature = "serde", serde(default))]
        angle0: Option<f64>,
    },
    /// A force (F_x, F_y) \[N\] at a body point, its components in the global or the body frame.
    Force {
        name: String,
        body: usize,
        point: [f64; 2],
        #[cfg_attr(feature = "serde", serde(default))]
        frame: Frame,
        fx: Profile,
        fy: Profile,
    },
    /// A torque [N m] on `body` (counter-clockwise positive), reacted on `reaction` if given.
    Torque {
        name: String,
        body: usize,
        #[cfg_attr(feature = "serde", serde(default))]
        reaction: BodyRef,
        magnitude: Profile,
    },
    /// A motor with a linear speed–torque line on `body`, its stator on `reaction` (ground if
    /// `None`): T = T_stall (1 − ω/ω₀) · sign(ω₀), ω the relative speed [rad/s].
    Motor {
        name: String,
        body: usize,
        #[cfg_attr(feature = "serde", serde(default))]
        reaction: BodyRef,
        /// Stall torque T_stall [N m] (> 0).
        stall_torque: f64,
        /// No-load speed ω₀ [rad/s] (≠ 0; its sign is the direction of rotation).
        no_load_speed: f64,
    },
}

impl ForceDesc {
    pub fn name(&self) -> &str {
        match self {
            ForceDesc::SpringDamper { name, .. }
            | ForceDesc::RotationalSpringDamper { name, .. }
            | ForceDesc::Force { name, .. }
            | ForceDesc::Torque { name, .. }
            | ForceDesc::Motor { name, .. } => name,
        }
    }
}

impl JointDesc {
    pub fn name(&self) -> &str {
        match self {
            JointDesc::Revolute { name, .. } | JointDesc::Prismatic { name, .. } => name,
        }
    }
}

/// Everything needed to compile a model.
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(default))]
#[derive(Debug, Clone, PartialEq)]
pub struct MechanismDesc {
    pub bodies: Vec<BodyDesc>,
    pub joints: Vec<JointDesc>,
    pub drivers: Vec<DriverDesc>,
    pub clearance_joints: Vec<ClearanceJointDesc>,
    /// Prismatic joints with clearance.
    pub prismatic_clearance_joints: Vec<PrismaticClearanceDesc>,
    /// Force elements and loads.
    pub forces: Vec<ForceDesc>,
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
            prismatic_clearance_joints: vec![],
            forces: vec![],
            gravity: [0.0, -9.81],
            baumgarte: [50.0, 50.0],
        }
    }
}

impl MechanismDesc {
    /// The ideal mechanism (docs/physics.md §5): every revolute clearance joint replaced by a
    /// revolute joint between its bearing and journal points, every prismatic clearance joint
    /// by a prismatic joint along its guide; the clearance joints' laws are dropped.
    ///
    /// Each new joint goes to its place in name order (after any equal name), so that joints
    /// sorted by name (as the Python layer writes every description, so that no answer depends
    /// on the order elements were defined in) stay sorted: the ideal mechanism's equations then
    /// come in the same order as if it had been built ideal.
    pub fn idealized(&self) -> MechanismDesc {
        let mut d = self.clone();
        let insert = |joints: &mut Vec<JointDesc>, joint: JointDesc| {
            let k = joints.partition_point(|j| j.name() <= joint.name());
            joints.insert(k, joint);
        };
        for c in d.clearance_joints.drain(..) {
            let joint = JointDesc::Revolute { name: c.name, body_a: c.bearing_body, point_a: c.bearing_point, body_b: c.journal_body, point_b: c.journal_point };
            insert(&mut d.joints, joint);
        }
        for p in d.prismatic_clearance_joints.drain(..) {
            let joint = JointDesc::Prismatic { name: p.name, body_a: p.guide_body, point_a: p.guide_point, axis: p.axis, body_b: p.slider_body, point_b: [0.0, 0.0] };
            insert(&mut d.joints, joint);
        }
        d
    }
}

#[cfg(feature = "serde")]
fn default_eps0() -> f64 {
    2e-6
}
#[cfg(feature = "serde")]
fn default_m() -> f64 {
    0.5
}
#[cfg(feature = "serde")]
fn default_eps_max() -> f64 {
    0.99
}

impl Default for DryDesc {
    fn default() -> Self {
        DryDesc::steel()
    }
}

impl DryDesc {
    /// The steel-on-steel defaults of docs/physics.md §7 (Lankarani–Nikravesh, c_e = 0.9, c_f = 0.1).
    pub fn steel() -> Self {
        DryDesc {
            normal_law: NormalLaw::LankaraniNikravesh,
            youngs_modulus: 207e9,
            journal_youngs_modulus: 207e9,
            poisson_ratio: 0.3,
            journal_poisson_ratio: 0.3,
            restitution: 0.9,
            exponent: 1.5,
            stiffness: None,
            stiffness_form: StiffnessForm::Internal,
            length: None,
            friction: 0.1,
            v0: 1e-4,
            v1: 1e-2,
            impact_speed_floor: 1e-3,
            wear: None,
        }
    }
}

/// The element lists of a description and what one element is called in messages.
pub const ELEMENTS: [(&str, &str); 6] = [
    ("bodies", "body"),
    ("joints", "joint"),
    ("drivers", "driver"),
    ("clearance_joints", "clearance joint"),
    ("prismatic_clearance_joints", "clearance joint"),
    ("forces", "force"),
];

/// Read a description from JSON (what the Python layer and scene files hand over; bodies and
/// drivers referred to by name or by index). A bad
/// entry is reported as an [`crate::error::Error::InvalidInput`] naming the element and the
/// field: `body 'crank'.mass`, `driver 'drive1'.law`.
#[cfg(feature = "serde")]
pub fn from_json(text: &str) -> crate::error::Result<MechanismDesc> {
    use crate::error::Error;
    let v: serde_json::Value = serde_json::from_str(text).map_err(|e| Error::invalid("description", "(JSON)", e.to_string()))?;
    from_value(v)
}

/// [`from_json`] for a parsed JSON value: the names by which elements refer to one another
/// resolved ([`crate::names::resolve`]), then read through serde.
#[cfg(feature = "serde")]
pub fn from_value(mut v: serde_json::Value) -> crate::error::Result<MechanismDesc> {
    use crate::error::Error;
    crate::names::resolve(&mut v)?;
    serde_path_to_error::deserialize::<_, MechanismDesc>(&v).map_err(|e| {
        let why = e.inner().to_string();
        // Inside an internally tagged enum (a joint's model, a force) serde's path stops at the
        // enum: an unknown name is then looked up by its value to name its field (`model.film`).
        let variant = why.strip_prefix("unknown variant `").and_then(|r| r.split('`').next());
        let (field, value) = name_path(&v, e.path(), variant);
        Error::invalid(field, value, why)
    })
}

/// The keys (depth first) leading from `v` to a string value equal to `s`, and that value.
#[cfg(feature = "serde")]
fn find_string<'a>(v: &'a serde_json::Value, s: &str) -> Option<(Vec<&'a str>, &'a serde_json::Value)> {
    let map = v.as_object()?;
    if let Some((k, x)) = map.iter().find(|(k, x)| *k != "kind" && x.as_str() == Some(s)) {
        return Some((vec![k.as_str()], x));
    }
    map.iter().find_map(|(k, x)| {
        let (mut keys, found) = find_string(x, s)?;
        keys.insert(0, k.as_str());
        Some((keys, found))
    })
}

/// The field a deserialisation error points at, named the way validation names it, and the
/// value found there (shortened).
#[cfg(feature = "serde")]
fn name_path(root: &serde_json::Value, path: &serde_path_to_error::Path, variant: Option<&str>) -> (String, String) {
    use serde_path_to_error::Segment;
    let mut field = String::new();
    let mut at = Some(root);
    let mut list: Option<&str> = None;
    for seg in path.iter() {
        match seg {
            Segment::Seq { index } => {
                let item = at.and_then(|v| v.get(*index));
                let named = list.and_then(|l| ELEMENTS.iter().find(|(k, _)| *k == l)).and_then(|(_, what)| {
                    item.and_then(|i| i.get("name")).and_then(|n| n.as_str()).map(|n| format!("{what} '{n}'"))
                });
                match named {
                    Some(n) if field == list.unwrap_or_default() => field = n,
                    _ => field.push_str(&format!("[{index}]")),
                }
                at = item;
            }
            Segment::Map { key } => {
                if !field.is_empty() {
                    field.push('.');
                }
                field.push_str(key);
                list = if at.is_some_and(|a| std::ptr::eq(a, root)) { Some(key.as_str()) } else { None };
                at = at.and_then(|v| v.get(key.as_str()));
            }
            Segment::Enum { .. } | Segment::Unknown => {}
        }
    }
    if let (Some(name), Some(here)) = (variant, at) {
        if let Some((keys, found)) = find_string(here, name) {
            for k in keys {
                field.push('.');
                field.push_str(k);
            }
            at = Some(found);
        }
    }
    if field.is_empty() {
        field.push_str("description");
    }
    // A string quoted as Python writes it ('hooke'), as every other message does.
    let mut value = at.map_or_else(|| "(missing)".to_string(), |v| v.as_str().map_or_else(|| v.to_string(), |s| format!("'{s}'")));
    if value.chars().count() > 80 {
        value = value.chars().take(77).collect::<String>() + "…";
    }
    (field, value)
}
