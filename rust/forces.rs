//! Force elements and loads (docs/physics.md §10): translational and rotational
//! spring-dampers, applied forces and torques (constant or tabulated in time or a body's
//! angle: rust/table.rs) and motors with a linear speed–torque line. Compiled from
//! [`crate::description::ForceDesc`]; a model without force elements carries an empty list and
//! runs none of this code.

use crate::constraints::{BodyKin, V2};
use crate::description::{Harmonic, Profile, TableArgument};
use crate::table::Tabulated;

/// A scalar load, constant, tabulated or harmonic in time.
#[derive(Debug, Clone, PartialEq)]
pub enum Magnitude {
    Constant(f64),
    OfTime(Tabulated),
    OfAngle(u32, Tabulated),
    /// offset + amplitude · cos(ω t + phase): smooth, so no step ends anywhere for it.
    Harmonic(Harmonic),
}

impl Magnitude {
    /// The first corner of a time table strictly inside (t0, t1): the integrator ends a step
    /// there, as at a contact switch, so the kink costs no accuracy.
    pub fn time_break_in(&self, t0: f64, t1: f64) -> Option<f64> {
        match self {
            Magnitude::OfTime(tab) => tab.first_break_in(t0, t1),
            _ => None,
        }
    }

    pub fn new(p: &Profile) -> Self {
        match p {
            Profile::Constant { value } => Magnitude::Constant(*value),
            Profile::Table { argument: TableArgument::Time, table } => Magnitude::OfTime(Tabulated::new(table)),
            Profile::Table { argument: TableArgument::Angle { body }, table } => Magnitude::OfAngle(*body as u32, Tabulated::new(table)),
            Profile::Harmonic(h) => Magnitude::Harmonic(*h),
        }
    }

    #[inline]
    pub fn eval(&self, t: f64, kin: &[BodyKin]) -> f64 {
        match self {
            Magnitude::Constant(v) => *v,
            Magnitude::OfTime(tab) => tab.eval(t),
            Magnitude::OfAngle(b, tab) => tab.eval(kin[*b as usize].th),
            Magnitude::Harmonic(h) => h.value(t),
        }
    }
}

/// A compiled force element. Body indices are `None` for the ground.
#[derive(Debug, Clone, PartialEq)]
pub enum ForceElement {
    /// Tension F = k (ℓ − ℓ₀) + c ℓ̇ (or table(ℓ − ℓ₀) + c ℓ̇) along the line from a to b (§10.1).
    SpringDamper { a: Option<u32>, sa: V2, b: Option<u32>, sb: V2, stiffness: f64, damping: f64, free_length: f64, table: Option<Tabulated> },
    /// Torque on b T = −k (θ_b − θ_a − φ₀) − c (θ̇_b − θ̇_a), −T on a (§10.2).
    RotationalSpringDamper { a: Option<u32>, b: Option<u32>, stiffness: f64, damping: f64, free_angle: f64 },
    /// (F_x, F_y) at body point s, components in the global or the body frame (§10.3).
    Force { body: u32, s: V2, body_frame: bool, fx: Magnitude, fy: Magnitude },
    /// Torque on `body`, reacted on `reaction` (§10.3).
    Torque { body: u32, reaction: Option<u32>, magnitude: Magnitude },
    /// T = T_stall (1 − ω/ω₀) sign(ω₀) with ω the speed of `body` relative to `reaction` (§10.4).
    Motor { body: u32, reaction: Option<u32>, stall_torque: f64, no_load_speed: f64 },
}

#[inline]
fn get(kin: &[BodyKin], b: Option<u32>) -> BodyKin {
    b.map_or(BodyKin::GROUND, |i| kin[i as usize])
}

#[inline]
fn add(g: &mut [f64], b: Option<u32>, f: V2, torque: f64) {
    if let Some(b) = b {
        let o = 3 * b as usize;
        g[o] += f.x;
        g[o + 1] += f.y;
        g[o + 2] += torque;
    }
}

/// Geometry of a spring-damper: unit vector from a's point to b's, length and its rate.
#[inline]
fn spring_line(ka: &BodyKin, sa: V2, kb: &BodyKin, sb: V2) -> (V2, V2, V2, f64, f64) {
    let (pa, pb) = (ka.point(sa), kb.point(sb));
    let d = pb.sub(pa);
    let len = d.norm();
    let u = if len > 0.0 { d.scale(1.0 / len) } else { V2::new(0.0, 0.0) };
    let rate = kb.point_velocity(sb).sub(ka.point_velocity(sa)).dot(u);
    (pa, pb, u, len, rate)
}

impl ForceElement {
    /// The first corner of this element's time table strictly inside (t0, t1), if any.
    pub fn time_break_in(&self, t0: f64, t1: f64) -> Option<f64> {
        match self {
            ForceElement::Force { fx, fy, .. } => match (fx.time_break_in(t0, t1), fy.time_break_in(t0, t1)) {
                (Some(a), Some(b)) => Some(a.min(b)),
                (a, b) => a.or(b),
            },
            ForceElement::Torque { magnitude, .. } => magnitude.time_break_in(t0, t1),
            _ => None,
        }
    }

    /// The spring-damper's tension \[N\] (positive pulls the points together), or the rotational
    /// element's torque on b [N m]; the applied load's magnitude otherwise.
    pub fn value(&self, t: f64, kin: &[BodyKin]) -> f64 {
        match self {
            ForceElement::SpringDamper { a, sa, b, sb, stiffness, damping, free_length, table } => {
                let (_, _, _, len, rate) = spring_line(&get(kin, *a), *sa, &get(kin, *b), *sb);
                let delta = len - free_length;
                table.as_ref().map_or(stiffness * delta, |tab| tab.eval(delta)) + damping * rate
            }
            ForceElement::RotationalSpringDamper { a, b, stiffness, damping, free_angle } => {
                let (ka, kb) = (get(kin, *a), get(kin, *b));
                -stiffness * (kb.th - ka.th - free_angle) - damping * (kb.w - ka.w)
            }
            ForceElement::Force { fx, fy, .. } => fx.eval(t, kin).hypot(fy.eval(t, kin)),
            ForceElement::Torque { magnitude, .. } => magnitude.eval(t, kin),
            ForceElement::Motor { body, reaction, stall_torque, no_load_speed } => {
                let w = kin[*body as usize].w - get(kin, *reaction).w;
                stall_torque * no_load_speed.signum() * (1.0 - w / no_load_speed)
            }
        }
    }

    /// An applied force's global vector [N] (zero for the other elements).
    #[inline]
    fn applied(&self, t: f64, kin: &[BodyKin]) -> V2 {
        match self {
            ForceElement::Force { body, body_frame, fx, fy, .. } => {
                let f = V2::new(fx.eval(t, kin), fy.eval(t, kin));
                if *body_frame {
                    kin[*body as usize].rot(f)
                } else {
                    f
                }
            }
            _ => V2::new(0.0, 0.0),
        }
    }

    /// Add this element's generalised forces to `g` (3 per body).
    #[inline]
    /// The two bodies of an element whose force depends on the state (spring-dampers,
    /// rotational spring-dampers, motors: their stiffness and damping go into the implicit
    /// methods' Newton matrix); `None` for loads that depend on time or a driver's angle only.
    pub fn stiff_bodies(&self) -> Option<[Option<u32>; 2]> {
        match self {
            ForceElement::SpringDamper { a, b, .. } | ForceElement::RotationalSpringDamper { a, b, .. } => Some([*a, *b]),
            ForceElement::Motor { body, reaction, .. } => Some([Some(*body), *reaction]),
            ForceElement::Force { .. } | ForceElement::Torque { .. } => None,
        }
    }

    pub fn apply(&self, t: f64, kin: &[BodyKin], g: &mut [f64]) {
        match self {
            ForceElement::SpringDamper { a, sa, b, sb, .. } => {
                let (ka, kb) = (get(kin, *a), get(kin, *b));
                let (_, _, u, _, _) = spring_line(&ka, *sa, &kb, *sb);
                let f = u.scale(self.value(t, kin)); // on a, towards b
                add(g, *a, f, ka.rot(*sa).cross(f));
                let fb = f.scale(-1.0);
                add(g, *b, fb, kb.rot(*sb).cross(fb));
            }
            ForceElement::RotationalSpringDamper { a, b, .. } => {
                let tq = self.value(t, kin);
                add(g, *b, V2::new(0.0, 0.0), tq);
                add(g, *a, V2::new(0.0, 0.0), -tq);
            }
            ForceElement::Force { body, s, .. } => {
                let k = kin[*body as usize];
                let f = self.applied(t, kin);
                add(g, Some(*body), f, k.rot(*s).cross(f));
            }
            ForceElement::Torque { body, reaction, .. } | ForceElement::Motor { body, reaction, .. } => {
                let tq = self.value(t, kin);
                add(g, Some(*body), V2::new(0.0, 0.0), tq);
                add(g, *reaction, V2::new(0.0, 0.0), -tq);
            }
        }
    }

    /// Power \[W\] this element feeds into the mechanism that is not the rate of a potential:
    /// the damper part of a spring-damper (≤ 0), the applied loads and motors. A spring's
    /// elastic part is counted in [`ForceElement::potential`] instead.
    pub fn power(&self, t: f64, kin: &[BodyKin]) -> f64 {
        match self {
            ForceElement::SpringDamper { a, sa, b, sb, damping, .. } => {
                let (_, _, _, _, rate) = spring_line(&get(kin, *a), *sa, &get(kin, *b), *sb);
                -damping * rate * rate
            }
            ForceElement::RotationalSpringDamper { a, b, damping, .. } => {
                let w = get(kin, *b).w - get(kin, *a).w;
                -damping * w * w
            }
            ForceElement::Force { body, s, .. } => self.applied(t, kin).dot(kin[*body as usize].point_velocity(*s)),
            ForceElement::Torque { body, reaction, .. } | ForceElement::Motor { body, reaction, .. } => {
                self.value(t, kin) * (kin[*body as usize].w - get(kin, *reaction).w)
            }
        }
    }

    /// Elastic energy \[J\] stored in a spring; 0 for the other elements.
    pub fn potential(&self, kin: &[BodyKin]) -> f64 {
        match self {
            ForceElement::SpringDamper { a, sa, b, sb, stiffness, free_length, table, .. } => {
                let (_, _, _, len, _) = spring_line(&get(kin, *a), *sa, &get(kin, *b), *sb);
                let delta = len - free_length;
                table.as_ref().map_or(0.5 * stiffness * delta * delta, |tab| tab.integral_from_zero(delta))
            }
            ForceElement::RotationalSpringDamper { a, b, stiffness, free_angle, .. } => {
                let d = get(kin, *b).th - get(kin, *a).th - free_angle;
                0.5 * stiffness * d * d
            }
            _ => 0.0,
        }
    }

    /// Which work column of [`crate::energy::ENERGY_COLUMNS`] this element's power goes to:
    /// 0 loads (forces, torques), 1 motors, 3 dampers.
    pub fn work_column(&self) -> usize {
        match self {
            ForceElement::SpringDamper { .. } | ForceElement::RotationalSpringDamper { .. } => 3,
            ForceElement::Motor { .. } => 1,
            ForceElement::Force { .. } | ForceElement::Torque { .. } => 0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spring_force_pulls_points_together_and_its_power_is_minus_the_energy_rate() {
        // Ground point at the origin, body point at (0.3, 0.4) moving at (1, 2): ℓ = 0.5, ℓ̇ = 2.2.
        let e = ForceElement::SpringDamper { a: None, sa: V2::new(0.0, 0.0), b: Some(0), sb: V2::new(0.0, 0.0), stiffness: 100.0, damping: 2.0, free_length: 0.4, table: None };
        let kin = [BodyKin::new(&[0.3, 0.4, 0.0], &[1.0, 2.0, 0.0])];
        let tension = 100.0 * 0.1 + 2.0 * 2.2;
        assert!((e.value(0.0, &kin) - tension).abs() < 1e-12);
        let mut g = [0.0; 3];
        e.apply(0.0, &kin, &mut g);
        assert!((g[0] + tension * 0.6).abs() < 1e-12 && (g[1] + tension * 0.8).abs() < 1e-12);
        assert!((e.power(0.0, &kin) + 2.0 * 2.2 * 2.2).abs() < 1e-12);
        assert!((e.potential(&kin) - 0.5 * 100.0 * 0.01).abs() < 1e-12);
    }

    #[test]
    fn harmonic_torque_is_offset_plus_amplitude_cosine() {
        let h = Harmonic { amplitude: 1.5, omega: 2.0 / 3.0, phase: 0.3, offset: -0.2 };
        let e = ForceElement::Torque { body: 0, reaction: None, magnitude: Magnitude::new(&Profile::Harmonic(h)) };
        let kin = [BodyKin::new(&[0.0; 3], &[0.0, 0.0, 2.0])];
        for t in [0.0, 1.0, 7.3] {
            let want = -0.2 + 1.5 * (2.0 / 3.0 * t + 0.3f64).cos();
            assert!((e.value(t, &kin) - want).abs() < 1e-15);
            assert!((e.power(t, &kin) - 2.0 * want).abs() < 1e-14);
            assert_eq!(e.time_break_in(0.0, 100.0), None);
        }
    }

    #[test]
    fn motor_torque_line() {
        let m = ForceElement::Motor { body: 0, reaction: None, stall_torque: 10.0, no_load_speed: -100.0 };
        let at = |w: f64| m.value(0.0, &[BodyKin::new(&[0.0; 3], &[0.0, 0.0, w])]);
        assert_eq!(at(0.0), -10.0);
        assert!((at(-50.0) + 5.0).abs() < 1e-12);
        assert!(at(-100.0).abs() < 1e-12);
        assert!(at(-150.0) > 0.0); // above no-load speed it brakes
    }
}
