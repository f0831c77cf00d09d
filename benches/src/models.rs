//! The committed models of `data/models/`: which generator and seed write each file, so
//! that the `gen_models` binary rewrites them all and a test checks that each file is what
//! its generator writes.

use std::path::PathBuf;

use crate::csg3d::{self, Flavour};
use crate::{csg2d, text2d};

/// A committed `.vm` model and the generator that writes it.
#[derive(Copy, Clone, Debug)]
pub struct Model {
    /// Short name, also the file's stem (`csg3d-660`).
    pub name: &'static str,
    /// What the model is.
    pub description: &'static str,
    /// The seed of the committed file.
    pub seed: u64,
    /// Whether the model depends on `z` (a 3D model).
    pub three_d: bool,
    generate: fn(u64) -> String,
    text: &'static str,
}

impl Model {
    /// The text the generator writes for `seed` (the committed file for [`Model::seed`]).
    pub fn generate(&self, seed: u64) -> String {
        (self.generate)(seed)
    }

    /// The committed file's text, as compiled into the crate.
    pub fn committed(&self) -> &'static str {
        self.text
    }

    /// The committed file's path, `data/models/NAME.vm` of the repository.
    pub fn path(&self) -> PathBuf {
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("..")
            .join("data")
            .join("models")
            .join(format!("{}.vm", self.name))
    }
}

/// Seed of `data/models/csg3d-660.vm`.
pub const CSG3D_660_SEED: u64 = 0x0c17_9660;
/// Seed of `data/models/csg3d-2k.vm`.
pub const CSG3D_2K_SEED: u64 = 0x3010_c2c0;

/// Every committed model.
pub const MODELS: [Model; 4] = [
    Model {
        name: "csg2d",
        description: "a page of glyphs built from 2D CSG primitives (min/max-heavy), about 6,400 operations",
        seed: csg2d::SEED,
        three_d: false,
        generate: csg2d::generate,
        text: include_str!("../../data/models/csg2d.vm"),
    },
    Model {
        name: "text2d",
        description: "lines of text with the operation mix of prospero.vm, about 6,500 operations and 1,400 constants",
        seed: text2d::SEED,
        three_d: false,
        generate: text2d::generate,
        text: include_str!("../../data/models/text2d.vm"),
    },
    Model {
        name: "csg3d-660",
        description: "a city of boxes and CSG in [-1, 1]³ (min/max-heavy), about 660 operations",
        seed: CSG3D_660_SEED,
        three_d: true,
        generate: |seed| csg3d::generate(Flavour::City, 660, seed),
        text: include_str!("../../data/models/csg3d-660.vm"),
    },
    Model {
        name: "csg3d-2k",
        description: "a molecule of spheres, capsules and tori in [-1, 1]³ (sqrt-heavy), about 2,000 operations",
        seed: CSG3D_2K_SEED,
        three_d: true,
        generate: |seed| csg3d::generate(Flavour::Molecule, 2000, seed),
        text: include_str!("../../data/models/csg3d-2k.vm"),
    },
];

/// The committed model called `name`.
pub fn get(name: &str) -> Option<&'static Model> {
    MODELS.iter().find(|m| m.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn committed_files_are_reproducible() {
        for m in &MODELS {
            assert!(
                m.committed() == m.generate(m.seed),
                "{} differs from its generator: regenerate with `cargo run -p benches --bin gen_models`",
                m.name
            );
        }
    }
}
