//! Python values to and from the engine's serde records. Dicts go through `toml::Value`,
//! the scene file's own data model: what `tomllib` reads from a scene is exactly what the
//! records accept, and infinite limits survive (JSON has no infinity).

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use serde::de::DeserializeOwned;
use serde::Serialize;

/// A Python dict (or list, number, string, bool) as a TOML value; `what` names it in errors.
pub fn to_toml(value: &Bound<'_, PyAny>, what: &str) -> PyResult<toml::Value> {
    nested(value, what, 0)
}

/// Deeper than any scene: a list that contains itself ends here, not in a stack overflow.
const MAX_DEPTH: usize = 32;

fn nested(value: &Bound<'_, PyAny>, what: &str, depth: usize) -> PyResult<toml::Value> {
    if depth > MAX_DEPTH {
        return Err(PyValueError::new_err(format!("{what}: nested too deeply")));
    }
    if value.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(value.extract()?));
    }
    if value.is_instance_of::<PyInt>() {
        let i: i64 = value
            .extract()
            .map_err(|_| PyValueError::new_err(format!("{what}: integer {value} is out of range")))?;
        return Ok(toml::Value::Integer(i));
    }
    if value.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(value.extract()?));
    }
    if value.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(value.extract()?));
    }
    if let Ok(dict) = value.cast::<PyDict>() {
        let mut table = toml::Table::new();
        for (k, v) in dict.iter() {
            let key: String = k
                .extract()
                .map_err(|_| PyTypeError::new_err(format!("{what}: keys must be strings, got {k:?}")))?;
            // None leaves a key out, as a missing key in a file.
            if v.is_none() {
                continue;
            }
            let inner = format!("{what}.{key}");
            table.insert(key, nested(&v, &inner, depth + 1)?);
        }
        return Ok(toml::Value::Table(table));
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() || value.hasattr("tolist")? {
        // numpy arrays and scalars say what they hold through tolist().
        let plain = if value.hasattr("tolist")? {
            value.call_method0("tolist")?
        } else {
            value.clone()
        };
        if plain.is_instance_of::<PyList>() || plain.is_instance_of::<PyTuple>() {
            let items = plain
                .try_iter()?
                .enumerate()
                .map(|(k, item)| nested(&item?, &format!("{what}[{k}]"), depth + 1))
                .collect::<PyResult<Vec<_>>>()?;
            return Ok(toml::Value::Array(items));
        }
        return nested(&plain, what, depth + 1);
    }
    if value.hasattr("__fspath__")? {
        let path = value.call_method0("__fspath__")?;
        return nested(&path, what, depth + 1);
    }
    Err(PyTypeError::new_err(format!(
        "{what}: cannot use a {} here (give dicts, lists, numbers, strings or booleans)",
        value.get_type().name()?
    )))
}

/// A record from a Python dict; serde's message (an unknown key, a missing one, a wrong
/// type) is prefixed with `what`.
pub fn from_dict<T: DeserializeOwned>(value: &Bound<'_, PyAny>, what: &str) -> PyResult<T> {
    from_toml_value(to_toml(value, what)?, what)
}

/// A record from a TOML value; serde's message is prefixed with `what`.
pub fn from_toml_value<T: DeserializeOwned>(value: toml::Value, what: &str) -> PyResult<T> {
    T::deserialize(value).map_err(|e| PyValueError::new_err(format!("{what}: {}", e.to_string().trim())))
}

/// A record as Python dicts, lists and numbers.
pub fn to_python<'py, T: Serialize>(py: Python<'py>, record: &T) -> PyResult<Bound<'py, PyAny>> {
    let v = toml::Value::try_from(record)
        .map_err(|e| PyValueError::new_err(format!("cannot convert to Python: {e}")))?;
    toml_to_python(py, &v)
}

fn toml_to_python<'py>(py: Python<'py>, v: &toml::Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        toml::Value::String(s) => s.into_pyobject(py)?.into_any(),
        toml::Value::Integer(i) => i.into_pyobject(py)?.into_any(),
        toml::Value::Float(f) => f.into_pyobject(py)?.into_any(),
        toml::Value::Boolean(b) => b.into_pyobject(py)?.to_owned().into_any(),
        toml::Value::Datetime(d) => d.to_string().into_pyobject(py)?.into_any(),
        toml::Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(toml_to_python(py, item)?)?;
            }
            list.into_any()
        }
        toml::Value::Table(table) => {
            let dict = PyDict::new(py);
            for (k, item) in table {
                dict.set_item(k, toml_to_python(py, item)?)?;
            }
            dict.into_any()
        }
    })
}

/// A record that serialises to JSON (the run report) as Python objects, as `json.loads`
/// would read the file.
pub fn json_to_python<'py, T: Serialize>(py: Python<'py>, record: &T) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(record)
        .map_err(|e| PyValueError::new_err(format!("cannot convert to Python: {e}")))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// `"y"` or `"z"` as the scene file reads `up_axis`.
pub fn up_axis(value: &str) -> PyResult<cloth::scene_file::UpAxis> {
    from_toml_value(toml::Value::String(value.to_string()), "up_axis")
}
