//! Constrained Delaunay triangulation of a random star-shaped polygon (issue 3's benchmark, issue
//! 14's table): vertices at sorted uniformly random angles, radius uniform in [0.1, 1],
//! consecutive vertices joined and the last to the first. Debian's Triangle 1.6 and ours (both
//! through the C ABI, switches `pQ`: the polygon's inside alone), and the Rust peers spade
//! (`ConstrainedDelaunayTriangulation::bulk_load_cdt`: the whole convex hull, nothing carved)
//! and cdt (`triangulate_with_edges`: the inside alone), interleaved round-robin `REPS` times
//! (default 3). Prints one table per size: median wall-clock and CPU seconds, Triangle's median
//! times divided by each one's (the machine may be shared: wall times are rough), peak memory
//! per vertex (growth of VmHWM over VmRSS during the call, outputs included) and the triangle
//! count. Checks that ours gives the polygon's n − 2 triangles, Triangle's (the CDT is unique
//! here), and that cdt finds as many.
//!
//! Sizes: env `N`, a comma-separated list (default 100_000,1_000_000). Triangle grows faster than
//! n log n here (about 2 s at 10^5 vertices, 13 s at 3·10^5), so it runs only up to
//! `TRIANGLE_MAX` vertices (default 300_000); the peers only up to `PEERS_MAX` (default
//! 1_000_000). With two sizes or more, our growth from the smallest to the largest is printed
//! against n log n's. Run with `cargo bench --bench cdt` (e.g. `REPS=5 N=100000 cargo bench
//! --bench cdt`). Under `cargo test --all-targets` it runs as a smoke test (1000 and 4000
//! vertices, one repetition, same checks).

#[path = "../tests/common/mod.rs"]
mod common;

use common::call::Triangulation;
use common::pslg::star_polygon;
use common::timing::{
    benchmarking, large_blocks_from_mmap, measured, measured_call, number_from_env, print_race,
    sizes_from_env, sorted_triangles, Library, RaceRow, Times,
};
use common::MeshInput;

const SWITCHES: &str = "pQ";
const SEED: u64 = 0x5EED_0C07;

#[derive(Clone, Copy, PartialEq)]
enum Contestant {
    Triangle,
    Ours,
    Spade,
    Cdt,
}

impl Contestant {
    fn name(self) -> &'static str {
        match self {
            Contestant::Triangle => "Triangle 1.6",
            Contestant::Ours => "triangle-rs",
            Contestant::Spade => "spade (whole hull)",
            Contestant::Cdt => "cdt",
        }
    }
}

/// One run: its times, the peak memory growth in bytes, the triangle count (`None`: the peer
/// failed), and (Triangle and ours) the output.
struct Run {
    times: Times,
    peak_bytes: u64,
    triangles: Option<usize>,
    mesh: Option<Triangulation>,
}

fn c_abi_run(library: Library, input: &MeshInput) -> Run {
    let (times, peak_bytes, mesh) = measured_call(library, SWITCHES, input);
    Run {
        times,
        peak_bytes,
        triangles: Some(mesh.counts.triangles as usize),
        mesh: Some(mesh),
    }
}

/// A peer on the polygon (zero-based segments); a panic inside it counts as a failed run (its
/// message is not printed: the table says "failed").
fn peer_run(contestant: Contestant, points: &[[f64; 2]], segments: &[[i32; 2]]) -> Run {
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let (times, peak_bytes, triangles) = match contestant {
        Contestant::Spade => {
            use spade::Triangulation as _;
            let vertices = common::points::spade_points(points);
            let edges: Vec<[usize; 2]> = segments.iter().map(|s| s.map(|v| v as usize)).collect();
            measured(|| {
                std::panic::catch_unwind(move || {
                    spade::ConstrainedDelaunayTriangulation::<spade::Point2<f64>>::bulk_load_cdt(
                        vertices, edges,
                    )
                    .map(|cdt| cdt.num_inner_faces())
                })
                .ok()
                .and_then(Result::ok)
            })
        }
        Contestant::Cdt => {
            let pairs: Vec<(f64, f64)> = points.iter().map(|p| (p[0], p[1])).collect();
            let edges: Vec<(usize, usize)> = segments
                .iter()
                .map(|s| (s[0] as usize, s[1] as usize))
                .collect();
            measured(|| {
                std::panic::catch_unwind(|| cdt::triangulate_with_edges(&pairs, &edges))
                    .ok()
                    .and_then(Result::ok)
                    .map(|triangles| triangles.len())
            })
        }
        _ => unreachable!("not a peer"),
    };
    std::panic::set_hook(hook);
    Run {
        times,
        peak_bytes,
        triangles,
        mesh: None,
    }
}

fn main() {
    let (sizes, reps) = if benchmarking() {
        let reps = number_from_env("REPS", 3).max(1);
        (sizes_from_env("N", &[100_000, 1_000_000]), reps)
    } else {
        (vec![1000, 4000], 1)
    };
    let triangle_max = number_from_env("TRIANGLE_MAX", 300_000);
    let peers_max = number_from_env("PEERS_MAX", 1_000_000);
    large_blocks_from_mmap();
    let reference = common::reference();

    let mut ours_by_size = Vec::new();
    for &n in &sizes {
        let (points, segments) = star_polygon(n, SEED);
        let input = MeshInput {
            // Triangle's default numbering starts at 1.
            segments: segments.iter().map(|s| s.map(|v| v + 1)).collect(),
            ..MeshInput::from_points(points.clone())
        };
        let mut contestants = vec![Contestant::Ours];
        let triangle = reference.filter(|_| n <= triangle_max);
        if triangle.is_some() {
            contestants.insert(0, Contestant::Triangle);
        }
        if n <= peers_max {
            contestants.extend([Contestant::Spade, Contestant::Cdt]);
        }
        let mut runs: Vec<Vec<Run>> = contestants.iter().map(|_| Vec::new()).collect();
        for _ in 0..reps {
            for (k, &c) in contestants.iter().enumerate() {
                let run = match c {
                    Contestant::Triangle => {
                        c_abi_run(Library::Triangle(triangle.expect("installed")), &input)
                    }
                    Contestant::Ours => c_abi_run(Library::Ours, &input),
                    _ => peer_run(c, &points, &segments),
                };
                runs[k].push(run);
            }
        }
        let medians = print_table(n, reps, &contestants, &runs);
        if triangle.is_none() {
            let why = if reference.is_none() {
                "not installed"
            } else {
                "not run above TRIANGLE_MAX"
            };
            println!("Triangle 1.6: {why}");
        }
        check(n, &contestants, &runs);
        let ours = contestants.iter().position(|&c| c == Contestant::Ours);
        ours_by_size.push((n, medians[ours.expect("ours ran")]));
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

/// Prints the table of one size; returns each contestant's median times.
fn print_table(n: usize, reps: usize, contestants: &[Contestant], runs: &[Vec<Run>]) -> Vec<Times> {
    let rows: Vec<RaceRow> = contestants
        .iter()
        .zip(runs)
        .map(|(c, r)| {
            let runs = r
                .iter()
                .map(|run| (run.times, run.peak_bytes, run.triangles));
            RaceRow::of(c.name(), runs)
        })
        .collect();
    let title = format!(
        "CDT of a random star-shaped polygon of {n} vertices (switches \"{SWITCHES}\"), medians of {reps} interleaved run(s)"
    );
    let triangle = contestants.iter().position(|&c| c == Contestant::Triangle);
    print_race(&title, n, &rows, triangle)
}

/// Ours gives the polygon's n − 2 triangles, Triangle's; cdt, when it succeeds, as many.
fn check(n: usize, contestants: &[Contestant], runs: &[Vec<Run>]) {
    let last = |c: Contestant| {
        contestants
            .iter()
            .position(|&x| x == c)
            .and_then(|k| runs[k].last())
    };
    let ours = last(Contestant::Ours).expect("ours ran");
    assert_eq!(
        ours.triangles,
        Some(n - 2),
        "{n} vertices: a simple polygon has n - 2 triangles"
    );
    let ours_mesh = ours.mesh.as_ref().expect("ours has its output");
    if let Some(triangle) = last(Contestant::Triangle) {
        let theirs = triangle.mesh.as_ref().expect("Triangle has its output");
        assert!(
            sorted_triangles(ours_mesh) == sorted_triangles(theirs),
            "the triangle sets differ: {} triangles (ours) vs {} (Triangle's)",
            n - 2,
            theirs.counts.triangles
        );
        println!("our triangle set is Triangle's ({} triangles)", n - 2);
    }
    if let Some(Some(count)) = last(Contestant::Cdt).map(|r| r.triangles) {
        assert_eq!(count, n - 2, "cdt found another triangle count");
    }
}
