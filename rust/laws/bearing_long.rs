//! Long (Pinkus–Sternlicht, infinitely long) journal bearing: the paper's film model
//! (Eqs. 10–14), with the pressure of docs/physics.md §4 (P12 corrected) and the Gümbel condition.
//!
//! Pressure (θ counter-clockwise from the thickest film, `h = c(1 + ε cos θ)`, wedge
//! `W = θ̇_j + θ̇_i − 2γ̇`):
//! `p(θ) = 6μ(R/c)² { W ε sinθ (2 + ε cosθ) / ((2 + ε²)(1 + ε cosθ)²)
//!                    + (ε̇/ε) [1/(1 + ε cosθ)² − 1/(1 + ε)²] }`.
//!
//! Positive-pressure arc. With φ = θ/2, `p (1 + ε cosθ)² / (6μ(R/c)²) = 2 sinφ · H(φ)`,
//! `H(φ) = a cosφ (2 − ε + 2ε cos²φ) + 2 s sinφ (1 + ε cos²φ)`, `a = Wε/(2 + ε²)`,
//! `s = ε̇/(1 + ε)²` (no division by ε). With x = cot φ, H ∝ a(2+ε)x³ + 2s(1+ε)x² + a(2−ε)x + 2s,
//! and `((1+ε)x² + 1)/(x((2+ε)x² + 2 − ε))` is strictly monotone on each half-line, so for
//! a ≠ 0, s ≠ 0 the pressure has exactly one zero θ* in (0, 2π) besides θ = 0: the positive arc
//! is (0, θ*) for a > 0 and (θ*, 2π) for a < 0. Pure wedge: θ* = π. Pure squeeze: p has the
//! sign of ε̇ everywhere (the whole film for ε̇ > 0, nothing for ε̇ < 0).
//!
//! Integration. [`long_bearing_force`] integrates p over the exact arc with closed-form
//! antiderivatives written in the Sommerfeld angle ψ (`1 + ε cosθ = (1 − ε²)/(1 − ε cosψ)`,
//! `cosψ = (cosθ + ε)/(1 + ε cosθ)`, `sinψ = √(1−ε²) sinθ/(1 + ε cosθ)`), arranged so that no
//! term divides by ε:
//! - `∫ sinθ cosθ (2 + ε cosθ)/v² dθ = −cos²θ / v`,
//! - `∫ sin²θ (2 + ε cosθ)/v² dθ = (ψ − sinψ cosθ)/√(1−ε²)`,
//! - `(1/ε) ∫ cosθ [1/v² − 1/(1+ε)²] dθ = [sinψ (2 − ε − cosψ) v/(1−ε²) − ψ] / (1−ε²)^{3/2}`,
//! - `(1/ε) ∫_{θ1}^{θ2} sinθ [1/v² − 1/(1+ε)²] dθ
//!    = (u1 − u2)(2 − u1 − u2 + ε(1 − u1 u2)) / ((1+ε)² v1 v2)`, `u = cosθ`, `v = 1 + εu`.
//!
//! Arcs shorter than 0.5 rad (always next to θ = 0 or 2π) use 8-point Gauss–Legendre instead,
//! where the antiderivative differences would cancel.
//!
//! [`long_bearing_force_quadrature`] is the same integral by composite 16-point Gauss–Legendre
//! on panels graded towards the thinnest film (θ = π) — the reference method of docs/physics.md §4. Measured
//! (tests): both agree with an independent adaptive Simpson rule to ≤ 5e-12 (closed form) and
//! ≤ 4e-13 (GL) relative for ε ∈ [0.01, 0.99]; with each other to ≤ 7e-10 up to ε = 0.999 (the
//! closed form loses a few digits there for small receding-squeeze forces: its terms scale as
//! (1−ε²)^{-3/2}). The closed form is the default: ~0.3 µs per call against ~1.3 µs for the graded
//! GL, since a single Gauss–Legendre rule would need ~60+ nodes at ε = 0.99 for 1e-6 (p has
//! poles at θ = π ± i·acosh(1/ε)).

use super::geometry::{BearingGeometry, FilmState};
use super::quadrature::{GL16, GL8};
use std::f64::consts::{PI, TAU};

/// `6 μ (R/c)²` [Pa·s]: pressure scale of the long bearing (times a rate gives Pa).
fn pressure_scale(g: &BearingGeometry) -> f64 {
    let r_over_c = g.journal_radius / g.clearance;
    6.0 * g.viscosity * r_over_c * r_over_c
}

/// Pressure kernel `p / (6μ(R/c)²)` [1/s] from sinθ, cosθ; `1 − cosθ` is formed as
/// `sin²θ/(1 + cosθ)` on the thick side so that it keeps full relative precision near θ = 0.
fn pressure_kernel(eps: f64, eps_dot: f64, wedge: f64, sn: f64, cs: f64) -> f64 {
    let v = 1.0 + eps * cs;
    let one_minus_cos = if cs > 0.0 { sn * sn / (1.0 + cs) } else { 1.0 - cs };
    let op = 1.0 + eps;
    let wedge_part = wedge * eps * sn * (2.0 + eps * cs) / (2.0 + eps * eps);
    let squeeze_part = eps_dot * one_minus_cos * (2.0 + eps + eps * cs) / (op * op);
    (wedge_part + squeeze_part) / (v * v)
}

/// Film pressure p(θ) \[Pa\] of the long bearing (docs/physics.md §4, P12 corrected), before the Gümbel
/// cut. θ \[rad\] counter-clockwise from the thickest film. Finite at ε = 0 (the squeeze term is
/// written as `ε̇ (1 − cosθ)(2 + ε + ε cosθ)/((1 + ε cosθ)²(1 + ε)²)`, its exact form).
pub fn long_bearing_pressure(g: &BearingGeometry, s: FilmState, theta: f64) -> f64 {
    let eps = s.clamped_eps();
    let (sn, cs) = theta.sin_cos();
    pressure_scale(g) * pressure_kernel(eps, s.eps_dot, s.wedge, sn, cs)
}

/// One end of the positive-pressure arc: θ with its sine, cosine and `1 − cosθ`, all computed
/// from θ/2 for full precision.
#[derive(Clone, Copy, Debug)]
struct ArcEnd {
    theta: f64,
    sin: f64,
    cos: f64,
    one_minus_cos: f64,
}

impl ArcEnd {
    const START: ArcEnd = ArcEnd { theta: 0.0, sin: 0.0, cos: 1.0, one_minus_cos: 0.0 };
    const MID: ArcEnd = ArcEnd { theta: PI, sin: 0.0, cos: -1.0, one_minus_cos: 2.0 };
    const END: ArcEnd = ArcEnd { theta: TAU, sin: 0.0, cos: 1.0, one_minus_cos: 0.0 };

    /// The end at θ = 2φ with `x = cot φ`, φ ∈ (0, π): `sin φ = 1/√(1 + x²)`, `cos φ = x sin φ`,
    /// so `sin θ = 2x/(1 + x²)`, `cos θ = (x² − 1)/(1 + x²)`, `1 − cos θ = 2/(1 + x²)`, each to
    /// full relative precision (for |x| > 1 written in y = 1/x = tan φ, so that nothing
    /// overflows), and one `atan2` for θ itself.
    fn from_half_angle_cot(x: f64) -> ArcEnd {
        let theta = 2.0 * 1.0_f64.atan2(x);
        if x.abs() <= 1.0 {
            let d = 1.0 + x * x;
            ArcEnd { theta, sin: 2.0 * x / d, cos: (x * x - 1.0) / d, one_minus_cos: 2.0 / d }
        } else {
            let y = 1.0 / x;
            let d = 1.0 + y * y;
            ArcEnd { theta, sin: 2.0 * y / d, cos: (1.0 - y * y) / d, one_minus_cos: 2.0 * y * y / d }
        }
    }
}

/// The positive-pressure arc (θ1, θ2) ⊂ [0, 2π] of the long-bearing pressure, or `None` when
/// p ≤ 0 everywhere (pure receding squeeze, or no motion). See the module doc.
fn positive_arc(eps: f64, eps_dot: f64, wedge: f64) -> Option<(ArcEnd, ArcEnd)> {
    let a = wedge * eps / (2.0 + eps * eps);
    let op = 1.0 + eps;
    let s = eps_dot / (op * op);
    if a == 0.0 {
        return if s > 0.0 { Some((ArcEnd::START, ArcEnd::END)) } else { None };
    }
    if s == 0.0 {
        return if a > 0.0 { Some((ArcEnd::START, ArcEnd::MID)) } else { Some((ArcEnd::MID, ArcEnd::END)) };
    }
    let end = ArcEnd::from_half_angle_cot(wedge_squeeze_zero(eps, a, s));
    if a > 0.0 {
        Some((ArcEnd::START, end))
    } else {
        Some((end, ArcEnd::END))
    }
}

/// The unique zero φ* ∈ (0, π) of `H(φ) = a cosφ (2 − ε + 2ε cos²φ) + 2 s sinφ (1 + ε cos²φ)`
/// (a ≠ 0, s ≠ 0), returned as `x* = cot φ*`: with x = cot φ, `H sin⁻³φ` is the cubic
/// `P(x) = a(2 + ε) x³ + 2s(1 + ε) x² + a(2 − ε) x + 2s` (module doc), whose only real root this
/// is, so no sine or cosine is needed per iteration. Safeguarded Newton iteration inside a sign
/// bracket, started from the exact ε = 0 root `x = −s/a` (there `P = 2(x² + 1)(a x + s)`); where
/// Newton leaves the bracket, the bracket is halved in φ. Where `|x*| > 1e8` (an arc within 1e-8
/// rad of θ = 0 or 2π) `x* = −B/A` to within 1e-16 relative (`x = −B/A − C/(A x) − D/(A x²)`).
fn wedge_squeeze_zero(eps: f64, a: f64, s: f64) -> f64 {
    // sign(a)·P: P → +∞ for x → +∞ (φ → 0), P → −∞ for x → −∞ (φ → π).
    let (a, s) = if a > 0.0 { (a, s) } else { (-a, -s) };
    let (ca, cb, cc, cd) = (a * (2.0 + eps), 2.0 * s * (1.0 + eps), a * (2.0 - eps), 2.0 * s);
    let far = -cb / ca;
    if far.abs() > 1e8 {
        return far;
    }
    // Cauchy's bound: every real root lies within |x| < 1 + max(|B|, |C|, |D|)/A.
    let bound = 1.0 + cb.abs().max(cc).max(cd.abs()) / ca;
    let (mut lo, mut hi) = (-bound, bound);
    let mut x = (-s / a).clamp(lo, hi);
    let mut last_newton = f64::INFINITY;
    for _ in 0..80 {
        let p = ((ca * x + cb) * x + cc) * x + cd;
        // P is zero to within its rounding error: x is the root as well as P can tell.
        let noise = 8.0 * f64::EPSILON * (((ca * x.abs() + cb.abs()) * x.abs() + cc) * x.abs() + cd.abs());
        if p.abs() <= noise {
            return x;
        }
        if p > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        let dp = (3.0 * ca * x + 2.0 * cb) * x + cc;
        let newton = x - p / dp;
        let in_bracket = newton > lo && newton < hi;
        let next = if in_bracket {
            newton
        } else {
            // Halve the bracket in φ = atan2(1, x) (rare: Newton left the bracket).
            (0.5 * (1.0_f64.atan2(lo) + 1.0_f64.atan2(hi))).tan().recip()
        };
        let step = (next - x).abs();
        x = next;
        let tol = 4e-16 * x.abs().max(1.0);
        if step <= tol || hi - lo <= tol {
            break;
        }
        // Newton has stalled at the rounding level of P: stop instead of spinning through all
        // 80 iterations.
        if in_bracket {
            if step >= 0.5 * last_newton && step <= 1e-12 * x.abs().max(1.0) {
                break;
            }
            last_newton = step;
        }
    }
    x
}

/// Arcs shorter than this [rad] (always adjacent to θ = 0 or 2π) are integrated by 8-point
/// Gauss–Legendre instead of the closed form, whose antiderivative differences lose relative
/// precision as (arc length)⁻² there; on such an arc the nearest pole of p is ≥ π − 0.5 away,
/// so the rule is exact to rounding.
const SHORT_ARC: f64 = 0.5;

/// `∫ kernel·(cosθ, sinθ) dθ` over a short arc by GL8; arcs ending at 2π are shifted by −2π so
/// that sinθ, cosθ keep their relative precision near the end.
fn short_arc_integral(eps: f64, eps_dot: f64, wedge: f64, e1: &ArcEnd, e2: &ArcEnd) -> (f64, f64) {
    let (t1, t2) = if e2.theta == TAU { (e1.theta - TAU, 0.0) } else { (e1.theta, e2.theta) };
    GL8.integrate2(t1, t2, |th| {
        let (sn, cs) = th.sin_cos();
        let p = pressure_kernel(eps, eps_dot, wedge, sn, cs).max(0.0);
        (p * cs, p * sn)
    })
}

/// What both long-bearing integrals start with: the positive-pressure arc of the state. No arc
/// (the whole film cavitated) or a short one (Gauss–Legendre) gives the force at once; a long
/// arc is left to the caller's method, with the clamped ε and the force scale `p₀ R L`.
enum Arc {
    Done((f64, f64)),
    Long { eps: f64, e1: ArcEnd, e2: ArcEnd, scale: f64 },
}

fn long_arc(g: &BearingGeometry, s: FilmState) -> Arc {
    let eps = s.clamped_eps();
    let Some((e1, e2)) = positive_arc(eps, s.eps_dot, s.wedge) else {
        return Arc::Done((0.0, 0.0));
    };
    let scale = pressure_scale(g) * g.journal_radius * g.length;
    if e2.theta - e1.theta < SHORT_ARC {
        let (fx, fy) = short_arc_integral(eps, s.eps_dot, s.wedge, &e1, &e2);
        return Arc::Done((scale * fx, scale * fy));
    }
    Arc::Long { eps, e1, e2, scale }
}

/// Long-bearing film force `(F_ξ, F_η)` \[N\] on the journal (docs/physics.md §4): `R L ∫ p⁺ (cosθ, sinθ) dθ`
/// over the exact positive-pressure arc, in closed form (see the module doc; arcs shorter than
/// 0.5 rad by Gauss–Legendre). Finite for every finite input: ε is clamped to [0, 1 − 1e-9];
/// ε = 0 uses the exact limit of the squeeze term.
pub fn long_bearing_force(g: &BearingGeometry, s: FilmState) -> (f64, f64) {
    let (eps, e1, e2, scale) = match long_arc(g, s) {
        Arc::Done(force) => return force,
        Arc::Long { eps, e1, e2, scale } => (eps, e1, e2, scale),
    };
    let beta2 = (1.0 - eps) * (1.0 + eps);
    let beta = beta2.sqrt();
    let beta3 = beta2 * beta;
    let op = 1.0 + eps;
    // Sommerfeld angle ψ(θ) (monotone in θ, ψ(0) = 0, ψ(π) = π, ψ(2π) = 2π), with sinψ, cosψ;
    // v = 1 + ε cosθ. Only differences of ψ enter, so an arc ending at 2π is measured from
    // there (ψ − 2π ∈ (−2π, 0]) to keep ψ precise when the arc is short and ε → 1.
    let ends_at_tau = e2.theta == TAU;
    let sommerfeld = |e: &ArcEnd| {
        let v = 1.0 + eps * e.cos;
        let (sp, cp) = (beta * e.sin / v, (e.cos + eps) / v);
        let psi = if e.theta == 0.0 || e.theta == TAU {
            0.0
        } else if e.theta == PI {
            if ends_at_tau { -PI } else { PI }
        } else {
            let p = sp.atan2(cp);
            if ends_at_tau {
                if p >= 0.0 { p - TAU } else { p }
            } else if p < 0.0 {
                p + TAU
            } else {
                p
            }
        };
        (v, psi, sp, cp)
    };
    let (v1, mut psi1, sp1, cp1) = sommerfeld(&e1);
    let (v2, psi2, sp2, cp2) = sommerfeld(&e2);
    if ends_at_tau && e1.theta == 0.0 {
        psi1 = -TAU; // the full film
    }
    let (u1, u2) = (e1.cos, e2.cos);
    // u1 − u2 from the precise 1 − cosθ values.
    let du = e2.one_minus_cos - e1.one_minus_cos;

    // Wedge part, coefficient a = Wε/(2 + ε²).
    // Δ[−u²/v] = (u1 − u2)(u1 + u2 + ε u1 u2)/(v1 v2).
    let a = s.wedge * eps / (2.0 + eps * eps);
    let i2 = |psi: f64, sp: f64, u: f64| (psi - sp * u) / beta;
    let wedge_xi = a * du * (u1 + u2 + eps * u1 * u2) / (v1 * v2);
    let wedge_eta = a * (i2(psi2, sp2, u2) - i2(psi1, sp1, u1));

    // Squeeze part, coefficient ε̇ (the 1/ε is inside the antiderivatives).
    let t3 = |psi: f64, sp: f64, cp: f64, v: f64| (sp * (2.0 - eps - cp) * v / beta2 - psi) / beta3;
    let squeeze_xi = s.eps_dot * (t3(psi2, sp2, cp2, v2) - t3(psi1, sp1, cp1, v1));
    // (u1 − u2)(2 − u1 − u2 + ε(1 − u1 u2)) with w = 1 − u: (w2 − w1)((w1 + w2)(1 + ε) − ε w1 w2).
    let (w1, w2) = (e1.one_minus_cos, e2.one_minus_cos);
    let squeeze_eta = s.eps_dot * du * ((w1 + w2) * op - eps * w1 * w2) / (op * op * v1 * v2);

    (scale * (wedge_xi + squeeze_xi), scale * (wedge_eta + squeeze_eta))
}

/// The long bearing's force at the bearing centre to first order in ε, `(F_ξ, F_η)` \[N\]
/// (docs/physics.md §4, "Through the centre"): with p = 0 at the thickest film the first-order
/// squeeze pressure ∝ ε̇ (1 − cos θ) is one-signed and depends on which side n points; the
/// periodic (Sommerfeld) first-order pressure with the Gümbel condition does not, and gives
/// `F = (π/2) 6μ(R/c)² R L u`, u = ε W t − 2 ε̇ n = (θ̇_sum e⊥ − 2 ė)/c: linear in the journal's
/// motion and smooth through e = 0. Its wedge part is the long bearing's own first-order force;
/// its squeeze part is the mean of the long bearing's squeeze force on both sides of the centre.
pub fn long_bearing_centre_limit(g: &BearingGeometry, s: FilmState) -> (f64, f64) {
    let scale = pressure_scale(g) * g.journal_radius * g.length * PI;
    let eps = s.clamped_eps();
    (-scale * s.eps_dot, 0.5 * scale * eps * s.wedge)
}

/// The same force as [`long_bearing_force`] by composite 16-point Gauss–Legendre quadrature of
/// p over the exact positive arc, on panels with breakpoints at `π ± d·3ᵏ`,
/// `d = acosh(1/ε)` (the distance of the poles of p from the real axis), so every panel sees
/// its nearest pole at ≳ its own length. Reference method (~1e-12 relative); slower.
pub fn long_bearing_force_quadrature(g: &BearingGeometry, s: FilmState) -> (f64, f64) {
    let (eps, e1, e2, scale) = match long_arc(g, s) {
        Arc::Done(force) => return force,
        Arc::Long { eps, e1, e2, scale } => (eps, e1, e2, scale),
    };
    let (t1, t2) = (e1.theta, e2.theta);
    // Pole distance d = acosh(1/ε) = ln((1 + √(1−ε²))/ε); +∞ at ε = 0.
    let d = if eps > 0.0 { ((1.0 + ((1.0 - eps) * (1.0 + eps)).sqrt()) / eps).ln() } else { f64::INFINITY };
    // Breakpoints strictly inside (t1, t2), ascending.
    let mut cuts = [0.0_f64; 40];
    let mut n = 0;
    cuts[n] = t1;
    n += 1;
    let mut offsets = [0.0_f64; 16];
    let mut k = 0;
    let mut off = d;
    while off < PI && k < offsets.len() {
        offsets[k] = off;
        k += 1;
        off *= 3.0;
    }
    for j in (0..k).rev() {
        let x = PI - offsets[j];
        if x > t1 && x < t2 {
            cuts[n] = x;
            n += 1;
        }
    }
    if PI > t1 && PI < t2 {
        cuts[n] = PI;
        n += 1;
    }
    for &o in offsets.iter().take(k) {
        let x = PI + o;
        if x > t1 && x < t2 {
            cuts[n] = x;
            n += 1;
        }
    }
    cuts[n] = t2;
    n += 1;
    let (mut fx, mut fy) = (0.0, 0.0);
    for w in cuts[..n].windows(2) {
        let (a, b) = GL16.integrate2(w[0], w[1], |th| {
            let (sn, cs) = th.sin_cos();
            let p = pressure_kernel(eps, s.eps_dot, s.wedge, sn, cs).max(0.0);
            (p * cs, p * sn)
        });
        fx += a;
        fy += b;
    }
    (scale * fx, scale * fy)
}

/// The paper's printed closed forms, Eqs. (13)–(14), as printed (a labelled variant; docs/physics.md §4
/// lists their errors: 10–25 % off at large squeeze ratios, wrong sign of F_ξ for ε̇ < 0, and a
/// large force for pure receding squeeze where the Gümbel integral is zero):
/// ε̇ > 0: `F_ξ = −(6μR³L/c²) ε̇/(1−ε²)^{3/2} (4kε²/(2+ε²) + π(k+3)/(k+1.5))`,
///         `F_η = (6μR³L/c²) π ε W /((2+ε²)(1−ε²)^{1/2}) (k+3)/(k+1.5)`;
/// ε̇ < 0: the same with `− π(k+3)/(k+1.5)` in F_ξ and `k/(k+1.5)` in F_η;
/// `k² = (1 − ε²)((W/(2ε̇))² + 1/ε²)` as printed.
/// ε̇ = 0 (k → ∞) is evaluated as the limit ε̇ → 0⁺, which is the half-Sommerfeld pure-rotation
/// result; `k ε̇` and `1/k` are formed without dividing by ε̇ or ε, so there is no NaN.
pub fn long_bearing_paper_closed_form(g: &BearingGeometry, s: FilmState) -> (f64, f64) {
    let eps = s.clamped_eps();
    let (w, ed) = (s.wedge, s.eps_dot);
    let beta2 = (1.0 - eps) * (1.0 + eps);
    let r_over_c = g.journal_radius / g.clearance;
    let scale = 6.0 * g.viscosity * r_over_c * r_over_c * g.journal_radius * g.length;
    // k ε̇ ε² = sign(ε̇) √((1−ε²)(W² ε⁴/4 + ε̇² ε²)); for ε̇ = 0 take sign +.
    let sign = if ed < 0.0 { -1.0 } else { 1.0 };
    let k_ed_eps2 = sign * (beta2 * (0.25 * w * w * eps.powi(4) + ed * ed * eps * eps)).sqrt();
    // 1/k = 2|ε̇| ε / √((1−ε²)(W²ε² + 4ε̇²)); 0 when k is infinite.
    let den = (beta2 * (w * w * eps * eps + 4.0 * ed * ed)).sqrt();
    let inv_k = if den > 0.0 { 2.0 * ed.abs() * eps / den } else { 0.0 };
    let k3 = (1.0 + 3.0 * inv_k) / (1.0 + 1.5 * inv_k); // (k+3)/(k+1.5)
    let k0 = 1.0 / (1.0 + 1.5 * inv_k); // k/(k+1.5)
    let radial = 4.0 * k_ed_eps2 / (2.0 + eps * eps);
    let (f_xi, f_eta_factor) = if ed >= 0.0 {
        (-(radial + PI * ed * k3), k3)
    } else {
        (-(radial - PI * ed * k3), k0)
    };
    let f_xi = scale * f_xi / (beta2 * beta2.sqrt());
    let f_eta = scale * PI * eps * w / ((2.0 + eps * eps) * beta2.sqrt()) * f_eta_factor;
    (f_xi, f_eta)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_limit_is_the_first_order_long_bearing() {
        // Closed forms at ε → 0: the wedge force is the long bearing's own (π/2)·6μ(R/c)²RL·εW
        // along t; the squeeze force is the mean of the one-sided long-bearing squeeze on the
        // two sides of the centre (approaching: all of it, receding: none).
        let g = BearingGeometry { viscosity: 0.4, journal_radius: 0.01, clearance: 5e-6, length: 0.025 };
        let p = 6.0 * 0.4 * (0.01f64 / 5e-6).powi(2) * 0.01 * 0.025;
        let eps = 1e-7;
        let wedge = FilmState { eps, eps_dot: 0.0, wedge: 300.0 };
        let (lx, le) = long_bearing_force(&g, wedge);
        let (cx, ce) = long_bearing_centre_limit(&g, wedge);
        assert!((ce - 0.5 * PI * p * eps * 300.0).abs() < 1e-12 * ce.abs() && cx == 0.0);
        assert!((le - ce).abs() < 1e-6 * ce.abs() && lx.abs() < 1e-6 * ce.abs(), "long ({lx}, {le}) vs centre ({cx}, {ce})");
        let squeeze = FilmState { eps, eps_dot: 2.0, wedge: 0.0 };
        let approaching = long_bearing_force(&g, squeeze).0;
        let receding = long_bearing_force(&g, FilmState { eps_dot: -2.0, ..squeeze }).0;
        let centre = long_bearing_centre_limit(&g, squeeze).0;
        assert!(receding == 0.0 && approaching < 0.0);
        assert!((centre - 0.5 * approaching).abs() < 1e-6 * centre.abs(), "{centre} vs {approaching}/2");
        assert!((centre + PI * p * 2.0).abs() < 1e-12 * centre.abs());
    }

    const G: BearingGeometry = BearingGeometry { viscosity: 0.4, journal_radius: 0.01, clearance: 5e-4, length: 0.05 };

    /// 6μR³L/c² [N·s]
    fn c0() -> f64 {
        6.0 * G.viscosity * G.journal_radius.powi(3) * G.length / (G.clearance * G.clearance)
    }

    /// The docs/physics.md §4 pressure, written out independently (divides by ε; ε > 0 only).
    fn p_spec(eps: f64, eps_dot: f64, wedge: f64, th: f64) -> f64 {
        let v = 1.0 + eps * th.cos();
        let k = 6.0 * G.viscosity * (G.journal_radius / G.clearance).powi(2);
        k * (wedge * eps * th.sin() * (2.0 + eps * th.cos()) / ((2.0 + eps * eps) * v * v)
            + (eps_dot / eps) * (1.0 / (v * v) - 1.0 / ((1.0 + eps) * (1.0 + eps))))
    }

    /// The same pressure in the stable algebraic form `ε(1 − cosθ)(2 + ε + ε cosθ)/(1 + ε)²`
    /// for `1 − v²/(1+ε)²`, with `1 − cosθ = 2 sin²(θ/2)` (checked against `p_spec` above).
    fn p_ref(eps: f64, eps_dot: f64, wedge: f64, th: f64) -> f64 {
        let (sn, cs) = th.sin_cos();
        let v = 1.0 + eps * cs;
        let omc = 2.0 * (0.5 * th).sin().powi(2);
        let k = 6.0 * G.viscosity * (G.journal_radius / G.clearance).powi(2);
        k * (wedge * eps * sn * (2.0 + eps * cs) / (2.0 + eps * eps) + eps_dot * omc * (2.0 + eps + eps * cs) / (1.0 + eps).powi(2)) / (v * v)
    }

    /// One adaptive-Simpson step on [a, b] for the pair-valued integrand f (Lyness criterion).
    #[allow(clippy::too_many_arguments)]
    fn adapt<F: Fn(f64) -> (f64, f64)>(f: &F, a: f64, b: f64, fa: (f64, f64), fm: (f64, f64), fb: (f64, f64), whole: (f64, f64), tol: f64, depth: u32) -> (f64, f64) {
        let m = 0.5 * (a + b);
        let (flm, frm) = (f(0.5 * (a + m)), f(0.5 * (m + b)));
        let h = (b - a) / 12.0;
        let left = (h * (fa.0 + 4.0 * flm.0 + fm.0), h * (fa.1 + 4.0 * flm.1 + fm.1));
        let right = (h * (fm.0 + 4.0 * frm.0 + fb.0), h * (fm.1 + 4.0 * frm.1 + fb.1));
        let d = (left.0 + right.0 - whole.0, left.1 + right.1 - whole.1);
        if depth == 0 || d.0.abs().max(d.1.abs()) <= 15.0 * tol {
            return (left.0 + right.0 + d.0 / 15.0, left.1 + right.1 + d.1 / 15.0);
        }
        let l = adapt(f, a, m, fa, flm, fm, left, 0.5 * tol, depth - 1);
        let r = adapt(f, m, b, fm, frm, fb, right, 0.5 * tol, depth - 1);
        (l.0 + r.0, l.1 + r.1)
    }

    /// Adaptive Simpson over [0, 2π] on an initial mesh graded geometrically towards 0 and 2π
    /// (where short positive arcs sit), absolute tolerance `tol` per panel.
    fn adaptive_simpson<F: Fn(f64) -> (f64, f64)>(f: &F, tol: f64) -> (f64, f64) {
        let mut cuts = vec![0.0];
        for k in (1..=60).rev() {
            cuts.push(PI * 0.5_f64.powi(k));
        }
        cuts.push(PI);
        for k in 1..=60 {
            cuts.push(TAU - PI * 0.5_f64.powi(k));
        }
        cuts.push(TAU);
        let (mut sx, mut sy) = (0.0, 0.0);
        for w in cuts.windows(2) {
            let (a, b) = (w[0], w[1]);
            let (fa, fm, fb) = (f(a), f(0.5 * (a + b)), f(b));
            let h = (b - a) / 6.0;
            let whole = (h * (fa.0 + 4.0 * fm.0 + fb.0), h * (fa.1 + 4.0 * fm.1 + fb.1));
            let r = adapt(f, a, b, fa, fm, fb, whole, tol, 50);
            sx += r.0;
            sy += r.1;
        }
        (sx, sy)
    }

    /// Independent reference: R L ∫₀^{2π} max(p, 0)·(cosθ, sinθ) dθ by adaptive Simpson (no
    /// knowledge of the zeros of p), to ~1e-11 relative.
    fn simpson_force(eps: f64, eps_dot: f64, wedge: f64) -> (f64, f64) {
        let f = |th: f64| {
            let p = p_ref(eps, eps_dot, wedge, th).max(0.0);
            (p * th.cos(), p * th.sin())
        };
        let rough = adaptive_simpson(&f, 1e-6 * c0() * (wedge.abs() + eps_dot.abs()));
        let m = rough.0.hypot(rough.1);
        if m == 0.0 {
            return (0.0, 0.0);
        }
        let r = adaptive_simpson(&f, 1e-13 * m);
        let rl = G.journal_radius * G.length;
        (rl * r.0, rl * r.1)
    }

    fn st(eps: f64, eps_dot: f64, wedge: f64) -> FilmState {
        FilmState { eps, eps_dot, wedge }
    }

    /// (wedge, ε̇) pairs from pure squeeze to pure wedge, both signs.
    fn motions() -> Vec<(f64, f64)> {
        let mut v = vec![(0.0, 5.0), (0.0, -5.0), (100.0, 0.0), (-100.0, 0.0)];
        for r in [0.001, 0.01, 0.1, 0.5, 2.0, 10.0, 100.0] {
            for sw in [1.0, -1.0] {
                for se in [1.0, -1.0] {
                    v.push((sw * 100.0, se * r * 100.0));
                }
            }
        }
        v
    }

    #[test]
    fn pressure_matches_spec_formula() {
        for eps in [0.01, 0.3, 0.9, 0.99] {
            for (w, ed) in motions() {
                for i in 0..50 {
                    let th = 0.1 + 0.125 * i as f64;
                    let (a, b) = (long_bearing_pressure(&G, st(eps, ed, w), th), p_spec(eps, ed, w, th));
                    let scale = 6.0 * G.viscosity * (G.journal_radius / G.clearance).powi(2) * (w.abs() + ed.abs());
                    assert!((a - b).abs() <= 1e-12 * scale.max(b.abs()), "ε {eps} θ {th}: {a} vs {b}");
                    let c = p_ref(eps, ed, w, th);
                    assert!((c - b).abs() <= 1e-12 * scale.max(b.abs()), "ε {eps} θ {th}: {c} vs {b}");
                }
            }
        }
        // ε = 0: finite squeeze limit 12μ(R/c)² ε̇ (1 − cosθ).
        let p0 = long_bearing_pressure(&G, st(0.0, 2.0, 50.0), 2.0);
        let want = 12.0 * G.viscosity * (G.journal_radius / G.clearance).powi(2) * 2.0 * (1.0 - 2.0_f64.cos());
        assert!((p0 / want - 1.0).abs() < 1e-14);
    }

    #[test]
    fn force_matches_independent_simpson() {
        let mut worst = 0.0_f64;
        let mut worst_comp = 0.0_f64;
        let mut worst_q = 0.0_f64;
        for eps in [0.01, 0.05, 0.1, 0.2, 0.35, 0.5, 0.65, 0.8, 0.9, 0.95, 0.99] {
            for (w, ed) in motions() {
                let r = simpson_force(eps, ed, w);
                let f = long_bearing_force(&G, st(eps, ed, w));
                let q = long_bearing_force_quadrature(&G, st(eps, ed, w));
                let norm = r.0.hypot(r.1);
                if norm == 0.0 {
                    assert_eq!(f, (0.0, 0.0), "ε {eps} W {w} ε̇ {ed}");
                    assert_eq!(q, (0.0, 0.0));
                    continue;
                }
                let err = (f.0 - r.0).abs().max((f.1 - r.1).abs()) / norm;
                let err_q = (q.0 - r.0).abs().max((q.1 - r.1).abs()) / norm;
                worst = worst.max(err);
                worst_q = worst_q.max(err_q);
                for (a, b) in [(f.0, r.0), (f.1, r.1)] {
                    if b.abs() > 1e-2 * norm {
                        worst_comp = worst_comp.max((a - b).abs() / b.abs());
                    }
                }
                assert!(err < 1e-6, "ε {eps} W {w} ε̇ {ed}: closed {f:?} vs Simpson {r:?} (rel {err:.2e})");
                assert!(err_q < 1e-6, "ε {eps} W {w} ε̇ {ed}: GL {q:?} vs Simpson {r:?} (rel {err_q:.2e})");
            }
        }
        eprintln!("long bearing vs Simpson: max |ΔF|/|F| closed form {worst:.2e}, GL {worst_q:.2e}; max per-component rel (closed) {worst_comp:.2e}");
    }

    #[test]
    fn gauss_legendre_reference_matches_closed_form() {
        let mut worst = 0.0_f64;
        for eps in [0.0, 1e-300, 1e-12, 1e-6, 1e-3, 0.02, 0.1, 0.3, 0.6, 0.85, 0.97, 0.99, 0.995, 0.999] {
            for (w, ed) in motions() {
                let f = long_bearing_force(&G, st(eps, ed, w));
                let q = long_bearing_force_quadrature(&G, st(eps, ed, w));
                let norm = q.0.hypot(q.1);
                assert!(f.0.is_finite() && f.1.is_finite());
                if norm == 0.0 {
                    assert!(f.0.hypot(f.1) <= 1e-300);
                    continue;
                }
                let err = (f.0 - q.0).abs().max((f.1 - q.1).abs()) / norm;
                worst = worst.max(err);
                assert!(err < 1e-9, "ε {eps} W {w} ε̇ {ed}: {f:?} vs {q:?} ({err:.2e})");
            }
        }
        eprintln!("long bearing closed form vs graded GL: max rel {worst:.2e}");
    }

    #[test]
    fn half_sommerfeld_pure_rotation() {
        // Gümbel (half-Sommerfeld) long bearing, pure rotation (e.g. Pinkus & Sternlicht 1961;
        // Flores et al. 2006): p > 0 on (0, π),
        // F_ξ = −12 μ W R³ L ε² / (c² (2 + ε²)(1 − ε²)), F_η = 6π μ W R³ L ε / (c² (2 + ε²) √(1 − ε²)).
        for eps in [1e-4, 0.1, 0.5, 0.9, 0.99] {
            for w in [37.0, -37.0] {
                let f = long_bearing_force(&G, st(eps, 0.0, w));
                let fx = -2.0 * c0() * w.abs() * eps * eps / ((2.0 + eps * eps) * (1.0 - eps * eps));
                let fy = PI * c0() * w * eps / ((2.0 + eps * eps) * (1.0 - eps * eps).sqrt());
                assert!((f.0 / fx - 1.0).abs() < 1e-10, "ε {eps} W {w}: F_ξ {} vs {fx}", f.0);
                assert!((f.1 / fy - 1.0).abs() < 1e-12, "ε {eps} W {w}: F_η {} vs {fy}", f.1);
                // CCW rotation (W > 0) pushes along +t; the film always pulls towards the centre.
                assert!(f.0 < 0.0 && f.1 * w > 0.0);
            }
        }
    }

    #[test]
    fn pure_squeeze() {
        // Approaching (ε̇ > 0): p ≥ 0 on the whole film (zero only at θ = 0), full-film result
        // F_ξ = −12π μ R³ L ε̇ / (c² (1 − ε²)^{3/2}), F_η = 0.
        for eps in [0.0, 1e-9, 0.2, 0.7, 0.99] {
            let f = long_bearing_force(&G, st(eps, 3.0, 0.0));
            let want = -2.0 * PI * c0() * 3.0 / (1.0 - eps * eps).powf(1.5);
            assert!((f.0 / want - 1.0).abs() < 1e-12, "ε {eps}: {} vs {want}", f.0);
            assert!(f.1.abs() < 1e-12 * want.abs());
        }
        // Receding (ε̇ < 0, no wedge): (ε̇/ε)[1/v² − 1/(1+ε)²] ≤ 0 everywhere, so p⁺ ≡ 0 and the
        // Gümbel force is exactly zero (the paper's Eq. 14 gives a large force here).
        for eps in [0.0, 0.2, 0.7, 0.99] {
            assert_eq!(long_bearing_force(&G, st(eps, -3.0, 0.0)), (0.0, 0.0));
            let r = simpson_force(eps.max(1e-3), -3.0, 0.0);
            assert_eq!(r, (0.0, 0.0));
        }
        // Receding with a little wedge: a small positive arc near θ = 0 (thick side) whose
        // force is tiny and pushes the journal outward-and-along-t (F_ξ > 0).
        let f = long_bearing_force(&G, st(0.5, -3.0, 1.0));
        let r = simpson_force(0.5, -3.0, 1.0);
        assert!(f.0 > 0.0 && f.1 > 0.0, "{f:?}");
        assert!((f.0 - r.0).abs() < 1e-6 * r.0.hypot(r.1));
    }

    /// The cubic's root against plain bisection of H(φ) on (0, π) (120 halvings, no shortcut),
    /// over twelve decades of the wedge-to-squeeze ratio either way, both signs, ε from 0 to
    /// 1 − 1e-9: the same φ* (relative to its distance from the nearer end, 0 or π) and the
    /// arc end's sine and cosine consistent with θ.
    #[test]
    fn pressure_zero_from_the_cubic_matches_bisection() {
        let h = |eps: f64, a: f64, s: f64, phi: f64| {
            let (sp, cp) = phi.sin_cos();
            let c2 = cp * cp;
            a * cp * (2.0 - eps + 2.0 * eps * c2) + 2.0 * s * sp * (1.0 + eps * c2)
        };
        let mut checked = 0;
        for eps in [0.0, 1e-6, 0.3, 0.9, 0.999, 1.0 - 1e-9] {
            for la in -6..=6 {
                for ls in -6..=6 {
                    for (sa, ss) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
                        let (a, s) = (sa * 10f64.powi(2 * la), ss * 10f64.powi(2 * ls));
                        let x = wedge_squeeze_zero(eps, a, s);
                        let phi = 1.0_f64.atan2(x);
                        // Reference: bisection of sign(a)·H, positive at 0, negative at π.
                        let (mut lo, mut hi) = (0.0_f64, PI);
                        for _ in 0..120 {
                            let mid = 0.5 * (lo + hi);
                            if sa * h(eps, a, s, mid) > 0.0 {
                                lo = mid;
                            } else {
                                hi = mid;
                            }
                        }
                        let want = 0.5 * (lo + hi);
                        let dist = want.min(PI - want);
                        assert!((phi - want).abs() <= 1e-12 * dist + 1e-15, "ε {eps} a {a:e} s {s:e}: φ* {phi} vs {want}");
                        let end = ArcEnd::from_half_angle_cot(x);
                        assert!((end.sin - end.theta.sin()).abs() < 1e-14 && (end.cos - end.theta.cos()).abs() < 1e-14);
                        // 1 − cos θ = 2 sin²φ, with sin φ = sin(atan(1/|x|)) for |x| > 1 (precise
                        // where φ is near π, unlike θ itself).
                        let sin_phi = if x.abs() > 1.0 { (1.0 / x.abs()).atan().sin() } else { (0.5 * end.theta).sin() };
                        let omc = 2.0 * sin_phi * sin_phi;
                        assert!((end.one_minus_cos - omc).abs() <= 1e-14 * omc, "ε {eps} a {a:e} s {s:e}: 1 − cos θ");
                        checked += 1;
                    }
                }
            }
        }
        assert_eq!(checked, 6 * 13 * 13 * 4);
    }

    #[test]
    fn exact_zero_of_pressure() {
        for eps in [1e-6, 0.1, 0.5, 0.9, 0.99] {
            for (w, ed) in motions() {
                let Some((e1, e2)) = positive_arc(eps, ed, w) else { continue };
                let scale = long_bearing_pressure(&G, st(eps, ed.abs(), w.abs()), PI * 0.9).abs().max(1.0);
                for e in [e1, e2] {
                    let p = long_bearing_pressure(&G, st(eps, ed, w), e.theta);
                    assert!(p.abs() < 1e-9 * scale, "ε {eps} W {w} ε̇ {ed}: p(θ* = {}) = {p}", e.theta);
                    assert!((e.sin - e.theta.sin()).abs() < 1e-14 && (e.cos - e.theta.cos()).abs() < 1e-14);
                }
                for i in 1..200 {
                    let th = TAU * i as f64 / 200.0;
                    let p = long_bearing_pressure(&G, st(eps, ed, w), th);
                    let inside = th > e1.theta && th < e2.theta;
                    let margin = 1e-9 * scale;
                    assert!(if inside { p > -margin } else { p < margin }, "ε {eps} W {w} ε̇ {ed}: θ {th} p {p} arc ({}, {})", e1.theta, e2.theta);
                }
            }
        }
    }

    #[test]
    fn continuous_through_zero_rates() {
        for eps in [0.0, 0.3, 0.95] {
            let base = long_bearing_force(&G, st(eps, 0.0, 50.0));
            for ed in [1e-9, -1e-9] {
                let f = long_bearing_force(&G, st(eps, ed, 50.0));
                let n = base.0.hypot(base.1).max(1e-30);
                assert!((f.0 - base.0).abs() + (f.1 - base.1).abs() < 1e-6 * n + 100.0 * c0() * ed.abs(), "ε {eps} ε̇ {ed}");
            }
            let base = long_bearing_force(&G, st(eps, 2.0, 0.0));
            for w in [1e-9, -1e-9] {
                let f = long_bearing_force(&G, st(eps, 2.0, w));
                let n = base.0.hypot(base.1);
                assert!((f.0 - base.0).abs() + (f.1 - base.1).abs() < 1e-6 * n, "ε {eps} W {w}: {f:?} vs {base:?}");
            }
        }
    }

    #[test]
    fn paper_closed_form_discrepancy() {
        // Pure rotation (ε̇ = 0, k → ∞ limit): Eq. 13 reduces to the half-Sommerfeld result.
        for eps in [0.1, 0.5, 0.9] {
            let p = long_bearing_paper_closed_form(&G, st(eps, 0.0, 40.0));
            let f = long_bearing_force(&G, st(eps, 0.0, 40.0));
            assert!((p.0 / f.0 - 1.0).abs() < 1e-12 && (p.1 / f.1 - 1.0).abs() < 1e-12, "{p:?} {f:?}");
        }
        // ε̇ > 0: report the discrepancy against the exact Gümbel integral, tabulated by the
        // squeeze-to-wedge ratio of the two pressure terms, q = (ε̇/ε) / (Wε/(2 + ε²)).
        eprintln!("paper Eq. 13 vs exact Gümbel integral, ε̇ > 0: |ΔF|/|F| by q = ε̇(2+ε²)/(ε² W)");
        let ratios = [0.001, 0.01, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0, 100.0];
        eprintln!("   q:    {}", ratios.iter().map(|q| format!("{q:8}")).collect::<String>());
        let mut small_q = 0.0_f64;
        let (mut large_min, mut large_max) = (f64::INFINITY, 0.0_f64);
        for eps in [0.1, 0.3, 0.5, 0.7, 0.9] {
            let mut line = format!("  ε {eps:.1}:");
            for q in ratios {
                let w = 100.0;
                let s = st(eps, q * w * eps * eps / (2.0 + eps * eps), w);
                let p = long_bearing_paper_closed_form(&G, s);
                let f = long_bearing_force(&G, s);
                let err = (p.0 - f.0).hypot(p.1 - f.1) / f.0.hypot(f.1);
                line += &format!(" {err:8.2e}");
                if q <= 0.01 {
                    small_q = small_q.max(err);
                }
                if q >= 3.0 {
                    large_min = large_min.min(err);
                    large_max = large_max.max(err);
                }
            }
            eprintln!("{line}");
        }
        eprintln!("  q ≤ 0.01: worst {small_q:.4}; q ≥ 3: from {large_min:.4} to {large_max:.4}");
        assert!(small_q < 0.02, "paper form should agree within 2 % at small squeeze ratio");
        assert!(large_min > 0.02 && large_max > 0.2, "paper form disagrees at large squeeze ratio");
        // ε̇ < 0: sign of F_ξ and the pure receding artefact.
        let s = st(0.5, -100.0, 100.0);
        let (p, f) = (long_bearing_paper_closed_form(&G, s), long_bearing_force(&G, s));
        eprintln!("  ε 0.5, ε̇/W = −1: paper {p:?}, Gümbel {f:?}");
        let s = st(0.5, -10.0, 0.0);
        let (p, f) = (long_bearing_paper_closed_form(&G, s), long_bearing_force(&G, s));
        eprintln!("  ε 0.5, pure receding ε̇ = −10: paper {p:?}, Gümbel {f:?}");
        assert_eq!(f, (0.0, 0.0));
        // The printed Eq. 14 pulls a receding journal back towards the centre (F_ξ < 0) with a
        // force of the size of an approaching squeeze; the Gümbel integral is exactly zero.
        assert!(p.0 < 0.0 && p.0.abs() > 1.0, "paper: {p:?}");
        let s = st(0.5, -100.0, 100.0);
        let (p, f) = (long_bearing_paper_closed_form(&G, s), long_bearing_force(&G, s));
        assert!(p.0 < 0.0 && f.0 > 0.0, "sign of F_ξ for ε̇ < 0: paper {p:?}, Gümbel {f:?}");
    }
}
