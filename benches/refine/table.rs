//! The differential table of issue 24 (points 2 and 4): every example file of the PyPI
//! `triangle` package's data directory (`common::examples`) with the switch sets of its kind,
//! meshed by Debian's Triangle 1.6 and by us, with a computed summary.
//!
//! Switch sets: `q q30 q33 q34` on point sets (`.node` files); `pq pq30 pq33 pq34 pqY pqYY pqD
//! pq30a<x>` on `.poly` files, `x` the largest power of two ≤ 1/1000 of the vertices' bounding
//! box area; `rpq30 rpq34 rq34` on the meshes (`.ele`) that have a `.poly`, `rq30 rq34` on the
//! others. Each case is first run by Debian's `triangle` program under a time limit of
//! [`TRIANGLE_TIME_LIMIT`] (DNF when it does not finish) and by our engine, in this process
//! (cancelled at [`OUR_TIME_LIMIT`]: DNF too); our counts and angles are from this run. Then the
//! cases that Triangle finishes are timed (`crate::race`): ours (where it finished) and
//! Triangle's library through their C ABIs, interleaved, the median of `TABLE_REPS` calls each
//! (default 3), or each side's best of about [`BUDGET`] of calls where Triangle's call takes less
//! than a millisecond; Triangle's counts and angles are from its last call.

use std::collections::HashSet;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

use triangle_rs::data::Hooks;

use crate::common;
use common::call::{MeshInput, Triangulation};
use common::examples::{data_dir, example_files, ExampleFile, Kind};
use common::points::Point;
use common::pslg_checks::MeshView;
use common::quality::{area, engine, smallest_angle};
use common::timing::number_from_env;

use crate::race::{self, geometric_mean, race};

/// How long Debian's `triangle` program may take on a case before it counts as not finishing.
pub const TRIANGLE_TIME_LIMIT: Duration = Duration::from_secs(10);
/// How long our refinement may take before it is cancelled (and counts as not finishing).
pub const OUR_TIME_LIMIT: Duration = Duration::from_secs(30);
/// Short cases repeat each side until it has spent about this long (best call).
pub const BUDGET: Duration = Duration::from_millis(20);
/// A side's timed calls in one case stop once they have spent about this long (one at least).
const MOST_TIME: Duration = Duration::from_secs(20);
/// Our smallest angle counts as at least Triangle's within this many degrees (rounding).
const ANGLE_SLACK: f64 = 1e-9;
/// Two segment directions at a vertex are the same within this many radians.
const SAME_DIRECTION: f64 = 1e-7;

/// Which cases the table runs.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Scope {
    /// Every example file with every switch set of its kind.
    Full,
    /// `face.poly` with `pq30` and `pqY` alone.
    Smoke,
}

/// One mesh's measurements.
struct Measure {
    triangles: usize,
    smallest_angle: f64,
    largest_area: f64,
    /// The timed calls' median or best (see the module doc), else the one call's.
    time: Duration,
    /// The same of the process CPU time (the one call's wall-clock time when untimed).
    cpu: Duration,
    /// Input angles kept unsplit (only measured with `Y`): (apex, two segment directions).
    kept: Vec<(Point, [f64; 2])>,
}

/// How one side of a case ended.
enum Outcome {
    Done(Measure),
    /// Did not finish within its time limit.
    Dnf,
    /// Finished with an error, an invalid mesh, or a panic.
    Failed(String),
}

struct Row {
    file: String,
    switches: String,
    /// `a<x>`'s bound, if the switches have one.
    bound: Option<f64>,
    theirs: Outcome,
    ours: Outcome,
    /// How the times were taken (`best of 9/700`), when Triangle's were.
    calls: Option<String>,
}

/// The switch sets (without `z` and `Q`) of `file`'s kind.
fn switch_sets(file: &ExampleFile) -> Vec<String> {
    let extra = super::extra_switches();
    let list = |s: &[&str]| s.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    let sets = match file.kind {
        Kind::Points => list(&["q", "q30", "q33", "q34"]),
        Kind::Poly => {
            let mut sets = list(&["pq", "pq30", "pq33", "pq34", "pqY", "pqYY", "pqD"]);
            sets.push(format!("pq30a{}", area_bound(&file.input.points)));
            sets
        }
        Kind::Mesh { .. } if file.input.segments.is_empty() => list(&["rq30", "rq34"]),
        Kind::Mesh { .. } => list(&["rpq30", "rpq34", "rq34"]),
    };
    sets.into_iter().map(|s| s + &extra).collect()
}

/// The largest power of two ≤ 1/1000 of the bounding box area of `points`, printed exactly in
/// decimals (Triangle reads no exponent notation).
fn area_bound(points: &[Point]) -> String {
    let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
    for p in points {
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    let area = (hi[0] - lo[0]) * (hi[1] - lo[1]) / 1000.0;
    format!("{}", 2f64.powi(area.log2().floor() as i32))
}

/// The bound of an `a<x>` in `switches`, if any.
fn bound_of(switches: &str) -> Option<f64> {
    let (_, rest) = switches.split_once('a')?;
    let number: String = rest
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    number.parse().ok()
}

/// Whether Debian's `triangle` program finishes `file` (in `scratch`, a copy of the data
/// directory) with `switches` within [`TRIANGLE_TIME_LIMIT`]. The library call cannot be
/// interrupted; `NEP` keeps the program from writing its output next to its input.
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

/// The measurements of a finished mesh (`time` and `cpu` its calls'), or why it is no valid mesh.
fn measure(
    out: &Triangulation,
    input: &MeshInput,
    (time, cpu): (Duration, Duration),
    keep_check: bool,
) -> Result<Measure, String> {
    let mesh = MeshView::of(out)?;
    let largest_area = mesh
        .triangles
        .iter()
        .map(|c| {
            let [a, b, d] = c.map(|v| mesh.points[v]);
            area(a, b, d)
        })
        .fold(0.0, f64::max);
    Ok(Measure {
        triangles: mesh.triangles.len(),
        smallest_angle: smallest_angle(&mesh),
        largest_area,
        time,
        cpu,
        kept: if keep_check {
            kept_input_angles(&mesh, input)
        } else {
            Vec::new()
        },
    })
}

/// The input angles that `mesh` keeps unsplit: an input angle is the angle at an input vertex
/// between two input segments consecutive around it; it is kept unsplit when one triangle has
/// it as a corner (its two edges from the vertex are both output segments: no edge of the mesh
/// leaves the vertex inside the angle). Each as the apex and the directions of both segments.
fn kept_input_angles(mesh: &MeshView<'_>, input: &MeshInput) -> Vec<(Point, [f64; 2])> {
    let input_places: HashSet<[u64; 2]> =
        input.points.iter().map(|p| p.map(f64::to_bits)).collect();
    let direction = |from: usize, to: usize| {
        let (p, q) = (mesh.points[from], mesh.points[to]);
        (q[1] - p[1]).atan2(q[0] - p[0])
    };
    let mut kept = Vec::new();
    for c in &mesh.triangles {
        for k in 0..3 {
            let (v, u, w) = (c[k], c[(k + 1) % 3], c[(k + 2) % 3]);
            if input_places.contains(&mesh.points[v].map(f64::to_bits))
                && mesh.is_segment(v, u)
                && mesh.is_segment(v, w)
            {
                kept.push((mesh.points[v], [direction(v, u), direction(v, w)]));
            }
        }
    }
    kept
}

/// The input angles that `theirs` keeps and `ours` does not.
fn lost_angles<'m>(theirs: &'m Measure, ours: &Measure) -> Vec<&'m (Point, [f64; 2])> {
    let close = |a: f64, b: f64| {
        let d = (a - b).abs();
        d.min(std::f64::consts::TAU - d) <= SAME_DIRECTION
    };
    theirs
        .kept
        .iter()
        .filter(|(apex, [u, w])| {
            !ours.kept.iter().any(|(p, [s, t])| {
                p == apex && ((close(*s, *u) && close(*t, *w)) || (close(*s, *w) && close(*t, *u)))
            })
        })
        .collect()
}

/// Triangle's outcome (and the calls' description) after timing both sides on a case `ours` has
/// already run (its time becomes the timed calls').
fn race_triangle(
    file: &ExampleFile,
    switches: &str,
    scratch: &Path,
    keep: bool,
    ours: &mut Outcome,
    (reps, budget): (usize, Duration),
) -> (Outcome, Option<String>) {
    let Some(reference) = common::reference() else {
        return (
            Outcome::Failed("Triangle 1.6 is not installed".into()),
            None,
        );
    };
    if !triangle_finishes(scratch, &file.name, switches) {
        return (Outcome::Dnf, None);
    }
    let result = race(
        &format!("{switches}zQ"),
        &file.input,
        matches!(ours, Outcome::Done(_)),
        Some(reference),
        reps,
        budget,
        MOST_TIME,
    );
    if let (Outcome::Done(m), Some(side)) = (&mut *ours, &result.ours) {
        m.time = side.time;
        m.cpu = side.cpu;
    }
    let theirs = result.theirs.as_ref().expect("Triangle ran");
    let outcome = match measure(&theirs.mesh, &file.input, (theirs.time, theirs.cpu), keep) {
        Ok(m) => Outcome::Done(m),
        Err(e) => Outcome::Failed(e),
    };
    (outcome, Some(result.calls()))
}

fn run_ours(file: &ExampleFile, switches: &str, keep: bool) -> Outcome {
    let start = Instant::now();
    let cancel = move || start.elapsed() >= OUR_TIME_LIMIT;
    let hooks = Hooks {
        cancel: Some(&cancel),
        ..Hooks::default()
    };
    let result = catch_unwind(AssertUnwindSafe(|| {
        engine(&format!("{switches}zQ"), &file.input, &hooks)
    }));
    let time = start.elapsed();
    match result {
        Err(_) => Outcome::Failed("panicked".into()),
        Ok(Err(e)) => Outcome::Failed(e),
        Ok(Ok(_)) if time >= OUR_TIME_LIMIT => Outcome::Dnf,
        Ok(Ok((out, _warnings))) => match measure(&out, &file.input, (time, time), keep) {
            Ok(m) => Outcome::Done(m),
            Err(e) => Outcome::Failed(e),
        },
    }
}

impl Row {
    /// Both meshes, when both finished with triangles.
    fn both(&self) -> Option<(&Measure, &Measure)> {
        match (&self.theirs, &self.ours) {
            (Outcome::Done(t), Outcome::Done(o)) if t.triangles > 0 && o.triangles > 0 => {
                Some((t, o))
            }
            _ => None,
        }
    }

    fn ratio(&self) -> Option<f64> {
        self.both()
            .map(|(t, o)| o.triangles as f64 / t.triangles as f64)
    }

    /// Our time over Triangle's, when both finished with triangles.
    fn time_ratio(&self) -> Option<f64> {
        self.both()
            .map(|(t, o)| o.time.as_secs_f64() / t.time.as_secs_f64())
    }

    fn name(&self) -> String {
        format!("{} {}", self.file, self.switches)
    }

    fn print(&self) {
        let side = |o: &Outcome| match o {
            Outcome::Done(m) if m.triangles == 0 => ("0".into(), "—".into(), race::ms(m.time)),
            Outcome::Done(m) => (
                m.triangles.to_string(),
                format!("{:.4}", m.smallest_angle),
                race::ms(m.time),
            ),
            Outcome::Dnf => ("DNF".into(), "".into(), "".into()),
            Outcome::Failed(e) => (format!("failed: {e}"), "".into(), "".into()),
        };
        let (t_count, t_angle, t_time) = side(&self.theirs);
        let (o_count, o_angle, o_time) = side(&self.ours);
        let ratio = self.ratio().map_or(String::new(), |r| format!("{r:.3}"));
        let largest = match (&self.theirs, &self.ours, self.bound) {
            (Outcome::Done(t), Outcome::Done(o), Some(x)) => {
                format!(
                    "T {:.3}, ours {:.3} of a",
                    t.largest_area / x,
                    o.largest_area / x
                )
            }
            (_, Outcome::Done(o), Some(x)) => format!("ours {:.3} of a", o.largest_area / x),
            (Outcome::Done(t), Outcome::Done(o), None) if t.triangles > 0 && o.triangles > 0 => {
                format!("{:.3}", o.largest_area / t.largest_area)
            }
            _ => String::new(),
        };
        let time_ratio = self
            .time_ratio()
            .map_or(String::new(), |r| format!("{r:.2}"));
        println!(
            "| {} | {} | {t_count} | {o_count} | {ratio} | {t_angle} | {o_angle} | {largest} | {t_time} | {o_time} | {time_ratio} | {} |",
            self.file,
            self.switches,
            self.calls.as_deref().unwrap_or("one call")
        );
    }
}

/// Prints the table and its summary.
pub fn run(scope: Scope) {
    let dir = data_dir();
    let (reps, budget) = if scope == Scope::Smoke {
        (1, Duration::ZERO)
    } else {
        (number_from_env("TABLE_REPS", 3).max(1), BUDGET)
    };
    let scratch =
        std::env::temp_dir().join(format!("triangle-rs-bench-table-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).expect("a scratch directory");
    for entry in std::fs::read_dir(&dir)
        .expect("the data directory")
        .flatten()
    {
        let _ = std::fs::copy(entry.path(), scratch.join(entry.file_name()));
    }
    println!(
        "Differential table over Triangle's example files ({}){}:",
        dir.display(),
        if scope == Scope::Smoke {
            ", smoke run (face.poly with pq30 and pqY)"
        } else {
            ""
        }
    );
    println!(
        "Triangle 1.6 (Debian's) first runs each case as a program under a {} s limit (DNF: it \
         did not finish); then Triangle's library and ours run it in this process (ours is \
         cancelled after {} s: DNF). Ratio: our triangle count / Triangle's. Smallest angle in \
         degrees. Largest area: with `a<x>`, each mesh's largest triangle area / x (≤ 1 is within \
         the bound); otherwise our largest triangle area / Triangle's. Times in ms, wall clock, \
         through both C ABIs, interleaved: the median of {reps} call(s) each (TABLE_REPS), or \
         each side's best of about {} ms of calls where Triangle's call takes < 1 ms (calls: \
         ours/Triangle's; one call: ours alone, where Triangle does not finish); time ratio: \
         ours / Triangle's.",
        TRIANGLE_TIME_LIMIT.as_secs(),
        OUR_TIME_LIMIT.as_secs(),
        budget.as_millis()
    );
    println!(
        "| file | switches | Triangle tris | our tris | ratio | Triangle min angle | our min angle | largest area | Triangle ms | our ms | time ratio | calls |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|");
    let only = std::env::var("REFINE_TABLE_FILES").ok();
    let mut rows = Vec::new();
    for file in example_files(&dir) {
        if scope == Scope::Smoke && file.name != "face.poly"
            || only
                .as_ref()
                .is_some_and(|list| !list.split(',').any(|f| f == file.name))
        {
            continue;
        }
        for switches in switch_sets(&file) {
            if scope == Scope::Smoke && switches != "pq30" && switches != "pqY" {
                continue;
            }
            let keep = switches.contains('Y');
            let mut ours = run_ours(&file, &switches, keep);
            let (theirs, calls) =
                race_triangle(&file, &switches, &scratch, keep, &mut ours, (reps, budget));
            let row = Row {
                bound: bound_of(&switches),
                theirs,
                ours,
                calls,
                file: file.name.clone(),
                switches,
            };
            row.print();
            rows.push(row);
        }
    }
    let _ = std::fs::remove_dir_all(&scratch);
    summary(&rows);
}

fn summary(rows: &[Row]) {
    let both: Vec<(&Row, &Measure, &Measure)> = rows
        .iter()
        .filter_map(|r| r.both().map(|(t, o)| (r, t, o)))
        .collect();
    let ratios: Vec<f64> = both
        .iter()
        .map(|(_, t, o)| o.triangles as f64 / t.triangles as f64)
        .collect();
    let at_most_one = ratios.iter().filter(|&&r| r <= 1.0).count();
    let geometric_mean = (ratios.iter().map(|r| r.ln()).sum::<f64>() / ratios.len() as f64).exp();
    let below: Vec<&(&Row, &Measure, &Measure)> = both
        .iter()
        .filter(|(_, t, o)| o.smallest_angle < t.smallest_angle - ANGLE_SLACK)
        .collect();
    let within_bound = both
        .iter()
        .filter(|(r, _, o)| r.bound.is_some_and(|x| o.largest_area <= x * (1.0 + 1e-12)))
        .count();
    let bounded = both.iter().filter(|(r, _, _)| r.bound.is_some()).count();
    println!();
    println!("Summary ({} cases):", rows.len());
    println!(
        "- Triangle finishes {} of {} cases; both finish with triangles on {}",
        rows.iter()
            .filter(|r| matches!(r.theirs, Outcome::Done(_)))
            .count(),
        rows.len(),
        both.len()
    );
    for (who, pick) in [
        ("Triangle", (|r: &Row| &r.theirs) as fn(&Row) -> &Outcome),
        ("ours", |r: &Row| &r.ours),
    ] {
        let dnf: Vec<String> = rows
            .iter()
            .filter(|r| !matches!(pick(r), Outcome::Done(_)))
            .map(Row::name)
            .collect();
        println!(
            "- {who} does not finish (or fails) on {}: {}",
            dnf.len(),
            if dnf.is_empty() {
                "—".to_string()
            } else {
                dnf.join(", ")
            }
        );
    }
    println!(
        "- our count ≤ 1.0× Triangle's on {at_most_one}/{} cases where both finish; geometric \
         mean ratio {geometric_mean:.3} (target ≤ 0.85); largest ratio {:.3}",
        ratios.len(),
        ratios.iter().copied().fold(0.0, f64::max)
    );
    println!(
        "- our smallest angle ≥ Triangle's on {}/{} cases",
        both.len() - below.len(),
        both.len()
    );
    println!("- our largest triangle within the `a` bound on {within_bound}/{bounded} cases");
    let mut y_total = 0;
    let mut y_lost = Vec::new();
    for (r, t, o) in both.iter().filter(|(r, _, _)| r.switches.contains('Y')) {
        y_total += t.kept.len();
        for (apex, [u, w]) in lost_angles(t, o) {
            y_lost.push(format!(
                "{} {} at {apex:?} ({:.3}°)",
                r.file,
                r.switches,
                (u - w)
                    .abs()
                    .to_degrees()
                    .min(360.0 - (u - w).abs().to_degrees())
            ));
        }
    }
    println!(
        "- Y/YY: of the {y_total} input angles (between consecutive input segments at an input \
         vertex) that Triangle's meshes keep unsplit (one triangle's corner), ours keep {}{}",
        y_total - y_lost.len(),
        if y_lost.is_empty() {
            String::new()
        } else {
            format!("; lost: {}", y_lost.join("; "))
        }
    );
    let mut worst: Vec<(&Row, f64)> = both
        .iter()
        .map(|(r, t, o)| (*r, o.triangles as f64 / t.triangles as f64))
        .collect();
    worst.sort_by(|a, b| b.1.total_cmp(&a.1));
    println!("- the 10 worst ratios:");
    for (r, ratio) in worst.iter().take(10) {
        println!("  - {}: {ratio:.3}", r.name());
    }
    time_summary(&both);
    println!("- our smallest angle below Triangle's:");
    if below.is_empty() {
        println!("  - none");
    }
    for (r, t, o) in &below {
        println!(
            "  - {}: {:.4}° (ours) < {:.4}° (Triangle's)",
            r.name(),
            o.smallest_angle,
            t.smallest_angle
        );
    }
    let empty: Vec<String> = rows
        .iter()
        .filter(|r| {
            [&r.theirs, &r.ours]
                .iter()
                .any(|o| matches!(o, Outcome::Done(m) if m.triangles == 0))
        })
        .map(Row::name)
        .collect();
    if !empty.is_empty() {
        println!(
            "- no triangle in a mesh (left out of the counts above): {}",
            empty.join(", ")
        );
    }
    let ours_only: Vec<String> = rows
        .iter()
        .filter_map(|r| match (&r.theirs, &r.ours) {
            (Outcome::Done(_), _) => None,
            (_, Outcome::Done(o)) => Some(format!(
                "{}: {} triangles, {:.4}°",
                r.name(),
                o.triangles,
                o.smallest_angle
            )),
            _ => None,
        })
        .collect();
    if !ours_only.is_empty() {
        println!("- where Triangle does not finish, ours gives:");
        for line in ours_only {
            println!("  - {line}");
        }
    }
}

/// The summary's lines on time: geometric means of the time ratios, how often ours is at most
/// Triangle's where Triangle takes at least a millisecond, the sums, the worst ten.
fn time_summary(both: &[(&Row, &Measure, &Measure)]) {
    let long = |t: &Measure| t.time >= race::SHORT;
    let ratio = |t: &Measure, o: &Measure| o.time.as_secs_f64() / t.time.as_secs_f64();
    let ratios: Vec<f64> = both.iter().map(|(_, t, o)| ratio(t, o)).collect();
    let cpu_ratios: Vec<f64> = both
        .iter()
        .map(|(_, t, o)| o.cpu.as_secs_f64() / t.cpu.as_secs_f64())
        .collect();
    let pick = |want_long: bool| -> Vec<f64> {
        both.iter()
            .filter(|(_, t, _)| long(t) == want_long)
            .map(|(_, t, o)| ratio(t, o))
            .collect()
    };
    let (long_ratios, short_ratios) = (pick(true), pick(false));
    let at_most = |r: &[f64]| r.iter().filter(|&&r| r <= 1.0).count();
    let mean = |r: &[f64]| {
        if r.is_empty() {
            "—".to_string()
        } else {
            format!("{:.2}", geometric_mean(r))
        }
    };
    let sum = |pick: fn(&(&Row, &Measure, &Measure)) -> Duration| {
        both.iter().map(pick).sum::<Duration>().as_secs_f64()
    };
    println!(
        "- time ours / Triangle's on the {} cases where both finish with triangles: geometric \
         mean {} (of the CPU times: {}); where Triangle takes ≥ 1 ms: {} over {} cases, ours ≤ Triangle's on {}/{}; \
         where it takes < 1 ms: {} over {} cases, ours ≤ Triangle's on {}/{}; sums of the \
         times: ours {:.3} s, Triangle's {:.3} s",
        both.len(),
        mean(&ratios),
        mean(&cpu_ratios),
        mean(&long_ratios),
        long_ratios.len(),
        at_most(&long_ratios),
        long_ratios.len(),
        mean(&short_ratios),
        short_ratios.len(),
        at_most(&short_ratios),
        short_ratios.len(),
        sum(|(_, _, o)| o.time),
        sum(|(_, t, _)| t.time),
    );
    let mut worst: Vec<(&Row, f64, Duration, Duration)> = both
        .iter()
        .map(|(r, t, o)| (*r, ratio(t, o), o.time, t.time))
        .collect();
    worst.sort_by(|a, b| b.1.total_cmp(&a.1));
    println!("- the 10 worst time ratios:");
    for (r, ratio, ours, theirs) in worst.iter().take(10) {
        println!(
            "  - {}: {ratio:.1} ({} ms against {} ms)",
            r.name(),
            race::ms(*ours),
            race::ms(*theirs)
        );
    }
}
