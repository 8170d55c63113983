//! The oil temperature of a lubricated joint along a run (docs/physics.md §4, *Heat*): one
//! effective temperature per joint, `C dT/dt = P_loss − hA (T − T_ambient)`
//! ([`crate::laws::viscosity::Thermal`]), the film evaluated at μ(T) (Vogel's law).
//!
//! The temperature is a slow state (C/hA is seconds to minutes, a step micro- to milliseconds),
//! so it is advanced once per accepted step, as the wear books are (rust/clearance/wear.rs),
//! and the step is integrated at the viscosity μ(T₀) of its start. Over the step the power loss
//! is its mean P̄ (Simpson's rule over the step's start, middle and end) plus its change with
//! the temperature, linearised about T₀: a film's loss at a given motion is ∝ μ, so
//! `P(T) ≈ P̄ + P_T (T − T₀)` with `P_T = P̄ μ'(T₀)/μ(T₀) = −P̄ b/(T₀ − c)² ≤ 0` (0 at a constant
//! viscosity). The balance is then linear in T and integrated exactly:
//! `T₁ = T_∞ + (T₀ − T_∞) exp(−h (hA − P_T)/C)`, `T_∞ = T₀ + (P̄ − hA (T₀ − T_ambient))/(hA − P_T)`.
//! This is unconditionally stable, exact for a constant power, and its fixed point is that of
//! `T = T_ambient + P_loss(μ(T))/hA` exactly (at T₁ = T₀: P̄ = hA (T₀ − T_ambient)), whatever the
//! step; a step far longer than C/hA (a mechanism at rest or turning steadily) is a Newton step
//! towards it. The error of a transient is first order in h/τ (τ = C/hA): the motion inside the
//! step does not see the temperature change over it.

use crate::laws::viscosity::{Thermal, Vogel};

/// The thermal model of one lubricated joint: its balance and, if the viscosity follows the
/// temperature, its Vogel law (else the film keeps its constant viscosity).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Heat {
    pub vogel: Option<Vogel>,
    pub thermal: Thermal,
}

/// The temperature of one joint along the run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeatBook {
    pub heat: Heat,
    /// Temperature \[K\] at the end of the last accepted step.
    pub temperature: f64,
    /// The last step: its start t₀ \[s\], T₀ \[K\], T_∞ \[K\] and (hA − P_T)/C \[1/s\] (for the
    /// outputs inside it).
    t0: f64,
    temperature0: f64,
    target: f64,
    rate: f64,
}

impl HeatBook {
    pub fn new(heat: Heat) -> Self {
        let t = heat.thermal.initial;
        HeatBook { heat, temperature: t, t0: f64::NEG_INFINITY, temperature0: t, target: t, rate: 0.0 }
    }

    /// The viscosity \[Pa s\] the next step is integrated with (`None`: the film's own constant).
    pub fn viscosity(&self) -> Option<f64> {
        self.heat.vogel.map(|v| v.viscosity(self.temperature))
    }

    /// The start of the run `t` \[s\].
    pub fn start(&mut self, t: f64) {
        self.t0 = t;
    }

    /// Close the accepted step (t0, t1] with the power loss \[W\] at its start, middle and end
    /// (all at the viscosity the step was integrated with); the new temperature, or `Err(T)` if it
    /// left the Vogel law's range (T ≤ c) or is not finite.
    pub fn step(&mut self, t0: f64, t1: f64, p_start: f64, p_mid: f64, p_end: f64) -> Result<f64, f64> {
        let th = &self.heat.thermal;
        let t_start = self.temperature;
        let mean = (p_start + 4.0 * p_mid + p_end) / 6.0;
        // dP/dT through the viscosity, a film's loss being ∝ μ (module doc); ≤ 0.
        let p_t = self.heat.vogel.map_or(0.0, |v| -mean.max(0.0) * v.b / ((t_start - v.c) * (t_start - v.c)));
        let cooling = th.heat_transfer - p_t;
        let target = t_start + (mean - th.heat_transfer * (t_start - th.ambient)) / cooling;
        let rate = cooling / th.heat_capacity;
        let t_new = target + (t_start - target) * (-(t1 - t0) * rate).exp();
        self.t0 = t0;
        self.temperature0 = t_start;
        self.target = target;
        self.rate = rate;
        self.temperature = t_new;
        match self.heat.vogel {
            Some(v) if !v.holds_at(t_new) => Err(t_new),
            _ if !t_new.is_finite() => Err(t_new),
            _ => Ok(t_new),
        }
    }

    /// The temperature \[K\] at `t` inside the last step (the same exact exponential), or at the
    /// start of the run.
    pub fn temperature_at(&self, t: f64) -> f64 {
        if t <= self.t0 {
            return self.temperature0;
        }
        self.target + (self.temperature0 - self.target) * (-(t - self.t0) * self.rate).exp()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Constant power: the exact solution T = T_∞ + (T₀ − T_∞) e^{−t/τ}, whatever the steps.
    #[test]
    fn constant_power_follows_the_exponential_exactly() {
        let thermal = Thermal { ambient: 300.0, heat_capacity: 50.0, heat_transfer: 2.0, initial: 310.0 };
        let mut b = HeatBook::new(Heat { vogel: None, thermal });
        b.start(0.0);
        let mut t = 0.0;
        for h in [0.3, 1e-3, 7.0, 2.5, 0.01, 12.0] {
            b.step(t, t + h, 40.0, 40.0, 40.0).unwrap();
            t += h;
            let exact = 320.0 + (310.0 - 320.0) * (-t / 25.0f64).exp();
            assert!((b.temperature - exact).abs() < 1e-11, "{t}: {} vs {exact}", b.temperature);
        }
        let mid = b.temperature_at(t - 6.0);
        assert!((mid - (320.0 - 10.0 * (-(t - 6.0) / 25.0f64).exp())).abs() < 1e-11);
    }

    /// Steps far longer than C/hA with a Petroff-like loss P = k μ(T): the temperature goes to
    /// the balance's fixed point ([`crate::laws::viscosity::steady_temperature`]) without
    /// oscillating, and stays there.
    #[test]
    fn long_steps_converge_to_the_fixed_point() {
        let vogel = Vogel { a: 6.4e-5, b: 900.0, c: 164.0 };
        let thermal = Thermal { ambient: 313.15, heat_capacity: 0.01, heat_transfer: 0.05, initial: 313.15 };
        let k = 125.66;
        let fixed = crate::laws::viscosity::steady_temperature(&vogel, &thermal, |mu| k * mu).unwrap();
        let mut b = HeatBook::new(Heat { vogel: Some(vogel), thermal });
        b.start(0.0);
        let mut errors = Vec::new();
        for n in 0..12 {
            let p = k * b.viscosity().unwrap();
            b.step(n as f64, n as f64 + 1.0, p, p, p).unwrap();
            errors.push(b.temperature - fixed);
        }
        assert!(errors.windows(2).all(|w| w[1].abs() <= w[0].abs()), "{errors:?}");
        assert!(errors.last().unwrap().abs() < 1e-9 * fixed, "{errors:?}");
    }

    #[test]
    fn falling_to_the_vogel_limit_is_an_error() {
        let thermal = Thermal { ambient: 150.0, heat_capacity: 1.0, heat_transfer: 1.0, initial: 300.0 };
        let vogel = Vogel { a: 6.4e-5, b: 900.0, c: 164.0 };
        let mut b = HeatBook::new(Heat { vogel: Some(vogel), thermal });
        b.start(0.0);
        assert!(b.step(0.0, 10.0, 0.0, 0.0, 0.0).is_err());
    }
}
