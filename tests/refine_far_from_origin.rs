//! Quality refinement far from the origin (issue 25): georeferenced coordinates, a survey of a
//! few metres at 10^6 m, where a double's rounding is large against the features. Debian's
//! `triangle` and ours run as programs on the same files (Triangle crashes on some of these
//! inputs: then only our output is checked), for offsets 10^3 … 10^15 and sides 10^-6 … 10^6,
//! with `q`, `q30`, `q33`, `q30a<x>`, `q30D`, `rq30` on 200 random points and `pq30` on a square
//! with a square hole and a 20° notch:
//! - our mesh is valid (counter-clockwise by exact orientation), and every triangle is within
//!   the area bound (its area in local coordinates, which are exact by Sterbenz's lemma);
//! - where Triangle reaches θ, so do we (angles measured in local coordinates), with a count
//!   within 0.5–2× Triangle's;
//! - where we do not reach θ, the program warns (never a silent sliver);
//! - the mesh of an input equals, vertex for vertex and triangle for triangle, the mesh of the
//!   input translated by its smallest coordinates (exactly) and translated back.
//!
//! Without /usr/bin/triangle the tests print SKIPPED and pass, unless env `CI` is set.

mod cli_support;

use std::collections::BTreeSet;
use std::path::Path;
use std::process::Command;

use cli_support::{ours, reference, Lcg, TempDir};
use triangle_rs::io::files::{read_ele, read_node};

/// Angles are compared to this many degrees.
const ANGLE_SLACK: f64 = 1e-9;

type Point = [f64; 2];

/// A program's run: whether it succeeded (within a time limit), and what it printed (stdout,
/// where the command-line programs print their warnings, as Triangle does, then stderr).
struct Ran {
    ok: bool,
    printed: String,
}

fn run(program: &Path, dir: &Path, args: &[&str]) -> Ran {
    let output = Command::new("timeout")
        .arg("60")
        .arg(program)
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap_or_else(|e| panic!("run {}: {e}", program.display()));
    Ran {
        ok: output.status.success(),
        printed: String::from_utf8_lossy(&output.stdout).into_owned()
            + &String::from_utf8_lossy(&output.stderr),
    }
}

/// A mesh read back from `base.node` / `base.ele`.
struct Mesh {
    points: Vec<Point>,
    triangles: Vec<[usize; 3]>,
}

fn read_mesh(dir: &TempDir, base: &str) -> Option<Mesh> {
    let (node, ele) = (format!("{base}.node"), format!("{base}.ele"));
    if !dir.exists(&node) || !dir.exists(&ele) {
        return None;
    }
    let node = read_node(&dir.read(&node), "node").ok()?;
    let ele = read_ele(&dir.read(&ele), "ele").ok()?;
    let first = node.first_number.unwrap_or(1) as i32;
    let points: Vec<Point> = node.points.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
    let triangles = ele
        .triangles
        .chunks_exact(ele.corners)
        .map(|t| [0, 1, 2].map(|k| (t[k] - first) as usize))
        .collect();
    Some(Mesh { points, triangles })
}

/// `p` relative to `origin`: exact for points within a factor of two of it (Sterbenz).
fn local(p: Point, origin: Point) -> Point {
    [p[0] - origin[0], p[1] - origin[1]]
}

fn smallest_angle(t: [Point; 3]) -> f64 {
    (0..3)
        .map(|k| {
            let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - a[0], c[1] - a[1]]);
            (u[0] * v[1] - u[1] * v[0])
                .abs()
                .atan2(u[0] * v[0] + u[1] * v[1])
                .to_degrees()
        })
        .fold(180.0, f64::min)
}

fn area(t: [Point; 3]) -> f64 {
    let [a, b, c] = t;
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
}

/// What a mesh achieves, in coordinates relative to `origin`.
struct Measures {
    triangles: usize,
    smallest_angle: f64,
    largest_area: f64,
}

impl Mesh {
    fn corners(&self, t: &[usize; 3]) -> [Point; 3] {
        t.map(|v| self.points[v])
    }

    /// Panics unless every triangle is counter-clockwise by exact orientation.
    fn assert_valid(&self, context: &str) {
        assert!(!self.triangles.is_empty(), "{context}: no triangle");
        for t in &self.triangles {
            let [a, b, c] = self.corners(t).map(|p| robust::Coord { x: p[0], y: p[1] });
            assert!(
                robust::orient2d(a, b, c) > 0.0,
                "{context}: triangle {t:?} is not counter-clockwise"
            );
        }
    }

    fn measures(&self, origin: Point) -> Measures {
        let local = |t: &[usize; 3]| self.corners(t).map(|p| local(p, origin));
        Measures {
            triangles: self.triangles.len(),
            smallest_angle: self
                .triangles
                .iter()
                .map(|t| smallest_angle(local(t)))
                .fold(180.0, f64::min),
            largest_area: self
                .triangles
                .iter()
                .map(|t| area(local(t)))
                .fold(0.0, f64::max),
        }
    }

    /// The triangles as sets of corner coordinates, each mapped by `map`.
    fn triangle_set(&self, map: impl Fn(Point) -> Point) -> BTreeSet<[[u64; 2]; 3]> {
        self.triangles
            .iter()
            .map(|t| {
                let mut c = self.corners(t).map(|p| map(p).map(f64::to_bits));
                c.sort();
                c
            })
            .collect()
    }
}

fn format_point(p: Point) -> String {
    format!("{:.17e} {:.17e}", p[0], p[1])
}

/// 200 random points in the square of side `side` at (`offset`, `offset`).
fn random_points(offset: f64, side: f64, seed: u64) -> Vec<Point> {
    let mut rng = Lcg::new(seed);
    (0..200)
        .map(|_| [offset + rng.next() * side, offset + rng.next() * side])
        .collect()
}

fn node_text(points: &[Point]) -> String {
    let mut text = format!("{} 2 0 0\n", points.len());
    for (i, &p) in points.iter().enumerate() {
        text += &format!("{} {}\n", i + 1, format_point(p));
    }
    text
}

/// A square of side `side` at (`offset`, `offset`) with a square hole, a notch of 20° in its top
/// side and a few points inside, relative to `origin` (exact for an origin at the offset, by
/// Sterbenz's lemma).
fn poly_text(offset: f64, side: f64, origin: Point) -> String {
    let at = |x: f64, y: f64| local([offset + x * side, offset + y * side], origin);
    let notch = 0.5 * (10f64.to_radians()).tan(); // half-width 0.05·tan… at depth 0.5
    let mut points = vec![
        at(0.0, 0.0),
        at(1.0, 0.0),
        at(1.0, 1.0),
        at(0.55 + notch * 0.1, 1.0),
        at(0.55, 0.5),
        at(0.55 - notch * 0.1, 1.0),
        at(0.0, 1.0),
        at(0.2, 0.2),
        at(0.4, 0.2),
        at(0.4, 0.4),
        at(0.2, 0.4),
    ];
    points.extend([at(0.7, 0.3), at(0.8, 0.8), at(0.15, 0.7)]);
    let mut text = format!("{} 2 0 0\n", points.len());
    for (i, &p) in points.iter().enumerate() {
        text += &format!("{} {}\n", i + 1, format_point(p));
    }
    let segments = [
        (1, 2),
        (2, 3),
        (3, 4),
        (4, 5),
        (5, 6),
        (6, 7),
        (7, 1),
        (8, 9),
        (9, 10),
        (10, 11),
        (11, 8),
    ];
    text += &format!("{} 0\n", segments.len());
    for (i, (a, b)) in segments.iter().enumerate() {
        text += &format!("{} {a} {b}\n", i + 1);
    }
    text += &format!("1\n1 {}\n", format_point(at(0.3, 0.3)));
    text
}

/// The angle bound of switches with `q` (20° without a number).
fn theta(switches: &str) -> f64 {
    let at = switches.find('q').expect("q");
    let number: String = switches[at + 1..]
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    number.parse().unwrap_or(20.0)
}

/// The smallest coordinates of `points`, per axis.
fn lowest(points: &[Point]) -> Point {
    points
        .iter()
        .fold([f64::MAX; 2], |m, p| [m[0].min(p[0]), m[1].min(p[1])])
}

/// Both programs on `file` with `texts[0]` (far from the origin) and Triangle on `texts[1]` (the
/// same input translated exactly to near the origin), with `switches` (plus `Q`), outputs `.1`.
/// For `r`, each input is first triangulated by our program (plain Delaunay) and both refine
/// that. Our count is held to Triangle's on the translated input, the same problem without the
/// rounding: far from the origin Triangle's own count can run away (344 381 triangles for 200
/// points at 10^6 with `q30D`, 1 471 near the origin).
fn compare(
    reference: &Path,
    case: &str,
    file: &str,
    texts: [&str; 2],
    switches: &str,
    origin: Point,
) {
    let context = format!("{case}, -{switches}");
    let dirs = [
        TempDir::new("far-ref"),
        TempDir::new("far-ours"),
        TempDir::new("near-ref"),
    ];
    let refine = switches.starts_with('r');
    for (dir, text) in dirs.iter().zip([texts[0], texts[0], texts[1]]) {
        dir.write(file, text);
        if refine {
            assert!(
                run(&ours(), dir.path(), &["-Q", file]).ok,
                "{context}: unrefined mesh"
            );
        }
    }
    let input = if refine {
        "x.1".to_string()
    } else {
        file.to_string()
    };
    let output = if refine { "x.2" } else { "x.1" };
    let args_quiet = [format!("-Q{switches}"), input.clone()];
    let args_loud = [format!("-{switches}"), input];
    let theirs = run(reference, dirs[0].path(), &[&args_quiet[0], &args_quiet[1]]);
    let mine = run(&ours(), dirs[1].path(), &[&args_loud[0], &args_loud[1]]);
    let theirs_near = run(reference, dirs[2].path(), &[&args_quiet[0], &args_quiet[1]]);
    assert!(mine.ok, "{context}: ours failed: {}", mine.printed);
    let our_mesh = read_mesh(&dirs[1], output).unwrap_or_else(|| panic!("{context}: no output"));
    our_mesh.assert_valid(&context);
    let m = our_mesh.measures(origin);
    let theta = theta(switches);
    let bound = switches.split('a').nth(1).and_then(|s| {
        let n: String = s
            .chars()
            .take_while(|c| c.is_ascii_digit() || "e.-".contains(*c))
            .collect();
        n.parse::<f64>().ok()
    });
    if let Some(bound) = bound {
        assert!(
            m.largest_area <= bound * (1.0 + 1e-12),
            "{context}: a triangle of area {:e} is above the bound {bound:e}",
            m.largest_area
        );
    }
    let warned = mine.printed.contains("arning");
    if m.smallest_angle < theta - ANGLE_SLACK {
        assert!(
            warned,
            "{context}: smallest angle {} below {theta} without a warning",
            m.smallest_angle
        );
    }
    let near_mesh = read_mesh(&dirs[2], output).filter(|_| theirs_near.ok);
    let near_mesh =
        near_mesh.unwrap_or_else(|| panic!("{context}: Triangle failed near the origin"));
    let near = near_mesh.measures([0.0, 0.0]);
    let their_mesh = read_mesh(&dirs[0], output).filter(|_| theirs.ok);
    let Some(their_mesh) = their_mesh else {
        return; // Triangle crashed or gave up: our valid mesh (and its warning) is all there is
    };
    let t = their_mesh.measures(origin);
    if t.smallest_angle >= theta - ANGLE_SLACK {
        assert!(
            m.smallest_angle >= theta - ANGLE_SLACK,
            "{context}: Triangle reaches {}°, ours {}°",
            t.smallest_angle,
            m.smallest_angle
        );
        let ratio = m.triangles as f64 / near.triangles as f64;
        assert!(
            (0.5..=2.0).contains(&ratio) && m.triangles <= 2 * t.triangles,
            "{context}: {} triangles against Triangle's {} ({} near the origin)",
            m.triangles,
            t.triangles,
            near.triangles
        );
    }
}

const OFFSETS: [f64; 5] = [1e3, 1e6, 1e9, 1e12, 1e15];
const SIDES: [f64; 5] = [1e-6, 1e-3, 1.0, 1e3, 1e6];

/// The pairs of offset and side where the side is below the offset (else the points are not
/// far from the origin) and above a few thousand units in the last place of the offset
/// (else the points collapse onto a handful of doubles; those are covered by the warnings).
fn pairs() -> Vec<(f64, f64)> {
    OFFSETS
        .iter()
        .flat_map(|&o| SIDES.iter().map(move |&s| (o, s)))
        .filter(|&(o, s)| s < o && s > o * 1e-13)
        .collect()
}

#[test]
fn random_points_far_from_the_origin_reach_the_angle_where_triangle_does() {
    let Some(reference) = reference() else { return };
    for (k, (offset, side)) in pairs().into_iter().enumerate() {
        let points = random_points(offset, side, 7 + k as u64);
        let text = node_text(&points);
        let origin = lowest(&points);
        let near: Vec<Point> = points.iter().map(|&p| local(p, origin)).collect();
        let near_text = node_text(&near);
        // Plain decimals: Triangle reads no exponent in a switch (`a3e3` is 3).
        let area = format!("{}", side * side / 300.0);
        for switches in ["q", "q30", "q33", &format!("q30a{area}"), "q30D", "rq30"] {
            let case = format!("200 points, offset {offset:e}, side {side:e}");
            compare(
                &reference,
                &case,
                "x.node",
                [&text, &near_text],
                switches,
                origin,
            );
        }
    }
}

#[test]
fn polygons_with_holes_far_from_the_origin_reach_the_angle_where_triangle_does() {
    let Some(reference) = reference() else { return };
    for (offset, side) in pairs() {
        let origin = [offset, offset];
        let (text, near_text) = (
            poly_text(offset, side, [0.0; 2]),
            poly_text(offset, side, origin),
        );
        let case = format!("square with a hole and a notch, offset {offset:e}, side {side:e}");
        compare(
            &reference,
            &case,
            "x.poly",
            [&text, &near_text],
            "pq30",
            origin,
        );
    }
}

#[test]
fn points_too_close_for_their_doubles_get_a_valid_mesh_and_a_warning() {
    // 300 points in a square of 800 units in the last place at 10^15 (Triangle crashes here).
    let points = random_points(1e15, 100.0, 3);
    let dir = TempDir::new("far-warn");
    dir.write("x.node", &node_text(&points));
    let ran = run(&ours(), dir.path(), &["-q30", "x.node"]);
    assert!(ran.ok, "{}", ran.printed);
    let mesh = read_mesh(&dir, "x.1").expect("output");
    mesh.assert_valid("side 100 at 1e15");
    let m = mesh.measures(lowest(&points));
    assert!(
        m.smallest_angle < 30.0,
        "reached {}: pick a harder case",
        m.smallest_angle
    );
    assert!(
        ran.printed.contains("precision"),
        "no warning: {}",
        ran.printed
    );
}

#[test]
fn a_mesh_far_from_the_origin_is_the_mesh_of_the_input_translated_there() {
    for (offset, side, switches) in [
        (1e6, 1e-3, "-Qq30"),
        (1e12, 1e3, "-Qq33"),
        (5e6, 1e-2, "-Qq30a1e-7"),
    ] {
        let points = random_points(offset, side, 11);
        let origin = lowest(&points);
        let translated: Vec<Point> = points.iter().map(|&p| local(p, origin)).collect();
        let dirs = [TempDir::new("far-at"), TempDir::new("far-near")];
        dirs[0].write("x.node", &node_text(&points));
        dirs[1].write("x.node", &node_text(&translated));
        for dir in &dirs {
            assert!(run(&ours(), dir.path(), &[switches, "x.node"]).ok);
        }
        let far = read_mesh(&dirs[0], "x.1").expect("far mesh");
        let near = read_mesh(&dirs[1], "x.1").expect("near mesh");
        let back = |p: Point| [p[0] + origin[0], p[1] + origin[1]];
        let context = format!("offset {offset:e}, side {side:e}, {switches}");
        let far_points: BTreeSet<[u64; 2]> =
            far.points.iter().map(|p| p.map(f64::to_bits)).collect();
        let near_points: BTreeSet<[u64; 2]> = near
            .points
            .iter()
            .map(|&p| back(p).map(f64::to_bits))
            .collect();
        assert_eq!(far_points, near_points, "{context}: vertices differ");
        assert!(
            far.triangle_set(|p| p) == near.triangle_set(back),
            "{context}: triangles differ"
        );
    }
}
