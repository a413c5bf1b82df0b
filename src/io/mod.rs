//! Conversion between the engine's plain data and the outside world.

pub mod triangulateio;
