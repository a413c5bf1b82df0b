//! Delaunay triangulation of N uniform random points (seeded; N = 10^6 unless env `N` says
//! otherwise): our `triangulate` through the C ABI against Debian's Triangle 1.6 in the same
//! process, interleaved (ours, Triangle, ours, Triangle, …), `REPS` repetitions each (at least 3,
//! default 5). (Under `cargo test --all-targets` it runs as a smoke test with 2000 points.) Prints the medians of wall-clock and process CPU time and the ratios, and checks
//! that the two triangle sets are identical. Run with `cargo bench --bench delaunay`.

#[path = "../tests/common/mod.rs"]
mod common;

use common::points;
use common::timing::{benchmarking, compare_interleaved, number_from_env};
use common::MeshInput;

const SWITCHES: &str = "Qz";

fn main() {
    let n = number_from_env("N", if benchmarking() { 1_000_000 } else { 2_000 });
    let reps = number_from_env("REPS", 5).max(3);
    let input = MeshInput::from_points(points::uniform(n, 0x5EED_0001));
    let reference = common::reference();

    println!("Delaunay triangulation of {n} uniform random points, switches \"{SWITCHES}\", {reps} interleaved repetitions");
    compare_interleaved(SWITCHES, &input, reps, reference, "");
    if reference.is_none() {
        println!("Triangle:     not installed, no comparison");
    }
}
