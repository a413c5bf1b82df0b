//! Calling a `triangulate` with Triangle's C ABI (ours, or Debian's through [`super::reference`])
//! from safe Rust: [`MeshInput`] owns the input arrays, [`Triangulation`] owns a copy of every
//! output array (the C arrays are freed with the library's own `trifree`).

use std::ffi::CString;
use std::os::raw::{c_char, c_int, c_void};
use std::ptr;

use triangle_rs::io::triangulateio::TriangulateIO;

use super::points::Point;

/// The input of one call, in the caller's numbering (indices must match the switches' base).
#[derive(Clone, Debug, Default)]
pub struct MeshInput {
    pub points: Vec<Point>,
    /// `attribute_count` values per point.
    pub attributes: Vec<f64>,
    pub attribute_count: usize,
    pub markers: Option<Vec<i32>>,
    pub segments: Vec<[i32; 2]>,
    pub segment_markers: Option<Vec<i32>>,
    pub holes: Vec<Point>,
    /// x, y, attribute, maximum area.
    pub regions: Vec<[f64; 4]>,
    /// `r`: `corners` indices per triangle.
    pub triangles: Vec<i32>,
    pub corners: usize,
    pub triangle_attributes: Vec<f64>,
    pub triangle_attribute_count: usize,
    pub triangle_areas: Option<Vec<f64>>,
}

impl MeshInput {
    pub fn from_points(points: Vec<Point>) -> Self {
        MeshInput {
            points,
            ..MeshInput::default()
        }
    }

    /// The input struct; its pointers borrow `self`'s vectors (Triangle never writes to them).
    fn as_raw(&mut self) -> TriangulateIO {
        fn mut_ptr<T>(v: &mut [T]) -> *mut T {
            if v.is_empty() {
                ptr::null_mut()
            } else {
                v.as_mut_ptr()
            }
        }
        TriangulateIO {
            pointlist: mut_ptr(self.points.as_flattened_mut()),
            pointattributelist: mut_ptr(&mut self.attributes),
            pointmarkerlist: self
                .markers
                .as_mut()
                .map_or(ptr::null_mut(), |m| mut_ptr(m)),
            numberofpoints: self.points.len() as c_int,
            numberofpointattributes: self.attribute_count as c_int,
            trianglelist: mut_ptr(&mut self.triangles),
            triangleattributelist: mut_ptr(&mut self.triangle_attributes),
            trianglearealist: self
                .triangle_areas
                .as_mut()
                .map_or(ptr::null_mut(), |a| mut_ptr(a)),
            neighborlist: ptr::null_mut(),
            numberoftriangles: self.triangles.len().checked_div(self.corners).unwrap_or(0) as c_int,
            numberofcorners: self.corners as c_int,
            numberoftriangleattributes: self.triangle_attribute_count as c_int,
            segmentlist: mut_ptr(self.segments.as_flattened_mut()),
            segmentmarkerlist: self
                .segment_markers
                .as_mut()
                .map_or(ptr::null_mut(), |m| mut_ptr(m)),
            numberofsegments: self.segments.len() as c_int,
            holelist: mut_ptr(self.holes.as_flattened_mut()),
            numberofholes: self.holes.len() as c_int,
            regionlist: mut_ptr(self.regions.as_flattened_mut()),
            numberofregions: self.regions.len() as c_int,
            edgelist: ptr::null_mut(),
            edgemarkerlist: ptr::null_mut(),
            normlist: ptr::null_mut(),
            numberofedges: 0,
        }
    }
}

/// The count fields of an output struct.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    pub points: i32,
    pub point_attributes: i32,
    pub triangles: i32,
    pub corners: i32,
    pub triangle_attributes: i32,
    pub segments: i32,
    pub holes: i32,
    pub regions: i32,
    pub edges: i32,
}

impl Counts {
    fn of(io: &TriangulateIO) -> Counts {
        Counts {
            points: io.numberofpoints,
            point_attributes: io.numberofpointattributes,
            triangles: io.numberoftriangles,
            corners: io.numberofcorners,
            triangle_attributes: io.numberoftriangleattributes,
            segments: io.numberofsegments,
            holes: io.numberofholes,
            regions: io.numberofregions,
            edges: io.numberofedges,
        }
    }
}

/// `vorout`: counts and arrays (`None` = the pointer stayed NULL).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Voronoi {
    pub points_count: i32,
    pub attribute_count: i32,
    pub edges_count: i32,
    pub points: Option<Vec<Point>>,
    pub point_attributes: Option<Vec<f64>>,
    pub edges: Option<Vec<[i32; 2]>>,
    pub norms: Option<Vec<Point>>,
    /// Triangle sets these to NULL with `v`; non-NULL here would be a bug.
    pub point_markers_written: bool,
    pub edge_markers_written: bool,
}

/// Everything one call wrote, copied out of the C arrays. `None` = the pointer stayed NULL.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Triangulation {
    /// The numbering base the switches asked for: 0 with `z`, else 1.
    pub base: i32,
    pub counts: Counts,
    pub points: Option<Vec<Point>>,
    pub point_attributes: Option<Vec<f64>>,
    pub point_markers: Option<Vec<i32>>,
    /// `counts.corners` indices per triangle.
    pub triangles: Option<Vec<i32>>,
    pub triangle_attributes: Option<Vec<f64>>,
    pub triangle_areas_written: bool,
    pub neighbors: Option<Vec<[i32; 3]>>,
    pub segments: Option<Vec<[i32; 2]>>,
    pub segment_markers: Option<Vec<i32>>,
    /// `out.holelist`/`out.regionlist` are either NULL or aliases of the input's arrays.
    pub holes_alias_input: bool,
    pub regions_alias_input: bool,
    pub edges: Option<Vec<[i32; 2]>>,
    pub edge_markers: Option<Vec<i32>>,
    pub norms_written: bool,
    /// `None` when the call was made without a `vorout` struct.
    pub voronoi: Option<Voronoi>,
}

impl Triangulation {
    /// The triangles as corner triples (the first three corners of each).
    pub fn triangle_triples(&self) -> Vec<[i32; 3]> {
        let corners = self.counts.corners.max(3) as usize;
        self.triangles
            .as_deref()
            .unwrap_or_default()
            .chunks_exact(corners)
            .map(|t| [t[0], t[1], t[2]])
            .collect()
    }
}

/// Copies `len` items out of a C array and frees it; `None` for NULL.
///
/// # Safety
/// `p` is NULL or a live allocation of at least `len` items owned by the library whose `free`
/// is given.
unsafe fn take<T: Copy>(p: *mut T, len: usize, free: &dyn Fn(*mut c_void)) -> Option<Vec<T>> {
    if p.is_null() {
        return None;
    }
    // SAFETY: non-NULL, `len` items (caller's contract).
    let items = unsafe { std::slice::from_raw_parts(p, len) }.to_vec();
    free(p as *mut c_void);
    Some(items)
}

/// Like [`take`] for arrays of `N`-wide rows.
///
/// # Safety
/// As [`take`], with `len * N` items.
unsafe fn take_rows<T: Copy + Default, const N: usize>(
    p: *mut T,
    len: usize,
    free: &dyn Fn(*mut c_void),
) -> Option<Vec<[T; N]>> {
    // SAFETY: forwarded contract.
    unsafe { take(p, len * N, free) }.map(|flat| {
        flat.chunks_exact(N)
            .map(|row| {
                let mut item = [T::default(); N];
                item.copy_from_slice(row);
                item
            })
            .collect()
    })
}

fn count(n: c_int) -> usize {
    usize::try_from(n).unwrap_or(0)
}

/// A `triangulate` with the C ABI: returns `Err(message)` on failure.
pub type RawCall<'a> = dyn Fn(
        *mut c_char,
        *mut TriangulateIO,
        *mut TriangulateIO,
        *mut TriangulateIO,
    ) -> Result<(), String>
    + 'a;

/// Runs one call with fresh zeroed `out` (and `vorout` when `with_vorout`) and copies every
/// output array, freeing it with `free`.
pub fn run_call(
    call: &RawCall<'_>,
    free: &dyn Fn(*mut c_void),
    switches: &str,
    input: &MeshInput,
    with_vorout: bool,
) -> Result<Triangulation, String> {
    let mut input = input.clone();
    let mut raw_in = input.as_raw();
    let mut out = TriangulateIO::default();
    let mut vorout = TriangulateIO::default();
    let switches = CString::new(switches).expect("switches without NUL");
    let vorout_ptr: *mut TriangulateIO = if with_vorout {
        &mut vorout
    } else {
        ptr::null_mut()
    };
    call(
        switches.as_ptr() as *mut c_char,
        &mut raw_in,
        &mut out,
        vorout_ptr,
    )?;

    let n = count(out.numberofpoints);
    let ntri = count(out.numberoftriangles);
    let nseg = count(out.numberofsegments);
    let nedge = count(out.numberofedges);
    // SAFETY: every non-NULL output array was allocated by the call with the size its count
    // gives (Triangle's contract), and is freed exactly once here.
    let mut result = unsafe {
        Triangulation {
            base: if switches.to_bytes().contains(&b'z') {
                0
            } else {
                1
            },
            counts: Counts::of(&out),
            points: take_rows::<f64, 2>(out.pointlist, n, free),
            point_attributes: take(
                out.pointattributelist,
                n * count(out.numberofpointattributes),
                free,
            ),
            point_markers: take(out.pointmarkerlist, n, free),
            triangles: take(out.trianglelist, ntri * count(out.numberofcorners), free),
            triangle_attributes: take(
                out.triangleattributelist,
                ntri * count(out.numberoftriangleattributes),
                free,
            ),
            triangle_areas_written: !out.trianglearealist.is_null(),
            neighbors: take_rows::<i32, 3>(out.neighborlist, ntri, free),
            segments: take_rows::<i32, 2>(out.segmentlist, nseg, free),
            segment_markers: take(out.segmentmarkerlist, nseg, free),
            holes_alias_input: !out.holelist.is_null(),
            regions_alias_input: !out.regionlist.is_null(),
            edges: take_rows::<i32, 2>(out.edgelist, nedge, free),
            edge_markers: take(out.edgemarkerlist, nedge, free),
            norms_written: !out.normlist.is_null(),
            voronoi: None,
        }
    };
    for (written, aliased, name) in [
        (out.holelist, raw_in.holelist, "holelist"),
        (out.regionlist, raw_in.regionlist, "regionlist"),
    ] {
        if !written.is_null() && written != aliased {
            return Err(format!("out.{name} is neither NULL nor the input's array"));
        }
    }
    if !out.normlist.is_null() {
        free(out.normlist as *mut c_void);
    }
    if with_vorout {
        let vn = count(vorout.numberofpoints);
        let ve = count(vorout.numberofedges);
        // SAFETY: as above, for `vorout`'s arrays.
        result.voronoi = Some(unsafe {
            Voronoi {
                points_count: vorout.numberofpoints,
                attribute_count: vorout.numberofpointattributes,
                edges_count: vorout.numberofedges,
                points: take_rows::<f64, 2>(vorout.pointlist, vn, free),
                point_attributes: take(
                    vorout.pointattributelist,
                    vn * count(vorout.numberofpointattributes),
                    free,
                ),
                edges: take_rows::<i32, 2>(vorout.edgelist, ve, free),
                norms: take_rows::<f64, 2>(vorout.normlist, ve, free),
                point_markers_written: !vorout.pointmarkerlist.is_null(),
                edge_markers_written: !vorout.edgemarkerlist.is_null(),
            }
        });
    }
    Ok(result)
}

/// The result of one of our calls that returned `rc`: `Err` with `triangulate_last_error()` (to
/// be read on the calling thread, right after the call) unless `rc` is 0.
pub fn ours_status(rc: c_int) -> Result<(), String> {
    if rc == 0 {
        return Ok(());
    }
    // SAFETY: the library returns a valid NUL-terminated string.
    let message = unsafe { std::ffi::CStr::from_ptr(triangle_rs::ffi::triangulate_last_error()) };
    Err(message.to_string_lossy().into_owned())
}

/// Our `triangulate` through its C ABI (the exported function, not the Rust engine API).
pub fn ours(switches: &str, input: &MeshInput) -> Result<Triangulation, String> {
    ours_with(switches, input, true)
}

/// As [`ours`], optionally with a NULL `vorout`.
pub fn ours_with(
    switches: &str,
    input: &MeshInput,
    with_vorout: bool,
) -> Result<Triangulation, String> {
    let call = |s: *mut c_char, i, o, v| {
        // SAFETY: valid, NUL-terminated switches and structs prepared by `run_call`.
        ours_status(unsafe { triangle_rs::ffi::triangulate(s, i, o, v) })
    };
    // SAFETY: arrays returned by our `triangulate` are freed with our `trifree`.
    let free = |p: *mut c_void| unsafe { triangle_rs::ffi::trifree(p) };
    run_call(&call, &free, switches, input, with_vorout)
}
