//! Quality meshing (issue "Quality meshing", item 8's benchmark): our `triangulate` through the
//! C ABI against Debian's Triangle 1.6 in the same process, interleaved (ours, Triangle, ours,
//! …), `REPS` repetitions each (default 5), on two inputs:
//! (a) the unit square with a circular hole (centre (0.5, 0.5), radius 0.2, 256 segments, a hole
//!     point at the centre) and four short free-standing segments (`common::pslg::square_with_hole`),
//!     switches `pq30a0.0000014Q` (about 10^6 triangles);
//! (b) random star-shaped polygons of 3000 and 5000 vertices (`common::pslg::star_polygon`,
//!     radius uniform in [0.1, 1]), switches `pq20Q`.
//! Prints the medians of wall-clock and process CPU time with the time ratio, and — refinement
//! has no unique answer — the triangle counts with their ratio and both smallest angles. Both
//! meshes are checked to be valid meshes of the domain (its area, every boundary edge a
//! segment).
//!
//! Then a table (issue 11) of Triangle's own example files (every `.poly`, `.node` and `.ele` of
//! the PyPI `triangle` package's data directory, `common::examples`) with `q`, `q30`, `q33` and
//! `q34` (`p…` for `.poly` files, `rp…` for meshes): for each, our and Triangle's triangle
//! count, smallest angle and median time. Triangle may loop (above 28.6°, or on Greenland's
//! vertices): each case is first tried with Debian's `triangle` program under a time limit, and
//! Triangle's column says so when it does not finish.
//!
//! Run with `cargo bench --bench refine` (`REPS=…` for more or fewer repetitions). Under
//! `cargo test --all-targets` it runs as a smoke test (a coarser area bound, a 200-vertex star,
//! one repetition, the table for `face.poly` alone).

#[path = "../tests/common/mod.rs"]
mod common;

use std::path::Path;
use std::process::Command;
use std::time::Duration;

use common::examples::{data_dir, example_files, ExampleFile, Kind};
use common::pslg::{square_with_hole, star_polygon_pslg, Pslg};
use common::pslg_checks::MeshView;
use common::quality::smallest_angle;
use common::timing::{
    benchmarking, number_from_env, seconds, time_interleaved, timed_call, Interleaved, Library,
    Times,
};
use common::Triangulation;

const STAR_SEED: u64 = 0x5EED_0C07;

/// How long Debian's `triangle` program may take on an example before it counts as looping.
const TRIANGLE_TIME_LIMIT: Duration = Duration::from_secs(10);

/// Triangles and smallest angle of a valid mesh of `pslg`'s domain (panics otherwise).
fn measure(pslg: &Pslg, switches: &str, who: &str, out: &Triangulation) -> (usize, f64) {
    let context = format!("{}, \"{switches}\", {who} mesh", pslg.name);
    let mesh = MeshView::of(out).unwrap_or_else(|e| panic!("{context}: {e}"));
    assert!(!mesh.triangles.is_empty(), "{context}: no triangle");
    if let Some(expected) = pslg.expected_area(switches) {
        let found = mesh.area();
        assert!(
            (found - expected).abs() <= 1e-9 * expected,
            "{context}: the triangles' area is {found}, the domain's {expected}"
        );
    }
    (mesh.triangles.len(), smallest_angle(&mesh))
}

fn bench(pslg: &Pslg, switches: &str, reps: usize) {
    println!("{}, switches \"{switches}\":", pslg.name);
    let reference = common::reference();
    let Interleaved {
        ours_mesh, theirs, ..
    } = time_interleaved(switches, &pslg.input_for(switches), reps, reference, "  ");
    let (ours_count, ours_angle) = measure(pslg, switches, "our", &ours_mesh);
    let Some((_, theirs_mesh)) = theirs else {
        println!("  Triangle 1.6: not installed, no comparison");
        println!("  triangles:    {ours_count}; min angle {ours_angle:.4}°");
        return;
    };
    let (theirs_count, theirs_angle) = measure(pslg, switches, "Triangle's", &theirs_mesh);
    println!(
        "  triangles:    {ours_count} (ours), {theirs_count} (Triangle's): {:.3}× Triangle's",
        ours_count as f64 / theirs_count as f64
    );
    println!("  min angle:    {ours_angle:.4}° (ours), {theirs_angle:.4}° (Triangle's)");
}

fn main() {
    let full = benchmarking();
    let reps = if full {
        number_from_env("REPS", 5).max(1)
    } else {
        1
    };
    println!(
        "Quality meshing against Triangle 1.6, {reps} interleaved repetition(s){}",
        if full {
            ""
        } else {
            " (smoke run: small inputs)"
        }
    );
    let square = square_with_hole(256);
    bench(
        &square,
        if full {
            "pq30a0.0000014Q"
        } else {
            "pq30a0.001Q"
        },
        reps,
    );
    // The two sizes of issue 14's table (3000 and 5000 vertices).
    let stars: &[usize] = if full { &[3000, 5000] } else { &[200] };
    for &n in stars {
        bench(&star_polygon_pslg(n, STAR_SEED), "pq20Q", reps);
    }
    example_table(full, reps);
}

/// Whether Debian's `triangle` program finishes `file` (with its companions, in `dir`) with
/// `switches` within [`TRIANGLE_TIME_LIMIT`]: the library call cannot be interrupted. Runs in a
/// scratch copy of the data directory (the program writes its output next to its input).
fn triangle_finishes(scratch: &Path, file: &str, switches: &str) -> bool {
    let status = Command::new("timeout")
        .arg(TRIANGLE_TIME_LIMIT.as_secs().to_string())
        .arg("triangle")
        .arg(format!("-{switches}NEPQ"))
        .arg(file)
        .current_dir(scratch)
        .status();
    status.is_ok_and(|s| s.success())
}

/// Median times of `reps` calls of `library`, and its last mesh's triangle count and smallest
/// angle.
fn measure_example(library: Library, switches: &str, file: &ExampleFile, reps: usize) -> String {
    let mut samples = Vec::new();
    let mut last = None;
    for _ in 0..reps {
        let (times, mesh) = timed_call(library, switches, &file.input);
        samples.push(times);
        last = Some(mesh);
    }
    let mesh = last.expect("one repetition");
    let view = MeshView::of(&mesh).unwrap_or_else(|e| panic!("{}, \"{switches}\": {e}", file.name));
    format!(
        "{:>7} | {:>8.4}° | {:>9}",
        view.triangles.len(),
        smallest_angle(&view),
        seconds(Times::median(&samples).wall)
    )
}

/// The table of Triangle's example files with `q`, `q30`, `q33`, `q34`.
fn example_table(full: bool, reps: usize) {
    let dir = data_dir();
    let reference = common::reference();
    let scratch = std::env::temp_dir().join(format!("triangle-rs-bench-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).expect("a scratch directory");
    for entry in std::fs::read_dir(&dir)
        .expect("the data directory")
        .flatten()
    {
        let _ = std::fs::copy(entry.path(), scratch.join(entry.file_name()));
    }
    println!("Triangle's example files ({}):", dir.display());
    println!(
        "| file | switches | ours: triangles | min angle | time | Triangle: triangles | min angle | time |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|");
    for file in example_files(&dir) {
        if !full && file.name != "face.poly" {
            continue;
        }
        let prefix = match file.kind {
            Kind::Poly => "p",
            Kind::Points => "",
            Kind::Mesh { .. } if file.input.segments.is_empty() => "r",
            Kind::Mesh { .. } => "rp",
        };
        for angle in ["q", "q30", "q33", "q34"] {
            let switches = format!("{prefix}{angle}");
            let ours = measure_example(Library::Ours, &format!("{switches}zQ"), &file, reps);
            let theirs = match reference {
                Some(triangle) if triangle_finishes(&scratch, &file.name, &switches) => {
                    measure_example(
                        Library::Triangle(triangle),
                        &format!("{switches}zQ"),
                        &file,
                        reps,
                    )
                }
                Some(_) => format!(
                    "does not finish in {} s | | ",
                    TRIANGLE_TIME_LIMIT.as_secs()
                ),
                None => "not installed | | ".into(),
            };
            println!("| {} | {switches} | {ours} | {theirs} |", file.name);
        }
    }
    let _ = std::fs::remove_dir_all(&scratch);
}
