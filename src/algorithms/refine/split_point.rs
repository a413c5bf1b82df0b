//! Bad triangles by their angles and where a bad triangle is split: the angle test with
//! Triangle's small-angle exemption, and the split point (circumcentre or Üngör's off-centre).

use super::VertexKind;
use crate::geometry::{circumcenter, frame_coordinates, Point};
use crate::mesh::{Mesh, VertexId};

/// Two distances from a corner are equal (for the small-angle exemption of vertices not on one
/// concentric shell: midpoints, or shells around two corners) within this fraction. Measured:
/// a tolerance of 10^-9 (rounding only) makes 10% more triangles than Triangle near input angles
/// of hundredths of a degree (random star polygons), 10^-3 as many as Triangle.
const EQUAL_DISTANCE_TOLERANCE: f64 = 1e-3;

/// The angle bound θ: which triangles are skinny, and where they are split.
#[derive(Clone, Copy, Debug)]
pub(super) struct AngleBound {
    /// cos² θ (2 when there is no bound: no triangle is skinny).
    cos2_min_angle: f64,
    /// Off-centre distance from the shortest edge, as a multiple of its length.
    off_center: f64,
}

impl AngleBound {
    /// For θ = `degrees`.
    pub(super) fn new(degrees: f64) -> Self {
        let theta = degrees.clamp(0.0, 60.0).to_radians();
        let cos = theta.cos();
        AngleBound {
            cos2_min_angle: if theta > 0.0 { cos * cos } else { 2.0 },
            off_center: if theta > 0.0 {
                0.475 * ((1.0 + cos) / (1.0 - cos)).sqrt()
            } else {
                f64::INFINITY
            },
        }
    }

    /// sin² θ (0 when there is no bound).
    pub(super) fn sin2(&self) -> f64 {
        (1.0 - self.cos2_min_angle).max(0.0)
    }

    /// If triangle `corners` (at `points`) has an angle below θ and is not excused by
    /// [`Self::is_excused_by_small_input_angle`]: the squared length of its shortest edge.
    /// `ends`: the ends of each segment id, as given.
    pub(super) fn skinny(
        &self,
        mesh: &Mesh,
        kinds: &[VertexKind],
        ends: &[(VertexId, VertexId)],
        [a, b, c]: [VertexId; 3],
        [pa, pb, pc]: [Point; 3],
    ) -> Option<f64> {
        if self.cos2_min_angle > 1.0 {
            return None;
        }
        let sq = |p: Point, q: Point| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
        let (lab, lbc, lca) = (sq(pa, pb), sq(pb, pc), sq(pc, pa));
        // The shortest edge (u, v), its opposite corner, and the squared lengths of the others.
        let (apex, u, v, l1, l2) = if lab <= lbc && lab <= lca {
            (c, a, b, lca, lbc)
        } else if lbc <= lca {
            (a, b, c, lab, lca)
        } else {
            (b, c, a, lbc, lab)
        };
        // The smallest angle is the one opposite the shortest edge; compared through cos².
        let (o, p, q) = (mesh.point(apex), mesh.point(u), mesh.point(v));
        let dot = (p[0] - o[0]) * (q[0] - o[0]) + (p[1] - o[1]) * (q[1] - o[1]);
        let cos2 = if dot > 0.0 {
            dot * dot / (l1 * l2)
        } else {
            0.0
        };
        (cos2 > self.cos2_min_angle
            && !self.is_excused_by_small_input_angle(mesh, kinds, ends, u, v))
        .then(|| lab.min(lbc).min(lca))
    }

    /// Whether a skinny triangle whose shortest edge is `u`–`v` is excused from splitting by
    /// Triangle's rule for small input angles (its manual on `-q`; Shewchuk 2002, §3.6; the
    /// "seditious edges" of Shewchuk 2000, "Mesh generation for domains with small angles"): `u`
    /// and `v` were put by refinement on two different segments that meet at a common vertex (a
    /// shared endpoint or their crossing) at less than θ, at equal distances from it. That is
    /// what concentric-shell splitting makes around a small input angle; splitting such a
    /// triangle would only cut the angle into ever smaller slivers. Nothing else is excused: a
    /// skinny triangle at an input angle whose sides along the two segments differ gets split,
    /// its split point encroaches the longer side, which is split on a shell until the excused
    /// configuration is reached (Ruppert 1995, §5).
    fn is_excused_by_small_input_angle(
        &self,
        mesh: &Mesh,
        kinds: &[VertexKind],
        ends: &[(VertexId, VertexId)],
        u: VertexId,
        v: VertexId,
    ) -> bool {
        let (
            VertexKind::OnSegment {
                corner: cu,
                shell: su,
            },
            VertexKind::OnSegment {
                corner: cv,
                shell: sv,
            },
        ) = (kinds[u.index()], kinds[v.index()])
        else {
            return false;
        };
        let (p, q) = (mesh.point(u), mesh.point(v));
        // Two segments meeting at `o` at less than θ (which also tells the two segments apart:
        // pieces of one segment on either side of `o` meet at 180°). Around a wider corner the
        // shells need no excuse: the triangles between them can be split (measured on
        // Triangle's behaviour, which refines them too).
        let narrow = |o: Point| {
            let (a, b) = ([p[0] - o[0], p[1] - o[1]], [q[0] - o[0], q[1] - o[1]]);
            let dot = a[0] * b[0] + a[1] * b[1];
            let (dp, dq) = (a[0] * a[0] + a[1] * a[1], b[0] * b[0] + b[1] * b[1]);
            dot > 0.0 && dot * dot > self.cos2_min_angle * dp * dq
        };
        // Both on the same concentric shell around the same corner: the distances are the same
        // power of two by construction, whatever the rounding of the points.
        if cu == cv && cu != VertexId::NONE && su == sv {
            return narrow(mesh.point(cu));
        }
        // Otherwise (midpoints, or shells around different corners), the common vertex of the
        // two segments as given, and equal distances within rounding.
        let (Some(segment_u), Some(segment_v)) =
            (segment_through(mesh, u), segment_through(mesh, v))
        else {
            return false;
        };
        let (ends_u, ends_v) = (ends[segment_u as usize], ends[segment_v as usize]);
        if segment_u == segment_v || ends_u.0 == VertexId::NONE || ends_v.0 == VertexId::NONE {
            return false;
        }
        let common = [ends_u.0, ends_u.1]
            .into_iter()
            .find(|&w| w == ends_v.0 || w == ends_v.1)
            .map(|w| mesh.point(w))
            .or_else(|| {
                crossing_point(
                    [ends_u.0, ends_u.1].map(|w| mesh.point(w)),
                    [ends_v.0, ends_v.1].map(|w| mesh.point(w)),
                )
            });
        let Some(o) = common else {
            return false;
        };
        let distance = |x: Point| (x[0] - o[0]).hypot(x[1] - o[1]);
        let (dp, dq) = (distance(p), distance(q));
        (dp - dq).abs() <= EQUAL_DISTANCE_TOLERANCE * dp.max(dq) && narrow(o)
    }

    /// The point where a bad triangle at `[a, b, c]` is split: its circumcentre, or Üngör's
    /// off-centre on the bisector of its shortest edge when that is nearer to the edge. Also its
    /// affine frame coordinates in the triangle, for interpolating attributes.
    pub(super) fn split_point(&self, [a, b, c]: [Point; 3]) -> (Point, f64, f64) {
        let (centre, xi, eta) = circumcenter(a, b, c);
        if !self.off_center.is_finite() {
            return (centre, xi, eta);
        }
        let sq = |p: Point, q: Point| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
        let (p, q) = if sq(a, b) <= sq(b, c) && sq(a, b) <= sq(c, a) {
            (a, b)
        } else if sq(b, c) <= sq(c, a) {
            (b, c)
        } else {
            (c, a)
        };
        let mid = [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])];
        // The bisector toward the triangle (left of p→q, the counter-clockwise side).
        let normal = [-(q[1] - p[1]), q[0] - p[0]];
        let off = [
            mid[0] + self.off_center * normal[0],
            mid[1] + self.off_center * normal[1],
        ];
        if sq(off, mid) < sq(centre, mid) {
            let (xi, eta) = frame_coordinates([a, b, c], off);
            (off, xi, eta)
        } else {
            (centre, xi, eta)
        }
    }
}

/// The id of a segment that vertex `v` lies on, if any.
fn segment_through(mesh: &Mesh, v: VertexId) -> Option<u32> {
    mesh.star(v)
        .find(|&e| mesh.is_segment(e))
        .map(|e| mesh.segment_of(e))
}

/// Where segments `a` and `b` cross (in floating point), if they do.
fn crossing_point(a: [Point; 2], b: [Point; 2]) -> Option<Point> {
    let d = [a[1][0] - a[0][0], a[1][1] - a[0][1]];
    let e = [b[1][0] - b[0][0], b[1][1] - b[0][1]];
    let denominator = d[0] * e[1] - d[1] * e[0];
    if denominator == 0.0 {
        return None;
    }
    let f = [b[0][0] - a[0][0], b[0][1] - a[0][1]];
    let s = (f[0] * e[1] - f[1] * e[0]) / denominator;
    let t = (f[0] * d[1] - f[1] * d[0]) / denominator;
    ((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t))
        .then(|| [a[0][0] + s * d[0], a[0][1] + s * d[1]])
}
