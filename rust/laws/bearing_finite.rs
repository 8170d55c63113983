//! Finite-length journal bearing: the isothermal Reynolds equation solved numerically, once per
//! bearing geometry, into a table the right-hand side interpolates (docs/physics.md §4.4).
//!
//! With h = c H, H = 1 + ε cos θ (θ from the thickest film), z = (L/2) ζ and
//! p = (6 μ R² ρ / c²) P, the Reynolds equation
//! `(1/R²) ∂θ(h³ ∂θ p) + ∂z(h³ ∂z p) = 6μ W ∂θh + 12μ ∂t h` becomes
//!
//! `∂θ(H³ ∂θ P) + k² ∂ζ(H³ ∂ζ P) = −cos(θ − θm)`,  k = D/L,
//!
//! with ρ = hypot(Wε, 2ε̇) and θm = atan2(Wε, −2ε̇) (`Wε sinθ − 2ε̇ cosθ = ρ cos(θ − θm)`, as in
//! [`super::bearing_short`]). The problem is homogeneous in ρ: for one bearing (one k) the
//! dimensionless load `I = ∫∫ P (cosθ, sinθ) dθ dζ` depends on ε and θm only, and the film force
//! on the journal is `(F_ξ, F_η) = (3 μ R³ L ρ / c²) I` (same frame as every film model,
//! [`super::film`]). Mirror symmetry: θm → −θm mirrors P in θ, so F_ξ stays and F_η changes sign;
//! the table covers θm ∈ [0, π].
//!
//! Cavitation: the Reynolds (Swift–Stieber) condition, P ≥ 0 with ∂P/∂n = 0 on the film's
//! rupture boundary, as the complementarity problem `P ≥ 0, L P + f ≥ 0, P (L P + f) = 0`, solved
//! by projected successive over-relaxation (PSOR). Finite volumes on a θ grid stretched towards the
//! thinnest film (θ = ξ + a sin ξ) and a uniform half-width ζ ∈ [0, 1] (symmetry at ζ = 0, P = 0
//! at the bearing's ends).
//!
//! Supply ([`FilmSupply`]): with `WidestGap` (the default) P = 0 also on the axial line θ = 0 of
//! the widest gap, where a bearing is fed (Butenschön's rotation table, Raimondi–Boyd, DIN 31652,
//! the paper's P12); with `None` the film is periodic in θ (his squeeze table). The line maps to
//! itself under θ → −θ and the problem stays homogeneous in ρ, so the table keeps its (ε, θm ∈
//! [0, π]) form.

use super::geometry::{BearingGeometry, FilmState, FilmSupply};
use std::f64::consts::{PI, TAU};

/// How the film ruptures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cavitation {
    /// Reynolds (Swift–Stieber): P ≥ 0 inside the solve (Butenschön's tables follow it).
    Reynolds,
    /// Gümbel (half Sommerfeld): solve without a bound, then drop the negative pressure.
    Gumbel,
}

/// Grid of one Reynolds solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReynoldsGrid {
    /// Cells around the bearing and across its half width.
    pub n_theta: usize,
    pub n_zeta: usize,
}

impl Default for ReynoldsGrid {
    fn default() -> Self {
        ReynoldsGrid { n_theta: 120, n_zeta: 20 }
    }
}

/// A solver for one bearing (k = D/L, supply convention) on one grid, reusing its buffers and
/// its last pressure field as the next starting guess.
#[derive(Clone, Debug)]
pub struct ReynoldsSolver {
    pub k: f64,
    pub supply: FilmSupply,
    pub grid: ReynoldsGrid,
    pressure: Vec<f64>,
    last_eps: f64,
    /// PSOR sweeps of the last solve.
    pub sweeps: usize,
    /// The θ nodes \[rad\] and their cells' widths of the last solve (its grid is stretched by ε).
    theta: Vec<f64>,
    width: Vec<f64>,
}

impl ReynoldsSolver {
    pub fn new(k: f64, supply: FilmSupply, grid: ReynoldsGrid) -> Self {
        ReynoldsSolver { k, supply, grid, pressure: vec![0.0; grid.n_theta * grid.n_zeta], last_eps: f64::NAN, sweeps: 0, theta: Vec::new(), width: Vec::new() }
    }

    /// The last solve's field: θ nodes \[rad\] (from the widest gap, counter-clockwise), their
    /// cells' widths \[rad\], and P ≥ 0 at (θ_i, ζ_j), row-major in θ, ζ_j = j/n_ζ from the
    /// mid-plane (j = 0) towards the end (P = 0 at ζ = 1, not stored).
    pub fn field(&self) -> (&[f64], &[f64], &[f64]) {
        (&self.theta, &self.width, &self.pressure)
    }

    /// The dimensionless load `I = (I_ξ, I_η)` at (ε, θm) (both halves of the width).
    pub fn solve(&mut self, eps: f64, theta_m: f64, cavitation: Cavitation) -> (f64, f64) {
        let (nt, nz) = (self.grid.n_theta, self.grid.n_zeta);
        let eps = eps.clamp(0.0, 0.9995);
        // θ grid stretched towards θ = π (thinnest film): spacing there ∝ 1 − a.
        let a = (1.0 - 2.0 * (1.0 - eps).sqrt()).clamp(0.0, 0.9);
        let theta_of = |xi: f64| xi + a * xi.sin();
        let th: Vec<f64> = (0..nt).map(|i| theta_of(TAU * i as f64 / nt as f64)).collect();
        let th_half: Vec<f64> = (0..nt).map(|i| theta_of(TAU * (i as f64 + 0.5) / nt as f64)).collect(); // θ_{i+½}
        let h3 = |t: f64| {
            let h = 1.0 + eps * t.cos();
            h * h * h
        };
        let dz = 1.0 / nz as f64;
        let k2 = self.k * self.k;
        // Per θ cell: width, east/west conductances, ζ conductance, source (cell mean of cos(θ − θm)).
        let mut width = vec![0.0; nt];
        let mut ae = vec![0.0; nt];
        let mut aw = vec![0.0; nt];
        let mut az = vec![0.0; nt];
        let mut src = vec![0.0; nt];
        for i in 0..nt {
            let ip = (i + 1) % nt;
            let im = (i + nt - 1) % nt;
            let (t_w, t_e) = (if i == 0 { th_half[nt - 1] - TAU } else { th_half[im] }, th_half[i]);
            let d_e = if ip == 0 { th[0] + TAU - th[i] } else { th[ip] - th[i] };
            let d_w = if i == 0 { th[0] + TAU - th[im] } else { th[i] - th[im] };
            let w = t_e - t_w;
            width[i] = w;
            ae[i] = h3(t_e) / (d_e * w);
            aw[i] = h3(t_w) / (d_w * w);
            az[i] = k2 * h3(th[i]) / (dz * dz);
            src[i] = ((t_e - theta_m).sin() - (t_w - theta_m).sin()) / w;
        }
        let p = &mut self.pressure;
        if !(self.last_eps - eps).abs().lt(&0.2) {
            p.iter_mut().for_each(|v| *v = 0.0);
        }
        self.last_eps = eps;
        let project = cavitation == Cavitation::Reynolds;
        // Supply line: the cells of node θ = 0 hold P = 0 (never updated).
        let first = if self.supply == FilmSupply::WidestGap {
            p[..nz].iter_mut().for_each(|v| *v = 0.0);
            1
        } else {
            0
        };
        // Optimal over-relaxation for the slowest mode (constant around the bearing, the lowest
        // across its width): Jacobi radius ρ ≈ 1 − λ_min/diag (unit film), ω = 2/(1 + √(1 − ρ²)).
        let diag = 2.0 * (nt as f64 / TAU).powi(2) + 2.0 * k2 / (dz * dz);
        let lambda_min = 2.0 * k2 / (dz * dz) * (1.0 - (0.5 * PI * dz).cos());
        let rho_j = 1.0 - lambda_min / diag;
        let omega = 2.0 / (1.0 + (1.0 - rho_j * rho_j).max(0.0).sqrt());
        let tol = 1e-8;
        let mut sweeps = 0;
        loop {
            let mut change = 0.0f64;
            let mut scale = 1e-300f64;
            for i in first..nt {
                let ip = (i + 1) % nt;
                let im = (i + nt - 1) % nt;
                let diag = ae[i] + aw[i] + 2.0 * az[i];
                for j in 0..nz {
                    let idx = i * nz + j;
                    let north = if j + 1 < nz { p[idx + 1] } else { 0.0 };
                    let south = if j > 0 { p[idx - 1] } else { north }; // symmetry at ζ = 0
                    let gs = (src[i] + ae[i] * p[ip * nz + j] + aw[i] * p[im * nz + j] + az[i] * (north + south)) / diag;
                    let mut v = p[idx] + omega * (gs - p[idx]);
                    if project && v < 0.0 {
                        v = 0.0;
                    }
                    change = change.max((v - p[idx]).abs());
                    scale = scale.max(v.abs());
                    p[idx] = v;
                }
            }
            sweeps += 1;
            if change <= tol * scale || sweeps >= 100_000 {
                break;
            }
        }
        self.sweeps = sweeps;
        self.theta.clone_from(&th);
        self.width.clone_from(&width);
        // I = 2 ∫₀¹ ∫ P (cosθ, sinθ) dθ dζ (trapezoid in ζ: half weight on the symmetry plane).
        let (mut ix, mut iy) = (0.0, 0.0);
        for i in 0..nt {
            let (sn, cs) = th[i].sin_cos();
            let mut col = 0.0;
            for j in 0..nz {
                let v = p[i * nz + j].max(0.0);
                col += if j == 0 { 0.5 * v } else { v };
            }
            let w = width[i] * col * dz;
            ix += w * cs;
            iy += w * sn;
        }
        (2.0 * ix, 2.0 * iy)
    }
}

/// Dimensionless loads of one bearing on a grid of (s = −ln(1 − ε), θm ∈ [0, π]), stored as
/// `J = I w(ε)`, `w = (1 − ε)² e^{2ε}` (bounded up to ε → 1 and flat at ε = 0, where a plain
/// (1 − ε)² would make J fall by half over the first two rows), and interpolated by Catmull–Rom
/// splines in both.
///
/// Through the centre: the line of the widest gap turns by π as the journal passes the bearing
/// centre, so the supply line's film jumps there (a squeeze through the centre at L/D = 2.5 meets
/// a 4.5× weaker film receding than approaching, both at ε → 0). Below
/// [`SUPPLY_CENTRE_BAND`] a `WidestGap` table blends into the periodic film, which has no
/// direction to refer to and is continuous through the centre:
/// `I = (1 − w) I_line + w I_periodic`, `w = (1 − ε/ε_c)²` (the long film's centre blend,
/// docs/physics.md §4); the periodic film's first rows are kept in `centre` for it.
#[derive(Debug, Clone, PartialEq)]
pub struct FiniteBearingTable {
    /// k = D/L.
    pub k: f64,
    /// The ambient-pressure convention it was solved with.
    pub supply: FilmSupply,
    /// The grid of each Reynolds solve.
    pub grid: ReynoldsGrid,
    pub s_step: f64,
    pub n_s: usize,
    pub n_theta_m: usize,
    /// J_ξ, J_η at (s index, θm index), row-major in s.
    pub j: Vec<(f64, f64)>,
    /// The periodic film's J at the first [`CENTRE_ROWS`] rows (`WidestGap` tables; else empty).
    pub centre: Vec<(f64, f64)>,
}

/// Largest ε the table covers (the film is evaluated at min(ε, ε_max) ≤ this).
pub const TABLE_EPS_MAX: f64 = 0.995;
const S_STEP: f64 = 0.15;
const THETA_M_CELLS: usize = 36; // 5°
/// ε below which the supply line's film blends into the periodic one (see [`FiniteBearingTable`]).
pub const SUPPLY_CENTRE_BAND: f64 = 0.05;
/// Rows of the periodic film a `WidestGap` table keeps: s = 0, 0.15, 0.30 (the first cell's
/// quadratic covers ε < 1 − e^{−0.15} = 0.139 > [`SUPPLY_CENTRE_BAND`]).
pub const CENTRE_ROWS: usize = 3;

impl FiniteBearingTable {
    /// The table's layout (key, ε and θm grids) without values.
    pub fn layout(k: f64, supply: FilmSupply, grid: ReynoldsGrid) -> Self {
        let s_max = -(1.0 - TABLE_EPS_MAX).ln();
        let n_s = (s_max / S_STEP).ceil() as usize + 1;
        FiniteBearingTable { k, supply, grid, s_step: S_STEP, n_s, n_theta_m: THETA_M_CELLS + 1, j: Vec::new(), centre: Vec::new() }
    }

    /// Rows of the periodic film the table keeps for its centre blend.
    pub fn centre_rows(&self) -> usize {
        if self.supply == FilmSupply::WidestGap { CENTRE_ROWS } else { 0 }
    }

    /// Solve the Reynolds equation on the table's grid (rows of ε in parallel).
    pub fn build(k: f64, supply: FilmSupply, grid: ReynoldsGrid) -> Self {
        let layout = Self::layout(k, supply, grid);
        let row = |(is, supply): (usize, FilmSupply)| -> Vec<(f64, f64)> {
            let eps = 1.0 - (-(is as f64) * layout.s_step).exp();
            let mut solver = ReynoldsSolver::new(k, supply, grid);
            let w = load_weight(eps);
            (0..layout.n_theta_m)
                .map(|im| {
                    let (ix, iy) = solver.solve(eps, PI * im as f64 / THETA_M_CELLS as f64, Cavitation::Reynolds);
                    (ix * w, iy * w)
                })
                .collect()
        };
        let jobs: Vec<(usize, FilmSupply)> = (0..layout.n_s).map(|is| (is, supply)).chain((0..layout.centre_rows()).map(|is| (is, FilmSupply::None))).collect();
        let mut rows: Vec<Vec<(f64, f64)>> = {
            use rayon::prelude::*;
            jobs.into_par_iter().map(row).collect()
        };
        let centre = rows.split_off(layout.n_s).into_iter().flatten().collect();
        FiniteBearingTable { j: rows.into_iter().flatten().collect(), centre, ..layout }
    }

    /// Dimensionless load I at (ε, θm), θm ∈ [0, π].
    pub fn eval(&self, eps: f64, theta_m: f64) -> (f64, f64) {
        let eps = eps.clamp(0.0, TABLE_EPS_MAX);
        let s = -(1.0 - eps).ln() / self.s_step;
        let m = theta_m.clamp(0.0, PI) / PI * (self.n_theta_m - 1) as f64;
        let w = load_weight(eps);
        let (x, y) = interpolate(&self.j, self.n_s, self.n_theta_m, s, m);
        if !self.centre.is_empty() && eps < SUPPLY_CENTRE_BAND {
            let (xc, yc) = interpolate(&self.centre, CENTRE_ROWS, self.n_theta_m, s, m);
            let b = (1.0 - eps / SUPPLY_CENTRE_BAND) * (1.0 - eps / SUPPLY_CENTRE_BAND);
            return (((1.0 - b) * x + b * xc) / w, ((1.0 - b) * y + b * yc) / w);
        }
        (x / w, y / w)
    }
}

/// J of `rows` (row-major, `n_s` × `n_m`) at grid coordinates (s, m): Catmull–Rom in both, a
/// quadratic through three rows in the first and last cells of s (θm has its mirror images
/// instead: θm → −θm and 2π − θm flip J_η).
fn interpolate(rows: &[(f64, f64)], n_s: usize, n_m: usize, s: f64, m: f64) -> (f64, f64) {
    let (is, fs) = split(s, n_s);
    let (im, fm) = split(m, n_m);
    let ws = if is == 0 {
        let l = lagrange3(fs);
        [0.0, l[0], l[1], l[2]]
    } else if is as usize == n_s - 2 {
        let l = lagrange3(fs + 1.0);
        [l[0], l[1], l[2], 0.0]
    } else {
        catmull_rom(fs)
    };
    let wm = catmull_rom(fm);
    let last = n_m as isize - 1;
    let at = |i: isize, k: isize| {
        let i = i.clamp(0, n_s as isize - 1) as usize;
        let (k, flip) = if k < 0 {
            (-k, true)
        } else if k > last {
            (2 * last - k, true)
        } else {
            (k, false)
        };
        let v = rows[i * n_m + k as usize];
        if flip { (v.0, -v.1) } else { v }
    };
    let (mut x, mut y) = (0.0, 0.0);
    for (a, wa) in ws.iter().enumerate() {
        for (b, wb) in wm.iter().enumerate() {
            let v = at(is + a as isize - 1, im + b as isize - 1);
            x += wa * wb * v.0;
            y += wa * wb * v.1;
        }
    }
    (x, y)
}

/// The weight w(ε) = (1 − ε)² e^{2ε} of the stored loads J = I w (see [`FiniteBearingTable`]).
fn load_weight(eps: f64) -> f64 {
    (1.0 - eps) * (1.0 - eps) * (2.0 * eps).exp()
}

/// Cell index and fraction of a grid coordinate in [0, n − 1].
fn split(x: f64, n: usize) -> (isize, f64) {
    let i = (x.floor() as isize).clamp(0, n as isize - 2);
    (i, x - i as f64)
}

/// Quadratic Lagrange weights of points 0, 1, 2 at x.
fn lagrange3(x: f64) -> [f64; 3] {
    [0.5 * (x - 1.0) * (x - 2.0), -x * (x - 2.0), 0.5 * x * (x - 1.0)]
}

/// Catmull–Rom weights of the four points i − 1 … i + 2 at fraction t of cell i.
fn catmull_rom(t: f64) -> [f64; 4] {
    let (t2, t3) = (t * t, t * t * t);
    [0.5 * (-t3 + 2.0 * t2 - t), 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0), 0.5 * (-3.0 * t3 + 4.0 * t2 + t), 0.5 * (t3 - t2)]
}

/// Film force `(F_ξ, F_η)` \[N\] on the journal from the bearing's table (module doc).
pub fn finite_bearing_force(g: &BearingGeometry, s: FilmState, table: &FiniteBearingTable) -> (f64, f64) {
    let eps = s.clamped_eps();
    let (a, b) = (s.wedge * eps, -2.0 * s.eps_dot);
    let rho = a.hypot(b);
    if rho.is_nan() || rho <= 0.0 || !rho.is_finite() {
        return (0.0, 0.0);
    }
    let theta_m = a.atan2(b);
    let (ix, iy) = table.eval(eps, theta_m.abs());
    let iy = if theta_m < 0.0 { -iy } else { iy };
    let r = g.journal_radius;
    let scale = 3.0 * g.viscosity * r * r * r * g.length * rho / (g.clearance * g.clearance);
    (scale * ix, scale * iy)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::laws::bearing_short::short_bearing_force;

    fn geometry(l_over_d: f64) -> BearingGeometry {
        BearingGeometry { viscosity: 0.4, journal_radius: 0.01, clearance: 5e-4, length: 0.02 * l_over_d }
    }

    /// Dimensionless load of a direct solve, converted to a force like `finite_bearing_force`.
    fn direct(g: &BearingGeometry, s: FilmState, supply: FilmSupply, grid: ReynoldsGrid, cav: Cavitation) -> (f64, f64) {
        let k = 2.0 * g.journal_radius / g.length;
        let (a, b) = (s.wedge * s.eps, -2.0 * s.eps_dot);
        let rho = a.hypot(b);
        let mut solver = ReynoldsSolver::new(k, supply, grid);
        let (ix, iy) = solver.solve(s.eps, a.atan2(b), cav);
        let r = g.journal_radius;
        let scale = 3.0 * g.viscosity * r * r * r * g.length * rho / (g.clearance * g.clearance);
        (scale * ix, scale * iy)
    }

    #[test]
    fn short_limit_matches_the_short_bearing_closed_form() {
        // L/D = 1/20, periodic film: the circumferential flow is negligible and both cavitation
        // conditions reduce to P = max(0, short-bearing pressure).
        let g = geometry(0.05);
        for (eps, eps_dot, wedge) in [(0.3, 0.0, 50.0), (0.6, 2.0, 0.0), (0.5, -1.0, 30.0), (0.8, 0.5, -40.0)] {
            let s = FilmState { eps, eps_dot, wedge };
            let f = direct(&g, s, FilmSupply::None, ReynoldsGrid { n_theta: 240, n_zeta: 16 }, Cavitation::Reynolds);
            let e = short_bearing_force(&g, s);
            let err = (f.0 - e.0).hypot(f.1 - e.1) / e.0.hypot(e.1);
            assert!(err < 0.02, "ε {eps} ε̇ {eps_dot} W {wedge}: finite {f:?} short {e:?} ({err:.3})");
        }
    }
}

#[cfg(test)]
mod butenschoen {
    use super::*;
    use crate::laws::bearing_finite_cache::table_for;

    /// Rows of a data file: B/D (as "1/8" or "1"), then the numeric columns.
    fn rows(name: &str) -> Vec<(f64, Vec<f64>)> {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/");
        let text = std::fs::read_to_string(format!("{path}{name}")).unwrap();
        text.lines()
            .filter(|l| !l.starts_with('#') && !l.starts_with("B_over_D"))
            .map(|l| {
                let mut cols = l.split(',');
                let bd = cols.next().unwrap().trim();
                let b_over_d = match bd.split_once('/') {
                    Some((a, b)) => a.parse::<f64>().unwrap() / b.parse::<f64>().unwrap(),
                    None => bd.parse::<f64>().unwrap(),
                };
                (b_over_d, cols.map(|v| v.trim().parse::<f64>().unwrap()).collect())
            })
            .collect()
    }

    /// Sommerfeld number and attitude [°] of pure rotation (So = 1.5 ε |I|) from a load I.
    fn rotation(eps: f64, i: (f64, f64)) -> (f64, f64) {
        (1.5 * eps * i.0.hypot(i.1), i.1.abs().atan2(-i.0).to_degrees())
    }

    /// Butenschön's rotation table (B/D = 1/8 … 1, ε = 0.1 … 0.99) with the supply line (his
    /// convention for rotation): Sommerfeld number within 1 % and attitude within 0.5° for every
    /// row, from a direct solve on the tables' grid, and from the tables the right-hand side
    /// uses at the ends of the range (B/D = 1/8 and 1; a table costs ~1 400 solves, a row one).
    /// Measured (`python benches/finite_bearing.py`): tables 0.97 % and 0.18° at worst, the largest
    /// So errors where the printed four decimals round by up to 2 % (So = 0.0025 at B/D = 1/8,
    /// ε = 0.1).
    #[test]
    fn rotation_with_the_supply_line_matches_every_b_over_d() {
        let data = rows("butenschoen_rotation_all.csv");
        assert_eq!(data.len(), 112);
        for (bd, r) in data {
            let mut solver = ReynoldsSolver::new(1.0 / bd, FilmSupply::WidestGap, ReynoldsGrid::default());
            let mut loads = vec![("direct", solver.solve(r[0], PI / 2.0, Cavitation::Reynolds))];
            if bd == 0.125 || bd == 1.0 {
                loads.push(("table", table_for(1.0 / bd, FilmSupply::WidestGap).eval(r[0], PI / 2.0)));
            }
            for (how, i) in loads {
                let (so, beta) = rotation(r[0], i);
                assert!((so / r[1] - 1.0).abs() < 0.01, "{how}: B/D {bd}, ε {}: So {so:.5} vs {}", r[0], r[1]);
                assert!((beta - r[2]).abs() < 0.5, "{how}: B/D {bd}, ε {}: β {beta:.2}° vs {}°", r[0], r[2]);
            }
        }
    }

    /// Butenschön's squeeze table (B/D = 1/8 and 1/4, both signs) against the periodic film (his
    /// convention for squeeze): Sommerfeld number within 2 %, force radial. The row B/D = 1/8,
    /// ε = −0.95 breaks the table's own monotonicity (0.0085 between 0.0087 and 0.0095: a
    /// transcription glitch, see the data file); the film gives 0.00885 there, checked against
    /// its neighbours instead.
    #[test]
    fn squeeze_without_the_supply_line_matches_b_over_d_one_eighth_and_one_quarter() {
        for name in ["butenschoen_squeeze_BD1_8.csv", "butenschoen_squeeze_BD1_4.csv"] {
            for (bd, r) in rows(name) {
                let table = table_for(1.0 / bd, FilmSupply::None);
                let (ix, iy) = table.eval(r[0].abs(), if r[0] < 0.0 { 0.0 } else { PI });
                let so = 3.0 * ix.hypot(iy);
                assert!(iy.abs() < 1e-6 * ix.abs(), "B/D {bd}, ε {}: tangential {iy}", r[0]);
                if bd == 0.125 && (r[0] + 0.95).abs() < 1e-9 {
                    assert!(so > 0.0087 && so < 0.0095, "squeeze ε −0.95: So {so:.5} not between its neighbours");
                    continue;
                }
                assert!((so / r[1] - 1.0).abs() < 0.02, "B/D {bd}, ε {}: So {so:.5} vs {}", r[0], r[1]);
            }
        }
    }

    /// Each table is met by its own convention only: pure rotation without the line and a
    /// receding squeeze with it miss by far more than the tables' precision (an approaching
    /// squeeze cavitates the thick side, so there the two conventions agree).
    #[test]
    fn each_table_needs_its_own_convention() {
        let solve = |k: f64, supply, eps, theta_m| ReynoldsSolver::new(k, supply, ReynoldsGrid::default()).solve(eps, theta_m, Cavitation::Reynolds);
        // B/D = 1, ε = 0.3: So 0.4091, β 68.264°.
        let (so_l, b_l) = rotation(0.3, solve(1.0, FilmSupply::WidestGap, 0.3, PI / 2.0));
        let (_, b_n) = rotation(0.3, solve(1.0, FilmSupply::None, 0.3, PI / 2.0));
        assert!((b_l - 68.264).abs() < 0.5 && (b_n - 68.264) > 2.0, "β with {b_l:.2}°, without {b_n:.2}°");
        assert!((so_l / 0.4091 - 1.0).abs() < 0.01, "So with the line {so_l:.4}");
        // B/D = 1/4, ε = −0.6: So 0.0583.
        let sq = |i: (f64, f64)| 3.0 * i.0.hypot(i.1);
        let (none, line) = (sq(solve(4.0, FilmSupply::None, 0.6, 0.0)), sq(solve(4.0, FilmSupply::WidestGap, 0.6, 0.0)));
        assert!((none / 0.0583 - 1.0).abs() < 0.02 && line / 0.0583 < 0.9, "without {none:.4}, with {line:.4}");
        let (a, b) = (solve(4.0, FilmSupply::WidestGap, 0.6, PI), solve(4.0, FilmSupply::None, 0.6, PI));
        assert!((a.0 - b.0).hypot(a.1 - b.1) < 1e-6 * b.0.hypot(b.1), "approaching squeeze: {a:?} vs {b:?}");
    }

    #[test]
    fn table_interpolates_direct_solves_off_its_grid() {
        let k = 1.0 / 2.5; // the paper's bearing, L/D = 2.5
        for supply in [FilmSupply::WidestGap, FilmSupply::None] {
            let table = table_for(k, supply);
            let mut solver = ReynoldsSolver::new(k, supply, ReynoldsGrid::default());
            for (eps, tm) in [(0.05, 0.3), (0.33, 1.1), (0.57, 2.9), (0.72, 0.05), (0.88, 1.7), (0.93, 3.1), (0.985, 0.8)] {
                let d = solver.solve(eps, tm, Cavitation::Reynolds);
                let t = table.eval(eps, tm);
                let err = (d.0 - t.0).hypot(d.1 - t.1) / d.0.hypot(d.1);
                assert!(err < 0.01, "{supply:?} ε {eps} θm {tm}: table {t:?} direct {d:?} ({err:.4})");
            }
        }
    }

    #[test]
    fn long_limit_with_gumbel_cavitation_approaches_the_long_bearing_closed_form() {
        // With the Gümbel condition and the supply line a long bearing tends to the long
        // (Pinkus–Sternlicht) closed form, which uses both (p = 0 at θ = 0, P12); the end leakage
        // of a finite length costs ∝ D/L.
        use crate::laws::bearing_long::long_bearing_force;
        for s in [FilmState { eps: 0.5, eps_dot: 0.0, wedge: 50.0 }, FilmState { eps: 0.5, eps_dot: 2.0, wedge: 0.0 }, FilmState { eps: 0.6, eps_dot: -1.0, wedge: 30.0 }] {
            let mut last = f64::INFINITY;
            for l_over_d in [10.0, 50.0] {
                let g = BearingGeometry { viscosity: 0.4, journal_radius: 0.01, clearance: 5e-4, length: 0.02 * l_over_d };
                let k = 2.0 * g.journal_radius / g.length;
                let (a, b) = (s.wedge * s.eps, -2.0 * s.eps_dot);
                let mut solver = ReynoldsSolver::new(k, FilmSupply::WidestGap, ReynoldsGrid { n_theta: 144, n_zeta: 64 });
                let (ix, iy) = solver.solve(s.eps, a.atan2(b), Cavitation::Gumbel);
                let r = g.journal_radius;
                let scale = 3.0 * g.viscosity * r * r * r * g.length * a.hypot(b) / (g.clearance * g.clearance);
                let f = (scale * ix, scale * iy);
                let e = long_bearing_force(&g, s);
                let err = (f.0 - e.0).hypot(f.1 - e.1) / e.0.hypot(e.1);
                assert!(err < last, "{s:?} L/D {l_over_d}: {err:.4} not below {last:.4}");
                last = err;
            }
            assert!(last < 0.03, "{s:?} L/D 50: {last:.4}");
        }
    }

    #[test]
    fn mirror_and_homogeneity() {
        let g = BearingGeometry { viscosity: 0.4, journal_radius: 0.01, clearance: 5e-4, length: 0.05 };
        for supply in [FilmSupply::WidestGap, FilmSupply::None] {
            let table = table_for(2.0 * g.journal_radius / g.length, supply);
            let f = finite_bearing_force(&g, FilmState { eps: 0.6, eps_dot: 0.3, wedge: 40.0 }, table);
            let m = finite_bearing_force(&g, FilmState { eps: 0.6, eps_dot: 0.3, wedge: -40.0 }, table);
            assert!((f.0 - m.0).abs() < 1e-12 * f.0.abs() && (f.1 + m.1).abs() < 1e-12 * f.1.abs());
            let d = finite_bearing_force(&g, FilmState { eps: 0.6, eps_dot: 0.6, wedge: 80.0 }, table);
            assert!((d.0 - 2.0 * f.0).abs() < 1e-12 * d.0.abs() && (d.1 - 2.0 * f.1).abs() < 1e-12 * d.1.abs());
            assert_eq!(finite_bearing_force(&g, FilmState { eps: 0.6, eps_dot: 0.0, wedge: 0.0 }, table), (0.0, 0.0));
            assert!(f.1 > 0.0, "a journal turning counter-clockwise gets F_η > 0");
        }
    }

    /// The supply line turns by π as the journal passes the bearing centre; below ε = 0.05 the
    /// line's table blends into the periodic film, so the force is continuous through the
    /// centre: at ε → 0 both conventions agree and a squeeze through the centre meets the same
    /// film on either side (|I(θm = 0)| = |I(θm = π)|, the periodic film only turning with θm).
    #[test]
    fn supply_line_film_is_continuous_through_the_centre() {
        let k = 0.4;
        let (line, none) = (table_for(k, FilmSupply::WidestGap), table_for(k, FilmSupply::None));
        let norm = |v: (f64, f64)| v.0.hypot(v.1);
        for tm in [0.0, 0.7, PI / 2.0, 2.5, PI] {
            let (a, b) = (line.eval(1e-12, tm), none.eval(1e-12, tm));
            assert!(norm((a.0 - b.0, a.1 - b.1)) < 1e-9 * norm(b), "θm {tm}: {a:?} vs {b:?}");
            let (lo, hi) = (line.eval(SUPPLY_CENTRE_BAND * (1.0 - 1e-9), tm), line.eval(SUPPLY_CENTRE_BAND * (1.0 + 1e-9), tm));
            assert!(norm((lo.0 - hi.0, lo.1 - hi.1)) < 1e-6 * norm(hi), "θm {tm} at ε_c: {lo:?} vs {hi:?}");
        }
        let (receding, approaching) = (line.eval(1e-12, 0.0), line.eval(1e-12, PI));
        assert!((norm(receding) / norm(approaching) - 1.0).abs() < 1e-3, "{receding:?} vs {approaching:?}");
        // Without the blend the line's film would jump by 4.5× there (direct solves at ε = 0.01).
        let mut solver = ReynoldsSolver::new(k, FilmSupply::WidestGap, ReynoldsGrid::default());
        let jump = norm(solver.solve(0.01, PI, Cavitation::Reynolds)) / norm(solver.solve(0.01, 0.0, Cavitation::Reynolds));
        assert!(jump > 4.0, "{jump}");
        // From ε_c on, the line's own film.
        let d = solver.solve(0.08, 0.3, Cavitation::Reynolds);
        let t = line.eval(0.08, 0.3);
        assert!(norm((d.0 - t.0, d.1 - t.1)) < 0.01 * norm(d), "{t:?} vs {d:?}");
    }
}
