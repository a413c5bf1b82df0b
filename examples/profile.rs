//! A driver for profilers (`perf record`, `valgrind --tool=callgrind`): runs our `triangulate`
//! on the benchmarks' inputs, without the reference library and without the benchmarks'
//! interleaving. `cargo run --release --example profile -- cdt 100000 3` (mode `cdt`, `hole`
//! (the square with a hole of benches/refine.rs; size: the circle's segments, 256 there) or
//! `delaunay`, or `grid` (a square grid of about that many points: in-circle ties everywhere),
//! size, repetitions; `SWITCHES` overrides the switches). Prints each run's times.
//! Mode `files` profiles the command-line program's file work on the Delaunay input in memory:
//! writing its `.node` text, reading it back, and writing the `.ele` of its triangulation. Mode
//! `order` times the default insertion order (Hilbert curve in random rounds) of those points,
//! with the points gathered afterwards and carried through the sort. Mode `dist` triangulates
//! (`Qz`) one of the distributions of the Delaunay benchmark (tests/common/points.rs,
//! `distributions`), named by the fourth argument with `_` for spaces (`cargo run --release
//! --example profile -- dist 1000000 1 kuzmin`).

#[allow(dead_code)]
#[path = "../tests/common/rng.rs"]
mod rng;

#[allow(dead_code)]
#[path = "../tests/common/points.rs"]
mod points;

use std::time::Instant;

use rng::SplitMix64;
use triangle_rs::{Hooks, Input, Options, SwitchSource};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mode = args.get(1).map_or("cdt", String::as_str);
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let reps: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1);
    if mode == "files" {
        return profile_files(n, reps);
    }
    if mode == "order" {
        return profile_order(n, reps);
    }
    let mut points = Vec::with_capacity(2 * n);
    let mut segments = Vec::new();
    let mut holes = Vec::new();
    let default_switches = match mode {
        "cdt" => {
            // The star polygon of benches/cdt.rs (same seed, same generator).
            let mut rng = SplitMix64::new(0x5EED_0C07);
            let mut angles: Vec<f64> = (0..n)
                .map(|_| rng.next_f64() * std::f64::consts::TAU)
                .collect();
            angles.sort_by(f64::total_cmp);
            for a in angles {
                let r = 0.1 + 0.9 * rng.next_f64();
                points.extend_from_slice(&[r * a.cos(), r * a.sin()]);
            }
            segments = (0..n)
                .flat_map(|i| [i as i32 + 1, ((i + 1) % n) as i32 + 1])
                .collect();
            "pQ"
        }
        "hole" => {
            // The square with a hole of benches/refine.rs (tests/common/pslg.rs,
            // `square_with_hole`: a circle of `n` segments, four free-standing segments).
            let mut add_chain = |polygon: &[[f64; 2]], closed: bool| {
                let first = (points.len() / 2) as i32 + 1;
                let k = polygon.len() as i32;
                points.extend(polygon.iter().flatten());
                let ends = if closed { k } else { k - 1 };
                segments.extend((0..ends).flat_map(|i| [first + i, first + (i + 1) % k]));
            };
            add_chain(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], true);
            let circle: Vec<[f64; 2]> = (0..n)
                .map(|k| {
                    let angle = std::f64::consts::TAU * k as f64 / n as f64;
                    [0.5 + 0.2 * angle.cos(), 0.5 + 0.2 * angle.sin()]
                })
                .collect();
            add_chain(&circle, true);
            for [a, b] in [
                [[0.10, 0.12], [0.20, 0.17]],
                [[0.82, 0.10], [0.90, 0.21]],
                [[0.85, 0.80], [0.93, 0.87]],
                [[0.08, 0.83], [0.17, 0.90]],
            ] {
                add_chain(&[a, b], false);
            }
            holes.extend([0.5, 0.5]);
            "pq30a0.0000014Q"
        }
        "dist" => {
            let name = args.get(4).map_or("uniform", String::as_str);
            let (_, generate) = points::distributions()
                .into_iter()
                .find(|(d, _)| d.replace(' ', "_") == name)
                .unwrap_or_else(|| panic!("no distribution {name}"));
            points.extend(generate(n, 0x5EED_0001).into_iter().flatten());
            "Qz"
        }
        "grid" => {
            // A square grid of about `n` points: cocircular everywhere, so every cell's diagonal
            // is a tie of the in-circle test, decided by the perturbation.
            let side = (n as f64).sqrt().ceil() as usize;
            for k in 0..side * side {
                points.extend_from_slice(&[(k % side) as f64, (k / side) as f64]);
            }
            "Qz"
        }
        _ => {
            let mut rng = SplitMix64::new(0x5EED_0001);
            for _ in 0..n {
                points.extend_from_slice(&[rng.next_f64(), rng.next_f64()]);
            }
            "Qz"
        }
    };
    let switches = std::env::var("SWITCHES").unwrap_or_else(|_| default_switches.to_string());
    let options = Options::parse(&switches, SwitchSource::Library).expect("switches");
    let input = Input {
        points: &points,
        segments: &segments,
        holes: &holes,
        ..Input::default()
    };
    // With `PHASES` set, each phase's start and end is printed, in milliseconds from the call's
    // start (the progress reports at the start and end of each phase).
    let phases = std::env::var_os("PHASES").is_some();
    // With `MMAP` set, large blocks come from mmap and are given back when freed, as in the
    // benchmarks (`large_blocks_from_mmap`): each run then pays for touching fresh pages.
    let fresh_memory = std::env::var_os("MMAP").is_some();
    if fresh_memory {
        // SAFETY: a valid mallopt parameter and value.
        unsafe { libc::mallopt(libc::M_MMAP_THRESHOLD, 128 * 1024) };
    }
    for _ in 0..reps {
        if fresh_memory {
            // SAFETY: no arguments to check; gives free heap memory back to the system.
            unsafe { libc::malloc_trim(0) };
        }
        let (start, cpu) = (Instant::now(), cpu_seconds());
        let report = |progress: triangle_rs::Progress| {
            if progress.done == 0 || progress.done == progress.estimate {
                let at = start.elapsed().as_secs_f64() * 1e3;
                eprint!("{:?} {} at {at:.1} ms; ", progress.phase, progress.done);
            }
        };
        let hooks = Hooks {
            progress: phases.then_some(&report as &(dyn Fn(triangle_rs::Progress) + Sync)),
            ..Hooks::default()
        };
        let (output, _) = triangle_rs::triangulate(&options, &input, &hooks).expect("triangulate");
        if phases {
            eprintln!();
        }
        println!(
            "{mode} n={n} \"{switches}\": wall {:.3} s, cpu {:.3} s, {} triangles",
            start.elapsed().as_secs_f64(),
            cpu_seconds() - cpu,
            output.triangle_count
        );
    }
}

/// Times writing the `.node` text of `n` uniform points (the Delaunay mode's), reading it back
/// and writing the `.ele` text of their triangulation, each `reps` times (the writers write to
/// a sink).
fn profile_files(n: usize, reps: usize) {
    use triangle_rs::io::files::{read_node, write_ele, write_node, EleData, NodeData};
    let mut rng = SplitMix64::new(0x5EED_0001);
    let points: Vec<f64> = (0..2 * n).map(|_| rng.next_f64()).collect();
    let markers = vec![0; n];
    let node = NodeData {
        points: &points,
        markers: Some(&markers),
        ..NodeData::default()
    };
    let options = Options::parse("Qz", SwitchSource::Library).expect("switches");
    let input = Input {
        points: &points,
        ..Input::default()
    };
    let (output, _) =
        triangle_rs::triangulate(&options, &input, &Hooks::default()).expect("triangulate");
    let triangles = output.triangles.expect("triangles");
    let ele = EleData {
        corners: 3,
        triangles: &triangles,
        ..EleData::default()
    };
    let mut text = Vec::with_capacity(48 * n);
    write_node(&mut text, &node, 0, None).expect("in memory");
    let text = String::from_utf8(text).expect("ASCII");
    for _ in 0..reps {
        // Written to a sink: the times leave out the page faults of a fresh buffer.
        let (start, cpu) = (Instant::now(), cpu_seconds());
        write_node(&mut std::io::sink(), &node, 0, None).expect("to a sink");
        let write_node_times = (start.elapsed().as_secs_f64(), cpu_seconds() - cpu);
        let (start, cpu) = (Instant::now(), cpu_seconds());
        let read = read_node(&text, "points.node").expect("read back");
        let read_times = (start.elapsed().as_secs_f64(), cpu_seconds() - cpu);
        assert!(read.points == points, "the points read back differ");
        let (start, cpu) = (Instant::now(), cpu_seconds());
        write_ele(&mut std::io::sink(), &ele, 0, None).expect("to a sink");
        let write_ele_times = (start.elapsed().as_secs_f64(), cpu_seconds() - cpu);
        println!(
            "files n={n}: write .node {:.3} s (cpu {:.3}), read .node {:.3} s (cpu {:.3}), \
             write .ele {:.3} s (cpu {:.3}); .node {} bytes",
            write_node_times.0,
            write_node_times.1,
            read_times.0,
            read_times.1,
            write_ele_times.0,
            write_ele_times.1,
            text.len(),
        );
    }
}

/// Times the default insertion order of `n` uniform points (the Delaunay mode's) with the
/// points gathered in it afterwards, and with the points carried through the sort, `reps` times.
fn profile_order(n: usize, reps: usize) {
    let mut rng = SplitMix64::new(0x5EED_0001);
    let points: Vec<[f64; 2]> = (0..n).map(|_| [rng.next_f64(), rng.next_f64()]).collect();
    for _ in 0..reps {
        let (start, cpu) = (Instant::now(), cpu_seconds());
        let order = triangle_rs::algorithms::delaunay::order::multiscale_order(&points);
        let sorted: Vec<[f64; 2]> = order.iter().map(|&v| points[v as usize]).collect();
        let gathered = (start.elapsed().as_secs_f64(), cpu_seconds() - cpu);
        drop((order, sorted));
        let (start, cpu) = (Instant::now(), cpu_seconds());
        let (order, sorted) =
            triangle_rs::algorithms::delaunay::order::multiscale_order_and_points(&points, None);
        println!(
            "order n={n}: then gathered wall {:.3} s, cpu {:.3} s; carried wall {:.3} s, \
             cpu {:.3} s (first {:?}, {:?})",
            gathered.0,
            gathered.1,
            start.elapsed().as_secs_f64(),
            cpu_seconds() - cpu,
            &order[..3],
            sorted[0]
        );
    }
}

/// CPU time of the whole process (all threads), in seconds.
fn cpu_seconds() -> f64 {
    let mut now = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: a valid clock id and a valid out-pointer.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut now) };
    now.tv_sec as f64 + now.tv_nsec as f64 * 1e-9
}
