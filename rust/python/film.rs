//! The film's pressure at a stored state for Python (`CompiledModel.film_field`; docs/physics.md
//! §4, "Oil flow and pressure"): solved when asked, from the state and the oil temperature (and a
//! mass-conserving joint's recorded fill) a run stored.

use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::{array2, input_error};
use crate::clearance::ImpactMemory;
use crate::model::Model;

/// `{"theta", "z", "pressure", "peak_pressure", "peak_angle", "side_leakage", "supply_flow"}` of
/// clearance joint `joint` in the state `y` (checked to have the state's length); `None` if dry.
pub(super) fn film_field<'py>(
    py: Python<'py>,
    model: &Model,
    joint: usize,
    y: &[f64],
    temperature: Option<f64>,
    content: Option<PyReadonlyArray1<'py, f64>>,
) -> PyResult<Option<Bound<'py, PyDict>>> {
    let Some(cj) = model.clearance.get(joint) else {
        return Err(input_error(py, "joint", joint, &format!("must be below {}", model.clearance.len())));
    };
    let n = 3 * model.n_bodies();
    let k = cj.kinematics_with(|b| match b {
        None => crate::constraints::BodyKin::GROUND,
        Some(i) => {
            let o = 3 * i as usize;
            crate::constraints::BodyKin::new(&y[o..o + 3], &y[n + o..n + o + 3])
        }
    });
    let vogel = cj.film.as_ref().and_then(|f| f.heat).and_then(|h| h.vogel);
    let viscosity = match (vogel, temperature) {
        (Some(v), Some(t)) if v.holds_at(t) => v.viscosity(t),
        _ => 0.0,
    };
    let mut memory = ImpactMemory { viscosity, ..ImpactMemory::default() };
    if let (Some(m), Some(film)) = (content, cj.film.as_ref().filter(|f| f.mass_conserving)) {
        let m: Vec<f64> = m.as_array().iter().copied().collect();
        let k = 2.0 * film.geometry.journal_radius / film.geometry.length;
        let Some(c) = crate::clearance::cavitation::FilmContent::holding(k, &m) else {
            return Err(input_error(py, "content", format!("array of length {}", m.len()), "must be the film content a run recorded"));
        };
        memory.film = Some(c.shared());
    }
    let (field, r) = py.detach(|| {
        let f = cj.force(&k, &memory);
        let mut scratch = cj.film_scratch();
        let r = cj.flow_and_peak(&k, &f, &memory, scratch.as_mut());
        (cj.film_field(&k, &f, &memory, scratch.as_mut()), r)
    });
    let Some(field) = field else { return Ok(None) };
    let d = PyDict::new(py);
    let nz = field.z.len();
    d.set_item("theta", PyArray1::from_slice(py, &field.theta))?;
    d.set_item("z", PyArray1::from_slice(py, &field.z))?;
    d.set_item("pressure", array2(py, &field.pressure, nz)?)?;
    d.set_item("peak_pressure", r.peak_pressure)?;
    d.set_item("peak_angle", r.peak_angle)?;
    d.set_item("side_leakage", r.side_leakage)?;
    d.set_item("supply_flow", r.supply)?;
    Ok(Some(d))
}

/// The `film` channel of a recording into `d`: `"film"` (outputs × joints ×
/// [`crate::clearance::FILM_COLUMNS`]) and, with mass-conserving joints, `"film_content"` (outputs ×
/// those joints × the fill of their nodes).
pub(super) fn recorded(py: Python<'_>, rec: &crate::record::Recording, d: &Bound<'_, PyDict>) -> PyResult<()> {
    let w = crate::clearance::FILM_COLUMNS.len();
    d.set_item("film", PyArray1::from_slice(py, &rec.film).reshape([rec.t.len(), rec.clearance_joints, w])?)?;
    if !rec.film_content.is_empty() {
        let per = crate::laws::bearing_jfo::JFO_THETA * crate::laws::bearing_jfo::JFO_ZETA;
        let n = rec.film_content.len() / (per * rec.t.len().max(1));
        d.set_item("film_content", PyArray1::from_slice(py, &rec.film_content).reshape([rec.t.len(), n, per])?)?;
    }
    Ok(())
}
