//! The Delaunay race (issues 14 and 38): the point distributions of Su and Drysdale's comparison
//! of Delaunay algorithms (1997) — uniform, normal, Kuzmin, line singularity, clusters, points on
//! a circle's arc, a jittered grid — plus clusters of mixed spreads and a dense patch in a
//! square (tests/common/points.rs, `distributions`), each seeded, triangulated by Debian's
//! Triangle 1.6, ours on one core and on two threads (both through the C ABI, switches `Qz`),
//! and the Rust peers spade, cdt and delaunator, interleaved round-robin `REPS` times (default
//! 3). Prints one table per distribution and size (median wall-clock and CPU seconds, Triangle's
//! median times divided by each one's, peak memory per vertex — growth of VmHWM over VmRSS
//! during the call, outputs included — and the triangle count), then one table of the ratios
//! per distribution and size; checks that our triangle sets (both ways) are Triangle's.
//!
//! Sizes: env `N`, a comma-separated list (default `100000,1000000`; e.g.
//! `N=100000,1000000,4000000`). `DIST` picks distributions by name (comma-separated, `_` for
//! spaces, e.g. `DIST=kuzmin,dense_patch`); `PEERS=0` leaves the Rust peers out.
//! "One core": the library reads the CPU count once per process, so our one-core runs are made
//! by a child process (this program again) pinned to one CPU before its first call; it reports
//! its times, peak memory and a hash of its triangle set.
//! Run with `cargo bench --bench delaunay`. Under `cargo test --all-targets` it runs as a smoke
//! test (2000 points of each distribution, one repetition, same checks).

#[path = "../tests/common/mod.rs"]
mod common;

use std::hash::{Hash, Hasher};
use std::os::raw::{c_char, c_void};
use std::time::Duration;

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
/// The environment variable that makes this program the one-core child: `<distribution>,<n>`.
const CHILD: &str = "DELAUNAY_BENCH_ONE_CORE";

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
/// ours) a hash of the sorted canonical triangles.
struct Run {
    times: Times,
    peak_bytes: u64,
    triangles: usize,
    triangle_set: Option<u64>,
}

/// The hash of a sorted triangle set (the same in every process of this program).
fn set_hash(triangles: &[[i32; 3]]) -> u64 {
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    triangles.hash(&mut hasher);
    hasher.finish()
}

/// One call through the C ABI (ours or Triangle's), measured around the C call alone.
fn c_abi_run(reference: Option<&'static Reference>, input: &MeshInput) -> Run {
    let measurement = std::cell::Cell::new(None);
    let call = |s: *mut c_char, i: *mut TriangulateIO, o: *mut TriangulateIO, v| {
        let (times, peak, result) = measured(|| match reference {
            // SAFETY: valid switches and structs prepared by `run_call`; finite points, which
            // Triangle accepts.
            Some(r) => unsafe {
                r.triangulate_raw(s, i, o, v);
                Ok(())
            },
            // SAFETY: as above, for our exported function.
            None => ours_status(unsafe { triangle_rs::ffi::triangulate(s, i, o, v) }),
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
        triangle_set: Some(set_hash(&triangle_set)),
    }
}

/// The points of the distribution called `name` (`_` for spaces).
fn generate(name: &str, n: usize) -> Vec<Point> {
    let (_, generator) = points::distributions()
        .into_iter()
        .find(|(d, _)| d.replace(' ', "_") == name)
        .unwrap_or_else(|| panic!("no distribution {name}"));
    generator(n, SEED)
}

/// The one-core child: pins itself to the CPU it runs on before any call of the library (which
/// then sees one core for the life of the process), makes one call and prints its measures.
fn one_core_child(spec: &str) {
    let (name, n) = spec.split_once(',').expect("<distribution>,<n>");
    let n: usize = n.parse().expect("a point count");
    // SAFETY: cpu_set_t is plain data; the calls get valid pointers and its true size.
    unsafe {
        let mut one: libc::cpu_set_t = std::mem::zeroed();
        libc::CPU_SET(libc::sched_getcpu().max(0) as usize, &mut one);
        libc::sched_setaffinity(0, std::mem::size_of::<libc::cpu_set_t>(), &one);
    }
    large_blocks_from_mmap();
    let input = MeshInput::from_points(generate(name, n));
    let run = c_abi_run(None, &input);
    println!(
        "{} {} {} {} {}",
        run.times.wall.as_nanos(),
        run.times.cpu.as_nanos(),
        run.peak_bytes,
        run.triangles,
        run.triangle_set.expect("ours")
    );
}

/// A run of the one-core child on distribution `name`, `n` points.
fn one_core_run(name: &str, n: usize) -> Run {
    let exe = std::env::current_exe().expect("this program");
    let output = std::process::Command::new(exe)
        .env(CHILD, format!("{name},{n}"))
        .output()
        .expect("the one-core child runs");
    let text = String::from_utf8_lossy(&output.stdout);
    let fields: Vec<u64> = text
        .split_whitespace()
        .map(|f| f.parse().expect("a number"))
        .collect();
    assert!(
        output.status.success() && fields.len() == 5,
        "the one-core child failed: {text} {}",
        String::from_utf8_lossy(&output.stderr)
    );
    Run {
        times: Times {
            wall: Duration::from_nanos(fields[0]),
            cpu: Duration::from_nanos(fields[1]),
        },
        peak_bytes: fields[2],
        triangles: fields[3] as usize,
        triangle_set: Some(fields[4]),
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
            measured(|| cdt::triangulate_points(&pairs).map_or(0, |t| t.len()))
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

/// One line of the final table: a distribution, a size and each contestant's median times.
struct Summary {
    name: &'static str,
    n: usize,
    medians: Vec<Times>,
}

fn main() {
    if let Ok(spec) = std::env::var(CHILD) {
        return one_core_child(&spec);
    }
    let (sizes, reps) = if benchmarking() {
        (
            sizes_from_env("N", &[100_000, 1_000_000]),
            number_from_env("REPS", 3).max(1),
        )
    } else {
        (vec![2_000], 1)
    };
    let chosen: Option<Vec<String>> = std::env::var("DIST")
        .ok()
        .map(|list| list.split(',').map(|s| s.trim().to_string()).collect());
    large_blocks_from_mmap();
    let reference = common::reference();
    let mut contestants = vec![Contestant::OursOneCore, Contestant::OursTwoThreads];
    if number_from_env("PEERS", 1) != 0 {
        contestants.extend([Contestant::Spade, Contestant::Cdt, Contestant::Delaunator]);
    }
    if reference.is_some() {
        contestants.insert(0, Contestant::Triangle);
    }
    let mut summaries = Vec::new();
    for (name, _) in points::distributions() {
        let key = name.replace(' ', "_");
        if chosen.as_ref().is_some_and(|c| !c.contains(&key)) {
            continue;
        }
        for &n in &sizes {
            let points = generate(&key, n);
            let input = MeshInput::from_points(points.clone());
            let mut runs: Vec<Vec<Run>> = contestants.iter().map(|_| Vec::new()).collect();
            for _ in 0..reps {
                for (k, &c) in contestants.iter().enumerate() {
                    let run = match c {
                        Contestant::Triangle => c_abi_run(reference, &input),
                        Contestant::OursOneCore => one_core_run(&key, n),
                        Contestant::OursTwoThreads => c_abi_run(None, &input),
                        _ => peer_run(c, &points),
                    };
                    runs[k].push(run);
                }
            }
            let medians = print_table(name, n, reps, &contestants, &runs);
            check_identical(&contestants, &runs);
            summaries.push(Summary { name, n, medians });
        }
    }
    if reference.is_none() {
        println!("Triangle 1.6: not installed, no comparison");
    } else {
        print_summary(&contestants, &summaries, reps);
    }
}

/// Prints the table of one distribution and size; returns each contestant's median times.
fn print_table(
    name: &str,
    n: usize,
    reps: usize,
    contestants: &[Contestant],
    runs: &[Vec<Run>],
) -> Vec<Times> {
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
        "Delaunay triangulation of {n} points, {name}, medians of {reps} interleaved run(s)"
    );
    let triangle = contestants.iter().position(|&c| c == Contestant::Triangle);
    let medians = print_race(&title, n, &rows, triangle);
    println!();
    medians
}

/// The ratios of Triangle's median times over each contestant's, one line per distribution and
/// size: wall-clock, and CPU time for ours on one core (the machine is shared).
fn print_summary(contestants: &[Contestant], summaries: &[Summary], reps: usize) {
    let triangle = contestants
        .iter()
        .position(|&c| c == Contestant::Triangle)
        .expect("Triangle ran");
    println!(
        "Triangle's median time / each one's (wall; cpu for one core), medians of {reps} \
         interleaved run(s)"
    );
    let mut header = format!(
        "| {:<16} | {:>9} | {:>10} |",
        "distribution", "n", "Triangle"
    );
    let mut rule = format!("|{:-<18}|{:->11}|{:->12}|", "", "", "");
    for &c in contestants.iter().filter(|&&c| c != Contestant::Triangle) {
        header.push_str(&format!(" {:>22} |", c.name()));
        rule.push_str(&format!("{:->24}|", ""));
    }
    println!("{header}\n{rule}");
    for s in summaries {
        let base = s.medians[triangle];
        let mut line = format!(
            "| {:<16} | {:>9} | {:>8.3} s |",
            s.name,
            s.n,
            base.wall.as_secs_f64()
        );
        for (k, &c) in contestants.iter().enumerate() {
            if c == Contestant::Triangle {
                continue;
            }
            let t = s.medians[k];
            let wall = base.wall.as_secs_f64() / t.wall.as_secs_f64();
            let cell = if c == Contestant::OursOneCore {
                let cpu = base.cpu.as_secs_f64() / t.cpu.as_secs_f64();
                format!("{wall:.2}× (cpu {cpu:.2}×)")
            } else {
                format!("{wall:.2}×")
            };
            line.push_str(&format!(" {cell:>22} |"));
        }
        println!("{line}");
    }
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
            "our triangle sets are Triangle's ({} triangles)\n",
            triangle.triangles
        );
    }
    for (c, r) in contestants.iter().zip(runs) {
        let count = r.last().map_or(0, |run| run.triangles);
        if count != ours.triangles {
            println!(
                "note: {} found {count} triangles, ours {}\n",
                c.name(),
                ours.triangles
            );
        }
    }
}
