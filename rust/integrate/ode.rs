//! The interface between the integrators and what they integrate: [`OdeSystem`] (the
//! right-hand side `f` and the hooks a mechanism needs: accepted steps, switching points, outputs,
//! the stiff part of the Jacobian) and [`DenseOutput`] (the continuous extension of one accepted
//! step that a method hands back).

use crate::error::Error;

/// A first-order ODE system `ẏ = f(t, y)` with hooks the mechanism needs.
pub trait OdeSystem {
    /// Length of the state vector.
    fn dim(&self) -> usize;
    /// `dy = f(t, y)`. Called for every stage, including stages of steps that get rejected,
    /// so it must not change any state that outlives the call.
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Error>;
    /// Called once after every accepted step `[t0, t1]`, before the outputs inside it are
    /// sampled. `dense` evaluates the step's continuous extension on `[t0, t1]`.
    /// Returns `Ok(true)` when the system changed an internal memory (e.g. recorded the start of
    /// an impact) so that `f(t1, y1)` must be evaluated again (no FSAL reuse).
    fn step_accepted(
        &mut self,
        _t0: f64,
        _y0: &[f64],
        _t1: f64,
        _y1: &[f64],
        _dense: &dyn DenseOutput,
    ) -> Result<bool, Error> {
        Ok(false)
    }
    /// The earliest switching point inside a step `[t0, t1]` that passed the error test: a time
    /// at which `f` stops being smooth (a contact starting or ending, a friction law's corner),
    /// located on `dense`, or
    /// `None`. Called before [`OdeSystem::step_accepted`]; must not change any state. When the
    /// point lies well inside the step, the drivers redo the step so that it ends there, so that
    /// no step straddles it (the error estimates assume a smooth `f`). Default: none.
    fn switching_point(&mut self, _t0: f64, _y0: &[f64], _t1: f64, _y1: &[f64], _dense: &dyn DenseOutput) -> Result<Option<f64>, Error> {
        Ok(None)
    }
    /// Called at every requested output time with the (interpolated) state.
    fn output(&mut self, t: f64, y: &[f64]) -> Result<(), Error>;
    /// For a second-order system, `y = (q, v)` and `f = (v, a(t, q, v))` with `q`, `v` of length
    /// `m = dim/2` (or `y = (q, v, z)`: [`OdeSystem::first_order_states`]): write an approximation of `∂a/∂q` and `∂a/∂v` (each `m × m`, column-major)
    /// and return `Ok(true)`. Used for the Newton matrices of RADAU5, whose simplified Newton
    /// iteration converges with any good approximation of the stiff part. The default,
    /// `Ok(false)`, makes it difference the whole `f` instead.
    fn acceleration_jacobian(&mut self, _t: f64, _y: &[f64], _a_q: &mut [f64], _a_v: &mut [f64]) -> Result<bool, Error> {
        Ok(false)
    }
    /// A second-order system whose accelerations solve a sparse linear system
    /// `A₀ (q̈, λ) = b(t, q, q̇)` (a mechanism: `A₀ = [[M, Φqᵀ], [Φq, 0]]`, `λ` its multipliers)
    /// can hand the implicit methods its Jacobian in *lifted* form instead of the dense
    /// `∂q̈/∂(q, q̇)` of [`OdeSystem::acceleration_jacobian`]: `A₀` and `K_x = ∂b/∂x` (`x` = `q` or
    /// `q̇`, at fixed `(q̈, λ)`), both sparse, with `∂q̈/∂x = [I 0] A₀⁻¹ K_x`. The Newton matrices
    /// then stay sparse (`lifted.rs`): their cost grows with the mechanism's size, not its cube.
    /// This returns the pattern both live on, once per run, or `None` (the default: no lifted
    /// form).
    fn lifted_pattern(&mut self) -> Option<LiftedPattern> {
        None
    }
    /// The values of `A₀`, `K_q` and `K_v` at `(t, y)` on the pattern of
    /// [`OdeSystem::lifted_pattern`] (each of its length; entries outside a matrix's own
    /// pattern zero). With `exact`, `K` is the whole derivative (for RODAS4, whose order needs
    /// the exact Jacobian, and RADAU5's fallback); without, its stiff part, as in
    /// [`OdeSystem::acceleration_jacobian`] (the same `∂q̈/∂x` then). Returns the right-hand
    /// sides it evaluated (counted in the statistics).
    fn lifted_jacobian(&mut self, _t: f64, _y: &[f64], _exact: bool, _a0: &mut [f64], _k_q: &mut [f64], _k_v: &mut [f64]) -> Result<usize, Error> {
        Err(Error::invalid("lifted_jacobian", "system", "this system has no lifted Jacobian"))
    }
    /// `k`: the state is `y = (q, v, z)` with `k` first-order states `z` after the second-order
    /// part (a heated joint's oil temperature). [`OdeSystem::acceleration_jacobian`] then covers
    /// `q`, `v` of length `m = (dim − k)/2` and [`OdeSystem::border_jacobian`] the rest. Default 0.
    fn first_order_states(&self) -> usize {
        0
    }
    /// The Jacobian's border for the states `z` ([`OdeSystem::first_order_states`]), asked right
    /// after [`OdeSystem::acceleration_jacobian`] at the same `(t, y)`: `a_z = ∂a/∂z` (`m × k`,
    /// column-major) and `z_y = ∂ż/∂y` (`k × dim`, row-major).
    fn border_jacobian(&mut self, _t: f64, _y: &[f64], _a_z: &mut [f64], _z_y: &mut [f64]) -> Result<(), Error> {
        Ok(())
    }
    /// Forward-difference step for component `j` of `y` when the implicit methods difference
    /// `f`. Default (Hairer): `√(ε_mach · max(1e-5, |y_j|))`. A system whose `f` varies on a
    /// scale much finer than `|y_j|` (a journal in a µm clearance) returns a smaller one.
    fn difference_step(&self, j: usize, y: &[f64]) -> f64 {
        (f64::EPSILON * 1e-5f64.max(y[j].abs())).sqrt()
    }
}

/// The pattern of a second-order system's Jacobian in lifted form
/// ([`OdeSystem::lifted_pattern`]): a square `(m + c) × (m + c)` pattern, `m` = half the state
/// (the coordinates `q`), `c` the multipliers, column by column with ascending row indices. It
/// holds `A₀` and, in its first `m` columns, `K_q` and `K_v` (the Newton matrices in lifted form
/// are `A₀` less a combination of the two: `lifted.rs`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LiftedPattern {
    /// `m`: the coordinates; the state is `(q, q̇)`, `2m` long.
    pub coords: usize,
    /// `m + c`.
    pub dim: usize,
    /// Where each column's entries start in `row` (`dim + 1` entries).
    pub col_start: Vec<usize>,
    pub row: Vec<usize>,
    /// Coordinates whose columns of `K` are structurally non-zero with `exact = false` (the
    /// stiff part: what the dense structured form would factorise).
    pub stiff_coords: usize,
}

/// Continuous extension of one accepted step.
pub trait DenseOutput {
    /// Interval `[t0, t1]` the extension covers.
    fn interval(&self) -> (f64, f64);
    /// The variable the polynomial is written in, at `t`. Default: `θ = (t − t0)/(t1 − t0)`
    /// (0 for an empty interval).
    fn fraction(&self, t: f64) -> f64 {
        let (t0, t1) = self.interval();
        if t1 != t0 { (t - t0) / (t1 - t0) } else { 0.0 }
    }
    /// Component `i` of the polynomial at `s` = [`fraction`](DenseOutput::fraction)`(t)`.
    fn component(&self, s: f64, i: usize) -> f64;
    /// State at `t` in `[t0, t1]` (extrapolated outside), written to `out` (length `dim`).
    /// Allocates nothing.
    fn eval(&self, t: f64, out: &mut [f64]) {
        let s = self.fraction(t);
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.component(s, i);
        }
    }
    /// Component `i` of the state at `t` (what [`eval`](DenseOutput::eval) writes to
    /// `out[i]`), for a caller that needs one coordinate of a large state.
    fn eval_component(&self, t: f64, i: usize) -> f64 {
        self.component(self.fraction(t), i)
    }
    /// Components `idx` of the state at `t`, each into `out[i]` (the other entries of `out`
    /// untouched): [`eval_component`](DenseOutput::eval_component) for several coordinates
    /// with one call through the trait object and `θ` computed once.
    fn eval_components(&self, t: f64, idx: &[usize], out: &mut [f64]) {
        let s = self.fraction(t);
        for &i in idx {
            out[i] = self.component(s, i);
        }
    }
    /// `f(t1, y1)` at the step's end when the method computed it exactly (the explicit
    /// Runge–Kutta methods' FSAL stage, with the memory the step was integrated with), so that
    /// a system needing the rate there need not evaluate `f` again. Default: `None`.
    fn end_rate(&self) -> Option<&[f64]> {
        None
    }
}
