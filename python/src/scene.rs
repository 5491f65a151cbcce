//! `noslip.Scene`: a validated scene (`noslip-scene`: the TOML format of `noslip simulate`,
//! errors naming the place), made from TOML text, a file or a dict, and picklable (it
//! pickles as its TOML text, so a Dask worker rebuilds the same scene).

use crate::error::input_error;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use std::path::{Path, PathBuf};

/// A validated scene (the TOML format of ``noslip simulate``) and the text it was read from.
///
/// Made from TOML text (``Scene(text)``), a file (``Scene.from_file``) or a dict
/// (``Scene.from_dict``); pickles as its text and origin (a Dask worker rebuilds the same
/// scene), and compares equal to a scene of the same text and origin.
///
/// Parameters
/// ----------
/// text : str
///     The scene as TOML.
/// origin : str
///     The scene's name in messages (default ``"<string>"``).
#[pyclass(module = "noslip._native", frozen)]
pub struct Scene {
    text: String,
    origin: String,
    /// The validated scene.
    pub inner: noslip_scene::Scene,
}

/// Scene `text` parsed and validated (`origin` names it in messages); a failure is an
/// [`InputError`](crate::error::InputError) naming the place, with a hint when the text
/// looks like a file name.
fn parse(text: &str, origin: &str) -> PyResult<noslip_scene::Scene> {
    noslip_scene::Scene::from_toml(text, origin).map_err(|e| {
        let mut message = e.to_string();
        // A file name given where TOML text is expected (`Scene("scenes/sinai.toml")`,
        // `simulate("scenes/sinai.toml")`) fails to parse on its first line.
        let path = text.trim();
        if !path.contains('\n') && (path.ends_with(".toml") || Path::new(path).is_file()) {
            message.push_str(&format!(
                " ({path:?} looks like a file name: read a file with \
                 noslip.Scene.from_file({path:?}))"
            ));
        }
        input_error(message)
    })
}

/// How deep the containers (dicts, lists, tuples) of a dict given to `Scene.from_dict` may
/// nest. The scene format nests at most four deep (`table.wedge.directions[0][0]`: a table,
/// a table, an array, an array), so 64 refuses nothing a scene can use, while each level
/// costs a few hundred bytes of the calling thread's stack (which may be a small one, a
/// Dask worker's): a deeper or self-referencing dict is an [`InputError`] naming the path
/// where the limit is passed, not a stack overflow.
///
/// [`InputError`]: crate::error::InputError
pub const MAX_DICT_DEPTH: usize = 64;

/// The reader of a dict given to `Scene.from_dict`: Python values to TOML values.
struct DictReader<'a> {
    /// The dict's name in messages (`<dict>`, or the caller's `origin`).
    origin: &'a str,
    /// The places of the ints beyond `i64`, kept as their decimal text (exact numbers may be
    /// that large), with that text: a field that wants a machine integer then says it is
    /// too large.
    big_ints: Vec<(String, String)>,
}

impl DictReader<'_> {
    /// A Python value as TOML: dicts (string keys), lists and tuples, bools, ints, floats,
    /// strings, and `fractions.Fraction` as the scene format's exact `"p/q"` string.
    /// `place` is its dict path (`species[0].mass`, empty for the dict itself), `depth` the
    /// number of containers around it, at most [`MAX_DICT_DEPTH`].
    fn read(
        &mut self,
        value: &Bound<'_, PyAny>,
        place: &str,
        depth: usize,
    ) -> PyResult<toml::Value> {
        let where_ = if place.is_empty() { "scene" } else { place };
        let origin = self.origin;
        let bad = |what: String| input_error(format!("{origin}: {where_}: {what}"));
        let is_container = value.is_instance_of::<PyDict>()
            || value.is_instance_of::<PyList>()
            || value.is_instance_of::<PyTuple>();
        if is_container && depth >= MAX_DICT_DEPTH {
            return Err(bad(format!(
                "nested more than {MAX_DICT_DEPTH} deep (a scene nests at most 4 deep; \
                 is a dict or list inside itself?)"
            )));
        }
        if let Ok(d) = value.cast::<PyDict>() {
            let mut table = toml::Table::new();
            for (k, v) in d.iter() {
                let key: String = k.extract().map_err(|_| {
                    bad(if k.is_instance_of::<PyString>() {
                        format!("a key {}", not_unicode(&k))
                    } else {
                        format!(
                            "keys must be strings, got {}",
                            k.repr().map_or("?".into(), |r| r.to_string())
                        )
                    })
                })?;
                let v = self.read(&v, &join(place, &key), depth + 1)?;
                table.insert(key, v);
            }
            return Ok(toml::Value::Table(table));
        }
        if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
            let items = value
                .try_iter()?
                .enumerate()
                .map(|(i, v)| self.read(&v?, &format!("{place}[{i}]"), depth + 1))
                .collect::<PyResult<Vec<_>>>()?;
            return Ok(toml::Value::Array(items));
        }
        if value.is_instance_of::<PyBool>() {
            return Ok(toml::Value::Boolean(value.extract()?));
        }
        if value.is_instance_of::<PyInt>() {
            if let Ok(i) = value.extract::<i64>() {
                return Ok(toml::Value::Integer(i));
            }
            let text = value
                .str()
                .map_err(
                    |_| bad("an int of more than 4300 digits, too large for any field".into()),
                )?
                .to_string();
            self.big_ints.push((place.to_string(), text.clone()));
            return Ok(toml::Value::String(text));
        }
        if value.is_instance_of::<PyFloat>() {
            return Ok(toml::Value::Float(value.extract()?));
        }
        if value.is_instance_of::<PyString>() {
            return value
                .extract()
                .map(toml::Value::String)
                .map_err(|_| bad(not_unicode(value)));
        }
        // NumPy arrays and scalars (`np.arange(3)`, `np.int64(10)`, `np.float32(0.5)`): read
        // as their Python values (`tolist()`: nested lists, ints, exact floats, bools), as a
        // sweep's grid hands them over.
        if value.hasattr("dtype")? && value.hasattr("tolist")? {
            let plain = value.call_method0("tolist")?;
            if !plain.is(value) {
                return self.read(&plain, place, depth + 1);
            }
        }
        let type_name = value.get_type().name()?.to_string();
        if type_name == "Decimal" {
            // Its exact decimal text, read as a scene reads a decimal string.
            return Ok(toml::Value::String(value.str()?.to_string()));
        }
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
}

/// A stretch `start..end` of the TOML text made from a dict, and the dict path it came
/// from (`species[0].mass`: a key, a value or a table's header).
struct Span {
    start: usize,
    end: usize,
    path: String,
}

/// TOML text written from a dict, remembering where each key, value and header came from,
/// so that an error at a line and column of that text (which the user never saw) can name
/// the dict path instead.
#[derive(Default)]
struct Emitter {
    text: String,
    spans: Vec<Span>,
}

/// `path.key`, or `key` at the top.
fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

/// A key as TOML writes it: bare when it can be, else quoted.
fn toml_key(key: &str) -> String {
    let bare = !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if bare {
        key.to_string()
    } else {
        toml::Value::String(key.to_string()).to_string()
    }
}

/// Whether `value` is written as a section (`[header]` or `[[header]]`) rather than inline.
fn is_section(value: &toml::Value) -> bool {
    match value {
        toml::Value::Table(_) => true,
        toml::Value::Array(a) => !a.is_empty() && a.iter().all(toml::Value::is_table),
        _ => false,
    }
}

impl Emitter {
    /// Record that `start..` (to the end of the text so far) came from `path`.
    fn span(&mut self, start: usize, path: String) {
        let end = self.text.len();
        self.spans.push(Span { start, end, path });
    }

    /// The table at TOML key path `keys` (dict path `path`): its plain keys, then its
    /// tables and arrays of tables as sections.
    fn table(&mut self, keys: &[String], path: &str, table: &toml::Table) {
        for (k, v) in table.iter().filter(|(_, v)| !is_section(v)) {
            let (start, inner) = (self.text.len(), join(path, k));
            self.text.push_str(&toml_key(k));
            self.span(start, inner.clone());
            self.text.push_str(" = ");
            self.inline(v, &inner);
            self.text.push('\n');
        }
        for (k, v) in table.iter().filter(|(_, v)| is_section(v)) {
            let keys: Vec<String> = keys.iter().cloned().chain([toml_key(k)]).collect();
            let header = keys.join(".");
            match v {
                toml::Value::Table(t) => {
                    let inner = join(path, k);
                    self.header(&format!("[{header}]"), inner.clone());
                    self.table(&keys, &inner, t);
                }
                toml::Value::Array(items) => {
                    for (i, t) in items.iter().filter_map(toml::Value::as_table).enumerate() {
                        let inner = format!("{}[{i}]", join(path, k));
                        self.header(&format!("[[{header}]]"), inner.clone());
                        self.table(&keys, &inner, t);
                    }
                }
                _ => unreachable!("a section is a table or an array of tables"),
            }
        }
    }

    /// A section's header line, from dict path `path`.
    fn header(&mut self, header: &str, path: String) {
        self.text.push('\n');
        let start = self.text.len();
        self.text.push_str(header);
        self.span(start, path);
        self.text.push('\n');
    }

    /// `value` inline (arrays and tables on one line), from dict path `path`.
    fn inline(&mut self, value: &toml::Value, path: &str) {
        let start = self.text.len();
        match value {
            toml::Value::Array(items) => {
                self.text.push('[');
                for (i, v) in items.iter().enumerate() {
                    if i > 0 {
                        self.text.push_str(", ");
                    }
                    self.inline(v, &format!("{path}[{i}]"));
                }
                self.text.push(']');
            }
            toml::Value::Table(t) => {
                self.text.push('{');
                for (i, (k, v)) in t.iter().enumerate() {
                    self.text.push_str(if i > 0 { ", " } else { " " });
                    let (key_start, inner) = (self.text.len(), join(path, k));
                    self.text.push_str(&toml_key(k));
                    self.span(key_start, inner.clone());
                    self.text.push_str(" = ");
                    self.inline(v, &inner);
                }
                self.text.push_str(if t.is_empty() { "}" } else { " }" });
            }
            leaf => self.text.push_str(&leaf.to_string()),
        }
        self.span(start, path.to_string());
    }

    /// The dict path of byte `offset`: that of the shortest span holding it.
    fn path_at(&self, offset: usize) -> Option<&str> {
        self.spans
            .iter()
            .filter(|s| s.start <= offset && offset < s.end)
            .min_by_key(|s| s.end - s.start)
            .map(|s| s.path.as_str())
    }
}

/// The byte offset of 1-based `line` and byte `column` in `text` (as `noslip-scene` counts
/// them in its `line L, column C` places).
fn offset_of(text: &str, place: &str) -> Option<usize> {
    let (line, column) = place.strip_prefix("line ")?.split_once(", column ")?;
    // `line 3, column 5: contact.balls.e`: the scene's key path follows the column.
    let column = column.split_once(':').map_or(column, |(c, _)| c);
    let (line, column): (usize, usize) = (line.parse().ok()?, column.parse().ok()?);
    let line_start = if line == 1 {
        0
    } else {
        text.match_indices('\n').nth(line - 2)?.0 + 1
    };
    Some(line_start + column.checked_sub(1)?)
}

/// Argument `name`, a Python `str`, as Rust text; an `InputError` naming
/// it if it holds a lone surrogate (which UTF-8 cannot encode).
fn unicode(text: &Bound<'_, PyString>, name: &str) -> PyResult<String> {
    text.to_cow().map(|t| t.into_owned()).map_err(|_| {
        input_error(format!(
            "{name}: not valid Unicode text (it holds a lone surrogate)"
        ))
    })
}

/// What is wrong with a Python `str` that Rust cannot take (a lone surrogate, which UTF-8
/// cannot encode), with its `repr` (which escapes it).
fn not_unicode(text: &Bound<'_, PyAny>) -> String {
    let shown = text.repr().map_or("?".into(), |r| r.to_string());
    format!("{shown} is not valid Unicode text (a lone surrogate)")
}

/// A dict's scene error with its place as the dict path the user wrote (`species[0].mass`),
/// not a line and column of the TOML text made from the dict; an int too large for a
/// machine-integer field (made a string by [`DictReader::read`]) says so.
fn dict_error(
    mut e: noslip_scene::SceneError,
    emitted: &Emitter,
    big_ints: &[(String, String)],
) -> noslip_scene::SceneError {
    let offset = offset_of(&emitted.text, &e.place);
    // A missing field is reported at the table that lacks it (`the top level`, or a table's
    // line and column): name the field itself, `species` or `box.boundary`.
    let missing = e
        .message
        .strip_prefix("missing field `")
        .and_then(|rest| rest.strip_suffix('`'))
        .map(str::to_string);
    if let (Some(field), "the top level") = (&missing, e.place.as_str()) {
        e.place = field.clone();
        e.message = "missing (a required field)".to_string();
        return e;
    }
    if let (Some(field), Some(o)) = (&missing, offset) {
        let table = if o == 0 {
            ""
        } else {
            emitted.path_at(o).unwrap_or("")
        };
        e.place = join(table, field);
        e.message = "missing (a required field)".to_string();
        return e;
    }
    if let Some(path) = offset.and_then(|o| emitted.path_at(o)) {
        e.place = path.to_string();
    } else if e.place.starts_with("line ") {
        e.place = "scene".to_string();
    }
    let big = big_ints.iter().find(|(place, _)| *place == e.place);
    if let (Some((_, int)), true) = (big, e.message.starts_with("invalid type: string")) {
        let expected = e
            .message
            .split_once(", expected ")
            .map_or(String::new(), |(_, x)| format!(" (expected {x})"));
        let sign = if int.starts_with('-') {
            "small"
        } else {
            "large"
        };
        e.message = format!("integer {int} is too {sign} for this field{expected}");
    }
    e
}

#[pymethods]
impl Scene {
    /// A scene from TOML text.
    ///
    /// Parameters
    /// ----------
    /// text : str
    ///     The scene as TOML (the format of ``noslip simulate``, ``docs/scenes.md``).
    /// origin : str
    ///     The scene's name in messages (default ``"<string>"``).
    ///
    /// Raises
    /// ------
    /// InputError
    ///     A bad scene, naming the place (``<string>: line 3, column 1: ...``). Text that
    ///     looks like a file name (one line, ending in ``.toml`` or naming a file) gets a hint
    ///     to use ``Scene.from_file``.
    #[new]
    #[pyo3(signature = (text, origin = None), text_signature = "(text, origin='<string>')")]
    fn new(text: &Bound<'_, PyString>, origin: Option<&Bound<'_, PyString>>) -> PyResult<Self> {
        let text = unicode(text, "text")?;
        let origin = origin.map_or(Ok("<string>".to_string()), |o| unicode(o, "origin"))?;
        let inner = parse(&text, &origin)?;
        Ok(Scene {
            text,
            origin,
            inner,
        })
    }

    /// A scene from a TOML file.
    ///
    /// Parameters
    /// ----------
    /// path : str or os.PathLike
    ///     The file (at most 16 MiB, as for ``noslip simulate``).
    ///
    /// Returns
    /// -------
    /// Scene
    ///     The scene, its ``origin`` the path.
    ///
    /// Raises
    /// ------
    /// InputError
    ///     A file that cannot be read, or a bad scene naming the place.
    #[staticmethod]
    #[pyo3(text_signature = "(path)")]
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

    /// A scene from a dict with the TOML file's structure.
    ///
    /// Parameters
    /// ----------
    /// scene : dict
    ///     ``{"dim": 2, "box": {...}, "species": [...], ...}``: dicts, lists, tuples, bools,
    ///     ints, floats and strings; exact numbers as strings (``"1/20"``) or ``Fraction``.
    /// origin : str
    ///     The scene's name in messages (default ``"<dict>"``).
    ///
    /// Returns
    /// -------
    /// Scene
    ///     The scene; its ``toml`` is the text written from the dict.
    ///
    /// Raises
    /// ------
    /// InputError
    ///     A bad scene, naming the dict path (``<dict>: species[0].mass: ...``, a missing
    ///     field by its own path: ``<dict>: species: missing (a required field)``);
    ///     containers nested more than 64 deep (or inside themselves) are refused.
    #[staticmethod]
    #[pyo3(signature = (scene, origin = None), text_signature = "(scene, origin='<dict>')")]
    fn from_dict(
        scene: &Bound<'_, PyDict>,
        origin: Option<&Bound<'_, PyString>>,
    ) -> PyResult<Self> {
        let origin = origin.map_or(Ok("<dict>".to_string()), |o| unicode(o, "origin"))?;
        let mut reader = DictReader {
            origin: &origin,
            big_ints: Vec::new(),
        };
        let value = reader.read(scene.as_any(), "", 0)?;
        let mut emitted = Emitter::default();
        if let toml::Value::Table(t) = &value {
            emitted.table(&[], "", t);
        }
        let inner = noslip_scene::Scene::from_toml(&emitted.text, &origin)
            .map_err(|e| input_error(dict_error(e, &emitted, &reader.big_ints).to_string()))?;
        Ok(Scene {
            text: emitted.text,
            origin,
            inner,
        })
    }

    /// str: the TOML text of the scene.
    #[getter]
    fn toml(&self) -> &str {
        &self.text
    }

    /// str: where the scene came from (a file name, ``<string>``, ``<dict>``).
    #[getter]
    fn origin(&self) -> &str {
        &self.origin
    }

    /// int: the dimension ``n``.
    #[getter]
    fn dim(&self) -> usize {
        self.inner.dim
    }

    /// str: the scene's ``description``.
    #[getter]
    fn description(&self) -> &str {
        &self.inner.description
    }

    /// int: the number of balls.
    #[getter]
    fn balls(&self) -> usize {
        self.inner.ball_count()
    }

    /// dict: the ball-ball contact law of every pair of species, keyed by the two species'
    /// names ``(a, b)`` in the order of ``species`` (a species with itself: ``(a, a)``): the
    /// pair's ``contact.pair`` law, else ``contact.balls``. Each law is ``"no-slip"``,
    /// ``"smooth"``, ``{"e": Fraction, "beta": Fraction}`` (rough) or ``{"e", "mu",
    /// "beta0"}`` (Walton), exact, as ``Scene.from_dict`` takes it.
    #[getter]
    fn ball_laws<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        crate::scene_laws::ball_laws(py, &self.inner)
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String, String))> {
        let me = slf.get();
        Ok((
            slf.get_type().into_any(),
            (me.text.clone(), me.origin.clone()),
        ))
    }

    /// Two scenes are equal when their TOML text and origin are: a pickle round trip (which
    /// rebuilds the scene from both) gives an equal scene.
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<Scene>()
            .is_ok_and(|o| o.get().text == self.text && o.get().origin == self.origin)
    }

    /// The hash of the TOML text and origin (equal scenes hash alike).
    fn __hash__(&self) -> u64 {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        (&self.text, &self.origin).hash(&mut h);
        h.finish()
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene(origin={:?}, dim={}, balls={}, description={:?})",
            self.origin,
            self.inner.dim,
            self.inner.ball_count(),
            self.inner.description
        )
    }
}
