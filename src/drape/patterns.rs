//! The patterns a batch drapes: files named on the command line, and every pattern file
//! in the folders named (searched to any depth, in name order).

use super::DrapeError;
use std::path::{Path, PathBuf};

/// A pattern to drape: the name its outputs go under, and its file.
#[derive(Debug, Clone, PartialEq)]
pub struct PatternInput {
    pub name: String,
    pub path: PathBuf,
}

/// Files a run writes, never patterns (a batch's output folder may be among the inputs).
const OUTPUTS: [&str; 4] = ["report.json", "summary.json", super::FINISHED_FILE, "scene.toml"];

fn is_pattern_file(path: &Path) -> bool {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
    matches!(extension.as_deref(), Some("json" | "toml"))
        && !name.starts_with('.')
        && !OUTPUTS.contains(&name)
}

/// The name of a pattern's outputs: GarmentCode's naming for its JSON (the stem without
/// `_specification`, or the folder for `specification.json`), the file stem otherwise.
fn name_of(path: &Path) -> String {
    let is_json = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("json"));
    if is_json {
        cloth_garment::garmentcode::pattern_name(&path.display().to_string())
    } else {
        path.file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("pattern")
            .to_string()
    }
}

/// Every pattern named by `inputs` (files, or folders to search), absolute, with its
/// name. Two patterns with the same name would write into one folder: refused, naming
/// both.
pub fn find_patterns(inputs: &[PathBuf]) -> Result<Vec<PatternInput>, DrapeError> {
    let mut files = Vec::new();
    for input in inputs {
        let meta = std::fs::metadata(input).map_err(|source| DrapeError::Io {
            path: input.clone(),
            source,
        })?;
        if meta.is_dir() {
            let before = files.len();
            search(input, &mut files)?;
            if files.len() == before {
                return Err(DrapeError::Input(format!(
                    "folder '{}' holds no pattern (.toml or .json)",
                    input.display()
                )));
            }
        } else {
            files.push(input.clone());
        }
    }
    let mut patterns: Vec<PatternInput> = Vec::with_capacity(files.len());
    for path in files {
        let path = std::path::absolute(&path).map_err(|source| DrapeError::Io {
            path: path.clone(),
            source,
        })?;
        let name = name_of(&path);
        if let Some(other) = patterns.iter().find(|p| p.name == name) {
            if other.path == path {
                continue;
            }
            return Err(DrapeError::Input(format!(
                "'{}' and '{}' are both called '{name}': their outputs would share a folder; drape them in \
                 separate batches",
                other.path.display(),
                path.display()
            )));
        }
        patterns.push(PatternInput { name, path });
    }
    if patterns.is_empty() {
        return Err(DrapeError::Input("no patterns given".into()));
    }
    Ok(patterns)
}

/// The pattern files under `folder`, in name order, folders after files at each level.
fn search(folder: &Path, out: &mut Vec<PathBuf>) -> Result<(), DrapeError> {
    let io = |source| DrapeError::Io {
        path: folder.to_path_buf(),
        source,
    };
    let mut entries: Vec<PathBuf> = std::fs::read_dir(folder)
        .map_err(io)?
        .map(|e| e.map(|e| e.path()))
        .collect::<Result<_, _>>()
        .map_err(io)?;
    entries.sort();
    let (folders, files): (Vec<PathBuf>, Vec<PathBuf>) = entries.into_iter().partition(|p| p.is_dir());
    out.extend(files.into_iter().filter(|p| is_pattern_file(p)));
    for f in folders {
        search(&f, out)?;
    }
    Ok(())
}
