//! `cloth.Fabric`: a fabric's SI parameters, from a preset, SI values or a KES-F record.

use crate::convert::{from_dict, to_python};
use crate::errors::input;
use cloth::presets::FabricLibrary;
use cloth::KesMeasurement;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A fabric's mechanical properties in SI units (the model's parameters). Made from a
/// preset, from SI values (the keys of a scene's `[fabric.si]`), or from a Kawabata (KES-F)
/// record (the keys of `[fabric.kes]`, in KES units).
#[pyclass(frozen, eq, module = "cloth")]
#[derive(Clone, PartialEq)]
pub struct Fabric {
    pub inner: cloth::Fabric,
}

impl Fabric {
    fn checked(fabric: cloth::Fabric) -> PyResult<Self> {
        fabric.validate().map_err(input)?;
        Ok(Self { inner: fabric })
    }
}

#[pymethods]
impl Fabric {
    /// The built-in preset `name` (see `presets()`); a ValueError names the known ones when
    /// it is not one of them.
    #[staticmethod]
    fn preset(name: &str) -> PyResult<Self> {
        let fabric = FabricLibrary::builtin().fabric(name).map_err(input)?;
        Ok(Self { inner: fabric })
    }

    /// The built-in presets: name to a one-line description.
    #[staticmethod]
    fn presets(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let dict = PyDict::new(py);
        for p in FabricLibrary::builtin().presets() {
            dict.set_item(&p.name, &p.description)?;
        }
        Ok(dict)
    }

    /// From SI values, as a scene's `[fabric.si]` table: `area_density` (kg/m^2), `warp`
    /// and `weft` tensile laws, `compression_warp`/`compression_weft`, `shear_modulus`
    /// (N/m), `bending` (N m), and optionally `thickness`, `bending_law`, `damping`,
    /// `drag`, `friction`. Unknown keys are refused.
    #[staticmethod]
    fn from_si(values: &Bound<'_, PyAny>) -> PyResult<Self> {
        Self::checked(from_dict(values, "fabric.si")?)
    }

    /// From a KES-F record, as a scene's `[fabric.kes]` table (`W`, `T`, `MIU`, and `warp`
    /// and `weft` tables of `EMT`, `LT`, `WT`, `G`, `B`, ...).
    #[staticmethod]
    fn from_kes(record: &Bound<'_, PyAny>) -> PyResult<Self> {
        let kes: KesMeasurement = from_dict(record, "fabric.kes")?;
        let fabric = kes.to_fabric().map_err(input)?.fabric;
        Self::checked(fabric)
    }

    /// The SI values; `Fabric.from_si(f.to_si()) == f`.
    fn to_si<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner)
    }

    /// The KES-F record this fabric would measure (the inverse of `from_kes`).
    fn to_kes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &KesMeasurement::from_fabric(&self.inner))
    }

    /// A copy with some SI values replaced (`f.with_values(damping=0.01)`).
    #[pyo3(signature = (**changes))]
    fn with_values(&self, py: Python<'_>, changes: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let values = to_python(py, &self.inner)?.cast_into::<PyDict>()?;
        if let Some(changes) = changes {
            values.update(changes.as_mapping())?;
        }
        Self::from_si(&values)
    }

    /// Mass per area, kg/m^2.
    #[getter]
    fn area_density(&self) -> f64 {
        self.inner.area_density
    }
    /// Thickness, m.
    #[getter]
    fn thickness(&self) -> f64 {
        self.inner.thickness
    }
    /// Coulomb coefficient against bodies.
    #[getter]
    fn friction(&self) -> f64 {
        self.inner.friction
    }
    /// Secant tensile stiffness at 1 % strain, the larger of warp and weft, N/m.
    #[getter]
    fn membrane_stiffness(&self) -> f64 {
        self.inner.membrane_stiffness()
    }

    fn __repr__(&self) -> String {
        format!(
            "Fabric(area_density={:.4} kg/m^2, membrane_stiffness={:.1} N/m)",
            self.inner.area_density,
            self.inner.membrane_stiffness()
        )
    }
}
