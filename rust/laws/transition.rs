//! Small-eccentricity scaling (paper Eqs. 15–16) and the film-to-contact transition (Eq. 18),
//! docs/physics.md §4.

/// Scale factor applied to both film-force components near the bearing centre (docs/physics.md
/// §4, P15–P16 made continuous): `(ε/ε0)^m` for `ε < ε0`, else 1.
///
/// The paper prints `ε^m` below ε0, which jumps from `ε0^m` (≈ 1.4e-3 for ε0 = 2e-6, m = 0.5)
/// to 1 at `ε = ε0`. With a µm clearance that jump is a discontinuity the film's huge damping
/// turns into chattering on the surface ε = ε0 (a 5 µm lubricated slider-crank starting centred
/// stopped with a step-size underflow at t = 4e-8 s); `(ε/ε0)^m` is continuous and equals the
/// paper's factor up to the constant ε0^m where both act, i.e. only for e < ε0 c (1 nm at
/// c = 0.5 mm). At `ε = 0` it gives 0 (for m > 0), so a centred journal (where `n` is
/// undefined) gets no film force. Negative ε is treated as 0.
pub fn small_eccentricity_scale(eps: f64, eps0: f64, m: f64) -> f64 {
    if eps < eps0 {
        (eps.max(0.0) / eps0).powf(m)
    } else {
        1.0
    }
}

/// Weights `(w_film, w_dry)` of the transition force (P18), eccentricity `e` \[m\], radial
/// clearance `c` \[m\], transition width `e0` \[m\]:
/// `e < c`: (1, 0); `c ≤ e ≤ c + e0`: `((c + e0 − e)/e0, (e − c)/e0)`; `e > c + e0`: (0, 1).
/// The force is `w_film F_film + w_dry F_dry`; the weights are continuous and sum to 1.
/// For `e0 ≤ 0` the blend degenerates to a switch at `e = c` (dry from `e = c` on).
pub fn transition_weights(e: f64, c: f64, e0: f64) -> (f64, f64) {
    if e < c {
        (1.0, 0.0)
    } else if e0.is_nan() || e0 <= 0.0 || e >= c + e0 {
        (0.0, 1.0)
    } else {
        let w_dry = ((e - c) / e0).clamp(0.0, 1.0);
        (1.0 - w_dry, w_dry)
    }
}

/// Eccentricity ratio at which the film is evaluated: `min(ε, ε_max)` (docs/physics.md §4: the film formula
/// is singular at ε → 1, so inside the blend, and beyond, it is evaluated at `ε_max`, assumed
/// 0.99). Negative or NaN ε gives 0.
pub fn film_eps(eps: f64, eps_max: f64) -> f64 {
    if eps.is_nan() || eps <= 0.0 {
        return 0.0;
    }
    eps.min(eps_max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::laws::film::{film_force, BearingGeometry, FilmModel, FilmState};

    #[test]
    fn weights_continuous_and_sum_to_one() {
        let (c, e0) = (5e-4, 0.05 * 5e-4);
        let h = 1e-15;
        for e_edge in [c, c + e0] {
            let a = transition_weights(e_edge - h, c, e0);
            let b = transition_weights(e_edge + h, c, e0);
            assert!((a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9, "jump at {e_edge}: {a:?} {b:?}");
        }
        for i in 0..=100 {
            let e = c * (0.9 + 0.002 * i as f64);
            let (wf, wd) = transition_weights(e, c, e0);
            assert!((wf + wd - 1.0).abs() < 1e-15 && (0.0..=1.0).contains(&wf));
        }
        assert_eq!(transition_weights(0.5 * c, c, e0), (1.0, 0.0));
        assert_eq!(transition_weights(2.0 * c, c, e0), (0.0, 1.0));
        let mid = transition_weights(c + 0.25 * e0, c, e0);
        assert!((mid.0 - 0.75).abs() < 1e-12 && (mid.1 - 0.25).abs() < 1e-12);
        assert_eq!(transition_weights(c, c, 0.0), (0.0, 1.0));
    }

    #[test]
    fn scale_values() {
        let (eps0, m) = (2e-6, 0.5);
        assert_eq!(small_eccentricity_scale(0.0, eps0, m), 0.0);
        assert!((small_eccentricity_scale(0.5e-6, eps0, m) - 0.5).abs() < 1e-15);
        assert_eq!(small_eccentricity_scale(2e-6, eps0, m), 1.0);
        assert_eq!(small_eccentricity_scale(0.5, eps0, m), 1.0);
        // Continuous at ε0 (the paper's printed ε^m jumps 700× there).
        assert!((small_eccentricity_scale(eps0 * (1.0 - 1e-12), eps0, m) - 1.0).abs() < 1e-11);
        assert_eq!(small_eccentricity_scale(-1.0, eps0, m), 0.0);
    }

    #[test]
    fn film_eps_values() {
        assert_eq!(film_eps(0.5, 0.99), 0.5);
        assert_eq!(film_eps(1.5, 0.99), 0.99);
        assert_eq!(film_eps(-0.1, 0.99), 0.0);
        assert_eq!(film_eps(f64::NAN, 0.99), 0.0);
    }

    #[test]
    fn no_nan_with_film_eps_applied() {
        let g = BearingGeometry { viscosity: 0.4, journal_radius: 0.01, clearance: 5e-4, length: 0.05 };
        let c = g.clearance;
        for model in [FilmModel::LongBearing, FilmModel::ShortBearing, FilmModel::LongBearingPaperClosedForm] {
            for eps in [0.0, 1e-9, 0.5, 0.99, 1.0, 1.5] {
                for (eps_dot, wedge) in [(0.0, 0.0), (3.0, 0.0), (-3.0, 0.0), (0.0, 40.0), (2.0, -40.0), (-2.0, 40.0)] {
                    let fe = film_eps(eps, 0.99);
                    let f = film_force(model, &g, FilmState { eps: fe, eps_dot, wedge }, None);
                    let k = small_eccentricity_scale(eps, 2e-6, 0.5);
                    let (wf, wd) = transition_weights(eps * c, c, 0.05 * c);
                    let total = (wf * k * f.0 + wd * 1.0, wf * k * f.1);
                    assert!(total.0.is_finite() && total.1.is_finite(), "{model:?} ε {eps}: {f:?}");
                }
            }
        }
    }
}
