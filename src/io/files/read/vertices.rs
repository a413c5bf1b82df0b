//! The vertex section of `.node` and `.poly` files, the bulk of a large input. Most of its lines
//! are plain: a vertex number, the coordinates, the attributes and the marker as plain decimal
//! numbers separated by blanks. Those are read by a byte scanner ([`plain_row`]) that gives the
//! values the general reader gives (each real is parsed by the same `str::parse::<f64>` on the
//! same characters); every other line (comments, other number forms, missing or extra fields,
//! errors) goes through the general reader of [`super::records`]. A large section is read on two
//! threads, split at a line boundary.

use super::records::{reserve, Lines, Record};
use super::{FileError, NodeFile};

/// From this many vertices on the section is read on two threads (when there are two cores).
const PARALLEL_VERTICES: usize = 100_000;

/// The columns of a vertex row.
#[derive(Clone, Copy)]
struct Columns {
    attribute_count: usize,
    has_markers: bool,
}

/// Reads the vertex header (already taken from `lines` as `header`) and the vertices.
pub(super) fn read_vertices(
    lines: &mut Lines<'_>,
    mut header: Record<'_>,
) -> Result<NodeFile, FileError> {
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
    let columns = Columns {
        attribute_count,
        has_markers,
    };
    let mut node = NodeFile {
        first_number: None,
        points: Vec::with_capacity(reserve(count, 2)),
        attribute_count,
        attributes: Vec::with_capacity(reserve(count, attribute_count)),
        markers: has_markers.then(|| Vec::with_capacity(reserve(count, 1))),
    };
    let two_cores = crate::threads::two_cores();
    if count >= PARALLEL_VERTICES && two_cores {
        read_rows_on_two_threads(lines, columns, count, &mut node)?;
    } else {
        read_rows(lines, columns, count, &mut node)?;
    }
    Ok(node)
}

/// Reads vertex rows from `lines` until `node` has `count` of them; an error at the end of the
/// text.
fn read_rows(
    lines: &mut Lines<'_>,
    columns: Columns,
    count: usize,
    node: &mut NodeFile,
) -> Result<(), FileError> {
    while node.point_count() < count {
        if !read_row(lines, columns, node)? {
            let k = node.point_count() + 1;
            return Err(lines.error(
                Some(lines.line_number().max(1)),
                format!("unexpected end of file: expected vertex {k} of {count}"),
            ));
        }
    }
    Ok(())
}

/// Reads the next vertex row into `node`: by the fast path if its line is plain, else by the
/// general reader. False at the end of the text.
fn read_row(
    lines: &mut Lines<'_>,
    columns: Columns,
    node: &mut NodeFile,
) -> Result<bool, FileError> {
    let k = node.point_count();
    if let Some(end) = plain_row(lines.text(), lines.position(), columns, node) {
        lines.skip_read_lines(end, 1);
        return Ok(true);
    }
    let Some(mut record) = lines.next_record() else {
        return Ok(false);
    };
    let number = record.integer(format_args!("the vertex number"))?;
    if k == 0 {
        node.first_number = Some(number);
    }
    let x = record.real(format_args!("the x coordinate of vertex {number}"))?;
    let y = record.real(format_args!("the y coordinate of vertex {number}"))?;
    node.points.extend_from_slice(&[x, y]);
    for a in 0..columns.attribute_count {
        let value = record.optional_real(format_args!("attribute {} of vertex {number}", a + 1))?;
        node.attributes.push(value.unwrap_or(0.0));
    }
    if let Some(markers) = node.markers.as_mut() {
        markers.push(
            record
                .optional_int32(format_args!("the marker of vertex {number}"))?
                .unwrap_or(0),
        );
    }
    Ok(true)
}

/// Reads the rows on two threads: this one reads the lines before a split point near the middle
/// of the section (fast path and general reader, errors and all), the other the plain lines from
/// the split point on, until it meets a line that is not plain. The rows of the second part
/// follow those of the first; whatever the second thread did not read is read after it, here.
fn read_rows_on_two_threads(
    lines: &mut Lines<'_>,
    columns: Columns,
    count: usize,
    node: &mut NodeFile,
) -> Result<(), FileError> {
    let split = split_point(lines, count);
    let text = lines.text();
    let (first, second) = std::thread::scope(|scope| {
        let second_part = scope.spawn(move || plain_rows_from(text, split, columns, count));
        let mut first_part = lines.ending_at(split);
        let mut first = Ok(());
        while node.point_count() < count {
            match read_row(&mut first_part, columns, node) {
                Ok(true) => {}
                Ok(false) => break,
                Err(e) => {
                    first = Err(e);
                    break;
                }
            }
        }
        // Go on from where the first part stopped (the split point, unless it read all rows).
        let read_lines = first_part.line_number() - lines.line_number();
        lines.skip_read_lines(first_part.position(), read_lines);
        let second = second_part
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (first, second)
    });
    first?;
    let wanted = count - node.point_count();
    if wanted > 0 && lines.position() == split {
        let taken = second.rows.min(wanted);
        if node.first_number.is_none() && taken > 0 {
            node.first_number = second.node.first_number;
        }
        node.points
            .extend_from_slice(&second.node.points[..2 * taken]);
        let width = columns.attribute_count;
        node.attributes
            .extend_from_slice(&second.node.attributes[..width * taken]);
        if let (Some(markers), Some(theirs)) = (node.markers.as_mut(), &second.node.markers) {
            markers.extend_from_slice(&theirs[..taken]);
        }
        let end = if taken == second.rows {
            second.end
        } else {
            // The section ended inside the second part (rare: a `.poly` file's segments were
            // taken for vertices there): find the end of its last vertex line.
            (0..taken).fold(split, |at, _| next_line(text.as_bytes(), at))
        };
        lines.skip_read_lines(end, taken);
    }
    read_rows(lines, columns, count, node)
}

/// A byte offset where a line starts, about halfway through the vertex section: its length is
/// estimated from the first rows' (a `.poly` file goes on with segments).
fn split_point(lines: &Lines<'_>, count: usize) -> usize {
    let text = lines.text().as_bytes();
    let start = lines.position();
    let mut sample_end = start;
    let mut sampled = 0;
    while sampled < 64 && sample_end < text.len() {
        sample_end = next_line(text, sample_end);
        sampled += 1;
    }
    let estimate = (sample_end - start) / sampled.max(1) * count;
    let middle = start + estimate.min(text.len() - start) / 2;
    next_line(text, middle)
}

/// The start of the line after the one holding byte `at` (the end of the text if none).
fn next_line(text: &[u8], at: usize) -> usize {
    text[at.min(text.len())..]
        .iter()
        .position(|&b| b == b'\n')
        .map_or(text.len(), |n| at + n + 1)
}

/// The plain rows of a part of the section.
struct PlainRows {
    node: NodeFile,
    rows: usize,
    /// Where the first line not read starts.
    end: usize,
}

/// Reads at most `count` plain rows from byte `start` on, stopping at the first line that is not
/// plain.
fn plain_rows_from(text: &str, start: usize, columns: Columns, count: usize) -> PlainRows {
    let bytes = text.as_bytes();
    let expected = (bytes.len() - start) / 16;
    let mut rows = PlainRows {
        node: NodeFile {
            points: Vec::with_capacity(reserve(expected.min(count), 2)),
            attributes: Vec::with_capacity(reserve(expected.min(count), columns.attribute_count)),
            markers: columns
                .has_markers
                .then(|| Vec::with_capacity(reserve(expected.min(count), 1))),
            ..NodeFile::default()
        },
        rows: 0,
        end: start,
    };
    while rows.rows < count {
        let Some(end) = plain_row(text, rows.end, columns, &mut rows.node) else {
            break;
        };
        rows.rows += 1;
        rows.end = end;
    }
    rows
}

/// The most attributes a plain row may have (more go through the general reader).
const PLAIN_ATTRIBUTES: usize = 8;

/// Reads the vertex row on the line that starts at byte `at` if the line is plain: blanks
/// (space, tab, carriage return), then the vertex number, the two coordinates, every attribute
/// and (if the header announces it) the marker, each a plain decimal number followed by a
/// blank or the end of the line, then anything (the general reader ignores the rest of a line
/// once it has its fields). Pushes the row onto `node` and returns where the next line starts;
/// `None` (nothing pushed) if the line is not plain.
fn plain_row(text: &str, at: usize, columns: Columns, node: &mut NodeFile) -> Option<usize> {
    let bytes = text.as_bytes();
    if columns.attribute_count > PLAIN_ATTRIBUTES {
        return None;
    }
    let (number, mut i) = plain_integer(bytes, skip_blanks(bytes, at))?;
    let mut reals = [0.0; 2 + PLAIN_ATTRIBUTES];
    for value in &mut reals[..2 + columns.attribute_count] {
        (*value, i) = plain_real(text, skip_blanks(bytes, i))?;
    }
    let marker = if columns.has_markers {
        let (marker, end) = plain_integer(bytes, skip_blanks(bytes, i))?;
        i = end;
        Some(i32::try_from(marker).ok()?)
    } else {
        None
    };
    i = skip_blanks(bytes, i);
    let end = match bytes.get(i) {
        None => i,
        Some(b'\n') => i + 1,
        Some(_) => next_line(bytes, i),
    };
    if node.points.is_empty() {
        node.first_number = Some(number);
    }
    node.points.extend_from_slice(&reals[..2]);
    node.attributes
        .extend_from_slice(&reals[2..2 + columns.attribute_count]);
    if let (Some(markers), Some(marker)) = (node.markers.as_mut(), marker) {
        markers.push(marker);
    }
    Some(end)
}

fn skip_blanks(bytes: &[u8], mut i: usize) -> usize {
    while i < bytes.len() && matches!(bytes[i], b' ' | b'\t' | b'\r') {
        i += 1;
    }
    i
}

/// Whether a number may end before byte `i`: a blank or a line's end follows it.
fn ends_field(bytes: &[u8], i: usize) -> bool {
    matches!(bytes.get(i), None | Some(b' ' | b'\t' | b'\r' | b'\n'))
}

/// A plain decimal integer at byte `i` (optional sign, no leading zero, at most 18 digits: what
/// `strtol` reads in base 0 as a decimal), and the byte after it.
fn plain_integer(bytes: &[u8], mut i: usize) -> Option<(i64, usize)> {
    let negative = match bytes.get(i) {
        Some(b'-') => {
            i += 1;
            true
        }
        Some(b'+') => {
            i += 1;
            false
        }
        _ => false,
    };
    let start = i;
    let mut value: i64 = 0;
    while let Some(&b) = bytes.get(i) {
        if !b.is_ascii_digit() {
            break;
        }
        value = 10 * value + i64::from(b - b'0');
        i += 1;
    }
    let digits = i - start;
    // A leading zero makes `strtol` read octal (or hex): only a lone 0 is plain.
    let plain = (1..=18).contains(&digits) && (bytes[start] != b'0' || digits == 1);
    (plain && ends_field(bytes, i)).then_some((if negative { -value } else { value }, i))
}

/// A plain decimal real at byte `i` (optional sign, digits with an optional point, at least one
/// digit, an optional exponent with digits), finite, and the byte after it. Parsed by
/// `str::parse::<f64>`, as the general reader parses the same characters.
fn plain_real(text: &str, mut i: usize) -> Option<(f64, usize)> {
    let bytes = text.as_bytes();
    let start = i;
    let digits = |mut i: usize| {
        while bytes.get(i).is_some_and(u8::is_ascii_digit) {
            i += 1;
        }
        i
    };
    if matches!(bytes.get(i), Some(b'-' | b'+')) {
        i += 1;
    }
    let integer_end = digits(i);
    let mut mantissa_digits = integer_end - i;
    i = integer_end;
    if bytes.get(i) == Some(&b'.') {
        let fraction_end = digits(i + 1);
        mantissa_digits += fraction_end - (i + 1);
        i = fraction_end;
    }
    if mantissa_digits == 0 {
        return None;
    }
    if matches!(bytes.get(i), Some(b'e' | b'E')) {
        let mut j = i + 1;
        if matches!(bytes.get(j), Some(b'-' | b'+')) {
            j += 1;
        }
        let exponent_end = digits(j);
        if exponent_end == j {
            return None;
        }
        i = exponent_end;
    }
    if !ends_field(bytes, i) {
        return None;
    }
    let value: f64 = text[start..i].parse().ok()?;
    value.is_finite().then_some((value, i))
}
