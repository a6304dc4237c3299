//! Scenes built from Python: a dict shaped like the TOML file (tables as dicts, arrays of
//! tables as lists of dicts, vectors and colours as lists or tuples) is written as that TOML and
//! read by the same reader, so it means what the file would and renders the same bits.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use toml::{Table, Value};

/// Deepest nesting of dicts and lists taken: scene files nest a few levels; a dict that
/// contains itself would otherwise recurse until the stack overflows.
const MAX_NESTING: usize = 32;

/// The TOML value of a Python object at `path` (`material[1].ior`, for errors), `depth`
/// containers down.
fn value(obj: &Bound<'_, PyAny>, path: &str, depth: usize) -> PyResult<Value> {
    if depth > MAX_NESTING {
        return Err(PyValueError::new_err(format!(
            "{path}: nested more than {MAX_NESTING} deep (does a dict or list contain itself?)"
        )));
    }
    // bool before int: True is an int in Python.
    if obj.is_instance_of::<PyBool>() {
        return Ok(Value::Boolean(obj.extract()?));
    }
    if obj.is_instance_of::<PyInt>() {
        return obj
            .extract::<i64>()
            .map(Value::Integer)
            .map_err(|_| PyValueError::new_err(format!("{path}: {obj} does not fit in 64 bits")));
    }
    if obj.is_instance_of::<PyFloat>() {
        return Ok(Value::Float(obj.extract()?));
    }
    if obj.is_instance_of::<PyString>() {
        return Ok(Value::String(obj.extract()?));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        return table(d, path, depth + 1).map(Value::Table);
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let items = obj
            .try_iter()?
            .enumerate()
            .map(|(i, item)| value(&item?, &format!("{path}[{i}]"), depth + 1))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(Value::Array(items));
    }
    // numpy scalars and arrays, and anything else that converts: as a float, an int or a list.
    if let Ok(list) = obj.call_method0("tolist")
        && !list.is(obj)
    {
        return value(&list, path, depth + 1);
    }
    let kind = obj.get_type().name()?;
    Err(PyValueError::new_err(format!(
        "{path}: a {kind} has no place in a scene (use numbers, strings, booleans, lists and dicts)"
    )))
}

fn table(d: &Bound<'_, PyDict>, path: &str, depth: usize) -> PyResult<Table> {
    let mut t = Table::new();
    for (k, v) in d.iter() {
        let Ok(key) = k.extract::<String>() else {
            return Err(PyValueError::new_err(format!(
                "{path}: keys are strings, not {k}"
            )));
        };
        let at = if path.is_empty() {
            key.clone()
        } else {
            format!("{path}.{key}")
        };
        if v.is_none() {
            // TOML has no null: a key given None is left out, as if not given.
            continue;
        }
        t.insert(key, value(&v, &at, depth)?);
    }
    Ok(t)
}

/// The TOML text of a scene given as a dict.
pub fn toml_text(scene: &Bound<'_, PyDict>) -> PyResult<String> {
    let t = table(scene, "", 0)?;
    toml::to_string(&t).map_err(|e| PyValueError::new_err(format!("the scene as TOML: {e}")))
}
