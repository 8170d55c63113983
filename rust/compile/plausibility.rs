//! Plausibility of a whole mechanism's numbers: what is valid but looks like a unit slip against
//! the mechanism's own size — lengths in millimetres where clearsim takes metres, a load point
//! far outside its body, an output point (a tool tip watched by a study, a scene's `[outputs]
//! points`) in mm or in the global frame ([`output_point`]). Each finding names the element, the field, the value and the unit
//! clearsim expected ([`Warning`]); the Python layer shows them as `PlausibilityWarning`s when
//! the mechanism compiles. (One joint's numbers on their own — a viscosity in cP, a clearance in
//! mm — are checked as the joint is added: `python/clearsim/plausibility.py`.)

use crate::assembly::extent;
use crate::description::*;
use crate::error::Warning;

use crate::text::g;

/// A journal radius above this fraction of the mechanism's span, or a bearing length above this
/// multiple of it, is more likely millimetres than metres.
pub const JOURNAL_SPAN_RATIO: f64 = 0.5;
pub const LENGTH_SPAN_RATIO: f64 = 2.0;
/// A body's inertia below this fraction of a uniform bar's, m d²/12 over the spread d of its
/// centroid and attachment points, is more likely coordinates in mm with the inertia in kg m²
/// (a ratio of about 1e-6).
pub const BAR_INERTIA_RATIO: f64 = 1e-3;
/// A load point further from its body's centroid than this multiple of the body's reach (its
/// attachment points' largest distance from the centroid) is more likely given in global
/// coordinates or in mm.
pub const LOAD_REACH_RATIO: f64 = 3.0;
/// A load table over a crank angle with a period (or span) of one of these is in degrees: a
/// half turn, a turn, a four-stroke cycle.
const DEGREE_CYCLES: [f64; 3] = [180.0, 360.0, 720.0];

/// An output point (a point on a body watched as an output, [`output_point`]) further from its
/// body's centroid than this multiple of the mechanism's span is more likely given in mm.
pub const OUTPUT_SPAN_RATIO: f64 = 10.0;
/// An output point further from its body's centroid than this multiple of the body's reach that,
/// read as a global point at the pose given, lies within this multiple of the reach of the
/// centroid is more likely given in the global frame.
pub const OUTPUT_REACH_RATIO: f64 = 1.5;

/// A body-frame point of body `body` (or the ground) in the global frame at the pose given.
pub(crate) fn global(desc: &MechanismDesc, body: BodyRef, p: [f64; 2]) -> (f64, f64) {
    match body {
        None => (p[0], p[1]),
        Some(b) => {
            let b = &desc.bodies[b];
            let (s, c) = b.angle.sin_cos();
            (b.position[0] + c * p[0] - s * p[1], b.position[1] + s * p[0] + c * p[1])
        }
    }
}

/// A joint's two bodies and points: (body a, point a, body b, point b).
pub(crate) fn ends(j: &JointDesc) -> (BodyRef, [f64; 2], BodyRef, [f64; 2]) {
    match j {
        JointDesc::Revolute { body_a, point_a, body_b, point_b, .. } => (*body_a, *point_a, *body_b, *point_b),
        JointDesc::Prismatic { body_a, point_a, body_b, point_b, .. } => (*body_a, *point_a, Some(*body_b), *point_b),
    }
}

/// The points where bodies meet — each joint's two points, a clearance joint's bearing centre
/// (its journal lies within the clearance of it, or at its initial eccentricity: no length of
/// the mechanism) — at the pose given, global frame.
fn joint_points(desc: &MechanismDesc) -> Vec<(f64, f64)> {
    let mut pts = Vec::new();
    for j in &desc.joints {
        let (a, pa, b, pb) = ends(j);
        pts.push(global(desc, a, pa));
        pts.push(global(desc, b, pb));
    }
    for c in &desc.clearance_joints {
        pts.push(global(desc, c.bearing_body, c.bearing_point));
    }
    pts
}

/// The mechanism's scale \[m\] for the size checks: the span ([`crate::assembly::extent`], x
/// extent plus y extent) of the points where its bodies meet. A mechanism whose joints all sit at
/// one place (a rotor in one bearing) has none (0): its bodies' sizes are not a scale.
pub fn scale(desc: &MechanismDesc) -> f64 {
    extent(joint_points(desc).into_iter())
}

/// Per body, the points attached to it (body frame): its joints', clearance joints' and
/// springs' points.
fn attachments(desc: &MechanismDesc) -> Vec<Vec<[f64; 2]>> {
    let mut points = vec![Vec::new(); desc.bodies.len()];
    let mut add = |b: BodyRef, p: [f64; 2]| {
        if let Some(b) = b {
            points[b].push(p);
        }
    };
    for j in &desc.joints {
        let (a, pa, b, pb) = ends(j);
        add(a, pa);
        add(b, pb);
    }
    for c in &desc.clearance_joints {
        add(c.bearing_body, c.bearing_point);
        add(c.journal_body, c.journal_point);
    }
    for f in &desc.forces {
        if let ForceDesc::SpringDamper { body_a, point_a, body_b, point_b, .. } = f {
            add(*body_a, *point_a);
            add(*body_b, *point_b);
        }
    }
    points
}

/// What looks wrong in an output point `point` (body frame \[m\]) on body `body` of a resolved
/// description, named `field` in the message: a point further from the centroid than
/// [`OUTPUT_SPAN_RATIO`] × the mechanism's span (mm?), or one further than [`OUTPUT_REACH_RATIO`]
/// × the body's reach that lies within that of the centroid when read as a global point (the
/// global frame?).
pub fn output_point(desc: &MechanismDesc, body: usize, point: [f64; 2], field: &str) -> Option<Warning> {
    let b = desc.bodies.get(body)?;
    let d = point[0].hypot(point[1]);
    let at = format!("{field} = ({}, {}) m lies {} m from the centroid of body '{}'", g(point[0], 4), g(point[1], 4), g(d, 3), b.name);
    let span = scale(desc);
    if span > 0.0 && d > OUTPUT_SPAN_RATIO * span {
        let message = format!("{at}, {} × the mechanism's span {} m: is it given in mm? clearsim takes the point in metres in the body's frame", g(d / span, 3), g(span, 3));
        return Some(Warning { field: field.to_string(), message });
    }
    let reach = attachments(desc)[body].iter().map(|p| p[0].hypot(p[1])).fold(0.0, f64::max);
    // The point read as a global one, in the body's frame at the pose given.
    let (s, c) = b.angle.sin_cos();
    let (gx, gy) = (point[0] - b.position[0], point[1] - b.position[1]);
    let read = (c * gx + s * gy).hypot(-s * gx + c * gy);
    if reach > 0.0 && d > OUTPUT_REACH_RATIO * reach && read <= OUTPUT_REACH_RATIO * reach {
        let message = format!(
            "{at}, {} × as far as its joints ({} m), but read as a global point it lies on the body ({} m from its centroid at the pose given): is it given in global coordinates? clearsim takes the point in metres in the body's frame",
            g(d / reach, 3),
            g(reach, 3),
            g(read, 3)
        );
        return Some(Warning { field: field.to_string(), message });
    }
    None
}

/// What looks wrong against the mechanism's size (a resolved description): a body far lighter in
/// inertia than a bar over its centroid and attachment points (lengths in mm, inertia in kg m²),
/// a load point far outside its body, a journal radius or a bearing length of the order of the
/// whole mechanism.
pub fn findings(desc: &MechanismDesc) -> Vec<Warning> {
    let mut out = Vec::new();
    let attached = attachments(desc);
    for (b, points) in desc.bodies.iter().zip(&attached) {
        // The spread of the centroid (the origin of the body frame) and the attached points.
        let mut with_centroid = points.clone();
        with_centroid.push([0.0, 0.0]);
        let d = with_centroid.iter().flat_map(|p| with_centroid.iter().map(move |q| (p[0] - q[0]).hypot(p[1] - q[1]))).fold(0.0, f64::max);
        let bar = b.mass * d * d / 12.0;
        if bar > 0.0 && 0.0 < b.inertia && b.inertia < BAR_INERTIA_RATIO * bar {
            let field = format!("body '{}'.inertia", b.name);
            out.push(Warning {
                message: format!(
                    "{field} = {} kg m² is {} × a uniform bar's of its mass {} kg between its joint points {} m apart (m d²/12 = {} kg m²): are the points and positions in mm? clearsim takes metres (and kg m²)",
                    g(b.inertia, 6),
                    g(b.inertia / bar, 1),
                    g(b.mass, 6),
                    g(d, 3),
                    g(bar, 3)
                ),
                field,
            });
        }
    }
    for f in &desc.forces {
        let ForceDesc::Force { name, body, point, .. } = f else { continue };
        let reach = attached[*body].iter().map(|p| p[0].hypot(p[1])).fold(0.0, f64::max);
        let d = point[0].hypot(point[1]);
        if reach > 0.0 && d > LOAD_REACH_RATIO * reach {
            let field = format!("force '{name}'.point");
            out.push(Warning {
                message: format!(
                    "{field} = ({}, {}) m lies {} m from the centroid of body '{}', {} × as far as its joints ({} m): is it given in global coordinates or in mm? clearsim takes the point in metres in the body's frame",
                    g(point[0], 4),
                    g(point[1], 4),
                    g(d, 3),
                    desc.bodies[*body].name,
                    g(d / reach, 3),
                    g(reach, 3)
                ),
                field,
            });
        }
    }
    for f in &desc.forces {
        let profiles: Vec<(&str, &Profile)> = match f {
            ForceDesc::Force { fx, fy, .. } => vec![("fx", fx), ("fy", fy)],
            ForceDesc::Torque { magnitude, .. } => vec![("magnitude", magnitude)],
            _ => continue,
        };
        // Once a force: its two components share their table's angles.
        out.extend(profiles.into_iter().find_map(|(part, p)| angle_table_in_degrees(&format!("force '{}'.{part}", f.name()), p)));
    }
    let size = scale(desc);
    if !(size > 0.0) {
        return out;
    }
    for cj in &desc.clearance_joints {
        let j = format!("clearance joint '{}'", cj.name);
        if cj.journal_radius > JOURNAL_SPAN_RATIO * size {
            let field = format!("{j}.journal_radius");
            out.push(Warning { message: format!("{field} = {} m is larger than half the mechanism's span {} m: did you give mm? clearsim takes metres", g(cj.journal_radius, 6), g(size, 3)), field });
        }
        if let ClearanceModelDesc::Lubricated(l) = &cj.model {
            if l.length > LENGTH_SPAN_RATIO * size {
                let field = format!("{j}.length");
                out.push(Warning {
                    message: format!(
                        "{field} = {} m (the bearing's length) is more than {} × the mechanism's span {} m: did you give mm? clearsim takes metres",
                        g(l.length, 6),
                        g(LENGTH_SPAN_RATIO, 6),
                        g(size, 3)
                    ),
                    field,
                });
            }
        }
    }
    out
}

/// A load table over a body's angle whose period (or, without one, whose span) is 180, 360 or
/// 720: angles in degrees where clearsim takes radians (a 360 rad period is 57 turns).
fn angle_table_in_degrees(field: &str, p: &Profile) -> Option<Warning> {
    let Profile::Table { argument: TableArgument::Angle { .. }, table } = p else { return None };
    let (key, value) = match table.period {
        Some(period) => ("period", period),
        None => ("angle", table.x.last().copied().unwrap_or(0.0) - table.x.first().copied().unwrap_or(0.0)),
    };
    if !DEGREE_CYCLES.iter().any(|&d| (value - d).abs() <= 1e-9 * d) {
        return None;
    }
    let field = format!("{field}.{key}");
    let what = if key == "period" { format!("{field} = {} rad", g(value, 6)) } else { format!("{field} spans {} rad", g(value, 6)) };
    Some(Warning {
        message: format!(
            "{what} ({} turns of the crank): are the angles in degrees? clearsim takes a load table's angles in radians ({}° = {} rad)",
            g(value / std::f64::consts::TAU, 3),
            g(value, 6),
            g(value.to_radians(), 6)
        ),
        field,
    })
}
