//! Encroached subsegments (diametral lenses, or circles with `D`): which subsegments a vertex
//! beside them or a new point encroaches, and where an encroached subsegment is split — its
//! midpoint, or a concentric shell around an acute input corner (Ruppert 1995 §5, Shewchuk 2002
//! §4.1).

use super::{inside, VertexKind};
use crate::algorithms::delaunay::Location;
use crate::geometry::{diametral_dot, Point, Predicates};
use crate::mesh::{EdgeId, Mesh, TriangleId, VertexId, GHOST};

/// The encroachment test for an angle bound θ.
#[derive(Clone, Copy, Debug)]
pub(super) struct Encroachment {
    /// cos² of the lens angle 180° − 2θ; `None`: diametral circles.
    lens_cos2: Option<f64>,
}

impl Encroachment {
    /// For θ = `degrees`; `conforming` (`D`): diametral circles, so that the result is truly
    /// Delaunay.
    pub(super) fn new(degrees: f64, conforming: bool) -> Self {
        let theta = degrees.clamp(0.0, 60.0).to_radians();
        // With no angle bound the lens is the narrowest one, of `FLAT_ANGLE`: only points within
        // rounding of a subsegment encroach it, as in Triangle (otherwise only a segment hiding
        // a new point from its triangle is split then).
        Encroachment {
            lens_cos2: (theta < std::f64::consts::FRAC_PI_4 && !conforming)
                .then(|| (2.0 * theta).cos().powi(2)),
        }
    }

    /// Whether `w` encroaches the subsegment from `pu` to `pv`: lies in its diametral lens
    /// (without `D`: the subsegment subtends at least 180° − 2θ at `w`, Shewchuk 2002 §3.2,
    /// which inserts fewer vertices; at least 180° − [`FLAT_ANGLE`] whatever θ, so with no
    /// angle bound only points within rounding of it or on it), else strictly inside its
    /// diametral circle.
    pub(super) fn encroaches(&self, pu: Point, pv: Point, w: Point) -> bool {
        let (a, b) = ([pu[0] - w[0], pu[1] - w[1]], [pv[0] - w[0], pv[1] - w[1]]);
        let dot = a[0] * b[0] + a[1] * b[1];
        match self.lens_cos2 {
            Some(cos2) => {
                // The second test is the first one's for the lens of `FLAT_ANGLE`, where the
                // first compares two numbers equal to within rounding: the tangent of the angle
                // by which `w` misses a straight one is |a × b| / |a · b|.
                let cross = a[0] * b[1] - a[1] * b[0];
                dot < 0.0
                    && (dot * dot
                        >= cos2 * (a[0] * a[0] + a[1] * a[1]) * (b[0] * b[0] + b[1] * b[1])
                        || cross * cross <= FLAT_TAN2 * (dot * dot))
            }
            // Exactly: `D` promises every Voronoi vertex inside the triangulation.
            None => diametral_dot(pu, pv, w) < 0.0,
        }
    }

    /// Whether an apex beside the subsegment of half-edge `e`, in the domain, encroaches it (in
    /// a constrained Delaunay triangulation, no other vertex can if these do not).
    pub(super) fn apex_encroaches(&self, mesh: &Mesh, e: EdgeId) -> bool {
        let (pu, pv) = (mesh.point(mesh.origin(e)), mesh.point(mesh.dest(e)));
        [e, mesh.twin(e)].iter().any(|&h| {
            let w = mesh.apex(h);
            w != GHOST && inside(mesh, h.triangle()) && self.encroaches(pu, pv, mesh.point(w))
        })
    }
}

/// The narrowest lens: a point at which a subsegment subtends at least 180° − `FLAT_ANGLE`
/// (radians) encroaches it, whatever the angle bound (so with none, or one below half of
/// this, the lens is this one). Such a point lies within rounding of the subsegment, or on it;
/// inserted as a free vertex, it would make a triangle with an angle of almost 180° that
/// refinement cannot mend. Measured on random equilateral triangles with `pu`: a right
/// triangle standing on a subsegment has its circumcentre at the subsegment's midpoint, which
/// rounding put just inside the domain, where the lens test of no angle (dot² ≥ |a|²·|b|²,
/// two numbers equal to within rounding there) said no; the sliver left (area 10^-18) was
/// bad, its split was blocked by the subsegment, whose split point, the rounded midpoint,
/// was the free vertex's own point: refused, the precision warning. With `a` such a sliver
/// meets the bound and stays (unless smoothing, which `S` and `u` leave out, moves the
/// vertex). The subsegment is split instead, as Ruppert's rule splits it when a point
/// encroaches.
///
/// 2^-26, about the square root of the unit roundoff: the lens test of no angle cannot tell a
/// point that near a subsegment from one on it (at height h over the middle, in units of half
/// the subsegment, its two sides differ by 4h² of themselves), and Triangle, observed, splits
/// the segment where its new point lies within about 2^-27 of that (a circumcentre 5·10^-9
/// over the middle of a base of length 2: the segment's midpoint; 10^-8: a free vertex).
/// This lens, decided on the cross product, has that width without the noise. (On the random
/// triangles, every rounded point it caught lay within 2^-44: a width of 2^-44 gives the same
/// meshes.)
const FLAT_ANGLE: f64 = 1.0 / (1u64 << 26) as f64;
/// tan² [`FLAT_ANGLE`] (to within rounding: 2^-52).
const FLAT_TAN2: f64 = FLAT_ANGLE * FLAT_ANGLE;

/// The Bowyer–Watson cavity of a new point, found to tell which subsegments the point would
/// encroach (its buffers are reused from point to point).
#[derive(Default)]
pub(super) struct Cavity {
    /// The triangles whose circumcircles contain the point.
    triangles: Vec<TriangleId>,
    stack: Vec<TriangleId>,
    /// Per triangle slot: the number of the last cavity it was in (`generation` for this one),
    /// so that membership is one look instead of a scan of `triangles`.
    stamp: Vec<u32>,
    generation: u32,
}

impl Cavity {
    /// The subsegments (`(origin, dest, half-edge)`) that `x` would encroach if inserted at
    /// `location`: those bounding the triangles whose circumcircles contain `x` (the cavity, which
    /// does not cross segments), with `x` inside their diametral lenses or circles.
    pub(super) fn encroached_by<P: Predicates>(
        &mut self,
        mesh: &Mesh,
        encroachment: &Encroachment,
        x: Point,
        location: Location,
    ) -> Vec<(VertexId, VertexId, EdgeId)> {
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.stamp.fill(0);
            self.generation = 1;
        }
        self.stamp.resize(mesh.triangle_count() as usize, 0);
        let generation = self.generation;
        let (stack, seen, stamp) = (&mut self.stack, &mut self.triangles, &mut self.stamp);
        stack.clear();
        seen.clear();
        match location {
            Location::InTriangle(t) | Location::Outside(t) => stack.push(t),
            Location::OnEdge(e) => {
                stack.extend_from_slice(&[e.triangle(), mesh.twin(e).triangle()])
            }
            Location::OnVertex(_) => {}
        }
        seen.extend_from_slice(stack);
        for t in seen.iter() {
            stamp[t.index()] = generation;
        }
        let mut found = Vec::new();
        while let Some(t) = stack.pop() {
            for e in t.edges() {
                if mesh.is_segment(e) {
                    let (u, v) = (mesh.origin(e), mesh.dest(e));
                    if encroachment.encroaches(mesh.point(u), mesh.point(v), x)
                        && !found
                            .iter()
                            .any(|&(a, b, _)| (a, b) == (u, v) || (a, b) == (v, u))
                    {
                        found.push((u, v, e));
                    }
                    continue;
                }
                let n = mesh.twin(e).triangle();
                if stamp[n.index()] == generation || !inside(mesh, n) || mesh.is_ghost(n) {
                    continue;
                }
                let [a, b, c] = mesh.triangle(n).map(|v| mesh.point(v));
                if P::incircle(a, b, c, x) > 0.0 {
                    stamp[n.index()] = generation;
                    seen.push(n);
                    stack.push(n);
                }
            }
        }
        found
    }
}

/// Where to split subsegment `u`–`v` (parameter from `u`): at a power-of-two distance from an
/// end that is an input vertex where segments meet at an acute angle ("concentric shells",
/// Ruppert 1995 §5, Shewchuk 2002 §4.1), from the sharper one if both are; else the midpoint.
/// The powers of two are absolute (2^k, k any integer), the same on every segment around a
/// corner, so that splits on two segments meet on common shells. Returns the parameter and the
/// kind of the new vertex (the corner and the exponent of its distance).
pub(super) fn split_parameter(
    mesh: &Mesh,
    kinds: &[VertexKind],
    u: VertexId,
    v: VertexId,
) -> (f64, VertexKind) {
    let (cu, cv) = (
        sharpest_corner(mesh, kinds, u),
        sharpest_corner(mesh, kinds, v),
    );
    let midpoint = VertexKind::OnSegment {
        corner: VertexId::NONE,
        shell: 0,
    };
    if cu.is_none() && cv.is_none() {
        return (0.5, midpoint);
    }
    let from_u = match (cu, cv) {
        (Some(a), Some(b)) => a >= b,
        (Some(_), None) => true,
        _ => false,
    };
    let (pu, pv) = (mesh.point(u), mesh.point(v));
    let length = ((pv[0] - pu[0]).powi(2) + (pv[1] - pu[1]).powi(2)).sqrt();
    // The power of two 2^k in [length/3, 2·length/3] (there is one: the interval spans a factor
    // of two), the nearest to the midpoint.
    let mut k = (length * 0.5).log2().round() as i32;
    while 2f64.powi(k) > length * (2.0 / 3.0) {
        k -= 1;
    }
    while 2f64.powi(k) < length / 3.0 {
        k += 1;
    }
    let d = 2f64.powi(k);
    if !(d.is_finite() && d > 0.0) {
        return (0.5, midpoint);
    }
    let (t, corner) = if from_u {
        (d / length, u)
    } else {
        (1.0 - d / length, v)
    };
    (t, VertexKind::OnSegment { corner, shell: k })
}

/// How much a split point rounded off a boundary subsegment may cut off the domain or add to it:
/// the sliver between the point and the subsegment, as a fraction of the domain triangle beside
/// the subsegment. Rounding moves a point by about 10^-16 of its coordinates: the sliver is that
/// distance over the triangle's height, which only a triangle less than some 10^-10 of its
/// coordinates high (10^6 roundings) makes larger than 2^-20. In a domain thinner than the rounding
/// of its coordinates every such split is refused unless the point falls exactly on the line.
/// (On the caller's grid in a translated frame, see [`GRID_SLIVER`].)
pub(super) const BOUNDARY_SLIVER: f64 = 1.0 / (1u64 << 20) as f64;

/// A sliver of at most this fraction of the whole domain's area is accepted on any boundary
/// subsegment ([`splits_faithfully`]): rounding moves a point by some 10^-16 of the
/// coordinates, so only a domain less than about 10^-4 of its extent wide (10^12 roundings)
/// sees such slivers add up to a visible part of its area (and a domain thinner than rounding
/// refuses them by [`BOUNDARY_SLIVER`] as before).
pub(super) const NEGLIGIBLE_SLIVER: f64 = 1.0 / (1u64 << 40) as f64;

/// [`BOUNDARY_SLIVER`] on the caller's grid in a translated frame (`Refinement::largest_sliver`):
/// the rounding there is the caller's own, half a unit in the last place of coordinates whose
/// features may be only thousands of units long, as Triangle's plain arithmetic rounds. A
/// sliver up to the area of the triangle beside the subsegment is accepted: only a triangle
/// within a unit in the last place of flat (a boundary running nearly through one of its
/// vertices) has a larger one, and splitting it with a point off the line would leave another
/// as flat beside it. (An eighth was too little: on 500 random points at 10^12 of side 1, two
/// hull subsegments stayed whole at 29.7° where Triangle reaches 30°.)
pub(super) const GRID_SLIVER: f64 = 1.0;

/// Whether `p`, the rounded split point of the subsegment of half-edge `e`, splits it faithfully:
/// - every triangle beside the subsegment splits into two counter-clockwise triangles (exact
///   orientation: `p` lies strictly inside the union of the two triangles beside it, so it is on
///   no existing vertex and no other edge);
/// - on a boundary subsegment (the domain on one side only), the sliver between `p` and the
///   subsegment (twice its area) is at most `negligible`, or at most `largest_sliver` of the
///   domain triangle beside it, on whichever side `p` was rounded to. Rounded outward, `p`
///   would widen the domain; rounded inward, it would narrow it; in a domain thinner than the
///   rounding of its coordinates either changes its area by a large fraction (exactly on the
///   line, `p` changes nothing). `negligible` is [`NEGLIGIBLE_SLIVER`] of the whole domain: a
///   triangle beside the boundary may be as thin as a few units in the last place where two
///   vertices are that close (Triangle splits there, and so must we to meet θ), while the
///   domain, unless it is itself that thin, does not notice.
///
/// The domain's area thus changes by at most that fraction of the triangles split at its
/// boundary, or of itself.
pub(super) fn splits_faithfully<P: Predicates>(
    mesh: &Mesh,
    e: EdgeId,
    p: Point,
    largest_sliver: f64,
    negligible: f64,
) -> bool {
    let sides = [e, mesh.twin(e)];
    let in_domain = sides.map(|h| mesh.apex(h) != GHOST && inside(mesh, h.triangle()));
    let splits_cleanly = sides.iter().all(|&h| {
        let w = mesh.apex(h);
        let (a, b) = (mesh.point(mesh.origin(h)), mesh.point(mesh.dest(h)));
        w == GHOST
            || (P::orient2d(a, p, mesh.point(w)) > 0.0 && P::orient2d(p, b, mesh.point(w)) > 0.0)
    });
    if !splits_cleanly {
        return false;
    }
    if in_domain[0] == in_domain[1] {
        return true; // inside the domain or outside it: its area stays the same
    }
    let h = if in_domain[0] { sides[0] } else { sides[1] };
    let (a, b) = (mesh.point(mesh.origin(h)), mesh.point(mesh.dest(h)));
    let sliver = P::orient2d(a, b, p).abs();
    sliver == 0.0
        || sliver <= negligible
        || sliver <= largest_sliver * P::orient2d(a, b, mesh.point(mesh.apex(h)))
}

/// For an input vertex `x` where two segments meet at less than 90°: the cosine of the smallest
/// such angle (larger is sharper). `None` for vertices inserted by refinement and for vertices
/// whose segments meet at right or obtuse angles only. The smallest angle is between two
/// segments consecutive around `x`, so one turn around it suffices.
fn sharpest_corner(mesh: &Mesh, kinds: &[VertexKind], x: VertexId) -> Option<f64> {
    if matches!(kinds[x.index()], VertexKind::OnSegment { .. }) {
        return None;
    }
    let o = mesh.point(x);
    let direction = |e: EdgeId| {
        let p = mesh.point(mesh.dest(e));
        let d = [p[0] - o[0], p[1] - o[1]];
        let length = (d[0] * d[0] + d[1] * d[1]).sqrt();
        [d[0] / length, d[1] / length]
    };
    let (mut first, mut previous): (Option<Point>, Option<Point>) = (None, None);
    let mut sharpest: Option<f64> = None;
    let mut consider = |a: Point, b: Point| {
        let cos = a[0] * b[0] + a[1] * b[1];
        if cos > 0.0 && sharpest.is_none_or(|s| cos > s) {
            sharpest = Some(cos);
        }
    };
    for e in mesh.star(x).filter(|&e| mesh.is_segment(e)) {
        let d = direction(e);
        match previous {
            Some(p) => consider(p, d),
            None => first = Some(d),
        }
        previous = Some(d);
    }
    if let (Some(a), Some(b)) = (first, previous) {
        if a != b {
            consider(b, a);
        }
    }
    sharpest
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn with_no_angle_bound_only_points_within_the_flat_angle_encroach() {
        let lens = Encroachment::new(0.0, false);
        let (u, v) = ([0.0, 0.0], [1.0, 0.0]);
        // Height h over the middle: the point misses a straight angle by about 4h.
        let at = |h: f64| [0.5, h];
        assert!(lens.encroaches(u, v, at(0.0)));
        assert!(lens.encroaches(u, v, at(1e-17)));
        assert!(lens.encroaches(u, v, at(-1e-17)));
        assert!(lens.encroaches(u, v, at(FLAT_ANGLE / 8.0)));
        assert!(!lens.encroaches(u, v, at(FLAT_ANGLE / 2.0)));
        assert!(!lens.encroaches(u, v, at(1e-3)));
        // Beyond an end the subsegment subtends no angle.
        assert!(!lens.encroaches(u, v, [1.5, 1e-17]));
        assert!(!lens.encroaches(u, v, [-0.5, 0.0]));
    }

    /// The report's case: a right triangle's circumcentre rounded onto the midpoint of a tilted
    /// subsegment, where the lens test of no angle (dot² ≥ |a|²·|b|²) said no by rounding.
    #[test]
    fn a_rounded_midpoint_of_a_tilted_subsegment_encroaches_it() {
        let (u, v) = (
            [0.8877063386411908, -1.7064211995971514],
            [0.4113453212579926, -1.5544995713882477],
        );
        let w = [0.6495258299495916, -1.6304603854926996];
        assert!(Encroachment::new(0.0, false).encroaches(u, v, w));
        assert!(Encroachment::new(20.0, false).encroaches(u, v, w));
        assert!(Encroachment::new(0.0, true).encroaches(u, v, w));
    }

    /// The lens of an angle bound is the same as without the flat floor: the floor lies inside it.
    #[test]
    fn an_angle_bound_keeps_its_lens() {
        let lens = Encroachment::new(20.0, false);
        let (u, v) = ([0.0, 0.0], [1.0, 0.0]);
        // The lens of 20°: the subsegment subtends at least 140°, at height tan(20°) / 2 over
        // the middle.
        let edge = 0.5 * 20f64.to_radians().tan();
        assert!(lens.encroaches(u, v, [0.5, edge * 0.999]));
        assert!(!lens.encroaches(u, v, [0.5, edge * 1.001]));
    }
}
