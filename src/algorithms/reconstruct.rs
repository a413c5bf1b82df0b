//! `r`: rebuilds the mesh topology from a triangle list (a previous run's output).
//!
//! Twins are found by matching each directed edge with its reverse. The boundary of the mesh —
//! which need not be convex, and may have holes or vertices where two parts touch — is covered
//! with ghost triangles as in [`crate::mesh`]: one per boundary edge, linked to its neighbours
//! around each boundary vertex by turning, inside the mesh, from one boundary edge to the next.

use crate::error::Error;
use crate::geometry::{Point, Predicates};
use crate::mesh::{EdgeId, Mesh, VertexId};

/// Builds the mesh of the given triangles (`corners` indices per triangle, the first three used,
/// numbered from `base`). Triangle `i` of the input becomes triangle `i` of the mesh (turned
/// counter-clockwise if it was clockwise); ghosts follow.
pub fn reconstruct<P: Predicates>(
    points: Vec<Point>,
    triangles: &[i32],
    corners: usize,
    base: i32,
) -> Result<Mesh, Error> {
    let n = points.len() as i64;
    let count = triangles.len() / corners;
    let mut mesh = Mesh::with_points(points);
    for (i, tri) in triangles.chunks_exact(corners).enumerate() {
        let mut v = [0u32; 3];
        for k in 0..3 {
            let index = tri[k] as i64 - base as i64;
            if index < 0 || index >= n {
                return Err(Error::IndexOutOfRange {
                    item: "Triangle",
                    number: i as i64 + base as i64,
                    role: "corner",
                    value: tri[k] as i64,
                    first: base as i64,
                    last: n - 1 + base as i64,
                });
            }
            v[k] = index as u32;
        }
        let mut v = v.map(VertexId::new);
        let o = P::orient2d(mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2]));
        if o == 0.0 {
            return Err(Error::InvalidMesh(format!(
                "triangle {} has no area",
                i + base as usize
            )));
        }
        if o < 0.0 {
            v.swap(1, 2);
        }
        mesh.add_triangle(v[0], v[1], v[2]);
    }
    // Twins: each directed edge meets its reverse, found among the edges out of its
    // destination (the edges grouped by origin in one counting sort: a few per vertex, where a
    // hash map of vertex pairs cost ~500 instructions an edge: 94 M of 209 M on Triangle's
    // 64 172-triangle `greenland.ele`).
    let edges = 3 * count as u32;
    let mut first = vec![0u32; n as usize + 1];
    for e in (0..edges).map(EdgeId::new) {
        first[mesh.origin(e).index() + 1] += 1;
    }
    for v in 0..n as usize {
        first[v + 1] += first[v];
    }
    // Per vertex, its outgoing edges with their destinations, sorted (by destination, then
    // edge): a twin is a binary search, and copies of an edge are neighbours (a scan of the
    // list was quadratic in the degree: a fan of 160 000 triangles took 8.7 s).
    let mut out = vec![(VertexId::new(0), EdgeId::new(0)); edges as usize];
    let mut next = first.clone();
    for e in (0..edges).map(EdgeId::new) {
        let slot = &mut next[mesh.origin(e).index()];
        out[*slot as usize] = (mesh.dest(e), e);
        *slot += 1;
    }
    for v in 0..n as usize {
        out[first[v] as usize..first[v + 1] as usize].sort_unstable();
    }
    let out_of = |v: VertexId| &out[first[v.index()] as usize..first[v.index() + 1] as usize];
    for e in (0..edges).map(EdgeId::new) {
        let (a, b) = (mesh.origin(e), mesh.dest(e));
        // The first edge, in order, with an earlier copy is the error (as a map of the pairs
        // would find it).
        let from_a = out_of(a);
        let earlier_copy = from_a
            .binary_search(&(b, e))
            .is_ok_and(|i| i > 0 && from_a[i - 1].0 == b);
        if earlier_copy {
            return Err(Error::InvalidMesh(format!(
                "the edge from vertex {} to vertex {} belongs to more than two triangles (or two triangles overlap)",
                a.raw() as i64 + base as i64,
                b.raw() as i64 + base as i64
            )));
        }
        let from_b = out_of(b);
        let i = from_b.partition_point(|&(d, _)| d < a);
        if let Some(&(d, f)) = from_b.get(i) {
            if d == a && f > e {
                mesh.link(e, f);
            }
        }
    }
    mesh.cover_boundary_with_ghosts();
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Exact;
    use crate::mesh::GHOST;

    #[test]
    fn an_edge_of_three_triangles_or_a_triangle_twice_is_an_error() {
        let points = vec![[0.0, 0.0], [1.0, 0.0], [0.5, 1.0], [0.5, -1.0], [0.3, 2.0]];
        let three = [0, 1, 2, 1, 0, 3, 0, 1, 4];
        let twice = [0, 1, 2, 2, 1, 0];
        for tris in [&three[..], &twice[..]] {
            match reconstruct::<Exact>(points.clone(), tris, 3, 0) {
                Err(Error::InvalidMesh(message)) => {
                    assert!(message.contains("more than two triangles"), "{message}")
                }
                other => panic!("{tris:?}: {:?}", other.map(|m| m.triangle_count())),
            }
        }
        // Two triangles sharing an edge: linked across it.
        let mesh = reconstruct::<Exact>(points, &three[..6], 3, 0).unwrap();
        mesh.check_topology().unwrap();
        assert_eq!(mesh.triangles().filter(|&t| !mesh.is_ghost(t)).count(), 2);
    }

    #[test]
    fn square_with_a_hole_and_a_bowtie_vertex() {
        // A 3×3 grid of unit squares without the middle one: an annulus of 16 triangles.
        let mut points = Vec::new();
        for j in 0..4 {
            for i in 0..4 {
                points.push([i as f64, j as f64]);
            }
        }
        let mut tris = Vec::new();
        for j in 0..3 {
            for i in 0..3 {
                if (i, j) == (1, 1) {
                    continue;
                }
                let v = |a: i32, b: i32| b * 4 + a;
                tris.extend_from_slice(&[v(i, j), v(i + 1, j), v(i + 1, j + 1)]);
                tris.extend_from_slice(&[v(i, j), v(i + 1, j + 1), v(i, j + 1)]);
            }
        }
        // A clockwise triangle touching the grid at one corner (a bowtie vertex).
        points.push([4.0, 4.0]);
        points.push([3.0, 5.0]);
        tris.extend_from_slice(&[15, 17, 16]);
        let mut mesh = reconstruct::<Exact>(points, &tris, 3, 0).unwrap();
        mesh.check_topology().unwrap();
        let ghosts = mesh.triangles().filter(|&t| mesh.is_ghost(t)).count();
        assert_eq!(ghosts, 12 + 4 + 3);
        // The star of the bowtie vertex is one cycle through both parts, counter-clockwise:
        // every edge at it is found by turning around it.
        mesh.track_vertex_edges();
        let bowtie = VertexId::new(15);
        let around: Vec<u32> = mesh.star(bowtie).map(|e| mesh.dest(e).raw()).collect();
        let mut real: Vec<u32> = around
            .iter()
            .copied()
            .filter(|&v| v != GHOST.raw())
            .collect();
        real.sort_unstable();
        assert_eq!(real, [10, 11, 14, 16, 17], "star {around:?}");
        for v in [10, 11, 14, 16, 17] {
            assert!(mesh.find_edge(bowtie, VertexId::new(v)).is_some());
        }
        // In angular order: the turns from each neighbour's direction to the next add up to
        // one full turn (two or more if the parts came out of order).
        let tau = 2.0 * std::f64::consts::PI;
        let directions: Vec<f64> = around
            .iter()
            .filter(|&&v| v != GHOST.raw())
            .map(|&v| {
                let (p, q) = (mesh.point(bowtie), mesh.point(VertexId::new(v)));
                (q[1] - p[1]).atan2(q[0] - p[0])
            })
            .collect();
        let turns: f64 = (0..directions.len())
            .map(|i| (directions[(i + 1) % directions.len()] - directions[i]).rem_euclid(tau))
            .sum();
        assert!((turns - tau).abs() < 1e-9, "{turns}");
        assert!(
            reconstruct::<Exact>(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], &[0, 1, 3], 3, 0)
                .is_err()
        );
        assert!(
            reconstruct::<Exact>(vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], &[0, 1, 2], 3, 0)
                .is_err()
        );
    }
}
