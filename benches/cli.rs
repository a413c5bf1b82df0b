//! The command-line race (issue 14): the whole run of Debian's `triangle` and of our
//! `triangle-rs` on the same generated `.node` file of N uniform random points (seeded, `%.17g`
//! coordinates as Triangle writes them), switches `-Q`: read, triangulate, write `.node` and
//! `.ele`. The two programs run interleaved `REPS` times (default 5) in a temporary directory;
//! prints median wall-clock and CPU seconds (user + system of the child) and Triangle's median
//! divided by ours, then checks that both wrote the same triangle set and the same vertices.
//!
//! Sizes: env `N`, a comma-separated list (default 1_000_000). Run with
//! `cargo bench --bench cli`. Under `cargo test --all-targets` it runs as a smoke test (2000
//! points, one repetition, same checks).

#[path = "../tests/cli_support/mod.rs"]
mod cli_support;
#[path = "../tests/common/mod.rs"]
mod common;

use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

use common::checks::canonical_triangle;
use common::points;
use common::timing::{benchmarking, median, number_from_env, sizes_from_env};
use triangle_rs::io::files::{self, g17};

const SEED: u64 = 0x5EED_0001;

/// The user + system CPU time of the children waited for so far.
fn children_cpu() -> Duration {
    // SAFETY: a zeroed rusage is a valid out-value, and RUSAGE_CHILDREN a valid selector.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: `usage` is a valid, writable rusage.
    unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut usage) };
    let time = |t: libc::timeval| Duration::new(t.tv_sec as u64, t.tv_usec as u32 * 1000);
    time(usage.ru_utime) + time(usage.ru_stime)
}

/// Runs `program -Q name` in `dir`: (wall, CPU) times.
fn timed_run(program: &Path, dir: &Path, name: &str) -> (Duration, Duration) {
    let (wall, cpu) = (Instant::now(), children_cpu());
    let status = Command::new(program)
        .args(["-Q", name])
        .current_dir(dir)
        .status()
        .unwrap_or_else(|e| panic!("run {}: {e}", program.display()));
    let times = (wall.elapsed(), children_cpu() - cpu);
    assert!(status.success(), "{} -Q {name} failed", program.display());
    times
}

/// The `.node` text of `n` uniform points, numbered from 1.
fn node_text(n: usize) -> String {
    let mut text = format!("{n} 2 0 0\n");
    for (i, p) in points::uniform(n, SEED).iter().enumerate() {
        text.push_str(&format!("{} {} {}\n", i + 1, g17(p[0]), g17(p[1])));
    }
    text
}

/// The triangles of an `.ele` file over the vertices of its `.node` file, as sets of vertex
/// coordinates (bit patterns), canonical and sorted: comparable whatever the numbering.
fn triangle_set(dir: &Path, base: &str) -> Vec<[[u64; 2]; 3]> {
    let read = |ext: &str| {
        let name = format!("{base}.{ext}");
        std::fs::read_to_string(dir.join(&name)).unwrap_or_else(|e| panic!("read {name}: {e}"))
    };
    let node = files::read_node(&read("node"), "node").expect("a .node file");
    let ele = files::read_ele(&read("ele"), "ele").expect("an .ele file");
    let first = node.first_number.unwrap_or(1);
    let point = |v: i32| {
        let i = (i64::from(v) - first) as usize;
        [
            node.points[2 * i].to_bits(),
            node.points[2 * i + 1].to_bits(),
        ]
    };
    let mut set: Vec<[[u64; 2]; 3]> = ele
        .triangles
        .chunks_exact(ele.corners)
        .map(|t| canonical_triangle([point(t[0]), point(t[1]), point(t[2])]))
        .collect();
    set.sort_unstable();
    set
}

fn main() {
    let (sizes, reps) = if benchmarking() {
        (
            sizes_from_env("N", &[1_000_000]),
            number_from_env("REPS", 5).max(1),
        )
    } else {
        (vec![2_000], 1)
    };
    let ours = cli_support::ours();
    let reference = cli_support::reference();
    for n in sizes {
        let dir = cli_support::TempDir::new("cli-bench");
        let text = node_text(n);
        // One input file per program: each writes its `.1.node` and `.1.ele` beside it.
        dir.write("ours.node", &text);
        dir.write("triangle.node", &text);
        drop(text);
        let mut ours_times = Vec::new();
        let mut triangle_times = Vec::new();
        for _ in 0..reps {
            if let Some(reference) = &reference {
                triangle_times.push(timed_run(reference, dir.path(), "triangle.node"));
            }
            ours_times.push(timed_run(&ours, dir.path(), "ours.node"));
        }
        let medians = |times: &[(Duration, Duration)]| {
            (
                median(times.iter().map(|t| t.0).collect()).as_secs_f64(),
                median(times.iter().map(|t| t.1).collect()).as_secs_f64(),
            )
        };
        println!(
            "Command line, {n}-point .node -> .1.node + .1.ele (-Q), medians of {reps} interleaved run(s)"
        );
        println!("| {:<12} | {:>7} | {:>7} |", "", "wall s", "cpu s");
        println!("|{:-<14}|{:->9}|{:->9}|", "", "", "");
        let (ours_wall, ours_cpu) = medians(&ours_times);
        if !triangle_times.is_empty() {
            let (wall, cpu) = medians(&triangle_times);
            println!("| {:<12} | {wall:>7.3} | {cpu:>7.3} |", "Triangle 1.6");
            println!(
                "| {:<12} | {ours_wall:>7.3} | {ours_cpu:>7.3} |",
                "triangle-rs"
            );
            println!(
                "Triangle's / ours: {:.2}× wall, {:.2}× cpu",
                wall / ours_wall,
                cpu / ours_cpu
            );
            let (a, b) = (
                triangle_set(dir.path(), "ours.1"),
                triangle_set(dir.path(), "triangle.1"),
            );
            assert!(
                a == b,
                "the triangle sets differ: {} vs {}",
                a.len(),
                b.len()
            );
            println!("our triangle set is Triangle's ({} triangles)", a.len());
        } else {
            println!(
                "| {:<12} | {ours_wall:>7.3} | {ours_cpu:>7.3} |",
                "triangle-rs"
            );
            println!("Triangle 1.6: not installed, no comparison");
        }
    }
}
