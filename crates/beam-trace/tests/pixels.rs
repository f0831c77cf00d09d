//! Pixels resolved by their beams, on the CPU: the cases of `pixel_cases`, with the default
//! anti-aliasing and without any.

#[macro_use]
mod pixel_cases;

use beam_trace::scene::AaMode;
use beam_trace::{NoProgress, Scene, render};

/// Runs `case` with the CPU renderer, with anti-aliasing off unless the case asks for some
/// where `plain`.
fn with_cpu(case: fn(pixel_cases::Render<'_>), plain: bool) {
    case(&|scene: &Scene| {
        let mut s = scene.clone();
        if plain {
            s.settings.aa.get_or_insert(AaMode::None);
        }
        render(&s, &NoProgress).expect("the render succeeds")
    });
}

/// Runs `case` with the CPU renderer.
fn on_cpu(case: fn(pixel_cases::Render<'_>)) {
    with_cpu(case, false);
}

pixel_tests!(on_cpu);

/// The same cases where a scene names no anti-aliasing rendered without it (`aa = "none"`):
/// the pixel-beams pass splitting only undecided beams.
mod without_anti_aliasing {
    use super::{pixel_cases, with_cpu};

    /// Runs `case` with the CPU renderer, anti-aliasing off unless the case asks for some.
    fn on_cpu(case: fn(pixel_cases::Render<'_>)) {
        with_cpu(case, true);
    }

    pixel_tests!(on_cpu);
}
