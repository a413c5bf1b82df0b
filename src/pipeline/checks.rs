//! The checks of a run: of its switches and input before any work (every error a typed
//! [`Error`], never a silent skip), and of the finished mesh (`C`).

use super::Meshed;
use crate::data::{Input, MeshCheck};
use crate::error::Error;
use crate::geometry::{Point, Predicates};
use crate::mesh::GHOST;
use crate::options::Options;
use crate::scaling::Magnitudes;
use std::mem::MaybeUninit;

/// Rejects the switches whose features have not landed yet, with a clear message.
pub(super) fn check_supported(options: &Options) -> Result<(), Error> {
    let unsupported = [(
        options.weighted != 0,
        "The `w`/`W` switches (weighted triangulation)",
    )];
    match unsupported.iter().find(|(on, _)| *on) {
        Some((_, what)) => Err(Error::Unsupported(what)),
        None => Ok(()),
    }
}

/// Checks the parts of the input that every run reads and collects the points, with their
/// [`Magnitudes`] (the scaling's screen, gathered by the same pass).
pub(super) fn checked_points(input: &Input<'_>) -> Result<(Vec<Point>, Magnitudes), Error> {
    let n = input.point_count();
    if n < 3 {
        return Err(Error::TooFewPoints);
    }
    if input.point_attributes.len() != n * input.point_attribute_count {
        return Err(Error::BadCount {
            field: "numberofpointattributes",
            value: input.point_attribute_count as i64,
        });
    }
    // Copied and screened in one pass (on two threads for a large input: the copy's cost is the
    // fresh pages it writes, which two cores fault in twice as fast); the culprit is looked for
    // only if there is one.
    let flat = &input.points[..2 * n];
    let mut points: Vec<Point> = crate::memory::with_capacity_on_huge_pages(n);
    let spare = &mut points.spare_capacity_mut()[..n];
    let two_cores = crate::threads::two_cores();
    let magnitudes = if two_cores && n >= PARALLEL_COPY {
        let half = n / 2;
        let (low, high) = spare.split_at_mut(half);
        let (flat_low, flat_high) = flat.split_at(2 * half);
        std::thread::scope(|scope| {
            let job = scope.spawn(|| copy_and_screen(flat_high, high));
            let m = copy_and_screen(flat_low, low);
            m.merge(job.join().unwrap_or_else(|p| std::panic::resume_unwind(p)))
        })
    } else {
        copy_and_screen(flat, spare)
    };
    // SAFETY: `copy_and_screen` wrote every one of the first `n` items (the two parts cover
    // them), and the capacity is `n`.
    unsafe { points.set_len(n) };
    if !magnitudes.all_finite() {
        let i = points
            .iter()
            .position(|p| !(p[0].is_finite() && p[1].is_finite()))
            .unwrap_or(0);
        return Err(Error::NonFinite {
            what: "Vertex",
            index: i,
        });
    }
    Ok((points, magnitudes))
}

/// From this many points on, [`checked_points`] copies on two threads (when there are two).
const PARALLEL_COPY: usize = 1 << 16;

/// Copies the coordinate pairs of `flat` into `out` (as long) and returns their magnitudes.
fn copy_and_screen(flat: &[f64], out: &mut [MaybeUninit<Point>]) -> Magnitudes {
    let mut magnitudes = Magnitudes::default();
    for (slot, c) in out.iter_mut().zip(flat.chunks_exact(2)) {
        magnitudes.add(c[0]);
        magnitudes.add(c[1]);
        slot.write([c[0], c[1]]);
    }
    magnitudes
}

/// Checks the vertex indices of segments (`p`) and triangles (`r`), and the hole and region
/// points that will be located: an index out of range is an error, never a silent skip.
pub(super) fn check_indices_and_seeds(options: &Options, input: &Input<'_>) -> Result<(), Error> {
    let base = i64::from(options.first_index());
    let n = input.point_count() as i64;
    let check = |item, role, list: &[i32], width: usize| {
        for (i, row) in list.chunks_exact(width).enumerate() {
            if let Some(&v) = row
                .iter()
                .find(|&&v| !(base..base + n).contains(&i64::from(v)))
            {
                return Err(Error::IndexOutOfRange {
                    item,
                    number: i as i64 + base,
                    role,
                    value: i64::from(v),
                    first: base,
                    last: base + n - 1,
                });
            }
        }
        Ok(())
    };
    if options.pslg {
        check("Segment", "endpoint", input.segments, 2)?;
    }
    if options.refine {
        if input.corners != 3 && input.corners != 6 {
            return Err(Error::BadCorners(input.corners as i64));
        }
        check("Triangle", "corner", input.triangles, input.corners)?;
    }
    if options.pslg && !options.refine {
        let number = |i: usize| (i as i64 + base) as usize;
        if !options.ignore_holes {
            if let Some(i) = input
                .holes
                .chunks_exact(2)
                .position(|h| !(h[0].is_finite() && h[1].is_finite()))
            {
                return Err(Error::NonFinite {
                    what: "Hole",
                    index: number(i),
                });
            }
        }
        for (i, r) in input.regions.chunks_exact(4).enumerate() {
            if !(r[0].is_finite() && r[1].is_finite()) {
                return Err(Error::NonFinite {
                    what: "Region",
                    index: number(i),
                });
            }
            if r[3].is_nan() {
                return Err(Error::NanRegionArea {
                    region: i as i64 + base,
                });
            }
        }
    }
    Ok(())
}

/// `C`: checks the final mesh with exact arithmetic: what it found (a passing check is no
/// warning; [`MeshCheck::warning`] gives the one of a failing check).
pub(super) fn check_mesh<P: Predicates>(meshed: &Meshed) -> MeshCheck {
    let mesh = &meshed.mesh;
    if let Err(why) = mesh.check_topology() {
        return MeshCheck::Inconsistent(why);
    }
    let mut inverted = 0;
    let mut not_delaunay = 0;
    for t in mesh.triangles() {
        if mesh.is_ghost(t) {
            continue;
        }
        let [a, b, c] = mesh.triangle(t).map(|v| mesh.point(v));
        if P::orient2d(a, b, c) <= 0.0 {
            inverted += 1;
        }
        for e in t.edges() {
            let q = mesh.apex(mesh.twin(e));
            if q != GHOST && !mesh.is_segment(e) && P::incircle(a, b, c, mesh.point(q)) > 0.0 {
                not_delaunay += 1;
            }
        }
    }
    match (inverted, not_delaunay) {
        (0, 0) => MeshCheck::Passed,
        _ => MeshCheck::Failed {
            inverted,
            not_delaunay,
        },
    }
}
