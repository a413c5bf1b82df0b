//! The driver: runs the algorithms that the options ask for on an [`Input`] and assembles the
//! [`Output`]. (Stub while the engine lands.)

use crate::data::{Hooks, Input, Output, VoronoiOutput};
use crate::error::Error;
use crate::options::Options;

pub fn triangulate(_options: &Options, _input: &Input<'_>, _hooks: &Hooks<'_>) -> Result<(Output, VoronoiOutput), Error> {
    Err(Error::Unsupported("everything"))
}
