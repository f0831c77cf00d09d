//! Render settings of a scene file (`[render]` and the primary mode), and the parsing of
//! settings from strings (also for command lines).

use std::str::FromStr;

use implicit_expr::parse::suggest;

use super::diagnostics::Doc;
use super::model::MAX_GRID_RESOLUTION;
use super::model::{AaMode, PrimaryMode, RenderSettings};
use super::schema::RawRender;
use crate::error::Error;

impl FromStr for PrimaryMode {
    type Err = String;

    /// `screen-boxes`, `screen-rays`, `per-pixel` or `octree`.
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "screen-boxes" => Ok(PrimaryMode::ScreenBoxes),
            "screen-rays" => Ok(PrimaryMode::ScreenRays),
            "per-pixel" => Ok(PrimaryMode::PerPixel),
            "octree" => Ok(PrimaryMode::Octree),
            _ => {
                let names = ["screen-boxes", "screen-rays", "per-pixel", "octree"];
                let hint = suggest::did_you_mean(s, names)
                    .map(|h| format!("; {h}"))
                    .unwrap_or_default();
                Err(format!(
                    "unknown primary mode '{s}'{hint} (one of: screen-boxes, screen-rays, per-pixel, octree)"
                ))
            }
        }
    }
}

pub(super) fn render_settings(doc: &Doc<'_>, r: &RawRender) -> Result<RenderSettings, Error> {
    let mut s = RenderSettings::default();
    if let Some(name) = &r.root_finder {
        s.root_finder = name.parse().map_err(|m| doc.err("render.root_finder", m))?;
    }
    if let Some(v) = r.epsilon {
        s.root.epsilon = doc.positive("render.epsilon", v)?;
    }
    if let Some(v) = r.max_steps {
        if v < 1 {
            return Err(doc.err("render.max_steps", format!("must be at least 1, got {v}")));
        }
        s.root.max_steps = v as u64;
    }
    if let Some(v) = r.sampling_step {
        let v = doc.positive("render.sampling_step", v)?;
        if v > 1.0 {
            return Err(doc.err(
                "render.sampling_step",
                format!("must be at most 1, got {v}"),
            ));
        }
        s.root.sampling_step = v;
    }
    if let Some(v) = r.lipschitz {
        s.root.lipschitz = doc.positive("render.lipschitz", v)?;
    }
    if let Some(p) = &r.primary {
        s.primary = p.parse().map_err(|m| doc.err("render.primary", m))?;
    }
    if let Some(v) = r.undecided_depth {
        s.undecided_depth = doc.int_in("render.undecided_depth", v, 0, 8)?;
    }
    if let Some(a) = &r.aa {
        s.aa = Some(a.parse().map_err(|m| doc.err("render.aa", m))?);
    }
    // The `iaa_*` keys are checked whatever the mode, and set what they name of the IAA
    // mode the render uses (the default one too); the others keep the mode's.
    let depth = r
        .iaa_depth
        .map(|v| doc.int_in("render.iaa_depth", v, 1, 8))
        .transpose()?;
    let threshold_key = r
        .iaa_threshold
        .map(|v| doc.positive("render.iaa_threshold", v))
        .transpose()?;
    let rays = r
        .iaa_limit_rays
        .map(|v| {
            doc.int_in(
                "render.iaa_limit_rays",
                v,
                1,
                i64::from(AaMode::MAX_LIMIT_RAYS),
            )
        })
        .transpose()?;
    if let AaMode::Iaa {
        max_depth,
        threshold,
        limit_rays,
    } = s.aa_mode()
        && (depth.is_some() || threshold_key.is_some() || rays.is_some())
    {
        s.aa = Some(AaMode::Iaa {
            max_depth: depth.unwrap_or(max_depth),
            threshold: threshold_key.unwrap_or(threshold),
            limit_rays: rays.unwrap_or(limit_rays),
        });
    }
    if let Some(v) = r.rays_per_undecided {
        s.rays_per_undecided = doc.square("render.rays_per_undecided", v)?;
    }
    if let Some(v) = r.rays_per_pixel {
        s.rays_per_pixel = doc.square("render.rays_per_pixel", v)?;
    }
    if let Some(v) = r.t_final_width {
        s.t_final_width = doc.positive("render.t_final_width", v)?;
    }
    if let Some(v) = r.grid {
        s.grid_resolution = doc.int_in("render.grid", v, 0, i64::from(MAX_GRID_RESOLUTION))?;
        s.grid_auto = false;
    }
    if let Some(v) = r.shadows {
        s.shadows = v;
    }
    if let Some(m) = &r.shadow_method {
        s.shadow_method = m.parse().map_err(|m| doc.err("render.shadow_method", m))?;
    }
    if let Some(p) = &r.precision {
        s.precision = p.parse().map_err(|m| doc.err("render.precision", m))?;
    }
    if let Some(v) = r.escalate {
        s.root.escalate = v;
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn aa_strings() {
        assert_eq!("none".parse::<AaMode>(), Ok(AaMode::None));
        assert_eq!("ss:3".parse::<AaMode>(), Ok(AaMode::Supersample(3)));
        assert!("ss:0".parse::<AaMode>().is_err());
        assert!("ss:17".parse::<AaMode>().is_err());
        assert!("ss:".parse::<AaMode>().is_err());
        assert!(matches!(
            "iaa".parse::<AaMode>(),
            Ok(AaMode::Iaa {
                max_depth: 4,
                limit_rays: 2,
                ..
            })
        ));
        assert_eq!(
            "iaa:3:0.1:4".parse::<AaMode>(),
            Ok(AaMode::Iaa {
                max_depth: 3,
                threshold: 0.1,
                limit_rays: 4
            })
        );
        assert!(matches!(
            "iaa:2".parse::<AaMode>(),
            Ok(AaMode::Iaa {
                max_depth: 2,
                limit_rays: 2,
                ..
            })
        ));
        for bad in [
            "iaa:3:0.1:0",
            "iaa:3:0.1:17",
            "iaa:3:0.1:2:1",
            "iaa:0",
            "iaa:3:-1",
        ] {
            assert!(bad.parse::<AaMode>().is_err(), "{bad}");
        }
        assert_eq!(
            "per-pixel".parse::<PrimaryMode>(),
            Ok(PrimaryMode::PerPixel)
        );
        assert!(
            "per_pixel"
                .parse::<PrimaryMode>()
                .unwrap_err()
                .contains("'per-pixel'")
        );
    }
}
