//! Quality refinement around vertices closer than the domain's resolution seems to allow (issue
//! 37.1): pairs and clusters of near-duplicates 10^-8 … 10^-15 of the domain apart, a few units
//! in the last place at the finest, as a survey re-exported with noise makes them. Triangle
//! refines around every one of them to θ; so must we, with no warning, on point sets (`q`,
//! `q30`) and PSLGs (`pq`, `pq30`, `pqa<x>`), against Debian's Triangle in the same process.
//! Each mesh is checked valid and constrained Delaunay by exact predicates first.
//!
//! Before, a floor of 2^-40 of the extent on new edges (some four thousand units in the last
//! place) and a refusal of boundary splits whose rounding cut more than 2^-20 of the thin
//! triangle beside them left 0° slivers from 10^-11 of the domain down.

mod common;

use common::call::MeshInput;
use common::pslg_checks::{check_constrained_delaunay, MeshView};
use common::quality::{engine, smallest_angle, ANGLE_TOLERANCE};
use common::reference::{Reference, REFERENCE_LIBRARY};
use common::rng::SplitMix64;
use triangle_rs::data::Hooks;

/// The side of the domains (metres of a survey site).
const SIDE: f64 = 1000.0;

/// Separations of the close vertices, as fractions of [`SIDE`].
const SEPARATIONS: [f64; 8] = [1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15];

fn reference_or_fail() -> &'static Reference {
    common::reference().unwrap_or_else(|| {
        panic!("{REFERENCE_LIBRARY} is missing: install Debian's libtriangle-dev (.ci/run does)")
    })
}

/// `θ` of `switches` (`q` alone: 20°).
fn theta(switches: &str) -> f64 {
    let after = &switches[switches.find('q').expect("a q switch") + 1..];
    let digits: String = after
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    digits.parse().unwrap_or(20.0)
}

/// Ours and Triangle's meshes of `input`: both valid; where Triangle's smallest angle reaches θ,
/// ours does, without a warning, and with at most twice Triangle's triangles.
fn compare(name: &str, input: &MeshInput, switches: &str) {
    let full = format!("{switches}zQ");
    let context = format!("{name}, \"{full}\"");
    let theirs = reference_or_fail().triangulate(&full, input);
    let (ours, warnings) =
        engine(&full, input, &Hooks::default()).unwrap_or_else(|e| panic!("{context}: {e}"));
    let measure = |who: &str, out| {
        let mesh = MeshView::of(out).unwrap_or_else(|e| panic!("{context}, {who}: {e}"));
        check_constrained_delaunay(&mesh).unwrap_or_else(|e| panic!("{context}, {who}: {e}"));
        (mesh.triangles.len(), smallest_angle(&mesh))
    };
    let (their_count, their_angle) = measure("Triangle's", &theirs);
    let (our_count, our_angle) = measure("ours", &ours);
    let theta = theta(switches);
    println!(
        "{context}: Triangle {their_count} triangles, {their_angle:.3}°; ours {our_count}, \
         {our_angle:.3}°"
    );
    if their_angle >= theta - ANGLE_TOLERANCE {
        assert!(
            our_angle >= theta - ANGLE_TOLERANCE && warnings.is_empty(),
            "{context}: ours {our_count} triangles, smallest angle {our_angle}° ({warnings:?}); \
             Triangle {their_count} at {their_angle}°"
        );
        assert!(
            our_count <= 2 * their_count,
            "{context}: ours {our_count} triangles, Triangle's {their_count}"
        );
    }
}

/// Three vertices of a triangle and a fourth `separation · SIDE` from the first, in `direction`:
/// the case (`[805, 400]` and `[805.00000001, 400.00000001]` in a 1000-unit domain)
/// and its kind, the pair on the hull or inside it.
fn pair(separation: f64, direction: [f64; 2], inside: bool) -> MeshInput {
    let norm = direction[0].hypot(direction[1]);
    let d = separation * SIDE / norm;
    let anchor = if inside {
        [500.0, 450.0]
    } else {
        [805.0, 400.0]
    };
    MeshInput::from_points(vec![
        [805.0, 400.0],
        [200.0, 30.0],
        [600.0, 900.0],
        if inside { anchor } else { [150.0, 800.0] },
        [anchor[0] + d * direction[0], anchor[1] + d * direction[1]],
    ])
}

/// Random points on the site, some re-entered with noise of `separation · SIDE` (a survey
/// exported twice), and clusters of three near-duplicates.
fn survey(seed: u64, separation: f64) -> MeshInput {
    let mut rng = SplitMix64::new(seed);
    let mut points: Vec<[f64; 2]> = (0..120)
        .map(|_| [rng.next_f64() * SIDE, rng.next_f64() * SIDE])
        .collect();
    let noise = separation * SIDE;
    for i in 0..12 {
        let p = points[i * 7];
        let copies = if i % 3 == 0 { 2 } else { 1 };
        for _ in 0..copies {
            points.push([
                p[0] + (rng.next_f64() - 0.5) * 2.0 * noise,
                p[1] + (rng.next_f64() - 0.5) * 2.0 * noise,
            ]);
        }
    }
    MeshInput::from_points(points)
}

/// A square with an inner segment to a vertex, a second vertex `separation · SIDE` beside that
/// one, and a boundary vertex as close to a corner.
fn pslg(separation: f64) -> MeshInput {
    let d = separation * SIDE;
    let mut input = MeshInput::from_points(vec![
        [0.0, 0.0],
        [SIDE, 0.0],
        [SIDE, SIDE],
        [0.0, SIDE],
        [300.0, 400.0],
        [300.0 + d, 400.0 + 0.3 * d],
        [SIDE - d, 0.0],
    ]);
    input.segments = vec![[0, 6], [6, 1], [1, 2], [2, 3], [3, 0], [4, 0]];
    input
}

#[test]
fn close_pairs_in_point_sets_reach_theta_as_in_triangle() {
    for &s in &SEPARATIONS {
        for (direction, inside) in [([1.0, 1.0], false), ([1.0, 0.0], false), ([0.3, 1.0], true)] {
            let input = pair(s, direction, inside);
            let name = format!("pair {s:e} apart toward {direction:?} (inside: {inside})");
            for switches in ["q", "q30"] {
                compare(&name, &input, switches);
            }
        }
    }
}

#[test]
fn surveys_with_near_duplicates_reach_theta_as_in_triangle() {
    for (i, &s) in SEPARATIONS.iter().enumerate() {
        let input = survey(37 + i as u64, s);
        // `q30` at three separations only: its meshes are some ten times larger.
        let switches: &[&str] = if i % 3 == 0 { &["q", "q30"] } else { &["q"] };
        for &switches in switches {
            compare(&format!("survey, noise {s:e}"), &input, switches);
        }
    }
}

#[test]
fn close_vertices_in_pslgs_reach_theta_as_in_triangle() {
    for (i, &s) in SEPARATIONS.iter().enumerate() {
        let input = pslg(s);
        let switches: &[&str] = if i % 3 == 0 {
            &["pq", "pq30", "pqa1000"]
        } else {
            &["pq", "pq30"]
        };
        for &switches in switches {
            compare(&format!("square, vertices {s:e} apart"), &input, switches);
        }
    }
}
