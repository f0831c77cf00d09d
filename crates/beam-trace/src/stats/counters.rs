//! The work counters of each pass, as named fields: the pipeline counts into them, and
//! [`PassStats`](super::PassStats) lists them by name, in the order of their declaration,
//! with the root-search counters of the pass's queries last.

use crate::beam::BoxClass;
use crate::root::RootCounters;

/// The root-search counters by name, in the order they are reported; `block_proven` only
/// where a block of frames handed proofs to the pass (it is 0 everywhere else).
pub fn search_counters(c: &RootCounters) -> Vec<(&'static str, u64)> {
    let mut v = vec![
        ("g_evals", c.g_evals),
        ("dg_evals", c.dg_evals),
        ("point_evals", c.point_evals),
        ("bisections", c.bisections),
        ("escalated", c.escalated),
        ("escalated_resolved", c.escalated_resolved),
        ("escalated_open", c.escalated - c.escalated_resolved),
    ];
    if c.block_proven > 0 {
        v.push(("block_proven", c.block_proven));
    }
    v
}

/// Counters a pass reports: named, in a fixed order.
pub trait Counters {
    /// The counters by name, in the order they are reported.
    fn list(&self) -> Vec<(&'static str, u64)>;
}

/// Defines a counter struct: `u64` fields counted by a pass, and, after `search`, the field
/// holding the root-search counters of its queries.
macro_rules! counters {
    (
        $(#[$meta:meta])*
        pub struct $name:ident {
            $($(#[$fmeta:meta])* $field:ident,)*
        }
        $(search: $search:ident)?
    ) => {
        $(#[$meta])*
        #[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
        pub struct $name {
            $($(#[$fmeta])* pub $field: u64,)*
            $(
                /// Root-search counters of the pass's queries.
                pub $search: RootCounters,
            )?
        }

        impl $name {
            /// Adds `other` into `self`.
            pub fn add(&mut self, other: &Self) {
                $(self.$field += other.$field;)*
                $(self.$search.add(&other.$search);)?
            }
        }

        impl Counters for $name {
            fn list(&self) -> Vec<(&'static str, u64)> {
                #[allow(unused_mut)]
                let mut v = vec![$((stringify!($field), self.$field)),*];
                $(v.extend(search_counters(&self.$search));)?
                v
            }
        }
    };
}

counters! {
    /// The regular grid (the CPU backend's acceleration structure).
    pub struct GridCounters {
        /// Cells of the grid.
        cells,
        /// Cells whose classification could not exclude the surface.
        non_empty,
        /// Distinct functions of the cells (CSG-reduced, then pruned per cell).
        functions,
        /// Distinct CSG reductions of the objects' trees.
        reduced,
        /// Mean instructions of a non-empty cell's function.
        cell_instrs,
        /// Instructions of the full scene function.
        full_instrs,
        /// Interval evaluations of leaf surfaces while classifying.
        leaf_evals,
    }
}

counters! {
    /// The screen box structure.
    pub struct ScreenBoxCounters {
        /// Beams classified.
        beams,
        /// Pixels in boxes proven to miss.
        miss_pixels,
        /// Pixels in boxes proven to hit.
        hit_pixels,
        /// Pixels in undecided boxes.
        undecided_pixels,
        /// Hit boxes of more than one pixel whose shading was proven to vary by at most
        /// the anti-aliasing threshold (interval anti-aliasing only).
        smooth_boxes,
        /// The pixels of those boxes, shaded once each with no beam of their own.
        smooth_pixels,
    }
    search: search
}

counters! {
    /// Ray-based primary visibility.
    pub struct PrimaryRayCounters {
        /// Rays searched.
        rays,
        /// Rays that met a surface (or may have).
        hits,
        /// Hits with a proven unique root.
        proven_unique,
        /// Hits with a possible root only.
        possible,
        /// Rays whose search hit its limits.
        undecided,
    }
    search: search
}

counters! {
    /// Pixels resolved by their beams (and interval anti-aliasing).
    pub struct PixelBeamCounters {
        /// Beams classified (pixels and sub-pixels).
        beams,
        /// Beams rejected.
        rejected,
        /// Sub-pixels shaded once.
        shaded_once,
        /// Splits of undecided beams.
        splits_undecided,
        /// Undecided beams at the depth limit.
        depth_limit,
        /// Central rays searched.
        rays,
        /// Splits of Hit beams on the shading-variation estimator.
        splits_variation,
    }
    search: search
}

counters! {
    /// Surface normals.
    pub struct NormalCounters {
        /// Normals computed.
        normals,
        /// Points whose gradient vanished.
        degenerate,
    }
    search: search
}

counters! {
    /// Hard shadows from point lights.
    pub struct HardShadowCounters {
        /// Shadow segments (hit sample × point light).
        segments,
        /// Segments proven free.
        lit,
        /// Segments that meet a surface.
        occluded,
        /// Segments whose search hit its limits.
        undecided,
        /// Samples facing away from the light (no segment searched).
        back_facing,
    }
    search: search
}

counters! {
    /// Soft shadows from one area light, or summed over all of them (the columns of the
    /// soft-shadow paper's Table 1 and more).
    pub struct SoftShadowCounters {
        /// Pixels with a shaded sample that does not see the whole light.
        pixels_in_shadow,
        /// Pixels proven fully lit.
        lit_pixels,
        /// Pixels proven in the umbra.
        umbra_pixels,
        /// Pixels in the penumbra (neither proven).
        penumbra_pixels,
        /// Queries (shaded point × light).
        queries,
        /// Samples facing away from the light.
        back_facing,
        /// Initial shadow beams over a whole light.
        initial_beams,
        /// Initial beams that could not be rejected.
        initial_beams_occluded,
        /// Initial beams proven blocked for every ray.
        umbra_proofs,
        /// Sub-beams over parts of a light.
        sub_beams,
        /// Shadow segments.
        rays,
        /// Segments decided by the last-occluder cache.
        cache_hits,
        /// Triangles kept by the exact method's shaft culling, over its queries.
        shaft_triangles,
        /// The faces those triangles make (coplanar neighbours merged): the exact method's
        /// occluders.
        shaft_faces,
        /// Inner nodes the exact method's BSPs created.
        bsp_nodes,
        /// The most nodes of one BSP alive at once (its peak memory, in nodes).
        bsp_peak_nodes,
        /// Visible fragments the exact method's queries returned.
        bsp_fragments,
        /// Pixels whose proven bound on the visible fraction is at most the method's
        /// tolerance wide (0 for methods without one: proven lit or umbra).
        certified_pixels,
        /// Mean width of the pixels' proven bounds, in millionths.
        bound_width_mean_ppm,
        /// Largest width of a pixel's proven bound, in millionths.
        bound_width_max_ppm,
    }
    search: search
}

counters! {
    /// Shading.
    pub struct ShadingCounters {
        /// Samples shaded.
        shaded_samples,
    }
}

impl ScreenBoxCounters {
    /// Counts `pixels` pixels of class `class`.
    pub fn add_pixels(&mut self, class: &BoxClass, pixels: u64) {
        let count = match class {
            BoxClass::Miss => &mut self.miss_pixels,
            BoxClass::Hit { .. } => &mut self.hit_pixels,
            BoxClass::Undecided { .. } => &mut self.undecided_pixels,
        };
        *count += pixels;
    }
}
