//! The algorithms, over the mesh of [`crate::mesh`]: Delaunay triangulation, segment insertion
//! (constrained Delaunay), carving the domain (holes, regions) and the Voronoi dual.

pub mod constrain;
pub mod delaunay;
pub mod domain;
pub mod reconstruct;
pub mod refine;
pub mod voronoi;
