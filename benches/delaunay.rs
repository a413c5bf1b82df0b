//! Delaunay triangulation of N uniform random points (seeded; N = 10^6 unless env `N` says
//! otherwise): our `triangulate` through the C ABI against Debian's Triangle 1.6 in the same
//! process, interleaved (ours, Triangle, ours, Triangle, …), `REPS` repetitions each (at least 3,
//! default 5). (Under `cargo test --all-targets` it runs as a smoke test with 2000 points.) Prints the medians of wall-clock and process CPU time and the ratios, and checks
//! that the two triangle sets are identical. Run with `cargo bench --bench delaunay`.

#[path = "../tests/common/mod.rs"]
mod common;

use std::ffi::CString;
use std::os::raw::c_void;
use std::time::{Duration, Instant};

use common::points;
use triangle_rs::io::triangulateio::TriangulateIO;

const SWITCHES: &str = "Qz";

fn cpu_time() -> Duration {
    let mut now = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: a valid clock id and a valid out-pointer.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut now) };
    Duration::new(now.tv_sec as u64, now.tv_nsec as u32)
}

fn median(mut samples: Vec<Duration>) -> Duration {
    samples.sort();
    samples[samples.len() / 2]
}

/// One timed call; returns (wall, cpu) and the canonical (sorted, rotated) triangle list.
fn timed(
    call: &mut dyn FnMut(*mut TriangulateIO, *mut TriangulateIO),
    free: &dyn Fn(*mut c_void),
    points: &mut [[f64; 2]],
    keep_triangles: bool,
) -> ((Duration, Duration), Option<Vec<[i32; 3]>>) {
    let mut input = TriangulateIO {
        pointlist: points.as_flattened_mut().as_mut_ptr(),
        numberofpoints: points.len() as i32,
        ..TriangulateIO::default()
    };
    let mut out = TriangulateIO::default();
    let (wall, cpu) = (Instant::now(), cpu_time());
    call(&mut input, &mut out);
    let times = (wall.elapsed(), cpu_time() - cpu);
    let triangles = keep_triangles.then(|| {
        // SAFETY: `trianglelist` holds 3 · numberoftriangles ints after a successful call.
        let flat = unsafe {
            std::slice::from_raw_parts(out.trianglelist, 3 * out.numberoftriangles as usize)
        };
        let mut triangles: Vec<[i32; 3]> = flat
            .chunks_exact(3)
            .map(|t| common::checks::canonical_triangle([t[0], t[1], t[2]]))
            .collect();
        triangles.sort_unstable();
        triangles
    });
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

fn seconds(d: Duration) -> String {
    format!("{:.3} s", d.as_secs_f64())
}

fn main() {
    // `cargo bench` passes `--bench`; `cargo test --all-targets` runs this binary without it: then
    // only a small smoke run (same code path, same checks).
    let benchmarking = std::env::args().any(|a| a == "--bench");
    let default_n = if benchmarking { 1_000_000 } else { 2_000 };
    let n: usize = std::env::var("N")
        .ok()
        .and_then(|v| v.replace('_', "").parse().ok())
        .unwrap_or(default_n);
    let reps: usize = std::env::var("REPS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(5)
        .max(3);
    let mut points = points::uniform(n, 0x5EED_0001);
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
        let reference = reference.expect("checked below");
        let mut vorout = TriangulateIO::default();
        // SAFETY: valid switches and structs, uniform random points Triangle accepts.
        unsafe { reference.triangulate_raw(switches.as_ptr() as *mut _, input, out, &mut vorout) };
    };
    // SAFETY: arrays from Triangle are freed with its trifree.
    let theirs_free = |p: *mut c_void| unsafe { reference.expect("checked below").trifree(p) };

    println!("Delaunay triangulation of {n} uniform random points, switches \"{SWITCHES}\", {reps} interleaved repetitions");
    let (mut ours_times, mut theirs_times) = (Vec::new(), Vec::new());
    let (mut ours_triangles, mut theirs_triangles) = (None, None);
    for rep in 0..reps {
        let last = rep + 1 == reps;
        let (time, triangles) = timed(&mut ours_call, &ours_free, &mut points, last);
        ours_times.push(time);
        ours_triangles = ours_triangles.or(triangles);
        if reference.is_some() {
            let (time, triangles) = timed(&mut theirs_call, &theirs_free, &mut points, last);
            theirs_times.push(time);
            theirs_triangles = theirs_triangles.or(triangles);
        }
    }
    let ours_wall = median(ours_times.iter().map(|t| t.0).collect());
    let ours_cpu = median(ours_times.iter().map(|t| t.1).collect());
    println!(
        "triangle-rs:  wall {} (median), cpu {}",
        seconds(ours_wall),
        seconds(ours_cpu)
    );
    if reference.is_none() {
        println!("Triangle:     not installed, no comparison");
        return;
    }
    let theirs_wall = median(theirs_times.iter().map(|t| t.0).collect());
    let theirs_cpu = median(theirs_times.iter().map(|t| t.1).collect());
    println!(
        "Triangle 1.6: wall {} (median), cpu {}",
        seconds(theirs_wall),
        seconds(theirs_cpu)
    );
    println!(
        "speed-up:     {:.2}× wall, {:.2}× cpu (Triangle's time / ours)",
        theirs_wall.as_secs_f64() / ours_wall.as_secs_f64(),
        theirs_cpu.as_secs_f64() / ours_cpu.as_secs_f64()
    );
    let (ours_triangles, theirs_triangles) = (ours_triangles.unwrap(), theirs_triangles.unwrap());
    assert!(
        ours_triangles == theirs_triangles,
        "the triangle sets differ: {} triangles (ours) vs {} (Triangle's)",
        ours_triangles.len(),
        theirs_triangles.len()
    );
    println!(
        "triangle sets identical ({} triangles)",
        ours_triangles.len()
    );
}
