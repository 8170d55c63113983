//! The recorder: the requested output channels on the output grid, stored row by row.

use crate::model::Model;
use crate::system::Workspace;

/// Which channels a run stores (only those are computed at output times).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize), serde(default, deny_unknown_fields))]
pub struct Channels {
    /// q and q̇ of every body.
    pub states: bool,
    /// q̈ of every body (one KKT solve per output time).
    pub accelerations: bool,
    /// Lagrange multipliers λ, and from them each ideal joint's and driver's force and torque on
    /// its second body ([`crate::constraints::Constraint::reaction`]).
    pub reactions: bool,
    /// Per clearance joint: see [`JOINT_COLUMNS`].
    pub joints: bool,
    /// ‖Φ‖ and ‖Φ̇‖.
    pub violation: bool,
    /// Stored energies and work done ([`crate::energy::ENERGY_COLUMNS`]).
    pub energy: bool,
    /// Per clearance joint: the film's oil flow and peak pressure
    /// ([`crate::clearance::FILM_COLUMNS`]; a finite film solves its Reynolds equation at each
    /// output time, so only a run that asks pays for it).
    pub film: bool,
}

impl Default for Channels {
    fn default() -> Self {
        Channels { states: true, accelerations: true, reactions: false, joints: true, violation: true, energy: false, film: false }
    }
}

/// Columns stored per clearance joint and output time: the kinematics and forces, then the
/// readings of [`crate::clearance::READING_COLUMNS`] (film thickness, friction torques, power loss).
pub const JOINT_COLUMNS: [&str; 19] = [
    "ex", "ey", "ex_dot", "ey_dot", "fx", "fy", "normal", "tangential", "film_xi", "film_eta", "w_dry", "state",
    "film_thickness", "friction_torque", "friction_torque_bearing", "couette_torque", "poiseuille_torque", "power_loss", "asperity_force",
];

/// Recorded outputs; each array is row-major with one row per output time.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Recording {
    pub channels: Option<Channels>,
    /// Widths of the rows: coordinates q (3 per body), constraint rows (λ) and clearance joints
    /// (a row of `joints` holds `JOINT_COLUMNS.len()` per joint), so that the recording can be
    /// read without its model.
    pub coordinates: usize,
    pub constraint_rows: usize,
    /// Number of ideal joints and drivers (model order: joints, then drivers).
    pub constraints: usize,
    pub clearance_joints: usize,
    pub t: Vec<f64>,
    /// 3 per body.
    pub q: Vec<f64>,
    pub qd: Vec<f64>,
    pub qdd: Vec<f64>,
    /// One per constraint row.
    pub lambda: Vec<f64>,
    /// Three per ideal joint or driver (model order): the force \[N\] (x, y) and couple
    /// \[N m\] it exerts on its second body, global frame ([`crate::constraints::Constraint::reaction`]).
    pub reactions: Vec<f64>,
    /// `JOINT_COLUMNS.len()` per clearance joint.
    pub joints: Vec<f64>,
    /// ‖Φ‖, ‖Φ̇‖.
    pub violation: Vec<f64>,
    /// `ENERGY_COLUMNS.len()` per output time.
    pub energy: Vec<f64>,
    /// The oil temperature \[K\] of each clearance joint per output time, when any joint models
    /// it (rust/clearance/thermal.rs; NaN for the joints that do not); empty otherwise.
    pub temperature: Vec<f64>,
    /// `FILM_COLUMNS.len()` per clearance joint and output time (the `film` channel).
    pub film: Vec<f64>,
    /// With the `film` channel: the film content of each mass-conserving joint (in joint order,
    /// [`crate::laws::bearing_jfo::JFO_THETA`] × [`crate::laws::bearing_jfo::JFO_ZETA`] values) per
    /// output time, so that its pressure can be solved again afterwards.
    pub film_content: Vec<f64>,
    /// The clearance joints whose readings the `joints` and `film` channels store (empty without them).
    readers: Vec<crate::clearance::ClearanceJoint>,
    /// The finite films' solvers of the `film` channel (one per joint; `None` for other films).
    film_scratch: Vec<Option<crate::laws::film_field::FiniteScratch>>,
    /// The ideal joints and drivers whose reactions the `reactions` channel stores (empty without it).
    holders: Vec<crate::constraints::Constraint>,
}

impl Recording {
    pub fn new(channels: Channels, capacity: usize, model: &Model) -> Self {
        let n = 3 * model.n_bodies();
        let cap = |on: bool, w: usize| if on { Vec::with_capacity(capacity * w) } else { Vec::new() };
        Recording {
            channels: Some(channels),
            coordinates: n,
            constraint_rows: model.rows,
            constraints: model.constraints.len(),
            clearance_joints: model.clearance.len(),
            t: Vec::with_capacity(capacity),
            q: cap(channels.states, n),
            qd: cap(channels.states, n),
            qdd: cap(channels.accelerations, n),
            lambda: cap(channels.reactions, model.rows),
            reactions: cap(channels.reactions, 3 * model.constraints.len()),
            joints: cap(channels.joints, JOINT_COLUMNS.len() * model.clearance.len()),
            violation: cap(channels.violation, 2),
            energy: cap(channels.energy, crate::energy::ENERGY_COLUMNS.len()),
            temperature: Vec::new(),
            film: cap(channels.film, crate::clearance::FILM_COLUMNS.len() * model.clearance.len()),
            film_content: Vec::new(),
            readers: if channels.joints || channels.film { model.clearance.clone() } else { Vec::new() },
            film_scratch: if channels.film { model.clearance.iter().map(|c| c.film_scratch()).collect() } else { Vec::new() },
            holders: if channels.reactions { model.constraints.clone() } else { Vec::new() },
        }
    }

    /// Whether an output needs a full right-hand-side evaluation.
    pub fn needs_evaluation(&self) -> bool {
        self.channels.is_some_and(|c| c.accelerations || c.reactions || c.joints || c.violation || c.energy || c.film)
    }

    /// Store one output row from the state and the workspace of its evaluation (with the joints'
    /// `memory` it was evaluated with).
    pub fn push(&mut self, t: f64, y: &[f64], ws: &Workspace, memory: &[crate::clearance::ImpactMemory]) {
        let ch = self.channels.unwrap_or_default();
        let n = ws.qdd.len();
        self.t.push(t);
        if ch.states {
            self.q.extend_from_slice(&y[..n]);
            self.qd.extend_from_slice(&y[n..2 * n]);
        }
        if ch.accelerations {
            self.qdd.extend_from_slice(&ws.qdd);
        }
        if ch.reactions {
            self.lambda.extend_from_slice(&ws.lambda);
            let mut r = 0;
            for con in &self.holders {
                let m = con.rows();
                self.reactions.extend_from_slice(&con.reaction(&ws.kin, &ws.lambda[r..r + m]));
                r += m;
            }
        }
        if ch.joints {
            for (((k, f), joint), mem) in ws.joint_kin.iter().zip(&ws.joint_force).zip(&self.readers).zip(memory) {
                self.joints.extend_from_slice(&[
                    k.e_vec.x,
                    k.e_vec.y,
                    k.e_dot.x,
                    k.e_dot.y,
                    f.total.x,
                    f.total.y,
                    f.normal,
                    f.tangential,
                    f.film_xi,
                    f.film_eta,
                    f.w_dry,
                    f.state as f64,
                ]);
                let (w_b, w_j) = crate::clearance::body_rates(joint, &y[n..2 * n]);
                self.joints.extend_from_slice(&joint.readings(k, f, &joint.memory_at(mem, y), w_b, w_j).columns());
            }
        }
        if ch.film {
            for (j, ((k, f), mem)) in ws.joint_kin.iter().zip(&ws.joint_force).zip(memory).enumerate() {
                let r = self.readers[j].flow_and_peak(k, f, mem, self.film_scratch[j].as_mut());
                self.film.extend_from_slice(&[r.side_leakage, r.supply, r.peak_pressure, r.peak_angle]);
                if let Some(fill) = crate::clearance::cavitation::recorded_fill(&self.readers[j], k, mem) {
                    self.film_content.extend_from_slice(&fill);
                }
            }
        }
        if ch.violation {
            let (a, b) = ws.violation();
            self.violation.extend_from_slice(&[a, b]);
        }
    }

    pub fn len(&self) -> usize {
        self.t.len()
    }

    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }
}
