//! The crate's error type: every variant names the place of the problem.

use std::path::PathBuf;

/// Errors of scene loading, set-up and output.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A scene file or text is malformed: the file (or `<built-in>`), the field path
    /// (`lights[1].size`) and the problem.
    #[error("{file}: {}{message}", if path.is_empty() { String::new() } else { format!("{path}: ") })]
    Scene {
        /// The file, or a name for an in-memory scene.
        file: String,
        /// The field path inside the scene (`surfaces[0].formula`), empty for the whole file.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// The camera cannot be built.
    #[error("camera: {0}")]
    Camera(String),
    /// A formula or expression error.
    #[error(transparent)]
    Expr(#[from] implicit_expr::Error),
    /// Reading or writing a file failed.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// An invalid render setting (command line or scene).
    #[error("setting {name}: {message}")]
    Setting {
        /// The setting.
        name: String,
        /// What is wrong.
        message: String,
    },
    /// Data handed in or read back is malformed (a float map's size, a PFM file's header).
    #[error("{0}")]
    Data(String),
    /// A render backend cannot run the scene, or failed.
    #[error("{backend} backend: {message}")]
    Backend {
        /// The backend.
        backend: String,
        /// What went wrong.
        message: String,
    },
}
