//! A driver for profilers (`perf record`, `valgrind --tool=callgrind`): runs our `triangulate`
//! on the benchmarks' inputs, without the reference library and without the benchmarks'
//! interleaving. `cargo run --release --example profile -- cdt 100000 3` (mode `cdt`, `hole`
//! (the square with a hole of benches/refine.rs; size: the circle's segments, 256 there) or
//! `delaunay`, size, repetitions; `SWITCHES` overrides the switches). Prints each run's times.

#[allow(dead_code)]
#[path = "../tests/common/rng.rs"]
mod rng;

use std::time::Instant;

use rng::SplitMix64;
use triangle_rs::{Hooks, Input, Options, SwitchSource};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mode = args.get(1).map_or("cdt", String::as_str);
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let reps: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1);
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
    for _ in 0..reps {
        let (start, cpu) = (Instant::now(), cpu_seconds());
        let (output, _) =
            triangle_rs::triangulate(&options, &input, &Hooks::default()).expect("triangulate");
        println!(
            "{mode} n={n} \"{switches}\": wall {:.3} s, cpu {:.3} s, {} triangles",
            start.elapsed().as_secs_f64(),
            cpu_seconds() - cpu,
            output.triangle_count
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
