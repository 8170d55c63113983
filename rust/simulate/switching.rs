//! Where a run's right-hand side stops being smooth inside a step (docs/physics.md §3): a clearance
//! joint's contact starting or ending, its slip crossing a corner of the friction ramp, a corner of
//! a time-tabulated load; located on the step's dense output, and the impact memory they change.

use super::MechanismSystem;
use crate::clearance::{grazing, JointKinematics};
use crate::error::{Error, Result};
use crate::integrate::DenseOutput;

/// Sub-intervals of a step in which [`MechanismSystem::first_switch`] looks for switches.
const SWITCH_SAMPLES: usize = 4;

/// A joint out of contact at both ends of a step cannot touch inside it when the cubic through
/// its penetration δ and rate δ̇ at the ends stays below zero with this much to spare: the
/// cubic lies within (4/27)(|δ̇0| + |δ̇1|)Δt of the larger end value (the bound of the Hermite
/// basis functions), and this factor widens that for the dense output's own deviation from it.
const QUIET_WIDENING: f64 = 2.0;

/// Whether joint kinematics `a`, `b` at the ends of a step `dt` long show a journal clear of
/// its wall throughout: then no switch (contact onset; the friction ramp's corners are crossed
/// only in contact) can lie inside the step, and the step needs no samples between its ends.
fn clear_throughout(a: &JointKinematics, b: &JointKinematics, dt: f64, gap_resolution: f64) -> bool {
    let reach = QUIET_WIDENING * 4.0 / 27.0 * (a.delta_dot.abs() + b.delta_dot.abs()) * dt;
    a.delta.max(b.delta) + reach + gap_resolution < 0.0
}

impl MechanismSystem<'_> {
    /// The first switching point inside the step
    /// ([`OdeSystem::switching_point`](crate::integrate::OdeSystem::switching_point)): a
    /// clearance joint's contact starting or ending, or the slip crossing a corner of the
    /// friction ramp — where the joint force stops being smooth — or a corner of a load table.
    ///
    /// The switching functions are sampled at the step's ends and at `SWITCH_SAMPLES − 1`
    /// interior points of the dense output, so that a switch crossed twice inside one step (a
    /// whole short contact, a slip reversal through the friction ramp) is seen too; the first
    /// crossing is located in the first sub-interval that has one.
    pub(super) fn first_switch(&mut self, t0: f64, y0: &[f64], t1: f64, y1: &[f64], dense: &dyn DenseOutput) -> Result<Option<f64>> {
        // Corners of time-tabulated loads (docs/physics.md §10.3) end a step like a switch.
        let t_break = self.model.forces.iter().filter_map(|f| f.time_break_in(t0, t1)).reduce(f64::min);
        let Some(tb) = t_break else {
            return self.joint_switch(t0, y0, t1, y1, dense);
        };
        let mut end = std::mem::take(&mut self.scratch2);
        end.resize(y0.len(), 0.0);
        dense.eval(tb, &mut end);
        let joint = self.joint_switch(t0, y0, tb, &end, dense);
        self.scratch2 = end;
        Ok(joint?.or(t_break))
    }

    /// The first switch of a clearance joint in (t0, t1] (see [`Self::first_switch`]).
    fn joint_switch(&mut self, t0: f64, y0: &[f64], t1: f64, y1: &[f64], dense: &dyn DenseOutput) -> Result<Option<f64>> {
        let nj = self.memory.len();
        for j in 0..nj {
            self.switch_prev[j] = (t0, self.joint_kinematics(j, y0));
        }
        // Journals clear of their walls at both ends with room to spare (a lubricated one in its
        // film, a dry one in free flight) cannot switch inside the step: no samples between.
        let mut quiet = true;
        for j in 0..nj {
            self.switch_end[j] = self.joint_kinematics(j, y1);
            quiet &= clear_throughout(&self.switch_prev[j].1, &self.switch_end[j], t1 - t0, self.gap_resolution);
        }
        if quiet {
            return Ok(None);
        }
        for i in 1..=SWITCH_SAMPLES {
            let tb = if i == SWITCH_SAMPLES { t1 } else { t0 + (t1 - t0) * i as f64 / SWITCH_SAMPLES as f64 };
            let mut s = std::mem::take(&mut self.scratch);
            let yb: &[f64] = if i == SWITCH_SAMPLES {
                y1
            } else {
                dense.eval_components(tb, &self.switch_components, &mut s);
                &s
            };
            for j in 0..nj {
                self.switch_next[j] = if i == SWITCH_SAMPLES { self.switch_end[j] } else { self.joint_kinematics(j, yb) };
            }
            self.scratch = s;
            // Sub-intervals are visited in time order: the first with a switch holds the earliest.
            let mut first: Option<f64> = None;
            for j in 0..nj {
                let (a, b) = (self.switch_prev[j], (tb, self.switch_next[j]));
                if let Some(ts) = self.first_switch_between(j, a, b, dense) {
                    first = Some(first.map_or(ts, |f| f.min(ts)));
                }
                self.switch_prev[j] = b;
            }
            if first.is_some() {
                return Ok(first);
            }
        }
        Ok(None)
    }

    /// The time in `[ta, tb]` where the switching function `g` of joint `j`'s kinematics
    /// changes sign (`g` at the two ends of opposite signs), by Illinois (modified regula falsi)
    /// on g(t) through the dense output; `tol` is an absolute tolerance on g. Returns the time
    /// and the joint's kinematics there.
    fn locate_crossing(
        &mut self,
        j: usize,
        g: impl Fn(&JointKinematics) -> f64,
        tol: f64,
        (mut ta, ka): (f64, JointKinematics),
        (mut tb, kb): (f64, JointKinematics),
        dense: &dyn DenseOutput,
    ) -> (f64, JointKinematics) {
        // Orient so that g(ta) ≤ 0 < g(tb).
        let sign = if g(&kb) > 0.0 { 1.0 } else { -1.0 };
        let (mut fa, mut fb) = (sign * g(&ka), sign * g(&kb));
        let (t_lo, t_hi) = (ta, tb);
        let mut side = 0i8;
        let mut kin = kb;
        let mut tm = tb;
        for _ in 0..60 {
            tm = (ta * fb - tb * fa) / (fb - fa);
            if !(tm.is_finite() && tm > ta && tm < tb) {
                tm = 0.5 * (ta + tb);
            }
            let mut s = std::mem::take(&mut self.scratch);
            dense.eval(tm, &mut s);
            kin = self.joint_kinematics(j, &s);
            self.scratch = s;
            let fm = sign * g(&kin);
            if fm > 0.0 {
                tb = tm;
                fb = fm;
                if side == 1 {
                    fa *= 0.5;
                }
                side = 1;
            } else {
                ta = tm;
                fa = fm;
                if side == -1 {
                    fb *= 0.5;
                }
                side = -1;
            }
            if (tb - ta) <= 1e-14 * (1.0 + t_hi.abs()) || fm.abs() <= tol {
                break;
            }
        }
        (tm.clamp(t_lo, t_hi), kin)
    }

    /// Locate where contact starts or ends (δ changes sign) inside a step: time and kinematics.
    fn locate_contact_change(&mut self, j: usize, start: (f64, JointKinematics), end: (f64, JointKinematics), dense: &dyn DenseOutput) -> (f64, JointKinematics) {
        let tol = 1e-15 * self.model.clearance[j].clearance;
        self.locate_crossing(j, |k| k.delta, tol, start, end, dense)
    }

    /// The first switching point of joint `j` between two samples `a`, `b` of a step: contact
    /// starting or ending (δ changes sign), or, in contact at both, the slip crossing a corner
    /// of the friction ramp (±v0, ±v1, P5).
    fn first_switch_between(
        &mut self,
        j: usize,
        a: (f64, JointKinematics),
        b: (f64, JointKinematics),
        dense: &dyn DenseOutput,
    ) -> Option<f64> {
        let (ka, kb) = (&a.1, &b.1);
        if (ka.delta > 0.0) != (kb.delta > 0.0) {
            if grazing(ka, kb, self.gap_resolution, self.model.clearance[j].contact.impact_speed_floor) {
                return None;
            }
            return Some(self.locate_contact_change(j, a, b, dense).0);
        }
        let fr = self.model.clearance[j].friction;
        if ka.delta <= 0.0 || fr.friction_coefficient <= 0.0 {
            return None;
        }
        let mut first: Option<f64> = None;
        for v in [-fr.v1, -fr.v0, fr.v0, fr.v1] {
            if (ka.slip > v) != (kb.slip > v) {
                let tol = 1e-12 * fr.v1.abs().max(1e-12);
                let ts = self.locate_crossing(j, |k| k.slip - v, tol, a, b, dense).0;
                first = Some(first.map_or(ts, |f| f.min(ts)));
            }
        }
        first
    }

    /// The impact memory after the accepted step (t0, t1]: a contact that starts inside it
    /// records its approach speed δ̇⁽⁻⁾ at the located onset (docs/physics.md §3, P3), one that
    /// ends is cleared; a penetration beyond the joint's limit stops the run. `true` when an
    /// impact began (the integrator restarts its step-size history).
    pub(super) fn update_contacts(&mut self, t0: f64, y0: &[f64], t1: f64, y1: &[f64], dense: &dyn DenseOutput) -> Result<bool> {
        let mut changed = false;
        for j in 0..self.memory.len() {
            let k1 = self.joint_kinematics(j, y1);
            let cj = &self.model.clearance[j];
            let limit = cj.penetration_limit;
            if k1.delta > limit {
                // The diagnosis (worst joint, its ε) describes the state that went too deep.
                self.last_t = t1;
                self.last_y.copy_from_slice(y1);
                let cj = &self.model.clearance[j];
                return Err(Error::PenetrationTooDeep { t: t1, joint: cj.name.clone(), penetration: k1.delta, limit });
            }
            if k1.delta > 0.0 && !self.memory[j].in_contact {
                let k0 = self.joint_kinematics(j, y0);
                let speed = if k0.delta >= 0.0 { k0.delta_dot } else { self.locate_contact_change(j, (t0, k0), (t1, k1), dense).1.delta_dot };
                let m = &mut self.memory[j];
                m.in_contact = true;
                m.impact_speed = speed.abs();
                m.impacts += 1;
                changed = true;
            } else if k1.delta <= 0.0 && self.memory[j].in_contact {
                self.memory[j].in_contact = false;
            }
        }
        Ok(changed)
    }
}
