//! Shared helpers of the integration tests and the benchmark: a seeded RNG, point generators,
//! safe wrappers around our C ABI and Debian's Triangle (the differential oracle), set views of
//! outputs and the validity checks of a triangulation.
#![allow(dead_code)]

pub mod call;
pub mod checks;
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

/// True while `triangle_rs::triangulate` cannot triangulate a plain point set yet ("not
/// supported yet"): the C programs may skip then, and only then.
pub fn engine_is_missing() -> bool {
    let input = MeshInput::from_points(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
    matches!(ours("zQ", &input), Err(message) if message.contains("not supported yet"))
}
