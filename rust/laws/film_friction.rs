//! Friction of a lubricated joint (docs/physics.md §4, friction): the torques of the film's shear
//! on journal and bearing, its power loss, and the dry friction's moment in the transition band
//! and in contact.
//!
//! Film shear (thin film, velocity profile Couette + Poiseuille across the gap y ∈ [0, h], y = 0
//! on the journal): the shear stress on the journal along +θ is
//! `τ_j = μ (U_b − U_j)/h − (h/(2R)) ∂p/∂θ`, on the bearing `τ_b = −μ (U_b − U_j)/h − (h/(2R)) ∂p/∂θ`,
//! with U = R θ̇ the surface speeds. Over the bearing (moment arm R, area R dθ dz):
//!
//! - Couette part, over the whole circumference (the oil that fills the cavitated zone in
//!   streamers is taken to shear like a full film, as Raimondi & Boyd (1958) do):
//!   `T_C = −μ R³ L (θ̇_j − θ̇_b)/c · ∫₀^{2π} dθ/(1 + ε cos θ) = −2π μ R³ L (θ̇_j − θ̇_b)/(c √(1 − ε²))`
//!   on the journal, `−T_C` on the bearing (Petroff's torque at ε = 0);
//! - Poiseuille part, by parts (h p periodic, p continuous at the film's rupture):
//!   `−(R/2) ∫∫ h ∂p/∂θ dθ dz = (R/2) ∫∫ p ∂h/∂θ = −(e/2) F_η` on each body, e = c ε and F_η the
//!   film force's tangential component (any film law: long, short or finite).
//!
//! So the journal gets `T_j = T_C − e F_η/2` and the bearing `T_b = −T_C − e F_η/2`; their sum
//! `−e F_η` balances the moment of the film force about the bearing centre. The power the film
//! takes from the bodies, `P = −(F·ė + T_j θ̇_j + T_b θ̇_b)`, is
//! `P = 2πμR³L (θ̇_j − θ̇_b)²/(c√(1−ε²)) + (e/2) F_η W − c ε̇ F_ξ` with W the wedge speed
//! ([`super::geometry::FilmState`]): it depends on relative motion only.
//!
//! Checks (tests): Petroff at ε → 0; the full-Sommerfeld long bearing's torque
//! `4πμR³Lω(1 + 2ε²)/(c (2 + ε²) √(1 − ε²))` (Pinkus & Sternlicht 1961; Hamrock, Schmid &
//! Jacobson 2004); the half-Sommerfeld (Gümbel) long bearing's `πμR³Lω(4 + 5ε²)/(c (2 + ε²) √(1 − ε²))`
//! and Ocvirk's short bearing's `2πμR³Lω/(c√(1−ε²)) + πμR L³ ω ε²/(8 c (1 − ε²)^{3/2})`, both
//! derived from the same two parts; a quadrature of τ_j over each film's own pressure field; and
//! Raimondi & Boyd's friction variable (R/c) f at L/D = 1.

use super::geometry::{BearingGeometry, FilmState};
use std::f64::consts::TAU;

/// Friction torques \[N m\] and power loss \[W\] of the film (module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FilmFriction {
    /// Torque on the journal about its centre, counter-clockwise positive.
    pub journal: f64,
    /// Torque on the bearing about its centre.
    pub bearing: f64,
    /// The Couette (shear-flow) part of the journal's torque (the bearing gets its negative).
    pub couette: f64,
    /// The Poiseuille (pressure-flow) part, the same on journal and bearing: −e F_η/2.
    pub poiseuille: f64,
    /// Power taken from the bodies by the film \[W\] (≥ 0 for the films' p ≥ 0).
    pub power_loss: f64,
}

/// Torques and power loss of the film of `g` in the state `s` (the ε the film force was evaluated
/// at) with the journal and bearing turning at `omega_journal`, `omega_bearing` [rad/s] and the
/// film force `force = (F_ξ, F_η)` \[N\] on the journal (from any film law, [`super::film`]).
pub fn film_friction(g: &BearingGeometry, s: FilmState, omega_journal: f64, omega_bearing: f64, force: (f64, f64)) -> FilmFriction {
    let eps = s.clamped_eps();
    let r = g.journal_radius;
    // 2πμR³L/(c√(1−ε²)), with 1 − ε² as (1 − ε)(1 + ε) for precision near ε = 1.
    let petroff = TAU * g.viscosity * r * r * r * g.length / (g.clearance * ((1.0 - eps) * (1.0 + eps)).sqrt());
    let sliding = omega_journal - omega_bearing;
    let couette = -petroff * sliding;
    let e = g.clearance * eps;
    let poiseuille = -0.5 * e * force.1;
    FilmFriction {
        journal: couette + poiseuille,
        bearing: -couette + poiseuille,
        couette,
        poiseuille,
        power_loss: petroff * sliding * sliding + 0.5 * e * force.1 * s.wedge - g.clearance * s.eps_dot * force.0,
    }
}

/// Petroff's torque 2πμR³Lω/c \[N m\] of a centred journal sliding at ω [rad/s] (magnitude).
pub fn petroff_torque(g: &BearingGeometry, omega: f64) -> f64 {
    TAU * g.viscosity * g.journal_radius.powi(3) * g.length * omega.abs() / g.clearance
}

/// Moments \[N m\] of the dry friction force `f_t` \[N\] (along t, on the journal at its contact
/// point, docs/physics.md §2–§3) about the journal's and the bearing's centres: `(R_j F_t, −R_b F_t)`.
/// In the transition band the joint blends them with the film's torques by the band's weights.
pub fn dry_friction_torque(journal_radius: f64, bearing_radius: f64, f_t: f64) -> (f64, f64) {
    (journal_radius * f_t, -bearing_radius * f_t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::laws::bearing_finite::{ReynoldsGrid, ReynoldsSolver};
    use crate::laws::bearing_long::{long_bearing_force, long_bearing_pressure};
    use crate::laws::bearing_short::{short_bearing_force, short_bearing_pressure};
    use crate::laws::film::{film_force, FilmModel};
    use crate::laws::geometry::FilmSupply;
    use crate::laws::quadrature::{GL16, GL8};
    use std::f64::consts::PI;

    const OMEGA: f64 = 100.0;

    fn geometry(l_over_d: f64) -> BearingGeometry {
        BearingGeometry { viscosity: 0.05, journal_radius: 0.02, clearance: 4e-5, length: 0.04 * l_over_d }
    }

    /// Pure rotation of the journal in a fixed bearing: wedge = ω.
    fn rotating(eps: f64) -> FilmState {
        FilmState { eps, eps_dot: 0.0, wedge: OMEGA }
    }

    #[test]
    fn a_centred_journal_gives_petroffs_torque_with_every_film() {
        for l_over_d in [0.25, 1.0, 2.5] {
            let g = geometry(l_over_d);
            let petroff = petroff_torque(&g, OMEGA);
            for model in [FilmModel::LongBearing, FilmModel::ShortBearing, FilmModel::LongBearingPaperClosedForm, FilmModel::Finite] {
                for eps in [0.0, 1e-3] {
                    let s = rotating(eps);
                    let f = film_force(model, &g, s, None);
                    let t = film_friction(&g, s, OMEGA, 0.0, f);
                    assert!((-t.journal / petroff - 1.0).abs() < 0.01, "{model:?} L/D {l_over_d} ε {eps}: {} vs {petroff}", t.journal);
                    assert!((t.bearing / petroff - 1.0).abs() < 0.01);
                    assert!((t.power_loss / (petroff * OMEGA) - 1.0).abs() < 0.01);
                }
            }
        }
    }

    #[test]
    fn long_bearing_closed_forms() {
        // Half Sommerfeld (the long film's Gümbel condition): πμR³Lω(4 + 5ε²)/(c(2 + ε²)√(1 − ε²)).
        // Full Sommerfeld (twice its F_η): 4πμR³Lω(1 + 2ε²)/(c(2 + ε²)√(1 − ε²)).
        let g = geometry(4.0);
        let k = PI * g.viscosity * g.journal_radius.powi(3) * g.length * OMEGA / g.clearance;
        for eps in [0.1, 0.3, 0.5, 0.7, 0.9, 0.99] {
            let s = rotating(eps);
            let root = ((1.0 - eps) * (1.0 + eps)).sqrt();
            let e2 = eps * eps;
            let f = long_bearing_force(&g, s);
            let half = film_friction(&g, s, OMEGA, 0.0, f).journal;
            let want = -k * (4.0 + 5.0 * e2) / ((2.0 + e2) * root);
            assert!((half / want - 1.0).abs() < 1e-9, "half ε {eps}: {half} vs {want}");
            let full = film_friction(&g, s, OMEGA, 0.0, (0.0, 2.0 * f.1)).journal;
            let want = -4.0 * k * (1.0 + 2.0 * e2) / ((2.0 + e2) * root);
            assert!((full / want - 1.0).abs() < 1e-9, "full ε {eps}: {full} vs {want}");
        }
    }

    #[test]
    fn short_bearing_closed_form() {
        // Ocvirk: F_η = πμRωεL³/(4c²(1 − ε²)^{3/2}), so T = 2πμR³Lω/(c√(1−ε²)) + πμRL³ωε²/(8c(1−ε²)^{3/2}).
        let g = geometry(0.25);
        let (mu, r, l, c) = (g.viscosity, g.journal_radius, g.length, g.clearance);
        for eps in [0.1, 0.5, 0.9, 0.99] {
            let s = rotating(eps);
            let b2 = (1.0 - eps) * (1.0 + eps);
            let t = film_friction(&g, s, OMEGA, 0.0, short_bearing_force(&g, s)).journal;
            let want = -(TAU * mu * r.powi(3) * l * OMEGA / (c * b2.sqrt()) + PI * mu * r * l.powi(3) * OMEGA * eps * eps / (8.0 * c * b2.powf(1.5)));
            assert!((t / want - 1.0).abs() < 1e-9, "ε {eps}: {t} vs {want}");
        }
    }

    /// ∫ f over [0, 2π] by 4096 panels of 8-point Gauss–Legendre (the Poiseuille integrand jumps
    /// where the film ruptures: the panels' width sets the error, ~1e-4 here).
    fn around(f: impl Fn(f64) -> f64) -> f64 {
        let n = 4096;
        let w = TAU / n as f64;
        (0..n).map(|k| GL8.integrate(w * k as f64, w * (k + 1) as f64, &f)).sum()
    }

    #[test]
    fn shear_quadrature_over_each_films_pressure() {
        // A second method: τ_j integrated over the film with ∂p/∂θ of the film's own positive
        // pressure (central differences), wedge, squeeze and sliding mixed.
        let s = FilmState { eps: 0.6, eps_dot: 3.0, wedge: 70.0 };
        let (wj, wb) = (50.0, -20.0);
        let d = 1e-6;
        for (name, g, pressure) in [
            ("long", geometry(4.0), Box::new(|g: &BearingGeometry, t: f64| long_bearing_pressure(g, s, t).max(0.0) * g.length) as Box<dyn Fn(&BearingGeometry, f64) -> f64>),
            ("short", geometry(0.25), Box::new(|g: &BearingGeometry, t: f64| {
                // ∫ p dz by 16-point Gauss–Legendre over the length.
                GL16.integrate(-0.5 * g.length, 0.5 * g.length, |z| short_bearing_pressure(g, s, t, z).max(0.0))
            })),
        ] {
            let (mu, r, c) = (g.viscosity, g.journal_radius, g.clearance);
            let h = |t: f64| c * (1.0 + s.eps * t.cos());
            // ∫ τ_j R dz per unit θ, times R: the torque.
            let couette = around(|t| mu * r * (wb - wj) / h(t)) * g.length * r * r;
            let poiseuille = around(|t| -(h(t) / (2.0 * r)) * (pressure(&g, t + d) - pressure(&g, t - d)) / (2.0 * d)) * r * r;
            let f = if name == "long" { long_bearing_force(&g, s) } else { short_bearing_force(&g, s) };
            let t = film_friction(&g, s, wj, wb, f);
            assert!((couette / t.couette - 1.0).abs() < 1e-9, "{name}: Couette {couette} vs {}", t.couette);
            assert!((poiseuille / t.poiseuille - 1.0).abs() < 1e-3, "{name}: Poiseuille {poiseuille} vs {}", t.poiseuille);
        }
    }

    #[test]
    fn torques_balance_the_film_moment_and_power_is_frame_free() {
        let g = geometry(1.0);
        let s = FilmState { eps: 0.7, eps_dot: -2.0, wedge: 40.0 };
        let f = film_force(FilmModel::Finite, &g, s, None);
        let t = film_friction(&g, s, 30.0, -10.0, f);
        let e = g.clearance * s.eps;
        assert!((t.journal + t.bearing + e * f.1).abs() < 1e-12 * (e * f.1).abs());
        // P = −(F·ė + T_j θ̇_j + T_b θ̇_b), ė = (c ε̇, e γ̇), wedge = θ̇_j + θ̇_b − 2γ̇ (γ̇ = 0 here).
        let s2 = FilmState { wedge: 30.0 - 10.0, ..s };
        let t2 = film_friction(&g, s2, 30.0, -10.0, f);
        let direct = -(f.0 * g.clearance * s.eps_dot + t2.journal * 30.0 + t2.bearing * -10.0);
        assert!((t2.power_loss / direct - 1.0).abs() < 1e-12, "{} vs {direct}", t2.power_loss);
        // Turning the whole joint at Ω adds Ω to both speeds and to the whirl γ̇: the wedge
        // θ̇_j + θ̇_b − 2γ̇ and the power stay.
        let omega = 17.0;
        let t3 = film_friction(&g, s2, 30.0 + omega, -10.0 + omega, f);
        assert_eq!(t3.power_loss, t2.power_loss);
    }

    #[test]
    fn raimondi_boyd_friction_variable_at_l_over_d_one() {
        // Raimondi & Boyd (1958), full bearing, L/D = 1: (ε, S, φ [°], (R/c) f), their S =
        // (R/c)² μ N/P with N in rev/s and P = F/(L D); clearsim's finite film with the supply
        // line (their convention) at the same ε, and this file's friction: (R/c) f = |T_j|/(c F).
        let rb = [(0.1, 1.33, 79.5, 26.4), (0.2, 0.631, 74.02, 12.8), (0.4, 0.264, 63.10, 5.79), (0.6, 0.121, 50.58, 3.22), (0.8, 0.0446, 36.24, 1.70), (0.9, 0.0188, 26.45, 1.05), (0.97, 0.00474, 15.47, 0.514)];
        let g = geometry(1.0);
        let mut solver = ReynoldsSolver::new(1.0, FilmSupply::WidestGap, ReynoldsGrid::default());
        for (eps, s_rb, phi_rb, f_rb) in rb {
            let (ix, iy) = solver.solve(eps, PI / 2.0, crate::laws::bearing_finite::Cavitation::Reynolds);
            let r = g.journal_radius;
            let scale = 3.0 * g.viscosity * r.powi(3) * g.length * OMEGA * eps / (g.clearance * g.clearance);
            let f = (scale * ix, scale * iy);
            let load = f.0.hypot(f.1);
            let s = (r / g.clearance).powi(2) * g.viscosity * (OMEGA / TAU) / (load / (g.length * 2.0 * r));
            let phi = f.1.atan2(-f.0).to_degrees();
            let t = film_friction(&g, rotating(eps), OMEGA, 0.0, f);
            let rcf = t.journal.abs() / (g.clearance * load);
            eprintln!("R-B L/D = 1, ε {eps}: S {s:.4} ({s_rb}), φ {phi:.2}° ({phi_rb}°), (R/c)f {rcf:.4} ({f_rb}, {:+.2} %)", 100.0 * (rcf / f_rb - 1.0));
            assert!((s / s_rb - 1.0).abs() < 0.02, "ε {eps}: S {s:.4} vs {s_rb}");
            assert!((phi - phi_rb).abs() < 0.7, "ε {eps}: φ {phi:.2} vs {phi_rb}");
            assert!((rcf / f_rb - 1.0).abs() < 0.02, "ε {eps}: (R/c)f {rcf:.4} vs {f_rb}");
        }
    }

    #[test]
    fn dry_moment() {
        assert_eq!(dry_friction_torque(0.01, 0.0105, -3.0), (-0.03, 0.0105 * 3.0));
    }
}
