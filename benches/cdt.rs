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

use std::ffi::CString;
use std::os::raw::c_void;
use std::time::{Duration, Instant};

use common::checks::canonical_triangle;
use common::pslg::star_polygon;
use common::timing::{cpu_time, median, number_from_env, seconds, sizes_from_env};
use triangle_rs::io::triangulateio::TriangulateIO;

const SWITCHES: &str = "pQ";
const SEED: u64 = 0x5EED_0C07;

type Call<'a> = dyn FnMut(*mut TriangulateIO, *mut TriangulateIO) + 'a;

/// One timed call on the polygon; returns (wall, cpu) and the sorted canonical triangles.
fn timed(
    call: &mut Call<'_>,
    free: &dyn Fn(*mut c_void),
    points: &mut [[f64; 2]],
    segments: &mut [[i32; 2]],
) -> ((Duration, Duration), Vec<[i32; 3]>) {
    let mut input = TriangulateIO {
        pointlist: points.as_flattened_mut().as_mut_ptr(),
        numberofpoints: points.len() as i32,
        segmentlist: segments.as_flattened_mut().as_mut_ptr(),
        numberofsegments: segments.len() as i32,
        ..TriangulateIO::default()
    };
    let mut out = TriangulateIO::default();
    let (wall, cpu) = (Instant::now(), cpu_time());
    call(&mut input, &mut out);
    let times = (wall.elapsed(), cpu_time() - cpu);
    // SAFETY: `trianglelist` holds 3 · numberoftriangles ints after a successful call.
    let flat =
        unsafe { std::slice::from_raw_parts(out.trianglelist, 3 * out.numberoftriangles as usize) };
    let mut triangles: Vec<[i32; 3]> = flat
        .chunks_exact(3)
        .map(|t| canonical_triangle([t[0], t[1], t[2]]))
        .collect();
    triangles.sort_unstable();
    for p in [
        out.pointlist as *mut c_void,
        out.pointattributelist as *mut c_void,
        out.pointmarkerlist as *mut c_void,
        out.trianglelist as *mut c_void,
        out.triangleattributelist as *mut c_void,
        out.neighborlist as *mut c_void,
        out.segmentlist as *mut c_void,
        out.segmentmarkerlist as *mut c_void,
        out.edgelist as *mut c_void,
        out.edgemarkerlist as *mut c_void,
    ] {
        free(p);
    }
    (times, triangles)
}

fn main() {
    // `cargo bench` passes `--bench`; `cargo test --all-targets` runs this binary without it:
    // then only a small smoke run (same code path, same checks).
    let benchmarking = std::env::args().any(|a| a == "--bench");
    let sizes = if benchmarking {
        sizes_from_env("N", &[100_000, 1_000_000])
    } else {
        vec![1000, 4000]
    };
    let reps = if benchmarking {
        number_from_env("REPS", 3).max(1)
    } else {
        1
    };
    let triangle_max = number_from_env("TRIANGLE_MAX", 300_000);
    let switches = CString::new(SWITCHES).unwrap();
    let reference = common::reference();

    let mut ours_call = |input: *mut TriangulateIO, out: *mut TriangulateIO| {
        // SAFETY: valid switches and structs; NULL vorout without `v`.
        let rc = unsafe {
            triangle_rs::ffi::triangulate(switches.as_ptr(), input, out, std::ptr::null_mut())
        };
        assert_eq!(rc, 0, "our triangulate failed");
    };
    // SAFETY: arrays from our triangulate are freed with our trifree.
    let ours_free = |p: *mut c_void| unsafe { triangle_rs::ffi::trifree(p) };
    let mut theirs_call = |input: *mut TriangulateIO, out: *mut TriangulateIO| {
        let reference = reference.expect("checked before calling");
        let mut vorout = TriangulateIO::default();
        // SAFETY: valid switches and structs; a simple polygon, which Triangle accepts.
        unsafe { reference.triangulate_raw(switches.as_ptr() as *mut _, input, out, &mut vorout) };
    };
    // SAFETY: arrays from Triangle are freed with its trifree.
    let theirs_free =
        |p: *mut c_void| unsafe { reference.expect("checked before calling").trifree(p) };

    println!("CDT of a random star-shaped polygon, switches \"{SWITCHES}\", {reps} interleaved repetition(s)");
    let mut ours_by_size = Vec::new();
    for &n in &sizes {
        let (mut points, segments) = star_polygon(n, SEED);
        // Triangle's default numbering starts at 1.
        let mut segments: Vec<[i32; 2]> = segments.into_iter().map(|s| s.map(|v| v + 1)).collect();
        let with_triangle = reference.is_some() && n <= triangle_max;
        let (mut ours_times, mut theirs_times) = (Vec::new(), Vec::new());
        let (mut ours_triangles, mut theirs_triangles) = (Vec::new(), Vec::new());
        for _ in 0..reps {
            let (time, triangles) = timed(&mut ours_call, &ours_free, &mut points, &mut segments);
            ours_times.push(time);
            ours_triangles = triangles;
            if with_triangle {
                let (time, triangles) =
                    timed(&mut theirs_call, &theirs_free, &mut points, &mut segments);
                theirs_times.push(time);
                theirs_triangles = triangles;
            }
        }
        assert_eq!(
            ours_triangles.len(),
            n - 2,
            "{n} vertices: a simple polygon has n - 2 triangles"
        );
        let ours_wall = median(ours_times.iter().map(|t| t.0).collect());
        let ours_cpu = median(ours_times.iter().map(|t| t.1).collect());
        ours_by_size.push((n, ours_wall, ours_cpu));
        println!("n = {n}:");
        println!(
            "  triangle-rs:  wall {} (median), cpu {}",
            seconds(ours_wall),
            seconds(ours_cpu)
        );
        if !with_triangle {
            let why = if reference.is_none() {
                "not installed"
            } else {
                "not run above TRIANGLE_MAX"
            };
            println!("  Triangle 1.6: {why}");
            continue;
        }
        let theirs_wall = median(theirs_times.iter().map(|t| t.0).collect());
        let theirs_cpu = median(theirs_times.iter().map(|t| t.1).collect());
        println!(
            "  Triangle 1.6: wall {} (median), cpu {}",
            seconds(theirs_wall),
            seconds(theirs_cpu)
        );
        println!(
            "  speed-up:     {:.2}× wall, {:.2}× cpu (Triangle's time / ours)",
            theirs_wall.as_secs_f64() / ours_wall.as_secs_f64(),
            theirs_cpu.as_secs_f64() / ours_cpu.as_secs_f64()
        );
        assert_eq!(
            theirs_triangles.len(),
            ours_triangles.len(),
            "{n} vertices: triangle counts differ"
        );
        assert!(
            ours_triangles == theirs_triangles,
            "{n} vertices: the triangle sets differ"
        );
        println!(
            "  triangle sets identical ({} triangles)",
            ours_triangles.len()
        );
    }
    if let (Some(&(n1, wall1, cpu1)), Some(&(n2, wall2, cpu2))) =
        (ours_by_size.first(), ours_by_size.last())
    {
        if n2 > n1 {
            let n_log_n = |n: usize| n as f64 * (n as f64).ln();
            println!(
                "growth of ours from {n1} to {n2} vertices: {:.2}× wall, {:.2}× cpu; n log n grows {:.2}×",
                wall2.as_secs_f64() / wall1.as_secs_f64(),
                cpu2.as_secs_f64() / cpu1.as_secs_f64(),
                n_log_n(n2) / n_log_n(n1)
            );
        }
    }
}
