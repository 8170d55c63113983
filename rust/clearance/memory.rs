//! The impact memory of a dry contact: δ̇⁽⁻⁾, the approach speed at the start of the current
//! impact (docs/physics.md §3, P3). It is changed only between accepted steps, never by trial stages.

/// Per-joint impact state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactMemory {
    /// True between a located contact onset and the following separation.
    pub in_contact: bool,
    /// δ̇⁽⁻⁾ [m/s] recorded at the onset (meaningful while `in_contact`).
    pub impact_speed: f64,
    /// Number of impacts located so far.
    pub impacts: u64,
    /// Worn depth \[m\] at the contact direction, added to the clearance of the contact law when
    /// the joint's wear is fed back (updated after every accepted step; docs/physics.md §12).
    pub wear_offset: f64,
    /// The film's viscosity \[Pa s\] when it follows the joint's oil temperature (updated after
    /// every accepted step, rust/clearance/thermal.rs); 0: the film's constant viscosity.
    pub viscosity: f64,
}

impl Default for ImpactMemory {
    fn default() -> Self {
        ImpactMemory { in_contact: false, impact_speed: 0.0, impacts: 0, wear_offset: 0.0, viscosity: 0.0 }
    }
}

impl ImpactMemory {
    /// δ̇⁽⁻⁾ to use in a force evaluation: the recorded one during a located impact; in a trial
    /// stage that has penetrated before the onset is located, the current approach speed
    /// (the law floors it).
    #[inline]
    pub fn impact_speed_for(&self, delta_dot: f64) -> f64 {
        if self.in_contact {
            self.impact_speed
        } else {
            delta_dot.abs()
        }
    }
}
