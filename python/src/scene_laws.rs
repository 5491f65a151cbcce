//! `Scene.ball_laws`: the ball-ball contact law of every pair of species of a scene (the
//! pair's `[[contact.pair]]` law, else `contact.balls`), in the forms `Scene.from_dict`
//! takes: `"no-slip"`, `"smooth"`, `{"e": Fraction, "beta": Fraction}` (rough) or
//! `{"e", "mu", "beta0"}` (Walton), exact.

use noslip_scene::ContactKind;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::fmt::Display;

/// `x` (an exact number) as a `fractions.Fraction`, from its `p/q` text.
fn fraction<'py>(py: Python<'py>, x: &dyn Display) -> PyResult<Bound<'py, PyAny>> {
    py.import("fractions")?
        .getattr("Fraction")?
        .call1((x.to_string(),))
}

/// `law` as a Python value: a name or a dict of exact numbers.
fn law<'py>(py: Python<'py>, law: &ContactKind) -> PyResult<Bound<'py, PyAny>> {
    let numbers = |pairs: &[(&str, &dyn Display)]| -> PyResult<Bound<'py, PyAny>> {
        let d = PyDict::new(py);
        for (k, x) in pairs {
            d.set_item(*k, fraction(py, x)?)?;
        }
        Ok(d.into_any())
    };
    match law {
        ContactKind::NoSlip => Ok("no-slip".into_pyobject(py)?.into_any()),
        ContactKind::Smooth => Ok("smooth".into_pyobject(py)?.into_any()),
        ContactKind::Rough { e, beta } => numbers(&[("e", e), ("beta", beta)]),
        ContactKind::Walton { e, mu, beta0 } => numbers(&[("e", e), ("mu", mu), ("beta0", beta0)]),
    }
}

/// `{(name_a, name_b): law}` for every pair of species `a <= b` (by index) of `scene`.
pub(crate) fn ball_laws<'py>(
    py: Python<'py>,
    scene: &noslip_scene::Scene,
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let species = &scene.species;
    for a in 0..species.len() {
        for b in a..species.len() {
            let key = (species[a].name.as_str(), species[b].name.as_str());
            out.set_item(key, law(py, scene.ball_law(a, b))?)?;
        }
    }
    Ok(out)
}
