//! Archard's wear law (docs/physics.md §12) as a pure function: a contact pressed with the
//! normal force F_N \[N\] that slides at |v_t| \[m/s\] wears the volume
//! dV/dt = (k/H) F_N |v_t| [m³/s] (k the dimensionless wear coefficient, H the hardness of the
//! softer surface \[Pa\]). Where the volume goes (the depth around each surface) is the wear
//! books' job (`clearance/wear.rs`).

/// Archard's law for one joint: its coefficient, the length the worn volume spreads over and
/// whether the worn depth is fed back into the contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Archard {
    /// Wear coefficient k over hardness H [1/Pa].
    pub k_over_h: f64,
    /// Bearing (contact) length L \[m\].
    pub length: f64,
    /// Feed the worn depth back into the contact: the clearance grows where it wears.
    pub feedback: bool,
}

impl Archard {
    /// The volume rate dV/dt = (k/H) F_N |v_t| [m³/s] of a contact pressed with `normal_force`
    /// F_N ≥ 0 \[N\] and sliding at `slip_speed` |v_t| \[m/s\].
    #[inline]
    pub fn volume_rate(&self, normal_force: f64, slip_speed: f64) -> f64 {
        self.k_over_h * normal_force * slip_speed
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_volume_rate_is_linear_in_load_and_speed() {
        // k = 1e-4, H = 2e9 Pa: 100 N sliding at 0.5 m/s wears 2.5e-12 m³/s.
        let law = Archard { k_over_h: 1e-4 / 2e9, length: 0.01, feedback: false };
        assert!((law.volume_rate(100.0, 0.5) - 2.5e-12).abs() < 1e-24);
        assert_eq!(law.volume_rate(0.0, 0.5), 0.0);
        assert_eq!(law.volume_rate(100.0, 0.0), 0.0);
    }
}
