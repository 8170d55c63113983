//! Modified Coulomb friction of a dry clearance joint (docs/physics.md §3, paper Eq. 5).

/// Coulomb friction with a dynamic correction `c_d` that ramps the friction up from 0 at small
/// slip speeds (avoids the discontinuity at `v_t = 0`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModifiedCoulomb {
    /// Coulomb coefficient `c_f`.
    pub friction_coefficient: f64,
    /// Slip speed [m/s] below which there is no friction.
    pub v0: f64,
    /// Slip speed [m/s] above which the full Coulomb friction acts (`v1 > v0`).
    pub v1: f64,
}

impl ModifiedCoulomb {
    /// Dynamic correction `c_d`: 0 for `|v| ≤ v0`, `(|v| − v0)/(v1 − v0)` for `v0 < |v| < v1`,
    /// 1 for `|v| ≥ v1`. If `v1 ≤ v0` it is a step at `v0` (no division by zero).
    pub fn dynamic_correction(&self, slip_speed: f64) -> f64 {
        let v = slip_speed.abs();
        if v.is_nan() || v <= self.v0 {
            0.0
        } else if v >= self.v1 {
            1.0
        } else {
            ((v - self.v0) / (self.v1 - self.v0)).clamp(0.0, 1.0)
        }
    }

    /// Tangential friction force \[N\] along the tangent `t`, given the normal force magnitude
    /// `F_N` \[N\] and the tangential slip velocity `v_t` [m/s] (relative velocity along `t` of the
    /// body the force acts on): `F_t = −c_f c_d F_N sign(v_t)`; 0 at `v_t = 0`.
    pub fn tangential_force(&self, normal_force: f64, slip_velocity: f64) -> f64 {
        if slip_velocity == 0.0 || slip_velocity.is_nan() {
            return 0.0;
        }
        -self.friction_coefficient * self.dynamic_correction(slip_velocity) * normal_force * slip_velocity.signum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const F: ModifiedCoulomb = ModifiedCoulomb { friction_coefficient: 0.1, v0: 1e-4, v1: 1e-2 };

    #[test]
    fn correction_piecewise_values() {
        assert_eq!(F.dynamic_correction(0.0), 0.0);
        assert_eq!(F.dynamic_correction(5e-5), 0.0);
        assert_eq!(F.dynamic_correction(-1e-4), 0.0);
        // Midpoint: (5.05e-3 − 1e-4)/(9.9e-3) = 0.5.
        assert!((F.dynamic_correction(5.05e-3) - 0.5).abs() < 1e-12);
        assert!((F.dynamic_correction(-5.05e-3) - 0.5).abs() < 1e-12);
        assert_eq!(F.dynamic_correction(1e-2), 1.0);
        assert_eq!(F.dynamic_correction(3.0), 1.0);
    }

    #[test]
    fn correction_continuous_at_v0_and_v1() {
        let h = 1e-12;
        for v in [F.v0, F.v1] {
            let (lo, hi) = (F.dynamic_correction(v - h), F.dynamic_correction(v + h));
            assert!((hi - lo).abs() < 1e-8, "jump at {v}: {lo} → {hi}");
        }
    }

    #[test]
    fn tangential_force_sign_and_magnitude() {
        // Full sliding: |F_t| = c_f F_N = 0.1·100 = 10 N, opposing the slip.
        assert!((F.tangential_force(100.0, 1.0) + 10.0).abs() < 1e-12);
        assert!((F.tangential_force(100.0, -1.0) - 10.0).abs() < 1e-12);
        assert_eq!(F.tangential_force(100.0, 0.0), 0.0);
        assert_eq!(F.tangential_force(100.0, -0.0), 0.0);
        assert_eq!(F.tangential_force(100.0, 1e-5), 0.0);
        // Half-way: −0.1·0.5·100 = −5 N.
        assert!((F.tangential_force(100.0, 5.05e-3) + 5.0).abs() < 1e-9);
        // Degenerate ramp v1 = v0: a step, finite.
        let s = ModifiedCoulomb { friction_coefficient: 0.1, v0: 1e-3, v1: 1e-3 };
        assert_eq!(s.dynamic_correction(1e-3), 0.0);
        assert_eq!(s.dynamic_correction(1.0001e-3), 1.0);
    }
}
