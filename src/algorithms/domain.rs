//! The meshed domain of a planar straight line graph: which triangles are kept (holes and the
//! outside of the boundary are eaten), and the regional attributes and area bounds.
//!
//! As in Triangle, triangles are "infected" from the outside of the triangulation (unless `c`) and
//! from each hole point, and the infection spreads to neighbours across every edge that is not a
//! segment. Regions spread the same way from their points.

use std::collections::VecDeque;

use crate::algorithms::constrain::Constrainer;
use crate::geometry::{Point, Predicates};
use crate::mesh::{Mesh, TriangleId, GHOST, OUTSIDE};

/// What the triangle tags ([`Mesh::tag`]) stand for: tag [`OUTSIDE`] for eaten triangles and
/// ghosts, [`INSIDE`] for the domain outside every region, `FIRST_REGION + r` for region `r`.
#[derive(Clone, Debug, Default)]
pub struct Domain {
    /// Triangle attributes per tag.
    pub attribute_count: usize,
    /// `attribute_count` values per tag: the regional attribute (0 outside every region), or
    /// with `r` the input triangle's attributes.
    pub attributes: Vec<f64>,
    /// Per tag: the maximum area (≤ 0: none).
    pub max_area: Vec<f64>,
}

pub const INSIDE: u32 = 1;
pub const FIRST_REGION: u32 = 2;

impl Domain {
    /// The domain without regions: every non-ghost triangle is inside.
    pub fn whole(mesh: &mut Mesh) -> Domain {
        let tags = mesh
            .triangles()
            .map(|t| if mesh.is_ghost(t) { OUTSIDE } else { INSIDE })
            .collect();
        mesh.set_tags(tags);
        Domain {
            attribute_count: 0,
            attributes: Vec::new(),
            max_area: vec![-1.0; 2],
        }
    }

    /// Gives the triangles of regions that no output tells apart (the same attributes and the
    /// same maximum area) one tag, the smallest of theirs: with `r`, every input triangle is a
    /// region of its own, and refinement's operations that need one tag around a vertex
    /// (deleting it, moving it) would stop at every input triangle's edge. Nothing the caller
    /// receives changes (a triangle's outputs are those of its tag).
    pub fn merge_equal_regions(&self, mesh: &mut Mesh) {
        let k = self.attribute_count;
        let tag_count = self.max_area.len();
        if !mesh.tracks_tags() || tag_count <= FIRST_REGION as usize + 1 {
            return;
        }
        // The region tags sorted by (area, attributes) bits, ties by tag: each run of equal keys
        // goes to its first tag (no key allocated per region: with `r` there is one per input
        // triangle, and a hash map of them cost 23 M instructions on Triangle's 64 172-triangle
        // `greenland.ele`). The area first: one integer comparison decides most pairs.
        let area = |t: u32| {
            let area = self.max_area[t as usize];
            if area > 0.0 {
                area.to_bits()
            } else {
                0
            }
        };
        let bits = |t: u32| {
            let t = t as usize;
            self.attributes[t * k..(t + 1) * k]
                .iter()
                .map(|a| a.to_bits())
        };
        let mut order: Vec<u32> = (INSIDE..tag_count as u32)
            .filter(|&t| (t as usize + 1) * k <= self.attributes.len())
            .collect();
        order.sort_unstable_by(|&a, &b| {
            area(a)
                .cmp(&area(b))
                .then_with(|| bits(a).cmp(bits(b)))
                .then(a.cmp(&b))
        });
        let mut class: Vec<u32> = (0..tag_count as u32).collect();
        for pair in order.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            if area(a) == area(b) && bits(a).eq(bits(b)) {
                class[b as usize] = class[a as usize];
            }
        }
        let mut tags = mesh.take_tags();
        for tag in tags.iter_mut() {
            if *tag != OUTSIDE {
                if let Some(&c) = class.get(*tag as usize) {
                    *tag = c;
                }
            }
        }
        mesh.set_tags(tags);
    }

    /// The domain of a reconstructed mesh (`r`): input triangle `i` is tagged
    /// `FIRST_REGION + i`, with its attributes and maximum area; ghosts are outside.
    pub fn per_triangle(
        mesh: &mut Mesh,
        input_triangles: usize,
        attributes: &[f64],
        areas: Option<&[f64]>,
    ) -> Domain {
        let tags = (0..mesh.triangle_count())
            .map(|t| {
                if (t as usize) < input_triangles {
                    FIRST_REGION + t
                } else {
                    OUTSIDE
                }
            })
            .collect();
        mesh.set_tags(tags);
        let attribute_count = attributes.len().checked_div(input_triangles).unwrap_or(0);
        let mut all_attributes = vec![0.0; FIRST_REGION as usize * attribute_count];
        all_attributes.extend_from_slice(attributes);
        let mut max_area = vec![-1.0; FIRST_REGION as usize];
        max_area.extend((0..input_triangles).map(|i| areas.map_or(-1.0, |a| a[i])));
        Domain {
            attribute_count,
            attributes: all_attributes,
            max_area,
        }
    }

    /// The attributes of the triangles of tag `tag`.
    pub fn attributes_of(&self, tag: u32) -> &[f64] {
        let k = self.attribute_count;
        &self.attributes[tag as usize * k..tag as usize * k + k]
    }
}

/// Gives tag `tag` to every triangle reachable from `seeds` across non-segment edges whose tag
/// is not `tag` already and `may_enter` its tag.
///
/// Breadth first, with what a visit reads fetched into the cache ahead of it (every access here
/// is to a scattered triangle, a cache miss each, which depth first cost 4 ms of a
/// 10^5-vertex polygon's carving): a triangle's twins and segment ids when it is queued, the
/// tags of its neighbours when it comes within `LOOKAHEAD` of the queue's front.
fn flood(
    mesh: &Mesh,
    seeds: Vec<TriangleId>,
    tags: &mut [u32],
    tag: u32,
    may_enter: impl Fn(u32) -> bool,
) {
    const LOOKAHEAD: usize = 8;
    let enter = |t: TriangleId, tags: &mut [u32]| {
        let old = tags[t.index()];
        let enters = old != tag && may_enter(old);
        if enters {
            tags[t.index()] = tag;
        }
        enters
    };
    let mut queue: VecDeque<TriangleId> = VecDeque::new();
    for t in seeds {
        if enter(t, tags) {
            queue.push_back(t);
        }
    }
    while let Some(t) = queue.pop_front() {
        if let Some(&ahead) = queue.get(LOOKAHEAD) {
            for e in ahead.edges() {
                let u = mesh.twin(e).triangle();
                if let Some(slot) = tags.get(u.index()) {
                    crate::memory::prefetch(slot);
                }
            }
        }
        for e in t.edges() {
            if mesh.is_segment(e) {
                continue;
            }
            let u = mesh.twin(e).triangle();
            if enter(u, tags) {
                mesh.prefetch_adjacency(u);
                queue.push_back(u);
            }
        }
    }
}

/// Carves the domain out of a constrained triangulation: sets the triangle tags.
///
/// `holes` are (x, y) pairs; `regions` are (x, y, attribute, max area) rows.
pub fn carve<P: Predicates>(
    cdt: &mut Constrainer<P>,
    keep_convex_hull: bool,
    holes: &[f64],
    regions: &[f64],
) -> Domain {
    let domain = Domain::whole(cdt.mesh_mut());
    let mut seeds = Vec::new();
    if !keep_convex_hull {
        // Real triangles along hull edges that are not segments: found from the ghost triangles
        // (tagged outside), whose one finite edge is a hull edge, rather than by looking across
        // every edge of every triangle.
        let mesh = cdt.mesh();
        for t in mesh.triangles() {
            if mesh.tag(t) != OUTSIDE {
                continue;
            }
            for e in t.edges() {
                let h = mesh.twin(e);
                if mesh.origin(e) != GHOST && mesh.dest(e) != GHOST && !mesh.is_segment(h) {
                    seeds.push(h.triangle());
                }
            }
        }
    }
    for hole in holes.chunks_exact(2) {
        if let Some(t) = cdt.triangle_at([hole[0], hole[1]]) {
            seeds.push(t);
        }
    }
    let mut tag = cdt.mesh_mut().take_tags();
    flood(cdt.mesh(), seeds, &mut tag, OUTSIDE, |_| true);

    let mut domain = domain;
    domain.attribute_count = 1;
    domain.attributes = vec![0.0; FIRST_REGION as usize];
    for (r, region) in regions.chunks_exact(4).enumerate() {
        let point: Point = [region[0], region[1]];
        let region_tag = FIRST_REGION + r as u32;
        domain.attributes.push(region[2]);
        domain.max_area.push(region[3]);
        let Some(t) = cdt.triangle_at(point) else {
            continue;
        };
        flood(cdt.mesh(), vec![t], &mut tag, region_tag, |old| {
            old != OUTSIDE
        });
    }
    cdt.mesh_mut().set_tags(tag);
    domain
}
