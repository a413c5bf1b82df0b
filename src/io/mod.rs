//! Conversion between the engine's plain data and the outside world.

pub mod files;
pub mod svg;
pub mod triangulateio;
