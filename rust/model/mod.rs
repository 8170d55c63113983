//! The compiled model: what the right-hand side reads, as flat arrays and enums
//! (docs/physics.md §1), immutable during a run. Built from a checked description by
//! [`Model::compile`] (rust/compile/); only the parts the scene uses are present: a mechanism
//! without lubricated joints has no film data, a joint without clearance is a constraint.

use crate::clearance::ClearanceJoint;
use crate::constraints::{Constraint, V2};
use crate::forces::ForceElement;

/// Everything the right-hand side needs, immutable during a run.
#[derive(Debug, Clone)]
pub struct Model {
    pub body_names: Vec<String>,
    /// m, m, J per body.
    pub mass: Vec<f64>,
    pub gravity: V2,
    pub alpha: f64,
    pub beta: f64,
    pub constraints: Vec<Constraint>,
    /// What each constraint is, for messages: `joint 'A'`, `driver 'drive1'`.
    pub constraint_names: Vec<String>,
    /// Number of scalar constraint equations.
    pub rows: usize,
    pub clearance: Vec<ClearanceJoint>,
    /// Force elements and loads (empty for a scene without any: nothing runs).
    pub forces: Vec<ForceElement>,
    pub force_names: Vec<String>,
    /// Approximate initial positions (x, y, θ per body) and velocity guesses.
    pub q_guess: Vec<f64>,
    pub qd_guess: Vec<f64>,
    /// What holds each clearance joint during the kinematic assembly: a revolute joint with
    /// the initial eccentricity as offset, or a prismatic joint (slider centred and aligned).
    pub assembly: Vec<(String, Constraint)>,
    /// Per clearance joint: the depths \[m\] worn before the run around the bearing and the
    /// journal (empty: unworn; docs/physics.md §12).
    pub initial_wear: Vec<(Vec<f64>, Vec<f64>)>,
    /// The pose given assembled at t = 0 (positions q, 3 per body), or why it did not assemble:
    /// done once when the model compiles ([`crate::assembly::pose_at_zero`]); every run and
    /// initial state starts from it (`None`: not assembled yet, [`crate::assembly::assemble`]
    /// does it then).
    pub start: Option<crate::error::Result<Vec<f64>>>,
}

impl Model {
    /// The name of the constraint that equation `row` belongs to (see `constraint_names`).
    pub fn constraint_of_row(&self, row: usize) -> String {
        let mut start = 0;
        for (c, name) in self.constraints.iter().zip(&self.constraint_names) {
            if row < start + c.rows() {
                return name.clone();
            }
            start += c.rows();
        }
        format!("constraint row {row}")
    }

    pub fn n_bodies(&self) -> usize {
        self.body_names.len()
    }

    /// Length of the state y = (q, q̇, T…): 3 coordinates and 3 rates per body, then the oil
    /// temperature of each clearance joint with a heat model, in joint order
    /// (rust/clearance/thermal.rs).
    pub fn state_dim(&self) -> usize {
        6 * self.n_bodies() + self.heat_states()
    }

    /// Number of oil temperatures in the state (0 without heat models).
    pub fn heat_states(&self) -> usize {
        self.clearance.iter().filter(|c| c.heat().is_some()).count()
    }

    /// The state y at the start of a run from the assembled (q, q̇): the oil temperatures at
    /// their initial values.
    pub fn initial_state(&self, q: &[f64], qd: &[f64]) -> Vec<f64> {
        let mut y = Vec::with_capacity(self.state_dim());
        y.extend_from_slice(q);
        y.extend_from_slice(qd);
        y.extend(self.clearance.iter().filter_map(|c| c.heat()).map(|h| h.thermal.initial));
        y
    }

    /// Degrees of freedom left after the constraints (clearance joints add 2 each).
    pub fn dof(&self) -> isize {
        3 * self.n_bodies() as isize - self.rows as isize
    }
}
