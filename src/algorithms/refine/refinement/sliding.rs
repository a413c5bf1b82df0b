//! Sliding: a vertex that refinement put on a segment is moved along the segment, between its
//! two neighbours there, where its star's smallest angle is larger (the one-dimensional
//! counterpart of the smoothing in [`super::improvement`]; optimization-based smoothing of
//! boundary vertices along their curve, Freitag and Ollivier-Gooch 1997).
//!
//! A move is made only if it raises the smallest angle of the star by [`GAIN`] to at least the
//! mesh's floor, every real triangle of the star stays counter-clockwise, neither subsegment
//! beside the vertex becomes encroached by a vertex of the star, no subsegment of the link is
//! encroached by the vertex, and the area bounds hold. The new place is rounded as any split
//! point is; its attributes are interpolated along the segment again.

use super::improvement::{star_min_sin2, GAIN, MARGIN};
use super::{Refinement, VertexKind};
use crate::geometry::{Point, Predicates};
use crate::mesh::{TriangleId, VertexId, GHOST};

/// The one-dimensional search: its first step (a fraction of the distance to the nearer
/// neighbour), its last (a fraction of the first) and its most evaluations.
const FIRST_STEP: f64 = 0.25;
const LAST_STEP: f64 = 1.0 / 1024.0;
const EVALUATIONS: usize = 64;

impl<P: Predicates> Refinement<'_, '_, P> {
    /// Slides vertex `w`, put on a segment by refinement, along it (see the module
    /// documentation). `link`: scratch space. Whether it moved.
    pub(super) fn try_sliding(
        &mut self,
        w: VertexId,
        floor: f64,
        link: &mut Vec<(Point, Point, bool)>,
    ) -> bool {
        if self.polling.poll(self.work, || 0)
            || !matches!(self.kinds[w.index()], VertexKind::OnSegment { .. })
        {
            return false;
        }
        let mesh = self.mesh();
        let Some([a, b]) = mesh.segment_neighbours(w) else {
            return false;
        };
        let Some(t) = mesh
            .star(w)
            .map(|e| e.triangle())
            .find(|&t| !mesh.is_ghost(t))
        else {
            return false;
        };
        link.clear();
        link.extend(
            mesh.star(w)
                .filter(|&e| mesh.dest(e) != GHOST && mesh.apex(e) != GHOST)
                .map(|e| {
                    let (x, y) = (mesh.dest(e), mesh.apex(e));
                    (mesh.point(x), mesh.point(y), mesh.is_segment(e.next()))
                }),
        );
        let (pa, pb, pw) = (mesh.point(a), mesh.point(b), mesh.point(w));
        let d = [pb[0] - pa[0], pb[1] - pa[1]];
        let length2 = d[0] * d[0] + d[1] * d[1];
        if length2 == 0.0 {
            return false;
        }
        let t0 = ((pw[0] - pa[0]) * d[0] + (pw[1] - pa[1]) * d[1]) / length2;
        let old = star_min_sin2(pw, link);
        let at = |s: f64| self.placed([pa[0] + s * d[0], pa[1] + s * d[1]]);
        let value = |p: Point| {
            if p != pw && self.may_slide_to(p, pa, pb, t, link) {
                star_min_sin2(p, link)
            } else {
                -1.0
            }
        };
        let (mut best, mut best_t, mut best_value) = (pw, t0, old);
        let mut step = FIRST_STEP * t0.min(1.0 - t0);
        let last = LAST_STEP * step;
        let mut evaluations = 0;
        while step >= last && step > 0.0 && evaluations < EVALUATIONS {
            let mut moved = false;
            for s in [best_t + step, best_t - step] {
                if !(0.0 < s && s < 1.0) {
                    continue;
                }
                let p = at(s);
                let v = value(p);
                evaluations += 1;
                if v > best_value {
                    (best, best_t, best_value, moved) = (p, s, v, true);
                    break;
                }
            }
            if !moved {
                step *= 0.5;
            }
        }
        if !(best_value > old * (1.0 + GAIN) && best_value >= floor * (1.0 + MARGIN)) {
            return false;
        }
        if !self.cdt.move_vertex(w, best) {
            return false;
        }
        self.attributes.set_on_segment(w, a, b, best_t);
        true
    }

    /// Whether the vertex between `pa` and `pb` on a segment, with the real triangles of its
    /// star `link` (in triangle `t`'s region), may go to `p`: every triangle of the star stays
    /// counter-clockwise, no vertex of the link encroaches the subsegments `pa`–`p` and
    /// `p`–`pb`, `p` encroaches no subsegment of the link, the area bounds hold.
    fn may_slide_to(
        &self,
        p: Point,
        pa: Point,
        pb: Point,
        t: TriangleId,
        link: &[(Point, Point, bool)],
    ) -> bool {
        link.iter().all(|&(x, y, segment)| {
            P::orient2d(p, x, y) > 0.0
                && !(segment && self.encroachment.encroaches(x, y, p))
                && [x, y].iter().all(|&z| {
                    z == pa
                        || z == pb
                        || !(self.encroachment.encroaches(pa, p, z)
                            || self.encroachment.encroaches(p, pb, z))
                })
                && !self.too_big(t, [p, x, y])
        })
    }
}
