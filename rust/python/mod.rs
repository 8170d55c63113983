//! The pyo3 glue: the only module that knows about Python (feature `python`).
//!
//! Descriptions and run settings arrive as plain data built by `python/clearsim/mechanism.py`
//! and `running.py` and enter the core through serde (`de.rs` for settings); results leave as
//! dicts of numpy arrays. Every [`Error`] becomes a Python exception of `clearsim.errors` in
//! [`to_pyerr`], and nowhere else. The GIL is released while integrating.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::Instant;

use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::batch::{run_batch, run_one, run_with_twin};
use crate::clearance::ImpactMemory;
use crate::error::Error;
use crate::integrate::OdeSystem;
use crate::description::{MechanismDesc, ELEMENTS};
use crate::model::Model;
use crate::error::Warning;
use crate::record::{Channels, JOINT_COLUMNS};
use crate::settings::RunSettingsDesc;
use crate::simulate::{simulate, MechanismSystem, RunSettings};
use crate::system::Workspace;

// ---------------------------------------------------------------- errors (the one mapping)

/// Map a crate error to the matching exception class of `clearsim.errors`.
fn to_pyerr(py: Python<'_>, e: &Error) -> PyErr {
    let build = || -> PyResult<PyErr> {
        let errors = py.import("clearsim.errors")?;
        let kwargs = PyDict::new(py);
        // A failed reference run is the kind of error its cause is, with the message saying whose.
        let class = match e.root() {
            Error::InvalidInput { field, value, .. } => {
                kwargs.set_item("field", field)?;
                kwargs.set_item("value", value)?;
                "InputError"
            }
            Error::Name { name, .. } => {
                kwargs.set_item("field", "name")?;
                kwargs.set_item("value", name)?;
                "InputError"
            }
            Error::Assembly { t, .. } => {
                kwargs.set_item("t", t)?;
                "AssemblyError"
            }
            Error::PoseMoved { body, joint, moved, turned, field, value, .. } => {
                kwargs.set_item("t", 0.0)?;
                kwargs.set_item("body", body)?;
                kwargs.set_item("joint", joint)?;
                kwargs.set_item("moved", moved)?;
                kwargs.set_item("turned", turned)?;
                kwargs.set_item("field", field)?;
                kwargs.set_item("value", value)?;
                kwargs.set_item("result", py.None())?;
                "AssemblyError"
            }
            Error::Interrupted { t } => {
                kwargs.set_item("t", t)?;
                "InterruptedRun"
            }
            Error::PenetrationTooDeep { t, joint, penetration, .. } => {
                kwargs.set_item("t", t)?;
                kwargs.set_item("joint", joint)?;
                kwargs.set_item("penetration", penetration)?;
                "SimulationError"
            }
            other => {
                kwargs.set_item("t", other.time())?;
                "SimulationError"
            }
        };
        kwargs.set_item("reason", e.to_string())?;
        let exc = errors.getattr(class)?.call((e.to_string(),), Some(&kwargs))?;
        Ok(PyErr::from_value(exc))
    };
    build().unwrap_or_else(|err| err)
}

fn input_error(py: Python<'_>, field: &str, value: impl std::fmt::Display, reason: &str) -> PyErr {
    to_pyerr(py, &Error::invalid(field, value, reason))
}

/// `v` (row-major, `cols` a row) as a numpy array of shape (rows, cols).
fn array2<'py>(py: Python<'py>, v: &[f64], cols: usize) -> PyResult<Bound<'py, PyAny>> {
    let rows = if cols == 0 { 0 } else { v.len() / cols };
    Ok(PyArray1::from_slice(py, v).reshape([rows, cols])?.into_any())
}

// ---------------------------------------------------------------- reading plain data

mod de;
mod film;
mod output;

use output::output_to_dict;

/// Run settings from Python plain data (the dict `Mechanism.run_settings` builds), through serde
/// ([`crate::settings::RunSettingsDesc`]) and validated. A key or value that does not fit is an
/// `InputError` naming its path (`monitors[0].quantity`).
fn read_settings(d: &Bound<'_, PyAny>) -> PyResult<RunSettings> {
    let py = d.py();
    let desc: RunSettingsDesc = serde_path_to_error::deserialize(de::PyData(d.clone())).map_err(|e| {
        let path = e.path().to_string();
        let field = if path == "." { "settings".to_string() } else { path };
        // The value as the user wrote it, for a top-level setting (`max_steps = True`).
        let value = d.get_item(field.as_str()).ok().and_then(|v| v.repr().ok()).map_or_else(|| "…".to_string(), |r| r.to_string());
        to_pyerr(py, &Error::invalid(field, value, e.inner().to_string()))
    })?;
    desc.into_settings().map_err(|e| to_pyerr(py, &e))
}

/// A description from Python: a JSON string, or plain data (dicts, lists, numbers, strings),
/// elements referring to one another by name. Either way it enters the core through serde
/// ([`crate::description::from_value`], names resolved there), the one path.
fn read_description(d: &Bound<'_, PyAny>) -> PyResult<MechanismDesc> {
    let py = d.py();
    let v = match d.extract::<String>() {
        Ok(text) => return crate::description::from_json(&text).map_err(|e| to_pyerr(py, &e)),
        Err(_) => plain_value(d, "", true)?,
    };
    crate::description::from_value(v).map_err(|e| to_pyerr(py, &e))
}

/// Python plain data as a JSON value. A number that is not finite (JSON has no NaN) is an
/// `InputError` naming its field the way validation does (`clearance joint 'B'.model.friction`).
fn plain_value(obj: &Bound<'_, PyAny>, field: &str, top: bool) -> PyResult<serde_json::Value> {
    use serde_json::Value;
    let py = obj.py();
    let key = |k: &str| if field.is_empty() { k.to_string() } else { format!("{field}.{k}") };
    if obj.is_none() {
        return Ok(Value::Null);
    }
    if let Ok(b) = obj.cast::<pyo3::types::PyBool>() {
        return Ok(Value::Bool(b.is_true()));
    }
    if let Ok(s) = obj.cast::<pyo3::types::PyString>() {
        return Ok(Value::String(s.extract::<String>()?));
    }
    if obj.cast::<pyo3::types::PyFloat>().is_err() {
        if let Ok(i) = obj.extract::<i64>() {
            return Ok(Value::from(i));
        }
    }
    if let Ok(x) = obj.extract::<f64>() {
        return serde_json::Number::from_f64(x)
            .map(Value::Number)
            .ok_or_else(|| input_error(py, if field.is_empty() { "description" } else { field }, crate::compile::num(x), "must be a finite number"));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        let mut map = serde_json::Map::with_capacity(d.len());
        for (k, v) in d.iter() {
            let k: String = k.extract().map_err(|_| input_error(py, field, &k, "keys must be strings"))?;
            let list_of = if top { ELEMENTS.iter().find(|(l, _)| *l == k).map(|(_, what)| *what) } else { None };
            let value = match list_of {
                Some(what) => {
                    let mut items = Vec::new();
                    for (i, item) in v.try_iter()?.enumerate() {
                        let item = item?;
                        let name = item.get_item("name").ok().and_then(|n| n.extract::<String>().ok());
                        let f = name.map_or_else(|| format!("{k}[{i}]"), |n| format!("{what} '{n}'"));
                        items.push(plain_value(&item, &f, false)?);
                    }
                    Value::Array(items)
                }
                None => plain_value(&v, &key(&k), false)?,
            };
            map.insert(k, value);
        }
        return Ok(Value::Object(map));
    }
    if obj.hasattr("tolist")? && !obj.is_instance_of::<PyList>() {
        return plain_value(&obj.call_method0("tolist")?, field, top); // numpy arrays and scalars
    }
    if let Ok(it) = obj.try_iter() {
        let mut items = Vec::new();
        for (i, item) in it.enumerate() {
            items.push(plain_value(&item?, &format!("{field}[{i}]"), false)?);
        }
        return Ok(Value::Array(items));
    }
    Err(input_error(py, if field.is_empty() { "description" } else { field }, obj.repr()?, "must be plain data (dicts, lists, numbers, strings)"))
}

/// The check polled during long runs (at most every 50 ms): runs Python's signal handlers
/// (Ctrl-C interrupts the run) and reports the simulated time reached to `progress(t)` if given
/// (an exception raised there also stops the run).
///
/// Python runs signal handlers only in its main thread, so without a progress callback the check
/// takes the GIL only on the thread that made it, and only if that is Python's main thread: a
/// run in a worker thread (or a batch's rayon threads) never waits for a GIL another thread holds
/// (which used to hold runs past their wall-time budget: 16 s against 5 s in `clearsim paper`).
fn make_stop(py: Python<'_>, progress: Option<Py<PyAny>>) -> impl Fn(f64) -> bool + Sync {
    let start = Instant::now();
    let last = AtomicU64::new(0);
    let on_main = match py.import("threading").and_then(|th| Ok(th.call_method0("current_thread")?.is(&th.call_method0("main_thread")?))) {
        Ok(v) => v,
        Err(e) => {
            // A Ctrl-C that lands in these calls must not be lost: trip the signal again, for
            // the first check of the run.
            if e.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py) {
                unsafe { pyo3::ffi::PyErr_SetInterrupt() };
            }
            true
        }
    };
    let owner = std::thread::current().id();
    move |t: f64| {
        if progress.is_none() && !(on_main && std::thread::current().id() == owner) {
            return false;
        }
        let now = start.elapsed().as_millis() as u64;
        if now.saturating_sub(last.load(Ordering::Relaxed)) < 50 {
            return false;
        }
        last.store(now, Ordering::Relaxed);
        Python::attach(|py| {
            if py.check_signals().is_err() {
                return true;
            }
            match &progress {
                Some(cb) => cb.call1(py, (t,)).is_err(),
                None => false,
            }
        })
    }
}

// ---------------------------------------------------------------- the Python classes

/// A validated, compiled mechanism (built by `clearsim.Mechanism`), assembled at t = 0 once,
/// with what looks wrong in it (`warnings`) and the pose check's verdict (raised before a run).
#[pyclass(module = "clearsim._core", frozen)]
pub struct CompiledModel {
    model: Model,
    /// What it was compiled from: the runs its monitors measure it against are made from it.
    desc: MechanismDesc,
    rhs_ws: Mutex<(Workspace, Vec<ImpactMemory>)>,
    warnings: Vec<Warning>,
    /// The pose given moved too far by its assembly ([`crate::pose::check`]).
    pose: Option<Error>,
}

#[pymethods]
impl CompiledModel {
    /// What `integrator = "auto"` picks for this model (`crate::settings::default_method`):
    /// `"radau"` when a clearance joint is lubricated, else `"rk45"`.
    #[getter]
    fn default_integrator(&self) -> &'static str {
        crate::settings::default_method(&self.model).name()
    }

    /// Length of the state y = (q, q̇, T…): 6 per body, then one oil temperature per clearance
    /// joint with a heat model (rust/clearance/thermal.rs).
    #[getter]
    fn state_dim(&self) -> usize {
        self.model.state_dim()
    }

    /// Number of scalar constraint equations.
    #[getter]
    fn constraint_rows(&self) -> usize {
        self.model.rows
    }

    /// Degrees of freedom (3 per body − constraint equations).
    #[getter]
    fn dof(&self) -> isize {
        self.model.dof()
    }

    /// What is valid but looks like a mistake, as `(field, message)`: a size that looks like
    /// millimetres against the mechanism's span ([`crate::compile::plausibility`]), a pose given
    /// that assembles but looks wrong ([`crate::pose`]).
    #[getter]
    fn warnings(&self) -> Vec<(String, String)> {
        self.warnings.iter().map(|w| (w.field.clone(), w.message.clone())).collect()
    }

    /// Raise the pose check's `AssemblyError` if the assembly moved a body too far (as
    /// `simulate` does before it runs).
    fn check_pose(&self, py: Python<'_>) -> PyResult<()> {
        self.pose.as_ref().map_or(Ok(()), |e| Err(to_pyerr(py, e)))
    }

    /// Contact stiffness K of each clearance joint [N/m^n].
    #[getter]
    fn contact_stiffness(&self) -> Vec<f64> {
        self.model.clearance.iter().map(|c| c.contact.stiffness).collect()
    }

    /// Consistent initial state y0 at t0 (kinematic assembly; the oil temperatures at their
    /// initial values).
    fn initial_state<'py>(&self, py: Python<'py>, t0: f64) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (q, qd) = crate::assembly::assemble(&self.model, t0).map_err(|e| to_pyerr(py, &e))?;
        Ok(PyArray1::from_vec(py, self.model.initial_state(&q, &qd)))
    }

    /// ẏ = f(t, y) for external integrators (no impact memory: δ̇⁽⁻⁾ is the current approach
    /// speed).
    fn rhs<'py>(&self, py: Python<'py>, t: f64, y: PyReadonlyArray1<'py, f64>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let y = self.state_vector(py, &y)?;
        let dim = y.len();
        let mut guard = self.rhs_ws.lock().map_err(|_| PyRuntimeError::new_err("workspace poisoned"))?;
        let (ws, mem) = &mut *guard;
        ws.evaluate(&self.model, mem, t, &y).map_err(|e| to_pyerr(py, &e))?;
        let mut dy = vec![0.0; dim];
        ws.derivative(&y, &mut dy);
        Ok(PyArray1::from_vec(py, dy))
    }

    /// The stiff part of ∂f/∂y at (t, y), dense (dim × dim): `[[0, I, 0], [W_q, W_v, A_T],
    /// [G_q, G_v, G_T]]` with the clearance joints' force derivatives mapped through the
    /// constrained mobility and, with heat models, the rows and columns of the oil temperatures
    /// (RADAU5's Newton matrix; no impact memory, as `rhs`).
    fn jacobian<'py>(&self, py: Python<'py>, t: f64, y: PyReadonlyArray1<'py, f64>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let y = self.state_vector(py, &y)?;
        let dim = y.len();
        let mut sys = MechanismSystem::new(&self.model, Channels::default(), 0, None);
        let k = sys.first_order_states();
        let m = (dim - k) / 2;
        let (mut w_q, mut w_v) = (vec![0.0; m * m], vec![0.0; m * m]);
        sys.acceleration_jacobian(t, &y, &mut w_q, &mut w_v).map_err(|e| to_pyerr(py, &e))?;
        let (mut a_z, mut z_y) = (vec![0.0; m * k], vec![0.0; k * dim]);
        sys.border_jacobian(t, &y, &mut a_z, &mut z_y).map_err(|e| to_pyerr(py, &e))?;
        let mut rows = vec![vec![0.0; dim]; dim];
        for i in 0..m {
            rows[i][m + i] = 1.0;
            for j in 0..m {
                rows[m + i][j] = w_q[i + j * m];
                rows[m + i][m + j] = w_v[i + j * m];
            }
            for c in 0..k {
                rows[m + i][2 * m + c] = a_z[i + c * m];
            }
        }
        for r in 0..k {
            rows[2 * m + r].copy_from_slice(&z_y[r * dim..(r + 1) * dim]);
        }
        PyArray2::from_vec2(py, &rows).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// Run the model; returns a dict of arrays (see `clearsim.result.Result`). `progress(t)`,
    /// if given, is called with the simulated time reached [s] about every 50 ms. Monitors
    /// measured against the model's own ideal twin (or, given `nominal`, a description of the
    /// nominal design, against its ideal) get their reference run here (`crate::batch::run_one`).
    #[pyo3(signature = (settings, progress=None, nominal=None))]
    fn simulate<'py>(&self, py: Python<'py>, settings: &Bound<'py, PyDict>, progress: Option<Py<PyAny>>, nominal: Option<Bound<'py, PyAny>>) -> PyResult<Bound<'py, PyDict>> {
        self.check_pose(py)?;
        let rs = read_settings(settings.as_any())?;
        let nominal = nominal.map(|d| read_description(&d)).transpose()?;
        let (model, desc) = (&self.model, &self.desc);
        let stop = make_stop(py, progress);
        let measured = rs.monitors.iter().any(|m| m.reference.is_some());
        let out = py
            .detach(|| if measured { run_one(model, desc, &rs, nominal.as_ref(), Some(&stop)) } else { simulate(model, &rs, Some(&stop)) })
            .map_err(|e| to_pyerr(py, &e))?;
        output_to_dict(py, &out)
    }

    /// Run the model and its ideal twin (`ideal`: the description `clearsim.Mechanism.idealized`
    /// gives, run with `ideal_settings`) side by side, the GIL released
    /// ([`crate::batch::run_with_twin`]): `(result, ideal)`, each a dict of arrays or the
    /// exception that prevented that run, as `run_batch` gives them.
    fn simulate_with_ideal<'py>(&self, py: Python<'py>, settings: &Bound<'py, PyDict>, ideal: &Bound<'py, PyAny>, ideal_settings: &Bound<'py, PyDict>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        self.check_pose(py)?;
        let (rs, twin, twin_rs) = (read_settings(settings.as_any())?, read_description(ideal)?, read_settings(ideal_settings.as_any())?);
        let stop = make_stop(py, None);
        let (own, other) = py.detach(|| run_with_twin(&self.model, &self.desc, &rs, &twin, &twin_rs, Some(&stop)));
        Ok((dict_or_error(py, &own)?, dict_or_error(py, &other)?))
    }

    /// The film pressure of clearance joint `joint` (its index) in the state `y` (docs/physics.md
    /// §4, "Oil flow and pressure"; `film.rs`); `temperature` [K] the oil's then, `content` the
    /// fill a mass-conserving joint's run recorded. `None` for a dry joint.
    #[pyo3(signature = (joint, y, temperature=None, content=None))]
    fn film_field<'py>(
        &self,
        py: Python<'py>,
        joint: usize,
        y: PyReadonlyArray1<'py, f64>,
        temperature: Option<f64>,
        content: Option<PyReadonlyArray1<'py, f64>>,
    ) -> PyResult<Option<Bound<'py, PyDict>>> {
        let y = self.state_vector(py, &y)?;
        film::film_field(py, &self.model, joint, &y, temperature, content)
    }
}

impl CompiledModel {
    /// `y` as a vector, checked to have the state's length.
    fn state_vector(&self, py: Python<'_>, y: &PyReadonlyArray1<'_, f64>) -> PyResult<Vec<f64>> {
        let y = y.as_array();
        let dim = self.model.state_dim();
        if y.len() != dim {
            return Err(input_error(py, "y", format!("array of length {}", y.len()), &format!("must have length {dim}")));
        }
        Ok(y.iter().copied().collect())
    }

    /// Compile `desc` and check it: its plausibility against its own size, and its pose given
    /// against the assembly at t = 0 with the assembly `tolerance` (`None` accepts any pose).
    fn build(py: Python<'_>, desc: MechanismDesc, tolerance: Option<f64>) -> PyResult<Self> {
        // Without the GIL: a finite-bearing table built here takes seconds, and other Python
        // threads (the runs of a thread pool, their stop checks) must not wait for it.
        let model = py.detach(|| Model::compile(&desc)).map_err(|e| to_pyerr(py, &e))?;
        let mut warnings = crate::compile::plausibility::findings(&desc);
        // A pose that does not assemble at all is the run's to report (with its diagnosis).
        let pose = match &model.start {
            Some(Ok(q0)) => match crate::pose::check(&desc, q0, tolerance) {
                Ok(w) => {
                    warnings.extend(w);
                    None
                }
                Err(e) => Some(e),
            },
            _ => None,
        };
        let ws = Workspace::new(&model);
        let mem = vec![ImpactMemory::default(); model.clearance.len()];
        Ok(CompiledModel { model, desc, rhs_ws: Mutex::new((ws, mem)), warnings, pose })
    }
}

/// Validate and compile a mechanism description (a dict, bodies named), assemble its pose given
/// and check it against the assembly `tolerance` (a fraction of the span; `None`: any pose).
#[pyfunction]
#[pyo3(signature = (description, assembly_tolerance = Some(crate::pose::ASSEMBLY_TOLERANCE)))]
fn compile(py: Python<'_>, description: &Bound<'_, PyAny>, assembly_tolerance: Option<f64>) -> PyResult<CompiledModel> {
    let desc = read_description(description)?;
    CompiledModel::build(py, desc, assembly_tolerance)
}

/// Check one element (`group`: `"bodies"`, `"joints"`, `"drivers"`, `"clearance_joints"`,
/// `"prismatic_clearance_joints"`, `"forces"`) or a clearance model alone (`"dry"`,
/// `"lubricated"`) as it is added: its own values, by the compile's checks
/// ([`crate::compile::check_element`]); its references by name are the compile's.
#[pyfunction]
fn check_element(group: &str, entry: &Bound<'_, PyAny>) -> PyResult<()> {
    let py = entry.py();
    // How a non-finite number's field is named, as in a description: `body 'crank'.mass`.
    let name = entry.get_item("name").ok().and_then(|n| n.extract::<String>().ok());
    let what = match (ELEMENTS.iter().find(|(l, _)| *l == group), name) {
        (Some((_, what)), Some(n)) => format!("{what} '{n}'"),
        _ => String::new(),
    };
    let v = plain_value(entry, &what, false)?;
    crate::compile::check_element(group, &v).map_err(|e| to_pyerr(py, &e))
}

/// A description (bodies named) with its references resolved into body indices (the ground:
/// `None`) and every default filled in, as plain data: how the core reads it (for drawings).
#[pyfunction]
fn resolve<'py>(py: Python<'py>, description: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    to_plain(py, &read_description(description)?)
}

/// What looks like a unit slip against the size of a description not yet valid as a whole
/// (`crate::compile::plausibility::findings`, as `(field, message)`): what explains an element
/// refused as it is added (a journal radius in mm gives a film outside the finite bearing's range).
#[pyfunction]
fn findings(description: &Bound<'_, PyAny>) -> PyResult<Vec<(String, String)>> {
    let desc = read_description(description)?;
    Ok(crate::compile::plausibility::findings(&desc).into_iter().map(|w| (w.field, w.message)).collect())
}

/// What looks wrong in an output point (`crate::compile::plausibility::output_point`): the point
/// `point` (body frame [m]) on the body named `body` of `description`, `field` naming it in the
/// message; `None` when nothing does (or no such body: the caller's InputError says so).
#[pyfunction]
fn output_point_finding(description: &Bound<'_, PyAny>, body: &str, point: [f64; 2], field: &str) -> PyResult<Option<(String, String)>> {
    let desc = read_description(description)?;
    let Some(b) = desc.bodies.iter().position(|x| x.name == body) else { return Ok(None) };
    Ok(crate::compile::plausibility::output_point(&desc, b, point, field).map(|w| (w.field, w.message)))
}

/// Poses given assembled by this process (one per compiled model; for tests).
#[pyfunction]
fn assembly_count() -> usize {
    crate::assembly::assembly_count()
}

/// Check run settings (the dict `Mechanism.run_settings` writes) as a run does, without running:
/// for a scene file, whose mistakes are reported at load with their line.
#[pyfunction]
fn check_settings(settings: &Bound<'_, PyAny>) -> PyResult<()> {
    read_settings(settings).map(|_| ())
}

/// The ideal counterpart of a description ([`MechanismDesc::idealized`], the one implementation
/// of idealisation): read through serde, idealised, and handed back as plain data with bodies
/// named again ([`crate::names::unresolve`]; written by serde with every default filled
/// in, read by Python's `json`: floats round-trip exactly).
#[pyfunction]
fn idealize<'py>(py: Python<'py>, description: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let desc = read_description(description)?.idealized();
    let mut v = serde_json::to_value(&desc).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    crate::names::unresolve(&mut v);
    to_plain(py, &v)
}

/// A serde-serialisable value as Python plain data (dicts, lists, floats, strings, None).
fn to_plain<'py, T: serde::Serialize>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// The defaults of the clearance-joint parameters, where they are defined (the serde defaults of
/// [`crate::description`]): `{"dry": {...}, "lubricated": {...}, "prismatic_clearance": {...}}`,
/// for `clearsim.joints` and `clearsim.Mechanism.prismatic_clearance`; and the integrator's
/// (`crate::integrate::Settings::default`) and the most outputs a `dt_out` grid may ask for
/// (`crate::settings::MAX_OUTPUTS`): `{"settings": {rtol, atol, h_min, max_steps, max_outputs}}`.
fn defaults(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    let lubricated: crate::description::LubricatedDesc = serde_json::from_value(serde_json::json!({"viscosity": 1.0, "length": 1.0}))
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    let mut lub = serde_json::to_value(&lubricated).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    if let Some(map) = lub.as_object_mut() {
        for required in ["viscosity", "length", "dry"] {
            map.remove(required);
        }
    }
    let corner: crate::description::PrismaticClearanceDesc =
        serde_json::from_value(serde_json::json!({"name": "", "guide_body": null, "guide_point": [0.0, 0.0], "slider_body": 0, "axis": [1.0, 0.0], "clearance": 1.0, "slider_length": 1.0}))
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    let ode = crate::integrate::Settings::default();
    let all = serde_json::json!({
        "dry": crate::description::DryDesc::default(),
        "lubricated": lub,
        "prismatic_clearance": {"corner_radius": corner.corner_radius},
        "settings": {"rtol": ode.rtol, "atol": ode.atol, "h_min": ode.h_min, "max_steps": ode.max_steps, "max_outputs": crate::settings::MAX_OUTPUTS},
    });
    to_plain(py, &all)
}

/// Run many descriptions in parallel on `threads` threads (0: all cores; rayon, GIL released).
/// `settings` is one dict shared by all runs or a list with one dict per description;
/// `nominal`, the nominal design's description, for monitors measured against its ideal
/// (`crate::batch::run_batch` makes each distinct reference run once). Returns one result dict
/// per description, or the exception that prevented that run.
#[pyfunction(name = "run_batch")]
#[pyo3(signature = (descriptions, settings, threads=0, nominal=None))]
fn batch<'py>(py: Python<'py>, descriptions: Vec<Bound<'py, PyAny>>, settings: &Bound<'py, PyAny>, threads: usize, nominal: Option<Bound<'py, PyAny>>) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let descs = descriptions.iter().map(|d| read_description(d)).collect::<PyResult<Vec<_>>>()?;
    let nominal = nominal.map(|d| read_description(&d)).transpose()?;
    let settings: Vec<RunSettings> = if let Ok(d) = settings.cast::<PyDict>() {
        vec![read_settings(d.as_any())?]
    } else {
        let list: Vec<Bound<'py, PyDict>> = settings.extract().map_err(|_| input_error(py, "settings", "<not a dict or list of dicts>", "must be a dict or a list of dicts"))?;
        if list.len() != descs.len() {
            return Err(input_error(py, "settings", format!("{} entries", list.len()), &format!("must have one entry per description ({})", descs.len())));
        }
        list.iter().map(|d| read_settings(d.as_any())).collect::<PyResult<Vec<_>>>()?
    };
    let stop = make_stop(py, None);
    let outs = py.detach(|| run_batch(&descs, &settings, nominal.as_ref(), threads, Some(&stop)));
    outs.iter().map(|o| dict_or_error(py, o)).collect()
}

/// A run's output as a dict of arrays, or the exception that prevented it (returned, not raised).
fn dict_or_error<'py>(py: Python<'py>, out: &crate::error::Result<crate::simulate::RunOutput>) -> PyResult<Bound<'py, PyAny>> {
    match out {
        Ok(out) => Ok(output_to_dict(py, out)?.into_any()),
        Err(e) => Ok(to_pyerr(py, e).value(py).clone().into_any()),
    }
}

/// Film force `(F_ξ, F_η)` [N] on the journal of a lubricated joint (docs/physics.md §4): `film`
/// one of long, short, long_paper, finite; the geometry in SI; ε, ε̇ [1/s], wedge speed [rad/s].
/// For studying the film laws; a finite bearing takes its table from the cache (or builds it),
/// with `supply` "widest_gap" (default) or "none" (docs/physics.md §4).
#[pyfunction]
#[pyo3(signature = (film, viscosity, journal_radius, clearance, length, eps, eps_dot, wedge, supply = "widest_gap"))]
#[allow(clippy::too_many_arguments)]
fn film_force(py: Python<'_>, film: &str, viscosity: f64, journal_radius: f64, clearance: f64, length: f64, eps: f64, eps_dot: f64, wedge: f64, supply: &str) -> PyResult<(f64, f64)> {
    use crate::laws::{BearingGeometry, FilmModel, FilmState, FilmSupply};
    let model = match film {
        "long" => FilmModel::LongBearing,
        "short" => FilmModel::ShortBearing,
        "long_paper" => FilmModel::LongBearingPaperClosedForm,
        "finite" => FilmModel::Finite,
        other => return Err(input_error(py, "film", other, "must be one of long, short, long_paper, finite")),
    };
    let supply = match supply {
        "widest_gap" => FilmSupply::WidestGap,
        "none" => FilmSupply::None,
        other => return Err(input_error(py, "supply", other, "must be one of widest_gap, none")),
    };
    for (name, v) in [("viscosity", viscosity), ("journal_radius", journal_radius), ("clearance", clearance), ("length", length)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(input_error(py, name, v, "must be positive and finite"));
        }
    }
    for (name, v) in [("eps", eps), ("eps_dot", eps_dot), ("wedge", wedge)] {
        if !v.is_finite() {
            return Err(input_error(py, name, v, "must be finite"));
        }
    }
    if model == FilmModel::Finite {
        crate::compile::check_finite_bearing_ratio("film", length / (2.0 * journal_radius)).map_err(|e| to_pyerr(py, &e))?;
    }
    let g = BearingGeometry { viscosity, journal_radius, clearance, length };
    Ok(py.detach(|| {
        let table = (model == FilmModel::Finite).then(|| crate::laws::bearing_finite_cache::table_for(2.0 * journal_radius / length, supply));
        crate::laws::film_force(model, &g, FilmState { eps, eps_dot, wedge }, table)
    }))
}

/// Finite-bearing tables solved and loaded from the disk cache by this process (for tests).
#[pyfunction]
fn finite_table_counts() -> (usize, usize) {
    crate::laws::bearing_finite_cache::table_counts()
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", crate::version())?;
    m.add("JOINT_COLUMNS", JOINT_COLUMNS.to_vec())?;
    m.add("ENERGY_COLUMNS", crate::energy::ENERGY_COLUMNS.to_vec())?;
    m.add("FILM_COLUMNS", crate::clearance::FILM_COLUMNS.to_vec())?;
    m.add_class::<CompiledModel>()?;
    m.add_function(wrap_pyfunction!(compile, m)?)?;
    m.add_function(wrap_pyfunction!(idealize, m)?)?;
    m.add_function(wrap_pyfunction!(check_element, m)?)?;
    m.add_function(wrap_pyfunction!(resolve, m)?)?;
    m.add_function(wrap_pyfunction!(assembly_count, m)?)?;
    m.add_function(wrap_pyfunction!(findings, m)?)?;
    m.add_function(wrap_pyfunction!(output_point_finding, m)?)?;
    m.add("MICROMETRE_FILM_RATIO", crate::simulate::MICROMETRE_FILM_RATIO)?;
    m.add_function(wrap_pyfunction!(check_settings, m)?)?;
    m.add("DEFAULTS", defaults(m.py())?)?;
    m.add_function(wrap_pyfunction!(batch, m)?)?;
    m.add_function(wrap_pyfunction!(film_force, m)?)?;
    m.add_function(wrap_pyfunction!(finite_table_counts, m)?)?;
    Ok(())
}
