//! Property-based fuzzing of the force laws, the clearance-joint force, the KKT solve and the
//! full right-hand side (issue "Hard cases and bad input"): on finite input nothing panics and
//! nothing returns NaN or ±∞ (a singular KKT matrix may be reported as an error, never as NaN).
//!
//! Default: 256 cases per property, a few seconds in total (`cargo test --test fuzz_laws`).
//! Longer campaigns: `PROPTEST_CASES=200000 cargo test --release --test fuzz_laws` (see
//! docs/hard_cases.md for the campaign that was run and how long it took).

use clearsim::clearance::{ClearanceJoint, Film, ImpactMemory, JointKinematics};
use clearsim::constraints::{BodyKin, JacRow, V2};
use clearsim::kkt::KktSolver;
use clearsim::laws::*;
use clearsim::description::*;
use clearsim::model::Model;
use clearsim::system::Workspace;
use proptest::prelude::*;

fn config() -> ProptestConfig {
    // PROPTEST_CASES in the environment overrides the default case count.
    let cases = std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(256);
    ProptestConfig { cases, failure_persistence: None, ..ProptestConfig::default() }
}

/// A finite f64 spread over many decades, both signs, with exact zeros and tiny values.
fn wide() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => -1e6f64..1e6,
        2 => (-12i32..7, -1.0f64..1.0).prop_map(|(k, m)| m * 10f64.powi(k)),
        1 => Just(0.0),
        1 => prop::sample::select(vec![5e-324, -5e-324, 1e-300, -1e-300, f64::MIN_POSITIVE, 1e300, -1e300]),
    ]
}

/// A finite rate (speed, ε̇, wedge) up to physically absurd but non-overflowing magnitudes:
/// the film pressure scales with 6μ(R/c)² × rate, so rates near 1e300 overflow legitimately.
fn rate() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => -1e4f64..1e4,
        2 => (-12i32..7, -1.0f64..1.0).prop_map(|(k, m)| m * 10f64.powi(k)),
        1 => Just(0.0),
        1 => prop::sample::select(vec![5e-324, -5e-324, 1e-300, -1e-300, f64::MIN_POSITIVE]),
    ]
}

/// A positive f64 over decades in [10^lo, 10^hi).
fn pos(lo: i32, hi: i32) -> impl Strategy<Value = f64> {
    (lo..hi, 1.0f64..10.0).prop_map(|(k, m)| m * 10f64.powi(k))
}

/// Eccentricity ratios that stress the film formulas: 0, tiny, around ε0, near and beyond 1.
fn eps_ratio() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => 0.0f64..1.2,
        1 => (-30i32..0, 1.0f64..10.0).prop_map(|(k, m)| m * 10f64.powi(k)),
        1 => (1i32..13).prop_map(|k| 1.0 - 10f64.powi(-k)),
        1 => prop::sample::select(vec![0.0, 5e-324, 2e-6, 1.0, 1.0 + 1e-12, 3.0, 1e6, -0.5]),
    ]
}

fn normal_law() -> impl Strategy<Value = NormalLaw> {
    prop::sample::select(vec![NormalLaw::Hertz, NormalLaw::LankaraniNikravesh, NormalLaw::HuntCrossley, NormalLaw::Flores])
}

fn film_model() -> impl Strategy<Value = FilmModel> {
    prop::sample::select(vec![FilmModel::LongBearing, FilmModel::ShortBearing, FilmModel::LongBearingPaperClosedForm, FilmModel::Finite])
}

/// The finite bearing's table for every random geometry (one table: building one per random L/D
/// would take seconds each; the table's evaluation is what is fuzzed).
fn table() -> Option<&'static clearsim::laws::bearing_finite::FiniteBearingTable> {
    Some(clearsim::laws::bearing_finite_cache::table_for(0.4, clearsim::laws::FilmSupply::WidestGap))
}

fn geometry() -> impl Strategy<Value = BearingGeometry> {
    (pos(-4, 1), pos(-4, 0), pos(-7, -2), pos(-3, 0))
        .prop_map(|(viscosity, journal_radius, clearance, length)| BearingGeometry { viscosity, journal_radius, clearance, length })
}

fn finite2(f: (f64, f64)) -> bool {
    f.0.is_finite() && f.1.is_finite()
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn contact_force_finite_and_non_negative(
        law in normal_law(), k in pos(3, 12), n in 1.0f64..3.0, ce in 0.01f64..=1.0, floor in pos(-9, 0),
        delta in rate(), delta_dot in rate(), impact in wide(),
    ) {
        let c = ContactLaw { line: None, law, stiffness: k, exponent: n, restitution: ce, impact_speed_floor: floor };
        let f = c.normal_force(delta, delta_dot, impact);
        prop_assert!(f.is_finite(), "F_N = {f}");
        prop_assert!(f >= 0.0, "contact pulls: {f}");
        if delta <= 0.0 { prop_assert_eq!(f, 0.0); }
    }

    #[test]
    fn stiffness_finite_for_valid_geometry(r_j in pos(-4, 0), c in pos(-7, -2), e in pos(9, 12), nu in -0.9f64..0.49) {
        let r_b = r_j + c;
        prop_assume!(r_b > r_j);
        let k1 = stiffness_internal(r_b, r_j, e, nu, e, nu);
        let k2 = stiffness_paper_printed(r_b, r_j, e, nu, e, nu);
        prop_assert!(k1.is_finite() && k1 > 0.0 && k2.is_finite() && k2 > 0.0, "{k1} {k2}");
        prop_assert!(k1 >= k2);
    }

    #[test]
    fn friction_bounded_and_opposes_slip(cf in 0.0f64..2.0, v0 in pos(-8, -3), ratio in 1.0001f64..1e4, fnorm in 0.0f64..1e9, v in wide()) {
        let f = ModifiedCoulomb { friction_coefficient: cf, v0, v1: v0 * ratio };
        let cd = f.dynamic_correction(v);
        prop_assert!((0.0..=1.0).contains(&cd));
        let ft = f.tangential_force(fnorm, v);
        prop_assert!(ft.is_finite());
        prop_assert!(ft.abs() <= cf * fnorm * (1.0 + 1e-12));
        prop_assert!(ft * v <= 0.0, "friction drives the slip: F_t = {ft}, v_t = {v}");
    }

    #[test]
    fn film_force_finite(model in film_model(), g in geometry(), eps in eps_ratio(), eps_dot in rate(), wedge in rate()) {
        let s = FilmState { eps, eps_dot, wedge };
        let f = film_force(model, &g, s, table());
        prop_assert!(finite2(f), "{model:?} {g:?} {s:?}: {f:?}");
        let q = long_bearing_force_quadrature(&g, s);
        prop_assert!(finite2(q), "quadrature {g:?} {s:?}: {q:?}");
    }

    #[test]
    fn film_force_vanishes_without_relative_motion(model in film_model(), g in geometry(), eps in 0.0f64..0.99) {
        let f = film_force(model, &g, FilmState { eps, eps_dot: 0.0, wedge: 0.0 }, table());
        prop_assert_eq!(f, (0.0, 0.0));
    }

    #[test]
    fn transition_weights_partition_unity(e in wide(), c in pos(-7, -2), frac in 0.0f64..0.5, eps in wide(), eps0 in 0.0f64..1e-3, m in 0.01f64..0.99) {
        let (wf, wd) = transition_weights(e, c, frac * c);
        prop_assert!((0.0..=1.0).contains(&wf) && (0.0..=1.0).contains(&wd));
        prop_assert!((wf + wd - 1.0).abs() < 1e-12);
        let s = small_eccentricity_scale(eps, eps0, m);
        prop_assert!(s.is_finite() && (0.0..=1.0).contains(&s), "scale {s}");
        let fe = film_eps(eps, 0.99);
        prop_assert!((0.0..=0.99).contains(&fe));
    }
}

// ------------------------------------------------------------------ clearance joint force

fn body() -> impl Strategy<Value = BodyKin> {
    (-1.0f64..1.0, -1.0f64..1.0, -10.0f64..10.0, wide(), wide(), -1e4f64..1e4).prop_map(|(x, y, th, vx, vy, w)| {
        let vx = vx.clamp(-1e4, 1e4);
        let vy = vy.clamp(-1e4, 1e4);
        BodyKin::new(&[x, y, th], &[vx, vy, w])
    })
}

fn joint(lubricated: bool, law: NormalLaw, film: FilmModel, c: f64, r_j: f64, ce: f64, cf: f64) -> ClearanceJoint {
    let k = stiffness_internal(r_j + c, r_j, 207e9, 0.3, 207e9, 0.3);
    ClearanceJoint {
        name: "J".into(),
        bearing: Some(0),
        bearing_point: V2::new(0.05, 0.0),
        journal: Some(1),
        journal_point: V2::new(-0.06, 0.0),
        journal_radius: r_j,
        bearing_radius: r_j + c,
        clearance: c,
        contact: ContactLaw { line: None, law, stiffness: k, exponent: 1.5, restitution: ce, impact_speed_floor: 1e-3 },
        friction: ModifiedCoulomb { friction_coefficient: cf, v0: 1e-4, v1: 1e-2 },
        film: lubricated.then_some(Film {
            model: film,
            table: if film == FilmModel::Finite { table() } else { None },
            geometry: BearingGeometry { viscosity: 0.04, journal_radius: r_j, clearance: c, length: 0.05 },
            eps0: 2e-6,
            m: 0.5,
            e0: 0.05 * c,
            eps_max: 0.99,
            mixed: None,
            heat: None,
            mass_conserving: false,
        }),
        guide_normal: None,
        penetration_limit: c.max(0.05 * r_j),
        wear: None,
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn clearance_force_finite(
        lub in any::<bool>(), law in normal_law(), film in film_model(),
        c in pos(-6, -2), r_j in pos(-3, -1), ce in 0.05f64..=1.0, cf in 0.0f64..0.8,
        bearing in body(), eps in eps_ratio(), in_contact in any::<bool>(), impact in wide(),
        seed in (-10.0f64..10.0, 0.0f64..std::f64::consts::TAU, -1e3f64..1e3, -1e3f64..1e3, -1e4f64..1e4),
    ) {
        let j = joint(lub, law, film, c, r_j, ce, cf);
        // Journal placed at eccentricity ratio `eps` from the bearing centre.
        let centre = bearing.point(j.bearing_point);
        let (th, ang, vx, vy, w) = seed;
        let (s, co) = th.sin_cos();
        let p = j.journal_point;
        let arm = V2::new(co * p.x - s * p.y, s * p.x + co * p.y);
        let eps = if eps.is_finite() { eps.clamp(-1.0, 1e3) } else { 0.0 };
        let r = centre.add(V2::new(ang.cos(), ang.sin()).scale(eps * c)).sub(arm);
        let journal = BodyKin::new(&[r.x, r.y, th], &[vx, vy, w]);
        let kin = [bearing, journal];
        let k: JointKinematics = j.kinematics(&kin);
        prop_assert!(k.eps.is_finite() && k.eps_dot.is_finite() && k.wedge.is_finite() && k.slip.is_finite(), "{k:?}");
        let mem = ImpactMemory { in_contact, impact_speed: impact.abs(), impacts: 0, wear_offset: 0.0, viscosity: 0.0, ..ImpactMemory::default() };
        let f = j.force(&k, &mem);
        prop_assert!(f.total.x.is_finite() && f.total.y.is_finite(), "force {f:?} at {k:?}");
        prop_assert!(f.normal >= 0.0 && (0.0..=1.0).contains(&f.w_dry));
        let mut g = [0.0; 6];
        j.apply(&kin, &k, &f, &mut g);
        prop_assert!(g.iter().all(|v| v.is_finite()), "{g:?}");
        // Newton's third law: the forces on the two bodies cancel.
        prop_assert!((g[0] + g[3]).abs() <= 1e-9 * (1.0 + g[0].abs()) && (g[1] + g[4]).abs() <= 1e-9 * (1.0 + g[1].abs()));
    }
}

// ------------------------------------------------------------------ KKT solve

/// Random sparse Jacobian rows over `nb` bodies.
fn jac_rows(nb: usize, rows: usize) -> impl Strategy<Value = Vec<JacRow>> {
    prop::collection::vec(
        (0..nb as u32, 0..nb as u32, any::<bool>(), prop::array::uniform3(-2.0f64..2.0), prop::array::uniform3(-2.0f64..2.0)),
        rows,
    )
    .prop_map(|v| {
        v.into_iter()
            .map(|(a, b, two, ca, cb)| {
                let two = two && a != b;
                JacRow { bodies: [a, b], count: if two { 2 } else { 1 }, coef: [ca, cb] }
            })
            .collect()
    })
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn kkt_solve_finite_or_singular(
        (nb, jac) in (1usize..6).prop_flat_map(|nb| (Just(nb), (0..=2 * nb).prop_flat_map(move |r| jac_rows(nb, r)))),
        masses in prop::collection::vec(pos(-4, 3), 18),
        force in prop::collection::vec(-1e6f64..1e6, 18),
        c in prop::collection::vec(-1e6f64..1e6, 12),
    ) {
        let inv_mass: Vec<f64> = masses[..3 * nb].iter().map(|m| 1.0 / m).collect();
        let mut kkt = KktSolver::new(inv_mass.clone(), &jac);
        let rows = jac.len();
        let mut qdd = vec![0.0; 3 * nb];
        let mut lam = vec![0.0; rows];
        match kkt.solve(&jac, &force[..3 * nb], &c[..rows], &mut qdd, &mut lam) {
            Err(index) => prop_assert!(index < rows.max(1)),
            Ok(()) => {
                prop_assert!(qdd.iter().chain(lam.iter()).all(|v| !v.is_nan()), "NaN: qdd {qdd:?} λ {lam:?}");
                // Well-conditioned solves satisfy the constraint rows Φq q̈ = c.
                if qdd.iter().chain(lam.iter()).all(|v| v.is_finite() && v.abs() < 1e9) {
                    for (r, row) in jac.iter().enumerate() {
                        let resid = row.dot(&qdd) - c[r];
                        prop_assert!(resid.abs() <= 1e-5 * (1.0 + c[r].abs() + qdd.iter().fold(0.0f64, |a, v| a.max(v.abs()))), "row {r}: {resid}");
                    }
                }
            }
        }
    }
}

// ------------------------------------------------------------------ full right-hand side

/// The docs/physics.md §8 slider-crank with a clearance joint between rod and slider.
fn slider_crank(lubricated: bool, law: NormalLaw, ce: f64, cf: f64, c: f64) -> MechanismDesc {
    let dry = DryDesc { normal_law: law, restitution: ce, friction: cf, ..DryDesc::steel() };
    let model = if lubricated {
        ClearanceModelDesc::Lubricated(LubricatedDesc {
            film: FilmModel::LongBearing,
            supply: clearsim::laws::FilmSupply::WidestGap,
            viscosity: ViscosityDesc::Constant(0.04),
            length: 0.04,
            eps0: 2e-6,
            m: 0.5,
            e0: Some(0.05 * c),
            eps_max: 0.99,
            dry,
            roughness: None,
            boundary_friction: None,
            boundary_slip: None,
            thermal: None,
            cavitation: Default::default(),
        })
    } else {
        ClearanceModelDesc::Dry(dry)
    };
    let b = |name: &str, mass, inertia, x| BodyDesc { name: name.into(), mass, inertia, position: [x, 0.0], angle: 0.0, velocity: [0.0; 3] };
    MechanismDesc {
        bodies: vec![b("crank", 0.3, 1e-4, 0.025), b("rod", 0.21, 2.5e-4, 0.11), b("slider", 0.14, 1e-4, 0.17)],
        joints: vec![
            JointDesc::Revolute { name: "O".into(), body_a: None, point_a: [0.0, 0.0], body_b: Some(0), point_b: [-0.025, 0.0] },
            JointDesc::Revolute { name: "A".into(), body_a: Some(0), point_a: [0.025, 0.0], body_b: Some(1), point_b: [-0.06, 0.0] },
            JointDesc::Prismatic { name: "G".into(), body_a: None, point_a: [0.0, 0.0], axis: [1.0, 0.0], body_b: 2, point_b: [0.0, 0.0] },
        ],
        drivers: vec![DriverDesc { name: "d".into(), body: 0, law: AngleLaw::ConstantSpeed { angle0: 0.0, omega: 523.6 } }],
        clearance_joints: vec![ClearanceJointDesc {
            name: "B".into(),
            bearing_body: Some(2),
            bearing_point: [0.0, 0.0],
            journal_body: Some(1),
            journal_point: [0.06, 0.0],
            journal_radius: 9.5e-3,
            clearance: c,
            model,
            initial_eccentricity: [0.0, 0.0],
        }],
        prismatic_clearance_joints: vec![],
        forces: vec![],
        gravity: [0.0, -9.81],
        baumgarte: [50.0, 50.0],
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn rhs_finite_on_finite_states(
        lub in any::<bool>(), law in normal_law(), ce in 0.05f64..=1.0, cf in 0.0f64..0.8, c in pos(-6, -2),
        t in 0.0f64..10.0,
        dq in prop::collection::vec(-1e-3f64..1e-3, 9),
        qd in prop::collection::vec(-50.0f64..50.0, 9),
        in_contact in any::<bool>(), impact in 0.0f64..10.0,
    ) {
        let desc = slider_crank(lub, law, ce, cf, c);
        let model = match Model::compile(&desc) {
            Ok(m) => m,
            // A film needs c ≪ R_j: large lubricated clearances are refused by validation.
            Err(e) if lub && e.to_string().contains("thin-film") => return Ok(()),
            Err(e) => panic!("valid description refused: {e}"),
        };
        let mut ws = Workspace::new(&model);
        // Perturb the assembled-ish guess: journals land inside, on and beyond the clearance.
        let mut y = model.q_guess.clone();
        for (v, d) in y.iter_mut().zip(&dq) { *v += d; }
        y.extend_from_slice(&qd);
        let mem = vec![ImpactMemory { in_contact, impact_speed: impact, impacts: 0, wear_offset: 0.0, viscosity: 0.0, ..ImpactMemory::default() }; model.clearance.len()];
        match ws.evaluate(&model, &mem, t, &y) {
            Ok(()) => {
                prop_assert!(ws.qdd.iter().all(|v| v.is_finite()), "q̈ = {:?}", ws.qdd);
                prop_assert!(ws.force.iter().all(|v| v.is_finite()));
                let (p, pd) = ws.violation();
                prop_assert!(p.is_finite() && pd.is_finite());
            }
            Err(e) => prop_assert!(false, "evaluate failed on a regular pose: {e}"),
        }
    }
}

#[test]
fn invalid_descriptions_are_errors_not_panics() {
    // Every numeric field set to NaN, ±∞, 0, a negative value and 1e308: a value the field
    // cannot take (non-finite anywhere; ≤ 0 where it must be positive; < 0 where it must not be
    // negative) must be an InvalidInput naming the field; the others compile or are an
    // InvalidInput naming the field; none panics.
    let base = slider_crank(true, NormalLaw::LankaraniNikravesh, 0.9, 0.1, 5e-4);
    let bad = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 0.0, -1.0, 1e308];
    #[derive(Clone, Copy, PartialEq)]
    enum Rule {
        Finite,
        Positive,
        NonNegative,
    }
    use Rule::*;
    type Setter = fn(&mut MechanismDesc, f64);
    let setters: Vec<(&str, Rule, Setter)> = vec![
        ("mass", Positive, |d, v| d.bodies[0].mass = v),
        ("inertia", Positive, |d, v| d.bodies[1].inertia = v),
        ("position", Finite, |d, v| d.bodies[2].position[0] = v),
        ("angle", Finite, |d, v| d.bodies[0].angle = v),
        ("clearance", Positive, |d, v| d.clearance_joints[0].clearance = v),
        ("journal_radius", Positive, |d, v| d.clearance_joints[0].journal_radius = v),
        ("initial_eccentricity", Finite, |d, v| d.clearance_joints[0].initial_eccentricity[1] = v),
        ("gravity", Finite, |d, v| d.gravity[1] = v),
        ("baumgarte", Finite, |d, v| d.baumgarte[0] = v),
        ("viscosity", Positive, |d, v| if let ClearanceModelDesc::Lubricated(l) = &mut d.clearance_joints[0].model { l.viscosity = ViscosityDesc::Constant(v) }),
        ("eps0", NonNegative, |d, v| if let ClearanceModelDesc::Lubricated(l) = &mut d.clearance_joints[0].model { l.eps0 = v }),
        ("restitution", NonNegative, |d, v| if let ClearanceModelDesc::Lubricated(l) = &mut d.clearance_joints[0].model { l.dry.restitution = v }),
        ("v1", Positive, |d, v| if let ClearanceModelDesc::Lubricated(l) = &mut d.clearance_joints[0].model { l.dry.v1 = v }),
    ];
    for (name, rule, set) in setters {
        for v in bad {
            let mut d = base.clone();
            set(&mut d, v);
            let must_fail = !v.is_finite() || (rule == Positive && v <= 0.0) || (rule == NonNegative && v < 0.0);
            match Model::compile(&d) {
                Ok(_) => assert!(!must_fail, "{name} = {v} compiled: it must be an InvalidInput"),
                // A huge journal radius makes the clearance too small against it: that check
                // names the clearance.
                Err(clearsim::Error::InvalidInput { field, .. }) => assert!(
                    field.contains(name) || (name == "journal_radius" && field.ends_with(".clearance")),
                    "{name} = {v}: error names {field}"
                ),
                Err(e) => panic!("{name} = {v}: unexpected error {e}"),
            }
        }
    }
}

/// A subnormal eccentricity (|e| < 2.2e-308 m, e.g. a journal started centred whose rod angle
/// is perturbed by 1e-310 rad) once gave NaN forces: `n = e_vec · (1/e)` overflowed and
/// `γ̇ = (e × ė)/(e·e)` divided by an underflowed e².
#[test]
fn subnormal_eccentricity_gives_finite_forces() {
    let bearing = BodyKin::new(&[0.0, 0.0, 0.0], &[0.0, 0.0, 0.0]);
    let journal = BodyKin::new(&[0.0, 6e-312, 0.0], &[1.0, 0.0, 0.0]);
    for lubricated in [false, true] {
        let j = joint(lubricated, NormalLaw::LankaraniNikravesh, FilmModel::LongBearing, 5e-4, 9.5e-3, 0.9, 0.1);
        let mut j = j;
        j.bearing_point = V2::new(0.0, 0.0);
        j.journal_point = V2::new(0.0, 0.0);
        let kin = [bearing, journal];
        let k = j.kinematics(&kin);
        let f = j.force(&k, &ImpactMemory::default());
        assert!(f.total.x.is_finite() && f.total.y.is_finite(), "non-finite joint force {f:?} at e = {}", k.e);
    }
}
