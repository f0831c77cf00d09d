//! Triangle meshes next to the implicit surfaces: triangles, a bounding-volume hierarchy,
//! and the proofs the renderer needs of them.
//!
//! Every test is made in outward-rounded interval arithmetic on the triangles' `f64`
//! vertices, so what it proves holds of those exact triangles:
//!
//! * a ray or segment **misses** a triangle when two of the signed volumes
//!   `dir · (a × b)` of its vertices seen from the origin have proven opposite signs, or
//!   when the crossing parameter is proven outside the searched window;
//! * it **crosses** it when all three are proven of one sign and the parameter is proven
//!   inside the window; otherwise the crossing is possible, and it counts as a possible
//!   root ([`Proof::Possible`](crate::root::Proof::Possible)): a shadow ray through an edge
//!   is never proven lit;
//! * a **beam** misses the triangles over a parameter range when the box of its points
//!   there is disjoint from every triangle's box or from its plane (the plane's equation
//!   enclosed over the box excludes zero), with the range halved while this fails.
//!
//! The renderer asks these beside the implicit surfaces' searches and keeps the first of
//! the two answers ([`RootResult::first_of`](crate::root::RootResult::first_of)).

mod bvh;
mod closed;
mod combine;
mod embedded;
mod faces;
mod inner;
mod obj;
mod orient;
mod shaft;
mod triangle;

use glam::DVec3;

use crate::ibox::{IBox, disjoint};

pub use bvh::{Bvh, FirstCrossing};
use closed::{closed_components, facing_of};
use embedded::embedded_components;
use inner::inner_squares_of;
pub(crate) use orient::in_range;

pub use closed::facing;
pub use faces::{Faces, MAX_FACE_VERTICES, faces};
pub use inner::{InnerSquare, inner_squares};
pub use obj::read_obj;
pub use shaft::Shaft;
pub use triangle::{Crossing, Triangle, bounds_of};

/// The triangles of several meshes in one hierarchy, each knowing the mesh it came from.
#[derive(Clone, Debug)]
pub struct MeshIndex {
    bvh: Bvh,
    /// Per triangle (in the order given), the mesh it belongs to.
    owner: Vec<u32>,
    /// Per triangle, its unit geometric normal.
    normals: Vec<DVec3>,
    /// Per triangle, which way it faces on its mesh's closed surface ([`facing`]).
    facing: Vec<i8>,
    /// Per mesh, the box of its vertices.
    bounds: Vec<IBox>,
    /// The squares inside the meshes' closed components of [`MIN_INNER_FACES`] faces or
    /// more ([`inner_squares`]).
    inner: Vec<InnerSquare>,
    /// The squares' boxes in a hierarchy: square `k` as the triangle of its first three
    /// corners, whose box is the square's (two of them are opposite corners).
    inner_bvh: Bvh,
    /// The triangles' faces ([`faces`]), each of one mesh and facing one way, numbered over
    /// all the meshes.
    faces: Faces,
}

/// The fewest faces of a closed component that the index looks for squares inside: a
/// square closes an umbra in fewer cells than the faces it stands for only where they are
/// many.
pub const MIN_INNER_FACES: usize = 32;

impl MeshIndex {
    /// The index of the meshes `meshes` (mesh `k` is the `k`-th slice).
    pub fn new<'a>(meshes: impl IntoIterator<Item = &'a [Triangle]>) -> Self {
        let mut all = Vec::new();
        let mut owner = Vec::new();
        let mut facings = Vec::new();
        let mut bounds = Vec::new();
        let mut inner = Vec::new();
        let mut all_faces = Faces::default();
        for (k, m) in meshes.into_iter().enumerate() {
            // Only closed components proven embedded are judged: what the shadows take of
            // them holds of the boundary of a solid.
            let components = embedded_components(m, &closed_components(m));
            inner.extend(inner_squares_of(m, &components, MIN_INNER_FACES));
            all.extend_from_slice(m);
            owner.extend(std::iter::repeat_n(k as u32, m.len()));
            let facing = facing_of(m, &components);
            let mine = faces(m, &facing);
            let first = all_faces.outlines.len() as u32;
            all_faces.of.extend(mine.of.iter().map(|f| f + first));
            all_faces.outlines.extend(mine.outlines);
            facings.extend(facing);
            bounds.push(bounds_of(m).unwrap_or([interval_core::Interval::EMPTY; 3]));
        }
        Self {
            normals: all.iter().map(Triangle::normal).collect(),
            bvh: Bvh::new(&all),
            owner,
            facing: facings,
            bounds,
            inner_bvh: Bvh::new(
                &inner
                    .iter()
                    .map(|sq| Triangle::new(sq.corners[0], sq.corners[1], sq.corners[2]))
                    .collect::<Vec<_>>(),
            ),
            inner,
            faces: all_faces,
        }
    }

    /// The face ([`faces`]) of triangle `triangle`.
    pub fn face_of(&self, triangle: u32) -> u32 {
        self.faces.of[triangle as usize]
    }

    /// The outline of face `face`: a strictly convex polygon that is exactly the union of
    /// its triangles (or one triangle).
    pub fn face(&self, face: u32) -> &[DVec3] {
        &self.faces.outlines[face as usize]
    }

    /// The number of faces of the meshes.
    pub fn face_count(&self) -> usize {
        self.faces.len()
    }

    /// The hierarchy; its triangle indices are those of [`MeshIndex::owner`].
    pub fn bvh(&self) -> &Bvh {
        &self.bvh
    }

    /// The mesh of triangle `triangle`.
    pub fn owner(&self, triangle: u32) -> u32 {
        self.owner[triangle as usize]
    }

    /// The unit geometric normal of triangle `triangle`.
    pub fn normal(&self, triangle: u32) -> DVec3 {
        self.normals[triangle as usize]
    }

    /// The squares inside closed meshes ([`InnerSquare`]) that some segment of `shaft` may
    /// reach, from solids whose box is disjoint from the box `light` (so a segment from a
    /// square to the light crosses a face of the square's mesh), on the axes along which
    /// `toward` (about the direction of the light) has at least half of its largest
    /// coordinate: squares seen edge-on from the light would only cut the trees.
    pub fn inner_in(&self, shaft: &Shaft, light: &IBox, toward: DVec3) -> Vec<Vec<DVec3>> {
        let reach = toward.abs();
        let most = reach.max_element();
        // Those whose box the shaft may reach, in the order of the list.
        let mut near = self.inner_bvh.boxes_in_shaft(shaft);
        near.sort_unstable();
        near.into_iter()
            .map(|k| &self.inner[k as usize])
            .filter(|sq| reach[sq.axis] >= 0.5 * most && disjoint(&sq.solid, light))
            .map(|sq| sq.corners.to_vec())
            .collect()
    }

    /// Whether triangle `triangle` is a face of a closed mesh turned away from a light
    /// whose points lie in the box `light`, outside the mesh's box, and whose `corners`
    /// span it: every corner is proven behind the face's outward plane. A segment from any
    /// point to the light that meets such a face meets the solid, and leaves it through a
    /// face the light is not behind before it reaches the light (outside the solid), so
    /// the face blocks no segment that another face of the mesh does not block. This holds
    /// of the boundary of a solid, so the index judges only closed components proven
    /// embedded (no two faces meet but where the mesh joins them: `embedded.rs`); the
    /// faces of others are never turned away.
    pub fn turned_away(&self, triangle: u32, light: &IBox, corners: &[DVec3]) -> bool {
        let t = triangle as usize;
        let facing = self.facing[t];
        facing != 0
            && disjoint(&self.bounds[self.owner[t] as usize], light)
            && self.bvh.triangle(triangle).side_of_all(corners) == Some(facing < 0)
    }
}

#[cfg(test)]
pub(crate) mod tests;
