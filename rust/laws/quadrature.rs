//! Gauss–Legendre quadrature on [a, b]: constant nodes and weights (8, 16 and 32 points,
//! computed with 40-digit arithmetic and rounded to the nearest f64) and allocation-free integration helpers.
//!
//! An n-point rule integrates polynomials of degree ≤ 2n − 1 exactly.

/// A Gauss–Legendre rule: nodes on [−1, 1] (ascending) and their weights.
#[derive(Clone, Copy, Debug)]
pub struct GaussLegendre {
    pub nodes: &'static [f64],
    pub weights: &'static [f64],
}

/// 8-point rule (exact to degree 15).
pub const GL8: GaussLegendre = GaussLegendre { nodes: &GL8_NODES, weights: &GL8_WEIGHTS };
/// 16-point rule (exact to degree 31).
pub const GL16: GaussLegendre = GaussLegendre { nodes: &GL16_NODES, weights: &GL16_WEIGHTS };
/// 32-point rule (exact to degree 63).
pub const GL32: GaussLegendre = GaussLegendre { nodes: &GL32_NODES, weights: &GL32_WEIGHTS };

impl GaussLegendre {
    /// Number of points.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// True for a rule without points (none of the provided rules).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// ∫ₐᵇ f(x) dx. Returns 0 for a == b; a > b gives the signed (negated) integral.
    pub fn integrate<F: FnMut(f64) -> f64>(&self, a: f64, b: f64, mut f: F) -> f64 {
        let half = 0.5 * (b - a);
        let mid = 0.5 * (a + b);
        let mut sum = 0.0;
        for (x, w) in self.nodes.iter().zip(self.weights.iter()) {
            sum += w * f(mid + half * x);
        }
        sum * half
    }

    /// ∫ₐᵇ f(x) dx for a pair-valued integrand (e.g. both force components at once).
    pub fn integrate2<F: FnMut(f64) -> (f64, f64)>(&self, a: f64, b: f64, mut f: F) -> (f64, f64) {
        let half = 0.5 * (b - a);
        let mid = 0.5 * (a + b);
        let (mut s0, mut s1) = (0.0, 0.0);
        for (x, w) in self.nodes.iter().zip(self.weights.iter()) {
            let (f0, f1) = f(mid + half * x);
            s0 += w * f0;
            s1 += w * f1;
        }
        (s0 * half, s1 * half)
    }
}

/// ∫ₐᵇ f(x) dx with the 16-point rule.
pub fn integrate<F: FnMut(f64) -> f64>(a: f64, b: f64, f: F) -> f64 {
    GL16.integrate(a, b, f)
}

/// Gauss–Legendre nodes on [−1, 1], 8 points, ascending.
pub const GL8_NODES: [f64; 8] = [
    -0.9602898564975363,
    -0.7966664774136267,
    -0.525532409916329,
    -0.1834346424956498,
    0.1834346424956498,
    0.525532409916329,
    0.7966664774136267,
    0.9602898564975363,
];
/// Gauss–Legendre weights matching [`GL8_NODES`].
pub const GL8_WEIGHTS: [f64; 8] = [
    0.10122853629037626,
    0.22238103445337448,
    0.31370664587788727,
    0.362683783378362,
    0.362683783378362,
    0.31370664587788727,
    0.22238103445337448,
    0.10122853629037626,
];
/// Gauss–Legendre nodes on [−1, 1], 16 points, ascending.
pub const GL16_NODES: [f64; 16] = [
    -0.9894009349916499,
    -0.9445750230732326,
    -0.8656312023878318,
    -0.755404408355003,
    -0.6178762444026438,
    -0.45801677765722737,
    -0.2816035507792589,
    -0.09501250983763744,
    0.09501250983763744,
    0.2816035507792589,
    0.45801677765722737,
    0.6178762444026438,
    0.755404408355003,
    0.8656312023878318,
    0.9445750230732326,
    0.9894009349916499,
];
/// Gauss–Legendre weights matching [`GL16_NODES`].
pub const GL16_WEIGHTS: [f64; 16] = [
    0.027152459411754096,
    0.062253523938647894,
    0.09515851168249279,
    0.12462897125553388,
    0.14959598881657674,
    0.16915651939500254,
    0.18260341504492358,
    0.1894506104550685,
    0.1894506104550685,
    0.18260341504492358,
    0.16915651939500254,
    0.14959598881657674,
    0.12462897125553388,
    0.09515851168249279,
    0.062253523938647894,
    0.027152459411754096,
];
/// Gauss–Legendre nodes on [−1, 1], 32 points, ascending.
pub const GL32_NODES: [f64; 32] = [
    -0.9972638618494816,
    -0.9856115115452684,
    -0.9647622555875064,
    -0.9349060759377397,
    -0.8963211557660521,
    -0.84936761373257,
    -0.7944837959679424,
    -0.7321821187402897,
    -0.6630442669302152,
    -0.5877157572407623,
    -0.5068999089322294,
    -0.42135127613063533,
    -0.33186860228212767,
    -0.23928736225213706,
    -0.1444719615827965,
    -0.04830766568773832,
    0.04830766568773832,
    0.1444719615827965,
    0.23928736225213706,
    0.33186860228212767,
    0.42135127613063533,
    0.5068999089322294,
    0.5877157572407623,
    0.6630442669302152,
    0.7321821187402897,
    0.7944837959679424,
    0.84936761373257,
    0.8963211557660521,
    0.9349060759377397,
    0.9647622555875064,
    0.9856115115452684,
    0.9972638618494816,
];
/// Gauss–Legendre weights matching [`GL32_NODES`].
pub const GL32_WEIGHTS: [f64; 32] = [
    0.007018610009470096,
    0.01627439473090567,
    0.02539206530926206,
    0.03427386291302143,
    0.04283589802222668,
    0.050998059262376175,
    0.058684093478535544,
    0.06582222277636185,
    0.0723457941088485,
    0.07819389578707031,
    0.08331192422694675,
    0.08765209300440381,
    0.09117387869576389,
    0.09384439908080457,
    0.09563872007927486,
    0.0965400885147278,
    0.0965400885147278,
    0.09563872007927486,
    0.09384439908080457,
    0.09117387869576389,
    0.08765209300440381,
    0.08331192422694675,
    0.07819389578707031,
    0.0723457941088485,
    0.06582222277636185,
    0.058684093478535544,
    0.050998059262376175,
    0.04283589802222668,
    0.03427386291302143,
    0.02539206530926206,
    0.01627439473090567,
    0.007018610009470096,
];

#[cfg(test)]
mod tests {
    use super::*;

    const RULES: [GaussLegendre; 3] = [GL8, GL16, GL32];

    #[test]
    fn weights_sum_to_two_and_nodes_symmetric() {
        for r in RULES {
            let s: f64 = r.weights.iter().sum();
            assert!((s - 2.0).abs() < 1e-14, "n = {}: Σw = {s}", r.len());
            let n = r.len();
            for i in 0..n {
                assert!((r.nodes[i] + r.nodes[n - 1 - i]).abs() < 1e-15);
                assert!((r.weights[i] - r.weights[n - 1 - i]).abs() < 1e-15);
                assert!(r.weights[i] > 0.0);
            }
        }
    }

    /// ∫₋₁¹ xᵏ dx = 2/(k+1) for even k, 0 for odd k.
    fn exact_monomial(k: i32) -> f64 {
        if k % 2 == 1 { 0.0 } else { 2.0 / (k as f64 + 1.0) }
    }

    #[test]
    fn exact_to_degree_2n_minus_1_not_2n() {
        for r in RULES {
            let n = r.len() as i32;
            for k in 0..2 * n {
                let q = r.integrate(-1.0, 1.0, |x| x.powi(k));
                assert!((q - exact_monomial(k)).abs() < 1e-14, "n = {n}, k = {k}: {q}");
            }
            // Degree 2n is not integrated exactly: the test above can fail. The error for x^{2n} is
            // 2^{2n+1}(n!)⁴/((2n+1)((2n)!)²): 4.7e-5 (n = 8), 7.2e-10 (n = 16), ~1e-19 (n = 32,
            // below rounding, so not checked).
            if n <= 16 {
                let k = 2 * n;
                let q = r.integrate(-1.0, 1.0, |x| x.powi(k));
                assert!((q - exact_monomial(k)).abs() > 1e-10, "n = {n}: degree 2n exact?");
            }
        }
    }

    #[test]
    fn shifted_interval_polynomial() {
        // ∫_1^3 (x³ − 2x + 5) dx = [x⁴/4 − x² + 5x]_1^3 = (81/4 − 9 + 15) − (1/4 − 1 + 5) = 22
        let q = GL8.integrate(1.0, 3.0, |x| x * x * x - 2.0 * x + 5.0);
        assert!((q - 22.0).abs() < 1e-13);
        let (a, b) = GL16.integrate2(0.0, std::f64::consts::PI, |x| (x.sin(), x.cos()));
        assert!((a - 2.0).abs() < 1e-14 && b.abs() < 1e-14);
        assert_eq!(integrate(2.0, 2.0, |x| x), 0.0);
    }
}
