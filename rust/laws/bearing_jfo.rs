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

/// The oil m = θ_f H_ref of node n (in cell i) of `fill` measured against `h_ref` (empty: `h`).
#[inline]
fn oil(fill: &[f64], h_ref: &[f64], h: &[f64], i: usize, n: usize) -> f64 {
    fill[n].clamp(0.0, 1.0) * if h_ref.is_empty() { h[i] } else { h_ref[i] }
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
    /// fills; N = [`JFO_THETA`] × [`JFO_ZETA`] values, row-major in θ, measured against the gaps
    /// `h_ref`, H per cell, or with `h_ref` empty against the gaps at `eps`) a time `since` \[s\]
    /// after the fill was taken, at eccentricity ratio `eps`, its rate `eps_dot` \[1/s\] and the
    /// wedge speed `wedge` \[rad/s\]: the pressure P \[1/s\], the oil's rate [`Self::rate`] (m = θ_f H,
    /// in units of c per second) and the fill now, [`Self::fill`].
    ///
    /// A full node (θ_f = 1) stays full while the gap moves (the pressure holds it so, or lets
    /// it go: the LCP with ∂H/∂t). A partly filled node's oil m is advanced over `since` by
    /// backward Euler, m + since · rate ≤ H with P ≥ 0 and equality where P > 0: the same LCP
    /// with q = (H − m)/since − Couette; so it fills, and carries pressure continuously from 0,
    /// within the step as the gap closes on it and the full film's pressure pushes oil into it
    /// (`since` ≤ 0 or NaN: at the fill's own time, a partly filled node carries no pressure
    /// unless the gap has closed below its oil).
    ///
    /// (With the fill frozen over a step, as before, the reformation front's nodes filled only at
    /// the step's end: a jump of the force at every step's start, and steps of ~1 µs through the
    /// reformation of an engine cycle's film.)
    pub fn solve(&mut self, fill: &[f64], h_ref: &[f64], since: f64, eps: f64, eps_dot: f64, wedge: f64) {
        let w2 = 0.5 * wedge;
        for i in 0..NT {
            let hf = 1.0 + eps * self.cos_face[i];
            let hc = 1.0 + eps * self.cos_centre[i];
            self.h[i] = 1.0 + eps * self.cos_mean[i];
            self.hf3[i] = hf * hf * hf;
            self.hc3[i] = hc * hc * hc;
        }
        self.effective_fill(fill, h_ref);
        let secant = since > 0.0;
        // A partly filled node whose pressure would need more than this rate is left empty of it.
        let cap = 1e3 * (wedge.abs() + eps_dot.abs() + 1.0);
        // With a time since the fill (backward Euler), the partly filled nodes' fill now and the
        // pressure are found together: the LCP at the fill of the last pass, then the fill from
        // the pressure (an upwind sweep), until the fill stops moving.
        for pass in 0..if secant { 4 } else { 1 } {
            self.couette_and_q(fill, h_ref, since, eps, eps_dot, w2, cap);
            self.solve_lcp();
            for i in 0..NT {
                for j in 0..NZ {
                    self.pressure_rate[i * NZ + j] = 0.5 * self.laplacian(i, j);
                }
            }
            if !secant || !self.sweep(fill, h_ref, since, eps, w2) || pass == 3 {
                break;
            }
        }
        for n in 0..N {
            self.rate[n] = self.couette[n] + self.pressure_rate[n];
        }
    }

    /// The Couette rate of every node at the fill [`Self::fill`] and the LCP's q and eligible set
    /// (module doc; [`Self::solve`]).
    #[allow(clippy::too_many_arguments)]
    fn couette_and_q(&mut self, fill: &[f64], h_ref: &[f64], since: f64, eps: f64, eps_dot: f64, w2: f64, cap: f64) {
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
                let full = i == 0 || fill[n] >= 1.0 - FULL;
                if full || since <= 0.0 {
                    self.q[n] = dhdt - self.couette[n];
                    self.eligible[n] = i > 0 && self.fill[n] >= 1.0 - FULL;
                } else {
                    let m = oil(fill, h_ref, &self.h, i, n);
                    self.q[n] = ((self.h[i] - m) / since - self.couette[n]).min(cap);
                    self.eligible[n] = true;
                }
            }
        }
    }

    /// The fill now of the partly filled nodes from the pressure of the last LCP: backward Euler
    /// θ H = m + since · (Couette(θ) + ½ L P), the Couette flux upwind, swept from the supply
    /// groove (full) with the flow; a node the LCP pressurises is full. `true` if a fill moved by
    /// more than 1e-12.
    fn sweep(&mut self, fill: &[f64], h_ref: &[f64], since: f64, eps: f64, w2: f64) -> bool {
        let mut moved = false;
        let k = since * w2.abs() / DTH;
        for step in 1..NT {
            // With the flow: the upwind neighbour comes first (the groove, cell 0, is full).
            let (i, up) = if w2 >= 0.0 { (step, step - 1) } else { (NT - step, (NT - step + 1) % NT) };
            // Faces: the one the oil leaves by and the one it comes in by.
            let (f_out, f_in) = if w2 >= 0.0 { (i, up) } else { (i - 1, i) };
            let (h_out, h_in) = (1.0 + eps * self.cos_face[f_out], 1.0 + eps * self.cos_face[f_in]);
            for j in 0..NZ {
                let n = i * NZ + j;
                if fill[n] >= 1.0 - FULL {
                    continue;
                }
                let theta = if self.pressure[n] > 0.0 {
                    1.0
                } else {
                    let m = oil(fill, h_ref, &self.h, i, n) + since * self.pressure_rate[n] + k * self.fill[up * NZ + j] * h_in;
                    (m / (self.h[i] + k * h_out)).clamp(0.0, 1.0)
                };
                moved |= (theta - self.fill[n]).abs() > 1e-12;
                self.fill[n] = theta;
            }
        }
        moved
    }

    /// The fill of each node at the gaps [`Self::h`] of this solve from `fill` measured against
    /// the gaps `h_ref` (empty: the same gaps): full nodes stay full, a partly filled node keeps
    /// its oil (θ_f H_ref / H, at most 1), the supply groove is full.
    fn effective_fill(&mut self, fill: &[f64], h_ref: &[f64]) {
        for i in 0..NT {
            let ratio = if h_ref.is_empty() { 1.0 } else { h_ref[i] / self.h[i] };
            for j in 0..NZ {
                let n = i * NZ + j;
                let f = fill[n].clamp(0.0, 1.0);
                self.fill[n] = if i == 0 || f >= 1.0 - FULL { 1.0 } else { (f * ratio).min(1.0) };
            }
        }
    }

    /// The fill of every node at eccentricity ratio `eps` from `fill` measured against the gaps
    /// `h_ref` (as [`Self::solve`] takes them), without solving.
    pub fn fill_at(&mut self, fill: &[f64], h_ref: &[f64], eps: f64) -> &[f64] {
        for i in 0..NT {
            self.h[i] = 1.0 + eps * self.cos_mean[i];
        }
        self.effective_fill(fill, h_ref);
        &self.fill
    }

    /// The oil in the gap \[in units of c R L\] of `fill` measured against the gaps `h` (cell
    /// means of H; the supply groove full): Σ θ_f H over the control volumes.
    pub fn oil_of(fill: &[f64], h: &[f64]) -> f64 {
        let mut oil = 0.0;
        for i in 0..NT {
            for j in 0..NZ {
                let f = if i == 0 { 1.0 } else { fill[i * NZ + j].clamp(0.0, 1.0) };
                oil += zw(j) * DZ * DTH * h[i] * f;
            }
        }
        oil
    }

    /// The fill of every node at the last solve (N values, row-major in θ; see [`Self::solve`]).
    pub fn fill(&self) -> &[f64] {
        &self.fill
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
    /// clearance `c`, length `l` \[m\] and viscosity `mu` \[Pa s\] (the oil from the fill it was
    /// solved with, [`Self::fill`]).
    pub fn reading(&self, r: f64, c: f64, l: f64, mu: f64, eps_dot: f64) -> JfoReading {
        let p_scale = 6.0 * mu * r * r / (c * c);
        let (mut ix, mut iy, mut leak, mut supply, mut oil) = (0.0, 0.0, 0.0, 0.0, 0.0);
        let (mut peak, mut at) = (0.0, usize::MAX);
        for i in 0..NT {
            let mut col = 0.0;
            for j in 0..NZ {
                let n = i * NZ + j;
                col += zw(j) * self.pressure[n] * DZ;
                oil += zw(j) * DZ * DTH * self.h[i] * self.fill[n];
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

    /// The fill a step of `dt` \[s\] leaves, from the last solve (made at the step's end with
    /// `since` = `dt` and the step's start fill `fill`): the supply groove and the nodes the solve
    /// held full (P > 0) full, a partly filled node's the solve's ([`Self::fill`], backward Euler),
    /// a full node the solve let go (P = 0, so the gap outran the oil by the slack s = q − ½LP)
    /// 1 − dt·s/H; into `out`.
    pub fn step_fill(&self, fill: &[f64], dt: f64, out: &mut [f64]) {
        for i in 0..NT {
            for j in 0..NZ {
                let n = i * NZ + j;
                out[n] = if i == 0 || (self.free[n] && self.pressure[n] > 0.0) {
                    1.0
                } else if fill[n] >= 1.0 - FULL {
                    (1.0 - dt * (self.q[n] - self.pressure_rate[n]) / self.h[i]).clamp(0.0, 1.0)
                } else {
                    self.fill[n]
                };
            }
        }
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
                film.solve(&m, &[], 0.0, eps, 0.0, 100.0);
                let (r, c, l, mu) = (0.01, 1e-5, 0.02 / k, 0.01);
                let f = film.reading(r, c, l, mu, 0.0).force;
                let psi = c / r;
                let so = f.0.hypot(f.1) * psi * psi / (l * 2.0 * r * mu * 100.0);
                let beta = f.1.abs().atan2(-f.0).to_degrees();
                eprintln!("flooded JFO film vs Butenschön, B/D {bd}, ε {eps}: So {:+.2} %, β {:+.2}°", 100.0 * (so / so_tab - 1.0), beta - beta_tab);
                assert!((so / so_tab - 1.0).abs() < 0.03 && (beta - beta_tab).abs() < 2.0, "B/D {bd} ε {eps}: So {so:.4} vs {so_tab}, β {beta:.2} vs {beta_tab}");
            }
        }
    }
}
