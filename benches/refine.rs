//! Quality meshing (issue "Quality meshing", item 8's benchmark): our `triangulate` through the
//! C ABI against Debian's Triangle 1.6 in the same process, interleaved (ours, Triangle, ours,
//! …), `REPS` repetitions each (default 3), on two inputs:
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
//! Then the differential table of issue 24 (`table.rs`): every example file of the PyPI
//! `triangle` package's data directory (`common::examples`; `TRIANGLE_DATA_DIR`, else the
//! `.venv`'s) with the switch sets of its kind (`q q30 q33 q34` on point sets; `pq pq30 pq33 pq34
//! pqY pqYY pqD pq30a<x>` on `.poly` files; `rpq30 rpq34 rq34` on meshes with a `.poly`, `rq30
//! rq34` on the others): our and Triangle's triangle count, ratio, smallest angle, largest area,
//! time and time ratio (both C ABIs in this process, interleaved, the median of `TABLE_REPS`
//! calls, default 3, or the best of many where Triangle's call takes < 1 ms: `race.rs`),
//! Triangle first run as a program under a 10 s limit (DNF), then a summary (count ≤ 1.0×
//! Triangle's, geometric mean of the ratios, smallest angle ≥ Triangle's, `Y`/`YY` keeping every
//! input angle that Triangle keeps, the worst cases; the geometric mean of the time ratios, how
//! often ours is at most Triangle's where Triangle takes ≥ 1 ms, the 10 worst time ratios).
//!
//! Then the size sweep of issue 36 (`sweep.rs`): four domains of area 1 (convex, with holes,
//! with reflex corners, with 5°–10° input angles) with `pq`, `pq30`, `pqa<A>` and `pq30a<A>`,
//! and point sets with `q30` and `q30a<A>`, at about 10^2…10^6 triangles (`SWEEP_SIZES=2,3,4`
//! for some), each row with both counts, times, smallest angles and mean radius ratios, then per
//! size the geometric mean and worst time ratio, the count ratio and the radius ratios.
//!
//! Run with `cargo bench --bench refine` (`REPS=…` for more or fewer repetitions of the speed
//! benchmarks; a full run takes about 15 minutes). `REFINE_EXTRA=R` appends our switch `R` (the
//! improvement of the finished mesh; Triangle ignores the letter) to every call of the table and
//! the sweep: the other end of issue 36's frontier. `REFINE_TABLE=only` runs the table alone,
//! `REFINE_TABLE=smoke` the table on `face.poly` with `pq30` and `pqY` alone, `REFINE_TABLE=skip`
//! skips the table; `REFINE_SWEEP=only` runs the sweep alone, `REFINE_SWEEP=skip` skips it. Under
//! `cargo test --all-targets` it runs as a smoke test (a coarser area bound, a 200-vertex star,
//! one repetition, the smoke table, the sweep's disk at 10^2).

#[path = "../tests/common/mod.rs"]
mod common;

#[path = "refine/race.rs"]
mod race;
#[path = "refine/sweep.rs"]
mod sweep;
#[path = "refine/table.rs"]
mod table;

use common::pslg::{square_with_hole, star_polygon_pslg, Pslg};
use common::pslg_checks::MeshView;
use common::quality::smallest_angle;
use common::timing::{benchmarking, number_from_env, time_interleaved, Interleaved};
use common::Triangulation;

const STAR_SEED: u64 = 0x5EED_0C07;

/// What [`measure`] finds in a mesh.
pub struct Measured {
    pub triangles: usize,
    /// Degrees.
    pub smallest_angle: f64,
    /// The mean over the triangles of 2·r_in/r_circ (1 for an equilateral triangle).
    pub radius_ratio: f64,
}

/// The mean radius ratio 2·r_in/r_circ of `mesh`'s triangles: with area K, perimeter p and sides
/// a, b, c, r_in = 2K/p and r_circ = abc/4K, so 2·r_in/r_circ = 16K²/(p·abc).
fn mean_radius_ratio(mesh: &MeshView<'_>) -> f64 {
    let sum: f64 = mesh
        .triangles
        .iter()
        .map(|c| {
            let [a, b, d] = c.map(|v| mesh.points[v]);
            let side = |p: [f64; 2], q: [f64; 2]| (q[0] - p[0]).hypot(q[1] - p[1]);
            let (x, y, z) = (side(a, b), side(b, d), side(d, a));
            let k = 0.5 * ((b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]));
            16.0 * k * k / ((x + y + z) * x * y * z)
        })
        .sum();
    sum / mesh.triangles.len().max(1) as f64
}

/// Triangles, smallest angle and mean radius ratio of a valid mesh of `pslg`'s domain (panics
/// otherwise).
pub fn measure(pslg: &Pslg, switches: &str, who: &str, out: &Triangulation) -> Measured {
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
    Measured {
        triangles: mesh.triangles.len(),
        smallest_angle: smallest_angle(&mesh),
        radius_ratio: mean_radius_ratio(&mesh),
    }
}

/// The switches the table and the sweep append to each of their sets (`REFINE_EXTRA`: `R`, or
/// nothing).
pub fn extra_switches() -> String {
    std::env::var("REFINE_EXTRA").unwrap_or_default()
}

fn bench(pslg: &Pslg, switches: &str, reps: usize) {
    println!("{}, switches \"{switches}\":", pslg.name);
    let reference = common::reference();
    let Interleaved {
        ours_mesh, theirs, ..
    } = time_interleaved(switches, &pslg.input_for(switches), reps, reference, "  ");
    let Measured {
        triangles: ours_count,
        smallest_angle: ours_angle,
        ..
    } = measure(pslg, switches, "our", &ours_mesh);
    let Some((_, theirs_mesh)) = theirs else {
        println!("  Triangle 1.6: not installed, no comparison");
        println!("  triangles:    {ours_count}; min angle {ours_angle:.4}°");
        return;
    };
    let Measured {
        triangles: theirs_count,
        smallest_angle: theirs_angle,
        ..
    } = measure(pslg, switches, "Triangle's", &theirs_mesh);
    println!(
        "  triangles:    {ours_count} (ours), {theirs_count} (Triangle's): {:.3}× Triangle's",
        ours_count as f64 / theirs_count as f64
    );
    println!("  min angle:    {ours_angle:.4}° (ours), {theirs_angle:.4}° (Triangle's)");
}

fn main() {
    let full = benchmarking();
    let mode = std::env::var("REFINE_TABLE").unwrap_or_default();
    let sweep_mode = std::env::var("REFINE_SWEEP").unwrap_or_default();
    let scope = if full && mode != "smoke" {
        table::Scope::Full
    } else {
        table::Scope::Smoke
    };
    let sweep_scope = if full {
        sweep::Scope::Full
    } else {
        sweep::Scope::Smoke
    };
    if sweep_mode == "only" {
        sweep::run(sweep_scope);
        return;
    }
    if mode == "only" || mode == "smoke" {
        table::run(scope);
        return;
    }
    let reps = if full {
        number_from_env("REPS", 3).max(1)
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
    if mode != "skip" {
        table::run(scope);
    }
    if sweep_mode != "skip" {
        sweep::run(sweep_scope);
    }
}
