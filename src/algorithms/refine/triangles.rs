//! Bad triangles: the quality test with Triangle's small-angle exemption, the split point
//! (circumcentre or Üngör's off-centre), the walk that locates it, and Ruppert's rule (a point
//! that would encroach a subsegment is rejected and the subsegment split instead).

use super::*;

impl<P: Predicates> Refiner<'_, '_, P> {
    /// Queues triangle `t` if it is bad.
    pub(super) fn check_triangle(&mut self, t: u32) {
        let mesh = self.cdt.mesh().raw();
        let [a, b, c] = mesh.triangle(t);
        let [pa, pb, pc] = [a, b, c].map(|v| mesh.point(v));
        let area = 0.5 * P::orient2d(pa, pb, pc);
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
        let shortest = lab.min(lbc).min(lca);
        // Angle: the smallest angle is the one opposite the shortest edge; compared through cos².
        let skinny = self.cos2_min_angle <= 1.0 && {
            let (o, p, q) = (mesh.point(apex), mesh.point(u), mesh.point(v));
            let dot = (p[0] - o[0]) * (q[0] - o[0]) + (p[1] - o[1]) * (q[1] - o[1]);
            let cos2 = if dot > 0.0 {
                dot * dot / (l1 * l2)
            } else {
                0.0
            };
            cos2 > self.cos2_min_angle && !self.is_excused_by_small_input_angle(u, v)
        };
        let bad = skinny || {
            let regional = if self.quality.variable_area {
                self.domain
                    .max_area
                    .get(mesh.tag(t) as usize)
                    .copied()
                    .unwrap_or(-1.0)
            } else {
                -1.0
            };
            let too_big = self.quality.max_area.is_some_and(|m| area > m)
                || (regional > 0.0 && area > regional);
            too_big
                || self
                    .quality
                    .user_test
                    .is_some_and(|f| f(pa[0], pa[1], pb[0], pb[1], pc[0], pc[1], area))
        };
        if bad {
            let bucket = if skinny {
                BadQueue::skinny_bucket(shortest / self.extent2)
            } else {
                BadQueue::SIZE_BUCKET
            };
            self.bad.push(BadTriangle {
                bucket,
                corners: [a, b, c],
            });
        }
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
    pub(super) fn is_excused_by_small_input_angle(&self, u: u32, v: u32) -> bool {
        let (
            VertexKind::OnSegment {
                corner: cu,
                shell: su,
            },
            VertexKind::OnSegment {
                corner: cv,
                shell: sv,
            },
        ) = (self.kinds[u as usize], self.kinds[v as usize])
        else {
            return false;
        };
        let (p, q) = (self.pt(u), self.pt(v));
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
        if cu == cv && cu != NONE && su == sv {
            return narrow(self.pt(cu));
        }
        // Otherwise (midpoints, or shells around different corners), the common vertex of the
        // two segments as given, and equal distances within rounding.
        let (Some(segment_u), Some(segment_v)) = (self.segment_through(u), self.segment_through(v))
        else {
            return false;
        };
        let (ends_u, ends_v) = (
            self.cdt.ends[segment_u as usize],
            self.cdt.ends[segment_v as usize],
        );
        if segment_u == segment_v || ends_u.0 == NONE || ends_v.0 == NONE {
            return false;
        }
        let common = [ends_u.0, ends_u.1]
            .into_iter()
            .find(|&w| w == ends_v.0 || w == ends_v.1)
            .map(|w| self.pt(w))
            .or_else(|| {
                crossing_point(
                    [ends_u.0, ends_u.1].map(|w| self.pt(w)),
                    [ends_v.0, ends_v.1].map(|w| self.pt(w)),
                )
            });
        let Some(o) = common else {
            return false;
        };
        let distance = |x: Point| (x[0] - o[0]).hypot(x[1] - o[1]);
        let (dp, dq) = (distance(p), distance(q));
        (dp - dq).abs() <= EQUAL_DISTANCE_TOLERANCE * dp.max(dq) && narrow(o)
    }

    /// The id of a segment that vertex `v` lies on, if any.
    pub(super) fn segment_through(&self, v: u32) -> Option<u32> {
        let mesh = self.cdt.mesh().raw();
        let start = mesh.vertex_edge(v);
        let mut e = start;
        loop {
            if mesh.is_segment(e) {
                return Some(mesh.segment_of(e));
            }
            e = mesh.twin(prev(e));
            if e == start {
                return None;
            }
        }
    }

    /// The point where a bad triangle is split: its circumcentre, or Üngör's off-centre on the
    /// bisector of its shortest edge when that is nearer to the edge. Also its affine frame
    /// coordinates in the triangle, for interpolating attributes.
    pub(super) fn split_point(&self, corners: [u32; 3]) -> (Point, f64, f64) {
        let [a, b, c] = corners.map(|v| self.pt(v));
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
            // Frame coordinates of the off-centre in triangle (a, b, c).
            let det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
            let (dx, dy) = (off[0] - a[0], off[1] - a[1]);
            let xi = (dx * (c[1] - a[1]) - dy * (c[0] - a[0])) / det;
            let eta = ((b[0] - a[0]) * dy - (b[1] - a[1]) * dx) / det;
            (off, xi, eta)
        } else {
            (centre, xi, eta)
        }
    }

    pub(super) fn split_triangle(&mut self, t: u32, bad: BadTriangle) {
        let corners = self.cdt.mesh().raw().triangle(t);
        let (x, xi, eta) = self.split_point(corners);
        if !(x[0].is_finite() && x[1].is_finite()) {
            return;
        }
        match self.walk(t, x) {
            Walk::Lost => self.skipped += 1,
            Walk::Blocked(s) => {
                // A segment hides the new point from the triangle: the point may not be
                // inserted, and the segment is split instead (Ruppert's rule; with lenses the
                // point need not lie in its diametral circle).
                let mesh = self.cdt.mesh().raw();
                let segment = (mesh.origin(s), mesh.dest(s), s);
                self.split_instead(&[segment], bad);
            }
            Walk::Found(location) => {
                if let Location::OnVertex(_) = location {
                    self.skipped += 1; // precision exhausted here
                    return;
                }
                let mut encroached = self.encroached_by(x, location);
                // Subsegments that `Y`/`YY` keep whole cannot be protected by splitting them:
                // the point goes in all the same if it makes no triangle worse than the bad one
                // (else the triangles along such a boundary could never improve), and the mesh
                // stays constrained Delaunay.
                let kept_whole = encroached.iter().any(|&(_, _, e)| !self.may_split(e));
                encroached.retain(|&(_, _, e)| self.may_split(e));
                if !encroached.is_empty() {
                    self.split_instead(&encroached, bad);
                    return;
                }
                if kept_whole
                    && self.worst_triangle_made(x) < min_angle_sin2(corners.map(|v| self.pt(v)))
                {
                    self.kept_whole += 1;
                    return;
                }
                if self.too_close(x, location) {
                    self.skipped += 1;
                    return;
                }
                let [a, b, c] = corners;
                let vertex = self.new_vertex(x, VertexKind::Free, |attrs, (i, k)| {
                    let (va, vb, vc) = (
                        attrs[a as usize * k + i],
                        attrs[b as usize * k + i],
                        attrs[c as usize * k + i],
                    );
                    va + xi * (vb - va) + eta * (vc - va)
                });
                let _ = self.cdt.insert_at(VertexId::new(vertex), location);
                self.after_insertion(vertex);
            }
        }
    }

    /// Splits the given subsegments (`(origin, dest, half-edge)`) instead of a bad triangle whose
    /// split point encroaches on them, and queues the triangle again to be reconsidered. Only if
    /// some subsegment was split: otherwise the triangle is left as it is, so that every time a
    /// triangle is queued again refinement has made progress.
    pub(super) fn split_instead(&mut self, subsegments: &[(u32, u32, u32)], bad: BadTriangle) {
        for &(u, v, e) in subsegments {
            if self.may_split(e) && !self.unsplittable.contains(&(u.min(v), u.max(v))) {
                self.encroached.push_back((u, v, true));
            }
        }
        if self.split_encroached() > 0 {
            self.bad.push(bad);
        } else if subsegments.iter().all(|&(_, _, e)| !self.may_split(e)) {
            self.kept_whole += 1;
        } else {
            self.skipped += 1;
        }
    }

    /// Whether `x`, at `location`, would make an edge shorter than the floor.
    pub(super) fn too_close(&self, x: Point, location: Location) -> bool {
        let mesh = self.cdt.mesh().raw();
        let triangles = match location {
            Location::InTriangle(t) | Location::Outside(t) => [t.raw(), t.raw()],
            Location::OnEdge(e) => [triangle_of(e.raw()), triangle_of(mesh.twin(e.raw()))],
            Location::OnVertex(_) => return true,
        };
        triangles
            .iter()
            .flat_map(|&t| mesh.triangle(t))
            .filter(|&v| v != GHOST)
            .any(|v| {
                let p = mesh.point(v);
                (p[0] - x[0]).powi(2) + (p[1] - x[1]).powi(2) < self.floor2
            })
    }

    /// Walks in a straight line from the centroid of triangle `t` to `x`, staying in the domain.
    pub(super) fn walk(&self, t: u32, x: Point) -> Walk {
        let mesh = self.cdt.mesh().raw();
        let [a, b, c] = mesh.triangle(t).map(|v| mesh.point(v));
        let g = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0];
        let mut t = t;
        let mut entry = NONE;
        for _ in 0..mesh.triangle_count() + 3 {
            // The edge through which the ray g→x leaves t (u right of the ray, v left of it).
            let mut exit = NONE;
            for e in 3 * t..3 * t + 3 {
                if e == entry {
                    continue;
                }
                let (u, v) = (mesh.point(mesh.origin(e)), mesh.point(mesh.dest(e)));
                if P::orient2d(g, x, u) <= 0.0 && P::orient2d(g, x, v) > 0.0 {
                    exit = e;
                    break;
                }
            }
            if exit == NONE {
                // No edge crosses the ray: it is too short to have a direction (x is the
                // centroid, as for an equilateral triangle's circumcentre), or degenerate.
                return self.walk_ends_in(t, x).unwrap_or(Walk::Lost);
            }
            let (u, v) = (mesh.point(mesh.origin(exit)), mesh.point(mesh.dest(exit)));
            let side = P::orient2d(u, v, x);
            if side > 0.0 {
                return Walk::Found(Location::InTriangle(TriangleId::new(t)));
            }
            if side == 0.0 {
                // On the exit edge (or its line beyond the triangle, which the ray rules out).
                if mesh.is_segment(exit) {
                    return Walk::Blocked(exit);
                }
                for w in [mesh.origin(exit), mesh.dest(exit)] {
                    if mesh.point(w) == x {
                        return Walk::Found(Location::OnVertex(VertexId::new(w)));
                    }
                }
                return Walk::Found(Location::OnEdge(EdgeId::new(exit)));
            }
            if mesh.is_segment(exit) {
                return Walk::Blocked(exit);
            }
            let f = mesh.twin(exit);
            let next_t = triangle_of(f);
            if !self.inside(next_t) || mesh.is_ghost(next_t) {
                return Walk::Lost;
            }
            t = next_t;
            entry = f;
        }
        Walk::Lost
    }

    /// Where `x` lies in triangle `t`, if it lies in it (closed): in it, on an edge (a segment
    /// hides nothing then, but a point on a segment splits it: `Blocked`), or on a vertex.
    pub(super) fn walk_ends_in(&self, t: u32, x: Point) -> Option<Walk> {
        let mesh = self.cdt.mesh().raw();
        let sides = [0, 1, 2].map(|i| {
            let e = 3 * t + i;
            P::orient2d(mesh.point(mesh.origin(e)), mesh.point(mesh.dest(e)), x)
        });
        if sides.iter().any(|&side| side < 0.0) {
            return None;
        }
        let on: Vec<u32> = (0..3)
            .filter(|&i| sides[i as usize] == 0.0)
            .map(|i| 3 * t + i)
            .collect();
        Some(match on[..] {
            [] => Walk::Found(Location::InTriangle(TriangleId::new(t))),
            [e] if mesh.is_segment(e) => Walk::Blocked(e),
            [e] => Walk::Found(Location::OnEdge(EdgeId::new(e))),
            // On two edges: at their common corner.
            _ => mesh
                .triangle(t)
                .into_iter()
                .find(|&w| mesh.point(w) == x)
                .map_or(Walk::Lost, |w| {
                    Walk::Found(Location::OnVertex(VertexId::new(w)))
                }),
        })
    }

    /// The subsegments that `x` would encroach if inserted at `location`: those bounding the
    /// triangles whose circumcircles contain `x` (the Bowyer–Watson cavity, which does not cross
    /// segments), with `x` inside their diametral circles.
    pub(super) fn encroached_by(&mut self, x: Point, location: Location) -> Vec<(u32, u32, u32)> {
        let mut stack = std::mem::take(&mut self.cavity_stack);
        let mut seen = std::mem::take(&mut self.cavity);
        stack.clear();
        seen.clear();
        let mesh = self.cdt.mesh().raw();
        match location {
            Location::InTriangle(t) | Location::Outside(t) => stack.push(t.raw()),
            Location::OnEdge(e) => {
                stack.extend_from_slice(&[triangle_of(e.raw()), triangle_of(mesh.twin(e.raw()))])
            }
            Location::OnVertex(_) => {}
        }
        seen.extend_from_slice(&stack);
        let mut found = Vec::new();
        while let Some(t) = stack.pop() {
            for e in 3 * t..3 * t + 3 {
                if mesh.is_segment(e) {
                    let (u, v) = (mesh.origin(e), mesh.dest(e));
                    if self.encroaches(u, v, x)
                        && !found
                            .iter()
                            .any(|&(a, b, _)| (a, b) == (u, v) || (a, b) == (v, u))
                    {
                        found.push((u, v, e));
                    }
                    continue;
                }
                let n = triangle_of(mesh.twin(e));
                if seen.contains(&n) || !self.inside(n) || mesh.is_ghost(n) {
                    continue;
                }
                let [a, b, c] = mesh.triangle(n).map(|v| mesh.point(v));
                if P::incircle(a, b, c, x) > 0.0 {
                    seen.push(n);
                    stack.push(n);
                }
            }
        }
        self.cavity_stack = stack;
        self.cavity = seen;
        found
    }

    /// The quality ([`min_angle_sin2`]) of the worst triangle that inserting `x` makes: `x`
    /// joined to the edges around the cavity that [`Self::encroached_by`] found for it.
    pub(super) fn worst_triangle_made(&self, x: Point) -> f64 {
        let mesh = self.cdt.mesh().raw();
        let mut worst = f64::INFINITY;
        for &t in &self.cavity {
            for e in 3 * t..3 * t + 3 {
                if !mesh.is_segment(e) && self.cavity.contains(&triangle_of(mesh.twin(e))) {
                    continue;
                }
                worst = worst.min(min_angle_sin2([
                    mesh.point(mesh.origin(e)),
                    mesh.point(mesh.dest(e)),
                    x,
                ]));
            }
        }
        worst
    }
}

/// Where segments `a` and `b` cross (in floating point), if they do.
pub(super) fn crossing_point(a: [Point; 2], b: [Point; 2]) -> Option<Point> {
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

/// The squared sine of the smallest angle of triangle (a, b, c), which grows with that angle
/// (at most 60°): twice the area over the product of the two longest edges is the sine of the
/// angle between them, the one opposite the shortest edge.
pub(super) fn min_angle_sin2([a, b, c]: [Point; 3]) -> f64 {
    let sq = |p: Point, q: Point| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
    let (ab, bc, ca) = (sq(a, b), sq(b, c), sq(c, a));
    let cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    let longest_two = ab * bc * ca / ab.min(bc).min(ca);
    if longest_two > 0.0 {
        cross * cross / longest_two
    } else {
        0.0
    }
}
