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

/// The real triangles of `m`, each rotated to start at its smallest corner, sorted.
fn triangle_set(m: &Mesh) -> Vec<[u32; 3]> {
    let mut set: Vec<[u32; 3]> = m
        .real_triangles()
        .map(|t| {
            let c = m.triangle(t).map(VertexId::raw);
            let k = (0..3).min_by_key(|&i| c[i]).unwrap();
            [c[k], c[(k + 1) % 3], c[(k + 2) % 3]]
        })
        .collect();
    set.sort_unstable();
    set
}

/// The CDT of `pts` with `segments` (pairs of indices into `pts`).
fn cdt_of(pts: &[Point], segments: &[(u32, u32)]) -> Constrainer<Exact> {
    let tri = crate::algorithms::delaunay::triangulate::<Exact>(pts.to_vec(), &hilbert_order(pts));
    let mut cdt = Constrainer::new(Inserter::<Exact>::new(tri.mesh));
    for &(a, b) in segments {
        let (a, b) = (VertexId::new(a), VertexId::new(b));
        let id = cdt.new_segment_id(1, a, b);
        cdt.insert_segment(a, b, id).unwrap();
    }
    cdt
}

/// Vertex deletion (`Mesh::delete_vertex`, Chew's rule in refinement) on CDTs of random points
/// with segments along some of their Delaunay edges, and on grid points without segments
/// (cocircular and collinear neighbours: degenerate stars, which keep their vertex and leave the
/// mesh as it was): after each
/// deletion the mesh is valid and constrained Delaunay, two triangle slots fewer, every tracked
/// vertex edge leaves its vertex; in the end its triangles are those of the CDT of the points
/// left, and with the deleted vertices removed from the numbering (`Mesh::remove_vertices`) it
/// is that CDT vertex for vertex.
#[test]
fn deleted_vertices_leave_the_cdt_of_the_others() {
    let (mut deleted_in_all, mut kept_deletable) = (0, 0);
    for seed in 0..400u64 {
        let mut s = seed;
        let grid = seed % 5 == 4;
        let n = if grid {
            25 + (splitmix64(&mut s) % 40) as usize
        } else {
            6 + (splitmix64(&mut s) % 80) as usize
        };
        let pts: Vec<Point> = (0..n)
            .map(|i| {
                if grid {
                    [(i % 7) as f64 * 0.25, (i / 7) as f64 * 0.25]
                } else {
                    [rand01(&mut s), rand01(&mut s)]
                }
            })
            .collect();
        let dt = cdt_of(&pts, &[]);
        let mut segments = Vec::new();
        if !grid {
            let m = dt.mesh();
            for _ in 0..(splitmix64(&mut s) % 8) {
                let e =
                    crate::mesh::EdgeId::new((splitmix64(&mut s) % m.edge_count() as u64) as u32);
                let (a, b) = (m.origin(e), m.dest(e));
                if a != GHOST && b != GHOST {
                    segments.push((a.raw(), b.raw()));
                }
            }
        }
        let mut cdt = cdt_of(&pts, &segments);
        let mut gone = vec![false; n];
        let mut order: Vec<u32> = (0..n as u32).collect();
        for i in (1..n).rev() {
            order.swap(i, (splitmix64(&mut s) % (i as u64 + 1)) as usize);
        }
        for &v in order.iter().filter(|_| splitmix64(&mut s) % 3 != 0) {
            let v = VertexId::new(v);
            let (before, triangles_before) =
                (cdt.mesh().triangle_count(), triangle_set(cdt.mesh()));
            let deletable = cdt.mesh().is_deletable(v);
            let m = match cdt.delete_vertex(v) {
                Some(made) => {
                    assert!(deletable, "seed {seed}: {v} deleted");
                    gone[v.index()] = true;
                    deleted_in_all += 1;
                    let m = cdt.mesh();
                    assert_eq!(m.triangle_count() + 2, before, "seed {seed}");
                    assert!(m.vertex_edge(v).is_none(), "seed {seed}");
                    assert!(made.iter().all(|t| t.raw() < m.triangle_count()));
                    assert!(made.iter().all(|&t| !m.triangle(t).contains(&v)));
                    m
                }
                None => {
                    kept_deletable += usize::from(deletable);
                    let m = cdt.mesh();
                    assert_eq!(m.triangle_count(), before, "seed {seed}: {v} kept");
                    assert_eq!(triangle_set(m), triangles_before, "seed {seed}: {v} kept");
                    m
                }
            };
            m.check_topology()
                .unwrap_or_else(|e| panic!("seed {seed}: {e}"));
            for w in (0..n as u32).map(VertexId::new) {
                let e = m.vertex_edge(w);
                assert_eq!(e.is_none(), gone[w.index()], "seed {seed}: {w}");
                assert!(e.is_none_or(|e| m.origin(e) == w), "seed {seed}: {w}");
            }
            for (a, b) in &segments {
                let e = m.find_edge(VertexId::new(*a), VertexId::new(*b));
                assert!(e.is_some_and(|e| m.is_segment(e)), "seed {seed}");
            }
            assert_constrained_delaunay(m, seed);
        }
        let kept: Vec<u32> = (0..n as u32).filter(|&v| !gone[v as usize]).collect();
        let renamed: Vec<u32> = {
            let mut renamed = vec![NONE; n];
            for (i, &v) in kept.iter().enumerate() {
                renamed[v as usize] = i as u32;
            }
            renamed
        };
        let rest_points: Vec<Point> = kept.iter().map(|&v| pts[v as usize]).collect();
        let rest_segments: Vec<(u32, u32)> = segments
            .iter()
            .map(|&(a, b)| (renamed[a as usize], renamed[b as usize]))
            .collect();
        let rest = cdt_of(&rest_points, &rest_segments);
        let expected = triangle_set(rest.mesh());
        let in_old_ids: Vec<[u32; 3]> = {
            let mut set: Vec<[u32; 3]> = expected
                .iter()
                .map(|t| {
                    let c = t.map(|v| kept[v as usize]);
                    let k = (0..3).min_by_key(|&i| c[i]).unwrap();
                    [c[k], c[(k + 1) % 3], c[(k + 2) % 3]]
                })
                .collect();
            set.sort_unstable();
            set
        };
        assert_eq!(triangle_set(cdt.mesh()), in_old_ids, "seed {seed}");
        let new_id = cdt.remove_vertices(|v| !gone[v.index()]);
        assert_eq!(new_id, renamed, "seed {seed}");
        let m = cdt.mesh();
        m.check_topology()
            .unwrap_or_else(|e| panic!("seed {seed}: {e}"));
        assert_eq!(m.points(), &rest_points[..], "seed {seed}");
        assert_eq!(triangle_set(m), expected, "seed {seed}");
        for w in (0..m.vertex_count()).map(VertexId::new) {
            assert!(m.vertex_edge(w).is_some_and(|e| m.origin(e) == w));
        }
    }
    assert!(deleted_in_all > 1000, "{deleted_in_all} deletions");
    assert!(kept_deletable > 0, "no degenerate star met");
}

/// Deleting a vertex between two subsegments (`Mesh::delete_segment_vertex`, the improvement
/// of a finished refinement): CDTs of random points on a grid of 1/1024 with segments along
/// some of their Delaunay edges (hull edges too: a side with the vertex at infinity), each
/// split at its midpoint (exact) as refinement splits one; then the midpoints are deleted in
/// a random order. After each deletion the mesh is valid and constrained Delaunay, two triangle
/// slots fewer, the merged subsegment is one segment edge with the segment's id, the vertex is
/// in no triangle and every other tracked vertex edge leaves its vertex; a vertex kept leaves
/// the mesh as it was. Input vertices and vertices on no segment are never deleted.
#[test]
fn deleted_segment_vertices_leave_one_subsegment_and_a_cdt() {
    let (mut deleted_in_all, mut on_hull) = (0, 0);
    for seed in 0..300u64 {
        let mut s = seed;
        let n = 6 + (splitmix64(&mut s) % 60) as usize;
        let mut pts: Vec<Point> = (0..n)
            .map(|_| {
                let k = |s: &mut u64| (splitmix64(s) % 1024) as f64 / 1024.0;
                [k(&mut s), k(&mut s)]
            })
            .collect();
        pts.sort_by(|a, b| a.partial_cmp(b).unwrap());
        pts.dedup();
        let n = pts.len();
        let dt = cdt_of(&pts, &[]);
        let m = dt.mesh();
        let mut segments = Vec::new();
        for _ in 0..1 + splitmix64(&mut s) % 8 {
            let e = crate::mesh::EdgeId::new((splitmix64(&mut s) % m.edge_count() as u64) as u32);
            let (a, b) = (m.origin(e), m.dest(e));
            if a != GHOST && b != GHOST && !segments.contains(&(a.raw(), b.raw())) {
                segments.push((a.raw(), b.raw()));
            }
        }
        let mut cdt = cdt_of(&pts, &segments);
        // Split each segment at its midpoint.
        let mut midpoints = Vec::new();
        for &(a, b) in &segments {
            let (a, b) = (VertexId::new(a), VertexId::new(b));
            let Some(e) = cdt.mesh().find_edge(a, b) else {
                continue;
            };
            let (pa, pb) = (cdt.mesh().point(a), cdt.mesh().point(b));
            let mid = [0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])];
            if pts.contains(&mid) {
                continue;
            }
            let id = cdt.mesh().segment_of(e);
            let v = cdt.add_point(mid);
            cdt.insert_at(v, Location::OnEdge(e)).unwrap();
            midpoints.push((v, a, b, id));
        }
        for v in (0..n as u32).map(VertexId::new) {
            assert!(
                cdt.delete_segment_vertex(v).is_none(),
                "seed {seed}: input {v}"
            );
        }
        for i in (1..midpoints.len()).rev() {
            midpoints.swap(i, (splitmix64(&mut s) % (i as u64 + 1)) as usize);
        }
        for &(v, a, b, id) in &midpoints {
            let (before, triangles_before) =
                (cdt.mesh().triangle_count(), triangle_set(cdt.mesh()));
            let hull = {
                let m = cdt.mesh();
                m.star(v).any(|e| m.dest(e) == GHOST)
            };
            let m = match cdt.delete_segment_vertex(v) {
                Some(made) => {
                    deleted_in_all += 1;
                    on_hull += usize::from(hull);
                    let m = cdt.mesh();
                    assert_eq!(m.triangle_count() + 2, before, "seed {seed}");
                    assert!(m.vertex_edge(v).is_none(), "seed {seed}");
                    assert!(made.iter().all(|t| t.raw() < m.triangle_count()));
                    assert!(made.iter().all(|&t| !m.triangle(t).contains(&v)));
                    let e = m.find_edge(a, b).expect("the merged subsegment");
                    assert!(m.is_segment(e) && m.segment_of(e) == id, "seed {seed}");
                    m
                }
                None => {
                    let m = cdt.mesh();
                    assert_eq!(triangle_set(m), triangles_before, "seed {seed}: {v} kept");
                    m
                }
            };
            m.check_topology()
                .unwrap_or_else(|e| panic!("seed {seed}: {e}"));
            for w in (0..m.points().len() as u32).map(VertexId::new) {
                let e = m.vertex_edge(w);
                assert!(e.is_none_or(|e| m.origin(e) == w), "seed {seed}: {w}");
            }
            assert_constrained_delaunay(m, seed);
        }
    }
    assert!(deleted_in_all > 500, "{deleted_in_all} deleted");
    assert!(on_hull > 50, "{on_hull} deleted on the hull");
}
