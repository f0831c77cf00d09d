//! Fuzz target: the TOML scene loader of `beam-trace`.
//!
//! The input bytes, decoded as UTF-8 (invalid sequences replaced), are loaded as a scene file
//! (`Scene::from_toml`). Any input must give a scene or an error, never a panic, and every
//! error of a scene text must be an `Error::Scene` whose message can be shown. The scene
//! files of the repository and the malformed-scene corpus are good seeds:
//!
//! ```text
//! cargo fuzz run scene_loader corpus/scene_loader ../scenes ../crates/beam-trace/tests/bad_scenes
//! ```

#![no_main]

use beam_trace::{Error, Scene};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    match Scene::from_toml(&text, "fuzz", None) {
        Ok(scene) => {
            assert!(!scene.geometry.leaves().is_empty());
            assert_eq!(scene.geometry.context().var_count(), 3);
        }
        Err(e @ Error::Scene { .. }) => {
            let _ = e.to_string();
        }
        Err(e) => panic!("unexpected error kind: {e:?}"),
    }
});
