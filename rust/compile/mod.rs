//! From what the user gives to what runs: a description by names (`crate::names`: resolved into
//! indices) read into a [`MechanismDesc`], checked once (`validate.rs`: every bad value named
//! with its field; `element.rs`: one element alone, as it is added), compiled into a [`Model`]
//! (flat arrays and enums, only the parts the scene uses) and assembled at t = 0 once
//! ([`Model::start`]). What is valid but looks like a mistake is `plausibility.rs`'s. The run
//! settings are checked in [`crate::settings`].

#[cfg(feature = "serde")]
mod element;
pub mod plausibility;
mod validate;

#[cfg(feature = "serde")]
pub use element::check_element;
pub(crate) use crate::text::{num, quoted};
pub use validate::{check_finite_bearing_ratio, FINITE_BEARING_L_OVER_D, MAX_FILM_CLEARANCE_RATIO};

use crate::assembly::pose_at_zero;
use crate::clearance::{max_penetration, ClearanceJoint, Film};
use crate::constraints::{BodyKin, CompiledAngleLaw, Constraint, V2};
use crate::description::*;
use crate::error::{Error, Result};
use crate::forces::{ForceElement, Magnitude};
use crate::table::Tabulated;
use crate::laws::contact::{stiffness_internal, stiffness_paper_printed, ContactLaw};
use crate::laws::film::BearingGeometry;
use crate::laws::friction::ModifiedCoulomb;
use crate::model::Model;

/// The transition band width e0 as a fraction of the clearance when a lubricated joint does
/// not give one (P18).
pub const DEFAULT_TRANSITION_WIDTH: f64 = 0.05;

impl Model {
    /// Validate a description and compile it.
    pub fn compile(desc: &MechanismDesc) -> Result<Model> {
        validate::validate(desc)?;
        let nb = desc.bodies.len();
        let mut mass = Vec::with_capacity(3 * nb);
        let mut q_guess = Vec::with_capacity(3 * nb);
        let mut qd_guess = Vec::with_capacity(3 * nb);
        for b in &desc.bodies {
            mass.extend([b.mass, b.mass, b.inertia]);
            q_guess.extend([b.position[0], b.position[1], b.angle]);
            qd_guess.extend(b.velocity);
        }
        let idx = |b: &BodyRef| b.map(|i| i as u32);
        let mut constraints = Vec::new();
        for j in &desc.joints {
            constraints.push(match j {
                JointDesc::Revolute { body_a, point_a, body_b, point_b, .. } => Constraint::Revolute {
                    a: idx(body_a),
                    sa: (*point_a).into(),
                    b: idx(body_b),
                    sb: (*point_b).into(),
                    offset: V2::default(),
                },
                JointDesc::Prismatic { body_a, point_a, axis, body_b, point_b, .. } => {
                    let u = V2::from(*axis);
                    let u = u.scale(1.0 / u.norm());
                    let th_a = body_a.map_or(0.0, |a| desc.bodies[a].angle);
                    Constraint::Prismatic {
                        a: idx(body_a),
                        sa: (*point_a).into(),
                        u_perp: u.perp(),
                        b: *body_b as u32,
                        sb: (*point_b).into(),
                        theta0: desc.bodies[*body_b].angle - th_a,
                    }
                }
            });
        }
        for d in &desc.drivers {
            constraints.push(Constraint::Driver {
                b: d.body as u32,
                law: CompiledAngleLaw::compile(&d.law, &format!("driver '{}'", d.name))?,
            });
        }
        let clearance = desc.clearance_joints.iter().map(compile_clearance).collect::<Result<Vec<_>>>()?;
        let rows = constraints.iter().map(Constraint::rows).sum();
        let mut model = Model {
            body_names: desc.bodies.iter().map(|b| b.name.clone()).collect(),
            mass,
            gravity: desc.gravity.into(),
            alpha: desc.baumgarte[0],
            beta: desc.baumgarte[1],
            constraint_names: desc
                .joints
                .iter()
                .map(|j| match j {
                    JointDesc::Revolute { name, .. } => format!("revolute joint '{name}'"),
                    JointDesc::Prismatic { name, .. } => format!("prismatic joint '{name}'"),
                })
                .chain(desc.drivers.iter().map(|d| format!("driver '{}'", d.name)))
                .collect(),
            constraints,
            rows,
            clearance,
            forces: Vec::new(),
            force_names: desc.forces.iter().map(|f| f.name().to_string()).collect(),
            q_guess,
            qd_guess,
            assembly: Vec::new(),
            initial_wear: desc.clearance_joints.iter().map(initial_wear).collect(),
            start: None,
        };
        for c in &desc.clearance_joints {
            model.assembly.push((
                format!("clearance joint '{}' (held at its initial eccentricity)", c.name),
                Constraint::Revolute { a: idx(&c.journal_body), sa: c.journal_point.into(), b: idx(&c.bearing_body), sb: c.bearing_point.into(), offset: c.initial_eccentricity.into() },
            ));
        }
        for p in &desc.prismatic_clearance_joints {
            let (guide, ends) = compile_prismatic_clearance(p, desc)?;
            model.initial_wear.extend(ends.iter().map(|_| (Vec::new(), Vec::new())));
            model.clearance.extend(ends);
            model.assembly.push((format!("clearance joint '{}' (held centred in its guide)", p.name), guide));
        }
        // The pose given assembled once, here: the springs' free lengths below and every run and
        // initial state of this model start from it.
        model.start = Some(pose_at_zero(&model));
        model.forces = compile_forces(&model, desc)?;
        // The oil temperatures follow (q, q̇) in the state, in joint order (rust/clearance/thermal.rs).
        let heats = model.clearance.iter_mut().filter_map(|c| c.film.as_mut().and_then(|f| f.heat.as_mut()));
        for (state, h) in (6 * nb..).zip(heats) {
            h.state = state;
        }
        Ok(model)
    }
}

fn contact_law(c: &ClearanceJointDesc, dry: &DryDesc) -> ContactLaw {
    let r_b = c.journal_radius + c.clearance;
    let cylinder = if dry.stiffness_form == StiffnessForm::Cylindrical { dry.length } else { None };
    let line = cylinder.map(|l| crate::laws::contact_line::LineContact::pin_in_bore(r_b, c.journal_radius, l, dry.youngs_modulus, dry.poisson_ratio, dry.journal_youngs_modulus, dry.journal_poisson_ratio));
    let k = match &line {
        Some(l) => l.force_scale(),
        None => dry.stiffness.unwrap_or_else(|| {
            let f = if dry.stiffness_form == StiffnessForm::PaperPrinted { stiffness_paper_printed } else { stiffness_internal };
            f(r_b, c.journal_radius, dry.youngs_modulus, dry.poisson_ratio, dry.journal_youngs_modulus, dry.journal_poisson_ratio)
        }),
    };
    ContactLaw {
        line,
        law: dry.normal_law,
        stiffness: k,
        exponent: dry.exponent,
        restitution: dry.restitution,
        impact_speed_floor: dry.impact_speed_floor,
    }
}

/// The depths worn before the run of a clearance joint with wear (empty when none).
fn initial_wear(c: &ClearanceJointDesc) -> (Vec<f64>, Vec<f64>) {
    let dry = match &c.model {
        ClearanceModelDesc::Dry(d) => d,
        ClearanceModelDesc::Lubricated(l) => &l.dry,
    };
    dry.wear.as_ref().map_or((Vec::new(), Vec::new()), |w| (w.initial_bearing.clone(), w.initial_journal.clone()))
}

/// The heat balance and viscosity law of a lubricated joint (validated), if it has one.
fn heat(l: &LubricatedDesc) -> Option<crate::clearance::thermal::Heat> {
    let th = l.thermal?;
    let vogel = match l.viscosity {
        ViscosityDesc::Vogel { vogel: [a, b, c] } => Some(crate::laws::viscosity::Vogel { a, b, c }),
        ViscosityDesc::Constant(_) => None,
    };
    let thermal = crate::laws::viscosity::Thermal { ambient: th.ambient, heat_capacity: th.heat_capacity, heat_transfer: th.heat_transfer, initial: th.initial.unwrap_or(th.ambient) };
    Some(crate::clearance::thermal::Heat { vogel, thermal, state: usize::MAX }) // numbered in `Model::compile`
}

/// The film's viscosity at the start: the constant, or Vogel's law at the initial temperature.
fn initial_viscosity(l: &LubricatedDesc) -> f64 {
    match (&l.viscosity, heat(l)) {
        (ViscosityDesc::Constant(mu), _) => *mu,
        (ViscosityDesc::Vogel { .. }, Some(h)) => h.vogel.map_or(f64::NAN, |v| v.viscosity(h.thermal.initial)),
        (ViscosityDesc::Vogel { .. }, None) => f64::NAN,
    }
}

fn compile_clearance(c: &ClearanceJointDesc) -> Result<ClearanceJoint> {
    let (dry, film) = match &c.model {
        ClearanceModelDesc::Dry(d) => (d, None),
        ClearanceModelDesc::Lubricated(l) => (
            &l.dry,
            Some(Film {
                model: l.film,
                table: (l.film == crate::laws::FilmModel::Finite && l.cavitation == crate::laws::FilmCavitation::Reynolds)
                    .then(|| crate::laws::bearing_finite_cache::table_for(2.0 * c.journal_radius / l.length, l.supply)),
                geometry: BearingGeometry {
                    viscosity: initial_viscosity(l),
                    journal_radius: c.journal_radius,
                    clearance: c.clearance,
                    length: l.length,
                },
                eps0: l.eps0,
                m: l.m,
                e0: l.e0.unwrap_or(DEFAULT_TRANSITION_WIDTH * c.clearance),
                eps_max: l.eps_max,
                mixed: l.roughness.map(|sigma| crate::clearance::mixed::Mixed {
                    asperity: crate::laws::asperity::GreenwoodTripp::typical(
                        sigma,
                        crate::clearance::mixed::composite_modulus(l.dry.youngs_modulus, l.dry.poisson_ratio, l.dry.journal_youngs_modulus, l.dry.journal_poisson_ratio),
                    ),
                    friction: crate::clearance::mixed::boundary_friction(l.boundary_friction.unwrap_or(l.dry.friction), l.boundary_slip),
                }),
                heat: heat(l),
                mass_conserving: l.cavitation == crate::laws::FilmCavitation::Jfo,
            }),
        ),
    };
    let contact = contact_law(c, dry);
    if !(contact.stiffness.is_finite() && contact.stiffness > 0.0) {
        return Err(Error::invalid(format!("clearance joint '{}'.stiffness", c.name), contact.stiffness, "must be positive and finite"));
    }
    Ok(ClearanceJoint {
        name: c.name.clone(),
        bearing: c.bearing_body.map(|i| i as u32),
        bearing_point: c.bearing_point.into(),
        journal: c.journal_body.map(|i| i as u32),
        journal_point: c.journal_point.into(),
        journal_radius: c.journal_radius,
        bearing_radius: c.journal_radius + c.clearance,
        clearance: c.clearance,
        contact,
        friction: ModifiedCoulomb { friction_coefficient: dry.friction, v0: dry.v0, v1: dry.v1 },
        film,
        guide_normal: None,
        penetration_limit: max_penetration(c.clearance, c.journal_radius),
        wear: dry.wear.as_ref().map(|w| crate::laws::wear::Archard { k_over_h: w.coefficient / w.hardness, length: w.length, feedback: w.feedback }),
    })
}

/// Compile the force elements. A spring without a free length (angle) takes the distance
/// (relative angle) of the mechanism assembled at t = 0 ([`Model::start`]).
fn compile_forces(model: &Model, desc: &MechanismDesc) -> Result<Vec<ForceElement>> {
    if desc.forces.is_empty() {
        return Ok(Vec::new());
    }
    let needs_pose = desc.forces.iter().any(|f| {
        matches!(f, ForceDesc::SpringDamper { free_length: None, .. } | ForceDesc::RotationalSpringDamper { angle0: None, .. })
    });
    let kin: Vec<BodyKin> = if needs_pose {
        let q = match &model.start {
            Some(Ok(q)) => q.clone(),
            Some(Err(e)) => return Err(e.clone()),
            None => pose_at_zero(model)?,
        };
        let rest = [0.0; 3]; // positions and angles only are read
        (0..model.n_bodies()).map(|b| BodyKin::new(&q[3 * b..3 * b + 3], &rest)).collect()
    } else {
        Vec::new()
    };
    let at = |b: &BodyRef| b.map_or(BodyKin::GROUND, |i| kin[i]);
    let idx = |b: &BodyRef| b.map(|i| i as u32);
    Ok(desc
        .forces
        .iter()
        .map(|f| match f {
            ForceDesc::SpringDamper { body_a, point_a, body_b, point_b, stiffness, damping, free_length, force_table, .. } => ForceElement::SpringDamper {
                a: idx(body_a),
                sa: (*point_a).into(),
                b: idx(body_b),
                sb: (*point_b).into(),
                stiffness: *stiffness,
                damping: *damping,
                free_length: free_length.unwrap_or_else(|| at(body_b).point((*point_b).into()).sub(at(body_a).point((*point_a).into())).norm()),
                table: force_table.as_ref().map(Tabulated::new),
            },
            ForceDesc::RotationalSpringDamper { body_a, body_b, stiffness, damping, angle0, .. } => ForceElement::RotationalSpringDamper {
                a: idx(body_a),
                b: idx(body_b),
                stiffness: *stiffness,
                damping: *damping,
                free_angle: angle0.unwrap_or_else(|| at(body_b).th - at(body_a).th),
            },
            ForceDesc::Force { body, point, frame, fx, fy, .. } => ForceElement::Force {
                body: *body as u32,
                s: (*point).into(),
                body_frame: *frame == Frame::Body,
                fx: Magnitude::new(fx),
                fy: Magnitude::new(fy),
            },
            ForceDesc::Torque { body, reaction, magnitude, .. } => ForceElement::Torque { body: *body as u32, reaction: idx(reaction), magnitude: Magnitude::new(magnitude) },
            ForceDesc::Motor { body, reaction, stall_torque, no_load_speed, .. } => {
                ForceElement::Motor { body: *body as u32, reaction: idx(reaction), stall_torque: *stall_torque, no_load_speed: *no_load_speed }
            }
        })
        .collect())
}

/// The two slider-end contacts of a prismatic clearance joint (docs/physics.md §11) and the
/// prismatic constraint that holds the slider centred and aligned during the assembly.
fn compile_prismatic_clearance(p: &PrismaticClearanceDesc, desc: &MechanismDesc) -> Result<(Constraint, [ClearanceJoint; 2])> {
    let u = V2::from(p.axis);
    let u = u.scale(1.0 / u.norm());
    let th_g = p.guide_body.map_or(0.0, |g| desc.bodies[g].angle);
    let th_s = desc.bodies[p.slider_body].angle;
    // The slider's axis in its own frame, aligned with the guide's at the described pose.
    let (s, c) = (th_g - th_s).sin_cos();
    let u_s = V2::new(c * u.x - s * u.y, s * u.x + c * u.y);
    let d = &p.model;
    let k = d.stiffness.unwrap_or_else(|| crate::laws::contact::stiffness_sphere_plane(p.corner_radius, d.youngs_modulus, d.poisson_ratio, d.journal_youngs_modulus, d.journal_poisson_ratio));
    let contact = ContactLaw { line: None, law: d.normal_law, stiffness: k, exponent: d.exponent, restitution: d.restitution, impact_speed_floor: d.impact_speed_floor };
    let half = 0.5 * p.clearance;
    let end = |sign: f64, label: &str| ClearanceJoint {
        name: format!("{} {label}", p.name),
        bearing: p.guide_body.map(|i| i as u32),
        bearing_point: p.guide_point.into(),
        journal: Some(p.slider_body as u32),
        journal_point: u_s.scale(sign * 0.5 * p.slider_length),
        journal_radius: 0.0,
        bearing_radius: 0.0,
        clearance: half,
        contact,
        friction: ModifiedCoulomb { friction_coefficient: d.friction, v0: d.v0, v1: d.v1 },
        film: None,
        guide_normal: Some(u.perp()),
        penetration_limit: max_penetration(half, p.corner_radius),
        wear: None,
    };
    let guide = Constraint::Prismatic { a: p.guide_body.map(|i| i as u32), sa: p.guide_point.into(), u_perp: u.perp(), b: p.slider_body as u32, sb: V2::default(), theta0: th_s - th_g };
    Ok((guide, [end(1.0, "front"), end(-1.0, "rear")]))
}

