//! Readers of Triangle's files, from text already in memory (the caller reads the file, so these
//! are testable without a file system and the error names the file it was given).
//!
//! The syntax follows Triangle's `-h` description and its reader's behaviour:
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
// Records and fields

/// The lines of a file, skipping those without data.
struct Lines<'a> {
    file: &'a str,
    text: &'a str,
    position: usize,
    line_number: usize,
}

/// One line with data: the part before `#`, read field by field. Fields are described with
/// `format_args!`, which is formatted only if an error is reported (files have millions of them).
struct Record<'a> {
    file: &'a str,
    line: usize,
    rest: &'a str,
}

fn starts_like_a_number(word: &str) -> bool {
    matches!(
        word.as_bytes().first(),
        Some(b'0'..=b'9' | b'.' | b'+' | b'-')
    )
}

impl<'a> Lines<'a> {
    fn new(file: &'a str, text: &'a str) -> Self {
        Lines {
            file,
            text,
            position: 0,
            line_number: 0,
        }
    }

    fn error(&self, line: Option<usize>, message: String) -> FileError {
        FileError {
            file: self.file.to_string(),
            line,
            message,
        }
    }

    /// The next line that holds a number, or `None` at the end of the file.
    fn next_record(&mut self) -> Option<Record<'a>> {
        while self.position < self.text.len() {
            let rest = &self.text[self.position..];
            let end = rest.find('\n').unwrap_or(rest.len());
            self.position += (end + 1).min(rest.len());
            self.line_number += 1;
            let line = &rest[..end];
            let data = line.find('#').map_or(line, |hash| &line[..hash]);
            // Most lines start with a number: look at the first word before splitting them all.
            let first = data.bytes().find(|b| !b.is_ascii_whitespace());
            let holds_a_number = match first {
                None => false,
                Some(b'0'..=b'9' | b'.' | b'+' | b'-') => true,
                Some(_) => data.split_ascii_whitespace().any(starts_like_a_number),
            };
            if holds_a_number {
                return Some(Record {
                    file: self.file,
                    line: self.line_number,
                    rest: data,
                });
            }
        }
        None
    }

    /// The next record, which must exist: `what` names what was expected.
    fn expect_record(&mut self, what: fmt::Arguments<'_>) -> Result<Record<'a>, FileError> {
        self.next_record().ok_or_else(|| {
            self.error(
                Some(self.line_number.max(1)),
                format!("unexpected end of file: expected {what}"),
            )
        })
    }
}

/// Reads the longest prefix of `word` that C's `strtol(word, NULL, 0)` converts.
fn parse_c_integer(word: &str) -> Option<Result<i64, ()>> {
    let bytes = word.as_bytes();
    let (negative, mut i) = match bytes.first() {
        Some(b'-') => (true, 1),
        Some(b'+') => (false, 1),
        _ => (false, 0),
    };
    let radix = if bytes.get(i) == Some(&b'0')
        && matches!(bytes.get(i + 1), Some(b'x' | b'X'))
        && bytes.get(i + 2).is_some_and(|b| b.is_ascii_hexdigit())
    {
        i += 2;
        16
    } else if bytes.get(i) == Some(&b'0') {
        8
    } else {
        10
    };
    let start = i;
    while i < bytes.len() && (bytes[i] as char).is_digit(radix) {
        i += 1;
    }
    if i == start {
        return None;
    }
    let magnitude = match i64::from_str_radix(&word[start..i], radix) {
        Ok(m) => m,
        Err(_) => return Some(Err(())),
    };
    Some(Ok(if negative { -magnitude } else { magnitude }))
}

/// Reads the longest prefix of `word` that C's `strtod` converts as a decimal number.
fn parse_c_real(word: &str) -> Option<f64> {
    let bytes = word.as_bytes();
    let mut i = 0;
    if matches!(bytes.first(), Some(b'-' | b'+')) {
        i = 1;
    }
    let mut mantissa_digits = 0;
    while i < bytes.len() && bytes[i].is_ascii_digit() {
        i += 1;
        mantissa_digits += 1;
    }
    if i < bytes.len() && bytes[i] == b'.' {
        i += 1;
        while i < bytes.len() && bytes[i].is_ascii_digit() {
            i += 1;
            mantissa_digits += 1;
        }
    }
    if mantissa_digits == 0 {
        return None;
    }
    let mantissa_end = i;
    if i < bytes.len() && matches!(bytes[i], b'e' | b'E') {
        let mut j = i + 1;
        if j < bytes.len() && matches!(bytes[j], b'-' | b'+') {
            j += 1;
        }
        let digits_start = j;
        while j < bytes.len() && bytes[j].is_ascii_digit() {
            j += 1;
        }
        if j > digits_start {
            i = j;
        }
    }
    let text = &word[..i];
    // Rust's parser accepts every form above ("1.", ".5", "+2e3"); only "1.e5"-like forms need
    // the point completed.
    text.parse::<f64>().ok().or_else(|| {
        let mut fixed = word[..mantissa_end].to_string();
        fixed.push('0');
        fixed.push_str(&word[mantissa_end..i]);
        fixed.parse::<f64>().ok()
    })
}

impl<'a> Record<'a> {
    fn error(&self, message: String) -> FileError {
        FileError {
            file: self.file.to_string(),
            line: Some(self.line),
            message,
        }
    }

    /// The next word that starts like a number.
    fn next_word(&mut self) -> Option<&'a str> {
        // Byte by byte: ASCII whitespace never occurs inside a multi-byte UTF-8 character, so
        // the slices below fall on character boundaries.
        loop {
            let bytes = self.rest.as_bytes();
            let start = bytes
                .iter()
                .position(|b| !b.is_ascii_whitespace())
                .unwrap_or(bytes.len());
            if start == bytes.len() {
                self.rest = "";
                return None;
            }
            let end = bytes[start..]
                .iter()
                .position(|b| b.is_ascii_whitespace())
                .map_or(bytes.len(), |n| start + n);
            let word = &self.rest[start..end];
            self.rest = &self.rest[end..];
            if starts_like_a_number(word) {
                return Some(word);
            }
        }
    }

    /// The next integer field, `None` if the line has no more fields.
    fn optional_integer(&mut self, what: fmt::Arguments<'_>) -> Result<Option<i64>, FileError> {
        let Some(word) = self.next_word() else {
            return Ok(None);
        };
        match parse_c_integer(word) {
            Some(Ok(value)) => Ok(Some(value)),
            Some(Err(())) => Err(self.error(format!("{what} `{word}` is out of range"))),
            None => Err(self.error(format!("{what} `{word}` is not a number"))),
        }
    }

    fn integer(&mut self, what: fmt::Arguments<'_>) -> Result<i64, FileError> {
        self.optional_integer(what)?
            .ok_or_else(|| self.error(format!("{what} is missing")))
    }

    /// The next integer field as an `i32` (an index or a marker).
    fn optional_int32(&mut self, what: fmt::Arguments<'_>) -> Result<Option<i32>, FileError> {
        match self.optional_integer(what)? {
            None => Ok(None),
            Some(value) => i32::try_from(value)
                .map(Some)
                .map_err(|_| self.error(format!("{what} {value} is out of range"))),
        }
    }

    fn int32(&mut self, what: fmt::Arguments<'_>) -> Result<i32, FileError> {
        self.optional_int32(what)?
            .ok_or_else(|| self.error(format!("{what} is missing")))
    }

    /// A count: an integer from 0 to `i32::MAX` (the C interface's limit).
    fn optional_count(&mut self, what: fmt::Arguments<'_>) -> Result<Option<usize>, FileError> {
        match self.optional_integer(what)? {
            None => Ok(None),
            Some(value) if (0..=i32::MAX as i64).contains(&value) => Ok(Some(value as usize)),
            Some(value) => Err(self.error(format!("{what} {value} is negative or too large"))),
        }
    }

    fn count(&mut self, what: fmt::Arguments<'_>) -> Result<usize, FileError> {
        self.optional_count(what)?
            .ok_or_else(|| self.error(format!("{what} is missing")))
    }

    /// The next real field, `None` if the line has no more fields; it must be finite.
    fn optional_real(&mut self, what: fmt::Arguments<'_>) -> Result<Option<f64>, FileError> {
        let Some(word) = self.next_word() else {
            return Ok(None);
        };
        match parse_c_real(word) {
            Some(value) if value.is_finite() => Ok(Some(value)),
            Some(_) => Err(self.error(format!("{what} `{word}` is not a finite number"))),
            None => Err(self.error(format!("{what} `{word}` is not a number"))),
        }
    }

    fn real(&mut self, what: fmt::Arguments<'_>) -> Result<f64, FileError> {
        self.optional_real(what)?
            .ok_or_else(|| self.error(format!("{what} is missing")))
    }
}

/// Capacity to reserve for `count` items announced by a header: bounded, so that a corrupt header
/// cannot make the reader allocate gigabytes before it finds out the file is short. Both the
/// count and the width (corners, attributes per item) come from the header: bound the product.
fn reserve(count: usize, width: usize) -> usize {
    count.saturating_mul(width).min(1 << 21)
}

// ------------------------------------------------------------------------------------------------
// Readers

/// Reads the vertex header (already taken from `lines` as `header`) and the vertices.
fn read_vertices(lines: &mut Lines<'_>, mut header: Record<'_>) -> Result<NodeFile, FileError> {
    let count = header.count(format_args!("the number of vertices"))?;
    let dimension = header
        .optional_integer(format_args!("the dimension"))?
        .unwrap_or(2);
    if dimension != 2 {
        return Err(header.error(format!(
            "the dimension is {dimension}, but triangle-rs only works with two-dimensional meshes"
        )));
    }
    let attribute_count = header
        .optional_count(format_args!("the number of vertex attributes"))?
        .unwrap_or(0);
    let has_markers = header
        .optional_count(format_args!("the number of boundary markers"))?
        .unwrap_or(0)
        != 0;
    let mut node = NodeFile {
        first_number: None,
        points: Vec::with_capacity(reserve(count, 2)),
        attribute_count,
        attributes: Vec::with_capacity(reserve(count, attribute_count)),
        markers: has_markers.then(|| Vec::with_capacity(reserve(count, 1))),
    };
    for k in 0..count {
        let mut record = lines.expect_record(format_args!("vertex {} of {count}", k + 1))?;
        let number = record.integer(format_args!("the vertex number"))?;
        if k == 0 {
            node.first_number = Some(number);
        }
        let x = record.real(format_args!("the x coordinate of vertex {number}"))?;
        let y = record.real(format_args!("the y coordinate of vertex {number}"))?;
        node.points.extend_from_slice(&[x, y]);
        for a in 0..attribute_count {
            let value =
                record.optional_real(format_args!("attribute {} of vertex {number}", a + 1))?;
            node.attributes.push(value.unwrap_or(0.0));
        }
        if let Some(markers) = node.markers.as_mut() {
            markers.push(
                record
                    .optional_int32(format_args!("the marker of vertex {number}"))?
                    .unwrap_or(0),
            );
        }
    }
    Ok(node)
}

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn c_number_prefixes() {
        assert_eq!(parse_c_integer("12"), Some(Ok(12)));
        assert_eq!(parse_c_integer("-3"), Some(Ok(-3)));
        assert_eq!(parse_c_integer("0x10"), Some(Ok(16)));
        assert_eq!(parse_c_integer("010"), Some(Ok(8)));
        assert_eq!(parse_c_integer("3.0"), Some(Ok(3)));
        assert_eq!(parse_c_integer("0"), Some(Ok(0)));
        assert_eq!(parse_c_integer("-"), None);
        assert_eq!(parse_c_integer("99999999999999999999"), Some(Err(())));
        assert_eq!(parse_c_real("0.418893E+02"), Some(41.8893));
        assert_eq!(parse_c_real("1."), Some(1.0));
        assert_eq!(parse_c_real("1.e2"), Some(100.0));
        assert_eq!(parse_c_real(".5"), Some(0.5));
        assert_eq!(parse_c_real("-2e-3x"), Some(-0.002));
        assert_eq!(parse_c_real("+7"), Some(7.0));
        assert_eq!(parse_c_real("3e"), Some(3.0));
        assert_eq!(parse_c_real("."), None);
        assert_eq!(parse_c_real("-"), None);
    }

    #[test]
    fn node_with_comments_blank_lines_and_defaults() {
        let text = "# a comment\n\n  4 2 1 1 # header\r\n\
                    1 0 0 10 5\n\
                    2\t1.5e0 0   # no attribute, no marker\n\
                    # between\n\
                    3 1 1 30 0 extra words\n\
                    4 0 1.0E+00 40 -2\n";
        let node = read_node(text, "x.node").unwrap();
        assert_eq!(node.first_number, Some(1));
        assert_eq!(node.points, vec![0.0, 0.0, 1.5, 0.0, 1.0, 1.0, 0.0, 1.0]);
        assert_eq!(node.attributes, vec![10.0, 0.0, 30.0, 40.0]);
        assert_eq!(node.markers, Some(vec![5, 0, 0, -2]));
    }

    #[test]
    fn node_header_defaults_and_zero_base() {
        let node = read_node("3\n0 0 0\n1 1 0\n2 0 1\n", "z.node").unwrap();
        assert_eq!(node.first_number, Some(0));
        assert_eq!(node.attribute_count, 0);
        assert_eq!(node.markers, None);
        assert_eq!(node.point_count(), 3);
    }

    #[test]
    fn node_errors_name_file_and_line() {
        let e = read_node("3 2 0 0\n1 0 0\n2 1\n3 0 1\n", "bad.node").unwrap_err();
        assert_eq!(e.line, Some(3));
        assert!(e.message.contains("y coordinate of vertex 2"), "{e}");
        assert!(e.to_string().starts_with("bad.node, line 3: "), "{e}");

        let e = read_node("4 2 0 0\n1 0 0\n2 1 0\n3 0 1\n", "short.node").unwrap_err();
        assert!(e.message.contains("unexpected end of file"), "{e}");

        let e = read_node("3 3 0 0\n", "dim.node").unwrap_err();
        assert!(e.message.contains("two-dimensional"), "{e}");
        assert_eq!(e.line, Some(1));

        let e = read_node("-3 2 0 0\n", "neg.node").unwrap_err();
        assert!(e.message.contains("negative"), "{e}");

        let e = read_node("3 2 0 0\n1 0 0\n2 - 1\n3 0 1\n", "dash.node").unwrap_err();
        assert!(
            e.message.contains("not a number") && e.line == Some(3),
            "{e}"
        );

        let e = read_node("3 2 0 0\n1 0 0\n2 1e999 1\n3 0 1\n", "inf.node").unwrap_err();
        assert!(e.message.contains("not a finite number"), "{e}");

        let e = read_node("", "empty.node").unwrap_err();
        assert!(e.message.contains("unexpected end of file"), "{e}");
    }

    #[test]
    fn ele_and_index_checks() {
        let text = "2 3 1\n1 1 2 3 0.5\n2 3 4 1\n";
        let ele = read_ele(text, "x.ele").unwrap();
        assert_eq!(ele.corners, 3);
        assert_eq!(ele.triangles, vec![1, 2, 3, 3, 4, 1]);
        assert_eq!(ele.attributes, vec![0.5, 0.0]);
        assert_eq!(ele.lines, vec![2, 3]);
        assert!(
            check_vertex_indices("x.ele", "triangle", &ele.triangles, 3, &ele.lines, 1, 4).is_ok()
        );
        let e = check_vertex_indices("x.ele", "triangle", &ele.triangles, 3, &ele.lines, 1, 3)
            .unwrap_err();
        assert_eq!(e.line, Some(3));
        assert!(e.message.contains("triangle 2 refers to vertex 4"), "{e}");
        let e = check_vertex_indices("x.ele", "triangle", &ele.triangles, 3, &ele.lines, 0, 4)
            .unwrap_err();
        assert!(e.message.contains("vertex 4"), "{e}");

        let e = read_ele("1 3 0\n1 1 2\n", "m.ele").unwrap_err();
        assert!(e.message.contains("node 3 of triangle 1 is missing"), "{e}");
        let e = read_ele("1 2 0\n1 1 2\n", "c.ele").unwrap_err();
        assert!(e.message.contains("at least 3"), "{e}");

        let six = read_ele("1 6\n0 0 1 2 3 4 5\n", "six.ele").unwrap();
        assert_eq!(six.triangle_count(), 1);
        assert_eq!(six.first_number, Some(0));
    }

    #[test]
    fn poly_sections() {
        let text = "\
# square with a hole and two regions
4 2 0 1
1 0 0 1
2 2 0 1
3 2 2 1
4 0 2 1
4 1
1 1 2 5
2 2 3 5
3 3 4
4 4 1 6
1
1 1.0 1.0
2
1 0.5 0.5 7 0.25
2 1.5 1.5 9
";
        let poly = read_poly(text, "sq.poly", true).unwrap();
        assert_eq!(poly.vertices.point_count(), 4);
        assert_eq!(poly.segments, vec![1, 2, 2, 3, 3, 4, 4, 1]);
        assert_eq!(poly.segment_markers, Some(vec![5, 5, 0, 6]));
        assert_eq!(poly.segment_lines, vec![8, 9, 10, 11]);
        assert_eq!(poly.holes, vec![1.0, 1.0]);
        assert_eq!(poly.regions, vec![0.5, 0.5, 7.0, 0.25, 1.5, 1.5, 9.0, 9.0]);

        let without_regions = read_poly(text, "sq.poly", false).unwrap();
        assert!(without_regions.regions.is_empty());

        // No vertices (they come from the .node file), no region section even when asked for.
        let empty = read_poly("0 2 0 1\n1 0\n1 1 2\n0\n", "e.poly", true).unwrap();
        assert_eq!(empty.vertices.point_count(), 0);
        assert_eq!(empty.vertices.first_number, None);
        assert_eq!(empty.segments, vec![1, 2]);
        assert_eq!(empty.segment_markers, None);

        let e = read_poly("0 2 0 0\n1 0\n1 1\n0\n", "s.poly", false).unwrap_err();
        assert!(
            e.message
                .contains("second endpoint of segment 1 is missing"),
            "{e}"
        );
        let e = read_poly("0 2 0 0\n1 0\n1 1 2\n", "h.poly", false).unwrap_err();
        assert!(
            e.message.contains("unexpected end of file") && e.message.contains("hole"),
            "{e}"
        );
        let e = read_poly("0 2 0 0\n0 0\n0\n1\n1 0.5 0.5\n", "r.poly", true).unwrap_err();
        assert!(
            e.message
                .contains("attribute (or area constraint) of region 1"),
            "{e}"
        );
    }

    #[test]
    fn output_formats_read_back() {
        let area = read_area("2\n1 0.5\n2 -1\n", "a.area").unwrap();
        assert_eq!(area.areas, vec![0.5, -1.0]);
        let edge = read_edge("2  1\n   1   4  1  1\n   2   1  5  0\n", "x.edge").unwrap();
        assert_eq!(edge.edges, vec![4, 1, 1, 5]);
        assert_eq!(edge.markers, Some(vec![1, 0]));
        let v = read_voronoi_edge("2  0\n   1   1  -1   -1  0\n   2   1  3\n", "x.v.edge").unwrap();
        assert_eq!(v.edges, vec![1, -1, 1, 3]);
        assert_eq!(v.norms, vec![-1.0, 0.0, 0.0, 0.0]);
        let n = read_neigh("1  3\n   1    -1  2  -1\n", "x.neigh").unwrap();
        assert_eq!(n.neighbors, vec![-1, 2, -1]);
        let off = read_off(
            "OFF\n3  1  3\n 0  0  0\n 1  0  0\n 0  1  0\n 3      0     1     2\n",
            "x.off",
        )
        .unwrap();
        assert_eq!(off.points.len(), 9);
        assert_eq!(off.triangles, vec![0, 1, 2]);
        assert_eq!(off.edge_count, 3);
    }
}
