//! A run's output as Python data: a dict of numpy arrays (see `clearsim.result.Result`), its
//! error as the matching `clearsim.errors` exception with the joint nearest contact and, for a
//! stalled lubricated run, the core's hint (`.hint`).

use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use super::{array2, to_pyerr};
use crate::record::JOINT_COLUMNS;
use crate::simulate::RunOutput;

/// The channels of a recording into `d` (`t`, `q`, `qd`, `qdd`, `lambda`, `joints`,
/// `temperature`, `violation`, `energy`: those it holds).
fn recording_into<'py>(py: Python<'py>, d: &Bound<'py, PyDict>, rec: &crate::record::Recording) -> PyResult<()> {
    let n = rec.coordinates;
    let ch = rec.channels.unwrap_or_default();
    d.set_item("t", PyArray1::from_slice(py, &rec.t))?;
    if ch.states {
        d.set_item("q", array2(py, &rec.q, n)?)?;
        d.set_item("qd", array2(py, &rec.qd, n)?)?;
    }
    if ch.accelerations {
        d.set_item("qdd", array2(py, &rec.qdd, n)?)?;
    }
    if ch.reactions {
        d.set_item("lambda", array2(py, &rec.lambda, rec.constraint_rows)?)?;
        let rows = rec.t.len();
        d.set_item("reactions", PyArray1::from_slice(py, &rec.reactions).reshape([rows, rec.constraints, 3])?)?;
    }
    if ch.joints {
        let nj = rec.clearance_joints;
        let w = JOINT_COLUMNS.len();
        let rows = rec.t.len();
        d.set_item("joints", PyArray1::from_slice(py, &rec.joints).reshape([rows, nj, w])?)?;
    }
    if !rec.temperature.is_empty() {
        d.set_item("temperature", array2(py, &rec.temperature, rec.clearance_joints)?)?;
    }
    if ch.violation {
        d.set_item("violation", array2(py, &rec.violation, 2)?)?;
    }
    if ch.energy {
        d.set_item("energy", array2(py, &rec.energy, crate::energy::ENERGY_COLUMNS.len())?)?;
    }
    if ch.film {
        super::film::recorded(py, rec, d)?;
    }
    Ok(())
}

pub(super) fn output_to_dict<'py>(py: Python<'py>, out: &RunOutput) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    recording_into(py, &d, &out.recording)?;
    if let Some(rec) = &out.sections {
        let sd = PyDict::new(py);
        recording_into(py, &sd, rec)?;
        d.set_item("sections", sd)?;
    }
    if let Some(book) = &out.lyapunov {
        let ld = PyDict::new(py);
        ld.set_item("t", PyArray1::from_slice(py, &book.t))?;
        ld.set_item("log_growth", PyArray1::from_slice(py, &book.log_growth))?;
        ld.set_item("steps", book.steps)?;
        ld.set_item("rhs_evaluations", book.rhs_evals)?;
        match &book.error {
            None => ld.set_item("error", py.None())?,
            Some(e) => ld.set_item("error", to_pyerr(py, e).value(py))?,
        }
        d.set_item("lyapunov", ld)?;
    }
    d.set_item("q0", PyArray1::from_slice(py, &out.q0))?;
    d.set_item("qd0", PyArray1::from_slice(py, &out.qd0))?;
    d.set_item("impacts", out.impacts.clone())?;
    d.set_item("max_violation", out.max_violation.to_vec())?;
    if !out.references.is_empty() {
        let n = out.recording.coordinates;
        let refs = PyDict::new(py);
        for r in &out.references {
            let rd = PyDict::new(py);
            rd.set_item("q", array2(py, &r.q, n)?)?;
            rd.set_item("qd", array2(py, &r.qd, n)?)?;
            rd.set_item("qdd", array2(py, &r.qdd, n)?)?;
            refs.set_item(r.of.name(), rd)?;
        }
        d.set_item("reference", refs)?;
    }
    let monitors = PyList::empty(py);
    for m in &out.monitors {
        let md = PyDict::new(py);
        md.set_item("peak", m.peak)?;
        md.set_item("t_peak", m.t_peak)?;
        md.set_item("first_passage", m.first_passage)?;
        md.set_item("bin_max", PyArray1::from_slice(py, &m.bin_max))?;
        md.set_item("bin_min", PyArray1::from_slice(py, &m.bin_min))?;
        md.set_item("bin_abs", PyArray1::from_slice(py, &m.bin_abs))?;
        md.set_item("bin_sq", PyArray1::from_slice(py, &m.bin_sq))?;
        md.set_item("bin_time", PyArray1::from_slice(py, &m.bin_time))?;
        md.set_item("max", m.max)?;
        md.set_item("t_max", m.t_max)?;
        md.set_item("min", m.min)?;
        md.set_item("t_min", m.t_min)?;
        monitors.append(md)?;
    }
    if !out.monitors.is_empty() {
        d.set_item("monitors", monitors)?;
    }
    if out.wear.iter().any(Option::is_some) {
        let wear = PyList::empty(py);
        for w in &out.wear {
            match w {
                None => wear.append(py.None())?,
                Some(w) => {
                    let wd = PyDict::new(py);
                    wd.set_item("bearing", PyArray1::from_slice(py, &w.bearing))?;
                    wd.set_item("journal", PyArray1::from_slice(py, &w.journal))?;
                    wd.set_item("volume", w.volume)?;
                    if let Some(m) = &w.at_mark {
                        wd.set_item("bearing_at_mark", PyArray1::from_slice(py, &m.bearing))?;
                        wd.set_item("journal_at_mark", PyArray1::from_slice(py, &m.journal))?;
                        wd.set_item("volume_at_mark", m.volume)?;
                    }
                    wear.append(wd)?;
                }
            }
        }
        d.set_item("wear", wear)?;
    }
    if !out.bearings.is_empty() {
        // Per clearance joint: the bearing summary (RunSettings::bearings), None for a dry joint.
        let bearings = PyList::empty(py);
        for b in &out.bearings {
            match b {
                None => bearings.append(py.None())?,
                Some(b) => {
                    let bd = PyDict::new(py);
                    bd.set_item("window_start", b.window_start)?;
                    bd.set_item("window_end", b.window_end)?;
                    bd.set_item("min_film_thickness", b.min_film_thickness)?;
                    bd.set_item("t_min_film", b.t_min_film)?;
                    bd.set_item("peak_power_loss", b.peak_power_loss)?;
                    bd.set_item("t_peak_power_loss", b.t_peak_power_loss)?;
                    bd.set_item("mean_power_loss", b.mean_power_loss())?;
                    bd.set_item("energy_loss", b.energy_loss)?;
                    bearings.append(bd)?;
                }
            }
        }
        d.set_item("bearings", bearings)?;
    }
    let s = PyDict::new(py);
    s.set_item("steps", out.stats.steps_accepted)?;
    s.set_item("rejected_steps", out.stats.steps_rejected)?;
    s.set_item("steps_to_switch", out.stats.steps_to_switch)?;
    s.set_item("rhs_evaluations", out.stats.rhs_evals)?;
    s.set_item("jacobians", out.stats.jacobians)?;
    s.set_item("force_evaluations", out.force_evaluations)?;
    s.set_item("min_step", out.stats.h_min_used)?;
    s.set_item("max_step", out.stats.h_max_used)?;
    s.set_item("t_reached", out.stats.t_reached)?;
    s.set_item("wall_time", out.wall_time)?;
    s.set_item("integrator", out.method.name())?;
    d.set_item("stats", s)?;
    match &out.error {
        None => d.set_item("error", py.None())?,
        Some(e) => {
            let err = to_pyerr(py, e);
            let value = err.value(py);
            if let Some((joint, eps)) = &out.failure_joint {
                value.setattr("joint", joint)?;
                value.setattr("eccentricity", eps)?;
                // Failures whose message carries no diagnosis (singular Jacobian, step budget)
                // still name the joint nearest contact, so a blown-up state is recognisable.
                let msg = e.to_string();
                if !msg.contains(&format!("joint '{joint}'")) {
                    let full = format!("{msg}; joint '{joint}' at eccentricity ε = {eps:.6}");
                    value.setattr("reason", &full)?;
                    value.setattr("args", (full,))?;
                }
            }
            if let Some(hint) = &out.hint {
                value.setattr("hint", hint)?;
            }
            d.set_item("error", value)?;
        }
    }
    Ok(d)
}
