//! The film-model dispatch (docs/physics.md §4): which film law a lubricated joint uses and its
//! force. The types the film laws share live in [`super::geometry`] (re-exported here).
//!
//! Convention (all film models): the returned pair `(F_ξ, F_η)` \[N\] is the force of the film ON
//! THE JOURNAL along `n` (unit eccentricity vector, bearing centre → journal centre) and along
//! `t` = `n` turned +90°. The angle θ is measured counter-clockwise from the thickest film (the
//! direction −n); film thickness `h = c (1 + ε cos θ)`; `F_ξ = R L ∫ p⁺ cos θ dθ`,
//! `F_η = R L ∫ p⁺ sin θ dθ` (Gümbel condition: only positive pressure carries load).
//! A squeezed journal (ε̇ > 0) gets `F_ξ < 0`; a journal turning counter-clockwise (wedge > 0)
//! gets `F_η > 0`.

use super::bearing_finite::{finite_bearing_force, FiniteBearingTable};
use super::{bearing_long, bearing_short};
pub use super::geometry::{attitude_angle, BearingGeometry, FilmState, FilmSupply, FILM_EPS_CEILING};

/// Which hydrodynamic film model a lubricated joint uses.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
pub enum FilmModel {
    /// Long (Pinkus–Sternlicht, infinitely long) bearing, pressure P12 corrected, Gümbel
    /// condition on the exact zeros of p (the paper's model; L/D > 2).
    #[cfg_attr(feature = "serde", serde(rename = "long"))]
    #[default]
    LongBearing,
    /// Short (Ocvirk) bearing with wedge and squeeze, Gümbel condition (L/D < 1).
    #[cfg_attr(feature = "serde", serde(rename = "short"))]
    ShortBearing,
    /// The paper's printed closed forms, Eqs. (13)–(14), errors included (labelled variant).
    #[cfg_attr(feature = "serde", serde(rename = "long_paper"))]
    LongBearingPaperClosedForm,
    /// Finite length: the Reynolds equation with the Reynolds (Swift–Stieber) cavitation
    /// condition solved once per L/D and supply convention ([`FilmSupply`]) into a table
    /// ([`super::bearing_finite`]); 1/16 ≤ L/D ≤ 16.
    #[cfg_attr(feature = "serde", serde(rename = "finite"))]
    Finite,
}

/// Film force `(F_ξ, F_η)` \[N\] on the journal for `model` (see the module doc for the frame).
/// `table` is the bearing's finite-length table (`FilmModel::Finite` only; without it the
/// finite model takes the default supply convention's table from the cache,
/// [`super::bearing_finite_cache::table_for`]).
pub fn film_force(model: FilmModel, g: &BearingGeometry, s: FilmState, table: Option<&FiniteBearingTable>) -> (f64, f64) {
    match model {
        FilmModel::LongBearing => bearing_long::long_bearing_force(g, s),
        FilmModel::ShortBearing => bearing_short::short_bearing_force(g, s),
        FilmModel::LongBearingPaperClosedForm => bearing_long::long_bearing_paper_closed_form(g, s),
        FilmModel::Finite => match table {
            Some(t) => finite_bearing_force(g, s, t),
            None => finite_bearing_force(g, s, super::bearing_finite_cache::table_for(2.0 * g.journal_radius / g.length, FilmSupply::default())),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dispatch_and_no_nan_at_extremes() {
        let g = BearingGeometry { viscosity: 0.4, journal_radius: 0.01, clearance: 5e-4, length: 0.05 };
        for model in [FilmModel::LongBearing, FilmModel::ShortBearing, FilmModel::LongBearingPaperClosedForm, FilmModel::Finite] {
            for eps in [0.0, 1e-300, 1e-9, 0.5, 0.99, 1.0, 1.5, -0.1] {
                for eps_dot in [-10.0, 0.0, 10.0] {
                    for wedge in [-50.0, 0.0, 50.0] {
                        let f = film_force(model, &g, FilmState { eps, eps_dot, wedge }, None);
                        assert!(f.0.is_finite() && f.1.is_finite(), "{model:?} ε {eps} ε̇ {eps_dot} w {wedge}: {f:?}");
                    }
                }
            }
            // Journal and bearing turning together rigidly (wedge 0) and no squeeze: no force.
            assert_eq!(film_force(model, &g, FilmState { eps: 0.5, eps_dot: 0.0, wedge: 0.0 }, None), (0.0, 0.0));
        }
        assert!(film_force(FilmModel::LongBearing, &g, FilmState { eps: 0.5, eps_dot: 0.0, wedge: 10.0 }, None).1 > 0.0);
        assert!(film_force(FilmModel::ShortBearing, &g, FilmState { eps: 0.5, eps_dot: 1.0, wedge: 0.0 }, None).0 < 0.0);
    }

    #[test]
    fn finite_for_extreme_finite_inputs() {
        let g = BearingGeometry { viscosity: 0.4, journal_radius: 0.01, clearance: 5e-4, length: 0.05 };
        let rates = [0.0, 1e-300, -1e-300, 1e-12, -1e-12, 1.0, -1.0, 1e6, -1e6];
        let epss = [0.0, 5e-324, 1e-300, 1e-12, 1e-6, 0.3, 0.9, 0.999, 0.999999, FILM_EPS_CEILING, 1.0, 7.0];
        for model in [FilmModel::LongBearing, FilmModel::ShortBearing, FilmModel::LongBearingPaperClosedForm, FilmModel::Finite] {
            for eps in epss {
                for eps_dot in rates {
                    for wedge in rates {
                        let f = film_force(model, &g, FilmState { eps, eps_dot, wedge }, None);
                        assert!(f.0.is_finite() && f.1.is_finite(), "{model:?} ε {eps} ε̇ {eps_dot} W {wedge}: {f:?}");
                    }
                }
            }
        }
        for eps in epss {
            for eps_dot in rates {
                for wedge in rates {
                    let q = super::bearing_long::long_bearing_force_quadrature(&g, FilmState { eps, eps_dot, wedge });
                    assert!(q.0.is_finite() && q.1.is_finite(), "GL ε {eps} ε̇ {eps_dot} W {wedge}: {q:?}");
                }
            }
        }
    }

    #[test]
    fn attitude_angle_frame() {
        // Pure radial restoring force (F_ξ < 0): load along n, angle 0.
        assert!(attitude_angle((-1.0, 0.0)).abs() < 1e-15);
        // Pure tangential: 90°.
        assert!((attitude_angle((0.0, 1.0)) - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    }
}
