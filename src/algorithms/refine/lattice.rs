//! Lattice seeding: where a fixed area bound governs (the global `a`, a region's own bound), the
//! interior of the domain is first filled with the points of an equilateral triangular lattice
//! whose triangles have a little less than the bound's area, kept a margin of about one lattice
//! spacing away from every segment and vertex; Delaunay refinement (Ruppert 1995, Shewchuk 2002)
//! then splits the encroached subsegments and fills the band along the boundary as usual.
//!
//! Why: refining a mesh to a small area bound one circumcentre at a time costs a bad-triangle test,
//! a walk, an encroachment cavity and a Delaunay insertion per vertex, and leaves triangles of
//! about 0.6 of the bound on average. The lattice's triangles (60°, just under the bound) are
//! never bad, so its points need only a walk and an insertion, and the mesh has about a third
//! fewer triangles. Seeding the interior of a domain with a regular point set and leaving the
//! boundary to a Delaunay method is a classical mesh-generation technique (regular interior
//! points: e.g. Shimada and Gossard's "bubble mesh", 1995, and advancing-front placements); here
//! the boundary band is left to Delaunay refinement, which keeps its
//! guarantees (every angle and area bound is checked on every triangle afterwards).
//!
//! Order: inserting the points row by row would keep a front of long triangles between the
//! seeded rows and the far boundary whose circumcircles contain each new point (tens of flips
//! per point). The points go in coarse to fine instead: level k holds the points whose lattice
//! coordinates are multiples of 2^k (and not of 2^(k+1)), so each level lands in a mesh already
//! refined to twice its spacing (a few flips per point), and within a level row by row, each
//! point located by a walk from a lattice neighbour already in the mesh.
//!
//! Which points: those whose lattice cell lies in a domain triangle of a tag with that bound (the
//! triangles of the unrefined mesh are rasterized row by row onto the lattice), at least the
//! margin away from every segment and vertex (the segments' capsules and the vertices' discs are
//! rasterized the same way). The point is inserted only if the walk finds it in a triangle of
//! that tag, so a rasterization rounded the wrong way costs a point, never the domain.

use super::area_bound;
use super::refinement::{Refinement, Seeded};
use crate::algorithms::domain::Domain;
use crate::geometry::{Point, Predicates};
use crate::mesh::{Mesh, TriangleId, VertexId};

/// The lattice's triangles have this fraction of the area bound: just under it, so that neither
/// the jitter (below 0.5% of a triangle's area) nor rounding makes one too big. (Measured on the
/// refinement benchmark: 0.9, 0.95, 0.98 give 0.71, 0.67, 0.65 times Triangle's triangles.)
const AREA_FRACTION: f64 = 0.98;
/// Lattice points keep at least this many lattice spacings from every segment and vertex. Closer,
/// the boundary band's refinement makes more (smaller) triangles around the points; farther, it
/// fills a wider band one circumcentre at a time. (Measured on the refinement benchmark: 0.5 to 2
/// spacings change its instructions by 1% and its triangles by 0.8%.)
const MARGIN: f64 = 1.0;
/// Each point is moved off the exact lattice by up to this fraction of the spacing (a hash of its
/// coordinates): the exact lattice and its coarse-to-fine subsets are full of cocircular points
/// (every isosceles trapezoid of midpoints, every hexagon around a missing centre), on which each
/// incircle test would fall through to exact arithmetic; moved, the tests decide in floating
/// point, and the triangles stay within a tenth of a degree of 60° and of their area.
const JITTER: f64 = 1.0 / 1024.0;
/// The coarsest level has lattice coordinates multiples of 2^k with about this many points across
/// the lattice's longer side.
const COARSEST_POINTS_ACROSS: usize = 8;
/// A lattice is not laid when its bounding box holds more than this many times the points its
/// domain needs (a thin domain across a large box), nor when there are more distinct bounds than
/// this many.
const SPARSE_FACTOR: f64 = 8.0;
const MAX_LATTICES: usize = 16;
/// Nor above this angle bound (degrees): a point that refinement puts into a lattice triangle
/// (at its centre, say) makes triangles of 30°, 30° and 120°, bad above 30°, whose splitting makes
/// more of them: refinement then cascades through the lattice (measured: 1.7 to 1.9 times
/// Triangle's triangles at 31° to 33° on `A.poly`, where 30.5° and below give 0.7 times).
const MAX_ANGLE: f64 = 30.0;
/// Nor for fewer points than this: nothing to gain; nor for more than this (2^26: a mesh of 10^8
/// triangles, gigabytes; an area bound asking for 10^10 triangles is refined, and cancelled or
/// stopped as a runaway, the classical way, its lattice's arrays alone would not fit).
const MIN_POINTS: f64 = 64.0;
const MAX_POINTS: f64 = (1u64 << 26) as f64;

/// Seeds the lattices of every fixed area bound of the domain (see the module's text). `global`:
/// the `a<x>` bound; `variable_area`: regional bounds apply (`domain.max_area` per tag);
/// `budget`: no more points than this in all (the runaway limit: no lattice is laid beyond).
pub(super) fn seed_lattices<P: Predicates>(
    refinement: &mut Refinement<'_, '_, P>,
    domain: &Domain,
    global: Option<f64>,
    variable_area: bool,
    budget: u64,
    min_angle: Option<f64>,
) {
    if min_angle.is_some_and(|angle| angle > MAX_ANGLE) {
        return;
    }
    let bound_of = |tag: u32| {
        area_bound(global, variable_area, domain, tag).filter(|b| b.is_finite() && *b > 0.0)
    };
    // The distinct bounds, and per tag which one applies (a mesh given with `r` has a tag per
    // triangle: one lattice for them all under a global bound).
    let mesh = refinement.mesh();
    let tag_count = mesh.tags().iter().max().map_or(0, |&t| t as usize + 1);
    let mut bounds: Vec<f64> = Vec::new();
    let mut lattice_of_tag: Vec<Option<usize>> = vec![None; tag_count];
    for (tag, lattice) in lattice_of_tag.iter_mut().enumerate().skip(1) {
        let Some(bound) = bound_of(tag as u32) else {
            continue;
        };
        *lattice = Some(match bounds.iter().position(|&b| b == bound) {
            Some(i) => i,
            None => {
                bounds.push(bound);
                if bounds.len() > MAX_LATTICES {
                    return; // many regions with bounds of their own: few points in each
                }
                bounds.len() - 1
            }
        });
    }
    let mut budget = budget as f64;
    for (i, &bound) in bounds.iter().enumerate() {
        let members: Vec<bool> = lattice_of_tag.iter().map(|&l| l == Some(i)).collect();
        let Some(mut lattice) = Lattice::lay(refinement.mesh(), bound, &members, budget) else {
            continue;
        };
        budget -= lattice.needed;
        if lattice.seed(refinement, &members) {
            return; // stopped (cancelled)
        }
    }
}

/// An equilateral lattice over the bounding box of the triangles of some tags: point `(c, j)` (row
/// `j`, column `c`) at `origin + ((c + (j mod 2)/2)·spacing, j·height)`; its lattice coordinates
/// are `i = c − ⌊j/2⌋` and `j` (the point is `origin + i·(s, 0) + j·(s/2, h)`).
struct Lattice {
    origin: Point,
    spacing: f64,
    height: f64,
    columns: usize,
    rows: usize,
    /// Per point: whether it is to be seeded (it lies in a domain triangle of the lattice's tags,
    /// away from segments and vertices).
    seeded: Vec<bool>,
    /// Per point: its vertex once inserted.
    vertex: Vec<VertexId>,
    /// A triangle of the tags: where the first walk starts.
    start: TriangleId,
    /// About how many points the domain of the tags takes.
    needed: f64,
}

impl Lattice {
    /// The lattice for area bound `bound` over the triangles of the tags that are `members`, with
    /// the points to seed
    /// marked; `None` when it is not worth laying, or would take more than `budget` points.
    fn lay(mesh: &Mesh, bound: f64, members: &[bool], budget: f64) -> Option<Lattice> {
        let spacing = (4.0 * AREA_FRACTION * bound / 3f64.sqrt()).sqrt();
        let height = spacing * 3f64.sqrt() / 2.0;
        let in_group = |t| !mesh.is_ghost(t) && members.get(mesh.tag(t) as usize) == Some(&true);
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        let mut area = 0.0;
        let mut start = TriangleId::NONE;
        for t in mesh.triangles().filter(|&t| in_group(t)) {
            start = t;
            let [a, b, c] = mesh.triangle(t).map(|v| mesh.point(v));
            area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
            for p in [a, b, c] {
                for k in 0..2 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
        let needed = area / (AREA_FRACTION * bound) / 2.0;
        if needed.is_nan() || needed < MIN_POINTS || needed > budget.min(MAX_POINTS) {
            return None;
        }
        let columns = ((hi[0] - lo[0]) / spacing).ceil() + 2.0;
        let rows = ((hi[1] - lo[1]) / height).ceil() + 1.0;
        if columns * rows > SPARSE_FACTOR * needed + 65536.0 {
            return None;
        }
        let (columns, rows) = (columns as usize, rows as usize);
        let mut lattice = Lattice {
            origin: [lo[0] - 0.5 * spacing, lo[1]],
            spacing,
            height,
            columns,
            rows,
            seeded: vec![false; columns * rows],
            vertex: vec![VertexId::NONE; columns * rows],
            start,
            needed,
        };
        for t in mesh.triangles().filter(|&t| in_group(t)) {
            let corners = mesh.triangle(t).map(|v| mesh.point(v));
            lattice.rasterize(&corners, true);
        }
        // Away from segments (their capsules) and vertices (their discs).
        let margin = MARGIN * spacing;
        for e in mesh.edges() {
            if !mesh.is_segment(e) || e > mesh.twin(e) {
                continue;
            }
            let (a, b) = (mesh.point(mesh.origin(e)), mesh.point(mesh.dest(e)));
            let (d, length) = ([b[0] - a[0], b[1] - a[1]], (b[0] - a[0]).hypot(b[1] - a[1]));
            if length > 0.0 {
                let n = [-d[1] / length * margin, d[0] / length * margin];
                let band = [
                    [a[0] + n[0], a[1] + n[1]],
                    [b[0] + n[0], b[1] + n[1]],
                    [b[0] - n[0], b[1] - n[1]],
                    [a[0] - n[0], a[1] - n[1]],
                ];
                lattice.rasterize(&band, false);
            }
        }
        for &p in mesh.points() {
            lattice.rasterize_disc(p, margin);
        }
        Some(lattice)
    }

    fn x(&self, c: usize, j: usize) -> f64 {
        self.origin[0] + (c as f64 + 0.5 * (j % 2) as f64) * self.spacing
    }

    /// Point `(c, j)`, moved off the lattice by its jitter.
    fn point(&self, c: usize, j: usize) -> Point {
        // SplitMix64's finalizer of the slot: two well-mixed 32-bit halves.
        let mut z = ((j * self.columns + c) as u64).wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        let unit = |bits: u64| (bits & 0xFFFF_FFFF) as f64 / f64::from(u32::MAX) * 2.0 - 1.0;
        let d = JITTER * self.spacing;
        [
            self.x(c, j) + d * unit(z),
            self.origin[1] + j as f64 * self.height + d * unit(z >> 32),
        ]
    }

    /// The columns of row `j` with x in `[left, right]`.
    fn columns_between(&self, j: usize, left: f64, right: f64) -> std::ops::Range<usize> {
        let shift = 0.5 * (j % 2) as f64;
        let first = ((left - self.origin[0]) / self.spacing - shift)
            .ceil()
            .max(0.0);
        let last = ((right - self.origin[0]) / self.spacing - shift).floor() + 1.0;
        let last = last.min(self.columns as f64);
        if last > first {
            first as usize..last as usize
        } else {
            0..0
        }
    }

    /// The rows with y in `[low, high]`.
    fn rows_between(&self, low: f64, high: f64) -> std::ops::Range<usize> {
        let first = ((low - self.origin[1]) / self.height).ceil().max(0.0);
        let last = (((high - self.origin[1]) / self.height).floor() + 1.0).min(self.rows as f64);
        if last > first {
            first as usize..last as usize
        } else {
            0..0
        }
    }

    /// Marks every lattice point in convex polygon `polygon` (closed; in floating point, which
    /// only the points within rounding of its edges notice) to be `seeded` or not.
    fn rasterize(&mut self, polygon: &[Point], seeded: bool) {
        let low = polygon.iter().map(|p| p[1]).fold(f64::MAX, f64::min);
        let high = polygon.iter().map(|p| p[1]).fold(f64::MIN, f64::max);
        for j in self.rows_between(low, high) {
            let y = self.origin[1] + j as f64 * self.height;
            let (mut left, mut right) = (f64::MAX, f64::MIN);
            for k in 0..polygon.len() {
                let (p, q) = (polygon[k], polygon[(k + 1) % polygon.len()]);
                if (p[1] - y) * (q[1] - y) > 0.0 {
                    continue; // the edge does not reach the row
                }
                let xs = if p[1] == q[1] {
                    [p[0], q[0]]
                } else {
                    let x = p[0] + (y - p[1]) / (q[1] - p[1]) * (q[0] - p[0]);
                    [x, x]
                };
                for x in xs {
                    left = left.min(x);
                    right = right.max(x);
                }
            }
            for c in self.columns_between(j, left, right) {
                self.seeded[j * self.columns + c] = seeded;
            }
        }
    }

    /// Unmarks the lattice points within `radius` of `p`.
    fn rasterize_disc(&mut self, p: Point, radius: f64) {
        for j in self.rows_between(p[1] - radius, p[1] + radius) {
            let dy = self.origin[1] + j as f64 * self.height - p[1];
            let half = (radius * radius - dy * dy).max(0.0).sqrt();
            for c in self.columns_between(j, p[0] - half, p[0] + half) {
                self.seeded[j * self.columns + c] = false;
            }
        }
    }

    /// The slot of lattice coordinates `(i, j)`, if in the lattice.
    fn slot(&self, i: i64, j: i64) -> Option<usize> {
        let c = i + j.div_euclid(2);
        (j >= 0 && (j as usize) < self.rows && c >= 0 && (c as usize) < self.columns)
            .then(|| j as usize * self.columns + c as usize)
    }

    /// Inserts the marked points, coarse to fine, each if it lies in a triangle of a tag that is
    /// one of the `members`; returns whether refinement is to stop.
    fn seed<P: Predicates>(
        &mut self,
        refinement: &mut Refinement<'_, '_, P>,
        members: &[bool],
    ) -> bool {
        // From the longer side: in a long thin domain the coarse levels are points along its first
        // row, which bisect it (a single level in row order would leave long triangles from the
        // seeded part to the far end, whose circumcircles contain each new point).
        let across = self.columns.max(self.rows) / COARSEST_POINTS_ACROSS;
        let coarsest = (usize::BITS - across.max(1).leading_zeros() - 1).min(12);
        let mut last = VertexId::NONE;
        let mut near = Vec::with_capacity(8);
        for level in (0..=coarsest).rev() {
            let step = 1i64 << level;
            for j in (0..self.rows as i64).step_by(step as usize) {
                // Columns whose lattice coordinate i is a multiple of the step.
                let first = (j.div_euclid(2)).rem_euclid(step) as usize;
                for c in (first..self.columns).step_by(step as usize) {
                    let slot = j as usize * self.columns + c;
                    let i = c as i64 - j.div_euclid(2);
                    let coarser = (i % (2 * step) == 0 && j % (2 * step) == 0) && level < coarsest;
                    if !self.seeded[slot] || coarser {
                        continue;
                    }
                    // Lattice neighbours at this level's spacing already in the mesh.
                    near.clear();
                    for (di, dj) in [(-1, 0), (1, 0), (1, -1), (0, -1), (0, 1), (-1, 1)] {
                        if let Some(n) = self.slot(i + di * step, j + dj * step) {
                            if self.vertex[n] != VertexId::NONE {
                                near.push(self.vertex[n]);
                            }
                        }
                    }
                    if last != VertexId::NONE {
                        near.push(last);
                    }
                    // Below the coarsest level the point is the midpoint of two points of the
                    // next coarser level; when both are in the mesh and joined by an edge, the
                    // point lies beside it (the walk from there takes a step or two).
                    let hint = (level < coarsest)
                        .then(|| {
                            let (di, dj) = if j % (2 * step) == 0 {
                                (1, 0)
                            } else if i % (2 * step) == 0 {
                                (0, 1)
                            } else {
                                (1, -1)
                            };
                            let parent = |sign: i64| {
                                self.slot(i + sign * di * step, j + sign * dj * step)
                                    .map(|n| self.vertex[n])
                                    .filter(|&v| v != VertexId::NONE)
                            };
                            let mesh = refinement.mesh();
                            mesh.find_edge(parent(-1)?, parent(1)?)
                                .map(|e| e.triangle())
                        })
                        .flatten();
                    match refinement.insert_seed(
                        self.point(c, j as usize),
                        hint,
                        &near,
                        self.start,
                        members,
                    ) {
                        Seeded::Inserted(v) => {
                            self.vertex[slot] = v;
                            last = v;
                        }
                        Seeded::Skipped => {}
                        Seeded::Stop => return true,
                    }
                }
            }
        }
        false
    }
}
