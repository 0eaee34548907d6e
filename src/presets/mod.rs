//! Named fabrics from a TOML file: the built-in `assets/fabrics.toml`, or a user's own.
//!
//! Each table of the file is one fabric, keyed by its name, with a `description`, an
//! `origin` (where its numbers come from) and the fabric in exactly one form:
//! `[name.si]` (the [`Fabric`] fields in SI), `[name.kes]` (a [`KesMeasurement`] in KES-F
//! units) or `[name.source]` (the source paper's `mu_b`, `mu_s`, with an area density
//! and a tensile law).

mod error;
mod record;

pub use error::PresetError;

use cloth_core::{Fabric, UnusedKes};
use record::PresetRecord;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::OnceLock;

/// How a preset's numbers were given.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PresetForm {
    Si,
    Kes,
    Source,
}

/// One named fabric.
#[derive(Debug, Clone, PartialEq)]
pub struct Preset {
    pub name: String,
    pub description: String,
    /// Where the numbers come from.
    pub origin: String,
    pub form: PresetForm,
    pub fabric: Fabric,
    /// KES values the SI fabric does not use, and why (empty for other forms).
    pub unused: Vec<UnusedKes>,
}

/// A set of named fabrics, in name order.
#[derive(Debug, Clone, PartialEq)]
pub struct FabricLibrary {
    presets: Vec<Preset>,
}

const BUILTIN_FILE: &str = "assets/fabrics.toml";
const BUILTIN: &str = include_str!("../../assets/fabrics.toml");

impl FabricLibrary {
    /// The presets shipped in `assets/fabrics.toml`.
    pub fn builtin() -> &'static FabricLibrary {
        static LIBRARY: OnceLock<FabricLibrary> = OnceLock::new();
        LIBRARY.get_or_init(|| {
            // The file is part of the build and checked by the tests; a failure here is a
            // broken release, not bad user input.
            Self::from_toml(BUILTIN, BUILTIN_FILE).unwrap_or_else(|e| panic!("built-in presets: {e}"))
        })
    }

    /// Reads presets from a TOML file.
    pub fn from_path(path: impl AsRef<Path>) -> Result<Self, PresetError> {
        let path = path.as_ref();
        let file = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|source| PresetError::Io {
            file: file.clone(),
            source,
        })?;
        Self::from_toml(&text, &file)
    }

    /// Reads presets from TOML text; `file` names it in errors.
    pub fn from_toml(text: &str, file: &str) -> Result<Self, PresetError> {
        let records: BTreeMap<String, PresetRecord> =
            toml::from_str(text).map_err(|e| PresetError::Parse {
                file: file.to_string(),
                message: e.to_string(),
            })?;
        let presets = records
            .into_iter()
            .map(|(name, record)| convert(name, record, file))
            .collect::<Result<_, _>>()?;
        Ok(Self { presets })
    }

    /// The preset called `name`; the error lists the known names.
    pub fn get(&self, name: &str) -> Result<&Preset, PresetError> {
        self.presets
            .iter()
            .find(|p| p.name == name)
            .ok_or_else(|| PresetError::Unknown {
                name: name.to_string(),
                known: self.names().map(str::to_string).collect(),
            })
    }

    /// The fabric of the preset called `name`.
    pub fn fabric(&self, name: &str) -> Result<Fabric, PresetError> {
        self.get(name).map(|p| p.fabric.clone())
    }

    /// Each panel's fabric: the preset it names, or `default` where it names none.
    pub fn panel_fabrics(
        &self,
        garment: &cloth_garment::Garment,
        default: &Fabric,
    ) -> Result<Vec<Fabric>, PresetError> {
        garment
            .panel_fabrics
            .iter()
            .map(|name| match name {
                Some(name) => self.fabric(name),
                None => Ok(default.clone()),
            })
            .collect()
    }

    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.presets.iter().map(|p| p.name.as_str())
    }

    pub fn presets(&self) -> &[Preset] {
        &self.presets
    }
}

fn convert(name: String, record: PresetRecord, file: &str) -> Result<Preset, PresetError> {
    let invalid = |source| PresetError::Invalid {
        file: file.to_string(),
        fabric: name.clone(),
        source,
    };
    let (form, fabric, unused) = match (&record.si, &record.kes, &record.source) {
        (Some(si), None, None) => {
            si.validate().map_err(invalid)?;
            (PresetForm::Si, si.clone(), Vec::new())
        }
        (None, Some(kes), None) => {
            let c = kes.to_fabric().map_err(invalid)?;
            (PresetForm::Kes, c.fabric, c.unused)
        }
        (None, None, Some(source)) => {
            let fabric = source.to_fabric();
            fabric.validate().map_err(invalid)?;
            (PresetForm::Source, fabric, Vec::new())
        }
        _ => {
            let given: Vec<&str> = [
                (record.si.is_some(), "si"),
                (record.kes.is_some(), "kes"),
                (record.source.is_some(), "source"),
            ]
            .iter()
            .filter_map(|&(present, form)| present.then_some(form))
            .collect();
            return Err(PresetError::Form {
                file: file.to_string(),
                found: if given.is_empty() {
                    "none".into()
                } else {
                    given.join(" and ")
                },
                fabric: name,
            });
        }
    };
    Ok(Preset {
        name,
        description: record.description,
        origin: record.origin,
        form,
        fabric,
        unused,
    })
}
