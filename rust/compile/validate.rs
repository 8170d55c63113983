//! Validation of a [`MechanismDesc`]: every bad value is reported with the field that holds it.

use std::collections::HashSet;

use crate::description::*;
use crate::error::{Error, Result};

use super::num;

fn finite(field: &str, v: f64) -> Result<()> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(Error::invalid(field, num(v), "must be a finite number"))
    }
}

/// The viscosity (a constant or Vogel's law) and the heat balance of lubricated joint `f`: a
/// Vogel law needs the temperature (`thermal`), and the law must hold (T > c) at the ambient and
/// initial temperatures — then it holds over the run, since the oil never cools below the lower
/// of the two (the power loss is ≥ 0, docs/physics.md §4, *Heat*).
fn validate_heat(f: &str, l: &LubricatedDesc) -> Result<()> {
    let vogel = match l.viscosity {
        ViscosityDesc::Constant(mu) => {
            positive(&format!("{f}.viscosity"), mu)?;
            None
        }
        ViscosityDesc::Vogel { vogel: [a, b, c] } => {
            let v = crate::laws::viscosity::Vogel::new(a, b, c).map_err(|(name, why)| {
                let value = match name {
                    "a" => a,
                    "b" => b,
                    _ => c,
                };
                Error::invalid(format!("{f}.viscosity.vogel.{name}"), num(value), why)
            })?;
            if l.thermal.is_none() {
                return Err(Error::invalid(format!("{f}.thermal"), "None", "a Vogel viscosity needs the oil temperature: give thermal = Thermal(ambient, heat_capacity, heat_transfer)"));
            }
            Some(v)
        }
    };
    if let Some(th) = &l.thermal {
        positive(&format!("{f}.thermal.ambient"), th.ambient)?;
        positive(&format!("{f}.thermal.heat_capacity"), th.heat_capacity)?;
        positive(&format!("{f}.thermal.heat_transfer"), th.heat_transfer)?;
        if let Some(t0) = th.initial {
            positive(&format!("{f}.thermal.initial"), t0)?;
        }
        if let Some(v) = vogel {
            for (name, t) in [("ambient", th.ambient), ("initial", th.initial.unwrap_or(th.ambient))] {
                if !v.holds_at(t) {
                    return Err(Error::invalid(
                        format!("{f}.thermal.{name}"),
                        num(t),
                        format!("must lie above the Vogel law's c = {} K (its viscosity is infinite there; temperatures in kelvin)", num(v.c)),
                    ));
                }
            }
        }
    }
    Ok(())
}

fn positive(field: &str, v: f64) -> Result<()> {
    finite(field, v)?;
    if v > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(field, num(v), "must be positive"))
    }
}

fn non_negative(field: &str, v: f64) -> Result<()> {
    finite(field, v)?;
    if v >= 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(field, num(v), "must not be negative"))
    }
}

fn within(field: &str, v: f64, lo: f64, hi: f64, lo_open: bool, hi_open: bool) -> Result<()> {
    finite(field, v)?;
    let ok_lo = if lo_open { v > lo } else { v >= lo };
    let ok_hi = if hi_open { v < hi } else { v <= hi };
    if ok_lo && ok_hi {
        Ok(())
    } else {
        let (l, r) = (if lo_open { "(" } else { "[" }, if hi_open { ")" } else { "]" });
        Err(Error::invalid(field, num(v), format!("must lie in {l}{lo}, {hi}{r}")))
    }
}

fn point(field: &str, p: [f64; 2]) -> Result<()> {
    finite(&format!("{field}[0]"), p[0])?;
    finite(&format!("{field}[1]"), p[1])
}

fn body_ref(field: &str, b: Option<usize>, nb: usize) -> Result<()> {
    match b {
        Some(i) if i >= nb => Err(Error::invalid(field, i, format!("no such body (there are {nb})"))),
        _ => Ok(()),
    }
}

fn unique<'a>(what: &'static str, names: impl Iterator<Item = &'a String>) -> Result<()> {
    let mut seen = HashSet::new();
    for n in names {
        if n.is_empty() {
            return Err(Error::Name { what, name: n.clone(), reason: "names must not be empty".into() });
        }
        if n == "ground" {
            return Err(Error::Name { what, name: n.clone(), reason: "'ground' is reserved for the fixed frame".into() });
        }
        if !seen.insert(n) {
            return Err(Error::Name { what, name: n.clone(), reason: "used twice".into() });
        }
    }
    Ok(())
}

pub(super) fn validate_dry(f: &str, d: &DryDesc) -> Result<()> {
    positive(&format!("{f}.youngs_modulus"), d.youngs_modulus)?;
    positive(&format!("{f}.journal_youngs_modulus"), d.journal_youngs_modulus)?;
    within(&format!("{f}.poisson_ratio"), d.poisson_ratio, -1.0, 0.5, true, true)?;
    within(&format!("{f}.journal_poisson_ratio"), d.journal_poisson_ratio, -1.0, 0.5, true, true)?;
    within(&format!("{f}.restitution"), d.restitution, 0.0, 1.0, true, false)?;
    positive(&format!("{f}.exponent"), d.exponent)?;
    if let Some(k) = d.stiffness {
        positive(&format!("{f}.stiffness"), k)?;
    }
    match (d.stiffness_form, d.length) {
        (StiffnessForm::Cylindrical, None) => {
            return Err(Error::invalid(format!("{f}.length"), "None", "stiffness_form = 'cylindrical' needs the pin length: Dry(..., length=L) [m]"));
        }
        (StiffnessForm::Cylindrical, Some(l)) => {
            positive(&format!("{f}.length"), l)?;
            // The line law is a whole force–penetration relation: a K or an n would be ignored.
            if let Some(k) = d.stiffness {
                return Err(Error::invalid(format!("{f}.stiffness"), num(k), "give either a stiffness or stiffness_form = \"cylindrical\", not both (the line contact computes its own force)"));
            }
            if d.exponent != 1.5 {
                return Err(Error::invalid(format!("{f}.exponent"), num(d.exponent), "is not used by stiffness_form = \"cylindrical\" (Johnson's line contact has its own force–penetration law): leave it at 1.5"));
            }
        }
        (_, Some(l)) => return Err(Error::invalid(format!("{f}.length"), num(l), "a pin length is used only with stiffness_form = 'cylindrical'")),
        (_, None) => {}
    }
    non_negative(&format!("{f}.friction"), d.friction)?;
    non_negative(&format!("{f}.v0"), d.v0)?;
    positive(&format!("{f}.v1"), d.v1)?;
    if d.v1 <= d.v0 {
        return Err(Error::invalid(format!("{f}.v1"), num(d.v1), format!("must exceed v0 = {}", num(d.v0))));
    }
    positive(&format!("{f}.impact_speed_floor"), d.impact_speed_floor)?;
    if let Some(w) = &d.wear {
        positive(&format!("{f}.wear.coefficient"), w.coefficient)?;
        positive(&format!("{f}.wear.hardness"), w.hardness)?;
        positive(&format!("{f}.wear.length"), w.length)?;
        for (name, depths) in [("initial_bearing", &w.initial_bearing), ("initial_journal", &w.initial_journal)] {
            let n = crate::clearance::wear::WEAR_BINS;
            if !depths.is_empty() && depths.len() != n {
                return Err(Error::invalid(format!("{f}.wear.{name}"), format!("{} depths", depths.len()), format!("must hold {n} depths (1° bins) or none")));
            }
            for (i, d) in depths.iter().enumerate() {
                non_negative(&format!("{f}.wear.{name}[{i}]"), *d)?;
            }
        }
    }
    Ok(())
}

/// The largest radial clearance of a lubricated joint, as a fraction of the journal radius:
/// the film laws (docs: "Lubricated joints") are thin-film theory, c ≪ R_j. Real bearings have
/// c/R_j ≈ 1e-3; the paper's exaggerated study clearances reach 0.06.
pub const MAX_FILM_CLEARANCE_RATIO: f64 = 0.25;

/// Check a whole description: each element's references (bodies by index, one driver per body,
/// unique names) and its own values ([`body`], [`joint`], [`driver`], [`clearance_joint`],
/// [`prismatic_clearance`], [`force`]: the checks an element also meets alone when it is added,
/// `super::check_element`).
pub(super) fn validate(desc: &MechanismDesc) -> Result<()> {
    let nb = desc.bodies.len();
    if nb == 0 {
        return Err(Error::invalid("bodies", "[]", "a mechanism needs at least one body"));
    }
    unique("body", desc.bodies.iter().map(|b| &b.name))?;
    unique(
        "joint",
        desc.joints
            .iter()
            .map(|j| match j {
                JointDesc::Revolute { name, .. } | JointDesc::Prismatic { name, .. } => name,
            })
            .chain(desc.clearance_joints.iter().map(|c| &c.name))
            .chain(desc.prismatic_clearance_joints.iter().map(|c| &c.name))
            .chain(desc.drivers.iter().map(|d| &d.name)),
    )?;
    for b in &desc.bodies {
        body(b)?;
    }
    for j in &desc.joints {
        let f = format!("joint '{}'", j.name());
        match j {
            JointDesc::Revolute { body_a, body_b, .. } => {
                body_ref(&format!("{f}.body_a"), *body_a, nb)?;
                body_ref(&format!("{f}.body_b"), *body_b, nb)?;
                if body_a == body_b {
                    return Err(Error::invalid(format!("{f}.body_b"), format!("{body_b:?}"), "a joint needs two different bodies"));
                }
            }
            JointDesc::Prismatic { body_a, body_b, .. } => {
                body_ref(&format!("{f}.body_a"), *body_a, nb)?;
                body_ref(&format!("{f}.body_b"), Some(*body_b), nb)?;
                if *body_a == Some(*body_b) {
                    return Err(Error::invalid(format!("{f}.body_b"), body_b, "a joint needs two different bodies"));
                }
            }
        }
        joint(j)?;
    }
    for (k, d) in desc.drivers.iter().enumerate() {
        body_ref(&format!("driver '{}'.body", d.name), Some(d.body), nb)?;
        if let Some(first) = desc.drivers[..k].iter().find(|o| o.body == d.body) {
            // Two angle laws on one body: identical ones are redundant (a singular constraint
            // Jacobian), different ones contradict each other (no assembly).
            return Err(Error::invalid(
                format!("driver '{}'.body", d.name),
                &desc.bodies[d.body].name,
                format!("the body is already driven by driver '{}': one body takes one driver", first.name),
            ));
        }
        driver(d)?;
    }
    for c in &desc.clearance_joints {
        let f = format!("clearance joint '{}'", c.name);
        body_ref(&format!("{f}.bearing_body"), c.bearing_body, nb)?;
        body_ref(&format!("{f}.journal_body"), c.journal_body, nb)?;
        if c.bearing_body == c.journal_body {
            return Err(Error::invalid(format!("{f}.journal_body"), format!("{:?}", c.journal_body), "bearing and journal must be on different bodies"));
        }
        clearance_joint(c)?;
    }
    for p in &desc.prismatic_clearance_joints {
        let f = format!("clearance joint '{}'", p.name);
        body_ref(&format!("{f}.guide_body"), p.guide_body, nb)?;
        body_ref(&format!("{f}.slider_body"), Some(p.slider_body), nb)?;
        if p.guide_body == Some(p.slider_body) {
            return Err(Error::invalid(format!("{f}.slider_body"), p.slider_body, "guide and slider must be different bodies"));
        }
        prismatic_clearance(p)?;
    }
    unique("force", desc.forces.iter().map(|f| match f {
        ForceDesc::SpringDamper { name, .. }
        | ForceDesc::RotationalSpringDamper { name, .. }
        | ForceDesc::Force { name, .. }
        | ForceDesc::Torque { name, .. }
        | ForceDesc::Motor { name, .. } => name,
    }))?;
    for fd in &desc.forces {
        force_refs(fd, nb)?;
        force(fd)?;
    }
    point("gravity", desc.gravity)?;
    non_negative("baumgarte.alpha", desc.baumgarte[0])?;
    non_negative("baumgarte.beta", desc.baumgarte[1])?;
    Ok(())
}

/// A body's own values.
pub(super) fn body(b: &BodyDesc) -> Result<()> {
    let f = format!("body '{}'", b.name);
    positive(&format!("{f}.mass"), b.mass)?;
    positive(&format!("{f}.inertia"), b.inertia)?;
    point(&format!("{f}.position"), b.position)?;
    finite(&format!("{f}.angle"), b.angle)?;
    for (k, v) in b.velocity.iter().enumerate() {
        finite(&format!("{f}.velocity[{k}]"), *v)?;
    }
    Ok(())
}

/// An ideal joint's own values (its points and axis).
pub(super) fn joint(j: &JointDesc) -> Result<()> {
    let f = format!("joint '{}'", j.name());
    match j {
        JointDesc::Revolute { point_a, point_b, .. } => {
            point(&format!("{f}.point_a"), *point_a)?;
            point(&format!("{f}.point_b"), *point_b)
        }
        JointDesc::Prismatic { point_a, axis, point_b, .. } => {
            point(&format!("{f}.point_a"), *point_a)?;
            point(&format!("{f}.point_b"), *point_b)?;
            point(&format!("{f}.axis"), *axis)?;
            if axis[0].hypot(axis[1]) < 1e-12 {
                return Err(Error::invalid(format!("{f}.axis"), format!("{axis:?}"), "must be a non-zero direction"));
            }
            Ok(())
        }
    }
}

/// A driver's angle law.
pub(super) fn driver(d: &DriverDesc) -> Result<()> {
    crate::constraints::CompiledAngleLaw::compile(&d.law, &format!("driver '{}'", d.name)).map(|_| ())
}

/// A revolute clearance joint's own values: its points, sizes and model.
pub(super) fn clearance_joint(c: &ClearanceJointDesc) -> Result<()> {
    let f = format!("clearance joint '{}'", c.name);
    point(&format!("{f}.bearing_point"), c.bearing_point)?;
    point(&format!("{f}.journal_point"), c.journal_point)?;
    point(&format!("{f}.initial_eccentricity"), c.initial_eccentricity)?;
    positive(&format!("{f}.journal_radius"), c.journal_radius)?;
    finite(&format!("{f}.clearance"), c.clearance)?;
    if c.clearance <= 0.0 {
        return Err(Error::invalid(
            format!("{f}.clearance"),
            num(c.clearance),
            format!("must be positive (c = R_b − R_j: the journal radius R_j = {} must be below the bearing radius R_b = R_j + c)", c.journal_radius),
        ));
    }
    if c.clearance < 1e-9 * c.journal_radius {
        return Err(Error::invalid(
            format!("{f}.clearance"),
            num(c.clearance),
            format!(
                "is too small against the journal radius R_j = {}: c/R_j must be at least 1e-9 (R_b = R_j + c would round to R_j and the contact stiffness diverge)",
                c.journal_radius
            ),
        ));
    }
    let e_init = c.initial_eccentricity[0].hypot(c.initial_eccentricity[1]);
    if e_init > 2.0 * c.clearance {
        return Err(Error::invalid(
            format!("{f}.initial_eccentricity"),
            format!("{:?}", c.initial_eccentricity),
            format!("its length must not exceed 2 × clearance = {} m (give e in metres, not in units of c)", 2.0 * c.clearance),
        ));
    }
    match &c.model {
        ClearanceModelDesc::Dry(d) => validate_dry(&f, d),
        ClearanceModelDesc::Lubricated(l) => {
            if c.clearance > MAX_FILM_CLEARANCE_RATIO * c.journal_radius {
                return Err(Error::invalid(
                    format!("{f}.clearance"),
                    num(c.clearance),
                    format!(
                        "is not small against the journal radius R_j = {} m (c/R_j = {} > {MAX_FILM_CLEARANCE_RATIO}): the film laws are thin-film (Reynolds) theory, valid for c ≪ R_j; is the clearance in metres?",
                        c.journal_radius,
                        num(c.clearance / c.journal_radius)
                    ),
                ));
            }
            lubricated(&f, l)?;
            if l.film == crate::laws::FilmModel::Finite {
                check_finite_bearing_ratio(&format!("{f}.film"), l.length / (2.0 * c.journal_radius))?;
            }
            if let Some(sigma) = l.roughness {
                if 4.0 * sigma >= c.clearance {
                    return Err(Error::invalid(
                        format!("{f}.roughness"),
                        num(sigma),
                        format!("must be below a quarter of the clearance c = {} m: the asperities (up to 4σ high) would touch with the journal centred; is it in metres?", num(c.clearance)),
                    ));
                }
            }
            Ok(())
        }
    }
}

/// A lubricated joint's model on its own (`f` names the joint, or is empty for the model alone):
/// viscosity and heat, length, film and supply, the transition's parameters, the dry law,
/// roughness and boundary friction. What needs the joint's sizes (c/R_j, L/D, σ against c) is
/// [`clearance_joint`]'s.
pub(super) fn lubricated(f: &str, l: &LubricatedDesc) -> Result<()> {
    validate_heat(f, l)?;
    positive(&format!("{f}.length"), l.length)?;
    if l.film != crate::laws::FilmModel::Finite && l.supply != crate::laws::FilmSupply::WidestGap {
        return Err(Error::invalid(
            format!("{f}.supply"),
            "none",
            "applies to film = \"finite\" only: the long films' pressure is referred to the widest gap (P12) and the short film has no flow around the bearing",
        ));
    }
    if l.cavitation == crate::laws::FilmCavitation::Jfo {
        if l.film != crate::laws::FilmModel::Finite {
            return Err(Error::invalid(
                format!("{f}.cavitation"),
                "jfo",
                "applies to film = \"finite\" only: mass-conserving cavitation follows the oil over the bearing, which the closed-form films do not resolve",
            ));
        }
        if l.supply != crate::laws::FilmSupply::WidestGap {
            return Err(Error::invalid(
                format!("{f}.supply"),
                "none",
                "cavitation = \"jfo\" needs the supply groove on the widest gap (supply = \"widest_gap\"): with the film ambient only at its ends no oil could come back in",
            ));
        }
    }
    within(&format!("{f}.eps0"), l.eps0, 0.0, 1.0, false, true)?;
    within(&format!("{f}.m"), l.m, 0.0, 1.0, true, true)?;
    if let Some(e0) = l.e0 {
        positive(&format!("{f}.e0"), e0)?;
    }
    within(&format!("{f}.eps_max"), l.eps_max, 0.0, 1.0, true, true)?;
    validate_dry(f, &l.dry)?;
    if let Some(sigma) = l.roughness {
        positive(&format!("{f}.roughness"), sigma)?;
    }
    if let Some(v) = l.boundary_slip {
        positive(&format!("{f}.boundary_slip"), v)?;
        if l.roughness.is_none() {
            return Err(Error::invalid(format!("{f}.boundary_slip"), num(v), "applies with roughness only (the boundary friction's slip ramp): give roughness too"));
        }
    }
    if let Some(mu_b) = l.boundary_friction {
        non_negative(&format!("{f}.boundary_friction"), mu_b)?;
        if l.roughness.is_none() {
            return Err(Error::invalid(format!("{f}.boundary_friction"), num(mu_b), "applies with roughness only (the friction on the asperity load): give roughness too"));
        }
    }
    Ok(())
}

/// A prismatic clearance joint's own values.
pub(super) fn prismatic_clearance(p: &PrismaticClearanceDesc) -> Result<()> {
    let f = format!("clearance joint '{}'", p.name);
    point(&format!("{f}.guide_point"), p.guide_point)?;
    point(&format!("{f}.axis"), p.axis)?;
    if p.axis[0].hypot(p.axis[1]) < 1e-12 {
        return Err(Error::invalid(format!("{f}.axis"), format!("{:?}", p.axis), "must be a non-zero direction"));
    }
    positive(&format!("{f}.clearance"), p.clearance)?;
    positive(&format!("{f}.slider_length"), p.slider_length)?;
    positive(&format!("{f}.corner_radius"), p.corner_radius)?;
    validate_dry(&f, &p.model)?;
    if p.model.stiffness_form == StiffnessForm::Cylindrical {
        return Err(Error::invalid(format!("{f}.stiffness_form"), "cylindrical", "is for revolute clearance joints (a pin in a bore); a slider's ends use the rounded-corner contact"));
    }
    if p.model.wear.is_some() {
        return Err(Error::invalid(format!("{f}.wear"), "Archard(...)", "wear is modelled for revolute clearance joints only"));
    }
    Ok(())
}

fn validate_table(f: &str, t: &Table) -> Result<()> {
    if t.x.len() < 2 || t.x.len() != t.y.len() {
        return Err(Error::invalid(format!("{f}.x"), format!("{} points ({} values y)", t.x.len(), t.y.len()), "a table needs at least 2 points and as many y as x"));
    }
    for (k, (x, y)) in t.x.iter().zip(&t.y).enumerate() {
        finite(&format!("{f}.x[{k}]"), *x)?;
        finite(&format!("{f}.y[{k}]"), *y)?;
    }
    if let Some(k) = t.x.windows(2).position(|w| !(w[1] > w[0])) {
        return Err(Error::invalid(format!("{f}.x[{}]", k + 1), num(t.x[k + 1]), format!("must exceed x[{k}] = {} (x increases strictly)", num(t.x[k]))));
    }
    if let Some(p) = t.period {
        positive(&format!("{f}.period"), p)?;
        let span = t.x[t.x.len() - 1] - t.x[0];
        if span > p * (1.0 + 1e-12) {
            return Err(Error::invalid(format!("{f}.period"), num(p), format!("must cover the table's span x_last − x₀ = {}", num(span))));
        }
        // A periodic spline through a last point one period after the first is the first point
        // again: it must carry its value (a linear table may jump there).
        let (n, scale) = (t.y.len(), t.y.iter().fold(0.0f64, |a, v| a.max(v.abs())));
        if t.interpolation == crate::description::Interpolation::Cubic && crate::table::closes_itself(t) && (t.y[n - 1] - t.y[0]).abs() > 1e-9 * scale {
            return Err(Error::invalid(
                format!("{f}.y[{}]", n - 1),
                num(t.y[n - 1]),
                format!("a periodic cubic table's point at x₀ + period repeats its first, y[0] = {} (or leave the point out)", num(t.y[0])),
            ));
        }
    }
    Ok(())
}

fn validate_profile(f: &str, p: &Profile) -> Result<()> {
    match p {
        Profile::Constant { value } => finite(f, *value),
        Profile::Table { table, .. } => validate_table(f, table),
        Profile::Harmonic(h) => crate::constraints::angle_law::check_harmonic(f, h),
    }
}

fn profile_ref(f: &str, p: &Profile, nb: usize) -> Result<()> {
    match p {
        Profile::Table { argument: TableArgument::Angle { body }, .. } => body_ref(&format!("{f}.argument.body"), Some(*body), nb),
        _ => Ok(()),
    }
}

fn two_bodies(f: &str, a: BodyRef, b: BodyRef, nb: usize) -> Result<()> {
    body_ref(&format!("{f}.body_a"), a, nb)?;
    body_ref(&format!("{f}.body_b"), b, nb)?;
    if a == b {
        return Err(Error::invalid(format!("{f}.body_b"), format!("{b:?}"), "must differ from body_a (an element acts between two bodies, or a body and the ground)"));
    }
    Ok(())
}

/// A force element's references to bodies (a load table's angle argument included).
fn force_refs(fd: &ForceDesc, nb: usize) -> Result<()> {
    let f = format!("force '{}'", fd.name());
    match fd {
        ForceDesc::SpringDamper { body_a, body_b, .. } | ForceDesc::RotationalSpringDamper { body_a, body_b, .. } => two_bodies(&f, *body_a, *body_b, nb),
        ForceDesc::Force { body, fx, fy, .. } => {
            body_ref(&format!("{f}.body"), Some(*body), nb)?;
            profile_ref(&format!("{f}.fx"), fx, nb)?;
            profile_ref(&format!("{f}.fy"), fy, nb)
        }
        ForceDesc::Torque { body, reaction, magnitude, .. } => {
            body_ref(&format!("{f}.body"), Some(*body), nb)?;
            body_ref(&format!("{f}.reaction"), *reaction, nb)?;
            if *reaction == Some(*body) {
                return Err(Error::invalid(format!("{f}.reaction"), body, "must differ from the loaded body"));
            }
            profile_ref(&format!("{f}.magnitude"), magnitude, nb)
        }
        ForceDesc::Motor { body, reaction, .. } => {
            body_ref(&format!("{f}.body"), Some(*body), nb)?;
            body_ref(&format!("{f}.reaction"), *reaction, nb)?;
            if *reaction == Some(*body) {
                return Err(Error::invalid(format!("{f}.reaction"), body, "must differ from the rotor body"));
            }
            Ok(())
        }
    }
}

/// A force element's own values.
pub(super) fn force(fd: &ForceDesc) -> Result<()> {
    let f = format!("force '{}'", fd.name());
    match fd {
        ForceDesc::SpringDamper { point_a, point_b, stiffness, damping, free_length, force_table, .. } => {
            point(&format!("{f}.point_a"), *point_a)?;
            point(&format!("{f}.point_b"), *point_b)?;
            non_negative(&format!("{f}.stiffness"), *stiffness)?;
            non_negative(&format!("{f}.damping"), *damping)?;
            if let Some(l0) = free_length {
                non_negative(&format!("{f}.free_length"), *l0)?;
            }
            if let Some(t) = force_table {
                if *stiffness != 0.0 {
                    return Err(Error::invalid(format!("{f}.stiffness"), num(*stiffness), "give either a stiffness or a force_table, not both"));
                }
                validate_table(&format!("{f}.force_table"), t)?;
            }
        }
        ForceDesc::RotationalSpringDamper { stiffness, damping, angle0, .. } => {
            non_negative(&format!("{f}.stiffness"), *stiffness)?;
            non_negative(&format!("{f}.damping"), *damping)?;
            if let Some(a) = angle0 {
                finite(&format!("{f}.angle0"), *a)?;
            }
        }
        ForceDesc::Force { point: p, fx, fy, .. } => {
            point(&format!("{f}.point"), *p)?;
            validate_profile(&format!("{f}.fx"), fx)?;
            validate_profile(&format!("{f}.fy"), fy)?;
        }
        ForceDesc::Torque { magnitude, .. } => validate_profile(&format!("{f}.magnitude"), magnitude)?,
        ForceDesc::Motor { stall_torque, no_load_speed, .. } => {
            positive(&format!("{f}.stall_torque"), *stall_torque)?;
            finite(&format!("{f}.no_load_speed"), *no_load_speed)?;
            if *no_load_speed == 0.0 {
                return Err(Error::invalid(format!("{f}.no_load_speed"), 0, "must not be zero (its sign is the direction of rotation)"));
            }
        }
    }
    Ok(())
}

/// L/D range of `film = "finite"`: its table is built by a Reynolds solve whose cost grows
/// beyond it; outside it the short (L/D small) or long (L/D large) closed forms apply.
pub const FINITE_BEARING_L_OVER_D: (f64, f64) = (1.0 / 16.0, 16.0);

/// An `InputError` unless `l_over_d` lies in [`FINITE_BEARING_L_OVER_D`].
pub fn check_finite_bearing_ratio(field: &str, l_over_d: f64) -> Result<()> {
    let (lo, hi) = FINITE_BEARING_L_OVER_D;
    if !(lo..=hi).contains(&l_over_d) {
        return Err(Error::invalid(
            field.to_string(),
            "finite",
            format!("the finite bearing covers {lo} ≤ L/D ≤ {hi}, this one has L/D = {l_over_d:.4}: use film = \"short\" (L/D < 1/16) or \"long\" (L/D > 16)"),
        ));
    }
    Ok(())
}
