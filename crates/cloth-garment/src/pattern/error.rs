//! What can be wrong with a pattern, named so a person can find it in the file.

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum PatternError {
    #[error("cannot read pattern '{path}': {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A syntax or schema error; `message` carries the line and column.
    #[error("{file}: {message}")]
    Parse { file: String, message: String },
    /// Something wrong in one panel; `edge` names the edge when one is at fault.
    #[error("{file}: panel '{panel}'{}: {reason}", edge.as_ref().map(|e| format!(", edge {e}")).unwrap_or_default())]
    Panel {
        file: String,
        panel: String,
        edge: Option<String>,
        reason: String,
    },
    /// Something wrong in one seam (numbered from 0 in file order).
    #[error("{file}: seam {seam}: {reason}")]
    Seam {
        file: String,
        seam: usize,
        reason: String,
    },
    #[error("{file}: {reason}")]
    Pattern { file: String, reason: String },
}

impl PatternError {
    pub(crate) fn panel(file: &str, panel: &str, edge: Option<String>, reason: impl Into<String>) -> Self {
        Self::Panel {
            file: file.to_string(),
            panel: panel.to_string(),
            edge,
            reason: reason.into(),
        }
    }
    pub(crate) fn seam(file: &str, seam: usize, reason: impl Into<String>) -> Self {
        Self::Seam {
            file: file.to_string(),
            seam,
            reason: reason.into(),
        }
    }
}
