//! Shared helpers of the integration tests and the benchmark: a seeded RNG, point generators,
//! safe wrappers around our C ABI and Debian's Triangle (the differential oracle), set views of
//! outputs, the validity checks of a triangulation, and Triangle's own example files.
#![allow(dead_code)]

pub mod call;
pub mod checks;
pub mod examples;
pub mod points;
pub mod pslg;
pub mod pslg_checks;
pub mod quality;
pub mod reference;
pub mod rng;
pub mod timing;

#[allow(unused_imports)]
pub use call::{ours, ours_with, MeshInput, Triangulation};
#[allow(unused_imports)]
pub use reference::{reference, reference_missing};
