//! A pin in a bore as a line contact (docs/physics.md §3, `Dry(stiffness_form="cylindrical")`):
//! the elastic force of two parallel cylinders of length L pressed together, after Johnson,
//! *Contact Mechanics* (1985), §5.6 (two-dimensional Hertz contact of cylinders).
//!
//! Hertz's line contact of load P = F/L per unit length and effective radius R* has the half
//! width a = √(4 P R*/(π E*)); the approach of the two cylinders' axes is, per body,
//! (P (1 − ν²)/(π E)) (2 ln(4R/a) − 1). clearsim takes one effective radius for both bodies, the
//! internal (conformal) radius R* = R_b R_j/(R_b − R_j) of the point-contact law, and the composite
//! modulus 1/E* = (1 − ν_b²)/E_b + (1 − ν_j²)/E_j:
//!
//! `δ = (P/(π E*)) [ln(4π E* R*/P) − 1]`,
//!
//! since 2 ln(4R*/a) = ln(16 R*²/a²) = ln(4π E* R*/P). With x = P/(π E*) \[m\] this is
//! `δ = x (ln(4R*/x) − 1)`, increasing in x while x < 4R*/e² (δ < 4R*/e², far beyond any
//! penetration a run accepts); [`LineContact::force`] inverts it by Newton's method. The force
//! grows almost linearly with δ (a logarithmic correction) and in proportion to L, so the
//! penetration under a given load falls nearly as 1/L.
//!
//! Validity: Hertz's assumptions, a contact half width small against the pin (a ≲ 0.1 R_j) and
//! elastic material; for a tight, heavily loaded pin the contact becomes conformal (a → R_j) and
//! the true stiffness rises above this law (Pereira, Ramalho & Ambrósio 2011, *Nonlinear Dyn.*
//! 63:681–697, compare such laws with finite elements).

/// Parameters of a line contact (module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineContact {
    /// Composite modulus E* \[Pa\], 1/E* = (1 − ν_b²)/E_b + (1 − ν_j²)/E_j.
    pub modulus: f64,
    /// Contact (pin) length L \[m\].
    pub length: f64,
    /// Effective radius R* \[m\] (R_b R_j/(R_b − R_j) for a pin in a bore).
    pub radius: f64,
}

impl LineContact {
    /// A pin of radius `r_journal` in a bore of radius `r_bearing`, length `length`, materials
    /// (E, ν) of bearing and journal.
    pub fn pin_in_bore(r_bearing: f64, r_journal: f64, length: f64, e_bearing: f64, nu_bearing: f64, e_journal: f64, nu_journal: f64) -> Self {
        let compliance = (1.0 - nu_bearing * nu_bearing) / e_bearing + (1.0 - nu_journal * nu_journal) / e_journal;
        LineContact { modulus: 1.0 / compliance, length, radius: r_bearing * r_journal / (r_bearing - r_journal) }
    }

    /// Penetration δ \[m\] under the force `force` \[N\] (Johnson's form, module doc).
    pub fn penetration(&self, force: f64) -> f64 {
        if force.is_nan() || force <= 0.0 {
            return 0.0;
        }
        let x = force / (self.length * std::f64::consts::PI * self.modulus);
        x * ((4.0 * self.radius / x).ln() - 1.0)
    }

    /// Scale π E* L \[N/m\] of the force: F = π E* L x(δ).
    pub fn force_scale(&self) -> f64 {
        std::f64::consts::PI * self.modulus * self.length
    }

    /// Elastic force F \[N\] at penetration `delta` \[m\] (0 for δ ≤ 0): the inverse of
    /// [`Self::penetration`], by Newton's method on δ = x (A − ln x), A = ln(4R*) − 1, to
    /// round-off. Beyond the law's turning point δ_max = 4R*/e² it continues with its slope there.
    pub fn force(&self, delta: f64) -> f64 {
        if delta.is_nan() || delta <= 0.0 {
            return 0.0;
        }
        let a = (4.0 * self.radius).ln() - 1.0;
        let x_max = 4.0 * self.radius * (-2.0f64).exp();
        let delta_max = x_max; // x_max (A − ln x_max) = x_max (ln 4R* − 1 − ln 4R* + 2)
        if delta >= 0.5 * delta_max {
            // Far outside the law's range (metres of penetration for a real pin): a straight
            // continuation keeps the force finite and increasing.
            let x_half = self.x_of(0.5 * delta_max, a, 0.25 * x_max);
            let slope = 1.0 / (a - x_half.ln() - 1.0);
            return self.force_scale() * (x_half + slope * (delta - 0.5 * delta_max));
        }
        // Start from x ≈ δ/(A − ln δ) (the law with ln x ≈ ln δ), already within a few %.
        let guess = delta / (a - delta.ln()).max(1.0);
        self.force_scale() * self.x_of(delta, a, guess)
    }

    /// x with x (A − ln x) = δ on the increasing branch, Newton from `x`.
    fn x_of(&self, delta: f64, a: f64, mut x: f64) -> f64 {
        for _ in 0..60 {
            let l = a - x.ln();
            let step = (x * l - delta) / (l - 1.0);
            let next = (x - step).max(0.5 * x);
            let done = (next - x).abs() <= 1e-15 * next;
            x = next;
            if done {
                break;
            }
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Steel pin R_j = 10 mm in a bore R_b = 10.5 mm (c = 0.5 mm), L = 20 mm:
    //   1/E* = 2 · 0.91/207e9 = 8.792271e-12 1/Pa → E* = 1.137363e11 Pa;
    //   R* = 10.5e-3 · 10e-3 / 0.5e-3 = 0.21 m.
    // By hand, F = 8.5 kN: P = F/L = 4.25e5 N/m; P/(πE*) = 4.25e5/3.573133e11 = 1.189432e-6 m;
    //   4πE*R*/P = 4 · 0.21/1.189432e-6 = 7.062129e5, ln = 13.46767;
    //   δ = 1.189432e-6 · (13.46767 − 1) = 1.482960e-5 m (14.8 µm).
    fn pin(length: f64) -> LineContact {
        LineContact::pin_in_bore(10.5e-3, 10e-3, length, 207e9, 0.3, 207e9, 0.3)
    }

    #[test]
    fn johnson_line_contact_by_hand() {
        let l = pin(0.02);
        assert!((l.modulus / 1.137363e11 - 1.0).abs() < 1e-6, "E* = {}", l.modulus);
        assert!((l.radius - 0.21).abs() < 1e-12);
        let d = l.penetration(8500.0);
        assert!((d / 1.482960e-5 - 1.0).abs() < 1e-5, "δ = {d}");
        let f = l.force(1.482960e-5);
        assert!((f / 8500.0 - 1.0).abs() < 1e-5, "F = {f}");
    }

    #[test]
    fn force_inverts_penetration_over_the_range() {
        let l = pin(0.02);
        for f in [1e-6, 1e-2, 1.0, 1e2, 1e4, 1e6, 1e8] {
            let d = l.penetration(f);
            let back = l.force(d);
            assert!((back / f - 1.0).abs() < 1e-12, "F {f}: δ {d}, back {back}");
        }
        assert_eq!(l.force(0.0), 0.0);
        assert_eq!(l.force(-1e-6), 0.0);
        assert_eq!(l.force(f64::NAN), 0.0);
        // Increasing and finite far beyond its range.
        let mut last = 0.0;
        for k in 0..200 {
            let d = 1e-9 * 1.2f64.powi(k);
            let f = l.force(d);
            assert!(f.is_finite() && f > last, "δ {d}: {f} after {last}");
            last = f;
        }
    }

    #[test]
    fn twice_the_length_about_half_the_penetration() {
        // Same load: δ(2L)/δ(L) = ½ (ln(2K) − 1)/(ln K − 1) with K = 4πE*R*L/F, slightly above ½.
        for f in [100.0, 8500.0] {
            let ratio = pin(0.04).penetration(f) / pin(0.02).penetration(f);
            assert!(ratio > 0.5 && ratio < 0.56, "F {f}: ratio {ratio}");
        }
    }
}
