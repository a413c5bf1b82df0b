//! triangle-rs: a two-dimensional Delaunay triangulator and quality mesh generator with the C ABI
//! of Jonathan Shewchuk's Triangle 1.6.
//!
//! Layers, bottom up (see ARCHITECTURE.md):
//! - [`geometry`]: exact predicates (`robust`) and constructions;
//! - [`mesh`]: the triangle mesh topology in flat arrays;
//! - [`algorithms`]: Delaunay triangulation, segment insertion, domain carving, Voronoi;
//! - [`options`], [`data`], [`pipeline`], [`assemble`]: parsed switches, plain input/output data,
//!   the driver that runs the algorithms the switches ask for, and the output numbering;
//! - [`io`]: `struct triangulateio` conversion (and file formats);
//! - [`ffi`]: the C ABI.

pub mod algorithms;
pub mod assemble;
pub mod data;
pub mod error;
pub mod ffi;
pub mod geometry;
pub mod io;
mod memory;
pub mod mesh;
pub mod options;
pub mod pipeline;
pub mod scaling;
mod threads;

/// With the `malloc-outputs` feature (the default) on Unix, every Rust allocation of this library
/// is the C library's: the standard library's system allocator is malloc-based there (malloc,
/// realloc, posix_memalign for large alignments, free). The C ABI then hands the arrays the
/// engine built to the caller as they are — the caller frees them with `free` or `trifree`, as
/// Triangle's — instead of copying them into new ones: at a million points that copy is some
/// 44 MB of fresh pages, a tenth of a triangulation's time.
#[cfg(all(unix, feature = "malloc-outputs"))]
#[global_allocator]
static MALLOC: std::alloc::System = std::alloc::System;

pub use data::{Hooks, Input, MeshCheck, Output, Phase, Progress, VoronoiDiagram, VoronoiOutput};
pub use error::Error;
pub use options::{Options, SwitchSource};
pub use pipeline::triangulate;
