//! Shadows. Point lights cast hard shadows ([`hard`]); a segment from a surface point to
//! the light is proven unoccluded by interval rejection, and otherwise a reliable root
//! search decides.

pub mod hard;
