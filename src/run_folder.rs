//! A run into an output folder, as `cloth run` and Python's `Scene.run` make it: the
//! folder is claimed (an existing non-empty one only when forced), the scene runs with
//! its frames inside it, and every output the scene asks for is written there, the last
//! good state included when the run fails or is stopped.

use crate::scene_file::{Prepared, RunObserver, RunResult, SceneFile, SceneFileError};
use std::path::{Path, PathBuf};

#[derive(Debug, thiserror::Error)]
pub enum RunFolderError {
    /// The folder holds something and writing into it was not forced; the caller says how
    /// to force it.
    #[error("output folder '{0}' exists and is not empty")]
    NotEmpty(PathBuf),
    #[error("cannot create output folder '{path}': {source}")]
    Create {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// The scene could not be run (nothing ran).
    #[error(transparent)]
    Scene(#[from] SceneFileError),
    /// The run ended but its outputs could not all be written.
    #[error("writing outputs to '{path}': {source}")]
    Write {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
}

/// A run whose outputs are written: its result and the files.
pub struct FolderRun {
    pub result: RunResult,
    pub written: Vec<PathBuf>,
}

/// Refuses an existing folder that holds anything unless `force`; checked before the
/// scene is prepared, so a long preparation is not wasted.
pub fn claim_output_folder(out: &Path, force: bool) -> Result<(), RunFolderError> {
    let occupied = out.exists()
        && std::fs::read_dir(out)
            .map(|mut d| d.next().is_some())
            .unwrap_or(true);
    if occupied && !force {
        return Err(RunFolderError::NotEmpty(out.to_path_buf()));
    }
    Ok(())
}

impl Prepared {
    /// Runs into `out` (created if missing), frames in `out/frames`, and writes the
    /// outputs of the state the run ended in.
    pub fn run_into(
        self,
        scene: &SceneFile,
        out: &Path,
        observer: &mut dyn RunObserver,
    ) -> Result<FolderRun, RunFolderError> {
        std::fs::create_dir_all(out).map_err(|source| RunFolderError::Create {
            path: out.to_path_buf(),
            source,
        })?;
        let bodies = self.bodies.clone();
        let result = self.run(scene, Some(&out.join("frames")), observer)?;
        let written =
            crate::output::write_outputs(out, &result, &bodies, &scene.output).map_err(|source| {
                RunFolderError::Write {
                    path: out.to_path_buf(),
                    source,
                }
            })?;
        Ok(FolderRun { result, written })
    }
}
