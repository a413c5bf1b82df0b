//! Constrained Delaunay triangulation of a random star-shaped polygon (issue 3's benchmark):
//! vertices at sorted uniformly random angles, radius uniform in [0.1, 1], consecutive vertices
//! joined and the last to the first; switches `pQ`. Our `triangulate` through the C ABI against
//! Debian's Triangle 1.6 in the same process, interleaved (ours, Triangle, ours, …), `REPS`
//! repetitions each (default 3); prints the medians of wall-clock and process CPU time and the
//! ratios, and checks that both give the polygon's n − 2 triangles, the same ones.
//!
//! Sizes: env `N`, a comma-separated list (default 100_000,1_000_000). Triangle grows faster than
//! n log n here (about 2 s at 10^5 vertices, 13 s at 3·10^5), so it runs only up to
//! `TRIANGLE_MAX` vertices (default 300_000); larger sizes time ours alone. With two sizes or
//! more, our growth from the smallest to the largest is printed against n log n's.
//! Run with `cargo bench --bench cdt` (e.g. `N=100000,300000,1000000 cargo bench --bench cdt`).
//! Under `cargo test --all-targets` it runs as a smoke test (1000 and 4000 vertices, 1 rep).

#[path = "../tests/common/mod.rs"]
mod common;

use common::pslg::star_polygon;
use common::timing::{benchmarking, compare_interleaved, number_from_env, sizes_from_env};
use common::MeshInput;

const SWITCHES: &str = "pQ";
const SEED: u64 = 0x5EED_0C07;

fn main() {
    let (sizes, reps) = if benchmarking() {
        let reps = number_from_env("REPS", 3).max(1);
        (sizes_from_env("N", &[100_000, 1_000_000]), reps)
    } else {
        (vec![1000, 4000], 1)
    };
    let triangle_max = number_from_env("TRIANGLE_MAX", 300_000);
    let reference = common::reference();

    println!("CDT of a random star-shaped polygon, switches \"{SWITCHES}\", {reps} interleaved repetition(s)");
    let mut ours_by_size = Vec::new();
    for &n in &sizes {
        let (points, segments) = star_polygon(n, SEED);
        let input = MeshInput {
            // Triangle's default numbering starts at 1.
            segments: segments.into_iter().map(|s| s.map(|v| v + 1)).collect(),
            ..MeshInput::from_points(points)
        };
        let triangle = reference.filter(|_| n <= triangle_max);
        println!("n = {n}:");
        let (ours, mesh) = compare_interleaved(SWITCHES, &input, reps, triangle, "  ");
        if triangle.is_none() {
            let why = if reference.is_none() {
                "not installed"
            } else {
                "not run above TRIANGLE_MAX"
            };
            println!("  Triangle 1.6: {why}");
        }
        assert_eq!(
            mesh.counts.triangles as usize,
            n - 2,
            "{n} vertices: a simple polygon has n - 2 triangles"
        );
        ours_by_size.push((n, ours));
    }
    if let (Some(&(n1, first)), Some(&(n2, last))) = (ours_by_size.first(), ours_by_size.last()) {
        if n2 > n1 {
            let n_log_n = |n: usize| n as f64 * (n as f64).ln();
            println!(
                "growth of ours from {n1} to {n2} vertices: {:.2}× wall, {:.2}× cpu; n log n grows {:.2}×",
                last.wall.as_secs_f64() / first.wall.as_secs_f64(),
                last.cpu.as_secs_f64() / first.cpu.as_secs_f64(),
                n_log_n(n2) / n_log_n(n1)
            );
        }
    }
}
