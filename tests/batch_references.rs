//! The batch's reference runs (rust/batch.rs): one per distinct ideal mechanism and run, shared by
//! the samples measured against it, with the answers of each sample run alone; a failed reference
//! fails its samples (not run) with the reason; a monitor never runs without its reference.

mod common;

use clearsim::batch::{reference_runs, run_batch, run_one};
use clearsim::description::{AngleLaw, MechanismDesc};
use clearsim::error::Error;
use clearsim::integrate::Method;
use clearsim::model::Model;
use clearsim::monitor::{MonitorSpec, Quantity, ReferenceGrid, ReferenceOf, Target};
use clearsim::simulate::RunSettings;

const SPAN: f64 = 0.25 * common::SLIDER_CRANK_CYCLE;

fn settings(of: ReferenceOf) -> RunSettings {
    let mut rs = common::bench_run(Method::Rk45, SPAN, 10);
    rs.reference = Some(ReferenceGrid { t_start: 0.0, t_end: SPAN, intervals: 1800, record: false });
    rs.monitors.push(MonitorSpec {
        target: Target::Coordinate(6), // the slider's x (bodies crank, rod, slider)
        quantity: Quantity::Displacement,
        reference: Some(of),
        t_start: 0.0,
        bin_width: SPAN / 4.0,
        bins: 4,
        limit: None,
        samples_per_step: 8,
        exact: false,
    });
    rs
}

/// The dry slider-crank with its clearance scaled by `c` and its crank speed by `w`.
fn sample(c: f64, w: f64) -> MechanismDesc {
    let mut d = common::description("slider_crank_dry");
    for j in &mut d.clearance_joints {
        j.clearance *= c;
    }
    for drv in &mut d.drivers {
        if let AngleLaw::ConstantSpeed { omega, .. } = &mut drv.law {
            *omega *= w;
        }
    }
    d
}

#[test]
fn shared_and_distinct_references_give_each_sample_its_own_answer() {
    let rs = settings(ReferenceOf::OwnIdeal);
    // Clearances change no ideal mechanism: one reference; speeds do: one each.
    let same: Vec<_> = [0.8, 1.0, 1.2].iter().map(|&c| sample(c, 1.0)).collect();
    let speeds: Vec<_> = [0.99, 1.0, 1.01, 1.02].iter().map(|&w| sample(1.0, w)).collect();
    assert_eq!(reference_runs(&same, std::slice::from_ref(&rs), None), 1);
    assert_eq!(reference_runs(&speeds, std::slice::from_ref(&rs), None), 4);
    for descs in [&same, &speeds] {
        for threads in [1, 2] {
            let outs = run_batch(descs, std::slice::from_ref(&rs), None, threads, None);
            for (d, out) in descs.iter().zip(outs) {
                let together = out.unwrap().monitors[0].peak;
                let model = Model::compile(d).unwrap();
                let alone = run_one(&model, d, &rs, None, None).unwrap().monitors[0].peak;
                assert_eq!(together.to_bits(), alone.to_bits());
                // Against its own ideal twin the slider's error stays within the play and its dynamics.
                assert!(together > 0.0 && together < 2e-3, "{together}");
            }
        }
    }
    // Against the nominal design: one reference for all speeds, and the phase drift counts.
    let nominal = sample(1.0, 1.0);
    let rs = settings(ReferenceOf::Nominal);
    assert_eq!(reference_runs(&speeds, std::slice::from_ref(&rs), Some(&nominal)), 1);
    let outs: Vec<f64> = run_batch(&speeds, std::slice::from_ref(&rs), Some(&nominal), 2, None).into_iter().map(|o| o.unwrap().monitors[0].peak).collect();
    // The nominal sample against the nominal ideal is its own-ideal answer; a 1 % slower crank
    // falls behind the nominal motion (by about r · 1 % of its quarter turn, 0.8 mm).
    let own = run_batch(&speeds[1..2], &[settings(ReferenceOf::OwnIdeal)], None, 1, None).pop().unwrap().unwrap().monitors[0].peak;
    assert_eq!(outs[1].to_bits(), own.to_bits());
    assert!(outs[0] > own + 3e-4, "{outs:?} {own}");
}

#[test]
fn a_failed_reference_fails_its_samples_with_the_reason() {
    let mut rs = settings(ReferenceOf::OwnIdeal);
    rs.ode.max_steps = 3; // the reference runs at a tenth of the tolerance: it uses them up
    let outs = run_batch(&[sample(1.0, 1.0)], std::slice::from_ref(&rs), None, 1, None);
    let err = outs.into_iter().next().unwrap().unwrap_err();
    assert!(matches!(err.root(), Error::TooManySteps { .. }), "{err}");
    assert!(err.to_string().ends_with("(ideal mechanism)"), "{err}");
}

#[test]
fn a_monitor_is_never_run_without_its_reference() {
    let d = sample(1.0, 1.0);
    let model = Model::compile(&d).unwrap();
    let rs = settings(ReferenceOf::OwnIdeal);
    let e = clearsim::simulate::simulate(&model, &rs, None).unwrap_err().to_string();
    assert!(e.starts_with("invalid monitors[0].reference = own_ideal"), "{e}");
    let e = run_batch(&[d.clone()], &[settings(ReferenceOf::Nominal)], None, 1, None).pop().unwrap().unwrap_err().to_string();
    assert!(e.contains("no nominal mechanism"), "{e}");
    let mut no_grid = settings(ReferenceOf::OwnIdeal);
    no_grid.reference = None;
    assert!(no_grid.validate().unwrap_err().to_string().contains("reference grid"));
}
