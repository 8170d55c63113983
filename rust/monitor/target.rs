//! What a monitor watches ([`Target`]): a body coordinate, a point fixed on a body, a clearance
//! joint, or an ideal joint's or driver's reaction, and how its error against a reference state
//! is formed. The same function is evaluated
//! on the sample's state and on the reference's ([`Kinematics`]: a state read by coordinate), so
//! any body target — a centroid coordinate or a tool point — is measured the same way.
//!
//! A point P fixed on body b at `p` (body frame \[m\]), with the body's pose (r, θ) and
//! A(θ) its rotation, B = dA/dθ:
//!
//! * displacement  r + A p
//! * velocity      ṙ + θ̇ B p
//! * acceleration  r̈ + θ̈ B p − θ̇² A p
//!
//! in the global frame; its component x or y, or the magnitude: of the error vector
//! |P − P_ref| against a reference, of the vector itself without one.

use super::Quantity;

/// A mechanism state read by coordinate (3 per body: x, y, θ, in the model's body order):
/// the positions q, velocities q̇ and accelerations q̈.
pub trait Kinematics {
    fn q(&self, c: usize) -> f64;
    fn qd(&self, c: usize) -> f64;
    fn qdd(&self, c: usize) -> f64;
}

/// A state held as y = (q, q̇) with q̈ beside it (`qdd` is read only for accelerations).
pub struct State<'a> {
    pub y: &'a [f64],
    pub qdd: &'a [f64],
    /// 3 × bodies: where q̇ starts in `y`.
    pub nq: usize,
}

impl Kinematics for State<'_> {
    fn q(&self, c: usize) -> f64 {
        self.y[c]
    }
    fn qd(&self, c: usize) -> f64 {
        self.y[self.nq + c]
    }
    fn qdd(&self, c: usize) -> f64 {
        self.qdd[c]
    }
}

/// Which part of a point's motion is watched.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize), serde(rename_all = "snake_case"))]
pub enum PointComponent {
    X,
    Y,
    /// |P − P_ref| against a reference, |P| without one.
    Magnitude,
}

/// What a monitor watches.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    /// Coordinate `c` of q (3 per body: x, y, θ): its displacement, velocity or acceleration.
    Coordinate(usize),
    /// A point fixed on body `body` at `at` (body frame \[m\]).
    Point { body: usize, at: [f64; 2], component: PointComponent },
    /// Clearance joint `j` (a joint quantity: [`Quantity::of_joint`]).
    Joint(usize),
    /// What ideal joint or driver `constraint` (model order: joints, then drivers) exerts on its
    /// second body ([`crate::constraints::Constraint::reaction`], from the KKT solve's λ): its
    /// force's `component` ([`Quantity::Force`] \[N\], global frame) or its couple
    /// ([`Quantity::Torque`] \[N m\]; `component` is then not read).
    Reaction { constraint: usize, component: PointComponent },
}

impl Target {
    /// The body whose coordinates the target reads (`None` for a joint).
    pub fn body(&self) -> Option<usize> {
        match *self {
            Target::Coordinate(c) => Some(c / 3),
            Target::Point { body, .. } => Some(body),
            Target::Joint(_) | Target::Reaction { .. } => None,
        }
    }

    /// The error of a body target's `quantity` at the state `sample` against the state
    /// `reference` (module doc); without a reference, the value itself.
    #[inline]
    pub fn error<S: Kinematics, R: Kinematics>(&self, quantity: Quantity, sample: &S, reference: Option<&R>) -> f64 {
        match *self {
            Target::Coordinate(c) => {
                let v = coordinate(quantity, sample, c);
                match reference {
                    Some(r) => v - coordinate(quantity, r, c),
                    None => v,
                }
            }
            Target::Point { body, at, component } => {
                let p = point(quantity, sample, body, at);
                let e = match reference {
                    Some(r) => {
                        let pr = point(quantity, r, body, at);
                        [p[0] - pr[0], p[1] - pr[1]]
                    }
                    None => p,
                };
                match component {
                    PointComponent::X => e[0],
                    PointComponent::Y => e[1],
                    PointComponent::Magnitude => e[0].hypot(e[1]),
                }
            }
            // joint quantities and reactions are read by the run (observe.rs)
            Target::Joint(_) | Target::Reaction { .. } => f64::NAN,
        }
    }
}

/// Coordinate `c`'s displacement, velocity or acceleration.
#[inline]
fn coordinate<S: Kinematics>(quantity: Quantity, s: &S, c: usize) -> f64 {
    match quantity {
        Quantity::Displacement => s.q(c),
        Quantity::Velocity => s.qd(c),
        _ => s.qdd(c),
    }
}

/// The global displacement, velocity or acceleration of the point `at` (body frame) of `body`.
#[inline]
pub fn point<S: Kinematics>(quantity: Quantity, s: &S, body: usize, at: [f64; 2]) -> [f64; 2] {
    let (x, y, th) = (3 * body, 3 * body + 1, 3 * body + 2);
    let (sin, cos) = s.q(th).sin_cos();
    // A p and B p = dA/dθ p = (−(A p)_y, (A p)_x).
    let ap = [cos * at[0] - sin * at[1], sin * at[0] + cos * at[1]];
    let bp = [-ap[1], ap[0]];
    match quantity {
        Quantity::Displacement => [s.q(x) + ap[0], s.q(y) + ap[1]],
        Quantity::Velocity => {
            let w = s.qd(th);
            [s.qd(x) + w * bp[0], s.qd(y) + w * bp[1]]
        }
        _ => {
            let (w, alpha) = (s.qd(th), s.qdd(th));
            [s.qdd(x) + alpha * bp[0] - w * w * ap[0], s.qdd(y) + alpha * bp[1] - w * w * ap[1]]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A crank turning at constant ω about the origin, its centroid at the pivot: the tip at
    /// (r, 0) moves on a circle with |v| = ω r and |a| = ω² r, pointing to the pivot.
    #[test]
    fn tip_of_a_constant_speed_crank() {
        let (w, r, t) = (7.0, 0.3, 0.41);
        let y = [0.0, 0.0, w * t, 0.0, 0.0, w];
        let qdd = [0.0, 0.0, 0.0];
        let s = State { y: &y, qdd: &qdd, nq: 3 };
        let target = |component| Target::Point { body: 0, at: [r, 0.0], component };
        let none: Option<&State> = None;
        let p = point(Quantity::Displacement, &s, 0, [r, 0.0]);
        assert!((p[0] - r * (w * t).cos()).abs() < 1e-15 && (p[1] - r * (w * t).sin()).abs() < 1e-15);
        let v = target(PointComponent::Magnitude).error(Quantity::Velocity, &s, none);
        let a = target(PointComponent::Magnitude).error(Quantity::Acceleration, &s, none);
        assert!((v - w * r).abs() < 1e-14 && (a - w * w * r).abs() < 1e-13, "{v} {a}");
        let ax = target(PointComponent::X).error(Quantity::Acceleration, &s, none);
        assert!((ax + w * w * r * (w * t).cos()).abs() < 1e-13);
        // Against itself the error is zero; a coordinate target reads the coordinate.
        assert_eq!(target(PointComponent::Magnitude).error(Quantity::Displacement, &s, Some(&s)), 0.0);
        assert_eq!(Target::Coordinate(2).error(Quantity::Velocity, &s, none), w);
    }
}
