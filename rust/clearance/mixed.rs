//! Mixed lubrication of a rough journal bearing (docs/physics.md §4, "Roughness and mixed
//! lubrication"): where the film is thinner than 4σ the asperities carry load (Greenwood–Tripp,
//! [`crate::laws::asperity`]) with the boundary friction μ_b on it. Given roughness, this replaces
//! the paper's linear film-to-contact band (P18): the film acts at every eccentricity (at
//! min(ε, ε_max)), the asperities add their load, and the dry law acts only where the mean
//! surfaces overlap (e > c). Without roughness none of this runs.

use crate::laws::asperity::GreenwoodTripp;
use crate::laws::film::BearingGeometry;
use crate::laws::friction::ModifiedCoulomb;

/// The rough surfaces of a lubricated joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mixed {
    /// Greenwood–Tripp parameters (σ, σηβ, σ/β, E').
    pub asperity: GreenwoodTripp,
    /// Boundary friction: the modified Coulomb law (P5) with μ_b, ramped up from slip 0 to
    /// [`BOUNDARY_SLIP`] (or the joint's `boundary_slip`): [`boundary_friction`].
    pub friction: ModifiedCoulomb,
}

/// Default slip speed [m/s] over which the boundary friction rises from 0 to μ_b. The dry law's
/// ramp (v0 = 1e-4, v1 = 1e-2 m/s) is a regularisation of impacts; on the asperities of a slowly
/// turning journal it made the friction fall to zero at standstill (a journal of R = 20 mm
/// slipping at 3 mm/s, 0.3 of v1, read f = 0.028 for μ_b = 0.1 on 94 % of the load, where the
/// boundary regime means f → μ_b × (asperity share) = 0.094). Below 1e-4 m/s the ramp is a
/// regularisation only: the Stribeck curve's low-speed end keeps its limit.
pub const BOUNDARY_SLIP: f64 = 1e-4;

/// The boundary friction law of a rough joint: μ_b on the asperity load, its correction
/// rising linearly from 0 at zero slip to 1 at `slip` [m/s] (default [`BOUNDARY_SLIP`]).
pub fn boundary_friction(mu_b: f64, slip: Option<f64>) -> ModifiedCoulomb {
    ModifiedCoulomb { friction_coefficient: mu_b, v0: 0.0, v1: slip.unwrap_or(BOUNDARY_SLIP) }
}

impl Mixed {
    /// The asperities' load \[N\] (≥ 0, pressing the journal back towards the centre, along −n)
    /// at eccentricity ratio `eps` and its friction force along t \[N\] at the contact slip `slip`
    /// [m/s]: `(F_a, F_t)`; (0, 0) while the thinnest gap is at least 4σ.
    #[inline]
    pub fn force(&self, g: &BearingGeometry, eps: f64, slip: f64) -> (f64, f64) {
        let (xi, _) = self.asperity.force(g, eps);
        let load = -xi;
        if load > 0.0 {
            (load, self.friction.tangential_force(load, slip))
        } else {
            (0.0, 0.0)
        }
    }

    /// The eccentricity ratio above which the asperities touch: 1 − 4σ/c.
    pub fn onset(&self, clearance: f64) -> f64 {
        1.0 - 4.0 * self.asperity.roughness / clearance
    }
}

/// The composite modulus E' \[Pa\] of Hertz's law, 1/E' = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂.
pub fn composite_modulus(e1: f64, nu1: f64, e2: f64, nu2: f64) -> f64 {
    1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn load_starts_at_four_sigma_and_friction_opposes_the_slip() {
        let g = BearingGeometry { viscosity: 0.05, journal_radius: 0.02, clearance: 4e-5, length: 0.04 };
        let e = composite_modulus(207e9, 0.3, 207e9, 0.3);
        assert!((e - 207e9 / (2.0 * 0.91)).abs() < 1e-3 * e);
        let m = Mixed { asperity: GreenwoodTripp::typical(1e-6, e), friction: boundary_friction(0.12, None) };
        assert!((m.onset(g.clearance) - 0.9).abs() < 1e-12);
        assert_eq!(m.force(&g, 0.899, 1.0), (0.0, 0.0));
        let (a, t) = m.force(&g, 0.95, 1.0);
        assert!(a > 0.0 && (t + 0.12 * a).abs() < 1e-12 * a, "{a} {t}");
        let (a2, t2) = m.force(&g, 0.95, -1.0);
        assert_eq!((a2, t2), (a, -t));
        assert!(m.force(&g, 0.99, 0.0).0 > a);
        // The boundary regime reaches μ_b at slips of 0.1 mm/s, not at the dry law's 1 cm/s: a
        // journal slipping at 3 mm/s reads μ_b (it read 0.29 μ_b on the dry ramp).
        let (a3, t3) = m.force(&g, 0.95, 3e-3);
        assert!((t3 + 0.12 * a3).abs() < 1e-12 * a3, "{t3} vs {}", -0.12 * a3);
        let (a4, t4) = m.force(&g, 0.95, 0.5 * BOUNDARY_SLIP);
        assert!((t4 + 0.06 * a4).abs() < 1e-12 * a4);
    }
}
