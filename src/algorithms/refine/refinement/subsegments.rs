//! The subsegments of a refinement: which are encroached (queued first in first out), which
//! `Y`/`YY` keep whole, and their splits (concentric shells, rounding checked, Chew's deletion of
//! the free vertices in the diametral circle first).

use super::{Encroached, Refinement};
use crate::algorithms::delaunay::Location;
use crate::algorithms::refine::encroachment::{split_parameter, splits_faithfully};
use crate::algorithms::refine::{inside, VertexKind};
use crate::geometry::{Point, Predicates};
use crate::mesh::{EdgeId, VertexId};

impl<P: Predicates> Refinement<'_, '_, P> {
    /// Whether the segment of half-edge `e` may receive Steiner points (`Y`, `YY`).
    pub(super) fn may_split(&self, e: EdgeId) -> bool {
        let mesh = self.mesh();
        match self.settings.quality.no_steiner_on_segments {
            0 => true,
            1 => inside(mesh, e.triangle()) && inside(mesh, mesh.twin(e).triangle()),
            _ => false,
        }
    }

    pub(super) fn is_unsplittable(&self, u: VertexId, v: VertexId) -> bool {
        self.unsplittable.contains(&(u.min(v), u.max(v)))
    }

    /// Queues the subsegment of half-edge `e` if an apex beside it encroaches it.
    pub(super) fn check_segment(&mut self, e: EdgeId) {
        let mesh = self.mesh();
        let (u, v) = (mesh.origin(e), mesh.dest(e));
        if self.encroachment.apex_encroaches(mesh, e)
            && self.may_split(e)
            && !self.is_unsplittable(u, v)
        {
            self.encroached.push_back(Encroached {
                u,
                v,
                edge: e,
                forced: false,
            });
        }
    }

    /// Splits the queued subsegments that are still encroached (or were queued `forced`);
    /// returns how many it split.
    pub(super) fn split_encroached(&mut self) -> usize {
        let mut splits = 0;
        while let Some(queued) = self.encroached.pop_front() {
            if self.should_stop() {
                self.encroached.push_front(queued);
                break;
            }
            let Some(e) = self.half_edge_of(queued) else {
                continue;
            };
            let still = self.encroachment.apex_encroaches(self.mesh(), e);
            if (queued.forced || still) && self.split_segment(e).is_some() {
                splits += 1;
            }
        }
        splits
    }

    /// The half-edge from `u` to `v` of a queued subsegment, if it is still a subsegment: mostly
    /// the half-edge it was queued with (one look, where finding it takes a turn around `u`).
    pub(super) fn half_edge_of(&self, queued: Encroached) -> Option<EdgeId> {
        let mesh = self.mesh();
        let Encroached { u, v, edge, .. } = queued;
        let e = if edge.raw() < mesh.edge_count() && mesh.origin(edge) == u && mesh.dest(edge) == v
        {
            edge // the one half-edge from u to v
        } else {
            mesh.find_edge(u, v)?
        };
        mesh.is_segment(e).then_some(e)
    }

    /// Splits the subsegment of half-edge `e`; returns the new vertex if it did. It does not when the
    /// pieces would be shorter than the floor, or when the rounded split point would make
    /// inverted triangles or move the domain's boundary by more than rounding
    /// ([`splits_faithfully`]). Such a subsegment is never tried again.
    pub(super) fn split_segment(&mut self, e: EdgeId) -> Option<VertexId> {
        let mesh = self.mesh();
        let (u, v) = (mesh.origin(e), mesh.dest(e));
        let (t, kind) = split_parameter(mesh, &self.kinds, u, v);
        let (pu, pv) = (mesh.point(u), mesh.point(v));
        let exact = [pu[0] + t * (pv[0] - pu[0]), pu[1] + t * (pv[1] - pu[1])];
        let floor2 = self.settings.floor2;
        let too_short = |q: Point, r: Point| (q[0] - r[0]).powi(2) + (q[1] - r[1]).powi(2) < floor2;
        let p = self.placed(exact);
        let faithful = |this: &Self, e| {
            splits_faithfully::<P>(
                this.mesh(),
                e,
                p,
                this.largest_sliver(),
                this.settings.negligible_sliver,
            )
        };
        let mut splits = !too_short(p, pu) && !too_short(p, pv) && faithful(self, e);
        let mut e = e;
        // Chew's rule: the free vertices in the diametral circle go first (the triangles beside
        // the subsegment may change).
        if splits && self.delete_free_vertices(e) {
            e = self.mesh().find_edge(u, v).expect("a subsegment stays");
            splits = faithful(self, e);
        }
        if !splits {
            self.unsplittable.insert((u.min(v), u.max(v)));
            self.tally.skipped += 1;
            return None;
        }
        let vertex = self.new_vertex(p, kind);
        self.attributes.push_on_segment(u, v, t);
        let _ = self.cdt.insert_at(vertex, Location::OnEdge(e));
        self.cdt.settle(vertex);
        self.after_insertion(vertex);
        Some(vertex)
    }

    /// Deletes the free vertices strictly inside the diametral circle of the subsegment of `e`,
    /// seen from it (Chew 1993, 1997; Shewchuk 2002 §5: [`super::deletion`]), and queues the
    /// triangles made if bad and the subsegments around them if encroached (queued ones that a
    /// deletion removed or moved are found again or skipped when taken out). Whether it did.
    pub(super) fn delete_free_vertices(&mut self, e: EdgeId) -> bool {
        let found = self.disk.free_vertices_in(self.cdt.mesh(), &self.kinds, e);
        if found.is_empty() {
            return false;
        }
        let (found, mut deleted) = (found.to_vec(), false);
        for w in found {
            let Some(made) = self.cdt.delete_vertex(w) else {
                continue;
            };
            self.kinds[w.index()] = VertexKind::Deleted;
            deleted = true;
            for t in made {
                for h in t.edges() {
                    if self.mesh().is_segment(h) {
                        self.check_segment(h);
                    }
                }
                if inside(self.mesh(), t) {
                    self.check_triangle(t);
                }
            }
        }
        deleted
    }
}
