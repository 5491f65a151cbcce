//! `noslip.InputError`: bad input, as a `ValueError` whose message names the field.

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::PyErr;

create_exception!(
    noslip,
    InputError,
    PyValueError,
    "Bad input: the message names the field (`bodies[1].gamma2: ...`, `row 17: normal: ...`)."
);

/// An [`InputError`] with `message`.
pub fn input_error(message: impl Into<String>) -> PyErr {
    InputError::new_err(message.into())
}
