//! The meshed domain of a planar straight line graph: which triangles are kept (holes and the
//! outside of the boundary are eaten), and the regional attributes and area bounds.
//!
//! As in Triangle, triangles are "infected" from the outside of the triangulation (unless `c`) and
//! from each hole point, and the infection spreads to neighbours across every edge that is not a
//! segment. Regions spread the same way from their points.

use crate::algorithms::constrain::Constrainer;
use crate::geometry::{Point, Predicates};
use crate::mesh::{triangle_of, Mesh};

/// Per triangle slot: kept or not, regional attribute and regional maximum area (≤ 0: none).
#[derive(Clone, Debug, Default)]
pub struct Domain {
    pub in_mesh: Vec<bool>,
    pub region_attribute: Vec<f64>,
    pub region_max_area: Vec<f64>,
}

/// Visits every triangle reachable from `seeds` across non-segment edges: `try_visit(t)` visits
/// `t` if it may be entered and was not visited yet, and says whether it did.
fn flood(mesh: &Mesh, seeds: Vec<u32>, mut try_visit: impl FnMut(u32) -> bool) {
    let mut stack: Vec<u32> = seeds.into_iter().filter(|&t| try_visit(t)).collect();
    while let Some(t) = stack.pop() {
        for e in 3 * t..3 * t + 3 {
            if mesh.is_segment(e) {
                continue;
            }
            let u = triangle_of(mesh.twin(e));
            if try_visit(u) {
                stack.push(u);
            }
        }
    }
}

/// Carves the domain out of a constrained triangulation.
///
/// `holes` are (x, y) pairs; `regions` are (x, y, attribute, max area) rows.
pub fn carve<P: Predicates>(
    cdt: &mut Constrainer<P>,
    keep_convex_hull: bool,
    holes: &[f64],
    regions: &[f64],
) -> Domain {
    let slots = cdt.inserter.mesh.triangle_count() as usize;
    let mut in_mesh: Vec<bool> = (0..slots as u32).map(|t| !cdt.inserter.mesh.is_ghost(t)).collect();
    let mut seeds = Vec::new();
    if !keep_convex_hull {
        // Real triangles along hull edges that are not segments.
        let mesh = &cdt.inserter.mesh;
        for t in 0..slots as u32 {
            if !in_mesh[t as usize] {
                continue;
            }
            for e in 3 * t..3 * t + 3 {
                if !mesh.is_segment(e) && mesh.is_ghost(triangle_of(mesh.twin(e))) {
                    seeds.push(t);
                    break;
                }
            }
        }
    }
    for hole in holes.chunks_exact(2) {
        if let Some(t) = cdt.triangle_at([hole[0], hole[1]]) {
            seeds.push(t);
        }
    }
    flood(&cdt.inserter.mesh, seeds, |t| std::mem::take(&mut in_mesh[t as usize]));

    let mut region_attribute = vec![0.0; slots];
    let mut region_max_area = vec![-1.0; slots];
    for region in regions.chunks_exact(4) {
        let point: Point = [region[0], region[1]];
        let Some(t) = cdt.triangle_at(point) else { continue };
        let mesh = &cdt.inserter.mesh;
        let mut seen = vec![false; slots];
        flood(mesh, vec![t], |u| {
            let enter = in_mesh[u as usize] && !seen[u as usize];
            if enter {
                seen[u as usize] = true;
                region_attribute[u as usize] = region[2];
                region_max_area[u as usize] = region[3];
            }
            enter
        });
    }
    Domain { in_mesh, region_attribute, region_max_area }
}
