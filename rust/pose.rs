//! The pose given, checked against its assembly (docs/physics.md §1, "Initial state"): a body
//! the assembly at t = 0 moves far from where it was given is an error naming the body and the
//! joint whose two points lie furthest apart at the pose given; smaller mismatches (a joint's
//! points more than 1 % of the mechanism's span apart, a body turned by more than 2°) are a
//! [`Warning`] naming the joint and both its points, body frame and global. A joint point given
//! in the global instead of the body frame, or a wrong length, is the usual cause.

use crate::assembly::span;
use crate::compile::plausibility::{ends, global};
use crate::text::g;
use crate::description::{BodyRef, JointDesc, MechanismDesc};
use crate::error::{Error, Warning};

/// Largest rotation \[rad\] of a body by the assembly before the pose given counts as wrong.
pub const ASSEMBLY_TURN: f64 = 0.5;
/// The default assembly tolerance: the largest move of a body, as a fraction of the span.
pub const ASSEMBLY_TOLERANCE: f64 = 0.2;
/// Above these the pose given draws a warning: a joint whose two points lie further apart than
/// this fraction of the mechanism's span, or a body that the assembly turns by more than this
/// angle \[rad\].
pub const POSE_GAP_WARNING: f64 = 0.01;
pub const POSE_TURN_WARNING: f64 = 2.0 * std::f64::consts::PI / 180.0;
/// A joint named as the cause of a body moved too far must have its points at least this
/// fraction of the span apart.
const GAP_CULPRIT: f64 = 0.05;

/// A two-point joint at the pose given: its name, its bodies, how far its two points lie apart
/// \[m\] (a prismatic joint: the slider's point off the guide line; a clearance joint: from its
/// bearing's centre or its initial eccentricity, whichever is nearer), each point as given (body
/// frame) and where it lies (global).
struct Gap {
    joint: String,
    bodies: [BodyRef; 2],
    gap: f64,
    local: [[f64; 2]; 2],
    world: [(f64, f64); 2],
}

/// The revolute, prismatic and clearance joints at the pose given (before assembly).
fn gaps(desc: &MechanismDesc) -> Vec<Gap> {
    let mut out = Vec::new();
    for j in &desc.joints {
        let (ba, pa, bb, pb) = ends(j);
        let (a, b) = (global(desc, ba, pa), global(desc, bb, pb));
        let gap = match j {
            JointDesc::Revolute { .. } => (a.0 - b.0).hypot(a.1 - b.1),
            JointDesc::Prismatic { axis, .. } => {
                let th = ba.map_or(0.0, |k| desc.bodies[k].angle);
                let (s, c) = th.sin_cos();
                let u = (c * axis[0] - s * axis[1], s * axis[0] + c * axis[1]);
                (u.0 * (b.1 - a.1) - u.1 * (b.0 - a.0)).abs() / u.0.hypot(u.1).max(1e-300)
            }
        };
        out.push(Gap { joint: j.name().to_string(), bodies: [ba, bb], gap, local: [pa, pb], world: [a, b] });
    }
    for c in &desc.clearance_joints {
        let (a, b) = (global(desc, c.bearing_body, c.bearing_point), global(desc, c.journal_body, c.journal_point));
        // The journal may be given centred or at its initial eccentricity e0 (the assembly puts it there).
        let e0 = c.initial_eccentricity;
        let gap = (b.0 - a.0).hypot(b.1 - a.1).min((b.0 - a.0 - e0[0]).hypot(b.1 - a.1 - e0[1]));
        out.push(Gap { joint: c.name.clone(), bodies: [c.bearing_body, c.journal_body], gap, local: [c.bearing_point, c.journal_point], world: [a, b] });
    }
    out
}

/// Both points of a joint, as given (body frame) and where they lie (global) \[m\].
fn points_text(gap: &Gap, desc: &MechanismDesc) -> String {
    let pair = |x: f64, y: f64| format!("({}, {})", g(x, 4), g(y, 4));
    let body = |b: BodyRef| b.map_or_else(|| "the ground".to_string(), |k| format!("body '{}'", desc.bodies[k].name));
    (0..2)
        .map(|k| format!("point {} on {} lies at {} (global)", pair(gap.local[k][0], gap.local[k][1]), body(gap.bodies[k]), pair(gap.world[k].0, gap.world[k].1)))
        .collect::<Vec<_>>()
        .join("; ")
}

/// The first of `gaps` with the largest gap.
fn widest<'a>(gaps: impl Iterator<Item = &'a Gap>) -> Option<&'a Gap> {
    gaps.fold(None, |best: Option<&Gap>, g| if best.is_none_or(|b| g.gap > b.gap) { Some(g) } else { best })
}

/// Check the pose given in `desc` (resolved) against `q0`, its assembly at t = 0 (3 per body),
/// with the assembly `tolerance` (a fraction of the span; `None` accepts any pose): an
/// [`Error::PoseMoved`] for a body moved further (or turned by more than [`ASSEMBLY_TURN`]), or
/// else at most one [`Warning`] for a pose that assembles but looks wrong.
pub fn check(desc: &MechanismDesc, q0: &[f64], tolerance: Option<f64>) -> Result<Option<Warning>, Error> {
    let Some(tol) = tolerance else { return Ok(None) };
    if !q0.iter().all(|v| v.is_finite()) || desc.bodies.is_empty() {
        return Ok(None);
    }
    let guess: Vec<f64> = desc.bodies.iter().flat_map(|b| [b.position[0], b.position[1], b.angle]).collect();
    let span = if desc.bodies.len() > 1 { span(&guess) } else { 1.0 };
    let moved: Vec<f64> = (0..desc.bodies.len()).map(|k| (q0[3 * k] - guess[3 * k]).hypot(q0[3 * k + 1] - guess[3 * k + 1])).collect();
    let turned: Vec<f64> = (0..desc.bodies.len())
        .map(|k| ((q0[3 * k + 2] - guess[3 * k + 2] + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI).abs())
        .collect();
    let k = argmax((0..moved.len()).map(|k| moved[k] / span + turned[k] / ASSEMBLY_TURN));
    let gaps = gaps(desc);
    if moved[k] <= tol * span && turned[k] <= ASSEMBLY_TURN {
        return Ok(warning(desc, &gaps, &turned, span));
    }
    let name = desc.bodies[k].name.clone();
    let culprit = widest(gaps.iter()).filter(|c| c.gap > GAP_CULPRIT * span);
    let because = culprit.map_or_else(String::new, |c| {
        format!("; joint '{}' has its two points {} m apart at the poses given ({})", c.joint, g(c.gap, 3), points_text(c, desc))
    });
    let message = format!(
        "the assembly of the pose given (the pose at t = 0) moves body '{name}' by {} m and {}° (tolerance: {} × the mechanism's span {} m, or {}°){because}: check the joint points (body frame, not global) and the lengths, or give poses nearer the assembled ones (m.assembly_tolerance = None accepts any)",
        g(moved[k], 3),
        g(turned[k].to_degrees(), 3),
        g(tol, 6),
        g(span, 3),
        g(ASSEMBLY_TURN.to_degrees(), 3),
    );
    let (field, value) = match culprit {
        Some(c) => (format!("joint '{}'", c.joint), c.gap),
        None => (format!("body '{name}'.position"), moved[k]),
    };
    Err(Error::PoseMoved { body: name, joint: culprit.map(|c| c.joint.clone()), moved: moved[k], turned: turned[k], field, value, message })
}

/// The first index of the largest value (NaN never wins).
fn argmax(values: impl Iterator<Item = f64>) -> usize {
    values.enumerate().fold((0, f64::NEG_INFINITY), |best, (k, v)| if v > best.1 { (k, v) } else { best }).0
}

/// The warning of a pose given that assembles but looks wrong: the joint whose points lie
/// furthest apart beyond [`POSE_GAP_WARNING`] × span, or else the joint of a body the assembly
/// turns by more than [`POSE_TURN_WARNING`].
fn warning(desc: &MechanismDesc, gaps: &[Gap], turned: &[f64], span: f64) -> Option<Warning> {
    let far: Vec<&Gap> = gaps.iter().filter(|g| g.gap > POSE_GAP_WARNING * span).collect();
    let k = argmax(turned.iter().copied());
    let (joint, what) = if let Some(j) = widest(far.iter().copied()) {
        (j, format!("joint '{}' has its two points {} m apart ({} % of the mechanism's span {} m)", j.joint, g(j.gap, 3), g(100.0 * j.gap / span, 3), g(span, 3)))
    } else if turned.get(k).is_some_and(|t| *t > POSE_TURN_WARNING) {
        let j = widest(gaps.iter().filter(|g| g.bodies.contains(&Some(k))))?;
        (j, format!("the assembly turns body '{}' by {}° (its joint '{}' has its points {} m apart)", desc.bodies[k].name, g(turned[k].to_degrees(), 3), j.joint, g(j.gap, 3)))
    } else {
        return None;
    };
    let others: Vec<String> = far.iter().filter(|o| !std::ptr::eq(**o, joint)).map(|o| format!("'{}' {} m", o.joint, g(o.gap, 3))).collect();
    let also = if others.is_empty() { String::new() } else { format!("; also apart: {}", others.join(", ")) };
    Some(Warning {
        field: String::new(),
        message: format!(
            "clearsim: the pose given looks wrong: {what}: {}{also}. Joint points are given in each body's own frame (a point given in global coordinates, or a wrong length, is the usual cause); the run goes on from the assembled pose (m.assembly_tolerance = None silences this)",
            points_text(joint, desc)
        ),
    })
}

#[cfg(all(test, feature = "serde"))]
mod tests {
    use super::check;
    use crate::description::{from_json, JointDesc, MechanismDesc};
    use crate::error::Error;
    use crate::model::Model;

    fn slider_crank() -> MechanismDesc {
        from_json(include_str!("../tests/data/slider_crank_dry.json")).unwrap()
    }

    fn assembled(desc: &MechanismDesc) -> Vec<f64> {
        Model::compile(desc).unwrap().start.unwrap().unwrap()
    }

    /// The crank's pin at `pin` (body frame; its right place is (0.025, 0)).
    fn with_pin(pin: [f64; 2]) -> MechanismDesc {
        let mut d = slider_crank();
        for j in &mut d.joints {
            if let JointDesc::Revolute { name, point_a, .. } = j {
                if name == "crank-rod" {
                    *point_a = pin;
                }
            }
        }
        d
    }

    #[test]
    fn a_pose_that_assembles_where_given_passes() {
        let d = slider_crank();
        assert_eq!(check(&d, &assembled(&d), Some(0.2)), Ok(None));
    }

    #[test]
    fn a_point_given_in_the_global_frame_is_named() {
        // 0.05 (the pin's global x) for 0.025: a gap of 0.025 m, 15 % of the span 0.145 m.
        let d = with_pin([0.05, 0.0]);
        let w = check(&d, &assembled(&d), Some(0.2)).unwrap().expect("a warning");
        assert!(w.message.starts_with("clearsim: the pose given looks wrong: joint 'crank-rod' has its two points 0.025 m apart"), "{}", w.message);
        assert!(w.message.contains("point (0.05, 0) on body 'crank' lies at (0.075, 0) (global)"), "{}", w.message);
        // Far beyond: the assembly moves a body more than the tolerance, an error naming the joint.
        let d = with_pin([0.1, 0.0]);
        match check(&d, &assembled(&d), Some(0.2)) {
            Err(Error::PoseMoved { joint, field, .. }) => {
                assert_eq!(joint.as_deref(), Some("crank-rod"));
                assert_eq!(field, "joint 'crank-rod'");
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(check(&d, &assembled(&d), None), Ok(None)); // no tolerance: any pose
    }
}
