//! The oil temperature of a lubricated joint (docs/physics.md §4, *Heat*): one effective
//! temperature T per joint with a heat model, a state of the run integrated with the mechanism,
//! `C dT/dt = P_loss − hA (T − T_ambient)` ([`crate::laws::viscosity::Thermal`]), the film
//! evaluated at μ(T) (Vogel's law) at every right-hand side.
//!
//! The state is y = (q, q̇, T₁ … T_k): the temperatures after the mechanism's coordinates, in
//! the order of the clearance joints that model heat ([`Heat::state`]); a model without them has
//! y = (q, q̇). The film's viscosity travels to the force laws in the joint's
//! [`ImpactMemory::viscosity`], set from the state for each evaluation ([`Heat::memory_at`]).

use super::{ClearanceJoint, ImpactMemory};
use crate::laws::viscosity::{Thermal, Vogel};

/// The thermal model of one lubricated joint: its balance, its Vogel law if the viscosity
/// follows the temperature (else the film keeps its constant viscosity), and where its
/// temperature sits in the state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Heat {
    pub vogel: Option<Vogel>,
    pub thermal: Thermal,
    /// Index of the joint's oil temperature \[K\] in the state y = (q, q̇, T…).
    pub state: usize,
}

impl Heat {
    /// Whether the joint's laws hold at the oil temperature `t` \[K\]: finite and, with a Vogel
    /// law, above its c.
    #[inline]
    pub fn holds_at(&self, t: f64) -> bool {
        t.is_finite() && self.vogel.is_none_or(|v| v.holds_at(t))
    }

    /// The joint's memory at oil temperature `t` \[K\]: with the viscosity μ(T) when it follows the
    /// temperature, else unchanged.
    #[inline]
    pub fn memory_at(&self, memory: &ImpactMemory, t: f64) -> ImpactMemory {
        match self.vogel {
            Some(v) => ImpactMemory { viscosity: v.viscosity(t), ..*memory },
            None => *memory,
        }
    }

    /// dT/dt \[K/s\] at the oil temperature `t` \[K\] and the joint's power loss `p_loss` \[W\].
    #[inline]
    pub fn rate(&self, t: f64, p_loss: f64) -> f64 {
        self.thermal.temperature_rate(t, p_loss)
    }

    /// Why the run cannot go on at oil temperature `t` (for errors): the joint and the limit.
    pub fn out_of_range(&self, joint: &str, t: f64) -> String {
        let c = self.vogel.map_or(f64::NAN, |v| v.c);
        format!("; clearance joint '{joint}': oil temperature {t} K at or below the Vogel law's c = {c} K (thermal)")
    }
}

impl ClearanceJoint {
    /// The joint's heat model, if it has one.
    #[inline]
    pub fn heat(&self) -> Option<&Heat> {
        self.film.as_ref().and_then(|f| f.heat.as_ref())
    }

    /// The joint's memory at the state `y`: with the viscosity of y's oil temperature when the
    /// joint has one that the film follows, else `memory` itself.
    #[inline]
    pub fn memory_at(&self, memory: &ImpactMemory, y: &[f64]) -> ImpactMemory {
        match self.heat() {
            Some(h) => h.memory_at(memory, y[h.state]),
            None => *memory,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_viscosity_follows_the_state() {
        let thermal = Thermal { ambient: 300.0, heat_capacity: 50.0, heat_transfer: 2.0, initial: 310.0 };
        let vogel = Vogel { a: 6.4e-5, b: 900.0, c: 164.0 };
        let h = Heat { vogel: Some(vogel), thermal, state: 3 };
        let m = ImpactMemory { wear_offset: 1e-6, ..ImpactMemory::default() };
        let at = h.memory_at(&m, 330.0);
        assert_eq!(at.viscosity, vogel.viscosity(330.0));
        assert_eq!(at.wear_offset, 1e-6);
        assert!(h.holds_at(170.0) && !h.holds_at(164.0) && !h.holds_at(f64::NAN));
        // A constant viscosity: the memory as it was (0: the film's own), any temperature holds.
        let plain = Heat { vogel: None, ..h };
        assert_eq!(plain.memory_at(&m, 330.0), m);
        assert!(plain.holds_at(100.0));
        assert_eq!(h.rate(300.0, 40.0), 0.8);
    }
}
