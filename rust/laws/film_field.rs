//! The film's pressure field and the oil it passes at one instant (docs/physics.md §4, "Oil flow
//! and pressure"): side leakage out of both ends, the flow the supply must deliver, the peak
//! pressure and where it sits, and the pressure over the bearing for a picture. Readings only,
//! computed when a run asks for them: the force laws ([`super::film`]) do not use this file.
//!
//! Frame as every film law ([`super::geometry`]): θ counter-clockwise from the widest gap,
//! h = c (1 + ε cos θ), W the wedge speed, ρ = hypot(Wε, 2ε̇).
//!
//! - Long (Pinkus–Sternlicht) film: infinitely long, no axial flow, so no side leakage; at a
//!   steady state it draws nothing from the supply either (the film's circumferential flow closes
//!   on itself), so both flows are 0. Pressure: P12 ([`super::long_bearing_pressure`]), cut at 0.
//! - Short (Ocvirk) film: p = (3μ/c²)(L²/4 − z²) ρ cos(θ − θm)/H³ on the half film where it is
//!   positive; the axial flux out of each end is h³/(12μ)·|∂p/∂z| = c L ρ cos(θ − θm)/4 per unit
//!   of circumference (H drops out), so out of both ends over the half film
//!   `Q_side = 2 · R ∫ c L ρ cos(θ − θm)/4 dθ = R c L ρ` (pure rotation: R c L W ε, Butenschön's
//!   Q = Q_side/(R² c W) = 2 (L/D) ε).
//! - Finite film (Reynolds condition): the field of a direct solve on the tables' grid
//!   ([`super::bearing_finite::ReynoldsSolver`]); with p = (6μR²ρ/c²) P and z = (L/2) ζ the
//!   flux out of an end is −(c R² ρ / L) H³ ∂P/∂ζ per unit of θ, so
//!   `Q_side = (2 c R³ ρ / L) ∫ H³ (−∂P/∂ζ)|_{ζ=1} dθ` (both ends; ∂P/∂ζ one-sided, second order).
//!
//! Supply flow of these films: they keep the gap full wherever p > 0 and do not follow the oil
//! through the ruptured zone (Reynolds or Gümbel condition), so the supply is their quasi-steady
//! balance: the gap's volume 2πRLc does not change with the journal's position, so the oil that
//! leaves at the ends must be fed — supply = side leakage. A film that follows its oil content
//! (mass-conserving cavitation) gives both separately.

use super::bearing_finite::{Cavitation, ReynoldsGrid, ReynoldsSolver};
use super::geometry::{BearingGeometry, FilmState, FilmSupply};
use super::{bearing_long, bearing_short, FilmModel};
use std::f64::consts::TAU;

/// What one instant's film passes and peaks at.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FlowAndPeak {
    /// Oil out of both ends of the bearing \[m³/s\] (≥ 0).
    pub side_leakage: f64,
    /// Oil the supply must deliver \[m³/s\] (module doc).
    pub supply: f64,
    /// Largest film pressure \[Pa\] (≥ 0; 0 when the film carries nothing).
    pub peak_pressure: f64,
    /// Where it is: θ \[rad\] in [0, 2π) counter-clockwise from the widest gap (NaN without a peak).
    pub peak_angle: f64,
}

/// The film pressure over the bearing: `pressure[i * z.len() + j]` \[Pa\] at θ_i \[rad\] (from the
/// widest gap, counter-clockwise) and axial position z_j \[m\] (from the bearing's mid-plane; the
/// long and short films give the mid-plane only, `z = [0]`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FilmField {
    pub theta: Vec<f64>,
    pub z: Vec<f64>,
    pub pressure: Vec<f64>,
}

/// θ samples of the closed-form films' peak search and pictures.
const SAMPLES: usize = 720;

/// A finite film's solver, kept between calls for its warm start (one per joint).
#[derive(Clone, Debug)]
pub struct FiniteScratch {
    solver: ReynoldsSolver,
}

/// Buffers, not data: any two compare equal (so that what holds them, a recording, compares by
/// what it recorded).
impl PartialEq for FiniteScratch {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl FiniteScratch {
    /// For a bearing of length `g.length` and journal radius `g.journal_radius` with `supply`,
    /// on the finite tables' grid.
    pub fn new(g: &BearingGeometry, supply: FilmSupply) -> Self {
        FiniteScratch { solver: ReynoldsSolver::new(2.0 * g.journal_radius / g.length, supply, ReynoldsGrid::default()) }
    }
}

/// (ρ, θm) of a film state: the combined wedge and squeeze action (module doc).
fn action(s: &FilmState, eps: f64) -> (f64, f64) {
    let (a, b) = (s.wedge * eps, -2.0 * s.eps_dot);
    (a.hypot(b), a.atan2(b))
}

/// The film's flows and peak pressure (module doc). `scratch` is needed by the finite film only.
pub fn flow_and_peak(model: FilmModel, g: &BearingGeometry, s: FilmState, scratch: Option<&mut FiniteScratch>) -> FlowAndPeak {
    let eps = s.clamped_eps();
    let (rho, theta_m) = action(&s, eps);
    if !(rho.is_finite() && rho > 0.0) {
        return FlowAndPeak { peak_angle: f64::NAN, ..FlowAndPeak::default() };
    }
    match model {
        FilmModel::LongBearing | FilmModel::LongBearingPaperClosedForm => {
            let (peak_pressure, peak_angle) = peak_of(|th| bearing_long::long_bearing_pressure(g, s, th));
            FlowAndPeak { side_leakage: 0.0, supply: 0.0, peak_pressure, peak_angle }
        }
        FilmModel::ShortBearing => {
            let side = g.journal_radius * g.clearance * g.length * rho;
            let (peak_pressure, peak_angle) = peak_of(|th| bearing_short::short_bearing_pressure(g, s, th, 0.0));
            FlowAndPeak { side_leakage: side, supply: side, peak_pressure, peak_angle }
        }
        FilmModel::Finite => {
            let solver = &mut scratch.expect("a finite film's readings need its scratch").solver;
            solver.solve(eps, theta_m, Cavitation::Reynolds);
            let (theta, width, p) = solver.field();
            let nz = solver.grid.n_zeta;
            let dz = 1.0 / nz as f64;
            let r = g.journal_radius;
            let p_scale = 6.0 * g.viscosity * r * r * rho / (g.clearance * g.clearance);
            // −∂P/∂ζ at ζ = 1 from P(1) = 0, P(1 − dz), P(1 − 2dz) (one-sided, second order).
            let mut flux = 0.0;
            for (i, (&th, &w)) in theta.iter().zip(width).enumerate() {
                let last = p[i * nz + nz - 1].max(0.0);
                let before = if nz > 1 { p[i * nz + nz - 2].max(0.0) } else { 2.0 * last };
                let h = 1.0 + eps * th.cos();
                flux += w * h * h * h * (4.0 * last - before) / (2.0 * dz);
            }
            let side = 2.0 * g.clearance * r * r * r * rho / g.length * flux;
            let (peak, angle) = grid_peak(theta, &p.iter().step_by(nz).copied().collect::<Vec<_>>());
            FlowAndPeak { side_leakage: side, supply: side, peak_pressure: p_scale * peak, peak_angle: angle }
        }
    }
}

/// The film's pressure over the bearing (see [`FilmField`]): the long and short films on
/// `SAMPLES` angles at the mid-plane, the finite film on its solver's grid over the whole width.
pub fn film_field(model: FilmModel, g: &BearingGeometry, s: FilmState, scratch: Option<&mut FiniteScratch>) -> FilmField {
    let eps = s.clamped_eps();
    let (rho, theta_m) = action(&s, eps);
    let uniform: Vec<f64> = (0..SAMPLES).map(|i| TAU * i as f64 / SAMPLES as f64).collect();
    match model {
        FilmModel::LongBearing | FilmModel::LongBearingPaperClosedForm => {
            let pressure = uniform.iter().map(|&th| bearing_long::long_bearing_pressure(g, s, th).max(0.0)).collect();
            FilmField { theta: uniform, z: vec![0.0], pressure }
        }
        FilmModel::ShortBearing => {
            let pressure = uniform.iter().map(|&th| bearing_short::short_bearing_pressure(g, s, th, 0.0).max(0.0)).collect();
            FilmField { theta: uniform, z: vec![0.0], pressure }
        }
        FilmModel::Finite => {
            let solver = &mut scratch.expect("a finite film's field needs its scratch").solver;
            let nz = solver.grid.n_zeta;
            if !(rho.is_finite() && rho > 0.0) {
                let theta = (0..solver.grid.n_theta).map(|i| TAU * i as f64 / solver.grid.n_theta as f64).collect::<Vec<_>>();
                let n = theta.len();
                return FilmField { theta, z: full_width(nz, g.length), pressure: vec![0.0; n * (2 * nz + 1)] };
            }
            solver.solve(eps, theta_m, Cavitation::Reynolds);
            let (theta, _, p) = solver.field();
            let r = g.journal_radius;
            let p_scale = 6.0 * g.viscosity * r * r * rho / (g.clearance * g.clearance);
            // Mirror the half width (ζ ≥ 0) to the whole, with P = 0 at both ends.
            let z = full_width(nz, g.length);
            let mut pressure = Vec::with_capacity(theta.len() * z.len());
            for i in 0..theta.len() {
                let row = &p[i * nz..(i + 1) * nz];
                pressure.push(0.0);
                pressure.extend(row.iter().rev().map(|v| p_scale * v.max(0.0)));
                pressure.extend(row[1..].iter().map(|v| p_scale * v.max(0.0)));
                pressure.push(0.0);
            }
            FilmField { theta: theta.to_vec(), z, pressure }
        }
    }
}

/// Axial positions \[m\] of a half-width grid of `nz` nodes mirrored over the whole length, ends
/// included: −L/2 … L/2 (2 nz + 1 values).
fn full_width(nz: usize, length: f64) -> Vec<f64> {
    let half = 0.5 * length;
    (0..=2 * nz).map(|j| half * (j as f64 - nz as f64) / nz as f64).collect()
}

/// Peak of a closed-form pressure p(θ): the largest of [`SAMPLES`] samples refined by golden
/// section between its neighbours; (0, NaN) where p ≤ 0 everywhere.
fn peak_of(p: impl Fn(f64) -> f64) -> (f64, f64) {
    let h = TAU / SAMPLES as f64;
    let (mut best, mut at) = (0.0, f64::NAN);
    for i in 0..SAMPLES {
        let th = h * i as f64;
        let v = p(th);
        if v > best {
            best = v;
            at = th;
        }
    }
    if !(best > 0.0) {
        return (0.0, f64::NAN);
    }
    let (mut a, mut b) = (at - h, at + h);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut x1, mut x2) = (b - g * (b - a), a + g * (b - a));
    let (mut f1, mut f2) = (p(x1), p(x2));
    for _ in 0..60 {
        if f1 > f2 {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - g * (b - a);
            f1 = p(x1);
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + g * (b - a);
            f2 = p(x2);
        }
        if b - a < 1e-12 {
            break;
        }
    }
    let (x, v) = if f1 > f2 { (x1, f1) } else { (x2, f2) };
    if v > best { (v, x.rem_euclid(TAU)) } else { (best, at.rem_euclid(TAU)) }
}

/// Peak of a sampled pressure on a (possibly non-uniform, periodic) θ grid: the largest node
/// refined by the parabola through it and its two neighbours.
fn grid_peak(theta: &[f64], p: &[f64]) -> (f64, f64) {
    let n = theta.len();
    let Some((k, &pk)) = p.iter().enumerate().max_by(|a, b| a.1.total_cmp(b.1)) else { return (0.0, f64::NAN) };
    if !(pk > 0.0) {
        return (0.0, f64::NAN);
    }
    let (km, kp) = ((k + n - 1) % n, (k + 1) % n);
    let (x0, x1, x2) = (theta[km] - if k == 0 { TAU } else { 0.0 }, theta[k], theta[kp] + if kp == 0 { TAU } else { 0.0 });
    let (y0, y1, y2) = (p[km].max(0.0), pk, p[kp].max(0.0));
    // Vertex of the parabola through the three points (divided differences).
    let d01 = (y1 - y0) / (x1 - x0);
    let d12 = (y2 - y1) / (x2 - x1);
    let a = (d12 - d01) / (x2 - x0);
    if !(a < 0.0) {
        return (pk, theta[k]);
    }
    let b = d01 - a * (x0 + x1);
    let x = (-b / (2.0 * a)).clamp(x0, x2);
    let y = y1 + (x - x1) * (d01 + a * (x - x0));
    (y.max(pk), x.rem_euclid(TAU))
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: BearingGeometry = BearingGeometry { viscosity: 0.05, journal_radius: 0.02, clearance: 4e-5, length: 0.04 };

    #[test]
    fn short_film_side_leakage_is_r_c_l_rho() {
        // Butenschön's normalisation: Q = Q_side/(R² c W) = 2 (L/D) ε for pure rotation.
        let g = BearingGeometry { length: 0.005, ..G };
        for eps in [0.1, 0.5, 0.9] {
            let f = flow_and_peak(FilmModel::ShortBearing, &g, FilmState { eps, eps_dot: 0.0, wedge: 100.0 }, None);
            let q = f.side_leakage / (g.journal_radius * g.journal_radius * g.clearance * 100.0);
            assert!((q - 2.0 * 0.125 * eps).abs() < 1e-12, "{q}");
            assert_eq!(f.supply, f.side_leakage);
        }
    }

    #[test]
    fn closed_form_peaks_match_their_pressures() {
        // Ocvirk, pure rotation: the mid-plane peak of p ∝ sinθ/(1 + ε cosθ)³ sits where
        // cosθ = (1 − √(1 + 24ε²))/(4ε) (dp/dθ = 0), in the loaded half (π/2, π).
        let eps = 0.6;
        let s = FilmState { eps, eps_dot: 0.0, wedge: 100.0 };
        let f = flow_and_peak(FilmModel::ShortBearing, &G, s, None);
        let th = ((1.0 - (1.0 + 24.0 * eps * eps).sqrt()) / (4.0 * eps)).acos();
        let p = bearing_short::short_bearing_pressure(&G, s, th, 0.0);
        assert!((f.peak_angle - th).abs() < 1e-7 && (f.peak_pressure / p - 1.0).abs() < 1e-12, "{f:?} vs {th}, {p}");
        let f = flow_and_peak(FilmModel::LongBearing, &G, s, None);
        assert_eq!((f.side_leakage, f.supply), (0.0, 0.0));
        for d in [-1e-4, 1e-4] {
            assert!(bearing_long::long_bearing_pressure(&G, s, f.peak_angle + d) < f.peak_pressure);
        }
        // No motion: no film, no peak.
        let none = flow_and_peak(FilmModel::ShortBearing, &G, FilmState { eps, eps_dot: 0.0, wedge: 0.0 }, None);
        assert_eq!((none.side_leakage, none.peak_pressure), (0.0, 0.0));
    }

    /// Butenschön's flow column (tests/data/butenschoen_flow_rotation.csv: side leakage out of
    /// both ends, Q = Q_side/((D/2)³ Ψ |W|), fed at ambient on the widest gap's line), every
    /// B/D from 1/8 to 1 and ε from 0.1 to 0.99, against the finite film with the supply line
    /// (his convention): within 3 % (the bound; MBDyn's own test accepts 8 %).
    #[test]
    fn finite_side_leakage_matches_butenschoens_flow_column() {
        let text = include_str!("../../tests/data/butenschoen_flow_rotation.csv");
        let mut worst = (0.0f64, String::new());
        let mut rows = 0;
        let mut per_bd: Vec<(f64, f64, f64)> = Vec::new(); // B/D, worst |error|, at ε
        for line in text.lines().filter(|l| !l.starts_with('#') && !l.starts_with("B_over_D")) {
            let cols: Vec<&str> = line.split(',').collect();
            let bd = match cols[0].split_once('/') {
                Some((a, b)) => a.parse::<f64>().unwrap() / b.parse::<f64>().unwrap(),
                None => cols[0].parse::<f64>().unwrap(),
            };
            let (eps, q_tab): (f64, f64) = (cols[1].parse().unwrap(), cols[2].parse().unwrap());
            let g = BearingGeometry { viscosity: 0.01, journal_radius: 0.01, clearance: 1e-5, length: 0.02 * bd };
            let mut sc = FiniteScratch::new(&g, FilmSupply::WidestGap);
            let w = 150.0;
            let f = flow_and_peak(FilmModel::Finite, &g, FilmState { eps, eps_dot: 0.0, wedge: w }, Some(&mut sc));
            let psi = g.clearance / g.journal_radius;
            let q = f.side_leakage / (g.journal_radius.powi(3) * psi * w);
            let err = q / q_tab - 1.0;
            if err.abs() > worst.0 {
                worst = (err.abs(), format!("B/D {bd}, ε {eps}: Q {q:.4} vs {q_tab}"));
            }
            match per_bd.iter_mut().find(|r| r.0 == bd) {
                Some(r) if err.abs() > r.1.abs() => *r = (bd, err, eps),
                Some(_) => {}
                None => per_bd.push((bd, err, eps)),
            }
            rows += 1;
        }
        assert_eq!(rows, 112);
        for (bd, err, eps) in &per_bd {
            eprintln!("side leakage vs Butenschön, B/D = 1/{:.3}: worst {:+.2} % at ε = {eps}", 1.0 / bd, 100.0 * err);
        }
        eprintln!("side leakage vs Butenschön: worst {:.4} at {}", worst.0, worst.1);
        assert!(worst.0 < 0.03, "{}", worst.1);
    }

    #[test]
    fn finite_field_is_the_readings_grid_mirrored() {
        let mut sc = FiniteScratch::new(&G, FilmSupply::WidestGap);
        let s = FilmState { eps: 0.7, eps_dot: 0.2, wedge: 80.0 };
        let f = flow_and_peak(FilmModel::Finite, &G, s, Some(&mut sc));
        let field = film_field(FilmModel::Finite, &G, s, Some(&mut sc));
        let nz = field.z.len();
        assert_eq!(nz, 2 * ReynoldsGrid::default().n_zeta + 1);
        assert!((field.z[0] + 0.5 * G.length).abs() < 1e-15 && (field.z[nz - 1] - 0.5 * G.length).abs() < 1e-15);
        let max = field.pressure.iter().copied().fold(0.0, f64::max);
        // The refined peak lies at or a little above the largest node.
        assert!(f.peak_pressure >= max && f.peak_pressure < 1.05 * max, "{} vs {max}", f.peak_pressure);
        for i in 0..field.theta.len() {
            let row = &field.pressure[i * nz..(i + 1) * nz];
            assert!(row.iter().zip(row.iter().rev()).all(|(a, b)| a == b) && row[0] == 0.0);
        }
    }
}
