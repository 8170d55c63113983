//! The rank of the constraint Jacobian Φq at one pose, for the failure paths only (assembly,
//! following the drivers, a run whose steps underflow): which joints and drivers have dependent
//! rows, and what that means in the mechanism's words (docs/physics.md §1, "Lock-ups and
//! over-constraint"). A dense SVD of the scaled Φq: never called from the right-hand side.

use nalgebra::DMatrix;

use crate::constraints::{BodyKin, Constraint, JacRow, V2};
use crate::model::Model;

/// σ_min/σ_max of the scaled Φq below which its rows count as dependent (a lock-up); above it a
/// step-size underflow has another cause. At a dead centre that a driver pushes into, the last
/// pose reached lies within ~1e-13 s of it (σ ∝ the square root of the distance): measured
/// 2e-6 … 8e-8 (tests/python/test_lockups.py); sound poses of the shipped models stay ≥ 0.0195.
pub const DEPENDENT_RATIO: f64 = 1e-3;

/// What the singular value decomposition of Φq found.
#[derive(Debug, Clone, PartialEq)]
pub struct RankReport {
    /// Smallest singular value of the scaled Φq over its largest (0 for more rows than coordinates).
    pub ratio: f64,
    /// Constraint equations and coordinates.
    pub rows: usize,
    pub coordinates: usize,
    /// Indices into `model.constraints` of the constraints taking part in the dependence: the
    /// drivers, then the joints, each the largest share first.
    pub constraints: Vec<usize>,
    /// What the pose looks like, in the mechanism's words: "'crank' and 'rod' aligned", "'rod'
    /// perpendicular to the guide of prismatic joint 'g'".
    pub geometry: Vec<String>,
}

impl RankReport {
    /// Whether the rows are dependent (a lock-up or over-constraint).
    pub fn deficient(&self) -> bool {
        self.rows > self.coordinates || self.ratio <= DEPENDENT_RATIO
    }

    /// The constraints' names as a list: "revolute joint 'a', revolute joint 'b' and driver 'd'".
    pub fn names(&self, model: &Model) -> String {
        let names: Vec<&str> = self.constraints.iter().map(|&c| model.constraint_names[c].as_str()).collect();
        match names.len() {
            0 => "no constraint".into(),
            1 => names[0].into(),
            k => format!("{} and {}", names[..k - 1].join(", "), names[k - 1]),
        }
    }

    /// The drivers among the dependent constraints.
    fn drivers<'m>(&self, model: &'m Model) -> Vec<&'m str> {
        self.constraints.iter().filter(|&&c| matches!(model.constraints[c], Constraint::Driver { .. })).map(|&c| model.constraint_names[c].as_str()).collect()
    }

    /// What an over-constrained mechanism (more equations than coordinates, or dependent rows at
    /// the pose given) means.
    pub fn over_constraint(&self, model: &Model) -> String {
        let (count, ratio) = if self.rows > self.coordinates {
            (format!("{} constraint equations for {} coordinates: ", self.rows, self.coordinates), String::new())
        } else {
            (String::new(), format!(", σ_min/σ_max = {:.1e}", self.ratio))
        };
        let drivers = self.drivers(model);
        let what = if drivers.len() > 1 {
            format!("{} prescribe motions that the joints tie to each other: drive one of them and leave the others free, or free a joint (e.g. a clearance joint)", list(&drivers))
        } else {
            "a joint or driver repeats what the others already fix: remove it, or free a joint (e.g. a clearance joint)".into()
        };
        format!("{count}the mechanism is over-constrained: {} are redundant (their rows are dependent{ratio}); {what}", self.names(model))
    }

    /// What a loss of rank at time `t` of a motion that follows the drivers means: a dead centre.
    pub fn lock_up(&self, model: &Model, t: f64) -> String {
        let drivers = self.drivers(model);
        let aligned = if self.geometry.is_empty() {
            String::new()
        } else {
            format!("{}: ", list(&self.geometry.iter().map(String::as_str).collect::<Vec<_>>()))
        };
        let who = match drivers.len() {
            0 => "the mechanism cannot move past it".to_string(),
            1 => format!("{} cannot drive the mechanism past it", drivers[0]),
            _ => format!("{} cannot drive the mechanism past it", list(&drivers)),
        };
        format!(
            "{aligned}dead centre (lock-up) at t = {t:.9} s; {who}: the constraint Jacobian loses rank there (σ_min/σ_max = {:.1e}) in the rows of {}; check the link lengths and the drivers' laws (a loop that cannot close beyond this pose, or a driver that pushes into a toggle position)",
            self.ratio,
            self.names(model)
        )
    }
}

fn list(items: &[&str]) -> String {
    match items.len() {
        0 => String::new(),
        1 => items[0].into(),
        k => format!("{} and {}", items[..k - 1].join(", "), items[k - 1]),
    }
}

/// The mechanism's length scale \[m\]: the extent of the bodies' positions and joint points at
/// `kin` (at least 1 mm), by which rotations are scaled to lengths.
fn length_scale(model: &Model, kin: &[BodyKin]) -> f64 {
    let (mut lo, mut hi) = (V2::new(f64::INFINITY, f64::INFINITY), V2::new(f64::NEG_INFINITY, f64::NEG_INFINITY));
    let mut grow = |p: V2| {
        lo = V2::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = V2::new(hi.x.max(p.x), hi.y.max(p.y));
    };
    for k in kin {
        grow(k.r());
    }
    for c in &model.constraints {
        if let Constraint::Revolute { a, sa, .. } = c {
            grow(a.map_or(BodyKin::GROUND, |i| kin[i as usize]).point(*sa));
        }
    }
    let extent = (hi.x - lo.x).max(0.0) + (hi.y - lo.y).max(0.0);
    if extent.is_finite() { extent.max(1e-3) } else { 1.0 }
}

/// Analyse Φq (`jac`, the rows of `model.constraints` at the pose `kin`). Rows are scaled to unit
/// length and rotations by the mechanism's size, so that the ratio compares like with like.
pub fn analyse(model: &Model, jac: &[JacRow], kin: &[BodyKin]) -> RankReport {
    let m = jac.len();
    let n = 3 * model.n_bodies();
    let scale = length_scale(model, kin);
    // Padded with zero columns to a square matrix when m > n, so that U holds Φq's left null space.
    let cols = n.max(m);
    let mut a = DMatrix::<f64>::zeros(m, cols);
    for (r, row) in jac.iter().enumerate() {
        for k in 0..row.count as usize {
            let o = 3 * row.bodies[k] as usize;
            let c = row.coef[k];
            a[(r, o)] += c[0];
            a[(r, o + 1)] += c[1];
            a[(r, o + 2)] += c[2] / scale;
        }
        let norm = a.row(r).norm();
        if norm > 0.0 {
            a.row_mut(r).scale_mut(1.0 / norm);
        }
    }
    let owner = row_owners(model, m);
    if m == 0 || !a.iter().all(|v| v.is_finite()) {
        return RankReport { ratio: f64::NAN, rows: m, coordinates: n, constraints: Vec::new(), geometry: Vec::new() };
    }
    let svd = a.svd(true, false);
    let Some(u) = svd.u else { unreachable!("the SVD was asked for U") };
    let s = &svd.singular_values;
    let s_max = s.iter().fold(0.0f64, |x, v| x.max(*v));
    let s_min = s.iter().fold(f64::INFINITY, |x, v| x.min(*v));
    let ratio = if s_max > 0.0 { s_min / s_max } else { 0.0 };
    // The left singular vectors of the dependence: all those at round-off, or the weakest one.
    let floor = (1e-9 * s_max).max(s_min * (1.0 + 1e-9));
    let mut share = vec![0.0f64; model.constraints.len()];
    for (k, &sk) in s.iter().enumerate() {
        if sk <= floor {
            for r in 0..m {
                share[owner[r]] += u[(r, k)] * u[(r, k)];
            }
        }
    }
    let top = share.iter().fold(0.0f64, |x, v| x.max(*v));
    let mut constraints: Vec<usize> = (0..share.len()).filter(|&c| share[c] > 1e-3 * top && share[c] > 1e-6).collect();
    // Drivers first (what the user set going), then the joints, each by their share.
    let driver = |c: usize| matches!(model.constraints[c], Constraint::Driver { .. });
    constraints.sort_by(|&x, &y| driver(y).cmp(&driver(x)).then(share[y].total_cmp(&share[x])).then(x.cmp(&y)));
    let geometry = geometry(model, kin, &constraints);
    RankReport { ratio, rows: m, coordinates: n, constraints, geometry }
}

/// The index into `model.constraints` of each of the `m` rows.
fn row_owners(model: &Model, m: usize) -> Vec<usize> {
    let mut owner = Vec::with_capacity(m);
    for (c, con) in model.constraints.iter().enumerate() {
        owner.extend(std::iter::repeat_n(c, con.rows()));
    }
    owner.resize(m, model.constraints.len().saturating_sub(1));
    owner
}

/// The dead centre's geometry among the `dependent` constraints: bodies joined by a revolute
/// joint whose lines through their dependent joints' points are parallel (within 2°), and
/// bodies whose line stands perpendicular to the guide of a prismatic joint their neighbour
/// slides on.
fn geometry(model: &Model, kin: &[BodyKin], dependent: &[usize]) -> Vec<String> {
    let at = |b: Option<u32>| b.map_or(BodyKin::GROUND, |i| kin[i as usize]);
    // Per body, the global points of its dependent revolute joints.
    let mut points: Vec<Vec<V2>> = vec![Vec::new(); model.n_bodies()];
    let mut links: Vec<(u32, u32)> = Vec::new();
    for &c in dependent {
        if let Constraint::Revolute { a, sa, b, sb, .. } = &model.constraints[c] {
            for (body, s) in [(a, sa), (b, sb)] {
                if let Some(i) = body {
                    points[*i as usize].push(at(*body).point(*s));
                }
            }
            if let (Some(i), Some(j)) = (a, b) {
                links.push((*i, *j));
            }
        }
    }
    let line = |b: u32| -> Option<V2> {
        let p = &points[b as usize];
        (p.len() >= 2).then(|| p[1].sub(p[0])).filter(|d| d.norm() > 0.0)
    };
    let small = 2f64.to_radians().sin();
    let name = |b: u32| &model.body_names[b as usize];
    let mut out = Vec::new();
    for &(i, j) in &links {
        if let (Some(u), Some(v)) = (line(i), line(j)) {
            if (u.cross(v) / (u.norm() * v.norm())).abs() < small {
                out.push(format!("'{}' and '{}' aligned", name(i), name(j)));
            }
        }
    }
    for &c in dependent {
        if let Constraint::Prismatic { a, u_perp, b: slider, .. } = &model.constraints[c] {
            let normal = at(*a).rot(*u_perp);
            for &(i, j) in &links {
                let other = if i == *slider { j } else if j == *slider { i } else { continue };
                if let Some(u) = line(other) {
                    if (u.cross(normal) / (u.norm() * normal.norm())).abs() < small {
                        out.push(format!("'{}' perpendicular to the guide of {}", name(other), model.constraint_names[c]));
                    }
                }
            }
        }
    }
    out
}
