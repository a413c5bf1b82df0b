//! `r`: rebuilds the mesh topology from a triangle list (a previous run's output).
//!
//! Twins are found by matching each directed edge with its reverse. The boundary of the mesh —
//! which need not be convex, and may have holes or vertices where two parts touch — is covered
//! with ghost triangles as in [`crate::mesh`]: one per boundary edge, linked to its neighbours
//! around each boundary vertex by turning, inside the mesh, from one boundary edge to the next.

use std::collections::HashMap;

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
    // Twins: each directed edge meets its reverse.
    let mut directed: HashMap<(VertexId, VertexId), EdgeId> = HashMap::with_capacity(3 * count);
    for e in (0..3 * count as u32).map(EdgeId::new) {
        let key = (mesh.origin(e), mesh.dest(e));
        if directed.insert(key, e).is_some() {
            return Err(Error::InvalidMesh(format!(
                "the edge from vertex {} to vertex {} belongs to more than two triangles (or two triangles overlap)",
                key.0.raw() as i64 + base as i64,
                key.1.raw() as i64 + base as i64
            )));
        }
    }
    for e in (0..3 * count as u32).map(EdgeId::new) {
        if let Some(&f) = directed.get(&(mesh.dest(e), mesh.origin(e))) {
            mesh.link(e, f);
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
