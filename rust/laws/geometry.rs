//! The film laws' shared leaf (docs/physics.md §4): bearing geometry, film kinematics, the
//! ambient-pressure (supply) convention and the attitude angle. Every film law imports only this
//! file; [`super::film`] dispatches to them.
//!
//! Frame (all film laws): θ runs counter-clockwise from the thickest film (direction −n, n the
//! unit eccentricity vector bearing centre → journal centre); `h = c (1 + ε cos θ)`; a film force
//! `(F_ξ, F_η)` \[N\] acts ON THE JOURNAL along n and along t = n turned +90°.

/// Largest eccentricity ratio at which the film formulas are evaluated (they are singular at
/// ε = 1). Inputs above it are clamped so that every film function stays finite; the simulator
/// itself evaluates the film at `min(ε, ε_max)` (see [`super::transition::film_eps`]).
pub const FILM_EPS_CEILING: f64 = 1.0 - 1e-9;

/// Geometry and lubricant of a journal bearing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BearingGeometry {
    /// Dynamic viscosity μ [Pa·s].
    pub viscosity: f64,
    /// Journal radius R \[m\].
    pub journal_radius: f64,
    /// Radial clearance c = R_b − R_j \[m\].
    pub clearance: f64,
    /// Bearing length L \[m\].
    pub length: f64,
}

/// Kinematic state of the film.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FilmState {
    /// Eccentricity ratio ε = e/c (clamped to [0, [`FILM_EPS_CEILING`]] by the film functions).
    pub eps: f64,
    /// ε̇ [1/s]; > 0 approaching the bearing wall (squeeze), < 0 receding.
    pub eps_dot: f64,
    /// Wedge speed θ̇_j + θ̇_i − 2γ̇ [rad/s] (docs/physics.md §4): sum of both surfaces' angular speeds
    /// minus twice the whirl rate of the line of centres.
    pub wedge: f64,
}

impl FilmState {
    /// ε clamped to the range where the film formulas are finite.
    pub fn clamped_eps(&self) -> f64 {
        if self.eps.is_nan() {
            return self.eps;
        }
        self.eps.clamp(0.0, FILM_EPS_CEILING)
    }
}

/// Where the finite film's pressure is referred to the ambient (docs/physics.md §4, finite
/// bearing): the two conventions of Butenschön's tables (1976).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
pub enum FilmSupply {
    /// Ambient pressure on the axial line of the widest gap (θ = 0), where a bearing is fed: the
    /// rotation table, the Raimondi–Boyd charts, DIN 31652 and the paper's long-bearing P12.
    #[cfg_attr(feature = "serde", serde(rename = "widest_gap"))]
    #[default]
    WidestGap,
    /// No supply line: a film periodic in θ, ambient pressure only at the bearing's ends (the
    /// squeeze table's convention).
    #[cfg_attr(feature = "serde", serde(rename = "none"))]
    None,
}

/// Attitude angle \[rad\] in [0, π]: the angle between the external load carried by the film
/// (`−F`) and the eccentricity direction `n`, `atan2(|F_η|, −F_ξ)`. Under a steady load a journal
/// turning counter-clockwise sits with `n` turned from the load line by this angle in the
/// direction of rotation (this is the β of Butenschön's tables).
pub fn attitude_angle(force: (f64, f64)) -> f64 {
    force.1.abs().atan2(-force.0)
}

/// How a finite film ruptures and reforms (docs/physics.md §4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
pub enum FilmCavitation {
    /// Reynolds (Swift–Stieber) condition, p ≥ 0 without following the oil (the tables').
    #[cfg_attr(feature = "serde", serde(rename = "reynolds"))]
    #[default]
    Reynolds,
    /// Jakobsson–Floberg–Olsson: mass-conserving, the film content carried as a state
    /// ([`super::bearing_jfo`]).
    #[cfg_attr(feature = "serde", serde(rename = "jfo"))]
    Jfo,
}
