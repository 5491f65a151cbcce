//! `noslip.Scene`: a validated scene (`noslip-scene`: the TOML format of `noslip simulate`,
//! errors naming the place), made from TOML text, a file or a dict, and picklable (it
//! pickles as its TOML text, so a Dask worker rebuilds the same scene).

use crate::error::input_error;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use std::path::PathBuf;

/// A validated scene and the TOML text it was read from.
#[pyclass(module = "noslip._native", frozen)]
pub struct Scene {
    text: String,
    origin: String,
    /// The validated scene.
    pub inner: noslip_scene::Scene,
}

fn parse(text: &str, origin: &str) -> PyResult<noslip_scene::Scene> {
    noslip_scene::Scene::from_toml(text, origin).map_err(|e| input_error(e.to_string()))
}

/// A Python value as TOML: dicts (string keys), lists and tuples, bools, ints, floats,
/// strings, and `fractions.Fraction` as the scene format's exact `"p/q"` string.
fn to_toml(value: &Bound<'_, PyAny>, place: &str) -> PyResult<toml::Value> {
    let bad = |what: String| input_error(format!("{place}: {what}"));
    if let Ok(d) = value.cast::<PyDict>() {
        let mut table = toml::Table::new();
        for (k, v) in d.iter() {
            let key: String = k.extract().map_err(|_| {
                bad(format!(
                    "keys must be strings, got {}",
                    k.repr().map_or("?".into(), |r| r.to_string())
                ))
            })?;
            let inner = if place.is_empty() {
                key.clone()
            } else {
                format!("{place}.{key}")
            };
            table.insert(key, to_toml(&v, &inner)?);
        }
        return Ok(toml::Value::Table(table));
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        let items = value
            .try_iter()?
            .enumerate()
            .map(|(i, v)| to_toml(&v?, &format!("{place}[{i}]")))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(items));
    }
    if value.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(value.extract()?));
    }
    if value.is_instance_of::<PyInt>() {
        return value
            .extract::<i64>()
            .map(toml::Value::Integer)
            .or_else(|_| Ok(toml::Value::String(value.str()?.to_string())));
    }
    if value.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(value.extract()?));
    }
    if value.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(value.extract()?));
    }
    let type_name = value.get_type().name()?.to_string();
    if type_name == "Fraction" {
        let (p, q): (String, String) = (
            value.getattr("numerator")?.str()?.to_string(),
            value.getattr("denominator")?.str()?.to_string(),
        );
        return Ok(toml::Value::String(format!("{p}/{q}")));
    }
    Err(bad(format!(
        "expected a table, an array, a number, a string or a boolean, got {type_name}"
    )))
}

#[pymethods]
impl Scene {
    /// A scene from TOML `text`; `origin` names it in messages.
    #[new]
    #[pyo3(signature = (text, origin = "<string>".to_string()))]
    fn new(text: String, origin: String) -> PyResult<Self> {
        let inner = parse(&text, &origin)?;
        Ok(Scene {
            text,
            origin,
            inner,
        })
    }

    /// A scene from a TOML file (at most 16 MiB, as for `noslip simulate`).
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<Self> {
        let inner =
            noslip_scene::Scene::from_file(&path).map_err(|e| input_error(e.to_string()))?;
        let text = std::fs::read_to_string(&path)
            .map_err(|e| input_error(format!("{}: cannot read: {e}", path.display())))?;
        Ok(Scene {
            text,
            origin: inner.origin.clone(),
            inner,
        })
    }

    /// A scene from a dict with the TOML file's structure (`{"dim": 2, "box": {...},
    /// "species": [...], ...}`); exact numbers as strings (`"1/20"`) or `Fraction`s.
    #[staticmethod]
    #[pyo3(signature = (scene, origin = "<dict>".to_string()))]
    fn from_dict(scene: &Bound<'_, PyDict>, origin: String) -> PyResult<Self> {
        let value = to_toml(scene.as_any(), "")?;
        let text = toml::to_string(&value).map_err(|e| input_error(format!("{origin}: {e}")))?;
        Scene::new(text, origin)
    }

    /// The TOML text of the scene.
    #[getter]
    fn toml(&self) -> &str {
        &self.text
    }

    /// Where the scene came from (a file name, `<string>`, `<dict>`).
    #[getter]
    fn origin(&self) -> &str {
        &self.origin
    }

    /// The dimension `n`.
    #[getter]
    fn dim(&self) -> usize {
        self.inner.dim
    }

    /// The scene's `description`.
    #[getter]
    fn description(&self) -> &str {
        &self.inner.description
    }

    /// The number of balls.
    #[getter]
    fn balls(&self) -> usize {
        self.inner.ball_count()
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String, String))> {
        let me = slf.get();
        Ok((
            slf.get_type().into_any(),
            (me.text.clone(), me.origin.clone()),
        ))
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene(origin={:?}, dim={}, balls={})",
            self.origin,
            self.inner.dim,
            self.inner.ball_count()
        )
    }
}
