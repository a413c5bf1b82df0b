//! Cocircular points (grids, lattices, points on concentric circles, duplicates mixed in): the
//! Delaunay triangulation is made unique by a tie rule that depends only on the points
//! (symbolic perturbation of the lifted points, ranked by their coordinates), so the triangle
//! set — as vertex triples by coordinates — is the same whatever the insertion order (default,
//! `i`), the thread count (one core, the two-core merge), the permutation of the input, and the
//! same as the full set's for a subset renumbered: every triangle of the full set whose three
//! vertices are in the subset, and every triangle of the subset whose circumdisk holds no point
//! that the subset lacks. Each result is valid (exact orientation, the convex hull with its
//! collinear points) and Delaunay (exact in-circle ≤ 0).

mod common;

use std::collections::BTreeSet;

use common::checks::{canonical_triangle, check_delaunay, check_mesh, zero_based};
use common::rng::SplitMix64;
use common::{ours, MeshInput};
use triangle_rs::algorithms::delaunay::merge;
use triangle_rs::geometry::Exact;

type Point = [f64; 2];
/// A point by its coordinates' bits (`-0.0` as `0.0`).
type Key = [u64; 2];
type TriangleSet = BTreeSet<[Key; 3]>;

fn key(p: Point) -> Key {
    [(p[0] + 0.0).to_bits(), (p[1] + 0.0).to_bits()]
}

fn by_coordinates(points: &[Point], triangles: &[[usize; 3]]) -> TriangleSet {
    triangles
        .iter()
        .map(|t| canonical_triangle(t.map(|i| key(points[i]))))
        .collect()
}

/// The triangles of one of our calls (`z` added), checked valid and Delaunay.
fn triangulated(context: &str, switches: &str, points: &[Point]) -> TriangleSet {
    let input = MeshInput::from_points(points.to_vec());
    let out = ours(&format!("{switches}z"), &input).unwrap_or_else(|e| panic!("{context}: {e}"));
    let triangles = zero_based(&out);
    check_mesh(points, &triangles).unwrap_or_else(|e| panic!("{context}, {switches}: {e}"));
    check_delaunay(points, &triangles).unwrap_or_else(|e| panic!("{context}, {switches}: {e}"));
    by_coordinates(points, &triangles)
}

/// [`triangulated`] on a thread allowed on one CPU only: the library sees one core and never
/// takes the two-thread paths.
fn triangulated_on_one_core(context: &str, switches: &str, points: &[Point]) -> TriangleSet {
    std::thread::scope(|s| {
        s.spawn(|| {
            // SAFETY: plain libc calls on a zeroed cpu_set_t of the calling thread (pid 0).
            unsafe {
                let mut set: libc::cpu_set_t = std::mem::zeroed();
                let size = std::mem::size_of::<libc::cpu_set_t>();
                assert_eq!(libc::sched_getaffinity(0, size, &mut set), 0);
                let first = (0..libc::CPU_SETSIZE as usize)
                    .find(|&c| libc::CPU_ISSET(c, &set))
                    .expect("a CPU");
                libc::CPU_ZERO(&mut set);
                libc::CPU_SET(first, &mut set);
                assert_eq!(libc::sched_setaffinity(0, size, &set), 0);
            }
            assert_eq!(std::thread::available_parallelism().unwrap().get(), 1);
            triangulated(context, switches, points)
        })
        .join()
        .unwrap()
    })
}

/// The two-core merge called directly (whatever the machine's core count).
fn triangulated_by_the_merge(context: &str, points: &[Point]) -> TriangleSet {
    let triangulation = merge::triangulate_two_halves::<Exact>(points.to_vec())
        .unwrap_or_else(|_| panic!("{context}: the merge declined"));
    let mesh = &triangulation.mesh;
    let triangles: Vec<[usize; 3]> = mesh
        .real_triangles()
        .map(|t| mesh.triangle(t).map(|v| v.index()))
        .collect();
    check_mesh(points, &triangles).unwrap_or_else(|e| panic!("{context}, merge: {e}"));
    check_delaunay(points, &triangles).unwrap_or_else(|e| panic!("{context}, merge: {e}"));
    by_coordinates(points, &triangles)
}

/// Panics with the count of triangles in one set and not the other, and an example.
fn assert_same(got: &TriangleSet, expected: &TriangleSet, context: &str) {
    if got != expected {
        let example = got.symmetric_difference(expected).next().unwrap();
        panic!(
            "{context}: {} of {} triangles differ, e.g. {:?}",
            got.symmetric_difference(expected).count(),
            expected.len(),
            example.map(|k| k.map(f64::from_bits))
        );
    }
}

fn square_grid(side: usize) -> Vec<Point> {
    (0..side * side)
        .map(|k| [(k % side) as f64, (k / side) as f64])
        .collect()
}

/// Rows shifted by half a spacing: with a row height of half the spacing every cell of four
/// points is a square (cocircular), with another height the lattice is triangular.
fn shifted_rows(columns: usize, rows: usize, height: f64) -> Vec<Point> {
    let mut points = Vec::new();
    for j in 0..rows {
        for i in 0..columns {
            let shift = if j % 2 == 1 { 0.5 } else { 0.0 };
            points.push([i as f64 + shift, j as f64 * height]);
        }
    }
    points
}

/// The integer points on circles of radii with many representations as sums of two squares
/// (exactly cocircular), around a few centres (concentric circles), and the centres.
fn concentric_circles() -> Vec<Point> {
    let mut points = Vec::new();
    for (cx, cy) in [(0i64, 0i64), (200, 0), (100, 170)] {
        points.push([cx as f64, cy as f64]);
        for r in [5i64, 25, 65, 85] {
            for x in -r..=r {
                let y2 = r * r - x * x;
                let y = (y2 as f64).sqrt().round() as i64;
                if y * y == y2 {
                    points.push([(cx + x) as f64, (cy + y) as f64]);
                    if y != 0 {
                        points.push([(cx + x) as f64, (cy - y) as f64]);
                    }
                }
            }
        }
    }
    points
}

/// `points` with copies of some of them inserted at random places.
fn with_duplicates(mut points: Vec<Point>, copies: usize, rng: &mut SplitMix64) -> Vec<Point> {
    for _ in 0..copies {
        let p = points[rng.below(points.len())];
        let at = rng.below(points.len() + 1);
        points.insert(at, p);
    }
    points
}

fn shuffled(points: &[Point], rng: &mut SplitMix64) -> Vec<Point> {
    let mut points = points.to_vec();
    rng.shuffle(&mut points);
    points
}

fn cases(rng: &mut SplitMix64) -> Vec<(&'static str, Vec<Point>)> {
    vec![
        ("square grid", square_grid(30)),
        ("square grid with duplicates", {
            let grid = square_grid(25);
            with_duplicates(grid, 60, rng)
        }),
        ("squares at 45 degrees", shifted_rows(20, 41, 0.5)),
        ("triangular lattice", shifted_rows(20, 24, 0.875)),
        ("concentric circles", concentric_circles()),
        ("concentric circles with duplicates", {
            let circles = concentric_circles();
            with_duplicates(circles, 40, rng)
        }),
        (
            "a small square",
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        ),
        ("a rectangle's border", {
            let mut border: Vec<Point> = (0..30)
                .flat_map(|i| [[i as f64, 0.0], [i as f64, 9.0]])
                .collect();
            border.extend((1..9).flat_map(|j| [[0.0, j as f64], [29.0, j as f64]]));
            border
        }),
        // Two lines of collinear points crossing inside, cocircular around the centre.
        (
            "a cross",
            (-20..=20)
                .filter(|&i| i != 0)
                .flat_map(|i| [[i as f64, 0.0], [0.0, i as f64]])
                .chain([[0.0, 0.0]])
                .collect(),
        ),
        (
            "a line of squares",
            square_grid(2)
                .into_iter()
                .chain((2..40).flat_map(|i| [[i as f64, 0.0], [i as f64, 1.0]]))
                .collect(),
        ),
    ]
}

/// Every way of inserting gives the triangle set of the points as given, whatever their order.
#[test]
fn cocircular_points_give_one_triangle_set_whatever_the_order() {
    let mut rng = SplitMix64::new(0x71E5);
    for (name, points) in cases(&mut rng) {
        let expected = triangulated(name, "Q", &points);
        for round in 0..4 {
            let permuted = shuffled(&points, &mut rng);
            let context = format!("{name}, permutation {round}");
            for switches in ["Q", "Qi"] {
                let got = triangulated(&context, switches, &permuted);
                assert_same(&got, &expected, &format!("{context}, \"{switches}\""));
            }
        }
        let got = triangulated_on_one_core(name, "Qi", &points);
        assert_same(&got, &expected, &format!("{name}: one core, \"Qi\""));
    }
}

/// Large enough for the two-core merge (≥ 20 000 points): one core, the merge, `i`, and
/// permutations agree.
#[test]
fn the_merge_and_one_core_agree_on_large_grids() {
    let mut rng = SplitMix64::new(0xB16);
    let large = [
        ("large square grid with duplicates", {
            let grid = square_grid(150);
            with_duplicates(grid, 300, &mut rng)
        }),
        ("large squares at 45 degrees", shifted_rows(110, 201, 0.5)),
    ];
    for (name, points) in large {
        assert!(points.len() >= merge::PARALLEL_THRESHOLD);
        let expected = triangulated_on_one_core(name, "Q", &points);
        let got = triangulated_by_the_merge(name, &points);
        assert_same(&got, &expected, &format!("{name}: the merge"));
        let got = triangulated(name, "Q", &points);
        assert_same(&got, &expected, &format!("{name}: default"));
        let got = triangulated(name, "Qi", &points);
        assert_same(&got, &expected, &format!("{name}: \"Qi\""));
        let permuted = shuffled(&points, &mut rng);
        let context = format!("{name}, permuted");
        let got = triangulated_by_the_merge(&context, &permuted);
        assert_same(&got, &expected, &format!("{context}: the merge"));
        let got = triangulated_on_one_core(&context, "Q", &permuted);
        assert_same(&got, &expected, &format!("{context}: one core"));
    }
}

/// Whether the closed circumdisk of the triangle lies strictly inside the rectangle `window`
/// (`[x0, y0, x1, y1]`), with a margin for the rounding of the circumcentre.
fn disk_inside(t: &[Key; 3], window: [f64; 4]) -> bool {
    let [a, b, c] = t.map(|k| [f64::from_bits(k[0]), f64::from_bits(k[1])]);
    let (bx, by) = (b[0] - a[0], b[1] - a[1]);
    let (cx, cy) = (c[0] - a[0], c[1] - a[1]);
    let d = 2.0 * (bx * cy - by * cx);
    let (b2, c2) = (bx * bx + by * by, cx * cx + cy * cy);
    let ux = (cy * b2 - by * c2) / d;
    let uy = (bx * c2 - cx * b2) / d;
    let r = (ux * ux + uy * uy).sqrt() * (1.0 + 1e-9) + 1e-9;
    let centre = [a[0] + ux, a[1] + uy];
    centre[0] - r > window[0]
        && centre[0] + r < window[2]
        && centre[1] - r > window[1]
        && centre[1] + r < window[3]
}

/// A subset renumbered (the points in a random window, a random part of the others, shuffled)
/// agrees with the full set: the tiles of a distributed triangulation can agree with one call.
#[test]
fn subsets_agree_with_the_full_set() {
    let mut rng = SplitMix64::new(0x5B5E7);
    let sets = [
        ("square grid with duplicates", {
            let grid = square_grid(40);
            with_duplicates(grid, 80, &mut rng)
        }),
        ("squares at 45 degrees", shifted_rows(30, 61, 0.5)),
        ("concentric circles", concentric_circles()),
    ];
    for (name, points) in sets {
        let full = triangulated(name, "Q", &points);
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        for p in &points {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        for round in 0..6 {
            let context = format!("{name}, subset {round}");
            let corner = |k: usize, r: &mut SplitMix64| lo[k] + r.next_f64() * (hi[k] - lo[k]);
            let (x0, x1) = (corner(0, &mut rng), corner(0, &mut rng));
            let (y0, y1) = (corner(1, &mut rng), corner(1, &mut rng));
            let window = [x0.min(x1), y0.min(y1), x0.max(x1), y0.max(y1)];
            let inside = |p: &Point| {
                p[0] > window[0] && p[0] < window[2] && p[1] > window[1] && p[1] < window[3]
            };
            let keep = 0.2 + 0.6 * rng.next_f64();
            let mut subset: Vec<Point> = points
                .iter()
                .copied()
                .filter(|p| inside(p) || rng.next_f64() < keep)
                .collect();
            rng.shuffle(&mut subset);
            if subset.len() < 3 {
                continue;
            }
            let switches = ["Q", "Qi"][round % 2];
            let part = triangulated(&context, switches, &subset);
            let in_subset: BTreeSet<Key> = subset.iter().map(|&p| key(p)).collect();
            let mut compared = 0;
            for t in &full {
                if t.iter().all(|k| in_subset.contains(k)) {
                    compared += 1;
                    assert!(
                        part.contains(t),
                        "{context}: full triangle {:?} missing",
                        t.map(|k| k.map(f64::from_bits))
                    );
                }
            }
            for t in &part {
                if disk_inside(t, window) {
                    compared += 1;
                    assert!(
                        full.contains(t),
                        "{context}: triangle {:?} not in the full set",
                        t.map(|k| k.map(f64::from_bits))
                    );
                }
            }
            assert!(
                compared > 0 || subset.len() < 50,
                "{context}: nothing compared"
            );
        }
    }
}
