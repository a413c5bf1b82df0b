//! triangle-rs: a two-dimensional Delaunay triangulator and quality mesh generator with the C ABI
//! of Jonathan Shewchuk's Triangle 1.6.
//!
//! Layers, bottom up (see ARCHITECTURE.md):
//! - [`geometry`]: exact predicates (`robust`) and constructions;
//! - [`mesh`]: the triangle mesh topology in flat arrays;
//! - [`delaunay`], [`voronoi`]: the algorithms;
//! - [`options`], [`data`], [`pipeline`]: parsed switches, plain input/output data and the
//!   driver that runs the algorithms the switches ask for;
//! - [`io`]: `struct triangulateio` conversion (and file formats);
//! - [`ffi`]: the C ABI.

pub mod assemble;
pub mod constrain;
pub mod data;
pub mod delaunay;
pub mod domain;
pub mod error;
pub mod ffi;
pub mod geometry;
pub mod io;
pub mod mesh;
pub mod options;
pub mod pipeline;
pub mod voronoi;

pub use data::{Hooks, Input, Output, VoronoiDiagram, VoronoiOutput};
pub use error::Error;
pub use options::{Options, SwitchSource};
pub use pipeline::triangulate;
