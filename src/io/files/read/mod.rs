//! Readers of Triangle's files, from text already in memory (the caller reads the file, so these
//! are testable without a file system and the error names the file it was given).
//!
//! The syntax follows Triangle's `-h` description and its reader's behaviour:
//! - a UTF-8 byte-order mark at the start of a file (EF BB BF, as some editors save) is skipped;
//! - `#` starts a comment that runs to the end of the line; lines without a number are skipped;
//! - fields are separated by white space; a word that does not start like a number (a digit,
//!   `.`, `+` or `-`) is skipped, so `1 0.5 0.5 boundary` reads three numbers;
//! - integers are read as C's `strtol(word, 0)` reads them (`0x10` is 16, `010` is 8) and reals
//!   as `strtod` (exponents such as `0.418893E+02` are fine); a number ends at the first character
//!   that cannot continue it, so an integer field may be written `3.0`;
//! - missing optional fields (attributes, markers, a region's area) read as Triangle defaults them.
//!
//! Stricter than Triangle, for clean errors: a numeric-looking word with no number in it (`-`,
//! `.`), a non-finite real, a count that is negative or beyond `i32`, and (checked by
//! [`check_vertex_indices`]) an index outside the vertex numbering are errors naming the file and
//! line. More lenient, as Triangle's documentation says: the region section of a `.poly` file is
//! optional even when regions are read.

use std::fmt;

// The parts: this file holds the readers of each format; `records` the lines, fields and numbers;
// `vertices` the vertex section, which has a fast path for large files.
mod records;
#[cfg(test)]
mod tests;
mod vertices;

use records::{reserve, Lines};
use vertices::read_vertices;

/// A problem in an input file: which file, which line (1-based, if one is to blame), and what.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FileError {
    pub file: String,
    pub line: Option<usize>,
    pub message: String,
}

impl fmt::Display for FileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "{}, line {}: {}", self.file, line, self.message),
            None => write!(f, "{}: {}", self.file, self.message),
        }
    }
}

impl std::error::Error for FileError {}

/// Vertices as a `.node` file (or the first section of a `.poly` file) gives them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NodeFile {
    /// The number written before the first vertex (`None` with no vertices). Triangle takes the
    /// numbering base of every file from it when it is 0 or 1.
    pub first_number: Option<i64>,
    /// x, y per vertex.
    pub points: Vec<f64>,
    pub attribute_count: usize,
    /// `attribute_count` values per vertex.
    pub attributes: Vec<f64>,
    /// One marker per vertex when the header announces a marker column.
    pub markers: Option<Vec<i32>>,
}

impl NodeFile {
    pub fn point_count(&self) -> usize {
        self.points.len() / 2
    }
}

/// Triangles as an `.ele` file gives them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EleFile {
    pub first_number: Option<i64>,
    /// Nodes per triangle: 3, or 6 for second-order triangles.
    pub corners: usize,
    /// `corners` vertex numbers per triangle, as written.
    pub triangles: Vec<i32>,
    pub attribute_count: usize,
    pub attributes: Vec<f64>,
    /// The line of each triangle, to name it in later checks.
    pub lines: Vec<u32>,
}

impl EleFile {
    pub fn triangle_count(&self) -> usize {
        self.triangles.len().checked_div(self.corners).unwrap_or(0)
    }
}

/// A `.poly` file: vertices (possibly none: then they come from the `.node` file), segments,
/// holes and, when asked for, regions.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PolyFile {
    pub vertices: NodeFile,
    /// Two vertex numbers per segment, as written.
    pub segments: Vec<i32>,
    /// One marker per segment when the segment header announces a marker column.
    pub segment_markers: Option<Vec<i32>>,
    /// The line of each segment.
    pub segment_lines: Vec<u32>,
    /// x, y per hole.
    pub holes: Vec<f64>,
    /// x, y, attribute, maximum area per region (a missing area equals the attribute, as in
    /// Triangle).
    pub regions: Vec<f64>,
}

/// An `.area` file: one maximum area per triangle (negative: no constraint).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AreaFile {
    pub first_number: Option<i64>,
    pub areas: Vec<f64>,
}

/// An `.edge` file (output only in Triangle; read back by tests and tools).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EdgeFile {
    pub first_number: Option<i64>,
    /// Two vertex numbers per edge.
    pub edges: Vec<i32>,
    pub markers: Option<Vec<i32>>,
}

/// A `.v.edge` file: Voronoi edges; the second vertex is -1 for a ray, whose direction is in
/// `norms` ((0, 0) for finite edges, as `VoronoiDiagram::norms`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VoronoiEdgeFile {
    pub first_number: Option<i64>,
    pub edges: Vec<i32>,
    pub norms: Vec<f64>,
}

/// A `.neigh` file: three neighbours per triangle, -1 for none.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NeighFile {
    pub first_number: Option<i64>,
    pub neighbors: Vec<i32>,
}

/// A Geomview `.off` file as Triangle writes it: 3-D vertices (z = 0) and 0-based triangles.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OffFile {
    /// x, y, z per vertex.
    pub points: Vec<f64>,
    /// Three 0-based vertex indices per face.
    pub triangles: Vec<i32>,
    pub edge_count: usize,
}

// ------------------------------------------------------------------------------------------------
// Readers

/// Reads a `.node` file (also `.v.node`). `file` names it in errors.
pub fn read_node(text: &str, file: &str) -> Result<NodeFile, FileError> {
    let mut lines = Lines::new(file, text);
    let header = lines.expect_record(format_args!("the header (number of vertices)"))?;
    read_vertices(&mut lines, header)
}

/// Reads an `.ele` file.
pub fn read_ele(text: &str, file: &str) -> Result<EleFile, FileError> {
    let mut lines = Lines::new(file, text);
    let mut header = lines.expect_record(format_args!("the header (number of triangles)"))?;
    let count = header.count(format_args!("the number of triangles"))?;
    let corners = header
        .optional_count(format_args!("the number of nodes per triangle"))?
        .unwrap_or(3);
    if corners < 3 {
        return Err(header.error(format!(
            "triangles must have at least 3 nodes, not {corners}"
        )));
    }
    let attribute_count = header
        .optional_count(format_args!("the number of triangle attributes"))?
        .unwrap_or(0);
    let mut ele = EleFile {
        first_number: None,
        corners,
        triangles: Vec::with_capacity(reserve(count, corners)),
        attribute_count,
        attributes: Vec::with_capacity(reserve(count, attribute_count)),
        lines: Vec::with_capacity(reserve(count, 1)),
    };
    for k in 0..count {
        let mut record = lines.expect_record(format_args!("triangle {} of {count}", k + 1))?;
        let number = record.integer(format_args!("the triangle number"))?;
        if k == 0 {
            ele.first_number = Some(number);
        }
        for c in 0..corners {
            let vertex = record.int32(format_args!("node {} of triangle {number}", c + 1))?;
            ele.triangles.push(vertex);
        }
        for a in 0..attribute_count {
            let value =
                record.optional_real(format_args!("attribute {} of triangle {number}", a + 1))?;
            ele.attributes.push(value.unwrap_or(0.0));
        }
        ele.lines
            .push(u32::try_from(record.line).unwrap_or(u32::MAX));
    }
    Ok(ele)
}

/// Reads a `.poly` file. Regions are read only when `read_regions` (Triangle reads them only for
/// `A` or `a` without a number, and not with `r`); their section may then be absent.
pub fn read_poly(text: &str, file: &str, read_regions: bool) -> Result<PolyFile, FileError> {
    let mut lines = Lines::new(file, text);
    let header = lines.expect_record(format_args!("the header (number of vertices)"))?;
    let vertices = read_vertices(&mut lines, header)?;

    let mut header =
        lines.expect_record(format_args!("the segment header (number of segments)"))?;
    let segment_count = header.count(format_args!("the number of segments"))?;
    let has_markers = header
        .optional_count(format_args!("the number of segment markers"))?
        .unwrap_or(0)
        != 0;
    let mut poly = PolyFile {
        vertices,
        segments: Vec::with_capacity(reserve(segment_count, 2)),
        segment_markers: has_markers.then(|| Vec::with_capacity(reserve(segment_count, 1))),
        segment_lines: Vec::with_capacity(reserve(segment_count, 1)),
        ..PolyFile::default()
    };
    for k in 0..segment_count {
        let mut record =
            lines.expect_record(format_args!("segment {} of {segment_count}", k + 1))?;
        let number = record.integer(format_args!("the segment number"))?;
        let first = record.int32(format_args!("the first endpoint of segment {number}"))?;
        let second = record.int32(format_args!("the second endpoint of segment {number}"))?;
        poly.segments.extend_from_slice(&[first, second]);
        if let Some(markers) = poly.segment_markers.as_mut() {
            markers.push(
                record
                    .optional_int32(format_args!("the marker of segment {number}"))?
                    .unwrap_or(0),
            );
        }
        poly.segment_lines
            .push(u32::try_from(record.line).unwrap_or(u32::MAX));
    }

    let mut header = lines.expect_record(format_args!("the hole header (number of holes)"))?;
    let hole_count = header.count(format_args!("the number of holes"))?;
    poly.holes.reserve(reserve(hole_count, 2));
    for k in 0..hole_count {
        let mut record = lines.expect_record(format_args!("hole {} of {hole_count}", k + 1))?;
        let number = record.integer(format_args!("the hole number"))?;
        let x = record.real(format_args!("the x coordinate of hole {number}"))?;
        let y = record.real(format_args!("the y coordinate of hole {number}"))?;
        poly.holes.extend_from_slice(&[x, y]);
    }

    if read_regions {
        if let Some(mut header) = lines.next_record() {
            let region_count = header.count(format_args!("the number of regions"))?;
            poly.regions.reserve(reserve(region_count, 4));
            for k in 0..region_count {
                let mut record =
                    lines.expect_record(format_args!("region {} of {region_count}", k + 1))?;
                let number = record.integer(format_args!("the region number"))?;
                let x = record.real(format_args!("the x coordinate of region {number}"))?;
                let y = record.real(format_args!("the y coordinate of region {number}"))?;
                let attribute = record.real(format_args!(
                    "the attribute (or area constraint) of region {number}"
                ))?;
                let area =
                    record.optional_real(format_args!("the area constraint of region {number}"))?;
                poly.regions
                    .extend_from_slice(&[x, y, attribute, area.unwrap_or(attribute)]);
            }
        }
    }
    Ok(poly)
}

/// Reads an `.area` file.
pub fn read_area(text: &str, file: &str) -> Result<AreaFile, FileError> {
    let mut lines = Lines::new(file, text);
    let mut header = lines.expect_record(format_args!("the header (number of triangles)"))?;
    let count = header.count(format_args!("the number of triangles"))?;
    let mut area = AreaFile {
        first_number: None,
        areas: Vec::with_capacity(reserve(count, 1)),
    };
    for k in 0..count {
        let mut record =
            lines.expect_record(format_args!("the area of triangle {} of {count}", k + 1))?;
        let number = record.integer(format_args!("the triangle number"))?;
        if k == 0 {
            area.first_number = Some(number);
        }
        area.areas
            .push(record.real(format_args!("the maximum area of triangle {number}"))?);
    }
    Ok(area)
}

/// Reads an `.edge` file.
pub fn read_edge(text: &str, file: &str) -> Result<EdgeFile, FileError> {
    let mut lines = Lines::new(file, text);
    let mut header = lines.expect_record(format_args!("the header (number of edges)"))?;
    let count = header.count(format_args!("the number of edges"))?;
    let has_markers = header
        .optional_count(format_args!("the number of boundary markers"))?
        .unwrap_or(0)
        != 0;
    let mut edge = EdgeFile {
        first_number: None,
        edges: Vec::with_capacity(reserve(count, 2)),
        markers: has_markers.then(|| Vec::with_capacity(reserve(count, 1))),
    };
    for k in 0..count {
        let mut record = lines.expect_record(format_args!("edge {} of {count}", k + 1))?;
        let number = record.integer(format_args!("the edge number"))?;
        if k == 0 {
            edge.first_number = Some(number);
        }
        let first = record.int32(format_args!("the first endpoint of edge {number}"))?;
        let second = record.int32(format_args!("the second endpoint of edge {number}"))?;
        edge.edges.extend_from_slice(&[first, second]);
        if let Some(markers) = edge.markers.as_mut() {
            markers.push(
                record
                    .optional_int32(format_args!("the marker of edge {number}"))?
                    .unwrap_or(0),
            );
        }
    }
    Ok(edge)
}

/// Reads a `.v.edge` file: rays (second endpoint -1) carry a direction.
pub fn read_voronoi_edge(text: &str, file: &str) -> Result<VoronoiEdgeFile, FileError> {
    let mut lines = Lines::new(file, text);
    let mut header = lines.expect_record(format_args!("the header (number of edges)"))?;
    let count = header.count(format_args!("the number of edges"))?;
    let mut voronoi = VoronoiEdgeFile {
        first_number: None,
        edges: Vec::with_capacity(reserve(count, 2)),
        norms: Vec::with_capacity(reserve(count, 2)),
    };
    for k in 0..count {
        let mut record = lines.expect_record(format_args!("edge {} of {count}", k + 1))?;
        let number = record.integer(format_args!("the edge number"))?;
        if k == 0 {
            voronoi.first_number = Some(number);
        }
        let first = record.int32(format_args!("the first endpoint of edge {number}"))?;
        let second = record.int32(format_args!("the second endpoint of edge {number}"))?;
        voronoi.edges.extend_from_slice(&[first, second]);
        if second == -1 {
            let dx = record.real(format_args!("the x direction of ray {number}"))?;
            let dy = record.real(format_args!("the y direction of ray {number}"))?;
            voronoi.norms.extend_from_slice(&[dx, dy]);
        } else {
            voronoi.norms.extend_from_slice(&[0.0, 0.0]);
        }
    }
    Ok(voronoi)
}

/// Reads a `.neigh` file.
pub fn read_neigh(text: &str, file: &str) -> Result<NeighFile, FileError> {
    let mut lines = Lines::new(file, text);
    let mut header = lines.expect_record(format_args!("the header (number of triangles)"))?;
    let count = header.count(format_args!("the number of triangles"))?;
    let per_triangle = header
        .optional_count(format_args!("the number of neighbours per triangle"))?
        .unwrap_or(3);
    if per_triangle != 3 {
        return Err(header.error(format!("triangles have 3 neighbours, not {per_triangle}")));
    }
    let mut neigh = NeighFile {
        first_number: None,
        neighbors: Vec::with_capacity(reserve(count, 3)),
    };
    for k in 0..count {
        let mut record = lines.expect_record(format_args!("triangle {} of {count}", k + 1))?;
        let number = record.integer(format_args!("the triangle number"))?;
        if k == 0 {
            neigh.first_number = Some(number);
        }
        for n in 0..3 {
            neigh
                .neighbors
                .push(record.int32(format_args!("neighbour {} of triangle {number}", n + 1))?);
        }
    }
    Ok(neigh)
}

/// Reads a Geomview `.off` file with triangular faces (as Triangle's `-g` writes it).
pub fn read_off(text: &str, file: &str) -> Result<OffFile, FileError> {
    let mut lines = Lines::new(file, text);
    // The `OFF` keyword has no number: the reader skips it like a comment.
    let mut header =
        lines.expect_record(format_args!("the header (vertex, face and edge counts)"))?;
    let vertex_count = header.count(format_args!("the number of vertices"))?;
    let face_count = header.count(format_args!("the number of faces"))?;
    let edge_count = header
        .optional_count(format_args!("the number of edges"))?
        .unwrap_or(0);
    let mut off = OffFile {
        points: Vec::with_capacity(reserve(vertex_count, 3)),
        triangles: Vec::with_capacity(reserve(face_count, 3)),
        edge_count,
    };
    for k in 0..vertex_count {
        let mut record = lines.expect_record(format_args!("vertex {} of {vertex_count}", k + 1))?;
        for axis in ["x", "y", "z"] {
            off.points
                .push(record.real(format_args!("the {axis} coordinate of vertex {k}"))?);
        }
    }
    for k in 0..face_count {
        let mut record = lines.expect_record(format_args!("face {} of {face_count}", k + 1))?;
        let sides = record.integer(format_args!("the number of face vertices"))?;
        if sides != 3 {
            return Err(record.error(format!(
                "face {k} has {sides} vertices; only triangles are read"
            )));
        }
        for c in 0..3 {
            let vertex = record.int32(format_args!("vertex {} of face {k}", c + 1))?;
            if vertex < 0 || vertex as usize >= vertex_count {
                return Err(record.error(format!(
                    "face {k} refers to vertex {vertex}, which does not exist"
                )));
            }
            off.triangles.push(vertex);
        }
    }
    Ok(off)
}

/// Checks that every vertex number in `indices` (items of `width` numbers, item `i` read from
/// line `lines[i]` of `file`) names one of `vertex_count` vertices numbered from `first_index`.
/// `what` names an item ("triangle", "segment").
pub fn check_vertex_indices(
    file: &str,
    what: &str,
    indices: &[i32],
    width: usize,
    lines: &[u32],
    first_index: i32,
    vertex_count: usize,
) -> Result<(), FileError> {
    let last = first_index as i64 + vertex_count as i64 - 1;
    for (item, chunk) in indices.chunks(width.max(1)).enumerate() {
        if let Some(&bad) = chunk
            .iter()
            .find(|&&v| (v as i64) < first_index as i64 || v as i64 > last)
        {
            return Err(FileError {
                file: file.to_string(),
                line: lines.get(item).map(|&l| l as usize),
                message: format!(
                    "{what} {} refers to vertex {bad}, but the vertices are numbered {first_index} to {last}",
                    item as i64 + first_index as i64
                ),
            });
        }
    }
    Ok(())
}
