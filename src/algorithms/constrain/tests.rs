use super::*;
use crate::algorithms::delaunay::order::{hilbert_order, splitmix64};
use crate::geometry::Exact;

/// Every real triangle counter-clockwise and every edge that is not a segment locally
/// Delaunay (exact predicates).
fn assert_constrained_delaunay(m: &Mesh, seed: u64) {
    for t in m.real_triangles() {
        let [p, q, r] = m.triangle(t).map(|v| m.point(v));
        assert!(
            Exact::orient2d(p, q, r) > 0.0,
            "seed {seed}: inverted triangle"
        );
        for e in t.edges() {
            let o = m.apex(m.twin(e));
            if o != GHOST && !m.is_segment(e) {
                assert!(
                    Exact::incircle(p, q, r, m.point(o)) <= 0.0,
                    "seed {seed}: not CDT"
                );
            }
        }
    }
}

fn rand01(s: &mut u64) -> f64 {
    splitmix64(s) as f64 / u64::MAX as f64
}

/// Builds the CDT of random points and random segments between them, checking after each
/// segment that the mesh is valid, the segment is present and non-segment edges are locally
/// Delaunay.
#[test]
fn random_segments_are_recovered() {
    let seeds: Vec<u64> = match std::env::var("SEED") {
        Ok(s) => vec![s.parse().unwrap()],
        Err(_) => (0..3000).collect(),
    };
    for seed in seeds.into_iter().take(1500) {
        let mut s = seed;
        let n = 5 + (splitmix64(&mut s) % 40) as usize;
        let pts: Vec<Point> = (0..n).map(|_| [rand01(&mut s), rand01(&mut s)]).collect();
        let order = hilbert_order(&pts);
        let tri = crate::algorithms::delaunay::triangulate::<Exact>(pts, &order);
        if tri.is_degenerate() {
            continue;
        }
        let mut cdt = Constrainer::new(Inserter::<Exact>::new(tri.mesh));
        // Every other seed recovers segments by splitting (`s`).
        cdt.split_segments = seed % 2 == 1;
        for k in 0..10 {
            let a = (splitmix64(&mut s) % n as u64) as u32;
            let b = (splitmix64(&mut s) % n as u64) as u32;
            let id = cdt.new_segment_id(k % 3, VertexId::new(a), VertexId::new(b));
            let (a, b) = (VertexId::new(a), VertexId::new(b));
            let mesh = cdt.mesh();
            let segments_before: Vec<(VertexId, VertexId)> = mesh
                .edges()
                .filter(|&e| mesh.is_segment(e))
                .map(|e| (mesh.origin(e), mesh.dest(e)))
                .collect();
            cdt.insert_segment(a, b, id).unwrap();
            let mesh = cdt.mesh();
            mesh.check_topology()
                .unwrap_or_else(|e| panic!("seed {seed}: {e}"));
            let is_segment = |x, y| mesh.find_edge(x, y).is_some_and(|f| mesh.is_segment(f));
            for &(u, v) in &segments_before {
                // A segment edge stays one, unless the new segment crossed it through a
                // vertex `w` (in floating point): then it was replaced by u-w and w-v.
                if let Some(e) = mesh.find_edge(u, v) {
                    let through_vertex = (0..mesh.vertex_count())
                        .map(VertexId::new)
                        .any(|w| w != u && w != v && is_segment(u, w) && is_segment(w, v));
                    assert!(
                        mesh.is_segment(e) || through_vertex,
                        "seed {seed}: segment edge {u}-{v} lost its mark"
                    );
                }
            }
            if let Some(e) = mesh.find_edge(a, b) {
                assert!(
                    mesh.is_segment(e),
                    "seed {seed}: segment {a}-{b} not marked"
                );
            }
            assert_constrained_delaunay(mesh, seed);
            for e in mesh.edges() {
                if mesh.origin(e) != GHOST && mesh.dest(e) != GHOST {
                    assert!(mesh.vertex_edge(mesh.origin(e)).is_some());
                }
            }
        }
    }
}

/// A star-shaped polygon's edges inserted in random orders: the cavities of long, thin
/// segments among earlier ones are often not simple polygons (an edge between two crossed
/// triangles, possibly a segment, lies on their boundary twice). Every edge must end up a
/// segment, every earlier segment must stay one, and the result must be constrained Delaunay.
#[test]
fn star_polygon_in_random_orders() {
    for seed in 0..20u64 {
        let mut s = seed;
        let n = 300 + (splitmix64(&mut s) % 700) as usize;
        let mut angles: Vec<f64> = (0..n)
            .map(|_| rand01(&mut s) * std::f64::consts::TAU)
            .collect();
        angles.sort_by(f64::total_cmp);
        let pts: Vec<Point> = angles
            .iter()
            .map(|&a| {
                let r = 0.1 + 0.9 * rand01(&mut s);
                [r * a.cos(), r * a.sin()]
            })
            .collect();
        let tri =
            crate::algorithms::delaunay::triangulate::<Exact>(pts.clone(), &hilbert_order(&pts));
        let mut cdt = Constrainer::new(Inserter::<Exact>::new(tri.mesh));
        let mut order: Vec<u32> = (0..n as u32).collect();
        for i in (1..n).rev() {
            order.swap(i, (splitmix64(&mut s) % (i as u64 + 1)) as usize);
        }
        for (k, &i) in order.iter().enumerate() {
            let (a, b) = (i, (i + 1) % n as u32);
            let id = cdt.new_segment_id(1, VertexId::new(a), VertexId::new(b));
            cdt.insert_segment(VertexId::new(a), VertexId::new(b), id)
                .unwrap();
            if k % 50 == 0 || k + 1 == n {
                let m = cdt.mesh();
                m.check_topology()
                    .unwrap_or_else(|e| panic!("seed {seed}: {e}"));
                for &j in &order[..=k] {
                    let (u, v) = (VertexId::new(j), VertexId::new((j + 1) % n as u32));
                    let e = m.find_edge(u, v).expect("polygon edge");
                    assert!(
                        m.is_segment(e),
                        "seed {seed}: polygon edge {j} not a segment after {k} insertions"
                    );
                }
            }
        }
        let m = cdt.mesh();
        assert_eq!(
            m.edge_count() as usize,
            tri_corner_count(n, m),
            "seed {seed}: no new vertices expected"
        );
        assert_constrained_delaunay(m, seed);
    }
}

/// Corners of a triangulation of `n` vertices with ghosts: 3 (2n − 2) half-edges, hull or not.
fn tri_corner_count(n: usize, m: &crate::mesh::Mesh) -> usize {
    assert_eq!(m.points().len(), n);
    3 * (2 * n - 2)
}
