//! The mechanism's Jacobian in lifted sparse form, for the implicit methods on large mechanisms
//! ([`OdeSystem::lifted_pattern`](crate::integrate::OdeSystem::lifted_pattern),
//! [`OdeSystem::lifted_jacobian`](crate::integrate::OdeSystem::lifted_jacobian); the integrator's side is
//! rust/integrate/lifted.rs): the KKT matrix `A₀ = [[M, Φqᵀ], [Φq, 0]]` and the derivative `K` of
//! its right-hand side `(g, c)` at fixed `(q̈, λ)`, on one pattern per model (body blocks of bodies
//! that share a constraint or a force, and the entries of `Φq`).
//!
//! `K` is either the stiff part (the clearance joints' and springs' force derivatives of
//! newton.rs, the same ones the dense form maps through the mobility) or the whole derivative:
//! the residual `ρ = (g − Φqᵀλ, c − Φq q̈)` differenced with `q̈`, `λ` held, for a group of bodies
//! at a time — bodies whose columns of `K` share no row (a distance-2 colouring of the
//! bodies' graph, once per model), so a chain takes about 6 × 3 residuals whatever its length,
//! where differencing `f` takes 6 per body.

use super::newton::{stiff_items, Stiff};
use super::MechanismSystem;
use crate::error::Result;
use crate::forces::{ForceElement, Magnitude};
use crate::integrate::LiftedPattern;
use crate::model::Model;

/// Where each part of `A₀` and `K` goes in the lifted pattern, the groups of bodies differenced
/// together, and the scratch of the differencing; built once per run.
pub struct LiftedLayout {
    pattern: LiftedPattern,
    /// Position of `M[i, i]`.
    diag: Vec<usize>,
    /// Per constraint row and entry `k` of its [`crate::constraints::JacRow`], per axis: the
    /// positions of `Φq[r, 3b + c]` and of its transpose.
    phi: Vec<[[usize; 3]; 2]>,
    phi_t: Vec<[[usize; 3]; 2]>,
    /// Per stiff item (newton.rs's order), per (body slot, other body's slot), per axis `c`: the
    /// position of row `3·other` in column `3·body + c` (its three rows follow).
    items: Vec<[[[usize; 3]; 2]; 2]>,
    /// The bodies differenced together, group after group (`group_start` delimits them).
    groups: Vec<u32>,
    group_start: Vec<usize>,
    /// The clearance joints on each body (their finite-difference steps), CSR.
    joint_start: Vec<usize>,
    joints: Vec<u32>,
    // Scratch.
    qdd: Vec<f64>,
    lambda: Vec<f64>,
    base: Vec<f64>,
    probed: Vec<f64>,
    probe: Vec<f64>,
    steps: Vec<f64>,
}

/// The bodies a force element's generalised forces depend on and the bodies they act on.
fn reads_writes(f: &ForceElement) -> ([Option<u32>; 3], [Option<u32>; 2]) {
    let angle = |m: &Magnitude| match m {
        Magnitude::OfAngle(b, _) => Some(*b),
        _ => None,
    };
    match f {
        ForceElement::SpringDamper { a, b, .. } | ForceElement::RotationalSpringDamper { a, b, .. } => ([*a, *b, None], [*a, *b]),
        ForceElement::Force { body, fx, fy, .. } => ([Some(*body), angle(fx), angle(fy)], [Some(*body), None]),
        ForceElement::Torque { body, reaction, magnitude } => ([angle(magnitude), None, None], [Some(*body), *reaction]),
        ForceElement::Motor { body, reaction, .. } => ([Some(*body), *reaction, None], [Some(*body), *reaction]),
    }
}

impl LiftedLayout {
    /// The layout of `model`, whose constraint rows touch the bodies of `jac` (any evaluation).
    pub fn new(model: &Model, jac: &[crate::constraints::JacRow]) -> Self {
        let nb = model.n_bodies();
        let (m, rows) = (3 * nb, model.rows);
        let dim = m + rows;
        // Bodies whose forces or constraint rows depend on each other's state.
        let mut adj: Vec<Vec<u32>> = (0..nb as u32).map(|b| vec![b]).collect();
        let mut pair = |a: Option<u32>, b: Option<u32>| {
            if let (Some(a), Some(b)) = (a, b) {
                adj[a as usize].push(b);
                adj[b as usize].push(a);
            }
        };
        for c in &model.clearance {
            pair(c.bearing, c.journal);
        }
        for f in &model.forces {
            let (reads, writes) = reads_writes(f);
            for w in writes {
                for r in reads {
                    pair(w, r);
                }
            }
        }
        let mut body_rows: Vec<Vec<usize>> = vec![Vec::new(); nb];
        for (r, row) in jac[..rows].iter().enumerate() {
            let bodies = &row.bodies[..row.count as usize];
            for (i, &a) in bodies.iter().enumerate() {
                body_rows[a as usize].push(r);
                for &b in &bodies[i + 1..] {
                    pair(Some(a), Some(b));
                }
            }
        }
        for list in &mut adj {
            list.sort_unstable();
            list.dedup();
        }
        // The pattern, column by column.
        let mut col_start = vec![0];
        let mut row = Vec::new();
        for b in 0..nb {
            for _ in 0..3 {
                row.extend(adj[b].iter().flat_map(|&o| 3 * o as usize..3 * o as usize + 3));
                row.extend(body_rows[b].iter().map(|r| m + r));
                col_start.push(row.len());
            }
        }
        for jr in &jac[..rows] {
            let mut bodies: Vec<u32> = jr.bodies[..jr.count as usize].to_vec();
            bodies.sort_unstable();
            row.extend(bodies.iter().flat_map(|&b| 3 * b as usize..3 * b as usize + 3));
            col_start.push(row.len());
        }
        let find = |i: usize, j: usize| -> usize { col_start[j] + row[col_start[j]..col_start[j + 1]].binary_search(&i).expect("an entry of the lifted pattern") };
        let diag = (0..m).map(|i| find(i, i)).collect();
        let mut phi = vec![[[0; 3]; 2]; rows];
        let mut phi_t = vec![[[0; 3]; 2]; rows];
        for (r, jr) in jac[..rows].iter().enumerate() {
            for k in 0..jr.count as usize {
                let b = 3 * jr.bodies[k] as usize;
                for c in 0..3 {
                    phi[r][k][c] = find(m + r, b + c);
                    phi_t[r][k][c] = find(b + c, m + r);
                }
            }
        }
        let mut stiff_bodies: Vec<u32> = Vec::new();
        let mut items = Vec::new();
        for item in stiff_items(model) {
            let bodies = match item {
                Stiff::Joint(j) => [model.clearance[j].bearing, model.clearance[j].journal],
                Stiff::Force(i) => model.forces[i].stiff_bodies().unwrap_or([None, None]),
            };
            let mut pos = [[[usize::MAX; 3]; 2]; 2];
            for (slot, b) in bodies.iter().enumerate() {
                let Some(b) = b else { continue };
                stiff_bodies.push(*b);
                for (oslot, ob) in bodies.iter().enumerate() {
                    let Some(ob) = ob else { continue };
                    for c in 0..3 {
                        pos[slot][oslot][c] = find(3 * *ob as usize, 3 * *b as usize + c);
                    }
                }
            }
            items.push(pos);
        }
        stiff_bodies.sort_unstable();
        stiff_bodies.dedup();
        // Groups: greedy colouring of the bodies, two bodies apart when their columns share a row
        // (a body's rows: its neighbours' and its constraint rows, keys nb + r).
        let keys = |b: usize| adj[b].iter().map(|&o| o as usize).chain(body_rows[b].iter().map(|r| nb + r));
        let mut holders: Vec<Vec<u32>> = vec![Vec::new(); nb + rows];
        let mut color = vec![usize::MAX; nb];
        let mut seen = vec![usize::MAX; nb + 1];
        for b in 0..nb {
            for key in keys(b) {
                for &o in &holders[key] {
                    seen[color[o as usize]] = b;
                }
            }
            color[b] = (0..).find(|&c| seen[c] != b).unwrap_or(0);
            for key in keys(b) {
                holders[key].push(b as u32);
            }
        }
        let n_colors = color.iter().map(|c| c + 1).max().unwrap_or(0);
        let mut groups = Vec::with_capacity(nb);
        let mut group_start = vec![0];
        for c in 0..n_colors {
            groups.extend((0..nb as u32).filter(|&b| color[b as usize] == c));
            group_start.push(groups.len());
        }
        let mut joint_start = vec![0];
        let mut joints = Vec::new();
        for b in 0..nb as u32 {
            joints.extend((0..model.clearance.len() as u32).filter(|&j| model.clearance[j as usize].bearing == Some(b) || model.clearance[j as usize].journal == Some(b)));
            joint_start.push(joints.len());
        }
        LiftedLayout {
            pattern: LiftedPattern { coords: m, dim, col_start, row, stiff_coords: 3 * stiff_bodies.len() },
            diag,
            phi,
            phi_t,
            items,
            groups,
            group_start,
            joint_start,
            joints,
            qdd: vec![0.0; m],
            lambda: vec![0.0; rows],
            base: vec![0.0; dim],
            probed: vec![0.0; dim],
            probe: vec![0.0; model.state_dim()], // (q, q̇) and any oil temperatures
            steps: vec![0.0; nb],
        }
    }

    /// The number of groups of bodies differenced together (6 residuals each).
    pub fn groups(&self) -> usize {
        self.group_start.len() - 1
    }
}

impl MechanismSystem<'_> {
    /// [`OdeSystem::lifted_pattern`](crate::integrate::OdeSystem::lifted_pattern): the layout is built on the first call of a run.
    pub(super) fn lifted_pattern_of(&mut self) -> Option<LiftedPattern> {
        if self.model.n_bodies() == 0 {
            return None;
        }
        if self.lifted.is_none() {
            self.lifted = Some(Box::new(LiftedLayout::new(self.model, &self.ws.jac)));
        }
        self.lifted.as_ref().map(|l| l.pattern.clone())
    }

    /// [`OdeSystem::lifted_jacobian`](crate::integrate::OdeSystem::lifted_jacobian). Returns the residuals evaluated (counted as right-hand
    /// sides).
    pub(super) fn lifted_values(&mut self, t: f64, y: &[f64], exact: bool, a0: &mut [f64], k_q: &mut [f64], k_v: &mut [f64]) -> Result<usize> {
        let Some(mut layout) = self.lifted.take() else {
            return Err(crate::error::Error::invalid("lifted_jacobian", "layout", "lifted_pattern was not asked for first"));
        };
        let result = self.fill_lifted(&mut layout, t, y, exact, a0, k_q, k_v);
        self.lifted = Some(layout);
        result
    }

    #[allow(clippy::too_many_arguments)]
    fn fill_lifted(&mut self, l: &mut LiftedLayout, t: f64, y: &[f64], exact: bool, a0: &mut [f64], k_q: &mut [f64], k_v: &mut [f64]) -> Result<usize> {
        let model = self.model;
        let m = 3 * model.n_bodies();
        let (col_start, row) = (&l.pattern.col_start, &l.pattern.row);
        self.ws.eval_constraints(model, t, &y[..m], &y[m..2 * m]);
        a0.fill(0.0);
        for (i, &p) in l.diag.iter().enumerate() {
            a0[p] = model.mass[i];
        }
        for (r, jr) in self.ws.jac[..model.rows].iter().enumerate() {
            for k in 0..jr.count as usize {
                for c in 0..3 {
                    a0[l.phi[r][k][c]] = jr.coef[k][c];
                    a0[l.phi_t[r][k][c]] = jr.coef[k][c];
                }
            }
        }
        k_q.fill(0.0);
        k_v.fill(0.0);
        if !exact {
            for (idx, item) in stiff_items(model).enumerate() {
                let bodies = self.stiff_item_bodies(item);
                let d = self.stiff_block(item, t, y);
                for (slot, b) in bodies.iter().enumerate() {
                    if b.is_none() {
                        continue;
                    }
                    for comp in 0..6 {
                        let target = if comp < 3 { &mut *k_q } else { &mut *k_v };
                        for (oslot, ob) in bodies.iter().enumerate() {
                            if ob.is_none() {
                                continue;
                            }
                            let at = l.items[idx][slot][oslot][comp % 3];
                            for o in 0..3 {
                                target[at + o] += d[3 * oslot + o][6 * slot + comp];
                            }
                        }
                    }
                }
            }
            return Ok(0);
        }
        // The whole K: the residual at (t, y) with its own q̈ and λ, then probed group by group.
        self.ws.evaluate(model, &self.memory, t, y)?;
        l.qdd.copy_from_slice(&self.ws.qdd);
        l.lambda.copy_from_slice(&self.ws.lambda);
        self.residual(t, y, &l.qdd, &l.lambda, &mut l.base)?;
        let mut evaluated = 2;
        l.probe.copy_from_slice(y);
        for g in 0..l.groups() {
            let group = &l.groups[l.group_start[g]..l.group_start[g + 1]];
            for comp in 0..6 {
                for (s, &b) in l.steps.iter_mut().zip(group) {
                    let j = if comp < 3 { 3 * b as usize + comp } else { m + 3 * b as usize + comp - 3 };
                    let joints = &l.joints[l.joint_start[b as usize]..l.joint_start[b as usize + 1]];
                    let step = self.difference_step_among(j, y, joints.iter().map(|&i| i as usize));
                    l.probe[j] = y[j] + step;
                    *s = l.probe[j] - y[j]; // the step actually taken
                }
                self.residual(t, &l.probe, &l.qdd, &l.lambda, &mut l.probed)?;
                evaluated += 1;
                let target = if comp < 3 { &mut *k_q } else { &mut *k_v };
                for (&s, &b) in l.steps.iter().zip(group) {
                    let j = if comp < 3 { 3 * b as usize + comp } else { m + 3 * b as usize + comp - 3 };
                    l.probe[j] = y[j];
                    let col = 3 * b as usize + comp % 3;
                    for k in col_start[col]..col_start[col + 1] {
                        target[k] = (l.probed[row[k]] - l.base[row[k]]) / s;
                    }
                }
            }
        }
        Ok(evaluated)
    }

    /// `ρ = (g − Φqᵀλ, c − Φq q̈)` at `(t, y)` with `q̈`, `λ` given, into `out` (`m + rows`).
    fn residual(&mut self, t: f64, y: &[f64], qdd: &[f64], lambda: &[f64], out: &mut [f64]) -> Result<()> {
        let model = self.model;
        let m = 3 * model.n_bodies();
        self.ws.eval_loads(model, &self.memory, t, y)?;
        let (g, rest) = out.split_at_mut(m);
        g.copy_from_slice(&self.ws.force);
        for ((jr, &l), (c, o)) in self.ws.jac[..model.rows].iter().zip(lambda).zip(self.ws.c.iter().zip(rest.iter_mut())) {
            for k in 0..jr.count as usize {
                let b = 3 * jr.bodies[k] as usize;
                for (gc, cf) in g[b..b + 3].iter_mut().zip(&jr.coef[k]) {
                    *gc -= cf * l;
                }
            }
            *o = c - jr.dot(qdd);
        }
        Ok(())
    }
}
