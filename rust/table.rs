//! A tabulated function y(x) (docs/physics.md §10.3): load tables in time or a body's angle and a
//! spring's force–deflection table. Piecewise linear, or (`interpolation = "cubic"`) a C² cubic
//! spline: not-a-knot (it reproduces any cubic), periodic when the table has a period. Held at
//! its end values outside [x₀, x_last]; with a period the argument is wrapped into
//! [x₀, x₀ + period) and the table is closed over the wrap: its last point is joined to its first
//! one period on (a straight line for a linear table, the periodic spline for a cubic one), so a
//! periodic table is continuous whatever its first point (a table held at its last value up to
//! x₀ + period and jumping to its first there stalled the implicit methods at that corner at tight
//! tolerances, issue 37).
//!
//! The spline is held as its second derivatives Mᵢ at the nodes (the moments): on
//! [xᵢ, xᵢ₊₁], hᵢ = xᵢ₊₁ − xᵢ, s = x − xᵢ,
//! `y = yᵢ + s (dᵢ − hᵢ (2Mᵢ + Mᵢ₊₁)/6) + s² Mᵢ/2 + s³ (Mᵢ₊₁ − Mᵢ)/(6hᵢ)`, dᵢ = (yᵢ₊₁ − yᵢ)/hᵢ,
//! with the moments from the tridiagonal continuity conditions of y′ (de Boor, *A Practical
//! Guide to Splines*, ch. IV): cyclic for a periodic table (solved by the Sherman–Morrison
//! formula on a tridiagonal one), closed by the not-a-knot conditions (y‴ continuous at x₁ and
//! x_{n−2}) otherwise. Three points give the parabola through them, two the straight line.

use crate::description::{Interpolation, Table};

/// A tabulated function (module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct Tabulated {
    /// The nodes: the table's points and, for a periodic table whose last point is not already
    /// one period after its first, the first point repeated at x₀ + period.
    x: Vec<f64>,
    y: Vec<f64>,
    /// The table's own points (the nodes but the closing one).
    points: usize,
    /// The spline's moments (second derivatives) at the nodes; empty for a linear table.
    moments: Vec<f64>,
    period: Option<f64>,
}

/// Whether a periodic table's last point lies one period after its first (it then closes the
/// table itself: its value must be the first's).
pub fn closes_itself(t: &Table) -> bool {
    let (x0, xl) = (t.x[0], t.x[t.x.len() - 1]);
    t.period.is_some_and(|p| xl - x0 >= p * (1.0 - 1e-12))
}

impl Tabulated {
    /// The function of a validated table (rust/compile/validate.rs: ≥ 2 points, x strictly
    /// increasing, a period covering them; a cubic periodic table that closes itself repeats its
    /// first value).
    pub fn new(t: &Table) -> Self {
        let (mut x, mut y) = (t.x.clone(), t.y.clone());
        let points = x.len();
        if let Some(p) = t.period {
            if closes_itself(t) {
                if t.interpolation == Interpolation::Cubic {
                    y[points - 1] = y[0];
                }
            } else {
                x.push(x[0] + p);
                y.push(y[0]);
            }
        }
        let moments = match (t.interpolation, t.period) {
            (Interpolation::Linear, _) => Vec::new(),
            (Interpolation::Cubic, Some(_)) => periodic_moments(&x, &y),
            (Interpolation::Cubic, None) => not_a_knot_moments(&x, &y),
        };
        Tabulated { x, y, points, moments, period: t.period }
    }

    #[inline]
    fn wrap(&self, x: f64) -> f64 {
        match self.period {
            Some(p) => self.x[0] + (x - self.x[0]).rem_euclid(p),
            None => x,
        }
    }

    /// y(x).
    #[inline]
    pub fn eval(&self, x: f64) -> f64 {
        let x = self.wrap(x);
        let n = self.x.len();
        if x <= self.x[0] {
            return self.y[0];
        }
        if x >= self.x[n - 1] {
            return self.y[n - 1];
        }
        let i = self.x.partition_point(|&xi| xi <= x); // x[i-1] <= x < x[i]
        let (x0, x1, y0, y1) = (self.x[i - 1], self.x[i], self.y[i - 1], self.y[i]);
        if self.moments.is_empty() {
            return y0 + (y1 - y0) * (x - x0) / (x1 - x0);
        }
        let (m0, m1, h, s) = (self.moments[i - 1], self.moments[i], x1 - x0, x - x0);
        y0 + s * ((y1 - y0) / h - h * (2.0 * m0 + m1) / 6.0) + s * s * (0.5 * m0 + s * (m1 - m0) / (6.0 * h))
    }

    /// The first corner of y (a point where its slope jumps, repeated every period) strictly
    /// inside (a, b): every point of a linear table; the two ends of a cubic one, where it is
    /// held (a periodic spline has none).
    pub fn first_break_in(&self, a: f64, b: f64) -> Option<f64> {
        let corners: &[f64] = match (self.moments.is_empty(), self.period) {
            (true, _) => &self.x[..self.points],
            (false, None) => &[self.x[0], self.x[self.points - 1]],
            (false, Some(_)) => &[],
        };
        let (x0, n) = (self.x[0], corners.len());
        if n == 0 {
            return None;
        }
        match self.period {
            None => corners.iter().copied().find(|&x| x > a && x < b),
            Some(p) => {
                let base = x0 + ((a - x0) / p).floor() * p; // the period [base, base + p) holding a
                let mut shift = base - x0;
                while x0 + shift < b {
                    if let Some(x) = corners.iter().map(|x| x + shift).find(|&x| x > a && x < b) {
                        return Some(x);
                    }
                    if corners[n - 1] + shift >= b {
                        return None;
                    }
                    shift += p;
                }
                None
            }
        }
    }

    /// ∫₀ˣ y(u) du (no period): the potential energy of a tabulated spring at deflection x.
    pub fn integral_from_zero(&self, x: f64) -> f64 {
        self.primitive(x) - self.primitive(0.0)
    }

    /// ∫ from x₀ to x of y, with the end values held outside the table (exact per segment:
    /// the trapezoid of a linear one, Simpson's rule of a cubic one).
    fn primitive(&self, x: f64) -> f64 {
        let n = self.x.len();
        if x <= self.x[0] {
            return self.y[0] * (x - self.x[0]);
        }
        let mut s = 0.0;
        for i in 1..n {
            let (a, b) = (self.x[i - 1], self.x[i].min(x));
            if b <= a {
                break;
            }
            let (ya, yb) = (self.y[i - 1], self.eval(b));
            s += if self.moments.is_empty() { 0.5 * (ya + yb) * (b - a) } else { (b - a) * (ya + 4.0 * self.eval(0.5 * (a + b)) + yb) / 6.0 };
        }
        if x > self.x[n - 1] {
            s += self.y[n - 1] * (x - self.x[n - 1]);
        }
        s
    }
}

/// The moments of the not-a-knot spline through (x, y) (module doc).
fn not_a_knot_moments(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len();
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let d: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
    match n {
        2 => return vec![0.0; 2],
        3 => return vec![2.0 * (d[1] - d[0]) / (x[2] - x[0]); 3],
        _ => {}
    }
    // Unknowns M₁ … M_{n−2}; rows i = 1 … n−2: h_{i−1} M_{i−1} + 2(h_{i−1} + hᵢ) Mᵢ + hᵢ M_{i+1}
    // = 6 (dᵢ − d_{i−1}), with M₀ = (1 + h₀/h₁) M₁ − (h₀/h₁) M₂ and its mirror at the far end
    // substituted into the first and last rows (both stay diagonally dominant).
    let k = n - 2;
    let (mut sub, mut diag, mut sup, mut rhs) = (vec![0.0; k], vec![0.0; k], vec![0.0; k], vec![0.0; k]);
    for r in 0..k {
        let i = r + 1;
        sub[r] = h[i - 1];
        diag[r] = 2.0 * (h[i - 1] + h[i]);
        sup[r] = h[i];
        rhs[r] = 6.0 * (d[i] - d[i - 1]);
    }
    let (h0, h1) = (h[0], h[1]);
    diag[0] += h0 * (1.0 + h0 / h1);
    sup[0] -= h0 * h0 / h1;
    let (ha, hb) = (h[n - 3], h[n - 2]);
    diag[k - 1] += hb * (1.0 + hb / ha);
    sub[k - 1] -= hb * hb / ha;
    let inner = thomas(&sub, &diag, &sup, &rhs);
    let mut m = vec![0.0; n];
    m[1..n - 1].copy_from_slice(&inner);
    m[0] = (1.0 + h0 / h1) * m[1] - (h0 / h1) * m[2];
    m[n - 1] = (1.0 + hb / ha) * m[n - 2] - (hb / ha) * m[n - 3];
    m
}

/// The moments of the periodic spline through the nodes (x, y), whose last node closes the
/// period (y_last = y₀): one per interval, the last repeating the first.
fn periodic_moments(x: &[f64], y: &[f64]) -> Vec<f64> {
    let k = x.len() - 1; // intervals = unknowns M₀ … M_{k−1}
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let d: Vec<f64> = (0..k).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
    let prev = |i: usize| (i + k - 1) % k;
    let mut m = vec![0.0; k + 1];
    match k {
        1 => {} // a constant
        2 => {
            // Both neighbours of each node are the other node: 2 (h₀ + h₁) Mᵢ + (h₀ + h₁) Mⱼ = rᵢ.
            let s = h[0] + h[1];
            let (r0, r1) = (6.0 * (d[0] - d[1]), 6.0 * (d[1] - d[0]));
            let det = 3.0 * s * s;
            m[0] = (2.0 * s * r0 - s * r1) / det;
            m[1] = (2.0 * s * r1 - s * r0) / det;
        }
        _ => {
            let (mut sub, mut diag, mut sup, mut rhs) = (vec![0.0; k], vec![0.0; k], vec![0.0; k], vec![0.0; k]);
            for i in 0..k {
                sub[i] = h[prev(i)];
                diag[i] = 2.0 * (h[prev(i)] + h[i]);
                sup[i] = h[i];
                rhs[i] = 6.0 * (d[i] - d[prev(i)]);
            }
            m[..k].copy_from_slice(&cyclic(&sub, &diag, &sup, &rhs));
        }
    }
    m[k] = m[0];
    m
}

/// The tridiagonal system (sub, diag, sup) x = rhs by elimination without pivoting (the spline's
/// systems are diagonally dominant); `sub[0]` and `sup[last]` are not used.
fn thomas(sub: &[f64], diag: &[f64], sup: &[f64], rhs: &[f64]) -> Vec<f64> {
    let n = diag.len();
    let (mut c, mut x) = (vec![0.0; n], vec![0.0; n]);
    let mut beta = diag[0];
    x[0] = rhs[0] / beta;
    for i in 1..n {
        c[i] = sup[i - 1] / beta;
        beta = diag[i] - sub[i] * c[i];
        x[i] = (rhs[i] - sub[i] * x[i - 1]) / beta;
    }
    for i in (0..n - 1).rev() {
        x[i] -= c[i + 1] * x[i + 1];
    }
    x
}

/// The cyclic tridiagonal system whose corners are `sub[0]` (row 0, last column) and
/// `sup[last]` (last row, column 0), n ≥ 3: the tridiagonal part with its first and last
/// diagonal entries changed so that the corners become a rank-one term u vᵀ, solved by
/// Sherman–Morrison from two tridiagonal solves.
fn cyclic(sub: &[f64], diag: &[f64], sup: &[f64], rhs: &[f64]) -> Vec<f64> {
    let n = diag.len();
    let (top, bottom) = (sub[0], sup[n - 1]); // A[0][n−1], A[n−1][0]
    let gamma = -diag[0];
    let mut b = diag.to_vec();
    b[0] -= gamma;
    b[n - 1] -= bottom * top / gamma;
    let x = thomas(sub, &b, sup, rhs);
    let mut u = vec![0.0; n];
    u[0] = gamma;
    u[n - 1] = bottom;
    let z = thomas(sub, &b, sup, &u);
    // v = (1, 0, …, 0, top/γ).
    let fact = (x[0] + top * x[n - 1] / gamma) / (1.0 + z[0] + top * z[n - 1] / gamma);
    x.iter().zip(&z).map(|(xi, zi)| xi - fact * zi).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tab(x: &[f64], y: &[f64], period: Option<f64>, interpolation: Interpolation) -> Tabulated {
        Tabulated::new(&Table { x: x.to_vec(), y: y.to_vec(), period, interpolation })
    }

    fn linear(x: &[f64], y: &[f64], period: Option<f64>) -> Tabulated {
        tab(x, y, period, Interpolation::Linear)
    }

    #[test]
    fn table_interpolates_holds_and_wraps() {
        let t = linear(&[0.0, 1.0, 3.0], &[0.0, 10.0, 30.0], None);
        assert_eq!(t.eval(0.5), 5.0);
        assert_eq!(t.eval(2.0), 20.0);
        assert_eq!(t.eval(-1.0), 0.0);
        assert_eq!(t.eval(7.0), 30.0);
        let p = linear(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0], Some(2.0));
        assert!((p.eval(2.5) - 0.5).abs() < 1e-15);
        assert!((p.eval(-0.5) - 0.5).abs() < 1e-15);
    }

    /// A periodic table whose first point is not at the wrap is closed over it by a straight
    /// line from its last point to its first one period on: continuous, no jump at x₀ + period.
    #[test]
    fn a_periodic_table_is_closed_over_the_wrap() {
        let p = linear(&[0.5, 1.0, 1.5], &[1.0, 3.0, 5.0], Some(2.0));
        // From (1.5, 5) to (2.5, 1): at 2.0 (≡ 0.0) halfway, 3.0.
        assert!((p.eval(2.0) - 3.0).abs() < 1e-15 && (p.eval(0.0) - 3.0).abs() < 1e-15);
        for x in [2.5 - 1e-12, 0.5 - 1e-12, 4.5 - 1e-9] {
            assert!((p.eval(x) - 1.0).abs() < 1e-8, "{x}: {}", p.eval(x));
        }
        // Equal end values: the old hold, bit for bit.
        let q = linear(&[0.5, 1.0, 1.5], &[2.0, 3.0, 2.0], Some(2.0));
        assert_eq!(q.eval(1.9), 2.0);
    }

    #[test]
    fn breakpoints_inside_an_interval_repeat_with_the_period() {
        let t = linear(&[0.0, 1.0, 3.0], &[0.0, 10.0, 30.0], None);
        assert_eq!(t.first_break_in(0.0, 2.0), Some(1.0));
        assert_eq!(t.first_break_in(1.0, 2.0), None);
        assert_eq!(t.first_break_in(3.0, 9.0), None);
        let p = linear(&[0.0, 0.5, 1.0], &[0.0, 1.0, 0.0], Some(2.0));
        assert_eq!(p.first_break_in(1.2, 2.7), Some(2.0));
        assert_eq!(p.first_break_in(2.0, 2.4), None);
        assert_eq!(p.first_break_in(-1.9, -1.2), Some(-1.5));
        // A cubic table has corners only where it is held; a periodic one none.
        let c = tab(&[0.0, 1.0, 2.0, 3.0], &[0.0, 1.0, 0.0, 1.0], None, Interpolation::Cubic);
        assert_eq!(c.first_break_in(0.5, 2.9), None);
        assert_eq!(c.first_break_in(0.5, 3.1), Some(3.0));
        assert_eq!(c.first_break_in(-1.0, 3.1), Some(0.0));
        let cp = tab(&[0.0, 1.0, 2.0, 3.0], &[0.0, 1.0, 0.0, 1.0], Some(4.0), Interpolation::Cubic);
        assert_eq!(cp.first_break_in(-10.0, 10.0), None);
    }

    #[test]
    fn table_integral_is_the_area_under_a_linear_spring() {
        // F = 3 δ tabulated on [-1, 2]: energy 1.5 δ² inside, end force held outside.
        let t = linear(&[-1.0, 2.0], &[-3.0, 6.0], None);
        for d in [-0.7, 0.0, 0.4, 1.9] {
            assert!((t.integral_from_zero(d) - 1.5 * d * d).abs() < 1e-12, "{d}");
        }
        assert!((t.integral_from_zero(3.0) - (1.5 * 4.0 + 6.0)).abs() < 1e-12);
        // A cubic spring F = δ³ through unevenly spaced points: energy δ⁴/4.
        let xs = [-1.0, -0.3, 0.2, 0.9, 1.5];
        let c = tab(&xs, &xs.map(|x: f64| x.powi(3)), None, Interpolation::Cubic);
        for d in [-0.8, 0.1, 1.2] {
            assert!((c.integral_from_zero(d) - d.powi(4) / 4.0).abs() < 1e-12, "{d}");
        }
    }

    /// Not-a-knot reproduces any cubic exactly, on uneven points; three points give the parabola
    /// through them, two the line.
    #[test]
    fn the_spline_reproduces_a_cubic_exactly() {
        let f = |x: f64| 2.0 - 0.7 * x + 1.3 * x * x - 0.4 * x * x * x;
        let xs = [-2.0, -1.1, -0.2, 0.05, 0.9, 2.4, 3.0];
        let t = tab(&xs, &xs.map(f), None, Interpolation::Cubic);
        for k in 0..=500 {
            let x = -2.0 + 5.0 * k as f64 / 500.0;
            assert!((t.eval(x) - f(x)).abs() < 1e-12, "{x}: {} vs {}", t.eval(x), f(x));
        }
        let four = [0.0, 0.3, 1.7, 2.0];
        let t4 = tab(&four, &four.map(f), None, Interpolation::Cubic);
        assert!((t4.eval(1.1) - f(1.1)).abs() < 1e-12);
        let q = |x: f64| 1.0 + x - 2.0 * x * x;
        let t3 = tab(&[0.0, 0.4, 2.0], &[q(0.0), q(0.4), q(2.0)], None, Interpolation::Cubic);
        assert!((t3.eval(1.3) - q(1.3)).abs() < 1e-12);
        let t2 = tab(&[0.0, 2.0], &[1.0, 5.0], None, Interpolation::Cubic);
        assert!((t2.eval(0.5) - 2.0).abs() < 1e-15);
    }

    /// The periodic spline of sin on n equal intervals over 2π stays within Hall's bound for
    /// periodic and clamped cubic splines, (5/384) h⁴ max|f⁗| (C. A. Hall, *J. Approx. Theory*
    /// 1 (1968) 209), and its error falls as h⁴; its first point off the wrap changes neither.
    #[test]
    fn the_periodic_spline_of_sin_is_within_the_fourth_order_bound() {
        let two_pi = 2.0 * std::f64::consts::PI;
        let mut last = f64::NAN;
        for n in [12usize, 24, 48, 96] {
            let h = two_pi / n as f64;
            for (offset, closed) in [(0.0, true), (0.37, false), (0.37, true)] {
                let count = if closed { n + 1 } else { n };
                let xs: Vec<f64> = (0..count).map(|k| (k as f64 + offset) * h).collect();
                let ys: Vec<f64> = xs.iter().map(|x| x.sin()).collect();
                let t = tab(&xs, &ys, Some(two_pi), Interpolation::Cubic);
                let err = (0..4000).map(|k| -7.0 + 20.0 * k as f64 / 4000.0).map(|x| (t.eval(x) - x.sin()).abs()).fold(0.0, f64::max);
                let bound = 5.0 / 384.0 * h.powi(4);
                assert!(err <= bound, "n = {n}, offset {offset}: {err:e} > {bound:e}");
                if offset == 0.0 {
                    if last.is_finite() {
                        let ratio = last / err;
                        assert!((12.0..20.0).contains(&ratio), "n = {n}: error ratio {ratio}");
                    }
                    last = err;
                }
            }
        }
    }

    /// The periodic spline is C² across the wrap: its one-sided slopes and curvatures match on
    /// both sides of x₀ + period (second-order one-sided differences), for two and for many
    /// intervals, and it passes through its points in every period.
    #[test]
    fn the_periodic_spline_is_smooth_across_the_wrap() {
        for (xs, ys) in [(vec![0.3, 1.1], vec![2.0, -1.0]), (vec![0.3, 1.1, 2.0, 2.2, 3.5], vec![2.0, -1.0, 0.5, 0.7, 1.5])] {
            let t = tab(&xs, &ys, Some(4.0), Interpolation::Cubic);
            let (w, e) = (4.3, 1e-4);
            let c = t.eval(w);
            let (l1, l2, r1, r2) = (t.eval(w - e), t.eval(w - 2.0 * e), t.eval(w + e), t.eval(w + 2.0 * e));
            let (slope_l, slope_r) = ((3.0 * c - 4.0 * l1 + l2) / (2.0 * e), (-3.0 * c + 4.0 * r1 - r2) / (2.0 * e));
            assert!((slope_l - slope_r).abs() < 1e-5, "slope {slope_l} vs {slope_r}");
            let (curv_l, curv_r) = ((c - 2.0 * l1 + l2) / (e * e), (c - 2.0 * r1 + r2) / (e * e));
            assert!((curv_l - curv_r).abs() < 1e-2, "curvature {curv_l} vs {curv_r}");
            for (x, y) in xs.iter().zip(&ys) {
                assert!((t.eval(*x) - y).abs() < 1e-12 && (t.eval(x + 8.0) - y).abs() < 1e-12);
            }
        }
        // A linear table closed over the wrap is continuous there, with a corner.
        let t = linear(&[0.3, 1.1], &[2.0, -1.0], Some(4.0));
        assert!((t.eval(4.3 - 1e-12) - 2.0).abs() < 1e-10 && (t.eval(4.3 + 1e-12) - 2.0).abs() < 1e-10);
    }
}
