//! The TOML scene file format (to be written).

/// The built-in default scene (TOML).
pub const DEFAULT_SCENE: &str = "";
