//! Butcher tableaus of the explicit Runge–Kutta methods (Hairer, Nørsett & Wanner, *Solving
//! Ordinary Differential Equations I*, 2nd ed., §II.1, §II.5, §II.6).
//!
//! Rows of `A` are stored as slices of length `i` (stage `i` depends on stages `0..i`); entries
//! past the end of a row are zero. Stage indices are 0-based here, 1-based in the literature.
#![allow(clippy::excessive_precision)]

/// Classic 4th-order Runge–Kutta method (Hairer I, Table II.1.2, "the" Runge–Kutta method).
pub mod rk4 {
    /// Nodes `c_i`.
    pub const C: [f64; 4] = [0.0, 0.5, 0.5, 1.0];
    /// Coupling coefficients `a_ij`.
    pub const A: [&[f64]; 4] = [&[], &[0.5], &[0.0, 0.5], &[0.0, 0.0, 1.0]];
    /// Weights `b_i` (order 4).
    pub const B: [f64; 4] = [1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0];
}

/// Dormand–Prince 5(4), "DOPRI5" (Dormand & Prince 1980; Hairer I, Table II.5.5), with the
/// 4th-order continuous extension of Shampine (1986) used in Hairer's code `DOPRI5` (§II.6).
///
/// The method is FSAL: row 6 of `A` equals `B`, so stage 6 is `f(t0 + h, y1)`.
pub mod dopri5 {
    /// Nodes `c_i`.
    pub const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
    /// Coupling coefficients `a_ij`.
    pub const A: [&[f64]; 7] = [
        &[],
        &[1.0 / 5.0],
        &[3.0 / 40.0, 9.0 / 40.0],
        &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
        &[19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0],
        &[
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
        ],
        &[
            35.0 / 384.0,
            0.0,
            500.0 / 1113.0,
            125.0 / 192.0,
            -2187.0 / 6784.0,
            11.0 / 84.0,
        ],
    ];
    /// Weights `b_i` of the propagated 5th-order solution.
    pub const B: [f64; 7] = [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
        0.0,
    ];
    /// Weights `b̂_i` of the embedded 4th-order solution.
    pub const BHAT: [f64; 7] = [
        5179.0 / 57600.0,
        0.0,
        7571.0 / 16695.0,
        393.0 / 640.0,
        -92097.0 / 339200.0,
        187.0 / 2100.0,
        1.0 / 40.0,
    ];
    /// Error weights `e_i = b_i − b̂_i`; the local error estimate is `h Σ e_i k_i`.
    pub const E: [f64; 7] = [
        71.0 / 57600.0,
        0.0,
        -71.0 / 16695.0,
        71.0 / 1920.0,
        -17253.0 / 339200.0,
        22.0 / 525.0,
        -1.0 / 40.0,
    ];
    /// Coefficients of the 5th term of the dense output (Hairer's `D1..D7`, after Shampine 1986):
    /// `rcont5 = h Σ d_i k_i`, see [`crate::integrate::dense`].
    pub const D: [f64; 7] = [
        -12715105075.0 / 11282082432.0,
        0.0,
        87487479700.0 / 32700410799.0,
        -10690763975.0 / 1880347072.0,
        701980252875.0 / 199316789632.0,
        -1453857185.0 / 822651844.0,
        69997945.0 / 29380423.0,
    ];
    /// Order of the propagated solution.
    pub const ORDER: i32 = 5;
}

/// Dormand–Prince 8(5,3), Hairer's code `DOP853` (Hairer I, §II.5 and §II.6; coefficients of
/// the published Fortran code `dop853.f`).
///
/// Stages `0..12` form the 12-stage 8th-order method (stage 11 at `c = 1`). The extended
/// tableau continues with stage 12 = `f(t0 + h, y1)` (row 12 of `A` equals `B`), which is also
/// the first stage of the next step, and the three extra stages 13, 14, 15 needed by the
/// 7th-order dense output.
pub mod dop853 {
    /// Number of stages of the basic 8th-order step.
    pub const STAGES: usize = 12;
    /// Number of stages of the extended tableau (basic + FSAL stage + 3 dense-output stages).
    pub const STAGES_DENSE: usize = 16;

    /// Nodes `c_i` of the extended tableau (`c_12 = 1` for `f(t1, y1)`, then `c_13..c_15`).
    pub const C: [f64; 16] = [
        0.0,
        0.526001519587677318785587544488e-01,
        0.789002279381515978178381316732e-01,
        0.118350341907227396726757197510e+00,
        0.281649658092772603273242802490e+00,
        0.333333333333333333333333333333e+00,
        0.25e+00,
        0.307692307692307692307692307692e+00,
        0.651282051282051282051282051282e+00,
        0.6e+00,
        0.857142857142857142857142857142e+00,
        1.0,
        1.0,
        0.1,
        0.2,
        0.777777777777777777777777777778e+00,
    ];

    /// Weights `b_i` of the 8th-order solution (stages 1..4 have weight 0).
    pub const B: [f64; 12] = [
        5.42937341165687622380535766363e-2,
        0.0,
        0.0,
        0.0,
        0.0,
        4.45031289275240888144113950566e0,
        1.89151789931450038304281599044e0,
        -5.8012039600105847814672114227e0,
        3.1116436695781989440891606237e-1,
        -1.52160949662516078556178806805e-1,
        2.01365400804030348374776537501e-1,
        4.47106157277725905176885569043e-2,
    ];

    /// Coupling coefficients `a_ij` of the extended tableau.
    pub const A: [&[f64]; 16] = [
        &[],
        &[5.26001519587677318785587544488e-2],
        &[1.97250569845378994544595329183e-2, 5.91751709536136983633785987549e-2],
        &[
            2.95875854768068491816892993775e-2,
            0.0,
            8.87627564304205475450678981324e-2,
        ],
        &[
            2.41365134159266685502369798665e-1,
            0.0,
            -8.84549479328286085344864962717e-1,
            9.24834003261792003115737966543e-1,
        ],
        &[
            3.7037037037037037037037037037e-2,
            0.0,
            0.0,
            1.70828608729473871279604482173e-1,
            1.25467687566822425016691814123e-1,
        ],
        &[
            3.7109375e-2,
            0.0,
            0.0,
            1.70252211019544039314978060272e-1,
            6.02165389804559606850219397283e-2,
            -1.7578125e-2,
        ],
        &[
            3.70920001185047927108779319836e-2,
            0.0,
            0.0,
            1.70383925712239993810214054705e-1,
            1.07262030446373284651809199168e-1,
            -1.53194377486244017527936158236e-2,
            8.27378916381402288758473766002e-3,
        ],
        &[
            6.24110958716075717114429577812e-1,
            0.0,
            0.0,
            -3.36089262944694129406857109825e0,
            -8.68219346841726006818189891453e-1,
            2.75920996994467083049415600797e1,
            2.01540675504778934086186788979e1,
            -4.34898841810699588477366255144e1,
        ],
        &[
            4.77662536438264365890433908527e-1,
            0.0,
            0.0,
            -2.48811461997166764192642586468e0,
            -5.90290826836842996371446475743e-1,
            2.12300514481811942347288949897e1,
            1.52792336328824235832596922938e1,
            -3.32882109689848629194453265587e1,
            -2.03312017085086261358222928593e-2,
        ],
        &[
            -9.3714243008598732571704021658e-1,
            0.0,
            0.0,
            5.18637242884406370830023853209e0,
            1.09143734899672957818500254654e0,
            -8.14978701074692612513997267357e0,
            -1.85200656599969598641566180701e1,
            2.27394870993505042818970056734e1,
            2.49360555267965238987089396762e0,
            -3.0467644718982195003823669022e0,
        ],
        &[
            2.27331014751653820792359768449e0,
            0.0,
            0.0,
            -1.05344954667372501984066689879e1,
            -2.00087205822486249909675718444e0,
            -1.79589318631187989172765950534e1,
            2.79488845294199600508499808837e1,
            -2.85899827713502369474065508674e0,
            -8.87285693353062954433549289258e0,
            1.23605671757943030647266201528e1,
            6.43392746015763530355970484046e-1,
        ],
        // Stage 12 = f(t0 + h, y1): its row is B.
        &B,
        // Extra stages for the dense output (Hairer's a14.., a15.., a16..).
        &[
            5.61675022830479523392909219681e-2,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            2.53500210216624811088794765333e-1,
            -2.46239037470802489917441475441e-1,
            -1.24191423263816360469010140626e-1,
            1.5329179827876569731206322685e-1,
            8.20105229563468988491666602057e-3,
            7.56789766054569976138603589584e-3,
            -8.298e-3,
        ],
        &[
            3.18346481635021405060768473261e-2,
            0.0,
            0.0,
            0.0,
            0.0,
            2.83009096723667755288322961402e-2,
            5.35419883074385676223797384372e-2,
            -5.49237485713909884646569340306e-2,
            0.0,
            0.0,
            -1.08347328697249322858509316994e-4,
            3.82571090835658412954920192323e-4,
            -3.40465008687404560802977114492e-4,
            1.41312443674632500278074618366e-1,
        ],
        &[
            -4.28896301583791923408573538692e-1,
            0.0,
            0.0,
            0.0,
            0.0,
            -4.69762141536116384314449447206e0,
            7.68342119606259904184240953878e0,
            4.06898981839711007970213554331e0,
            3.56727187455281109270669543021e-1,
            0.0,
            0.0,
            0.0,
            -1.39902416515901462129418009734e-3,
            2.9475147891527723389556272149e0,
            -9.15095847217987001081870187138e0,
        ],
    ];

    /// Weights of the 3rd-order embedded solution (Hairer's `BHH1, BHH2, BHH3` on stages 0, 8, 11).
    pub const BHH: [f64; 12] = [
        0.244094488188976377952755905512e+00,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.733846688281611857341361741547e+00,
        0.0,
        0.0,
        0.220588235294117647058823529412e-01,
    ];

    /// 3rd-order error weights `b_i − bhh_i`.
    pub const E3: [f64; 12] = [
        B[0] - BHH[0],
        0.0,
        0.0,
        0.0,
        0.0,
        B[5],
        B[6],
        B[7],
        B[8] - BHH[8],
        B[9],
        B[10],
        B[11] - BHH[11],
    ];

    /// 5th-order error weights (Hairer's `ER1, ER6..ER12`): `b − b̂` with `b̂` of order 5.
    pub const E5: [f64; 12] = [
        0.1312004499419488073250102996e-01,
        0.0,
        0.0,
        0.0,
        0.0,
        -0.1225156446376204440720569753e+01,
        -0.4957589496572501915214079952e+00,
        0.1664377182454986536961530415e+01,
        -0.3503288487499736816886487290e+00,
        0.3341791187130174790297318841e+00,
        0.8192320648511571246570742613e-01,
        -0.2235530786388629525884427845e-01,
    ];

    /// Coefficients of the terms 5..8 of the 7th-order dense output (Hairer's `D4j..D7j`):
    /// `rcont(5+r) = h Σ_j D[r][j] k_j` over the 16 stages of the extended tableau.
    pub const D: [[f64; 16]; 4] = [
        [
            -0.84289382761090128651353491142e+01,
            0.0,
            0.0,
            0.0,
            0.0,
            0.56671495351937776962531783590e+00,
            -0.30689499459498916912797304727e+01,
            0.23846676565120698287728149680e+01,
            0.21170345824450282767155149946e+01,
            -0.87139158377797299206789907490e+00,
            0.22404374302607882758541771650e+01,
            0.63157877876946881815570249290e+00,
            -0.88990336451333310820698117400e-01,
            0.18148505520854727256656404962e+02,
            -0.91946323924783554000451984436e+01,
            -0.44360363875948939664310572000e+01,
        ],
        [
            0.10427508642579134603413151009e+02,
            0.0,
            0.0,
            0.0,
            0.0,
            0.24228349177525818288430175319e+03,
            0.16520045171727028198505394887e+03,
            -0.37454675472269020279518312152e+03,
            -0.22113666853125306036270938578e+02,
            0.77334326684722638389603898808e+01,
            -0.30674084731089398182061213626e+02,
            -0.93321305264302278729567221706e+01,
            0.15697238121770843886131091075e+02,
            -0.31139403219565177677282850411e+02,
            -0.93529243588444783865713862664e+01,
            0.35816841486394083752465898540e+02,
        ],
        [
            0.19985053242002433820987653617e+02,
            0.0,
            0.0,
            0.0,
            0.0,
            -0.38703730874935176555105901742e+03,
            -0.18917813819516756882830838328e+03,
            0.52780815920542364900561016686e+03,
            -0.11573902539959630126141871134e+02,
            0.68812326946963000169666922661e+01,
            -0.10006050966910838403183860980e+01,
            0.77771377980534432092869265740e+00,
            -0.27782057523535084065932004339e+01,
            -0.60196695231264120758267380846e+02,
            0.84320405506677161018159903784e+02,
            0.11992291136182789328035130030e+02,
        ],
        [
            -0.25693933462703749003312586129e+02,
            0.0,
            0.0,
            0.0,
            0.0,
            -0.15418974869023643374053993627e+03,
            -0.23152937917604549567536039109e+03,
            0.35763911791061412378285349910e+03,
            0.93405324183624310003907691704e+02,
            -0.37458323136451633156875139351e+02,
            0.10409964950896230045147246184e+03,
            0.29840293426660503123344363579e+02,
            -0.43533456590011143754432175058e+02,
            0.96324553959188282948394950600e+02,
            -0.39177261675615439165231486172e+02,
            -0.14972683625798562581422125276e+03,
        ],
    ];
    /// Order of the propagated solution.
    pub const ORDER: i32 = 8;
}

/// Rooted trees and their elementary weights, for checking order conditions in tests
/// (Hairer I, §II.2, Theorem 2.13: `Σ b_i Φ_i(t) = 1/γ(t)` for all trees `|t| ≤ p`).
#[cfg(test)]
pub(crate) mod trees {
    /// A rooted tree: the ids of its root's subtrees (into the list it belongs to).
    pub struct Tree {
        pub children: Vec<usize>,
        pub order: usize,
        pub gamma: f64,
    }

    /// All rooted trees with at most `max_order` vertices, sorted by order.
    pub fn all_trees(max_order: usize) -> Vec<Tree> {
        fn rec(trees: &[Tree], remaining: usize, max_id: usize, cur: &mut Vec<usize>, out: &mut Vec<Vec<usize>>) {
            if remaining == 0 {
                out.push(cur.clone());
                return;
            }
            // Children as a non-increasing id sequence: each multiset exactly once.
            for id in 0..=max_id {
                if trees[id].order <= remaining {
                    cur.push(id);
                    rec(trees, remaining - trees[id].order, id, cur, out);
                    cur.pop();
                }
            }
        }
        let mut trees = vec![Tree {
            children: vec![],
            order: 1,
            gamma: 1.0,
        }];
        for n in 2..=max_order {
            let mut sets = Vec::new();
            rec(&trees, n - 1, trees.len() - 1, &mut Vec::new(), &mut sets);
            for children in sets {
                let gamma = n as f64 * children.iter().map(|&c| trees[c].gamma).product::<f64>();
                trees.push(Tree {
                    children,
                    order: n,
                    gamma,
                });
            }
        }
        trees
    }

    /// Elementary weights `g[t][i] = Π_{u child of t} (Σ_j a_ij g[u][j])`, so that the order
    /// condition of tree `t` reads `Σ_i b_i g[t][i] = 1/γ(t)`.
    pub fn weights(trees: &[Tree], a: &[&[f64]]) -> Vec<Vec<f64>> {
        let s = a.len();
        let mut g: Vec<Vec<f64>> = Vec::with_capacity(trees.len());
        for t in trees {
            let mut gi = vec![1.0; s];
            for &u in &t.children {
                for (i, row) in a.iter().enumerate() {
                    gi[i] *= row.iter().zip(&g[u]).map(|(x, y)| x * y).sum::<f64>();
                }
            }
            g.push(gi);
        }
        g
    }

    /// Largest violation of the order conditions of order `≤ p` by the weights `b`, where the
    /// right-hand side for tree `t` is `rhs_scale^|t| / γ(t)` (1 for a step, `θ^|t|` for dense
    /// output at θ).
    pub fn max_defect(trees: &[Tree], g: &[Vec<f64>], b: &[f64], p: usize, rhs_scale: f64) -> f64 {
        trees
            .iter()
            .zip(g)
            .filter(|(t, _)| t.order <= p)
            .map(|(t, gt)| {
                let lhs: f64 = b.iter().zip(gt).map(|(x, y)| x * y).sum();
                (lhs - rhs_scale.powi(t.order as i32) / t.gamma).abs()
            })
            .fold(0.0, f64::max)
    }
}

#[cfg(test)]
mod tests {
    use super::trees::{all_trees, max_defect, weights};
    use super::*;

    fn row_sum_defect(c: &[f64], a: &[&[f64]]) -> f64 {
        c.iter()
            .zip(a)
            .map(|(ci, row)| (ci - row.iter().sum::<f64>()).abs())
            .fold(0.0, f64::max)
    }

    #[test]
    fn tree_counts_match_oeis_a000081() {
        let trees = all_trees(8);
        let counts: Vec<usize> = (1..=8).map(|n| trees.iter().filter(|t| t.order == n).count()).collect();
        assert_eq!(counts, vec![1, 1, 2, 4, 9, 20, 48, 115]);
        // γ of the tall tree of order 4 is 4! and of the bushy one 4.
        let g4: Vec<f64> = trees.iter().filter(|t| t.order == 4).map(|t| t.gamma).collect();
        assert!(g4.contains(&24.0) && g4.contains(&4.0) && g4.contains(&8.0) && g4.contains(&12.0));
    }

    #[test]
    fn rk4_row_sums_and_order_4() {
        assert!(row_sum_defect(&rk4::C, &rk4::A) < 1e-15);
        let trees = all_trees(5);
        let g = weights(&trees, &rk4::A);
        assert!(max_defect(&trees, &g, &rk4::B, 4, 1.0) < 1e-15);
        // Not order 5: the conditions of order 5 must fail (the test can fail).
        assert!(max_defect(&trees, &g, &rk4::B, 5, 1.0) > 1e-3);
    }

    #[test]
    fn dopri5_row_sums_and_orders_5_and_4() {
        assert!(row_sum_defect(&dopri5::C, &dopri5::A) < 1e-14);
        let trees = all_trees(6);
        let g = weights(&trees, &dopri5::A);
        assert!(max_defect(&trees, &g, &dopri5::B, 5, 1.0) < 1e-14);
        assert!(max_defect(&trees, &g, &dopri5::B, 6, 1.0) > 1e-5);
        assert!(max_defect(&trees, &g, &dopri5::BHAT, 4, 1.0) < 1e-14);
        assert!(max_defect(&trees, &g, &dopri5::BHAT, 5, 1.0) > 1e-5);
        // FSAL: last row of A is B; E = B − B̂.
        for i in 0..7 {
            let a6 = dopri5::A[6].get(i).copied().unwrap_or(0.0);
            assert_eq!(a6, dopri5::B[i]);
            assert!((dopri5::E[i] - (dopri5::B[i] - dopri5::BHAT[i])).abs() < 1e-16);
        }
    }

    #[test]
    fn dop853_row_sums_and_order_8() {
        assert!(row_sum_defect(&dop853::C, &dop853::A) < 1e-14);
        let a12 = &dop853::A[..dop853::STAGES];
        let trees = all_trees(8);
        let g = weights(&trees, a12);
        // Σb = 1, Σbc = 1/2, …, Σ b a c = 1/6, … all 200 conditions up to order 8.
        assert!(max_defect(&trees, &g, &dop853::B, 5, 1.0) < 1e-14);
        assert!(max_defect(&trees, &g, &dop853::B, 8, 1.0) < 1e-13);
        // The embedded formulas: e5 = b − b̂ with b̂ of order 5, e3 = b − bhh with bhh of order 3,
        // so Σ e Φ(t) = 0 for |t| ≤ 5 resp. 3.
        let zero = |e: &[f64], p: usize| {
            trees
                .iter()
                .zip(&g)
                .filter(|(t, _)| t.order <= p)
                .map(|(_, gt)| e.iter().zip(gt).map(|(x, y)| x * y).sum::<f64>().abs())
                .fold(0.0, f64::max)
        };
        assert!(zero(&dop853::E5, 5) < 1e-14);
        assert!(zero(&dop853::E3, 3) < 1e-14);
        assert!(zero(&dop853::E5, 6) > 1e-6, "e5 must not vanish on order-6 trees");
        // Explicit low-order conditions from the literature.
        let b = &dop853::B;
        let c = &dop853::C;
        let s = |f: &dyn Fn(usize) -> f64| (0..12).map(f).sum::<f64>();
        assert!((s(&|i| b[i]) - 1.0).abs() < 1e-14);
        assert!((s(&|i| b[i] * c[i]) - 0.5).abs() < 1e-14);
        assert!((s(&|i| b[i] * c[i] * c[i]) - 1.0 / 3.0).abs() < 1e-14);
        assert!((s(&|i| b[i] * c[i].powi(3)) - 0.25).abs() < 1e-14);
        let ac = |i: usize| dop853::A[i].iter().zip(c).map(|(x, y)| x * y).sum::<f64>();
        assert!((s(&|i| b[i] * ac(i)) - 1.0 / 6.0).abs() < 1e-14);
    }
}
