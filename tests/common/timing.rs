//! Timing helpers of the benchmarks: process CPU time, medians, command-line sizes, peak memory,
//! and timed, interleaved calls of our C ABI and Debian's Triangle on the same input.

use std::cell::Cell;
use std::os::raw::{c_char, c_void};
use std::time::{Duration, Instant};

use super::call::{ours_status, run_call, MeshInput, RawCall, Triangulation};
use super::checks::canonical_triangle;
use super::reference::Reference;
use triangle_rs::io::triangulateio::TriangulateIO;

/// CPU time of the whole process (all threads).
pub fn cpu_time() -> Duration {
    let mut now = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: a valid clock id and a valid out-pointer.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut now) };
    Duration::new(now.tv_sec as u64, now.tv_nsec as u32)
}

/// The median (the upper one for an even count); `samples` must not be empty.
pub fn median(mut samples: Vec<Duration>) -> Duration {
    samples.sort();
    samples[samples.len() / 2]
}

pub fn seconds(d: Duration) -> String {
    format!("{:.3} s", d.as_secs_f64())
}

/// A comma-separated list of sizes from the environment variable `name` (underscores allowed:
/// `N=100_000,1_000_000`), or `default`.
pub fn sizes_from_env(name: &str, default: &[usize]) -> Vec<usize> {
    match std::env::var(name) {
        Ok(list) => list
            .split(',')
            .map(|s| {
                s.trim()
                    .replace('_', "")
                    .parse()
                    .unwrap_or_else(|_| panic!("{name}: not a size list: {list}"))
            })
            .collect(),
        Err(_) => default.to_vec(),
    }
}

/// A number from the environment variable `name`, or `default`.
pub fn number_from_env(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|v| v.replace('_', "").parse().ok())
        .unwrap_or(default)
}

/// True under `cargo bench`, which passes `--bench`. `cargo test --all-targets` runs the
/// benchmark binaries without it: they then make only a small smoke run (same code path, same
/// checks).
pub fn benchmarking() -> bool {
    std::env::args().any(|a| a == "--bench")
}

/// Wall-clock and process CPU time of one run.
#[derive(Clone, Copy, Debug)]
pub struct Times {
    pub wall: Duration,
    pub cpu: Duration,
}

impl Times {
    /// Runs `run` and measures it.
    pub fn measure<T>(run: impl FnOnce() -> T) -> (Times, T) {
        let (wall, cpu) = (Instant::now(), cpu_time());
        let result = run();
        let times = Times {
            wall: wall.elapsed(),
            cpu: cpu_time() - cpu,
        };
        (times, result)
    }

    /// The median wall-clock time and the median CPU time (each taken on its own); `samples`
    /// must not be empty.
    pub fn median(samples: &[Times]) -> Times {
        Times {
            wall: median(samples.iter().map(|t| t.wall).collect()),
            cpu: median(samples.iter().map(|t| t.cpu).collect()),
        }
    }

    /// `wall … (median), cpu …`.
    fn describe(&self) -> String {
        format!(
            "wall {} (median), cpu {}",
            seconds(self.wall),
            seconds(self.cpu)
        )
    }
}

/// A field of /proc/self/status in bytes (0 where unreadable).
pub fn status_bytes(field: &str) -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|line| line.strip_prefix(field))
        .and_then(|rest| {
            rest.trim()
                .trim_end_matches("kB")
                .trim()
                .parse::<u64>()
                .ok()
        })
        .map_or(0, |kb| kb * 1024)
}

/// Makes every large block come from mmap (no dynamic threshold), so that a freed one leaves
/// the process and each run's peak memory growth ([`measured`]) is its own. Call it before the
/// runs allocate.
pub fn large_blocks_from_mmap() {
    // SAFETY: a valid mallopt parameter and value.
    unsafe { libc::mallopt(libc::M_MMAP_THRESHOLD, 128 * 1024) };
}

/// Runs `work` and measures its time and its peak memory growth in bytes: the kernel's
/// high-water mark is reset (`clear_refs` 5) to the current resident size first, then read
/// while `work`'s result (the outputs) is still alive.
pub fn measured<T>(work: impl FnOnce() -> T) -> (Times, u64, T) {
    // SAFETY: no arguments to check; returns free heap memory to the system, so that memory
    // freed by earlier runs and still resident does not hide this run's growth.
    unsafe { libc::malloc_trim(0) };
    let _ = std::fs::write("/proc/self/clear_refs", "5");
    let before = status_bytes("VmRSS:");
    let (times, result) = Times::measure(work);
    let peak = status_bytes("VmHWM:").saturating_sub(before);
    (times, peak, result)
}

/// One implementation of Triangle's C ABI.
#[derive(Clone, Copy)]
pub enum Library {
    /// Ours: the exported `triangle_rs::ffi::triangulate`.
    Ours,
    /// Debian's Triangle 1.6 (only pass it input it accepts: it exits the process otherwise).
    Triangle(&'static Reference),
}

/// One call of `library`'s `triangulate` on `input`, timed around the C call alone (not the
/// copies of the input and output arrays); panics if the call fails.
pub fn timed_call(library: Library, switches: &str, input: &MeshInput) -> (Times, Triangulation) {
    let (times, _, output) = call_with(library, switches, input, |call| {
        let (times, result) = Times::measure(call);
        (times, 0, result)
    });
    (times, output)
}

/// [`timed_call`] with the call's peak memory growth in bytes ([`measured`]).
pub fn measured_call(
    library: Library,
    switches: &str,
    input: &MeshInput,
) -> (Times, u64, Triangulation) {
    call_with(library, switches, input, |call| measured(call))
}

/// One call of `library`'s `triangulate` on `input`, measured by `measure` around the C call
/// alone; panics if the call fails.
fn call_with(
    library: Library,
    switches: &str,
    input: &MeshInput,
    measure: impl Fn(&dyn Fn() -> Result<(), String>) -> (Times, u64, Result<(), String>),
) -> (Times, u64, Triangulation) {
    let (call, free): (Box<RawCall<'_>>, Box<dyn Fn(*mut c_void)>) = match library {
        Library::Ours => (
            // SAFETY: valid switches and structs prepared by `run_call`.
            Box::new(|s, i, o, v| {
                ours_status(unsafe { triangle_rs::ffi::triangulate(s, i, o, v) })
            }),
            // SAFETY: arrays returned by our `triangulate` are freed with our `trifree`.
            Box::new(|p| unsafe { triangle_rs::ffi::trifree(p) }),
        ),
        Library::Triangle(reference) => (
            Box::new(|s, i, o, v| {
                // SAFETY: valid switches and structs prepared by `run_call`; input Triangle
                // accepts (the caller's duty).
                unsafe { reference.triangulate_raw(s, i, o, v) };
                Ok(())
            }),
            // SAFETY: arrays from Triangle are freed with its trifree.
            Box::new(|p| unsafe { reference.trifree(p) }),
        ),
    };
    let measurement = Cell::new(None);
    let measured_call =
        |s: *mut c_char, i: *mut TriangulateIO, o: *mut TriangulateIO, v: *mut TriangulateIO| {
            let (times, peak, result) = measure(&|| call(s, i, o, v));
            measurement.set(Some((times, peak)));
            result
        };
    let output = run_call(&measured_call, &*free, switches, input, false)
        .unwrap_or_else(|message| panic!("triangulate failed: {message}"));
    let (times, peak) = measurement.get().expect("run_call made the call");
    (times, peak, output)
}

/// The triangles of `mesh`, each rotated to start at its smallest corner, sorted: equal for two
/// outputs exactly when they have the same triangles, whatever their order.
pub fn sorted_triangles(mesh: &Triangulation) -> Vec<[i32; 3]> {
    let mut triangles: Vec<[i32; 3]> = mesh
        .triangle_triples()
        .into_iter()
        .map(canonical_triangle)
        .collect();
    triangles.sort_unstable();
    triangles
}

/// What [`time_interleaved`] measured: our median times and last output, and Triangle's when it
/// ran.
pub struct Interleaved {
    pub ours: Times,
    pub ours_mesh: Triangulation,
    pub theirs: Option<(Times, Triangulation)>,
}

/// Calls ours and, if `triangle` is given, Triangle alternately on `input` (ours, Triangle,
/// ours, …), `reps` times each; prints the median times (each line starting with `indent`) and
/// the speed-up. The outputs are returned unchecked: refinement gives different, equally valid
/// meshes (see [`compare_interleaved`] for outputs that must be identical).
pub fn time_interleaved(
    switches: &str,
    input: &MeshInput,
    reps: usize,
    triangle: Option<&'static Reference>,
    indent: &str,
) -> Interleaved {
    let (mut ours_times, mut theirs_times) = (Vec::new(), Vec::new());
    let (mut ours_mesh, mut theirs_mesh) = (None, None);
    for _ in 0..reps.max(1) {
        let (times, mesh) = timed_call(Library::Ours, switches, input);
        ours_times.push(times);
        ours_mesh = Some(mesh);
        if let Some(reference) = triangle {
            let (times, mesh) = timed_call(Library::Triangle(reference), switches, input);
            theirs_times.push(times);
            theirs_mesh = Some(mesh);
        }
    }
    let ours = Times::median(&ours_times);
    println!("{indent}triangle-rs:  {}", ours.describe());
    let theirs = theirs_mesh.map(|mesh| {
        let theirs = Times::median(&theirs_times);
        println!("{indent}Triangle 1.6: {}", theirs.describe());
        println!(
            "{indent}speed-up:     {:.2}× wall, {:.2}× cpu (Triangle's time / ours)",
            theirs.wall.as_secs_f64() / ours.wall.as_secs_f64(),
            theirs.cpu.as_secs_f64() / ours.cpu.as_secs_f64()
        );
        (theirs, mesh)
    });
    Interleaved {
        ours,
        ours_mesh: ours_mesh.expect("at least one repetition"),
        theirs,
    }
}

/// [`time_interleaved`], then checks that both give the same triangles (for the unique answers:
/// Delaunay and constrained Delaunay triangulations). Returns our median times and our last
/// output.
pub fn compare_interleaved(
    switches: &str,
    input: &MeshInput,
    reps: usize,
    triangle: Option<&'static Reference>,
    indent: &str,
) -> (Times, Triangulation) {
    let Interleaved {
        ours,
        ours_mesh,
        theirs,
    } = time_interleaved(switches, input, reps, triangle, indent);
    let Some((_, theirs_mesh)) = theirs else {
        return (ours, ours_mesh);
    };
    let (ours_triangles, theirs_triangles) =
        (sorted_triangles(&ours_mesh), sorted_triangles(&theirs_mesh));
    assert!(
        ours_triangles == theirs_triangles,
        "the triangle sets differ: {} triangles (ours) vs {} (Triangle's)",
        ours_triangles.len(),
        theirs_triangles.len()
    );
    println!(
        "{indent}triangle sets identical ({} triangles)",
        ours_triangles.len()
    );
    (ours, ours_mesh)
}

/// One contestant's row of a race table: its name, and per run its times and peak bytes; its
/// triangle count (`None`: it failed).
pub struct RaceRow {
    pub name: &'static str,
    pub times: Vec<Times>,
    pub peak_bytes: Vec<u64>,
    pub triangles: Option<usize>,
}

impl RaceRow {
    /// The row of `(times, peak bytes, triangle count or None)` per run; the last run's count.
    pub fn of(name: &'static str, runs: impl Iterator<Item = (Times, u64, Option<usize>)>) -> Self {
        let mut row = RaceRow {
            name,
            times: Vec::new(),
            peak_bytes: Vec::new(),
            triangles: None,
        };
        for (times, peak_bytes, triangles) in runs {
            row.times.push(times);
            row.peak_bytes.push(peak_bytes);
            row.triangles = triangles;
        }
        row
    }
}

/// Prints `title` and a race table of `rows` on `n` vertices: median wall and CPU seconds, the
/// ratio of row `reference`'s (Triangle's) times over each one's, median peak bytes per vertex,
/// triangles. Returns each row's median times.
pub fn print_race(title: &str, n: usize, rows: &[RaceRow], reference: Option<usize>) -> Vec<Times> {
    let medians: Vec<(Times, u64)> = rows
        .iter()
        .map(|row| {
            let peaks = row.peak_bytes.iter().map(|&b| Duration::from_nanos(b));
            (
                Times::median(&row.times),
                median(peaks.collect()).as_nanos() as u64,
            )
        })
        .collect();
    let baseline = reference.map(|k| medians[k].0);
    println!("{title}");
    println!(
        "| {:<22} | {:>7} | {:>7} | {:>22} | {:>13} | {:>9} |",
        "", "wall s", "cpu s", "Triangle's / ours", "peak B/vertex", "triangles"
    );
    println!(
        "|{:-<24}|{:->9}|{:->9}|{:->24}|{:->15}|{:->11}|",
        "", "", "", "", "", ""
    );
    for (row, &(times, peak)) in rows.iter().zip(&medians) {
        let ratio = baseline.map_or("—".to_string(), |t| {
            format!(
                "{:.2}× wall {:.2}× cpu",
                t.wall.as_secs_f64() / times.wall.as_secs_f64(),
                t.cpu.as_secs_f64() / times.cpu.as_secs_f64()
            )
        });
        let triangles = row
            .triangles
            .map_or("failed".to_string(), |count| count.to_string());
        println!(
            "| {:<22} | {:>7.3} | {:>7.3} | {:>22} | {:>13.0} | {:>9} |",
            row.name,
            times.wall.as_secs_f64(),
            times.cpu.as_secs_f64(),
            ratio,
            peak as f64 / n as f64,
            triangles
        );
    }
    medians.into_iter().map(|(times, _)| times).collect()
}
