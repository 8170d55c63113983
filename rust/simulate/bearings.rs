//! The bearing summary of a run, tracked along its accepted steps when the run asks for it
//! ([`RunSettings::bearings`](crate::settings::RunSettings::bearings); `Result.bearing_summary()`,
//! docs/physics.md §4, "Film thickness, friction and power"): per lubricated clearance joint the
//! minimum film thickness h = c − |e| and when, located between the step ends on the step's dense
//! output, and the peak and the time integral of the power loss at the step ends, over the
//! window from [`RunSettings::bearings_from`](crate::settings::RunSettings::bearings_from) (or
//! the run's start) to its end: the books start at the window's start, the state there read off
//! the dense output of the step that holds it.
//!
//! Cheap by construction (issue 37: a run pays only for what it asks): per step and joint one
//! kinematics at the step's end, the joint's force there taken from the step's own last
//! evaluation when it was made at that state (the explicit methods' FSAL stage; the implicit
//! methods' f(t1, y1), which their next step reuses), and the readings. The minimum film is
//! searched (golden section on the dense positions, no force) only in a step whose end slopes
//! show a minimum inside that may beat the running one.

use super::MechanismSystem;
use crate::error::Result;
use crate::integrate::DenseOutput;
use crate::monitor::golden_section;

/// What the summary reports for one lubricated clearance joint over the run (so far).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BearingSummary {
    /// The window the summary covers \[s\]: from its start to the last step's end booked.
    pub window_start: f64,
    pub window_end: f64,
    /// Smallest film thickness h = c − |e| \[m\] and its time \[s\] (located on the dense output).
    pub min_film_thickness: f64,
    pub t_min_film: f64,
    /// Largest power loss at a step's end \[W\] and its time \[s\].
    pub peak_power_loss: f64,
    pub t_peak_power_loss: f64,
    /// ∫ P dt over the run \[J\] (trapezoids over the steps) and the time it covers \[s\].
    pub energy_loss: f64,
    pub time: f64,
}

impl BearingSummary {
    /// The mean power loss \[W\] over the time covered (NaN before any step).
    pub fn mean_power_loss(&self) -> f64 {
        if self.time > 0.0 {
            self.energy_loss / self.time
        } else {
            f64::NAN
        }
    }
}

/// The summary of one joint and what its next step starts from: the film thickness, its rate
/// and the power loss at the last step's end.
#[derive(Debug, Clone, Copy)]
pub struct BearingBook {
    pub summary: BearingSummary,
    t: f64,
    h: f64,
    h_dot: f64,
    power: f64,
    /// The step end before `t` and the power loss there (NaN: none yet), for the curvature.
    t_before: f64,
    power_before: f64,
}

/// A step's inside is searched when the cubic through the end values and rates could dip below
/// the running minimum: its lowest value is at least min(h0, h1) − (4/27)(|ḣ0| + |ḣ1|) Δt
/// (the bound of the Hermite basis functions); this factor widens that bound for the dense
/// output's own deviation from the cubic.
const SEARCH_WIDENING: f64 = 1.5;

impl BearingBook {
    /// The book at the run's start (t, film thickness h \[m\], its rate ḣ \[m/s\], power loss P \[W\]).
    pub fn new(t: f64, h: f64, h_dot: f64, power: f64) -> Self {
        let summary = BearingSummary { window_start: t, window_end: t, min_film_thickness: h, t_min_film: t, peak_power_loss: power, t_peak_power_loss: t, energy_loss: 0.0, time: 0.0 };
        BearingBook { summary, t, h, h_dot, power, t_before: f64::NAN, power_before: f64::NAN }
    }

    /// Book the step ending at `t1` with the values there; returns the bracket to search for a
    /// minimum of the film inside the step, if the ends show one that may beat the running one.
    pub fn step(&mut self, t1: f64, h1: f64, h_dot1: f64, power1: f64) -> Option<(f64, f64)> {
        let (t0, h0, d0) = (self.t, self.h, self.h_dot);
        let dt = t1 - t0;
        let s = &mut self.summary;
        s.energy_loss += integral(self.t_before, self.power_before, t0, self.power, t1, power1);
        s.time += dt;
        s.window_end = t1;
        if power1 > s.peak_power_loss {
            (s.peak_power_loss, s.t_peak_power_loss) = (power1, t1);
        }
        if h1 < s.min_film_thickness {
            (s.min_film_thickness, s.t_min_film) = (h1, t1);
        }
        (self.t_before, self.power_before) = (t0, self.power);
        (self.t, self.h, self.h_dot, self.power) = (t1, h1, h_dot1, power1);
        // A minimum inside: the film thins at the start and thickens at the end.
        let dip = SEARCH_WIDENING * 4.0 / 27.0 * (d0.abs() + h_dot1.abs()) * dt;
        (d0 < 0.0 && h_dot1 > 0.0 && h0.min(h1) - dip < s.min_film_thickness && dt > 0.0).then_some((t0, t1))
    }

    /// A film thickness found inside the last step: kept if it is the smallest.
    pub fn found(&mut self, t: f64, h: f64) {
        let s = &mut self.summary;
        if h < s.min_film_thickness {
            (s.min_film_thickness, s.t_min_film) = (h, t);
        }
    }
}

/// ∫ P dt over `[t0, t1]` from the values at the step's ends and at the end `ta` of the step
/// before (NaN on the first step): the trapezoid less its error as the parabola through the
/// three points gives it, −(t1 − t0)³ P''/12 (third order in the step, as the four samples a step
/// of a monitor's trapezoids are on the steps of RADAU5, and with no evaluation between the ends).
fn integral(ta: f64, pa: f64, t0: f64, p0: f64, t1: f64, p1: f64) -> f64 {
    let (h, g) = (t1 - t0, t0 - ta);
    let trapezoid = 0.5 * (p0 + p1) * h;
    if !(g > 0.0 && h > 0.0 && pa.is_finite()) {
        return trapezoid;
    }
    let curvature = 2.0 * ((p1 - p0) / h - (p0 - pa) / g) / (h + g);
    trapezoid - h * h * h * curvature / 12.0
}

impl MechanismSystem<'_> {
    /// Joint `j`'s film thickness \[m\], its rate \[m/s\] and power loss \[W\] at `y`, the
    /// joint's force taken from the workspace when it holds the evaluation at that state.
    fn bearing_values(&self, j: usize, y: &[f64], workspace_current: bool) -> (f64, f64, f64) {
        let joint = &self.model.clearance[j];
        let k = self.joint_kinematics(j, y);
        // The workspace's force is the one at this state when its kinematics are (bit for bit):
        // a joint's force is a function of its kinematics and its memory, which is the same.
        // The joint at the state's oil temperature (heat as a state: rust/clearance/thermal.rs).
        let memory = joint.memory_at(&self.memory[j], y);
        let f = if workspace_current && self.ws.joint_kin[j] == k { self.ws.joint_force[j] } else { joint.force(&k, &memory) };
        let nq = 3 * self.model.n_bodies();
        let (w_b, w_j) = crate::clearance::body_rates(joint, &y[nq..2 * nq]);
        let r = joint.readings(&k, &f, &memory, w_b, w_j);
        (r.film_thickness, -k.delta_dot, r.power_loss)
    }

    /// Start the bearing books of the lubricated joints at the state `y` at `t`: the run's
    /// initial state, or the window's start (when asked).
    pub fn bearings_start(&mut self, t: f64, y: &[f64]) {
        for j in 0..self.bearings.len() {
            if self.model.clearance[j].film.is_some() {
                let (h, h_dot, p) = self.bearing_values(j, y, false);
                self.bearings[j] = Some(BearingBook::new(t, h, h_dot, p));
            }
        }
    }

    /// Book the accepted step (t0, t1] (module doc): nothing before the window's start; the
    /// step that holds it starts the books at the state there, on its dense output, and is
    /// booked from there. An implicit method's f(t1, y1) is evaluated here and kept for its next
    /// step, which needs it.
    pub(super) fn bearings_step(&mut self, t1: f64, y1: &[f64], dense: &dyn DenseOutput) -> Result<()> {
        if let Some(w) = self.bearings_from {
            if t1 < w {
                return Ok(());
            }
            self.bearings_from = None;
            if t1 == w {
                self.bearings_start(t1, y1);
                return Ok(());
            }
            let mut s = std::mem::take(&mut self.scratch);
            dense.eval(w, &mut s);
            self.bearings_start(w, &s);
            self.scratch = s;
        }
        let explicit = dense.end_rate().is_some();
        if !explicit {
            self.ws.evaluate_and_keep(self.model, &self.memory, t1, y1)?;
        }
        for j in 0..self.bearings.len() {
            if self.bearings[j].is_none() {
                continue;
            }
            let (h, h_dot, p) = self.bearing_values(j, y1, true);
            let Some(bracket) = self.bearings[j].as_mut().and_then(|b| b.step(t1, h, h_dot, p)) else { continue };
            let found = self.film_minimum(j, bracket, dense);
            if let Some(b) = self.bearings[j].as_mut() {
                b.found(found.0, found.1);
            }
        }
        Ok(())
    }

    /// The smallest film thickness of joint `j` on `(a, b)` of the step's dense output, by
    /// golden section (positions only: no force).
    fn film_minimum(&mut self, j: usize, (a, b): (f64, f64), dense: &dyn DenseOutput) -> (f64, f64) {
        let joint = &self.model.clearance[j];
        let mut idx = [0usize; 6];
        let mut len = 0;
        for body in [joint.bearing, joint.journal].into_iter().flatten() {
            for c in 0..3 {
                idx[len] = 3 * body as usize + c;
                len += 1;
            }
        }
        let mut s = std::mem::take(&mut self.scratch);
        let clearance = joint.clearance;
        let found = golden_section::<std::convert::Infallible>(a, b, |t| {
            dense.eval_components(t, &idx[..len], &mut s);
            // Only the positions enter |e|; the velocities in `s` are not read for it.
            Ok(-(clearance - self.joint_kinematics(j, &s).e))
        });
        self.scratch = s;
        let (t, v) = found.unwrap_or_else(|never| match never {});
        (t, -v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_book_integrates_the_power_and_keeps_the_extremes() {
        // P = 3t² on [0, 1] in uneven steps: ∫ = 1; the trapezoids alone give 1.0415 on these
        // steps, the curvature from the step before is exact for a parabola past the first step.
        let steps = [0.0, 0.3, 0.45, 0.7, 0.8, 1.0];
        let mut b = BearingBook::new(0.0, 1.0, -1.0, 0.0);
        for &t in &steps[1..] {
            b.step(t, 1.0 - t, -1.0, 3.0 * t * t);
        }
        let s = b.summary;
        let first_step_error = 0.5 * 0.27 * 0.3 - 0.027; // the trapezoid's on [0, 0.3]
        assert!((s.energy_loss - 1.0 - first_step_error).abs() < 1e-14 && s.time == 1.0, "{s:?}");
        // P = 2t, linear: exact.
        let mut b = BearingBook::new(0.0, 1.0, -1.0, 0.0);
        for i in 1..=4 {
            let t = 0.25 * i as f64;
            b.step(t, 1.0 - t, -1.0, 2.0 * t);
        }
        let s = b.summary;
        assert!((s.energy_loss - 1.0).abs() < 1e-15 && s.time == 1.0, "{s:?}");
        assert_eq!((s.peak_power_loss, s.t_peak_power_loss), (2.0, 1.0));
        assert_eq!((s.min_film_thickness, s.t_min_film), (0.0, 1.0));
        assert!((s.mean_power_loss() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn a_step_is_searched_only_when_its_ends_show_a_minimum_that_may_beat_the_record() {
        // h = (t − 0.5)² on steps of 0.4: the step [0.4, 0.8] holds the minimum 0 at 0.5.
        let h = |t: f64| (t - 0.5) * (t - 0.5);
        let hd = |t: f64| 2.0 * (t - 0.5);
        let mut b = BearingBook::new(0.0, h(0.0), hd(0.0), 0.0);
        assert_eq!(b.step(0.4, h(0.4), hd(0.4), 0.0), None, "still thinning");
        assert_eq!(b.step(0.8, h(0.8), hd(0.8), 0.0), Some((0.4, 0.8)));
        b.found(0.5, 0.0);
        assert_eq!((b.summary.min_film_thickness, b.summary.t_min_film), (0.0, 0.5));
        // A later, shallower dip well above the record is not searched.
        let mut b2 = b;
        b2.step(1.2, 0.5, -0.1, 0.0);
        assert_eq!(b2.step(1.3, 0.5, 0.1, 0.0), None);
    }
}
