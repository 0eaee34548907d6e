//! Why a fabric preset could not be read or found.

use cloth_core::ParamError;
use thiserror::Error;

#[derive(Debug, Error)]
pub enum PresetError {
    #[error("cannot read fabric presets from {file}: {source}")]
    Io {
        file: String,
        #[source]
        source: std::io::Error,
    },
    /// Malformed TOML, a missing or unknown field: `message` carries the line and column.
    #[error("{file}: {message}")]
    Parse { file: String, message: String },
    #[error("{file}: fabric `{fabric}` must give exactly one of [{fabric}.si], [{fabric}.kes] or [{fabric}.source]; it gives {found}")]
    Form {
        file: String,
        fabric: String,
        found: String,
    },
    #[error("{file}: fabric `{fabric}`: {source}")]
    Invalid {
        file: String,
        fabric: String,
        #[source]
        source: ParamError,
    },
    #[error("unknown fabric preset `{name}`; the known presets are: {}", known.join(", "))]
    Unknown { name: String, known: Vec<String> },
}
