//! clearsim: planar multibody dynamics with dry and lubricated revolute clearance joints.
//!
//! The flow of one run (README "Layout"): a plain [`description::MechanismDesc`] is compiled
//! ([`compile`]) into a [`model::Model`]; [`simulate::simulate`] assembles it, integrates
//! `ẏ = f(t, y)` ([`system`], [`kkt`], [`clearance`], [`laws`]) with an [`integrate`] method under
//! the [`settings`] of the run and records the requested channels ([`record`]); [`batch`] runs
//! many in parallel. `rust/python/` (feature `python`) is the only module that knows about
//! Python.

pub mod assembly;
pub mod batch;
pub mod clearance;
pub mod compile;
pub mod constraints;
pub mod description;
pub mod energy;
pub mod error;
pub mod forces;
pub mod integrate;
pub mod kkt;
pub mod laws;
pub mod model;
#[cfg(feature = "serde")]
pub mod names;
pub mod monitor;
pub mod pose;
pub mod rank;
pub mod record;
pub mod settings;
pub mod simulate;
pub mod system;
pub mod table;
mod text;

#[cfg(feature = "python")]
mod python;

pub use error::{Error, Result};

/// The crate version.
pub fn version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}
