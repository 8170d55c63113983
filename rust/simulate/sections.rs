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
