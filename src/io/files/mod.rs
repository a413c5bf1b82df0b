//! Triangle's file formats: readers and writers of `.node`, `.ele`, `.poly`, `.area`, `.edge`,
//! `.neigh`, `.v.node`, `.v.edge` and `.off`, and the rules of its command line: file names, which
//! files a run reads and writes ([`plan`]).
//!
//! Readers take text already in memory and the file's name (for error messages); writers take
//! borrowed flat arrays in the layout of [`crate::data::Output`] and write Triangle's exact
//! layouts (`%.17g` reals, its column widths), so outputs can be diffed line by line with the
//! reference program's.

pub mod format;
pub mod load;
pub mod naming;
pub mod plan;
pub mod read;
pub mod write;

pub use format::{g17, push_g17};
pub use load::{read_file, read_text_file};
pub use naming::{next_iteration_name, split_input_name, InputName};
pub use plan::{plan_outputs, read_inputs, repeated_path, FileWriter, InputFiles, PlannedFile};
pub use read::{
    check_vertex_indices, read_area, read_edge, read_ele, read_neigh, read_node, read_off,
    read_poly, read_voronoi_edge, AreaFile, EdgeFile, EleFile, FileError, NeighFile, NodeFile,
    OffFile, PolyFile, VoronoiEdgeFile,
};
pub use write::{
    write_area, write_edge, write_ele, write_neigh, write_node, write_off, write_poly,
    write_voronoi_edge, EleData, NodeData, PolyData, PolyVertices,
};
