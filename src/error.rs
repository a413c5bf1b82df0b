//! Typed errors of the engine and of the input checks. The C edge turns them into a non-zero
//! return code and a message kept for `triangulate_last_error`.

use std::fmt;

#[derive(Clone, Debug, PartialEq)]
pub enum Error {
    /// A required pointer (`in`, `out`, `vorout` with `v`, or the switch string) is NULL.
    NullArgument(&'static str),
    /// A count field is negative or an array's size overflows.
    BadCount { field: &'static str, value: i64 },
    /// An array is NULL although its count says it has items.
    MissingArray(&'static str),
    /// Fewer than three input vertices.
    TooFewPoints,
    /// `a` with a number ≤ 0.
    NonPositiveMaxArea,
    /// `q` with a number that overflows (`q1e999`).
    NonFiniteMinAngle,
    /// A coordinate or attribute is NaN or infinite.
    NonFinite { what: &'static str, index: usize },
    /// A switch that this version does not implement.
    Unsupported(&'static str),
    /// `r`: `numberofcorners` is neither 3 nor 6.
    BadCorners(i64),
    /// A segment endpoint or a triangle corner is not a vertex number. `item` is numbered as the
    /// caller numbers it; `first..=last` is the valid range.
    IndexOutOfRange {
        item: &'static str,
        number: i64,
        role: &'static str,
        value: i64,
        first: i64,
        last: i64,
    },
    /// A region's maximum area is NaN (`item` in the caller's numbering).
    NanRegionArea { region: i64 },
    /// The coordinates span more binary orders of magnitude than exact arithmetic allows, even
    /// after scaling by a power of two (see `crate::scaling`).
    CoordinateRange(String),
    /// `r`: the given triangles do not form a valid mesh.
    InvalidMesh(String),
    /// The switch string is not valid UTF-8 / ASCII.
    BadSwitches,
    /// `malloc` returned NULL.
    OutOfMemory,
    /// Refinement was cancelled by the caller.
    Cancelled,
    /// A bug: an invariant of the engine failed (caught panic or failed check).
    Internal(String),
}

impl Error {
    /// The internal error for a caught panic, with the panic's message.
    pub fn from_panic(payload: Box<dyn std::any::Any + Send>) -> Error {
        let why = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "panic".into());
        Error::Internal(why)
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NullArgument(name) => write!(f, "The argument `{name}` is NULL."),
            Error::BadCount { field, value } => write!(f, "Invalid count {field} = {value}."),
            Error::MissingArray(name) => {
                write!(f, "The array `{name}` is NULL but its count is not zero.")
            }
            Error::TooFewPoints => write!(f, "Input must have at least three input vertices."),
            Error::NonPositiveMaxArea => write!(f, "Maximum area must be greater than zero."),
            Error::NonFiniteMinAngle => write!(f, "Minimum angle (q) must be a finite number."),
            Error::NonFinite { what, index } => {
                write!(f, "{what} {index} has a coordinate or value that is not finite (NaN or infinity).")
            }
            Error::Unsupported(what) => write!(f, "{what} is not supported yet by triangle-rs."),
            Error::BadCorners(n) => {
                write!(
                    f,
                    "Triangles must have 3 or 6 vertices (numberofcorners = {n})."
                )
            }
            Error::IndexOutOfRange {
                item,
                number,
                role,
                value,
                first,
                last,
            } => write!(
                f,
                "{item} {number} has {role} {value}, which is not a vertex: vertices are numbered {first} to {last}."
            ),
            Error::NanRegionArea { region } => {
                write!(f, "Region {region} has a maximum area that is NaN.")
            }
            Error::CoordinateRange(why) => write!(f, "{why}"),
            Error::InvalidMesh(why) => write!(f, "The input mesh is not valid: {why}"),
            Error::BadSwitches => write!(f, "The switch string is not valid ASCII text."),
            Error::OutOfMemory => write!(f, "Out of memory."),
            Error::Cancelled => write!(f, "Triangulation cancelled by the caller."),
            Error::Internal(why) => write!(
                f,
                "Internal error in triangle-rs: {why}. Please report this bug."
            ),
        }
    }
}

impl std::error::Error for Error {}
