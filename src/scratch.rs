//! Files the unit tests write into the temporary folder, removed when dropped.

use std::path::{Path, PathBuf};

/// A file `name` in the temporary folder (named for this process, so parallel test runs do
/// not meet), holding `contents` until dropped.
pub(crate) struct ScratchFile(PathBuf);

impl ScratchFile {
    pub(crate) fn new(name: &str, contents: &[u8]) -> Self {
        let path = std::env::temp_dir().join(format!("cloth-test-{}-{name}", std::process::id()));
        std::fs::write(&path, contents).unwrap();
        Self(path)
    }
}

impl std::ops::Deref for ScratchFile {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl Drop for ScratchFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}
