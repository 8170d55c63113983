//! Short (Ocvirk) journal bearing with wedge and squeeze and the Gümbel condition (docs/physics.md §4).
//!
//! Short-bearing Reynolds equation (circumferential pressure flow neglected, L/D < 1):
//! `∂/∂z (h³ ∂p/∂z) = 6μ W ∂h/∂θ + 12μ ∂h/∂t`, `h = c(1 + ε cosθ)`, `∂h/∂θ = −cε sinθ`,
//! `∂h/∂t = c ε̇ cosθ`, W = θ̇_j + θ̇_i − 2γ̇, with p = 0 at z = ±L/2:
//! `p(θ, z) = (3μ/c²)(L²/4 − z²) (Wε sinθ − 2ε̇ cosθ)/(1 + ε cosθ)³`.
//! Integrated over z ∈ [−L/2, L/2] (∫(L²/4 − z²)dz = L³/6):
//! `P(θ) = (μL³/(2c²)) (Wε sinθ − 2ε̇ cosθ)/(1 + ε cosθ)³`.
//!
//! Positive arc (sign-aware): `Wε sinθ − 2ε̇ cosθ = ρ cos(θ − θm)` with
//! `θm = atan2(Wε, −2ε̇)`, so p > 0 exactly on (θm − π/2, θm + π/2) — a half film turned by the
//! combined wedge and squeeze action (pure rotation: (0, π); approaching squeeze: (π/2, 3π/2);
//! receding squeeze: (−π/2, π/2), the thick side).
//!
//! θ-integrals in closed form with the Sommerfeld angle ψ (`cosψ = (cosθ + ε)/(1 + ε cosθ)`,
//! `sinψ = β sinθ/(1 + ε cosθ)`, β = √(1−ε²), `dθ/(1+ε cosθ)³ = (1 − ε cosψ)²/β⁵ dψ`), where every
//! integrand becomes a trigonometric polynomial in ψ:
//! - `∫ sin²θ/v³ dθ = (ψ − sinψ cosψ)/(2β³)`,
//! - `∫ cos²θ/v³ dθ = (ψ(1/2 + ε²) + sinψ cosψ/2 − 2ε sinψ)/β⁵`,
//! - `∫ sinθ cosθ/v³ dθ = (sin²ψ/2 + ε cosψ)/β⁴`.

use super::geometry::{BearingGeometry, FilmState};
use std::f64::consts::TAU;

/// Axially integrated short-bearing pressure P(θ) = ∫ p dz [Pa·m] before the Gümbel cut,
/// θ \[rad\] counter-clockwise from the thickest film.
pub fn short_bearing_pressure_integrated(g: &BearingGeometry, s: FilmState, theta: f64) -> f64 {
    let eps = s.clamped_eps();
    let (sn, cs) = theta.sin_cos();
    let v = 1.0 + eps * cs;
    let l3 = g.length * g.length * g.length;
    g.viscosity * l3 / (2.0 * g.clearance * g.clearance) * (s.wedge * eps * sn - 2.0 * s.eps_dot * cs) / (v * v * v)
}

/// Short-bearing pressure p(θ, z) \[Pa\] before the Gümbel cut, z \[m\] ∈ [−L/2, L/2] axial.
pub fn short_bearing_pressure(g: &BearingGeometry, s: FilmState, theta: f64, z: f64) -> f64 {
    let half = 0.5 * g.length;
    let weight = (half * half - z * z).max(0.0);
    // P(θ) = (μL³/(2c²))·G/v³ and p = (3μ/c²)(L²/4 − z²)·G/v³ = P · 6(L²/4 − z²)/L³.
    short_bearing_pressure_integrated(g, s, theta) * 6.0 * weight / (g.length * g.length * g.length)
}

/// Short-bearing film force `(F_ξ, F_η)` \[N\] on the journal: `R ∫ P⁺ (cosθ, sinθ) dθ` over the
/// positive half film (module doc), in closed form. ε is clamped to [0, 1 − 1e-9].
pub fn short_bearing_force(g: &BearingGeometry, s: FilmState) -> (f64, f64) {
    let eps = s.clamped_eps();
    // G(θ) = A sinθ + B cosθ.
    let (a, b) = (s.wedge * eps, -2.0 * s.eps_dot);
    let rho = a.hypot(b);
    if rho.is_nan() || rho <= 0.0 {
        return (0.0, 0.0);
    }
    // Arc ends θm ∓ π/2: sin, cos from sinθm = A/ρ, cosθm = B/ρ.
    let (sm, cm) = (a / rho, b / rho);
    let (s1, c1) = (-cm, sm);
    let (s2, c2) = (cm, -sm);
    let beta2 = (1.0 - eps) * (1.0 + eps);
    let beta = beta2.sqrt();
    let sommerfeld = |sn: f64, cs: f64| {
        let v = 1.0 + eps * cs;
        let (sp, cp) = (beta * sn / v, (cs + eps) / v);
        (sp.atan2(cp), sp, cp)
    };
    let (psi1, sp1, cp1) = sommerfeld(s1, c1);
    let (mut psi2, sp2, cp2) = sommerfeld(s2, c2);
    // ψ(θ) is increasing; the arc has length π in θ, so 0 < ψ2 − ψ1 < 2π.
    if psi2 <= psi1 {
        psi2 += TAU;
    }
    let beta3 = beta2 * beta;
    let k_ss = |psi: f64, sp: f64, cp: f64| (psi - sp * cp) / (2.0 * beta3);
    let k_cc = |psi: f64, sp: f64, cp: f64| (psi * (0.5 + eps * eps) + 0.5 * sp * cp - 2.0 * eps * sp) / (beta3 * beta2);
    let k_cs = |sp: f64, cp: f64| (0.5 * sp * sp + eps * cp) / (beta2 * beta2);
    let d_ss = k_ss(psi2, sp2, cp2) - k_ss(psi1, sp1, cp1);
    let d_cc = k_cc(psi2, sp2, cp2) - k_cc(psi1, sp1, cp1);
    let d_cs = k_cs(sp2, cp2) - k_cs(sp1, cp1);
    let l3 = g.length * g.length * g.length;
    let scale = g.journal_radius * g.viscosity * l3 / (2.0 * g.clearance * g.clearance);
    (scale * (a * d_cs + b * d_cc), scale * (a * d_ss + b * d_cs))
}


#[cfg(test)]
mod tests {
    use super::*;
    use crate::laws::geometry::attitude_angle;
    use crate::laws::quadrature::GL16;
    use std::f64::consts::PI;

    /// B/D = 1/8: R = 10 mm, L = 2.5 mm.
    const G: BearingGeometry = BearingGeometry { viscosity: 0.05, journal_radius: 0.01, clearance: 2e-5, length: 0.0025 };

    fn st(eps: f64, eps_dot: f64, wedge: f64) -> FilmState {
        FilmState { eps, eps_dot, wedge }
    }

    /// Butenschön's Sommerfeld number: So = F Ψ²/(B D η |ω|) with Ψ = c/R, B = L, D = 2R,
    /// and |ω| = |wedge| (rotation) or |ε̇| (squeeze).
    fn sommerfeld(f: (f64, f64), rate: f64) -> f64 {
        let psi = G.clearance / G.journal_radius;
        f.0.hypot(f.1) * psi * psi / (G.length * 2.0 * G.journal_radius * G.viscosity * rate.abs())
    }

    /// Rows of a Butenschön table: the numeric columns after "B_over_D".
    fn table(text: &str) -> Vec<Vec<f64>> {
        text.lines()
            .filter(|l| !l.starts_with('#') && !l.starts_with("B_over_D") && !l.trim().is_empty())
            .map(|l| l.split(',').skip(1).map(|x| x.trim().parse::<f64>().unwrap()).collect())
            .collect()
    }

    #[test]
    fn ocvirk_pure_rotation_closed_form() {
        // Ocvirk half film (e.g. Hamrock, Fundamentals of Fluid Film Lubrication, short bearing):
        // F_ξ = −μ W R L³ ε² / (c² (1 − ε²)²), F_η = π μ W R L³ ε / (4 c² (1 − ε²)^{3/2}).
        let k = G.viscosity * G.journal_radius * G.length.powi(3) / (G.clearance * G.clearance);
        for eps in [0.0, 1e-8, 0.1, 0.5, 0.9, 0.99] {
            for w in [60.0, -60.0] {
                let f = short_bearing_force(&G, st(eps, 0.0, w));
                let fx = -k * w.abs() * eps * eps / (1.0 - eps * eps).powi(2);
                let fy = PI * k * w * eps / (4.0 * (1.0 - eps * eps).powf(1.5));
                assert!((f.0 - fx).abs() <= 1e-12 * fx.abs().max(fy.abs()) + 1e-300, "ε {eps}: F_ξ {} vs {fx}", f.0);
                assert!((f.1 - fy).abs() <= 1e-12 * fy.abs() + 1e-300, "ε {eps}: F_η {} vs {fy}", f.1);
            }
        }
    }

    #[test]
    fn pure_squeeze_signs_and_closed_form() {
        // Approaching: half film (π/2, 3π/2) on the thin side pushes the journal back (F_ξ < 0).
        // Receding: half film on the thick side (−π/2, π/2); F_ξ > 0. F_η = 0 in both.
        // ε = 0: |F| = R (μL³/(2c²)) 2|ε̇| ∫_{π/2}^{3π/2} cos²θ dθ = π μ R L³ |ε̇|/(2c²).
        let k = G.viscosity * G.journal_radius * G.length.powi(3) / (G.clearance * G.clearance);
        let f = short_bearing_force(&G, st(0.0, 2.0, 0.0));
        assert!((f.0 + PI * k * 2.0 / 2.0).abs() < 1e-12 * k && f.1.abs() < 1e-12 * k);
        for eps in [0.2, 0.8] {
            let a = short_bearing_force(&G, st(eps, 2.0, 0.0));
            let r = short_bearing_force(&G, st(eps, -2.0, 0.0));
            assert!(a.0 < 0.0 && r.0 > 0.0 && a.1.abs() < 1e-12 * a.0.abs() && r.1.abs() < 1e-12 * r.0.abs());
            assert!(a.0.abs() > r.0.abs());
        }
    }

    /// Independent reference: composite Simpson (200 000 intervals) over [0, 2π] of
    /// R·max(P, 0)·(cosθ, sinθ) with P written out from the module doc.
    fn simpson_force(eps: f64, eps_dot: f64, wedge: f64) -> (f64, f64) {
        let n = 200_000;
        let h = 2.0 * PI / n as f64;
        let k = G.viscosity * G.length.powi(3) / (2.0 * G.clearance * G.clearance);
        let (mut fx, mut fy) = (0.0, 0.0);
        for i in 0..=n {
            let th = i as f64 * h;
            let w = if i == 0 || i == n { 1.0 } else if i % 2 == 1 { 4.0 } else { 2.0 };
            let p = (k * (wedge * eps * th.sin() - 2.0 * eps_dot * th.cos()) / (1.0 + eps * th.cos()).powi(3)).max(0.0);
            fx += w * p * th.cos();
            fy += w * p * th.sin();
        }
        (G.journal_radius * h / 3.0 * fx, G.journal_radius * h / 3.0 * fy)
    }

    #[test]
    fn force_matches_independent_simpson() {
        let mut worst = 0.0_f64;
        for eps in [0.0, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.95, 0.99] {
            for (w, ed) in [(0.0, 3.0), (0.0, -3.0), (50.0, 0.0), (-50.0, 0.0), (50.0, 0.5), (50.0, -0.5), (-50.0, 5.0), (-50.0, -50.0), (7.0, 30.0)] {
                let f = short_bearing_force(&G, st(eps, ed, w));
                let r = simpson_force(eps, ed, w);
                let n = r.0.hypot(r.1);
                if n == 0.0 {
                    assert_eq!(f, (0.0, 0.0), "ε {eps} W {w} ε̇ {ed}");
                    continue;
                }
                let err = (f.0 - r.0).abs().max((f.1 - r.1).abs()) / n;
                worst = worst.max(err);
                assert!(err < 1e-6, "ε {eps} W {w} ε̇ {ed}: {f:?} vs {r:?} ({err:.2e})");
            }
        }
        eprintln!("short bearing vs Simpson: max |ΔF|/|F| {worst:.2e}");
    }

    #[test]
    fn pressure_axial_profile_integrates_to_p() {
        let s = st(0.6, 1.5, 40.0);
        for th in [0.3, 1.9, 4.0] {
            let big_p = short_bearing_pressure_integrated(&G, s, th);
            let q = GL16.integrate(-0.5 * G.length, 0.5 * G.length, |z| short_bearing_pressure(&G, s, th, z));
            assert!((q - big_p).abs() < 1e-12 * big_p.abs());
        }
        assert_eq!(short_bearing_pressure(&G, s, 1.0, 0.5 * G.length), 0.0);
    }

    #[test]
    fn butenschoen_rotation_bd_1_8() {
        // Butenschön's β is the attitude angle: the angle between the load line (the external
        // load, −F) and the eccentricity n, here atan2(|F_η|, −F_ξ). So with ω_res = wedge.
        let rows = table(include_str!("../../tests/data/butenschoen_rotation_BD1_8.csv"));
        assert_eq!(rows.len(), 14);
        let (mut worst_so, mut worst_beta) = (0.0_f64, 0.0_f64);
        eprintln!("short bearing vs Butenschön B/D = 1/8, rotation:   ε   So(table) So(Ocvirk) rel   β(table) β(Ocvirk) rel");
        for r in rows {
            let (eps, so_tab, beta_tab) = (r[0], r[1], r[2]);
            let w = 120.0;
            let f = short_bearing_force(&G, st(eps, 0.0, w));
            let so = sommerfeld(f, w);
            let beta = attitude_angle(f).to_degrees();
            let (e_so, e_beta) = (so / so_tab - 1.0, beta / beta_tab - 1.0);
            eprintln!("  {eps:5.2} {so_tab:9.4} {so:9.4} {e_so:+7.3}  {beta_tab:7.3} {beta:7.3} {e_beta:+7.4}");
            if eps <= 0.6 + 1e-12 {
                worst_so = worst_so.max(e_so.abs());
                worst_beta = worst_beta.max(e_beta.abs());
            }
        }
        eprintln!("  ε ≤ 0.6: max |rel err| So {worst_so:.4}, β {worst_beta:.4}");
        assert!(worst_so < 0.03 && worst_beta < 0.03);
    }

    #[test]
    fn butenschoen_squeeze_bd_1_8() {
        // Negative table ε: receding journal (ε̇ < 0) at eccentricity |ε|.
        let rows = table(include_str!("../../tests/data/butenschoen_squeeze_BD1_8.csv"));
        assert_eq!(rows.len(), 29);
        let mut worst = 0.0_f64;
        eprintln!("short bearing vs Butenschön B/D = 1/8, squeeze:   ε   So(table) So(Ocvirk) rel");
        for r in rows {
            let (eps_signed, so_tab) = (r[0], r[1]);
            let eps_dot = if eps_signed < 0.0 { -0.7 } else { 0.7 };
            let f = short_bearing_force(&G, st(eps_signed.abs(), eps_dot, 0.0));
            let so = sommerfeld(f, eps_dot);
            let e = so / so_tab - 1.0;
            eprintln!("  {eps_signed:+5.2} {so_tab:10.4} {so:10.4} {e:+7.3}");
            if eps_signed.abs() <= 0.6 + 1e-12 {
                worst = worst.max(e.abs());
            }
        }
        eprintln!("  |ε| ≤ 0.6: max |rel err| So {worst:.4}");
        assert!(worst < 0.03);
    }
}
