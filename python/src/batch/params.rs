//! A batch's body parameters in `noslip.collide`'s vocabulary: `mass` (`inf` immovable),
//! `lambda` or `distribution`, turned into the kernels' `inv_mass = 1/m` and
//! `gamma2 = 2 lambda / R^2` row by row by `collision_core::Ball::new`, the constructor
//! `noslip.collide` builds its balls with, so a row gets the same ball, bit for bit, and a
//! bad value the same message (naming the key the caller gave).

use super::inputs::{shape_error, shape_text};
use crate::error::input_error;
use collision_core::{Ball, Inertia, Mass, Scalar};
use noslip_case::CaseError;
use numpy::ndarray::ArrayView1;
use numpy::{Element, PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;

/// Entry `i` of a parameter array of length 1 (shared) or `rows`.
fn at<T: Copy>(a: &ArrayView1<'_, T>, i: usize) -> T {
    a[if a.len() == 1 { 0 } else { i }]
}

/// The rows of the given arrays: the longest length (each must be 1 or that).
fn rows<T>(body: usize, arrays: &[(&str, Option<&ArrayView1<'_, T>>)]) -> PyResult<usize> {
    let rows = arrays
        .iter()
        .filter_map(|(_, a)| a.map(|a| a.len()))
        .max()
        .unwrap_or(1);
    for (name, a) in arrays {
        if let Some(a) = a.filter(|a| a.len() != 1 && a.len() != rows) {
            return Err(shape_error(
                &format!("bodies[{body}].{name}"),
                format!("({rows},) or a scalar"),
                a.shape(),
            ));
        }
    }
    Ok(rows)
}

/// `inv_mass` (when `mass` is given) and `gamma2` (when `lambda` or `distribution` is) of
/// body `body` in dimension `dim`, each of length `rows` (or 1 when every input is).
#[allow(clippy::type_complexity)]
fn params<T: Scalar + Copy + Element>(
    dim: usize,
    body: usize,
    mass: Option<ArrayView1<'_, T>>,
    radius: ArrayView1<'_, T>,
    lambda: Option<ArrayView1<'_, T>>,
    distribution: Option<&str>,
) -> PyResult<(Option<Vec<T>>, Option<Vec<T>>)> {
    let inertia_of = |l: Option<T>| match (l, distribution) {
        (Some(l), _) => Ok(Some(Inertia::Lambda(l))),
        (None, Some("uniform")) => Ok(Some(Inertia::Uniform)),
        (None, Some("shell")) => Ok(Some(Inertia::Shell)),
        (None, Some(d)) => Err(input_error(format!(
            "bodies[{body}].distribution: must be \"uniform\" or \"shell\", got {d:?}"
        ))),
        (None, None) => Ok(None),
    };
    let rows = rows(
        body,
        &[
            ("mass", mass.as_ref()),
            ("radius", Some(&radius)),
            ("lambda", lambda.as_ref()),
        ],
    )?;
    let shared = rows == 1;
    let mut inv_mass = mass.as_ref().map(|_| Vec::with_capacity(rows));
    let mut gamma2 = (lambda.is_some() || distribution.is_some()).then(|| Vec::with_capacity(rows));
    for i in 0..rows {
        let m = match mass.as_ref().map(|m| at(m, i)) {
            Some(m) if !m.is_finite() && m > T::zero() => Mass::Infinite,
            Some(m) => Mass::Finite(m),
            None => Mass::Finite(T::one()),
        };
        let inertia = inertia_of(lambda.as_ref().map(|l| at(l, i)))?.unwrap_or(Inertia::Uniform);
        let ball = Ball::new(dim, m, at(&radius, i), inertia).map_err(|e| {
            let e = CaseError::from(e.at_body(body));
            input_error(if shared {
                e.to_string()
            } else {
                format!("row {i}: {e}")
            })
        })?;
        if let Some(v) = inv_mass.as_mut() {
            v.push(ball.inv_mass);
        }
        if let Some(v) = gamma2.as_mut() {
            v.push(ball.gamma2);
        }
    }
    Ok((inv_mass, gamma2))
}

/// The new parameter arrays, for Python.
type ParamsOut<'py, T> = (
    Option<Bound<'py, PyArray1<T>>>,
    Option<Bound<'py, PyArray1<T>>>,
);

fn params_py<'py, T: Scalar + Copy + Element>(
    py: Python<'py>,
    dim: usize,
    body: usize,
    mass: Option<PyReadonlyArray1<'py, T>>,
    radius: PyReadonlyArray1<'py, T>,
    lambda: Option<PyReadonlyArray1<'py, T>>,
    distribution: Option<&str>,
) -> PyResult<ParamsOut<'py, T>> {
    if !(2..=noslip_case::case::MAX_DIM).contains(&dim) {
        return Err(input_error(format!(
            "normal: expected n in 2..={}, got shape {}",
            noslip_case::case::MAX_DIM,
            shape_text(&[dim])
        )));
    }
    let (inv_mass, gamma2) = params(
        dim,
        body,
        mass.as_ref().map(|a| a.as_array()),
        radius.as_array(),
        lambda.as_ref().map(|a| a.as_array()),
        distribution,
    )?;
    Ok((
        inv_mass.map(|v| PyArray1::from_vec(py, v)),
        gamma2.map(|v| PyArray1::from_vec(py, v)),
    ))
}

/// Body ``body``'s kernel parameters from ``noslip.collide``'s keys, in float64.
///
/// Returns ``(inv_mass, gamma2)``: ``1/mass`` (0 for ``inf``) when ``mass`` is given, and
/// ``2 lambda / R^2`` (or the ``distribution``'s) when ``lambda`` or ``distribution`` is,
/// else ``None``; each computed by the constructor of ``noslip.collide``'s balls. Raises
/// ``InputError`` naming ``row i: bodies[b].key``.
#[pyfunction]
#[pyo3(signature = (dim, body, mass, radius, lambda_, distribution))]
pub fn batch_params_f64<'py>(
    py: Python<'py>,
    dim: usize,
    body: usize,
    mass: Option<PyReadonlyArray1<'py, f64>>,
    radius: PyReadonlyArray1<'py, f64>,
    lambda_: Option<PyReadonlyArray1<'py, f64>>,
    distribution: Option<&str>,
) -> PyResult<ParamsOut<'py, f64>> {
    params_py(py, dim, body, mass, radius, lambda_, distribution)
}

/// ``batch_params_f64`` in float32.
#[pyfunction]
#[pyo3(signature = (dim, body, mass, radius, lambda_, distribution))]
pub fn batch_params_f32<'py>(
    py: Python<'py>,
    dim: usize,
    body: usize,
    mass: Option<PyReadonlyArray1<'py, f32>>,
    radius: PyReadonlyArray1<'py, f32>,
    lambda_: Option<PyReadonlyArray1<'py, f32>>,
    distribution: Option<&str>,
) -> PyResult<ParamsOut<'py, f32>> {
    params_py(py, dim, body, mass, radius, lambda_, distribution)
}
