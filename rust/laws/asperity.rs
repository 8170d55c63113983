//! Rough surfaces in a lubricated joint (docs/physics.md §4, roughness): the Greenwood–Tripp
//! asperity pressure, the load the asperities carry where the film is thinner than 4σ, and
//! boundary friction on that load.
//!
//! Greenwood & Tripp (1970–71, *Proc. IMechE* 185:625–633), two rough surfaces with Gaussian
//! heights of composite RMS roughness σ, asperity density η [1/m²] and summit radius β \[m\], a
//! mean gap h and the Hertz composite modulus E' (1/E' = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂, the modulus
//! of the Hertz law from which the model is built):
//!
//! `p_a(h) = K E' F_{5/2}(h/σ)`, `K = (16√2/15) π (σηβ)² √(σ/β)`,
//! `F_{5/2}(H) = (1/√(2π)) ∫_H^∞ (s − H)^{5/2} e^{−s²/2} ds`.
//!
//! [`f52`] is the integral by quadrature; [`f52_fit`] the power-law fit
//! `4.4086·10⁻⁵ (4 − H)^{6.804}` for H < 4, 0 beyond (Hu, Cheng, Arai, Kobayashi & Aoyama 1994,
//! *J. Tribol.* 116:470–478, the fit used throughout mixed-lubrication models). Measured (tests):
//! the fit is 10.7 % low at H = 0, within 11 % up to H = 2.05 (closest, −1.6 %, near H = 1.4),
//! and falls short of the tail beyond (−35 % at H = 2.5, −74 % at 3); from H = 1.5 on its error
//! stays below 8.2·10⁻⁴ of F_{5/2}(0).
//!
//! Typical surface parameters: σηβ ≈ 0.03–0.05 for machined surfaces (Greenwood & Williamson
//! 1966, *Proc. R. Soc. A* 295:300–319), σ/β ≈ 10⁻⁴–10⁻²; [`GreenwoodTripp::typical`] takes
//! σηβ = 0.04 and σ/β = 10⁻³.
//!
//! In a journal bearing the gap is h(θ) = c (1 + ε cos θ) (θ from the widest gap, the film
//! laws' frame, [`super::geometry`]); the asperities press on the journal over the arc where
//! h < 4σ (where the fit is nonzero), uniformly along the length:
//! `F_ξ = R L ∫ p_a(h(θ)) cos θ dθ` along n (negative: away from the wall), `F_η = 0`.
//! Boundary friction: a coefficient μ_b on that load, acting like the dry friction of §3
//! (the modified Coulomb law of [`super::friction`] with μ_b in place of c_f).

use super::geometry::BearingGeometry;
use super::quadrature::{GL16, GL32};
use std::f64::consts::PI;

/// F_{5/2}(H) by quadrature (module doc), to ~1e-13 relative where it is above 1e-300.
pub fn f52(h_ratio: f64) -> f64 {
    // s = H + v²: ∫ (s − H)^{5/2} e^{−s²/2} ds = ∫₀^∞ 2 v⁶ e^{−(H + v²)²/2} dv, smooth in v.
    // Beyond v² = max(0, −H) + 12 the integrand is below e^{−72} of its scale: integrate to there
    // (plus a margin) in 16 panels.
    let v_max = ((-h_ratio).max(0.0) + 12.0).sqrt() + 1.0;
    let panels = 16;
    let w = v_max / panels as f64;
    let sum: f64 = (0..panels)
        .map(|k| {
            GL16.integrate(w * k as f64, w * (k + 1) as f64, |v| {
                let v2 = v * v;
                let s = h_ratio + v2;
                2.0 * v2 * v2 * v2 * (-0.5 * s * s).exp()
            })
        })
        .sum();
    sum / (2.0 * PI).sqrt()
}

/// The fit 4.4086·10⁻⁵ (4 − H)^{6.804} of F_{5/2} for H < 4, 0 for H ≥ 4 (module doc).
pub fn f52_fit(h_ratio: f64) -> f64 {
    if h_ratio.is_nan() || h_ratio >= 4.0 {
        return 0.0;
    }
    4.4086e-5 * (4.0 - h_ratio).powf(6.804)
}

/// Greenwood–Tripp parameters of the two surfaces of a joint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GreenwoodTripp {
    /// Composite RMS roughness σ = √(σ₁² + σ₂²) \[m\].
    pub roughness: f64,
    /// Roughness parameter σηβ [-].
    pub sigma_eta_beta: f64,
    /// σ/β [-] (β the asperity summit radius).
    pub sigma_over_beta: f64,
    /// Composite modulus E' \[Pa\] (module doc).
    pub modulus: f64,
}

impl GreenwoodTripp {
    /// σηβ = 0.04, σ/β = 10⁻³ (module doc) for roughness `sigma` \[m\] and modulus `modulus` \[Pa\].
    pub fn typical(sigma: f64, modulus: f64) -> Self {
        GreenwoodTripp { roughness: sigma, sigma_eta_beta: 0.04, sigma_over_beta: 1e-3, modulus }
    }

    /// K E' \[Pa\]: p_a = K E' F_{5/2}(h/σ).
    pub fn pressure_scale(&self) -> f64 {
        16.0 * 2f64.sqrt() / 15.0 * PI * self.sigma_eta_beta * self.sigma_eta_beta * self.sigma_over_beta.sqrt() * self.modulus
    }

    /// Asperity pressure p_a \[Pa\] at the gap `h` \[m\], with the fit (0 where h ≥ 4σ).
    pub fn pressure(&self, h: f64) -> f64 {
        self.pressure_scale() * f52_fit(h / self.roughness)
    }

    /// The asperities' force `(F_ξ, F_η)` \[N\] on the journal of bearing `g` at eccentricity ratio
    /// `eps` (module doc): 0 while the smallest gap c (1 − ε) is at least 4σ. `eps` may exceed 1
    /// (the surfaces' mean lines then overlap: h < 0 at the thinnest point).
    pub fn force(&self, g: &BearingGeometry, eps: f64) -> (f64, f64) {
        if eps.is_nan() || eps <= 0.0 {
            return (0.0, 0.0);
        }
        // h(θ) < 4σ ⟺ cos θ < (4σ/c − 1)/ε: the arc (θ0, 2π − θ0), symmetric about θ = π.
        let x = (4.0 * self.roughness / g.clearance - 1.0) / eps;
        if x <= -1.0 {
            return (0.0, 0.0);
        }
        let theta0 = if x >= 1.0 { 0.0 } else { x.acos() };
        // Two panels of 32-point Gauss–Legendre over (θ0, π), the half the arc: p_a rises from 0
        // as (4 − H)^6.8 at θ0 and peaks at π.
        let mid = 0.5 * (theta0 + PI);
        let f = |t: f64| self.pressure(g.clearance * (1.0 + eps * t.cos())) * t.cos();
        let half = GL32.integrate(theta0, mid, f) + GL32.integrate(mid, PI, f);
        (2.0 * g.journal_radius * g.length * half, 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integral_at_zero_and_by_a_second_rule() {
        // F_{5/2}(0) = 2^{3/4} Γ(7/4)/√(2π), Γ(7/4) = 0.9190625268488832.
        let exact = 2f64.powf(0.75) * 0.919_062_526_848_883_2 / (2.0 * PI).sqrt();
        assert!((f52(0.0) / exact - 1.0).abs() < 1e-13, "{} vs {exact}", f52(0.0));
        // Composite Simpson in s on [H, H + 12] with 200 000 intervals.
        for h in [-1.0, 0.5, 2.0, 3.5] {
            let n = 200_000;
            let w = 12.0 / n as f64;
            let f = |s: f64| (s - h).max(0.0).powf(2.5) * (-0.5 * s * s).exp();
            let mut sum = f(h) + f(h + 12.0);
            for i in 1..n {
                sum += f(h + w * i as f64) * if i % 2 == 1 { 4.0 } else { 2.0 };
            }
            let simpson = sum * w / 3.0 / (2.0 * PI).sqrt();
            assert!((f52(h) / simpson - 1.0).abs() < 1e-9, "H {h}: {} vs {simpson}", f52(h));
        }
        // dF_{5/2}/dH = −(5/2) F_{3/2} < 0: decreasing.
        let mut last = f64::INFINITY;
        for k in 0..60 {
            let v = f52(-2.0 + 0.1 * k as f64);
            assert!(v < last && v > 0.0);
            last = v;
        }
    }

    /// The fit against the integral over its range H ∈ [0, 4): the accuracy the module doc states.
    #[test]
    fn fit_against_the_integral() {
        let peak = f52(0.0);
        let (mut worst_rel, mut worst_abs) = (0.0f64, 0.0f64);
        for k in 0..400 {
            let h = 0.01 * k as f64;
            let (exact, fit) = (f52(h), f52_fit(h));
            if h <= 2.05 {
                worst_rel = worst_rel.max((fit / exact - 1.0).abs());
            }
            if h >= 1.5 {
                worst_abs = worst_abs.max((fit - exact).abs() / peak);
            }
            assert!(fit < exact, "H {h}: the fit is below the integral everywhere");
        }
        assert!(worst_rel < 0.11, "relative error up to H = 2.05: {worst_rel}");
        assert!(worst_abs < 8.2e-4, "error beyond H = 1.5, of F(0): {worst_abs}");
        assert!((f52_fit(0.0) / peak - 1.0 + 0.1073).abs() < 1e-3);
        assert!((f52_fit(1.4) / f52(1.4) - 1.0).abs() < 0.017);
        assert_eq!(f52_fit(4.0), 0.0);
        assert_eq!(f52_fit(7.0), 0.0);
    }

    #[test]
    fn journal_force() {
        let g = BearingGeometry { viscosity: 0.05, journal_radius: 0.02, clearance: 2e-5, length: 0.02 };
        let gt = GreenwoodTripp::typical(1e-6, 1.137e11);
        // Smallest gap c (1 − ε) ≥ 4σ: no asperity contact.
        assert_eq!(gt.force(&g, 0.5), (0.0, 0.0));
        assert_eq!(gt.force(&g, 0.8), (0.0, 0.0));
        // Closer: a force pushing the journal back (F_ξ < 0), growing with ε; against a fine
        // trapezoid rule over the whole circumference.
        let mut last = 0.0;
        for eps in [0.82, 0.85, 0.9, 0.95, 1.0, 1.02] {
            let (fx, fy) = gt.force(&g, eps);
            assert!(fx < last && fy == 0.0, "ε {eps}: {fx}");
            last = fx;
            let n = 200_000;
            let w = 2.0 * PI / n as f64;
            let trap: f64 = (0..n).map(|i| {
                let t = w * i as f64;
                gt.pressure(g.clearance * (1.0 + eps * t.cos())) * t.cos()
            }).sum::<f64>() * w * g.journal_radius * g.length;
            assert!((fx / trap - 1.0).abs() < 1e-6, "ε {eps}: {fx} vs {trap}");
        }
        // h_min = 0 (ε = 1): p_a(0) = K E' F(0) over an arc of width ~ 2√(8σ/c).
        let (f1, _) = gt.force(&g, 1.0);
        assert!(f1 < 0.0 && f1.is_finite());
    }
}
