//! The wear books of a revolute clearance joint (docs/physics.md §12): the volume that
//! Archard's law ([`crate::laws::wear`]) wears is laid down where the contact is, as a depth
//! around the bearing and around the journal, dh = dV / (L R Δφ) in bins of
//! Δφ = 2π/[`WEAR_BINS`] (L the bearing length, R the radius of the worn surface). Integrated
//! along every accepted step (Simpson's rule, with the step's midpoint from the dense output), so
//! the depth does not depend on the output grid.
//!
//! A run may start from depths worn before it (`initial_bearing`, `initial_journal` of the
//! description). With [`Archard::feedback`] the wear is fed back: after every accepted step the
//! depth worn at the contact direction ([`WearBook::depth_at`]) becomes the joint's
//! `ImpactMemory::wear_offset`, and the contact law measures the penetration from the worn
//! surfaces (from the first step when the run starts worn).

use super::{ClearanceJoint, JointForce, JointKinematics};
use crate::laws::wear::Archard;

/// Bins around each worn surface (1° each).
pub const WEAR_BINS: usize = 360;

/// What a contact wears at one instant: the volume rate [m³/s] and the contact's angle on the
/// bearing and on the journal \[rad\], counter-clockwise from each body's x axis.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WearRate {
    pub volume_rate: f64,
    pub angle_bearing: f64,
    pub angle_journal: f64,
}

impl WearRate {
    /// The rate of a contact with kinematics `k` and force `f`, its bearing and journal turned
    /// by `theta_bearing`, `theta_journal` \[rad\].
    pub fn new(law: &Archard, k: &JointKinematics, f: &JointForce, theta_bearing: f64, theta_journal: f64) -> Self {
        let direction = k.n.y.atan2(k.n.x);
        WearRate {
            volume_rate: law.volume_rate((f.w_dry * f.normal).max(0.0), k.slip.abs()),
            angle_bearing: direction - theta_bearing,
            angle_journal: direction - theta_journal,
        }
    }
}

/// The wear depth accumulated around the bearing and the journal of one joint \[m\].
#[derive(Debug, Clone, PartialEq)]
pub struct WearBook {
    pub law: Archard,
    pub radius_bearing: f64,
    pub radius_journal: f64,
    pub bearing: Vec<f64>,
    pub journal: Vec<f64>,
    /// Volume worn during this run \[m³\] (not counting the depths it started from).
    pub volume: f64,
    /// The book at the run's wear mark, if it has one and reached it.
    pub at_mark: Option<WearSnapshot>,
    last: WearRate,
}

/// Depths \[m\] around the bearing and the journal and the volume worn \[m³\] at one instant.
#[derive(Debug, Clone, PartialEq)]
pub struct WearSnapshot {
    pub bearing: Vec<f64>,
    pub journal: Vec<f64>,
    pub volume: f64,
}

/// Add `amount` (in bin units) uniformly over the arc from angle `a` to `b` [rad], the short
/// way round (a step sweeps less than half a turn of contact).
fn spread(bins: &mut [f64], a: f64, b: f64, amount: f64) {
    let n = bins.len() as f64;
    let tau = std::f64::consts::TAU;
    let d = (b - a + std::f64::consts::PI).rem_euclid(tau) - std::f64::consts::PI;
    let (lo, hi) = if d >= 0.0 { (a, a + d) } else { (a + d, a) };
    let (x0, x1) = (lo.rem_euclid(tau) / tau * n, lo.rem_euclid(tau) / tau * n + (hi - lo) / tau * n);
    if x1 - x0 < 1e-12 {
        bins[(x0 as usize).min(bins.len() - 1)] += amount;
        return;
    }
    let per = amount / (x1 - x0);
    let mut x = x0;
    while x < x1 {
        let cell = x.floor();
        let next = (cell + 1.0).min(x1);
        bins[(cell as usize) % bins.len()] += per * (next - x);
        x = next;
    }
}

impl WearBook {
    /// The book of `joint`, starting from the depths `worn` \[m\] (bearing, journal; an empty
    /// vector is unworn). `volume` counts only what this run wears.
    pub fn new(law: Archard, joint: &ClearanceJoint, worn: &(Vec<f64>, Vec<f64>)) -> Self {
        let start = |d: &Vec<f64>| if d.len() == WEAR_BINS { d.clone() } else { vec![0.0; WEAR_BINS] };
        WearBook {
            law,
            radius_bearing: joint.bearing_radius,
            radius_journal: joint.journal_radius,
            bearing: start(&worn.0),
            journal: start(&worn.1),
            volume: 0.0,
            at_mark: None,
            last: WearRate::default(),
        }
    }

    /// The depths and volume now.
    pub fn snapshot(&self) -> WearSnapshot {
        WearSnapshot { bearing: self.bearing.clone(), journal: self.journal.clone(), volume: self.volume }
    }

    /// Record the mark a `fraction` of the way through the step that began at `before`.
    pub fn mark_between(&mut self, before: WearSnapshot, fraction: f64) {
        let lerp = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x + fraction * (y - x)).collect();
        self.at_mark = Some(WearSnapshot {
            bearing: lerp(&before.bearing, &self.bearing),
            journal: lerp(&before.journal, &self.journal),
            volume: before.volume + fraction * (self.volume - before.volume),
        });
    }

    /// The worn depth \[m\] at the contact direction `direction` [rad, global], bearing turned by
    /// `theta_bearing`, journal by `theta_journal`: the deepest bin within half a bin of the
    /// direction on each surface (a contact on a bin edge sees the groove on either side), summed.
    pub fn depth_at(&self, direction: f64, theta_bearing: f64, theta_journal: f64) -> f64 {
        let n = WEAR_BINS as f64;
        let look = |bins: &[f64], angle: f64| {
            let x = (angle / std::f64::consts::TAU).rem_euclid(1.0) * n;
            let (a, b) = ((x - 0.5).floor(), (x + 0.5).floor());
            let at = |i: f64| bins[(i.rem_euclid(n) as usize).min(WEAR_BINS - 1)];
            at(a).max(at(b))
        };
        look(&self.bearing, direction - theta_bearing) + look(&self.journal, direction - theta_journal)
    }

    /// The rate at the start of the run.
    pub fn start(&mut self, r: WearRate) {
        self.last = r;
    }

    /// Lay `volume` down on the arc the contact swept from `a` to `b`, both surfaces.
    fn deposit(&mut self, a: &WearRate, b: &WearRate, volume: f64) {
        if volume <= 0.0 {
            return;
        }
        self.volume += volume;
        let dphi = std::f64::consts::TAU / WEAR_BINS as f64;
        let (lb, lj) = (self.law.length * self.radius_bearing * dphi, self.law.length * self.radius_journal * dphi);
        spread(&mut self.bearing, a.angle_bearing, b.angle_bearing, volume / lb);
        spread(&mut self.journal, a.angle_journal, b.angle_journal, volume / lj);
    }

    /// Close an accepted step of length `h` with the rates at its middle and end: Simpson's
    /// volume, each half spread along the arc it swept.
    pub fn step(&mut self, h: f64, mid: WearRate, end: WearRate) {
        let start = self.last;
        self.deposit(&start, &mid, h / 6.0 * (start.volume_rate + 2.0 * mid.volume_rate));
        self.deposit(&mid, &end, h / 6.0 * (2.0 * mid.volume_rate + end.volume_rate));
        self.last = end;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn depth_integrates_to_the_volume_and_lands_in_the_contact_bin() {
        let law = Archard { k_over_h: 1e-12, length: 0.02, feedback: false };
        let joint_radii = (0.0105, 0.01);
        let mut w = WearBook { law, radius_bearing: joint_radii.0, radius_journal: joint_radii.1, bearing: vec![0.0; WEAR_BINS], journal: vec![0.0; WEAR_BINS], volume: 0.0, at_mark: None, last: WearRate::default() };
        let r = WearRate { volume_rate: 2e-9, angle_bearing: -std::f64::consts::FRAC_PI_2, angle_journal: 0.3 };
        w.start(r);
        for _ in 0..100 {
            w.step(0.01, r, r);
        }
        assert!((w.volume - 2e-9).abs() < 1e-22);
        let dphi = std::f64::consts::TAU / WEAR_BINS as f64;
        let vol_b: f64 = w.bearing.iter().sum::<f64>() * law.length * joint_radii.0 * dphi;
        assert!((vol_b - w.volume).abs() < 1e-21);
        assert_eq!(w.bearing.iter().position(|d| *d > 0.0), Some(270));
        assert_eq!(w.journal.iter().position(|d| *d > 0.0), Some(17));
    }

    #[test]
    fn an_arc_is_spread_evenly_across_bins_and_round_zero() {
        let mut bins = vec![0.0; WEAR_BINS];
        let deg = std::f64::consts::TAU / 360.0;
        spread(&mut bins, 358.5 * deg, 2.5 * deg, 4.0); // through 0°, the short way
        assert!((bins[358] - 0.5).abs() < 1e-12 && (bins[359] - 1.0).abs() < 1e-12);
        assert!((bins[0] - 1.0).abs() < 1e-12 && (bins[1] - 1.0).abs() < 1e-12 && (bins[2] - 0.5).abs() < 1e-12);
        assert!((bins.iter().sum::<f64>() - 4.0).abs() < 1e-12);
    }
}
