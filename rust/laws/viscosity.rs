//! The oil's viscosity as a function of temperature (Vogel's law) and the effective-temperature
//! energy balance of a lubricated joint (docs/physics.md §4, heat).
//!
//! - Vogel (1921): `μ(T) = a exp(b/(T − c))`, T in kelvin, valid for T > c; a \[Pa s\], b, c \[K\].
//!   [`Vogel::through`] fits the three constants exactly through three measured (T, μ) points.
//! - Energy balance of one joint with an effective oil temperature T (a lumped, isothermal film):
//!   `C dT/dt = P_loss − hA (T − T_ambient)`, C the heat capacity of the oil and the parts that
//!   follow its temperature \[J/K\], hA the heat transfer to the ambient \[W/K\], P_loss the film's
//!   power loss \[W\] ([`super::film_friction`]) at μ(T). Its steady state solves
//!   `T = T_ambient + P_loss(μ(T))/hA`: [`steady_temperature`].

/// Vogel's viscosity law μ = a exp(b/(T − c)) (module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vogel {
    /// a \[Pa s\] (> 0): the viscosity as T → ∞.
    pub a: f64,
    /// b \[K\] (≥ 0).
    pub b: f64,
    /// c \[K\]: the law holds for T > c.
    pub c: f64,
}

impl Vogel {
    /// The law, or the name of the first constant out of range and why.
    pub fn new(a: f64, b: f64, c: f64) -> Result<Self, (&'static str, &'static str)> {
        if !(a.is_finite() && a > 0.0) {
            return Err(("a", "must be a positive viscosity [Pa s]"));
        }
        if !(b.is_finite() && b >= 0.0) {
            return Err(("b", "must be finite and not negative [K] (the viscosity falls with temperature)"));
        }
        if !(c.is_finite() && c < 1000.0) {
            return Err(("c", "must be a finite temperature [K] below the oil's"));
        }
        Ok(Vogel { a, b, c })
    }

    /// The law through three points (T₁, μ₁), (T₂, μ₂), (T₃, μ₃) with T₁ < T₂ < T₃ [K, Pa s] and μ
    /// falling: with r = ln(μ₁/μ₂)/ln(μ₂/μ₃), `c = ((T₂ − T₁) T₃ − r (T₃ − T₂) T₁)/((T₂ − T₁) − r (T₃ − T₂))`,
    /// then b and a from two of the points. `None` when no Vogel law passes through them.
    pub fn through(points: [(f64, f64); 3]) -> Option<Self> {
        let [(t1, m1), (t2, m2), (t3, m3)] = points;
        if !(t1 < t2 && t2 < t3 && m1 > m2 && m2 > m3 && m3 > 0.0) {
            return None;
        }
        let r = (m1 / m2).ln() / (m2 / m3).ln();
        let den = (t2 - t1) - r * (t3 - t2);
        if den == 0.0 {
            return None;
        }
        let c = ((t2 - t1) * t3 - r * (t3 - t2) * t1) / den;
        if c.is_nan() || c >= t1 {
            return None;
        }
        let b = (m1 / m2).ln() / (1.0 / (t1 - c) - 1.0 / (t2 - c));
        let a = m1 * (-b / (t1 - c)).exp();
        Vogel::new(a, b, c).ok()
    }

    /// Whether the law holds at `t` \[K\] (T > c, finite).
    pub fn holds_at(&self, t: f64) -> bool {
        t.is_finite() && t > self.c
    }

    /// μ(T) [Pa s]; NaN where the law does not hold (T ≤ c): callers check [`Self::holds_at`].
    pub fn viscosity(&self, t: f64) -> f64 {
        if !self.holds_at(t) {
            return f64::NAN;
        }
        self.a * (self.b / (t - self.c)).exp()
    }

    /// dμ/dT = −μ b/(T − c)² [Pa s/K] (for the implicit methods' Newton matrix).
    pub fn derivative(&self, t: f64) -> f64 {
        let d = t - self.c;
        -self.viscosity(t) * self.b / (d * d)
    }
}

/// The lumped heat balance of one joint (module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Thermal {
    /// Ambient temperature \[K\].
    pub ambient: f64,
    /// Heat capacity C \[J/K\] (> 0).
    pub heat_capacity: f64,
    /// Heat transfer coefficient times area, hA \[W/K\] (> 0).
    pub heat_transfer: f64,
    /// Temperature at the start of the run \[K\].
    pub initial: f64,
}

impl Thermal {
    /// dT/dt \[K/s\] = (P_loss − hA (T − T_ambient))/C at the oil temperature `t` \[K\] and the power
    /// loss `p_loss` \[W\].
    pub fn temperature_rate(&self, t: f64, p_loss: f64) -> f64 {
        (p_loss - self.heat_transfer * (t - self.ambient)) / self.heat_capacity
    }
}

/// The steady oil temperature \[K\]: the root of `g(T) = T − T_amb − P_loss(μ(T))/hA`, for a power
/// loss `p_loss(μ)` \[W\] that does not fall as the viscosity rises (a film's loss at a given
/// motion grows with μ), so that g increases and the root is unique; it lies between T_amb (where
/// g ≤ 0) and T_amb + P_loss(μ(T_amb))/hA (where g ≥ 0). Found by the Illinois variant of regula
/// falsi on that bracket, to 1e-12 K relative. `None` if the law does not hold at T_amb or the
/// power loss is not finite.
pub fn steady_temperature(vogel: &Vogel, thermal: &Thermal, p_loss: impl Fn(f64) -> f64) -> Option<f64> {
    let t_amb = thermal.ambient;
    if !vogel.holds_at(t_amb) {
        return None;
    }
    let g = |t: f64| t - t_amb - p_loss(vogel.viscosity(t)) / thermal.heat_transfer;
    let (mut lo, mut hi) = (t_amb, t_amb + p_loss(vogel.viscosity(t_amb)) / thermal.heat_transfer);
    if !hi.is_finite() {
        return None;
    }
    let (mut g_lo, mut g_hi) = (g(lo), g(hi));
    if g_lo >= 0.0 {
        return Some(lo);
    }
    if g_hi <= 0.0 {
        return Some(hi);
    }
    let mut side = 0i8;
    for _ in 0..200 {
        let t = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
        let gt = g(t);
        if gt == 0.0 || (hi - lo) <= 1e-12 * hi {
            return Some(t);
        }
        if gt < 0.0 {
            lo = t;
            g_lo = gt;
            if side == -1 {
                g_hi *= 0.5;
            }
            side = -1;
        } else {
            hi = t;
            g_hi = gt;
            if side == 1 {
                g_lo *= 0.5;
            }
            side = 1;
        }
    }
    Some(0.5 * (lo + hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    // An illustrative oil of ISO VG 32 grade: a = 6.4e-5 Pa s, b = 900 K, c = 164 K gives
    // μ(40 °C) = 0.0267 Pa s and μ(100 °C) = 0.00473 Pa s.
    const OIL: Vogel = Vogel { a: 6.4e-5, b: 900.0, c: 164.0 };

    #[test]
    fn hand_values_and_checks() {
        let mu = OIL.viscosity(313.15);
        assert!((mu / (6.4e-5 * (900.0f64 / 149.15).exp()) - 1.0).abs() < 1e-15);
        assert!((mu - 0.02672).abs() < 1e-5, "{mu}");
        assert!(OIL.viscosity(164.0).is_nan() && !OIL.holds_at(100.0));
        let h = 1e-4;
        let fd = (OIL.viscosity(330.0 + h) - OIL.viscosity(330.0 - h)) / (2.0 * h);
        assert!((OIL.derivative(330.0) / fd - 1.0).abs() < 1e-7);
        assert_eq!(Vogel::new(-1.0, 900.0, 164.0).unwrap_err().0, "a");
        assert_eq!(Vogel::new(1e-4, -1.0, 164.0).unwrap_err().0, "b");
        assert_eq!(Vogel::new(1e-4, 900.0, f64::NAN).unwrap_err().0, "c");
    }

    #[test]
    fn three_points_give_the_law_back() {
        let pts = [313.15, 343.15, 373.15].map(|t| (t, OIL.viscosity(t)));
        let v = Vogel::through(pts).unwrap();
        assert!((v.a / OIL.a - 1.0).abs() < 1e-9 && (v.b / OIL.b - 1.0).abs() < 1e-9 && (v.c / OIL.c - 1.0).abs() < 1e-9, "{v:?}");
        assert!(Vogel::through([(313.0, 0.01), (343.0, 0.02), (373.0, 0.005)]).is_none());
    }

    #[test]
    fn heat_balance_rate() {
        let th = Thermal { ambient: 293.15, heat_capacity: 500.0, heat_transfer: 2.0, initial: 293.15 };
        assert_eq!(th.temperature_rate(293.15, 100.0), 0.2);
        assert_eq!(th.temperature_rate(343.15, 100.0), 0.0);
    }

    /// The fixed point of a Petroff-loaded bearing, P = k μ: the law's solver against a plain
    /// bisection of T − T_amb − k μ(T)/hA.
    #[test]
    fn steady_temperature_matches_bisection() {
        for (k, ha) in [(2000.0, 2.0), (2.0e4, 2.0), (1.0e5, 0.5), (10.0, 5.0), (0.0, 1.0)] {
            let th = Thermal { ambient: 293.15, heat_capacity: 500.0, heat_transfer: ha, initial: 293.15 };
            let t = steady_temperature(&OIL, &th, |mu| k * mu).unwrap();
            let g = |t: f64| t - 293.15 - k * OIL.viscosity(t) / ha;
            let (mut lo, mut hi) = (293.15, 2000.0);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if g(mid) < 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            assert!((t - lo).abs() < 1e-9 * lo, "k {k}, hA {ha}: {t} vs {lo}");
            assert!(th.temperature_rate(t, k * OIL.viscosity(t)).abs() < 1e-9);
        }
        let cold = Thermal { ambient: 150.0, heat_capacity: 1.0, heat_transfer: 1.0, initial: 150.0 };
        assert!(steady_temperature(&OIL, &cold, |mu| mu).is_none());
    }
}
