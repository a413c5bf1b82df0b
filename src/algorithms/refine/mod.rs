//! Delaunay refinement: quality meshing with angle, area and user constraints.
//!
//! Ruppert's algorithm ("A Delaunay refinement algorithm for quality 2-dimensional mesh
//! generation", 1995) as refined by Shewchuk ("Delaunay refinement algorithms for triangular mesh
//! generation", 2002):
//! - a subsegment is *encroached* when a vertex lies strictly inside its diametral circle; in a
//!   constrained Delaunay triangulation it suffices to look at the two apices beside it. Encroached
//!   subsegments are split first, at their midpoints, or — next to an input vertex shared with
//!   another segment — at a power-of-two distance from it ("concentric shells", Shewchuk §4.1),
//!   which keeps small input angles from causing endless splitting;
//! - a bad triangle (an angle below θ, an area above the bound, or the user's test) is split at its
//!   circumcentre or, when that is closer to the shortest edge, at Üngör's off-centre ("Off-centers:
//!   a new type of Steiner points for computing size-optimal quality-guaranteed Delaunay
//!   triangulations", 2004), which needs fewer vertices;
//! - a new point that would encroach a subsegment is rejected, and the subsegment is split instead
//!   (Ruppert's rule); the bad triangle is queued again.
//!
//! Worst triangles go first. Termination: for θ ≤ 28.6° the algorithm terminates (Shewchuk
//! 2002); beyond, it may not, so every split checks that it makes an edge no shorter than a floor
//! far above the floating-point resolution of the domain, skips (and reports) a triangle or
//! segment it cannot split, and stops at the Steiner-point budget (`S`) or when cancelled.

use crate::algorithms::domain::Domain;
use crate::data::{ProgressFn, UnsuitableFn};
use crate::geometry::{min_angle_sin2, Grid};
use crate::mesh::{Mesh, TriangleId, VertexId, OUTSIDE};

// The parts, each a type with its own state:
mod attributes; // `Attributes`: the interpolated attributes of new vertices
mod builtin_test; // `builtin_unsuitable`: Triangle's `u` test when the caller registers none
mod deletion; // `DiskWalk`: the free vertices deleted before a subsegment is split (Chew)
mod driver; // `refine`: strategy above the guaranteed angle, budgets, runaway limit, report
mod encroachment; // `Encroachment`, `Cavity`: encroached subsegments, where subsegments are split
mod lattice; // `seed_lattices`: lattice points where a fixed area bound governs
mod polling; // `Polling`: the caller's cancel and progress hooks, asked now and then
mod queue; // `BadQueue`: the bad-triangle queue
mod refinement; // `Refinement`: the loop, splitting segments and triangles, the mesh's bookkeeping
mod report; // `Report`, `Warning`
mod split_point; // `AngleBound`: skinny triangles, the small-angle exemption, split points
#[cfg(test)]
mod tests;
mod walk; // the straight walk from a bad triangle toward its split point

pub use builtin_test::builtin_unsuitable;
pub use driver::refine;
pub use report::{Report, Warning};

/// The largest minimum angle for which Delaunay refinement is proven to terminate.
pub const GUARANTEED_ANGLE: f64 = 28.6;

/// What makes a triangle bad, and what may be done about it.
pub struct Quality<'a> {
    /// Minimum angle in degrees (`q`).
    pub min_angle: Option<f64>,
    /// Global maximum area (`a<x>`).
    pub max_area: Option<f64>,
    /// Regional / per-triangle maximum areas (`a`), from the domain's tags.
    pub variable_area: bool,
    /// The user's test (`u`), or the built-in one ([`builtin_unsuitable`]) when none is
    /// registered.
    pub user_test: Option<&'a UnsuitableFn<'a>>,
    /// `Y` (1): no Steiner points on boundary segments; `YY` (2): on any segment.
    pub no_steiner_on_segments: u8,
    /// `S`: the Steiner-point budget.
    pub max_steiner: Option<u64>,
    /// `R`: the finished mesh is reduced (decimated and polished: fewer triangles for a few
    /// times the time; see `refinement::improvement`).
    pub reduce: bool,
    /// Whether the interior may first be seeded with lattice points where a fixed area bound
    /// governs (global or regional `a`; not for per-triangle bounds of a mesh given with `r`,
    /// and never with the user's test or an `S` budget).
    pub area_lattice: bool,
    /// Polled now and then; `true` stops refinement with a valid mesh.
    pub cancel: Option<&'a (dyn Fn() -> bool + Sync + 'a)>,
    /// Told of the work done and waiting where `cancel` is polled.
    pub progress: Option<&'a ProgressFn<'a>>,
    /// The points the caller's coordinates can hold, when the engine's frame is not the
    /// caller's (a translation makes rounding finer than the caller's): the mesh the caller
    /// receives must meet the quality on it (see `Constrainer::move_onto_grid`).
    pub caller_grid: Option<CallerGrid<'a>>,
}

/// How refinement meets the quality on the caller's grid ([`Quality::caller_grid`]).
#[derive(Clone, Copy)]
pub struct CallerGrid<'a> {
    /// The grid.
    pub grid: &'a dyn Grid,
    /// Whether every new point is rounded to the grid as it is made (Triangle's plain
    /// arithmetic, where the caller's coordinates are all there is). Else the mesh is refined
    /// in the finer frame (the mesh of the translated input), moved onto the grid, and
    /// refined again there with new points rounded to it; where the move would invert a
    /// triangle (refinement in the finer frame went below the caller's rounding) the
    /// refinement reports `off_grid`, to be run again from the start on the grid.
    pub from_the_start: bool,
}

/// How a vertex came to be: it decides where segments next to it are split.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum VertexKind {
    /// An input vertex (or a crossing of input segments).
    Input,
    /// A vertex inserted on a segment by refinement; `corner`: the input vertex it was put at a
    /// power-of-two distance from (concentric shells), or [`VertexId::NONE`] (a midpoint);
    /// `shell`: that distance's exponent (the distance is 2^shell; 0 for a midpoint).
    OnSegment { corner: VertexId, shell: i32 },
    /// A vertex inserted inside the domain by refinement, at a bad triangle's split point:
    /// deleted when a subsegment whose diametral circle holds it is split (Chew's rule, see
    /// [`deletion`]).
    Free,
    /// A lattice point seeded before the loop ([`lattice`]): free, but never deleted (the lattice
    /// stands for the points the area bound asks for; long subsegments split early would
    /// delete swaths of it).
    Seed,
    /// A free vertex deleted (in no triangle); dropped from the numbering when refinement ends.
    Deleted,
}

/// The area bound of the domain's triangles tagged `tag`: the global one (`a<x>`, `global`) or
/// their region's (`a`, where `variable_area`; a positive one), the smaller where both apply.
fn area_bound(global: Option<f64>, variable_area: bool, domain: &Domain, tag: u32) -> Option<f64> {
    let regional = if variable_area {
        domain
            .max_area
            .get(tag as usize)
            .copied()
            .filter(|&m| m > 0.0)
    } else {
        None
    };
    match (global, regional) {
        (Some(g), Some(r)) => Some(g.min(r)),
        (g, r) => g.or(r),
    }
}

/// Whether triangle `t` belongs to the domain (refinement works on the domain alone; the
/// triangles outside it are tagged [`OUTSIDE`]).
fn inside(mesh: &Mesh, t: TriangleId) -> bool {
    mesh.tag(t) != OUTSIDE
}

/// The domain's triangle with the smallest angle, and that angle's sine squared (`None` for no
/// triangle).
fn worst_triangle(mesh: &Mesh) -> Option<(TriangleId, f64)> {
    mesh.triangles()
        .filter(|&t| inside(mesh, t))
        .map(|t| (t, min_angle_sin2(mesh.triangle(t).map(|v| mesh.point(v)))))
        .min_by(|a, b| a.1.total_cmp(&b.1))
}
