//! numpy arrays in and out. Inputs are converted as numpy would (lists, float32, integers)
//! but must hold real numbers of the right shape; errors name the argument. Outputs are
//! fresh arrays the caller owns.

use cloth::math::Vec3;
use nalgebra::Vector2;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;

/// `value` as a C-contiguous float64 array, refusing what is not a real number.
fn float_array<'py>(value: &Bound<'py, PyAny>, name: &str) -> PyResult<Bound<'py, PyAny>> {
    let np = value.py().import("numpy")?;
    let array = np
        .call_method1("asarray", (value,))
        .map_err(|e| PyTypeError::new_err(format!("{name}: not an array of numbers: {e}")))?;
    let kind: String = array.getattr("dtype")?.getattr("kind")?.extract()?;
    if !matches!(kind.as_str(), "f" | "i" | "u") {
        let dtype = array.getattr("dtype")?.str()?.to_string();
        return Err(PyTypeError::new_err(format!(
            "{name}: expected real numbers (a float64 array), got dtype {dtype}"
        )));
    }
    np.call_method1("ascontiguousarray", (array, "float64"))
}

fn shape_of(array: &Bound<'_, PyAny>) -> PyResult<Vec<usize>> {
    array.getattr("shape")?.extract()
}

fn describe(shape: &[usize]) -> String {
    let parts: Vec<String> = shape.iter().map(ToString::to_string).collect();
    if parts.len() == 1 {
        format!("({},)", parts[0])
    } else {
        format!("({})", parts.join(", "))
    }
}

/// An `(N, C)` float64 array's rows; `rows` is the N required, if one is.
fn float_rows<const C: usize>(
    value: &Bound<'_, PyAny>,
    name: &str,
    rows: Option<usize>,
) -> PyResult<Vec<[f64; C]>> {
    let array = float_array(value, name)?;
    let shape = shape_of(&array)?;
    let expected = match rows {
        Some(n) => format!("({n}, {C})"),
        None => format!("(N, {C})"),
    };
    if shape.len() != 2 || shape[1] != C || rows.is_some_and(|n| n != shape[0]) {
        return Err(PyValueError::new_err(format!(
            "{name}: expected shape {expected}, got {}",
            describe(&shape)
        )));
    }
    let array = array.cast::<PyArray2<f64>>()?;
    let view = array.readonly();
    let flat = view.as_slice()?;
    let out: Vec<[f64; C]> = flat
        .chunks_exact(C)
        .map(|c| std::array::from_fn(|k| c[k]))
        .collect();
    if let Some((row, _)) = out
        .iter()
        .enumerate()
        .find(|(_, r)| r.iter().any(|c| !c.is_finite()))
    {
        return Err(PyValueError::new_err(format!("{name}: row {row} is not finite")));
    }
    Ok(out)
}

/// `(N, 3)` points.
pub fn points(value: &Bound<'_, PyAny>, name: &str, rows: Option<usize>) -> PyResult<Vec<Vec3>> {
    Ok(float_rows::<3>(value, name, rows)?
        .into_iter()
        .map(Vec3::from)
        .collect())
}

/// `(N, 2)` material coordinates.
pub fn plane_points(
    value: &Bound<'_, PyAny>,
    name: &str,
    rows: Option<usize>,
) -> PyResult<Vec<Vector2<f64>>> {
    Ok(float_rows::<2>(value, name, rows)?
        .into_iter()
        .map(Vector2::from)
        .collect())
}

/// `N` finite numbers (a tuple, list or array).
pub fn numbers<const N: usize>(value: &Bound<'_, PyAny>, name: &str) -> PyResult<[f64; N]> {
    let array = float_array(value, name)?;
    let shape = shape_of(&array)?;
    if shape != [N] {
        return Err(PyValueError::new_err(format!(
            "{name}: expected {N} numbers, got shape {}",
            describe(&shape)
        )));
    }
    let v: Vec<f64> = array.call_method0("tolist")?.extract()?;
    if !v.iter().all(|c| c.is_finite()) {
        return Err(PyValueError::new_err(format!("{name}: not finite")));
    }
    Ok(std::array::from_fn(|k| v[k]))
}

/// A point given as three numbers.
pub fn point(value: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec3> {
    numbers::<3>(value, name).map(Vec3::from)
}

/// Non-negative integers of shape `(N, C)`, each below `bound`.
pub fn indices<const C: usize>(
    value: &Bound<'_, PyAny>,
    name: &str,
    bound: usize,
) -> PyResult<Vec<[usize; C]>> {
    let np = value.py().import("numpy")?;
    let array = np
        .call_method1("asarray", (value,))
        .map_err(|e| PyTypeError::new_err(format!("{name}: not an array of integers: {e}")))?;
    let kind: String = array.getattr("dtype")?.getattr("kind")?.extract()?;
    let shape = shape_of(&array)?;
    let empty = shape.iter().product::<usize>() == 0;
    if !matches!(kind.as_str(), "i" | "u") && !empty {
        let dtype = array.getattr("dtype")?.str()?.to_string();
        return Err(PyTypeError::new_err(format!(
            "{name}: expected integers, got dtype {dtype}"
        )));
    }
    if !((shape.len() == 2 && shape[1] == C) || (empty && shape.len() == 1)) {
        return Err(PyValueError::new_err(format!(
            "{name}: expected shape (N, {C}), got {}",
            describe(&shape)
        )));
    }
    let flat: Vec<i64> = np
        .call_method1("ascontiguousarray", (array, "int64"))?
        .call_method0("ravel")?
        .call_method0("tolist")?
        .extract()?;
    flat.chunks_exact(C)
        .enumerate()
        .map(|(row, c)| {
            let mut out = [0usize; C];
            for (k, &i) in c.iter().enumerate() {
                if i < 0 || i as u64 >= bound as u64 {
                    return Err(PyValueError::new_err(format!(
                        "{name}[{row}] = {c:?}: index {i} is outside 0..{bound}"
                    )));
                }
                out[k] = i as usize;
            }
            Ok(out)
        })
        .collect()
}

/// 1-D non-negative integers below `bound`.
pub fn index_list(value: &Bound<'_, PyAny>, name: &str, bound: usize) -> PyResult<Vec<usize>> {
    let np = value.py().import("numpy")?;
    let flat = np.call_method1("atleast_1d", (value,))?;
    let array = np.call_method1("asarray", (flat,))?;
    let shape = shape_of(&array)?;
    if shape.len() != 1 {
        return Err(PyValueError::new_err(format!(
            "{name}: expected a list of particle numbers, got shape {}",
            describe(&shape)
        )));
    }
    let rows = indices::<1>(&array.call_method1("reshape", ((-1i64, 1i64),))?, name, bound)?;
    Ok(rows.into_iter().map(|[i]| i).collect())
}

pub fn vec3_array<'py>(py: Python<'py>, v: &[Vec3]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = v.iter().flat_map(|p| [p.x, p.y, p.z]).collect();
    rows_array(py, flat, 3)
}

pub fn vec2_array<'py>(py: Python<'py>, v: &[Vector2<f64>]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = v.iter().flat_map(|p| [p.x, p.y]).collect();
    rows_array(py, flat, 2)
}

pub fn index_array<'py, const C: usize>(py: Python<'py>, v: &[[usize; C]]) -> Bound<'py, PyArray2<i64>> {
    let flat: Vec<i64> = v.iter().flatten().map(|&i| i as i64).collect();
    let n = v.len();
    PyArray1::from_vec(py, flat)
        .reshape([n, C])
        .expect("a flat array of n * C reshapes to (n, C)")
}

pub fn index_vector<'py>(py: Python<'py>, v: impl IntoIterator<Item = usize>) -> Bound<'py, PyArray1<i64>> {
    PyArray1::from_vec(py, v.into_iter().map(|i| i as i64).collect())
}

fn rows_array<'py>(py: Python<'py>, flat: Vec<f64>, width: usize) -> Bound<'py, PyArray2<f64>> {
    let n = flat.len() / width;
    PyArray1::from_vec(py, flat)
        .reshape([n, width])
        .expect("a flat array of n * width reshapes to (n, width)")
}
