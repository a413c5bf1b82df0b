//! The size sweep of issue 36 (point 4): quality meshes of about 10^2, 10^3, 10^4, 10^5 and 10^6
//! triangles (Triangle's count), ours against Debian's Triangle 1.6 through their C ABIs in this
//! process ([`crate::race`]).
//!
//! Inputs, each scaled to area 1:
//! - four domains: a disk polygon (convex); a square plate with four round holes; a comb of four
//!   teeth (six reflex corners); a star of six spikes with tip angles of 5°–10° (small input
//!   angles); each with `pq` and `pq30` — the boundary split into pieces of length h (a circle
//!   into max(base, ⌈2πr/h⌉) segments), h chosen for the size — and with `pqa<A>` and
//!   `pq30a<A>` on its coarse form (corners only, circles of their base segment count), A chosen
//!   for the size;
//! - point sets in the unit square (its corners included, so the domain is the square):
//!   uniform and clustered ones with `q30`, n points chosen for the size, and 20 uniform points
//!   with `q30a<A>`.
//!
//! h, A and n are calibrated by running Triangle: from a guess at 10^2, scaled by 10 from one size
//! to the next, up to four multiplicative steps (count ∝ 1/h, 1/A, n) per size up to 10^5; 10^6
//! and 10^7 take the last value scaled by 10 unmeasured (the rows show Triangle's counts). Each row prints both counts, times (see `race`) and ratios,
//! both smallest angles and both mean radius ratios (2·r_in/r_circ, 1 for an equilateral
//! triangle); every mesh is checked to be a valid mesh of its domain (`crate::measure`). Then per
//! size: the geometric mean and the worst of the time ratios, the geometric mean of the count
//! ratios, the mean radius ratios.
//!
//! `SWEEP_SIZES=2,3,4` restricts the sizes (exponents of 10); `SWEEP_REPS` sets the calls of
//! each side per row (default 5 up to 10^4, 3 at 10^5, 2 from 10^6; the median of an even count
//! is the lower one), fewer where they would pass [`MOST_TIME`] (one at least); short rows
//! (Triangle under a millisecond) are each side's best of about [`BUDGET`] of calls. The smoke
//! run (under `cargo test`) is the disk alone at 10^2, one call each.

use std::f64::consts::TAU;
use std::time::{Duration, Instant};

use crate::common;
use crate::race::{geometric_mean, ms, race};
use crate::{measure, Measured};
use common::call::MeshInput;
use common::points::Point;
use common::pslg::{polygon_area, Pslg};
use common::reference::Reference;
use common::rng::SplitMix64;
use common::timing::{number_from_env, sizes_from_env};

/// Short rows repeat each side until it has spent about this long (best call).
const BUDGET: Duration = Duration::from_millis(50);
/// A side's calls in one row stop once they have spent about this long (one call at least).
const MOST_TIME: Duration = Duration::from_secs(6);
const SEED: u64 = 0x5EED_0036;

/// Which rows the sweep runs.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Scope {
    /// Every input at `SWEEP_SIZES` (default 10^2…10^6).
    Full,
    /// The disk at 10^2, one call each.
    Smoke,
}

/// A closed boundary loop.
enum Loop {
    /// Corners, counter-clockwise for the outer loop.
    Polygon(Vec<Point>),
    /// A circle of at least `base` segments.
    Circle {
        centre: Point,
        radius: f64,
        base: usize,
    },
}

impl Loop {
    fn scaled(&self, s: f64) -> Loop {
        match self {
            Loop::Polygon(corners) => {
                Loop::Polygon(corners.iter().map(|p| p.map(|x| x * s)).collect())
            }
            Loop::Circle {
                centre,
                radius,
                base,
            } => Loop::Circle {
                centre: centre.map(|x| x * s),
                radius: radius * s,
                base: *base,
            },
        }
    }

    /// The loop's vertices: each side split into pieces no longer than `spacing` (corners
    /// only, or the base circle, without).
    fn points(&self, spacing: Option<f64>) -> Vec<Point> {
        match self {
            Loop::Polygon(corners) => {
                let mut points = Vec::new();
                for (i, &a) in corners.iter().enumerate() {
                    let b = corners[(i + 1) % corners.len()];
                    let length = (b[0] - a[0]).hypot(b[1] - a[1]);
                    let pieces = spacing.map_or(1, |h| (length / h).ceil().max(1.0) as usize);
                    points.extend((0..pieces).map(|j| {
                        let t = j as f64 / pieces as f64;
                        [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
                    }));
                }
                points
            }
            Loop::Circle {
                centre,
                radius,
                base,
            } => {
                let n = spacing.map_or(*base, |h| (*base).max((TAU * radius / h).ceil() as usize));
                (0..n)
                    .map(|k| {
                        let angle = TAU * k as f64 / n as f64;
                        [
                            centre[0] + radius * angle.cos(),
                            centre[1] + radius * angle.sin(),
                        ]
                    })
                    .collect()
            }
        }
    }
}

/// A domain: an outer loop and round holes.
struct Shape {
    name: &'static str,
    outer: Loop,
    holes: Vec<Loop>,
}

impl Shape {
    /// `outer` and `holes` scaled so that the coarse domain has area 1.
    fn new(name: &'static str, outer: Loop, holes: Vec<Loop>) -> Shape {
        let raw = Shape { name, outer, holes };
        let scale = 1.0 / raw.pslg(None).area.expect("known area").sqrt();
        Shape {
            name,
            outer: raw.outer.scaled(scale),
            holes: raw.holes.iter().map(|h| h.scaled(scale)).collect(),
        }
    }

    /// The domain as a PSLG (zero-based), sides split at `spacing`, with its area.
    fn pslg(&self, spacing: Option<f64>) -> Pslg {
        let mut input = MeshInput::default();
        let mut add_loop = |polygon: &[Point]| {
            let first = input.points.len() as i32;
            let n = polygon.len() as i32;
            input.points.extend_from_slice(polygon);
            input
                .segments
                .extend((0..n).map(|k| [first + k, first + (k + 1) % n]));
        };
        let outer = self.outer.points(spacing);
        add_loop(&outer);
        let mut area = polygon_area(&outer).abs();
        let outer_area = area;
        for hole in &self.holes {
            let polygon = hole.points(spacing);
            add_loop(&polygon);
            area -= polygon_area(&polygon).abs();
            if let Loop::Circle { centre, .. } = hole {
                input.holes.push(*centre);
            }
        }
        Pslg {
            area: Some(area),
            area_ignoring_holes: Some(outer_area),
            ..Pslg::new(self.name.to_string(), input)
        }
    }
}

/// The four domains.
fn shapes() -> Vec<Shape> {
    let disk = Shape::new(
        "disk",
        Loop::Circle {
            centre: [0.0, 0.0],
            radius: 1.0,
            base: 32,
        },
        Vec::new(),
    );
    let circle = |x: f64, y: f64, radius: f64| Loop::Circle {
        centre: [x, y],
        radius,
        base: 8,
    };
    let plate = Shape::new(
        "plate, 4 holes",
        Loop::Polygon(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]),
        vec![
            circle(0.27, 0.30, 0.12),
            circle(0.71, 0.28, 0.10),
            circle(0.30, 0.72, 0.09),
            circle(0.70, 0.69, 0.14),
        ],
    );
    // Four teeth 0.1 wide and 0.7 long on a 0.3-high back: six reflex corners.
    let mut comb = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]];
    for (right, left) in [(0.9, 0.7), (0.6, 0.4), (0.3, 0.1)] {
        comb.extend([[right, 1.0], [right, 0.3], [left, 0.3], [left, 1.0]]);
    }
    comb.push([0.0, 1.0]);
    let comb = Shape::new("comb, 6 reflex corners", Loop::Polygon(comb), Vec::new());
    // Six spikes of tip angles 5°…10° on a core of radius 0.35, tips at radius 1: a tip's
    // half-angle α/2 has tan(α/2) = r sin β / (1 − r cos β), β the spike's half-width at the
    // core, so r sin β + tan(α/2) r cos β = tan(α/2).
    let core = 0.35;
    let mut star = Vec::new();
    for k in 0..6 {
        let direction = TAU * k as f64 / 6.0;
        let t = (0.5 * (5.0 + k as f64).to_radians()).tan();
        // r·hypot(1, t)·sin(β + φ) = t with tan φ = t.
        let beta = (t / (core * 1f64.hypot(t))).asin() - t.atan();
        let at = |r: f64, a: f64| [r * a.cos(), r * a.sin()];
        star.extend([
            at(core, direction - beta),
            at(1.0, direction),
            at(core, direction + beta),
        ]);
    }
    let star = Shape::new("star, 5°–10° spikes", Loop::Polygon(star), Vec::new());
    vec![disk, plate, comb, star]
}

/// The unit square's corners and `n` − 4 uniform points in it.
fn uniform_points(n: usize) -> Vec<Point> {
    let mut rng = SplitMix64::new(SEED);
    let mut points = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    points.extend((4..n.max(4)).map(|_| [rng.next_f64(), rng.next_f64()]));
    points
}

/// The unit square's corners; a quarter of the other points uniform, the rest in clusters of
/// about 150 around uniform centres (each coordinate the centre plus 0.02 × (a sum of three
/// uniforms − 1.5), kept in the square).
fn clustered_points(n: usize) -> Vec<Point> {
    let mut rng = SplitMix64::new(SEED ^ 0xC1);
    let mut points = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let rest = n.max(8) - 4;
    let centres: Vec<Point> = (0..(rest / 200).max(1))
        .map(|_| [0.05 + 0.9 * rng.next_f64(), 0.05 + 0.9 * rng.next_f64()])
        .collect();
    for k in 0..rest {
        if k % 4 == 0 {
            points.push([rng.next_f64(), rng.next_f64()]);
            continue;
        }
        let c = centres[rng.below(centres.len())];
        let mut spread = || 0.02 * (rng.next_f64() + rng.next_f64() + rng.next_f64() - 1.5);
        let p = [
            (c[0] + spread()).clamp(1e-3, 1.0 - 1e-3),
            (c[1] + spread()).clamp(1e-3, 1.0 - 1e-3),
        ];
        points.push(p);
    }
    points
}

/// What calibration varies: Triangle's count grows as 1/h, 1/A, or n.
#[derive(Clone, Copy)]
enum Knob {
    Spacing,
    Area,
    Points,
}

impl Knob {
    /// The exponent s of count ∝ knob^s.
    fn exponent(self) -> f64 {
        match self {
            Knob::Spacing | Knob::Area => -1.0,
            Knob::Points => 1.0,
        }
    }

    /// A first guess for `target` triangles (area-1 domains).
    fn guess(self, target: f64) -> f64 {
        match self {
            Knob::Spacing => 8.0 / target,
            Knob::Area => 1.3 / target,
            Knob::Points => target / 3.0,
        }
    }

    /// The value as it is used: A as printed (four significant digits, Triangle reads no
    /// exponent), n whole, all within sane bounds.
    fn clamp(self, value: f64) -> f64 {
        match self {
            Knob::Spacing => value.clamp(1e-7, 2.0),
            Knob::Area => decimal(value.clamp(1e-9, 1.0)).parse().expect("a number"),
            Knob::Points => value.clamp(8.0, 1e7).round(),
        }
    }
}

/// `x` in decimals with four significant digits.
fn decimal(x: f64) -> String {
    let digits = (3 - x.log10().floor() as i32).max(0) as usize;
    let text = format!("{x:.digits$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

/// The input family of a row.
#[derive(Clone, Copy)]
enum Family {
    Shape(usize),
    Uniform,
    Clustered,
    /// 20 uniform points (with `a`).
    FewUniform,
}

/// One row of the sweep at every size: an input family and switches (without `zQ`), and the
/// knob calibrated for the size.
struct Case {
    family: Family,
    /// The switches; with [`Knob::Area`] the bound follows.
    switches: &'static str,
    knob: Knob,
}

impl Case {
    fn input_name(&self, shapes: &[Shape]) -> String {
        match self.family {
            Family::Shape(k) => shapes[k].name.to_string(),
            Family::Uniform => "uniform points".into(),
            Family::Clustered => "clustered points".into(),
            Family::FewUniform => "20 uniform points".into(),
        }
    }

    /// The input and the switches (without `zQ`) for the knob's `value`.
    fn instance(&self, shapes: &[Shape], value: f64) -> (Pslg, String) {
        let points = |points: Vec<Point>, name: &str| Pslg {
            convex: true,
            ..Pslg::new(name.to_string(), MeshInput::from_points(points))
        };
        let pslg = match (self.family, self.knob) {
            (Family::Shape(k), Knob::Spacing) => shapes[k].pslg(Some(value)),
            (Family::Shape(k), _) => shapes[k].pslg(None),
            (Family::Uniform, _) => points(uniform_points(value as usize), "uniform points"),
            (Family::Clustered, _) => points(clustered_points(value as usize), "clustered points"),
            (Family::FewUniform, _) => points(uniform_points(20), "20 uniform points"),
        };
        let switches = match self.knob {
            Knob::Area => format!("{}{}", self.switches, decimal(value)),
            _ => self.switches.to_string(),
        };
        (pslg, switches + &super::extra_switches())
    }
}

fn cases(scope: Scope, shapes: &[Shape]) -> Vec<Case> {
    let mut cases = Vec::new();
    let domains = if scope == Scope::Smoke {
        1
    } else {
        shapes.len()
    };
    for k in 0..domains {
        for (switches, knob) in [
            ("pq", Knob::Spacing),
            ("pq30", Knob::Spacing),
            ("pqa", Knob::Area),
            ("pq30a", Knob::Area),
        ] {
            cases.push(Case {
                family: Family::Shape(k),
                switches,
                knob,
            });
        }
    }
    if scope == Scope::Full {
        for (family, switches, knob) in [
            (Family::Uniform, "q30", Knob::Points),
            (Family::Clustered, "q30", Knob::Points),
            (Family::FewUniform, "q30a", Knob::Area),
        ] {
            cases.push(Case {
                family,
                switches,
                knob,
            });
        }
    }
    cases
}

/// Triangle's triangle count on `case` with `value`.
fn triangle_count(reference: &Reference, shapes: &[Shape], case: &Case, value: f64) -> usize {
    let (pslg, switches) = case.instance(shapes, value);
    let out = reference.triangulate_with(&format!("{switches}zQ"), &pslg.input, false);
    out.counts.triangles as usize
}

/// Per size exponent in `exponents` (sorted), the knob's value for `case`: a chain from 10^2
/// (the guess) up, each size starting from the last one's value scaled by 10, then (up to 10^5)
/// at most four runs of Triangle, each correcting the value by the count's miss; the value whose
/// count came closest stands.
fn calibrate(reference: &Reference, shapes: &[Shape], case: &Case, exponents: &[u32]) -> Vec<f64> {
    let knob = case.knob;
    let s = knob.exponent();
    let last = *exponents.last().expect("a size");
    let mut value = knob.clamp(knob.guess(100.0));
    let mut values = Vec::new();
    for exponent in 2..=last {
        let target = 10f64.powi(exponent as i32);
        if exponent > 2 {
            value = knob.clamp(value * 10f64.powf(1.0 / s));
        }
        let steps = match exponent {
            0..=5 => 4,
            _ => 0,
        };
        let mut best = (f64::INFINITY, value);
        for _ in 0..steps {
            let count = triangle_count(reference, shapes, case, value).max(1) as f64;
            let miss = (count / target).ln().abs();
            if miss < best.0 {
                best = (miss, value);
            }
            if miss < 0.03 {
                break;
            }
            let next = knob.clamp(value * (target / count).powf(1.0 / s));
            if next == value {
                break;
            }
            value = next;
        }
        value = best.1;
        if exponents.contains(&exponent) {
            values.push(value);
        }
    }
    values
}

/// One finished row.
struct Row {
    exponent: u32,
    name: String,
    switches: String,
    theirs: Measured,
    ours: Measured,
    theirs_time: Duration,
    ours_time: Duration,
    /// Process CPU time ours / Triangle's.
    cpu_ratio: f64,
}

impl Row {
    fn time_ratio(&self) -> f64 {
        self.ours_time.as_secs_f64() / self.theirs_time.as_secs_f64()
    }

    fn count_ratio(&self) -> f64 {
        self.ours.triangles as f64 / self.theirs.triangles as f64
    }
}

/// The calls of each side per row at size 10^`exponent`.
fn reps_at(scope: Scope, exponent: u32) -> usize {
    if scope == Scope::Smoke {
        return 1;
    }
    let default = match exponent {
        0..=4 => 5,
        5 => 3,
        _ => 2,
    };
    number_from_env("SWEEP_REPS", default).max(1)
}

/// Runs the sweep and prints its rows and per-size summary.
pub fn run(scope: Scope) {
    let Some(reference) = common::reference() else {
        println!("Size sweep: Triangle 1.6 is not installed, no sweep");
        return;
    };
    let start = Instant::now();
    let exponents: Vec<u32> = if scope == Scope::Smoke {
        vec![2]
    } else {
        let mut e: Vec<u32> = sizes_from_env("SWEEP_SIZES", &[2, 3, 4, 5, 6])
            .into_iter()
            .map(|e| e as u32)
            .filter(|e| (2..=7).contains(e))
            .collect();
        e.sort_unstable();
        e.dedup();
        e
    };
    if exponents.is_empty() {
        println!("Size sweep: no size in SWEEP_SIZES (exponents 2 to 7)");
        return;
    }
    let shapes = shapes();
    let cases = cases(scope, &shapes);
    println!();
    println!(
        "Size sweep{}: quality meshes of about 10^{} triangles (Triangle's count; h, A and n \
         calibrated by running Triangle), ours against Triangle 1.6 through their C ABIs in this \
         process, interleaved; times in ms (wall clock; the CPU time ratio is of the process \
         CPU times), the best of about {} ms of calls where Triangle's \
         call takes < 1 ms, else the median of SWEEP_REPS calls (5; 3 at 10^5, 2 from 10^6, \
         the lower one of two; fewer where a side's calls would pass {} s); ratios ours / Triangle's; ρ the mean radius ratio \
         2·r_in/r_circ.",
        if scope == Scope::Smoke {
            " (smoke run: the disk at 10^2, one call each)"
        } else {
            ""
        },
        exponents
            .iter()
            .map(|e| e.to_string())
            .collect::<Vec<_>>()
            .join(", 10^"),
        BUDGET.as_millis(),
        MOST_TIME.as_secs()
    );
    let values: Vec<Vec<f64>> = cases
        .iter()
        .map(|case| calibrate(reference, &shapes, case, &exponents))
        .collect();
    println!("(calibration: {:.1} s)", start.elapsed().as_secs_f64());
    println!(
        "| size | input | switches | Triangle tris | our tris | count ratio | Triangle ms | our ms | time ratio | CPU time ratio | calls (ours/Triangle's) | Triangle min angle | our min angle | Triangle ρ | our ρ |"
    );
    println!("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|");
    let mut rows = Vec::new();
    let mut checking = Duration::ZERO;
    for (i, &exponent) in exponents.iter().enumerate() {
        let reps = reps_at(scope, exponent);
        let budget = if scope == Scope::Smoke {
            Duration::ZERO
        } else {
            BUDGET
        };
        for (case, values) in cases.iter().zip(&values) {
            let (pslg, switches) = case.instance(&shapes, values[i]);
            let call = format!("{switches}zQ");
            let result = race(
                &call,
                &pslg.input,
                true,
                Some(reference),
                reps,
                budget,
                MOST_TIME,
            );
            let (Some(o), Some(t)) = (&result.ours, &result.theirs) else {
                unreachable!("both sides ran");
            };
            let checks = Instant::now();
            let (ours, theirs) = (
                measure(&pslg, &call, "our", &o.mesh),
                measure(&pslg, &call, "Triangle's", &t.mesh),
            );
            checking += checks.elapsed();
            let row = Row {
                exponent,
                name: case.input_name(&shapes),
                ours,
                theirs,
                ours_time: o.time,
                theirs_time: t.time,
                cpu_ratio: o.cpu.as_secs_f64() / t.cpu.as_secs_f64(),
                switches,
            };
            println!(
                "| 10^{} | {} | {} | {} | {} | {:.3} | {} | {} | {:.2} | {:.2} | {} | {:.2} | {:.2} | {:.4} | {:.4} |",
                row.exponent,
                row.name,
                row.switches,
                row.theirs.triangles,
                row.ours.triangles,
                row.count_ratio(),
                ms(row.theirs_time),
                ms(row.ours_time),
                row.time_ratio(),
                row.cpu_ratio,
                result.calls(),
                row.theirs.smallest_angle,
                row.ours.smallest_angle,
                row.theirs.radius_ratio,
                row.ours.radius_ratio,
            );
            rows.push(row);
        }
    }
    println!();
    println!("Per size (time and count ratios ours / Triangle's):");
    println!(
        "| size | rows | Triangle's counts | time ratio, geometric mean (CPU time) | worst time ratio | count ratio, geometric mean | mean ρ ours / Triangle's | our min angle ≥ Triangle's |"
    );
    println!("|---|---:|---|---:|---|---:|---|---:|");
    for &exponent in &exponents {
        let at: Vec<&Row> = rows.iter().filter(|r| r.exponent == exponent).collect();
        let times: Vec<f64> = at.iter().map(|r| r.time_ratio()).collect();
        let cpu: Vec<f64> = at.iter().map(|r| r.cpu_ratio).collect();
        let counts: Vec<f64> = at.iter().map(|r| r.count_ratio()).collect();
        let worst = at
            .iter()
            .max_by(|a, b| a.time_ratio().total_cmp(&b.time_ratio()))
            .expect("a row");
        let lowest = at.iter().map(|r| r.theirs.triangles).min().unwrap_or(0);
        let highest = at.iter().map(|r| r.theirs.triangles).max().unwrap_or(0);
        let mean = |f: fn(&Measured) -> f64, pick: fn(&Row) -> &Measured| {
            at.iter().map(|r| f(pick(r))).sum::<f64>() / at.len() as f64
        };
        let angles_kept = at
            .iter()
            .filter(|r| r.ours.smallest_angle >= r.theirs.smallest_angle - 1e-9)
            .count();
        println!(
            "| 10^{exponent} | {} | {lowest}–{highest} | {:.2} ({:.2}) | {:.2} ({} {}) | {:.3} | {:.4} / {:.4} | {angles_kept}/{} |",
            at.len(),
            geometric_mean(&times),
            geometric_mean(&cpu),
            worst.time_ratio(),
            worst.name,
            worst.switches,
            geometric_mean(&counts),
            mean(|m| m.radius_ratio, |r| &r.ours),
            mean(|m| m.radius_ratio, |r| &r.theirs),
            at.len()
        );
    }
    let all: Vec<f64> = rows.iter().map(Row::time_ratio).collect();
    println!(
        "All {} rows: time ratio geometric mean {:.2}; the sweep took {:.0} s ({:.0} s of it \
         checking the meshes)",
        rows.len(),
        geometric_mean(&all),
        start.elapsed().as_secs_f64(),
        checking.as_secs_f64()
    );
}
