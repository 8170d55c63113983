//! Poincaré (stroboscopic) sections of a run: its channels recorded at the exact times of a
//! [`SectionSpec`], t_k = (k + phase/2π) · period, from the dense output of the accepted step
//! that holds each one — not from the output grid, so what a section holds does not depend on
//! `dt_out`. A run without sections carries none of this.

use super::MechanismSystem;
use crate::error::Result;
use crate::integrate::DenseOutput;
use crate::model::Model;
use crate::record::{Channels, Recording};
use crate::settings::SectionSpec;

/// The section times still to come and what was recorded at those passed.
#[derive(Debug, Clone)]
pub struct Sections {
    times: Vec<f64>,
    next: usize,
    pub recording: Recording,
}

impl Sections {
    /// The sections of `spec` over [t0, t_end], recording the run's `channels` (the states always;
    /// energies and temperatures are left to the output grid).
    pub fn new(spec: &SectionSpec, t0: f64, t_end: f64, channels: Channels, model: &Model) -> Self {
        let times: Vec<f64> = spec.times(t0, t_end).collect();
        let channels = Channels { states: true, energy: false, ..channels };
        let recording = Recording::new(channels, times.len(), model);
        Sections { times, next: 0, recording }
    }
}

impl MechanismSystem<'_> {
    /// Record a section at the run's start `t0` (state `y0`), if one falls there.
    pub(super) fn sections_start(&mut self, t0: f64, y0: &[f64]) -> Result<()> {
        let Some(mut sec) = self.sections.take() else { return Ok(()) };
        let res = (|| {
            while sec.times.get(sec.next) == Some(&t0) {
                self.ws.evaluate(self.model, &self.memory, t0, y0)?;
                sec.recording.push(t0, y0, &self.ws, &self.memory);
                sec.next += 1;
            }
            Ok(())
        })();
        self.sections = Some(sec);
        res
    }

    /// Record the sections inside the accepted step (t0, t1] from its dense output, evaluated
    /// with the impact memory the step was integrated with (as the outputs are).
    pub(super) fn record_sections(&mut self, t1: f64, dense: &dyn DenseOutput) -> Result<()> {
        let Some(mut sec) = self.sections.take() else { return Ok(()) };
        let mut y = std::mem::take(&mut self.scratch);
        let res = (|| {
            while let Some(&t) = sec.times.get(sec.next) {
                if t > t1 {
                    break;
                }
                dense.eval(t, &mut y);
                if sec.recording.needs_evaluation() {
                    self.ws.evaluate(self.model, &self.step_memory, t, &y)?;
                }
                sec.recording.push(t, &y, &self.ws, &self.step_memory);
                sec.next += 1;
            }
            Ok(())
        })();
        self.scratch = y;
        self.sections = Some(sec);
        res
    }
}

#[cfg(test)]
mod tests {
    use crate::description::{BodyDesc, ForceDesc, Harmonic, JointDesc, MechanismDesc, Profile};
    use crate::integrate::{Method, Settings};
    use crate::model::Model;
    use crate::settings::{RunSettings, SectionSpec};
    use crate::simulate::simulate;

    /// A pendulum under a harmonic torque, run with sections every 0.7 s at phase π/2 and with
    /// an output grid that holds those times and others.
    fn run(t_out: Vec<f64>) -> crate::simulate::RunOutput {
        let mut d = MechanismDesc { gravity: [0.0, -2.0], baumgarte: [5.0, 5.0], ..MechanismDesc::default() };
        d.bodies.push(BodyDesc { name: "bob".into(), mass: 1.0, inertia: 0.75, position: [0.5 * 0.2f64.sin(), -0.5 * 0.2f64.cos()], angle: 0.2, velocity: [0.0; 3] });
        d.joints.push(JointDesc::Revolute { name: "pivot".into(), body_a: None, point_a: [0.0, 0.0], body_b: Some(0), point_b: [0.0, 0.5] });
        d.forces.push(ForceDesc::Torque { name: "drive".into(), body: 0, reaction: None, magnitude: Profile::Harmonic(Harmonic { amplitude: 1.2, omega: 2.0, phase: 0.0, offset: 0.0 }) });
        let model = Model::compile(&d).unwrap();
        let ode = Settings { rtol: 1e-9, atol: 1e-11, ..Settings::default() };
        let sections = Some(SectionSpec { period: 0.7, phase: std::f64::consts::FRAC_PI_2 });
        let rs = RunSettings { sections, ..RunSettings::plain(Some(Method::Dop853), ode, 0.0, 7.0, t_out) };
        rs.validate().unwrap();
        simulate(&model, &rs, None).unwrap()
    }

    #[test]
    fn sections_are_the_dense_output_at_their_times_whatever_the_grid() {
        let times: Vec<f64> = (0..10).map(|k| (k as f64 + 0.25) * 0.7).collect();
        let sparse = run(vec![0.0, 7.0]);
        let mixed: Vec<f64> = { let mut v: Vec<f64> = (0..=70).map(|k| 0.1 * k as f64).chain(times.iter().copied()).collect(); v.sort_by(f64::total_cmp); v.dedup(); v };
        let dense = run(mixed.clone());
        let (a, b) = (sparse.sections.unwrap(), dense.sections.unwrap());
        assert_eq!(a.t, times);
        assert_eq!(a.t, b.t);
        assert_eq!(a.q, b.q, "the sections do not depend on the output grid");
        assert_eq!(a.qd, b.qd);
        assert_eq!(a.qdd, b.qdd);
        // ... and are what an output at the same time records (both from the step's dense output).
        for (k, t) in times.iter().enumerate() {
            let i = mixed.iter().position(|x| x == t).unwrap();
            assert_eq!(&dense.recording.q[3 * i..3 * i + 3], &b.q[3 * k..3 * k + 3]);
        }
        assert_eq!(sparse.stats.steps_accepted, dense.stats.steps_accepted, "neither shortens a step");
    }
}
