//! Mass-conserving cavitation in a finite journal bearing (docs/physics.md §4, *Mass-conserving
//! cavitation*): the Jakobsson–Floberg–Olsson conditions in Elrod and Adams' film-content form,
//! with the pressure found as a complementarity problem (as Giacopini, Fowell, Dini & Strozzi
//! 2010 pose it) at every evaluation and the film content carried from step to step.
//!
//! Oil per unit area m = θ h (θ the fraction of the gap the oil fills, h = c H, H = 1 + ε cos θ)
//! obeys, in the frame of the line of centres (θ from the widest gap, W the wedge speed),
//!
//! `∂m/∂t + (W/2) ∂θ(θ_f H) = ½ [∂θ(H³ ∂θ P) + k² ∂ζ(H³ ∂ζ P)]`,   p = (6μR²/c²) P,  k = D/L,
//!
//! m in units of c and P in 1/s (so μ only scales the pressure). Where the gap is full
//! (m = H) the oil cannot gather, and P ≥ 0 holds it full: `P ≥ 0, s = ∂H/∂t − r(P) ≥ 0, P s = 0`
//! with r the right-hand side's rate; where it is not (m < H) P = 0 and the content moves with
//! the mean surface speed (the cavitated zone's striated flow). With θ_f = 1 everywhere this is
//! the Reynolds equation of [`super::bearing_finite`] (P there is this P divided by ρ).
//!
//! Discretisation: finite volumes on a uniform θ grid ([`JFO_THETA`] cells, cell 0 the supply
//! groove on the widest gap, one cell wide, held full at ambient pressure: the oil comes in there)
//! and [`JFO_ZETA`] nodes over the half width (mid-plane symmetric, P = 0 at the ends). Couette
//! flux upwind in the content (Elrod–Adams), H at the cell faces, so that a full film's flux
//! difference is the exact cell integral of ∂θH; ∂H/∂t the cell mean of ε̇ cos θ. The
//! complementarity problem is an M-matrix LCP, solved exactly (to round-off) by active sets on a
//! banded LDLᵀ factorisation (bandwidth [`JFO_ZETA`]), warm-started from the last free set and
//! falling back to Chandrasekaran's monotone method (only adding nodes: converges for M-matrices).

use std::f64::consts::TAU;

/// Cells around the bearing of the film-content grid (4° each).
pub const JFO_THETA: usize = 90;
/// Nodes across the bearing's half width (from the mid-plane; P = 0 at the end, not a node).
pub const JFO_ZETA: usize = 8;
/// A fill within this of 1 counts as full.
const FULL: f64 = 1e-10;

/// What one evaluation of the film gives (dimensional where a unit is named).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct JfoReading {
    /// Film force on the journal (F_ξ, F_η) \[N\].
    pub force: (f64, f64),
    /// Oil out of both ends \[m³/s\].
    pub side_leakage: f64,
    /// Oil fed through the supply groove \[m³/s\] (negative: the film pushes oil out there).
    pub supply: f64,
    /// Largest pressure \[Pa\] and its θ \[rad\] from the widest gap (NaN without one).
    pub peak_pressure: f64,
    pub peak_angle: f64,
    /// Oil in the gap \[m³\].
    pub oil: f64,
}

/// The film of one bearing on the content grid: its geometry tables and the solver's buffers.
#[derive(Clone, Debug)]
pub struct JfoFilm {
    /// k² = (D/L)².
    k2: f64,
    /// sin, cos at the faces θ_{i+½} (index i) and the cell means of cos.
    sin_face: Vec<f64>,
    cos_face: Vec<f64>,
    cos_mean: Vec<f64>,
    /// cos at the cell centres θ_i.
    cos_centre: Vec<f64>,
    // Per evaluation.
    h: Vec<f64>,
    hf3: Vec<f64>,
    hc3: Vec<f64>,
    fill: Vec<f64>,
    /// Couette rate, ∂H/∂t − Couette (q of the LCP), P, the rate r = Couette + ½ L P and its
    /// pressure part ½ L P.
    couette: Vec<f64>,
    q: Vec<f64>,
    pub pressure: Vec<f64>,
    pub rate: Vec<f64>,
    pub pressure_rate: Vec<f64>,
    eligible: Vec<bool>,
    free: Vec<bool>,
    band: Vec<f64>,
    rhs: Vec<f64>,
    /// Active-set iterations of the last solve.
    pub iterations: usize,
}

const NT: usize = JFO_THETA;
const NZ: usize = JFO_ZETA;
const N: usize = NT * NZ;
/// Unknowns of the LCP: every node off the supply groove.
const NU: usize = (NT - 1) * NZ;
const DTH: f64 = TAU / NT as f64;
const DZ: f64 = 1.0 / NZ as f64;

/// Weight of node j's control volume across the half width (the mid-plane node has half).
#[inline]
fn zw(j: usize) -> f64 {
    if j == 0 { 0.5 } else { 1.0 }
}

impl JfoFilm {
    /// The film of a bearing with diameter-to-length ratio `k` = D/L.
    pub fn new(k: f64) -> Self {
        let face = |i: usize| DTH * (i as f64 + 0.5);
        let sin_face: Vec<f64> = (0..NT).map(|i| face(i).sin()).collect();
        let cos_face: Vec<f64> = (0..NT).map(|i| face(i).cos()).collect();
        let west = |i: usize| (i + NT - 1) % NT;
        let cos_mean = (0..NT).map(|i| (sin_face[i] - sin_face[west(i)]) / DTH).collect();
        JfoFilm {
            k2: k * k,
            cos_centre: (0..NT).map(|i| (DTH * i as f64).cos()).collect(),
            sin_face,
            cos_face,
            cos_mean,
            h: vec![0.0; NT],
            hf3: vec![0.0; NT],
            hc3: vec![0.0; NT],
            fill: vec![0.0; N],
            couette: vec![0.0; N],
            q: vec![0.0; N],
            pressure: vec![0.0; N],
            rate: vec![0.0; N],
            pressure_rate: vec![0.0; N],
            eligible: vec![false; N],
            free: vec![false; N],
            band: vec![0.0; NU * (NZ + 1)],
            rhs: vec![0.0; NU],
            iterations: 0,
        }
    }

    /// Cell angles θ_i \[rad\] (from the widest gap) and node positions ζ_j ∈ [0, 1).
    pub fn grid() -> (Vec<f64>, Vec<f64>) {
        ((0..NT).map(|i| DTH * i as f64).collect(), (0..NZ).map(|j| DZ * j as f64).collect())
    }

    /// H of cell i at the last evaluation's ε (cell mean of 1 + ε cos θ).
    pub fn gap(&self, i: usize) -> f64 {
        self.h[i]
    }

    /// The gaps H of the cells at the last solve's ε (cell means of 1 + ε cos θ).
    pub fn gaps(&self) -> &[f64] {
        &self.h
    }

    /// Solve the film with the fill `fill` (the fraction θ_f ∈ [0, 1] of each node's gap the oil
    /// fills; N = [`JFO_THETA`] × [`JFO_ZETA`] values, row-major in θ) at eccentricity ratio `eps`,
    /// its rate `eps_dot` \[1/s\] and the wedge speed `wedge` \[rad/s\]: the pressure P \[1/s\] and the
    /// oil's rate [`Self::rate`] (m = θ_f H, in units of c per second). A full node (θ_f = 1) stays
    /// full while the gap moves within a step (the pressure holds it so, or lets it go: the LCP).
    pub fn solve(&mut self, fill: &[f64], eps: f64, eps_dot: f64, wedge: f64) {
        let w2 = 0.5 * wedge;
        for i in 0..NT {
            let hf = 1.0 + eps * self.cos_face[i];
            let hc = 1.0 + eps * self.cos_centre[i];
            self.h[i] = 1.0 + eps * self.cos_mean[i];
            self.hf3[i] = hf * hf * hf;
            self.hc3[i] = hc * hc * hc;
        }
        for i in 0..NT {
            for j in 0..NZ {
                let n = i * NZ + j;
                self.fill[n] = if i == 0 { 1.0 } else { fill[n].clamp(0.0, 1.0) };
            }
        }
        for i in 0..NT {
            let (e, wst) = ((i + 1) % NT, (i + NT - 1) % NT);
            let dhdt = eps_dot * self.cos_mean[i];
            for j in 0..NZ {
                let n = i * NZ + j;
                // Upwind content at the east and west faces.
                let up_e = if w2 >= 0.0 { self.fill[n] } else { self.fill[e * NZ + j] };
                let up_w = if w2 >= 0.0 { self.fill[wst * NZ + j] } else { self.fill[n] };
                let flux_e = up_e * (1.0 + eps * self.cos_face[i]);
                let flux_w = up_w * (1.0 + eps * self.cos_face[wst]);
                self.couette[n] = -w2 * (flux_e - flux_w) / DTH;
                self.q[n] = dhdt - self.couette[n];
                self.eligible[n] = i > 0 && fill[n] >= 1.0 - FULL;
            }
        }
        self.solve_lcp();
        for i in 0..NT {
            for j in 0..NZ {
                let n = i * NZ + j;
                self.pressure_rate[n] = 0.5 * self.laplacian(i, j);
                self.rate[n] = self.couette[n] + self.pressure_rate[n];
            }
        }
    }

    /// (L P) at node (i, j): the discrete ∂θ(H³∂θP) + k²∂ζ(H³∂ζP).
    #[inline]
    fn laplacian(&self, i: usize, j: usize) -> f64 {
        let p = &self.pressure;
        let (e, w) = ((i + 1) % NT, (i + NT - 1) % NT);
        let c = p[i * NZ + j];
        let theta = (self.hf3[i] * (p[e * NZ + j] - c) - self.hf3[w] * (c - p[w * NZ + j])) / (DTH * DTH);
        let north = if j + 1 < NZ { p[i * NZ + j + 1] } else { 0.0 };
        let south = if j > 0 { p[i * NZ + j - 1] } else { north };
        theta + self.k2 * self.hc3[i] * (north - 2.0 * c + south) / (DZ * DZ)
    }

    /// The LCP P ≥ 0, s = q − ½ L P ≥ 0, P s = 0 on the eligible nodes (P = 0 elsewhere), by
    /// active sets on the free set (module doc).
    fn solve_lcp(&mut self) {
        // Warm start: the last free set where still eligible; none at all: the nodes with q < 0.
        let mut any = false;
        for n in 0..N {
            self.free[n] &= self.eligible[n];
            any |= self.free[n];
        }
        if !any {
            for n in 0..N {
                self.free[n] = self.eligible[n] && self.q[n] < 0.0;
            }
        }
        let scale = self.q.iter().fold(0.0f64, |a, v| a.max(v.abs())).max(1e-300);
        let mut monotone = false;
        self.iterations = 0;
        loop {
            self.iterations += 1;
            self.factor_and_solve();
            let mut changed = false;
            if !monotone {
                for n in 0..N {
                    if self.free[n] && self.pressure[n] < 0.0 {
                        self.free[n] = false;
                        changed = true;
                    }
                }
                if changed {
                    if self.iterations > 40 {
                        // Restart monotone (Chandrasekaran) from the nodes with q < 0.
                        monotone = true;
                        for n in 0..N {
                            self.free[n] = self.eligible[n] && self.q[n] < 0.0;
                        }
                    }
                    continue;
                }
            }
            for i in 1..NT {
                for j in 0..NZ {
                    let n = i * NZ + j;
                    if self.eligible[n] && !self.free[n] && self.q[n] - 0.5 * self.laplacian(i, j) < -1e-12 * scale {
                        self.free[n] = true;
                        changed = true;
                    }
                }
            }
            if !changed || self.iterations > 2 * N {
                break;
            }
        }
        for v in self.pressure.iter_mut() {
            *v = v.max(0.0);
        }
    }

    /// Solve M_FF P_F = −q_F (rows weighted by their control volumes: symmetric), P = 0 off F,
    /// by a banded LDLᵀ (unknowns (i − 1) NZ + j for i ≥ 1, bandwidth NZ).
    fn factor_and_solve(&mut self) {
        let b = NZ + 1; // stored diagonals: 0 (main) … NZ
        self.band.iter_mut().for_each(|v| *v = 0.0);
        for i in 1..NT {
            let w = i - 1;
            for j in 0..NZ {
                let n = i * NZ + j;
                let u = w * NZ + j;
                if !self.free[n] {
                    self.band[u * b] = 1.0;
                    self.rhs[u] = 0.0;
                    continue;
                }
                let zj = zw(j);
                let west = (i + NT - 1) % NT;
                let zc = self.k2 * self.hc3[i] / (DZ * DZ);
                let diag = 0.5 * zj * ((self.hf3[i] + self.hf3[west]) / (DTH * DTH) + 2.0 * zc);
                self.band[u * b] = diag;
                self.rhs[u] = -zj * self.q[n];
                // Lower neighbours: (i, j − 1) at distance 1 and (i − 1, j) at distance NZ.
                if j > 0 && self.free[n - 1] {
                    // Symmetric coupling ½ k² H³/dz² (×2 ×½ for the mid-plane row).
                    self.band[u * b + 1] = -0.5 * zc;
                }
                if i > 1 && self.free[n - NZ] {
                    self.band[u * b + NZ] = -0.5 * zj * self.hf3[west] / (DTH * DTH);
                }
            }
        }
        // LDLᵀ in place: band[u*b + d] holds L(u, u − d) (d ≥ 1) and D(u) (d = 0).
        for u in 0..NU {
            for d in (1..b).rev() {
                if d > u {
                    continue;
                }
                let v = u - d;
                let mut s = self.band[u * b + d];
                for e in d + 1..b {
                    if e > u {
                        break;
                    }
                    // L(u, u − e) D(u − e) L(v, u − e), with u − e = v − (e − d).
                    s -= self.band[u * b + e] * self.band[(u - e) * b] * self.band[v * b + (e - d)];
                }
                self.band[u * b + d] = s / self.band[v * b];
            }
            let mut dd = self.band[u * b];
            for d in 1..b.min(u + 1) {
                let l = self.band[u * b + d];
                dd -= l * l * self.band[(u - d) * b];
            }
            self.band[u * b] = dd;
        }
        for u in 0..NU {
            let mut s = self.rhs[u];
            for d in 1..b.min(u + 1) {
                s -= self.band[u * b + d] * self.rhs[u - d];
            }
            self.rhs[u] = s;
        }
        for u in 0..NU {
            self.rhs[u] /= self.band[u * b];
        }
        for u in (0..NU).rev() {
            let mut s = self.rhs[u];
            for d in 1..b {
                if u + d < NU {
                    s -= self.band[(u + d) * b + d] * self.rhs[u + d];
                }
            }
            self.rhs[u] = s;
        }
        for j in 0..NZ {
            self.pressure[j] = 0.0;
        }
        for u in 0..NU {
            let n = NZ + u;
            self.pressure[n] = if self.free[n] { self.rhs[u] } else { 0.0 };
        }
    }

    /// Force, flows, peak and oil of the last solve for a bearing of journal radius `r`,
    /// clearance `c`, length `l` \[m\] and viscosity `mu` \[Pa s\], with the fill it was solved for.
    pub fn reading(&self, fill: &[f64], r: f64, c: f64, l: f64, mu: f64, eps_dot: f64) -> JfoReading {
        let p_scale = 6.0 * mu * r * r / (c * c);
        let (mut ix, mut iy, mut leak, mut supply, mut oil) = (0.0, 0.0, 0.0, 0.0, 0.0);
        let (mut peak, mut at) = (0.0, usize::MAX);
        for i in 0..NT {
            let mut col = 0.0;
            for j in 0..NZ {
                let n = i * NZ + j;
                col += zw(j) * self.pressure[n] * DZ;
                oil += zw(j) * DZ * DTH * self.h[i] * if i == 0 { 1.0 } else { fill[n].clamp(0.0, 1.0) };
                if j == 0 && self.pressure[n] > peak {
                    peak = self.pressure[n];
                    at = i;
                }
            }
            let w = (i + NT - 1) % NT;
            ix += col * (self.sin_face[i] - self.sin_face[w]);
            iy += col * (self.cos_face[w] - self.cos_face[i]);
            leak += 0.5 * self.k2 * self.hc3[i] * self.pressure[i * NZ + NZ - 1] / DZ * DTH;
        }
        for j in 0..NZ {
            supply += zw(j) * DZ * DTH * (eps_dot * self.cos_mean[0] - self.rate[j]);
        }
        let volume = c * r * l;
        let (peak, angle) = if at == usize::MAX { (0.0, f64::NAN) } else { (peak, DTH * at as f64) };
        JfoReading {
            force: (r * l * p_scale * ix, r * l * p_scale * iy),
            side_leakage: volume * leak,
            supply: volume * supply,
            peak_pressure: p_scale * peak,
            peak_angle: angle,
            oil: volume * oil,
        }
    }

    /// Advance the fill over a (sub-)step of `dt` \[s\]: the oil m = θ_f H (H at the step's
    /// start, `h_start`) gains `dt` × `pressure_rate` (the mean of the step's solves'
    /// [`Self::pressure_rate`]) and is carried `shift` \[rad\] around the bearing with the mean
    /// surface speed (upwind in θ_f; |shift| ≤ ½ cell keeps it stable and positive); the new fill
    /// is m over the gap at the last solve's ε (the step's end), the supply groove and the nodes
    /// the last solve held full (P > 0) full, every other within [0, 1].
    pub fn apply(&self, fill: &mut [f64], h_start: &[f64], pressure_rate: &[f64], dt: f64, shift: f64, scratch: &mut Vec<f64>) {
        scratch.clear();
        scratch.extend(fill.iter().enumerate().map(|(n, v)| if n < NZ { 1.0 } else { v.clamp(0.0, 1.0) }));
        let c = shift / DTH;
        for i in 0..NT {
            let (e, w) = ((i + 1) % NT, (i + NT - 1) % NT);
            let (hf_e, hf_w) = (self.hf3[i].cbrt(), self.hf3[w].cbrt());
            for j in 0..NZ {
                let n = i * NZ + j;
                if i == 0 || (self.free[n] && self.pressure[n] > 0.0) {
                    fill[n] = 1.0;
                    continue;
                }
                let up_e = if c >= 0.0 { scratch[n] } else { scratch[e * NZ + j] };
                let up_w = if c >= 0.0 { scratch[w * NZ + j] } else { scratch[n] };
                let m = scratch[n] * h_start[i] + dt * pressure_rate[n] - c * (up_e * hf_e - up_w * hf_w);
                fill[n] = (m / self.h[i]).clamp(0.0, 1.0);
            }
        }
    }

    /// The largest |W|/2 · dt / Δθ a step of `dt` \[s\] at wedge speed `wedge` \[rad/s\] may take
    /// for the upwind transport to stay stable and positive: ½.
    pub fn courant(wedge: f64, dt: f64) -> f64 {
        0.5 * wedge.abs() * dt / DTH
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Butenschön's rotation table (with the supply line, his convention) at one B/D.
    fn butenschoen(bd: &str) -> Vec<(f64, f64, f64)> {
        let text = include_str!("../../tests/data/butenschoen_rotation_all.csv");
        text.lines()
            .filter(|l| l.starts_with(&format!("{bd},")))
            .map(|l| {
                let v: Vec<f64> = l.split(',').skip(1).map(|x| x.trim().parse().unwrap()).collect();
                (v[0], v[1], v[2])
            })
            .collect()
    }

    #[test]
    fn a_full_film_is_the_reynolds_problem_of_butenschoens_table() {
        // Content full everywhere (a flooded bearing), pure rotation: the LCP is the Reynolds
        // (Swift–Stieber) problem with the supply line, Butenschön's convention. So = F Ψ²/(B D η W)
        // = 3 ε |I|/2 with F = (3 μ R³ L ρ/c²) I, ρ = W ε; here F = R L (6μR²/c²) Σ P …
        for (bd, k) in [("1/2", 2.0), ("1", 1.0)] {
            let mut film = JfoFilm::new(k);
            for (eps, so_tab, beta_tab) in butenschoen(bd) {
                if eps > 0.8 {
                    continue;
                }
                let m = vec![1.0; N];
                film.solve(&m, eps, 0.0, 100.0);
                let (r, c, l, mu) = (0.01, 1e-5, 0.02 / k, 0.01);
                let f = film.reading(&m, r, c, l, mu, 0.0).force;
                let psi = c / r;
                let so = f.0.hypot(f.1) * psi * psi / (l * 2.0 * r * mu * 100.0);
                let beta = f.1.abs().atan2(-f.0).to_degrees();
                eprintln!("flooded JFO film vs Butenschön, B/D {bd}, ε {eps}: So {:+.2} %, β {:+.2}°", 100.0 * (so / so_tab - 1.0), beta - beta_tab);
                assert!((so / so_tab - 1.0).abs() < 0.03 && (beta - beta_tab).abs() < 2.0, "B/D {bd} ε {eps}: So {so:.4} vs {so_tab}, β {beta:.2} vs {beta_tab}");
            }
        }
    }
}
