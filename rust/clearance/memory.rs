//! The impact memory of a dry contact: δ̇⁽⁻⁾, the approach speed at the start of the current
//! impact (docs/physics.md §3, P3). It is changed only between accepted steps, never by trial stages.

/// Per-joint impact state.
#[derive(Debug, Clone)]
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
    /// The film content of a joint with mass-conserving cavitation (rust/clearance/cavitation.rs)
    /// and the generation of it this memory's evaluations use; `None` for every other joint.
    pub film: Option<super::cavitation::SharedContent>,
    pub film_generation: u64,
}

impl Default for ImpactMemory {
    fn default() -> Self {
        ImpactMemory { in_contact: false, impact_speed: 0.0, impacts: 0, wear_offset: 0.0, viscosity: 0.0, film: None, film_generation: 0 }
    }
}

impl PartialEq for ImpactMemory {
    /// Equal when every value is and both hold the same film content (by identity) at the same generation.
    fn eq(&self, o: &Self) -> bool {
        self.in_contact == o.in_contact
            && self.impact_speed == o.impact_speed
            && self.impacts == o.impacts
            && self.wear_offset == o.wear_offset
            && self.viscosity == o.viscosity
            && self.film_generation == o.film_generation
            && match (&self.film, &o.film) {
                (None, None) => true,
                (Some(a), Some(b)) => std::sync::Arc::ptr_eq(a, b),
                _ => false,
            }
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
