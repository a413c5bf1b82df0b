//! The Delaunay race (issue 14): N uniform random points (seeded), triangulated in one process by
//! Debian's Triangle 1.6, ours on one core and on two threads (both through the C ABI, switches
//! `Qz`), and the Rust peers spade, cdt and delaunator, interleaved round-robin `REPS` times
//! (default 3). Prints one table per size: median wall-clock and CPU seconds, Triangle's median
//! times divided by each one's (wall and CPU: the machine is shared), peak memory per vertex (growth of VmHWM over VmRSS during
//! the call, outputs included) and the triangle count; checks that our triangle sets are
//! Triangle's.
//!
//! Sizes: env `N`, a comma-separated list (default 1_000_000; e.g. `N=1000000,4000000`).
//! "One core" pins the calling thread to one CPU for the call: our merge asks
//! `std::thread::available_parallelism`, which then says 1, and triangulates on that thread.
//! Run with `cargo bench --bench delaunay`. Under `cargo test --all-targets` it runs as a smoke
//! test (2000 points, one repetition, same checks).

#[path = "../tests/common/mod.rs"]
mod common;

use std::os::raw::{c_char, c_void};

use common::call::{ours_status, run_call, MeshInput};
use common::points::{self, Point};
use common::reference::Reference;
use common::timing::{
    benchmarking, large_blocks_from_mmap, measured, number_from_env, print_race, sizes_from_env,
    sorted_triangles, RaceRow, Times,
};
use triangle_rs::io::triangulateio::TriangulateIO;

const SWITCHES: &str = "Qz";
const SEED: u64 = 0x5EED_0001;

#[derive(Clone, Copy, PartialEq)]
enum Contestant {
    Triangle,
    OursOneCore,
    OursTwoThreads,
    Spade,
    Cdt,
    Delaunator,
}

impl Contestant {
    fn name(self) -> &'static str {
        match self {
            Contestant::Triangle => "Triangle 1.6",
            Contestant::OursOneCore => "triangle-rs, 1 core",
            Contestant::OursTwoThreads => "triangle-rs, 2 threads",
            Contestant::Spade => "spade",
            Contestant::Cdt => "cdt",
            Contestant::Delaunator => "delaunator",
        }
    }
}

/// One run: its times, the peak memory growth in bytes, the triangle count, and (Triangle and
/// ours) the sorted canonical triangles.
struct Run {
    times: Times,
    peak_bytes: u64,
    triangles: usize,
    triangle_set: Option<Vec<[i32; 3]>>,
}

/// Pins the calling thread to the CPU it runs on for `work`, then restores its affinity.
fn on_one_core<T>(work: impl FnOnce() -> T) -> T {
    // SAFETY: cpu_set_t is plain data; the calls get valid pointers and their true size.
    unsafe {
        let mut saved: libc::cpu_set_t = std::mem::zeroed();
        let size = std::mem::size_of::<libc::cpu_set_t>();
        libc::sched_getaffinity(0, size, &mut saved);
        let mut one: libc::cpu_set_t = std::mem::zeroed();
        libc::CPU_SET(libc::sched_getcpu().max(0) as usize, &mut one);
        libc::sched_setaffinity(0, size, &one);
        let result = work();
        libc::sched_setaffinity(0, size, &saved);
        result
    }
}

/// One call through the C ABI (ours or Triangle's), measured around the C call alone.
fn c_abi_run(reference: Option<&'static Reference>, one_core: bool, input: &MeshInput) -> Run {
    let measurement = std::cell::Cell::new(None);
    let call = |s: *mut c_char, i: *mut TriangulateIO, o: *mut TriangulateIO, v| {
        let (times, peak, result) = measured(|| match reference {
            // SAFETY: valid switches and structs prepared by `run_call`; uniform points, which
            // Triangle accepts.
            Some(r) => unsafe {
                r.triangulate_raw(s, i, o, v);
                Ok(())
            },
            None => {
                // SAFETY: as above, for our exported function.
                let ours = || ours_status(unsafe { triangle_rs::ffi::triangulate(s, i, o, v) });
                if one_core {
                    on_one_core(ours)
                } else {
                    ours()
                }
            }
        });
        measurement.set(Some((times, peak)));
        result
    };
    let free = |p: *mut c_void| match reference {
        // SAFETY: arrays from Triangle are freed with its trifree, ours with ours.
        Some(r) => unsafe { r.trifree(p) },
        None => unsafe { triangle_rs::ffi::trifree(p) },
    };
    let mesh = run_call(&call, &free, SWITCHES, input, false)
        .unwrap_or_else(|message| panic!("triangulate failed: {message}"));
    let (times, peak_bytes) = measurement.get().expect("the call ran");
    let triangle_set = sorted_triangles(&mesh);
    Run {
        times,
        peak_bytes,
        triangles: triangle_set.len(),
        triangle_set: Some(triangle_set),
    }
}

fn peer_run(contestant: Contestant, points: &[Point]) -> Run {
    let (times, peak_bytes, triangles) = match contestant {
        Contestant::Spade => {
            use spade::Triangulation as _;
            let vertices = common::points::spade_points(points);
            measured(|| {
                spade::DelaunayTriangulation::<spade::Point2<f64>>::bulk_load(vertices)
                    .expect("spade")
                    .num_inner_faces()
            })
        }
        Contestant::Cdt => {
            let pairs: Vec<(f64, f64)> = points.iter().map(|p| (p[0], p[1])).collect();
            measured(|| cdt::triangulate_points(&pairs).expect("cdt").len())
        }
        Contestant::Delaunator => {
            let converted: Vec<delaunator::Point> = points
                .iter()
                .map(|p| delaunator::Point { x: p[0], y: p[1] })
                .collect();
            measured(|| delaunator::triangulate(&converted).triangles.len() / 3)
        }
        _ => unreachable!("not a peer"),
    };
    Run {
        times,
        peak_bytes,
        triangles,
        triangle_set: None,
    }
}

fn main() {
    let (sizes, reps) = if benchmarking() {
        (
            sizes_from_env("N", &[1_000_000]),
            number_from_env("REPS", 3).max(1),
        )
    } else {
        (vec![2_000], 1)
    };
    large_blocks_from_mmap();
    let reference = common::reference();
    let mut contestants = vec![
        Contestant::OursOneCore,
        Contestant::OursTwoThreads,
        Contestant::Spade,
        Contestant::Cdt,
        Contestant::Delaunator,
    ];
    if reference.is_some() {
        contestants.insert(0, Contestant::Triangle);
    }
    for n in sizes {
        let points = points::uniform(n, SEED);
        let input = MeshInput::from_points(points.clone());
        let mut runs: Vec<Vec<Run>> = contestants.iter().map(|_| Vec::new()).collect();
        for _ in 0..reps {
            for (k, &c) in contestants.iter().enumerate() {
                let run = match c {
                    Contestant::Triangle => c_abi_run(reference, false, &input),
                    Contestant::OursOneCore => c_abi_run(None, true, &input),
                    Contestant::OursTwoThreads => c_abi_run(None, false, &input),
                    _ => peer_run(c, &points),
                };
                runs[k].push(run);
            }
        }
        print_table(n, reps, &contestants, &runs);
        check_identical(&contestants, &runs);
    }
    if reference.is_none() {
        println!("Triangle 1.6: not installed, no comparison");
    }
}

/// Prints the table of one size.
fn print_table(n: usize, reps: usize, contestants: &[Contestant], runs: &[Vec<Run>]) {
    let rows: Vec<RaceRow> = contestants
        .iter()
        .zip(runs)
        .map(|(c, r)| {
            let runs = r
                .iter()
                .map(|run| (run.times, run.peak_bytes, Some(run.triangles)));
            RaceRow::of(c.name(), runs)
        })
        .collect();
    let title = format!(
        "Delaunay triangulation of {n} uniform random points, medians of {reps} interleaved run(s)"
    );
    let triangle = contestants.iter().position(|&c| c == Contestant::Triangle);
    print_race(&title, n, &rows, triangle);
}

/// Our triangle sets (both ways) are Triangle's; every contestant found the same number.
fn check_identical(contestants: &[Contestant], runs: &[Vec<Run>]) {
    let last = |c: Contestant| {
        contestants
            .iter()
            .position(|&x| x == c)
            .and_then(|k| runs[k].last())
    };
    let ours = last(Contestant::OursOneCore).expect("ours ran");
    let two = last(Contestant::OursTwoThreads).expect("ours ran");
    assert!(
        ours.triangle_set == two.triangle_set,
        "one core and two threads differ"
    );
    if let Some(triangle) = last(Contestant::Triangle) {
        assert!(
            ours.triangle_set == triangle.triangle_set,
            "the triangle sets differ: {} triangles (ours) vs {} (Triangle's)",
            ours.triangles,
            triangle.triangles
        );
        println!(
            "our triangle sets are Triangle's ({} triangles)",
            triangle.triangles
        );
    }
    for r in runs {
        let count = r.last().map_or(0, |run| run.triangles);
        assert_eq!(
            count, ours.triangles,
            "a contestant found another triangle count"
        );
    }
}
