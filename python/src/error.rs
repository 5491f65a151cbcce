//! `noslip.InputError`: bad input, as a `ValueError` whose message names the field.

use pyo3::create_exception;
use pyo3::exceptions::{PyOverflowError, PyTypeError, PyValueError};
use pyo3::prelude::*;

create_exception!(
    noslip,
    InputError,
    PyValueError,
    "Bad input (a ``ValueError``): the message names the field (``bodies[1].gamma2: ...``, ``row 17: normal: ...``)."
);

/// An [`InputError`] with `message`.
pub fn input_error(message: impl Into<String>) -> PyErr {
    InputError::new_err(message.into())
}

/// An unsigned integer argument `name` (`events`, `seed`, `dims[0]`, ...), extracted as `T`.
///
/// PyO3's own extraction raises a bare `OverflowError: can't convert negative int to
/// unsigned` for a negative or too large int, naming nothing; this one raises an
/// [`InputError`] naming the argument and its range `low..=high` (the caller passes `T`'s
/// largest value as `high` where the argument has no smaller bound). Values inside `T`'s range
/// but outside `low..=high` pass: the callers' own checks name them with more to say (a
/// count of 0, a `k` above the dimension). A non-integer (`None`, a str, a float) is a
/// `TypeError` naming the argument and the type given (PyO3's own said only `'str' object
/// cannot be interpreted as an integer`).
pub fn unsigned<'py, T>(value: &Bound<'py, PyAny>, name: &str, low: T, high: T) -> PyResult<T>
where
    T: for<'a> FromPyObject<'a, 'py, Error = PyErr> + std::fmt::Display,
{
    match value.extract::<T>() {
        Err(e) if e.is_instance_of::<PyOverflowError>(value.py()) => {
            // `str` of an int beyond Python's digit limit (4300 digits) fails: say so instead.
            let got = value.str().map_or_else(
                |_| "an int of more than 4300 digits".into(),
                |s| s.to_string(),
            );
            Err(input_error(format!(
                "{name}: must be an integer in {low}..={high}, got {got}"
            )))
        }
        Err(e) if e.is_instance_of::<PyTypeError>(value.py()) => {
            let given = value
                .get_type()
                .name()
                .map_or_else(|_| "?".into(), |t| t.to_string());
            Err(PyTypeError::new_err(format!(
                "{name}: must be an integer in {low}..={high}, got {given}"
            )))
        }
        Err(e) => Err(e),
        Ok(v) => Ok(v),
    }
}

/// [`unsigned`] for an optional argument (`None` stays `None`).
pub fn unsigned_opt<'py, T>(
    value: Option<&Bound<'py, PyAny>>,
    name: &str,
    low: T,
    high: T,
) -> PyResult<Option<T>>
where
    T: for<'a> FromPyObject<'a, 'py, Error = PyErr> + std::fmt::Display,
{
    value
        .filter(|v| !v.is_none())
        .map(|v| unsigned(v, name, low, high))
        .transpose()
}
