//! `struct triangulateio`, field for field, and its conversion to and from the engine's plain data.
//!
//! Reading checks every count and pointer the switches make Triangle read; writing follows
//! Triangle's memory rules: an output array is `malloc`ed only when its pointer is NULL (a
//! non-NULL pointer is the caller's buffer, written into unchecked as Triangle does), and
//! `holelist`/`regionlist` alias the input's arrays.

use std::os::raw::{c_int, c_void};
use std::ptr;

use crate::data::{Input, Output, VoronoiOutput};
use crate::error::Error;
use crate::options::Options;

/// Triangle 1.6's `struct triangulateio` (168 bytes on LP64 and LLP64).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct TriangulateIO {
    pub pointlist: *mut f64,
    pub pointattributelist: *mut f64,
    pub pointmarkerlist: *mut c_int,
    pub numberofpoints: c_int,
    pub numberofpointattributes: c_int,

    pub trianglelist: *mut c_int,
    pub triangleattributelist: *mut f64,
    pub trianglearealist: *mut f64,
    pub neighborlist: *mut c_int,
    pub numberoftriangles: c_int,
    pub numberofcorners: c_int,
    pub numberoftriangleattributes: c_int,

    pub segmentlist: *mut c_int,
    pub segmentmarkerlist: *mut c_int,
    pub numberofsegments: c_int,

    pub holelist: *mut f64,
    pub numberofholes: c_int,

    pub regionlist: *mut f64,
    pub numberofregions: c_int,

    pub edgelist: *mut c_int,
    pub edgemarkerlist: *mut c_int,
    pub normlist: *mut f64,
    pub numberofedges: c_int,
}

impl Default for TriangulateIO {
    fn default() -> Self {
        TriangulateIO {
            pointlist: ptr::null_mut(),
            pointattributelist: ptr::null_mut(),
            pointmarkerlist: ptr::null_mut(),
            numberofpoints: 0,
            numberofpointattributes: 0,
            trianglelist: ptr::null_mut(),
            triangleattributelist: ptr::null_mut(),
            trianglearealist: ptr::null_mut(),
            neighborlist: ptr::null_mut(),
            numberoftriangles: 0,
            numberofcorners: 0,
            numberoftriangleattributes: 0,
            segmentlist: ptr::null_mut(),
            segmentmarkerlist: ptr::null_mut(),
            numberofsegments: 0,
            holelist: ptr::null_mut(),
            numberofholes: 0,
            regionlist: ptr::null_mut(),
            numberofregions: 0,
            edgelist: ptr::null_mut(),
            edgemarkerlist: ptr::null_mut(),
            normlist: ptr::null_mut(),
            numberofedges: 0,
        }
    }
}

fn count(field: &'static str, value: c_int) -> Result<usize, Error> {
    usize::try_from(value).map_err(|_| Error::BadCount {
        field,
        value: value as i64,
    })
}

fn product(field: &'static str, items: usize, width: usize) -> Result<usize, Error> {
    items
        .checked_mul(width)
        .filter(|&n| n <= isize::MAX as usize / 8)
        .ok_or(Error::BadCount {
            field,
            value: items as i64,
        })
}

/// A required array of `len` items: NULL is an error unless `len` is 0.
///
/// # Safety
/// `p` must be NULL or valid for reads of `len` items for `'a`.
unsafe fn required<'a, T>(name: &'static str, p: *const T, len: usize) -> Result<&'a [T], Error> {
    if len == 0 {
        Ok(&[])
    } else if p.is_null() {
        Err(Error::MissingArray(name))
    } else {
        // SAFETY: non-NULL and, by the caller's contract, valid for `len` reads.
        Ok(unsafe { std::slice::from_raw_parts(p, len) })
    }
}

/// An optional array of `len` items: NULL gives `None`.
///
/// # Safety
/// As [`required`].
unsafe fn optional<'a, T>(p: *const T, len: usize) -> Option<&'a [T]> {
    if p.is_null() {
        None
    } else if len == 0 {
        Some(&[])
    } else {
        // SAFETY: non-NULL and, by the caller's contract, valid for `len` reads.
        Some(unsafe { std::slice::from_raw_parts(p, len) })
    }
}

/// Borrows the arrays of `tio` that the switches make the engine read, checking counts and
/// pointers.
///
/// # Safety
/// Every non-NULL array of `tio` that is read must hold as many items as its count says.
pub unsafe fn input_from_raw<'a>(
    tio: &'a TriangulateIO,
    options: &Options,
) -> Result<Input<'a>, Error> {
    let n = count("numberofpoints", tio.numberofpoints)?;
    let nattr = count("numberofpointattributes", tio.numberofpointattributes)?;
    let mut input = Input {
        // SAFETY (all reads below): the caller's contract above.
        points: unsafe { required("pointlist", tio.pointlist, product("numberofpoints", n, 2)?)? },
        point_attributes: unsafe {
            required(
                "pointattributelist",
                tio.pointattributelist,
                product("numberofpointattributes", n, nattr)?,
            )?
        },
        point_attribute_count: nattr,
        point_markers: unsafe { optional(tio.pointmarkerlist, n) },
        ..Input::default()
    };
    if options.refine {
        let ntri = count("numberoftriangles", tio.numberoftriangles)?;
        // 3 or 6: checked by the engine (`pipeline`), for every caller.
        let corners = count("numberofcorners", tio.numberofcorners)?;
        let ntattr = count("numberoftriangleattributes", tio.numberoftriangleattributes)?;
        input.corners = corners;
        input.triangles = unsafe {
            required(
                "trianglelist",
                tio.trianglelist,
                product("numberoftriangles", ntri, corners)?,
            )?
        };
        input.triangle_attribute_count = ntattr;
        input.triangle_attributes = unsafe {
            required(
                "triangleattributelist",
                tio.triangleattributelist,
                product("numberoftriangleattributes", ntri, ntattr)?,
            )?
        };
        if options.variable_area {
            input.triangle_areas =
                Some(unsafe { required("trianglearealist", tio.trianglearealist, ntri)? });
        }
    }
    if options.pslg {
        let nseg = count("numberofsegments", tio.numberofsegments)?;
        input.segments = unsafe {
            required(
                "segmentlist",
                tio.segmentlist,
                product("numberofsegments", nseg, 2)?,
            )?
        };
        input.segment_markers = unsafe { optional(tio.segmentmarkerlist, nseg) };
        // Read with `r` too: refinement carves nothing, but `out` lists them as with `p` alone.
        let nholes = count("numberofholes", tio.numberofholes)?;
        let nregions = count("numberofregions", tio.numberofregions)?;
        input.holes = unsafe {
            required(
                "holelist",
                tio.holelist,
                product("numberofholes", nholes, 2)?,
            )?
        };
        input.regions = unsafe {
            required(
                "regionlist",
                tio.regionlist,
                product("numberofregions", nregions, 4)?,
            )?
        };
    }
    Ok(input)
}

fn to_c_int(field: &'static str, value: usize) -> Result<c_int, Error> {
    c_int::try_from(value).map_err(|_| Error::BadCount {
        field,
        value: value as i64,
    })
}

/// An output array the engine built, owned until it is handed to the caller or copied.
enum Array {
    F64(Vec<f64>),
    I32(Vec<i32>),
}

impl Array {
    fn bytes(&self) -> &[u8] {
        match self {
            Array::F64(v) => as_bytes(v),
            Array::I32(v) => as_bytes(v),
        }
    }

    /// Whether its allocation can become the caller's array: it is malloc's ([`HAND_OVER`])
    /// and holds items (an empty vector may have no allocation, and shrinking one frees it).
    fn can_hand_over(&self) -> bool {
        HAND_OVER
            && match self {
                Array::F64(v) => !v.is_empty(),
                Array::I32(v) => !v.is_empty(),
            }
    }

    /// Gives up the allocation (shrunk to the items; with malloc-based Rust allocations, see
    /// lib.rs) as a pointer for the caller to `free`.
    fn into_raw(self) -> *mut c_void {
        fn leak<T>(mut v: Vec<T>) -> *mut c_void {
            v.shrink_to_fit();
            std::mem::ManuallyDrop::new(v).as_mut_ptr().cast()
        }
        match self {
            Array::F64(v) => leak(v),
            Array::I32(v) => leak(v),
        }
    }
}

/// Whether Rust's allocations are malloc's, so that an output array can be handed over as it
/// is (see lib.rs).
const HAND_OVER: bool = cfg!(all(unix, feature = "malloc-outputs"));

/// One array for the caller: the destination field and the data.
struct Transfer {
    field: *mut *mut c_void,
    data: Array,
}

fn as_bytes<T: Copy>(v: &[T]) -> &[u8] {
    // SAFETY: T is a plain number type (f64 or c_int) with no padding; the byte view covers
    // exactly the slice's memory and lives as long as it.
    unsafe { std::slice::from_raw_parts(v.as_ptr() as *const u8, std::mem::size_of_val(v)) }
}

/// Puts every array into its field: into the caller's buffer when the field is non-NULL, else
/// the array itself when it can be handed over, else a new `malloc`ed copy. If an allocation
/// fails, everything allocated here is freed again and the fields are left as they were.
///
/// # Safety
/// Each non-NULL destination field must point to a buffer large enough for its data, and each
/// `field` pointer must be valid for reads and writes.
unsafe fn transfer_all(mut transfers: Vec<Transfer>) -> Result<(), Error> {
    // The copies first, those handed over after, in the one array (a small call allocates
    // nothing more here).
    let hand_over = |t: &Transfer| {
        // SAFETY: `field` points into a live TriangulateIO (caller's contract).
        let null = unsafe { (*t.field).is_null() };
        null && t.data.can_hand_over()
    };
    transfers.sort_unstable_by_key(hand_over);
    let first_handed = transfers
        .iter()
        .position(hand_over)
        .unwrap_or(transfers.len());
    let copies = &transfers[..first_handed];
    let mut fresh: Vec<(*mut *mut c_void, *mut c_void)> = Vec::with_capacity(copies.len());
    for t in copies {
        // SAFETY: `field` points into a live TriangulateIO (caller's contract).
        if unsafe { (*t.field).is_null() } {
            // malloc(0) may return NULL; ask for at least one byte so that a written array is
            // always a non-NULL pointer the caller can free().
            // SAFETY: plain libc allocation.
            let p = unsafe { libc::malloc(t.data.bytes().len().max(1)) };
            if p.is_null() {
                for (field, p) in fresh {
                    // SAFETY: `p` was allocated above and not yet handed out; `field` is live.
                    unsafe {
                        libc::free(p);
                        *field = ptr::null_mut();
                    }
                }
                return Err(Error::OutOfMemory);
            }
            crate::memory::prefer_huge_pages(p as *const u8, t.data.bytes().len());
            // SAFETY: the field is live; we own `p` until the caller takes it.
            unsafe { *t.field = p };
            fresh.push((t.field, p));
        }
    }
    let total: usize = copies.iter().map(|t| t.data.bytes().len()).sum();
    let two_cores = crate::threads::two_cores();
    // Each destination: where its bytes go (an address, so that the halves can cross threads).
    let destinations: Vec<(usize, &[u8])> = copies
        .iter()
        .map(|t| {
            // SAFETY: each field is live (caller's contract) and now non-NULL.
            let destination = unsafe { *t.field } as usize;
            (destination, t.data.bytes())
        })
        .collect();
    if two_cores && total >= PARALLEL_COPY_BYTES {
        // Large copies (into the caller's buffers, or all outputs without `malloc-outputs`: a
        // million points are some 44 MB, mostly fresh pages that the kernel faults in one by
        // one) go in two halves, the second on another thread.
        std::thread::scope(|scope| {
            let spawned =
                std::thread::Builder::new().spawn_scoped(scope, || copy_parts(&destinations, 1));
            copy_parts(&destinations, 0);
            if spawned.is_err() {
                copy_parts(&destinations, 1); // no second thread to be had: this one copies it
            }
        });
    } else {
        copy_parts(&destinations, 0);
        copy_parts(&destinations, 1);
    }
    for t in transfers.drain(first_handed..) {
        // SAFETY: the field is live and NULL; the array's allocation is malloc's (HAND_OVER),
        // and from here the caller owns it.
        unsafe { *t.field = t.data.into_raw() };
    }
    Ok(())
}

/// Outputs larger than this in all are copied on two threads.
const PARALLEL_COPY_BYTES: usize = 4 << 20;

/// Copies half `half` (0: the first, 1: the second) of each array to its destination.
fn copy_parts(copies: &[(usize, &[u8])], half: usize) {
    for &(destination, bytes) in copies {
        let middle = bytes.len() / 2;
        let range = if half == 0 {
            0..middle
        } else {
            middle..bytes.len()
        };
        // SAFETY: the destination is either our new allocation of `bytes.len()` bytes or the
        // caller's buffer, which the caller promises is large enough; the source is a Rust slice
        // that overlaps neither; the two halves are disjoint, so two threads never write the
        // same byte.
        unsafe {
            ptr::copy_nonoverlapping(
                bytes[range.clone()].as_ptr(),
                (destination as *mut u8).add(range.start),
                range.len(),
            )
        };
    }
}

macro_rules! field_ptr {
    ($tio:expr, $field:ident) => {
        (&mut $tio.$field) as *mut _ as *mut *mut c_void
    };
}

/// Writes the engine's output into `out` (and `vorout` when given), following Triangle's rules.
///
/// # Safety
/// `out` and `vorout` must be valid; their non-NULL array fields must be large enough for what
/// is written into them; `input` is the struct the input was read from (its hole and region
/// pointers are aliased into `out`).
pub unsafe fn write_output(
    input: &TriangulateIO,
    mut output: Output,
    out: &mut TriangulateIO,
    voronoi: Option<(VoronoiOutput, &mut TriangulateIO)>,
) -> Result<(), Error> {
    // Room for every array of both structs: no regrowth.
    let mut transfers: Vec<Transfer> = Vec::with_capacity(24);
    macro_rules! push {
        ($tio:expr, $field:ident, $kind:ident, $data:expr) => {
            if let Some(d) = $data {
                transfers.push(Transfer {
                    field: field_ptr!($tio, $field),
                    data: Array::$kind(d),
                });
            }
        };
    }
    push!(out, pointlist, F64, output.points.take());
    push!(out, pointattributelist, F64, output.point_attributes.take());
    push!(out, pointmarkerlist, I32, output.point_markers.take());
    push!(out, trianglelist, I32, output.triangles.take());
    push!(
        out,
        triangleattributelist,
        F64,
        output.triangle_attributes.take()
    );
    push!(out, neighborlist, I32, output.neighbors.take());
    push!(out, segmentlist, I32, output.segments.take());
    push!(out, segmentmarkerlist, I32, output.segment_markers.take());
    push!(out, edgelist, I32, output.edges.take());
    push!(out, edgemarkerlist, I32, output.edge_markers.take());

    let counts = (
        to_c_int("numberofpoints", output.point_count)?,
        to_c_int("numberofpointattributes", output.point_attribute_count)?,
        to_c_int("numberoftriangles", output.triangle_count)?,
        to_c_int("numberofcorners", output.corners)?,
        to_c_int(
            "numberoftriangleattributes",
            output.triangle_attribute_count,
        )?,
        to_c_int("numberofsegments", output.segment_count)?,
        to_c_int("numberofholes", output.hole_count)?,
        to_c_int("numberofregions", output.region_count)?,
        to_c_int("numberofedges", output.edge_count)?,
    );

    let mut vorout_fields = None;
    if let Some((vor, vorout)) = voronoi {
        let vor_counts = (
            to_c_int("numberofpoints", vor.point_count)?,
            to_c_int("numberofpointattributes", vor.point_attribute_count)?,
            to_c_int("numberofedges", vor.edge_count)?,
        );
        let written = vor.diagram.is_some();
        if let Some(d) = vor.diagram {
            push!(vorout, pointlist, F64, Some(d.points));
            push!(vorout, pointattributelist, F64, Some(d.point_attributes));
            push!(vorout, edgelist, I32, Some(d.edges));
            push!(vorout, normlist, F64, Some(d.norms));
        }
        vorout_fields = Some((vorout, vor_counts, written));
    }
    // SAFETY: the fields point into `out`/`vorout`, live for this call; buffer sizes are the
    // caller's contract.
    unsafe { transfer_all(transfers)? };

    if let Some((vorout, (np, na, ne), written)) = vorout_fields {
        vorout.numberofpoints = np;
        vorout.numberofpointattributes = na;
        vorout.numberofedges = ne;
        if written {
            // Triangle sets these two to NULL explicitly with `v`.
            vorout.pointmarkerlist = ptr::null_mut();
            vorout.edgemarkerlist = ptr::null_mut();
        }
    }
    out.numberofpoints = counts.0;
    out.numberofpointattributes = counts.1;
    out.numberoftriangles = counts.2;
    out.numberofcorners = counts.3;
    out.numberoftriangleattributes = counts.4;
    out.numberofsegments = counts.5;
    out.numberofholes = counts.6;
    out.numberofregions = counts.7;
    out.numberofedges = counts.8;
    if output.alias_holes_and_regions {
        out.holelist = input.holelist;
        out.regionlist = input.regionlist;
    }
    Ok(())
}
