//! Encroached subsegments (diametral lenses, or circles with `D`) and where a subsegment is
//! split: its midpoint, or a concentric shell around an acute input corner (Ruppert 1995 §5,
//! Shewchuk 2002 §4.1).

use super::*;

impl<P: Predicates> Refiner<'_, '_, P> {
    /// Whether the segment of half-edge `e` may receive Steiner points (`Y`, `YY`).
    pub(super) fn may_split(&self, e: u32) -> bool {
        let mesh = self.cdt.mesh().raw();
        match self.quality.no_steiner_on_segments {
            0 => true,
            1 => self.inside(triangle_of(e)) && self.inside(triangle_of(mesh.twin(e))),
            _ => false,
        }
    }

    /// Whether `w` encroaches subsegment `u`–`v`: lies in its diametral lens (without `D`:
    /// `u`–`v` subtends at least 180° − 2θ at `w`, Shewchuk 2002 §3.2, which inserts fewer
    /// vertices; with no angle bound, never), else strictly inside its diametral circle.
    pub(super) fn encroaches(&self, u: u32, v: u32, w: Point) -> bool {
        let (pu, pv) = (self.pt(u), self.pt(v));
        let (a, b) = ([pu[0] - w[0], pu[1] - w[1]], [pv[0] - w[0], pv[1] - w[1]]);
        let dot = a[0] * b[0] + a[1] * b[1];
        match self.lens_cos2 {
            Some(cos2) => {
                dot < 0.0
                    && dot * dot >= cos2 * (a[0] * a[0] + a[1] * a[1]) * (b[0] * b[0] + b[1] * b[1])
            }
            None => dot < 0.0,
        }
    }

    /// Queues the subsegment of half-edge `e` if an apex beside it encroaches it.
    pub(super) fn check_segment(&mut self, e: u32) {
        let mesh = self.cdt.mesh().raw();
        let (u, v) = (mesh.origin(e), mesh.dest(e));
        for h in [e, mesh.twin(e)] {
            let w = mesh.apex(h);
            if w != GHOST && self.inside(triangle_of(h)) && self.encroaches(u, v, mesh.point(w)) {
                if self.may_split(e) && !self.unsplittable.contains(&(u.min(v), u.max(v))) {
                    self.encroached.push_back((u, v, false));
                }
                return;
            }
        }
    }

    /// Splits the queued subsegments that are still encroached (or were queued `forced`);
    /// returns how many it split.
    pub(super) fn split_encroached(&mut self) -> usize {
        let mut splits = 0;
        while let Some((u, v, forced)) = self.encroached.pop_front() {
            if self.should_stop() {
                self.encroached.push_front((u, v, forced));
                break;
            }
            let mesh = self.cdt.mesh().raw();
            let Some(e) = mesh.find_edge(u, v).filter(|&e| mesh.is_segment(e)) else {
                continue;
            };
            let still = [e, mesh.twin(e)].iter().any(|&h| {
                let w = mesh.apex(h);
                w != GHOST && self.inside(triangle_of(h)) && self.encroaches(u, v, mesh.point(w))
            });
            if (forced || still) && self.split_segment(e) {
                splits += 1;
            }
        }
        splits
    }

    /// Where to split subsegment `u`–`v` (parameter from `u`): at a power-of-two distance from
    /// an end that is an input vertex where segments meet at an acute angle ("concentric shells",
    /// Ruppert 1995 §5, Shewchuk 2002 §4.1), from the sharper one if both are; else the midpoint.
    /// The powers of two are absolute (2^k, k any integer), the same on every segment around a
    /// corner, so that splits on two segments meet on common shells. Returns the parameter and
    /// the kind of the new vertex (the corner and the exponent of its distance).
    pub(super) fn split_parameter(&self, u: u32, v: u32) -> (f64, VertexKind) {
        let (cu, cv) = (self.sharpest_corner(u), self.sharpest_corner(v));
        let midpoint = VertexKind::OnSegment {
            corner: NONE,
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
        let (pu, pv) = (self.pt(u), self.pt(v));
        let length = ((pv[0] - pu[0]).powi(2) + (pv[1] - pu[1]).powi(2)).sqrt();
        // The power of two 2^k in [length/3, 2·length/3] (there is one: the interval spans a
        // factor of two), the nearest to the midpoint.
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

    /// For an input vertex `x` where two segments meet at less than 90°: the cosine of the
    /// smallest such angle (larger is sharper). `None` for vertices inserted by refinement and
    /// for vertices whose segments meet at right or obtuse angles only. The smallest angle is
    /// between two segments consecutive around `x`, so one turn around it suffices.
    pub(super) fn sharpest_corner(&self, x: u32) -> Option<f64> {
        if matches!(self.kinds[x as usize], VertexKind::OnSegment { .. }) {
            return None;
        }
        let mesh = self.cdt.mesh().raw();
        let o = mesh.point(x);
        let direction = |e: u32| {
            let p = mesh.point(mesh.dest(e));
            let d = [p[0] - o[0], p[1] - o[1]];
            let length = (d[0] * d[0] + d[1] * d[1]).sqrt();
            [d[0] / length, d[1] / length]
        };
        let start = mesh.vertex_edge(x);
        let (mut e, mut first, mut previous): (u32, Option<Point>, Option<Point>) =
            (start, None, None);
        let mut sharpest: Option<f64> = None;
        let mut consider = |a: Point, b: Point| {
            let cos = a[0] * b[0] + a[1] * b[1];
            if cos > 0.0 && sharpest.is_none_or(|s| cos > s) {
                sharpest = Some(cos);
            }
        };
        loop {
            if mesh.is_segment(e) {
                let d = direction(e);
                match previous {
                    Some(p) => consider(p, d),
                    None => first = Some(d),
                }
                previous = Some(d);
            }
            e = mesh.twin(prev(e));
            if e == start {
                break;
            }
        }
        if let (Some(a), Some(b)) = (first, previous) {
            if a != b {
                consider(b, a);
            }
        }
        sharpest
    }

    /// Splits the subsegment of half-edge `e`; returns whether it did. It does not when the
    /// pieces would be shorter than the floor, or when the rounded split point would fall on or
    /// beyond the line from an end to a vertex beside the subsegment (a vertex within rounding
    /// distance of it): the triangles made would be inverted. Such a subsegment is never tried
    /// again.
    pub(super) fn split_segment(&mut self, e: u32) -> bool {
        let mesh = self.cdt.mesh().raw();
        let (u, v) = (mesh.origin(e), mesh.dest(e));
        let (t, kind) = self.split_parameter(u, v);
        let (pu, pv) = (self.pt(u), self.pt(v));
        let p = [pu[0] + t * (pv[0] - pu[0]), pu[1] + t * (pv[1] - pu[1])];
        let too_short =
            |q: Point, r: Point| (q[0] - r[0]).powi(2) + (q[1] - r[1]).powi(2) < self.floor2;
        let splits_cleanly = [e, mesh.twin(e)].iter().all(|&h| {
            let w = mesh.apex(h);
            let (a, b) = (mesh.point(mesh.origin(h)), mesh.point(mesh.dest(h)));
            w == GHOST
                || (P::orient2d(a, p, mesh.point(w)) > 0.0
                    && P::orient2d(p, b, mesh.point(w)) > 0.0)
        });
        if too_short(p, pu) || too_short(p, pv) || !splits_cleanly {
            self.unsplittable.insert((u.min(v), u.max(v)));
            self.skipped += 1;
            return false;
        }
        let vertex = self.new_vertex(p, kind, |attrs, i| {
            attrs[u as usize * i.1 + i.0]
                + t * (attrs[v as usize * i.1 + i.0] - attrs[u as usize * i.1 + i.0])
        });
        let _ = self
            .cdt
            .insert_at(VertexId::new(vertex), Location::OnEdge(EdgeId::new(e)));
        self.cdt.settle(VertexId::new(vertex));
        self.after_insertion(vertex);
        true
    }
}
