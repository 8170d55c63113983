//! The laws of clearance joints (docs/physics.md §3–§4, §12): functions of kinematic inputs and
//! parameters, without state. One exception keeps state: the finite bearing's tables, solved once
//! per L/D and supply and kept in the process and in a folder on disk ([`bearing_finite_cache`]).
//!
//! - [`contact`]: normal impact force (Hertz, Lankarani–Nikravesh, Hunt–Crossley, Flores) and
//!   contact stiffness (docs/physics.md §3, P3–P4); [`contact_line`]: a pin as a line contact.
//! - [`friction`]: modified Coulomb friction (docs/physics.md §3, P5).
//! - [`geometry`]: the film laws' shared leaf (bearing geometry, film state, supply convention).
//! - [`film`]: the film-model dispatch (docs/physics.md §4).
//! - [`bearing_long`]: long (Pinkus–Sternlicht) bearing, Gümbel condition (docs/physics.md §4, P10–P14).
//! - [`bearing_short`]: short (Ocvirk) bearing, Gümbel condition (docs/physics.md §4).
//! - [`bearing_finite`]: finite bearing, the Reynolds equation solved into a table per L/D and
//!   supply; [`bearing_finite_cache`]: where those tables are kept (process and disk);
//!   [`bearing_jfo`]: the finite film with mass-conserving cavitation (film content as a state).
//! - [`film_friction`]: the film's friction torques and power loss; the dry friction's moment.
//! - [`film_field`]: the film's oil flow, peak pressure and pressure field (readings only).
//! - [`viscosity`]: Vogel's viscosity law and the joint's lumped heat balance.
//! - [`asperity`]: Greenwood–Tripp asperity pressure and load (rough surfaces).
//! - [`transition`]: small-eccentricity scaling (P15–P16) and film-to-contact blend (P18).
//! - [`quadrature`]: Gauss–Legendre rules.
//! - [`wear`]: Archard's wear law (docs/physics.md §12).
//!
//! Imports run downward: the film laws import [`geometry`] (and [`quadrature`]) only; [`film`]
//! imports them. Film-force convention everywhere: `(F_ξ, F_η)` is the force ON THE JOURNAL
//! along `n` (bearing centre → journal centre) and along `t` = `n` turned +90°.

pub mod asperity;
pub mod bearing_finite;
pub mod bearing_finite_cache;
pub mod bearing_jfo;
pub mod bearing_long;
pub mod bearing_short;
pub mod contact;
pub mod contact_line;
pub mod film;
pub mod film_field;
pub mod film_friction;
pub mod friction;
pub mod geometry;
pub mod quadrature;
pub mod transition;
pub mod viscosity;
pub mod wear;

pub use bearing_long::{long_bearing_centre_limit, long_bearing_force, long_bearing_force_quadrature, long_bearing_paper_closed_form, long_bearing_pressure};
pub use bearing_short::{short_bearing_force, short_bearing_pressure, short_bearing_pressure_integrated};
pub use contact::{hysteresis_factor, stiffness_internal, stiffness_paper_printed, ContactLaw, NormalLaw};
pub use film::{film_force, FilmModel};
pub use geometry::{attitude_angle, BearingGeometry, FilmCavitation, FilmState, FilmSupply, FILM_EPS_CEILING};
pub use friction::ModifiedCoulomb;
pub use transition::{film_eps, small_eccentricity_scale, transition_weights};
