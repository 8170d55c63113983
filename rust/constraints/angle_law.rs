//! Prescribed angle laws θ(t) of driving constraints, with their first two time derivatives.

use crate::error::{Error, Result};
use crate::description::{AngleLaw, Harmonic};

/// A driver law ready for evaluation: θ(t), θ'(t), θ''(t).
#[derive(Debug, Clone, PartialEq)]
pub enum CompiledAngleLaw {
    ConstantSpeed { angle0: f64, omega: f64 },
    Polynomial { c: Vec<f64> },
    /// Natural cubic spline through (t_k, θ_k) with second derivatives `m_k`; linear (C²)
    /// continuation outside the samples.
    Spline { t: Vec<f64>, y: Vec<f64>, m: Vec<f64> },
    /// θ = offset + amplitude · cos(ω t + phase).
    Harmonic(Harmonic),
}

impl CompiledAngleLaw {
    pub fn compile(law: &AngleLaw, field: &str) -> Result<Self> {
        Ok(match law {
            AngleLaw::ConstantSpeed { angle0, omega } => {
                check_finite(&format!("{field}.angle0"), *angle0)?;
                check_finite(&format!("{field}.omega"), *omega)?;
                CompiledAngleLaw::ConstantSpeed { angle0: *angle0, omega: *omega }
            }
            AngleLaw::Polynomial { coefficients } => {
                if coefficients.is_empty() {
                    return Err(Error::invalid(format!("{field}.coefficients"), "[]", "needs at least one coefficient"));
                }
                for (k, c) in coefficients.iter().enumerate() {
                    check_finite(&format!("{field}.coefficients[{k}]"), *c)?;
                }
                CompiledAngleLaw::Polynomial { c: coefficients.clone() }
            }
            AngleLaw::Samples { times, angles } => {
                if times.len() != angles.len() || times.len() < 3 {
                    return Err(Error::invalid(
                        format!("{field}.times"),
                        format!("{} times / {} angles", times.len(), angles.len()),
                        "needs at least 3 samples and as many angles as times",
                    ));
                }
                for k in 0..times.len() {
                    check_finite(&format!("{field}.times[{k}]"), times[k])?;
                    check_finite(&format!("{field}.angles[{k}]"), angles[k])?;
                    if k > 0 && times[k] <= times[k - 1] {
                        return Err(Error::invalid(format!("{field}.times[{k}]"), times[k], "times must increase strictly"));
                    }
                }
                let m = natural_spline_moments(times, angles);
                CompiledAngleLaw::Spline { t: times.clone(), y: angles.clone(), m }
            }
            AngleLaw::Harmonic(h) => {
                check_harmonic(field, h)?;
                CompiledAngleLaw::Harmonic(*h)
            }
        })
    }

    /// (θ, θ', θ'') at time t.
    #[inline]
    pub fn eval(&self, t: f64) -> (f64, f64, f64) {
        match self {
            CompiledAngleLaw::ConstantSpeed { angle0, omega } => (angle0 + omega * t, *omega, 0.0),
            CompiledAngleLaw::Polynomial { c } => {
                // Horner for p, p', p''.
                let (mut p, mut d1, mut d2) = (0.0, 0.0, 0.0);
                for &ck in c.iter().rev() {
                    d2 = d2 * t + 2.0 * d1;
                    d1 = d1 * t + p;
                    p = p * t + ck;
                }
                (p, d1, d2)
            }
            CompiledAngleLaw::Spline { t: ts, y, m } => spline_eval(ts, y, m, t),
            CompiledAngleLaw::Harmonic(h) => h.eval(t),
        }
    }
}

/// Every check of a [`Harmonic`] (a load's or a driver's), naming `field`'s parts: amplitude,
/// phase and offset finite, omega positive and finite \[rad/s\].
pub fn check_harmonic(field: &str, h: &Harmonic) -> Result<()> {
    use crate::error::num;
    for (part, v) in [("amplitude", h.amplitude), ("phase", h.phase), ("offset", h.offset)] {
        if !v.is_finite() {
            return Err(Error::invalid(format!("{field}.{part}"), num(v), "must be a finite number"));
        }
    }
    if !(h.omega > 0.0 && h.omega.is_finite()) {
        return Err(Error::invalid(format!("{field}.omega"), num(h.omega), "must be a positive, finite angular frequency [rad/s]"));
    }
    Ok(())
}

fn check_finite(field: &str, v: f64) -> Result<()> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(Error::invalid(field, v, "must be a finite number"))
    }
}

/// Second derivatives of the natural cubic spline (tridiagonal solve, Thomas algorithm).
fn natural_spline_moments(t: &[f64], y: &[f64]) -> Vec<f64> {
    let n = t.len();
    let mut m = vec![0.0; n];
    let mut c_prime = vec![0.0; n];
    let mut d_prime = vec![0.0; n];
    for i in 1..n - 1 {
        let h0 = t[i] - t[i - 1];
        let h1 = t[i + 1] - t[i];
        let a = h0 / 6.0;
        let b = (h0 + h1) / 3.0;
        let c = h1 / 6.0;
        let d = (y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0;
        let denom = b - a * c_prime[i - 1];
        c_prime[i] = c / denom;
        d_prime[i] = (d - a * d_prime[i - 1]) / denom;
    }
    for i in (1..n - 1).rev() {
        m[i] = d_prime[i] - c_prime[i] * m[i + 1];
    }
    m
}

fn spline_eval(t: &[f64], y: &[f64], m: &[f64], x: f64) -> (f64, f64, f64) {
    let n = t.len();
    if x <= t[0] || x >= t[n - 1] {
        // Linear continuation with the end slope (natural ends have θ'' = 0).
        let (i, j, end) = if x <= t[0] { (0, 1, 0) } else { (n - 2, n - 1, n - 1) };
        let h = t[j] - t[i];
        let slope = (y[j] - y[i]) / h + if end == 0 { -h * (2.0 * m[i] + m[j]) / 6.0 } else { h * (m[i] + 2.0 * m[j]) / 6.0 };
        return (y[end] + slope * (x - t[end]), slope, 0.0);
    }
    let i = match t.binary_search_by(|v| v.partial_cmp(&x).unwrap_or(std::cmp::Ordering::Less)) {
        Ok(k) => k.min(n - 2),
        Err(k) => k - 1,
    };
    let h = t[i + 1] - t[i];
    let a = (t[i + 1] - x) / h;
    let b = (x - t[i]) / h;
    let val = a * y[i] + b * y[i + 1] + ((a * a * a - a) * m[i] + (b * b * b - b) * m[i + 1]) * h * h / 6.0;
    let d1 = (y[i + 1] - y[i]) / h + (-(3.0 * a * a - 1.0) * m[i] + (3.0 * b * b - 1.0) * m[i + 1]) * h / 6.0;
    let d2 = a * m[i] + b * m[i + 1];
    (val, d1, d2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polynomial_derivatives() {
        let law = CompiledAngleLaw::Polynomial { c: vec![1.0, 2.0, 3.0, 4.0] };
        let t: f64 = 0.7;
        let (p, d1, d2) = law.eval(t);
        assert!((p - (1.0 + 2.0 * t + 3.0 * t * t + 4.0 * t.powi(3))).abs() < 1e-14);
        assert!((d1 - (2.0 + 6.0 * t + 12.0 * t * t)).abs() < 1e-13);
        assert!((d2 - (6.0 + 24.0 * t)).abs() < 1e-13);
    }

    #[test]
    fn spline_reproduces_a_smooth_law() {
        let times: Vec<f64> = (0..201).map(|k| k as f64 * 0.01).collect();
        let angles: Vec<f64> = times.iter().map(|t| t.sin()).collect();
        let law = CompiledAngleLaw::compile(&AngleLaw::Samples { times, angles }, "driver").unwrap();
        let (p, d1, d2) = law.eval(1.234);
        assert!((p - 1.234f64.sin()).abs() < 1e-8);
        assert!((d1 - 1.234f64.cos()).abs() < 1e-5);
        assert!((d2 + 1.234f64.sin()).abs() < 1e-3);
    }

    #[test]
    fn harmonic_law_and_its_derivatives() {
        let h = Harmonic { amplitude: 0.4, omega: 3.0, phase: -0.5, offset: 1.0 };
        let law = CompiledAngleLaw::compile(&AngleLaw::Harmonic(h), "driver 'd'").unwrap();
        let t = 0.37;
        let (p, d1, d2) = law.eval(t);
        let arg = 3.0 * t - 0.5;
        assert!((p - (1.0 + 0.4 * f64::cos(arg))).abs() < 1e-15);
        assert!((d1 + 1.2 * f64::sin(arg)).abs() < 1e-15);
        assert!((d2 + 3.6 * f64::cos(arg)).abs() < 1e-14);
        let bad = CompiledAngleLaw::compile(&AngleLaw::Harmonic(Harmonic { omega: -1.0, ..h }), "driver 'd'").unwrap_err().to_string();
        assert_eq!(bad, "invalid driver 'd'.omega = -1.0: must be a positive, finite angular frequency [rad/s]");
        let bad = CompiledAngleLaw::compile(&AngleLaw::Harmonic(Harmonic { amplitude: f64::NAN, ..h }), "driver 'd'").unwrap_err().to_string();
        assert_eq!(bad, "invalid driver 'd'.amplitude = nan: must be a finite number");
    }

    #[test]
    fn spline_rejects_unsorted_times() {
        let e = CompiledAngleLaw::compile(&AngleLaw::Samples { times: vec![0.0, 2.0, 1.0], angles: vec![0.0; 3] }, "d");
        assert!(matches!(e, Err(Error::InvalidInput { .. })));
    }
}
