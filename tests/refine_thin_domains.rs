//! Refinement of domains thinner than the rounding of their coordinates (all vertices within a few
//! ulps of one line), where a split point rounded off a boundary segment would move the boundary
//! by a large fraction of the domain's width (found by fuzzing: a domain widened by 30% and two
//! vertices at one place). Every output must be a valid mesh (counter-clockwise by exact
//! orientation, manifold, no two vertices at one place, boundary edges are segments) covering
//! exactly the area of the unrefined domain (summed exactly, within 10^-12): the fuzz case itself,
//! random near-collinear sets, and a thin polygon at the scales 1, 10^-300 and 10^200.

mod common;

use common::call::MeshInput;
use common::pslg_checks::MeshView;
use common::rng::SplitMix64;
use common::{ours, Triangulation};

/// `v` moved by `k` ulps (toward larger bit patterns: away from zero for positive `v`).
fn nudged(v: f64, k: i64) -> f64 {
    f64::from_bits((v.to_bits() as i64 + k) as u64)
}

/// Error-free transformations (Shewchuk, "Adaptive precision floating-point arithmetic and fast
/// robust geometric predicates", 1997): a + b and a · b as unevaluated sums of two doubles.
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bv = s - a;
    (s, (a - (s - bv)) + (b - bv))
}

fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// An exact sum of doubles, as a nonoverlapping expansion (Shewchuk's Grow-Expansion with zero
/// elimination).
#[derive(Default)]
struct ExactSum(Vec<f64>);

impl ExactSum {
    fn add(&mut self, b: f64) {
        let mut q = b;
        let mut kept = Vec::with_capacity(self.0.len() + 1);
        for &h in &self.0 {
            let (s, e) = two_sum(q, h);
            if e != 0.0 {
                kept.push(e);
            }
            q = s;
        }
        if q != 0.0 {
            kept.push(q);
        }
        self.0 = kept;
    }

    fn value(&self) -> f64 {
        self.0.iter().sum()
    }
}

/// The largest coordinate magnitude, as a power of two (the scale the areas are summed at, so
/// that products neither overflow nor underflow).
fn scale_of(points: &[[f64; 2]]) -> f64 {
    let largest = points.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    2f64.powi(largest.log2().floor() as i32)
}

/// Twice the mesh's area, summed exactly (coordinates divided by `scale`, a power of two: exact):
/// the sum over triangles of a×b + b×c + c×a.
fn doubled_area(out: &Triangulation, scale: f64) -> f64 {
    let points = out.points.as_deref().unwrap_or_default();
    let mut sum = ExactSum::default();
    for corners in out.triangle_triples() {
        let [a, b, c] = corners.map(|v| points[(v - out.base) as usize].map(|x| x / scale));
        for (p, q) in [(a, b), (b, c), (c, a)] {
            let (h1, l1) = two_product(p[0], q[1]);
            let (h2, l2) = two_product(-p[1], q[0]);
            for term in [h1, l1, h2, l2] {
                sum.add(term);
            }
        }
    }
    sum.value()
}

/// Refines `input` with each switch string and checks the output against the unrefined domain
/// (`unrefined` switches): valid, no two vertices at one place, the same area.
fn check(name: &str, input: &MeshInput, unrefined: &str, refined: &[&str]) {
    let scale = scale_of(&input.points);
    let before = ours(unrefined, input).unwrap_or_else(|e| panic!("{name} {unrefined}: {e}"));
    MeshView::of(&before).unwrap_or_else(|e| panic!("{name} {unrefined}: {e}"));
    let area = doubled_area(&before, scale);
    for switches in refined {
        let out = ours(switches, input).unwrap_or_else(|e| panic!("{name} {switches}: {e}"));
        MeshView::of(&out).unwrap_or_else(|e| panic!("{name} {switches}: {e}"));
        let refined_area = doubled_area(&out, scale);
        assert!(
            (refined_area - area).abs() <= 1e-12 * area.abs(),
            "{name} {switches}: the domain's area {:e} became {:e} (in units of {scale:e})",
            area / 2.0,
            refined_area / 2.0,
        );
    }
}

#[test]
fn the_fuzzed_case_keeps_its_area() {
    // Case 93436 of the extreme-coordinates fuzz target (tests/fuzz_driver.rs): points a few ulps
    // off the line y = 0.3 x, six segments, two holes.
    let points = vec![
        [4.07, 1.221],
        [11.47, 3.441000000000001],
        [9.62, 2.8859999999999992],
        [0.74, 0.222],
        [5.55, 1.6649999999999998],
        [2.2199999999999998, 0.6659999999999998],
        [21.83, 6.549000000000001],
        [2.59, 0.7769999999999999],
        [3.7, 1.1099999999999997],
        [6.66, 1.9979999999999996],
        [5.92, 1.7760000000000005],
        [10.73, 3.219],
        [18.13, 5.439],
        [17.759999999999998, 5.328000000000001],
    ];
    let segments = [[8, 9], [2, 7], [10, 1], [1, 12], [6, 7], [13, 6]];
    let input = MeshInput {
        segments: segments
            .iter()
            .map(|s: &[i32; 2]| s.map(|v| v + 1))
            .collect(),
        ..MeshInput::from_points(points)
    };
    check(
        "fuzz case",
        &input,
        "pcQ",
        &[
            "pcq30S10Q",
            "pcq30DS1000Q",
            "pcq30Q",
            "pcDq30Q",
            "pcqa1e-16Q",
        ],
    );
    let with_holes = MeshInput {
        holes: vec![[-0.5, -6.5], [-7.5, -3.5]],
        ..input
    };
    check(
        "fuzz case with holes",
        &with_holes,
        "pQ",
        &["pq30S20000Q", "pq30Q", "pDq30Q"],
    );
}

#[test]
fn random_near_collinear_sets_keep_their_area() {
    let mut rng = SplitMix64::new(0x7417_0001);
    for case in 0..40 {
        // As the fuzz target draws them: on y = 0.3 x, each y moved by up to two ulps.
        let n = 4 + rng.below(40);
        let points: Vec<[f64; 2]> = (0..n)
            .map(|_| {
                let x = (1 + rng.below(63)) as f64 * 0.37;
                [x, nudged(0.3 * x, rng.below(5) as i64 - 2)]
            })
            .collect();
        let segments = (0..rng.below(12))
            .map(|_| [rng.below(n) as i32 + 1, rng.below(n) as i32 + 1])
            .filter(|s| s[0] != s[1])
            .collect();
        let input = MeshInput {
            segments,
            ..MeshInput::from_points(points)
        };
        check(
            &format!("near-collinear set {case}"),
            &input,
            "pcQ",
            &["pcq30Q", "pcDq30S50Q", "pcq33S200Q", "pcqa1e-15Q"],
        );
    }
}

/// A polygon around a stretch of the line y = 0.3 x, `width` ulps above and below it, its
/// vertices at the multiples of 0.37 · `scale`.
fn thin_polygon(scale: f64, count: usize, width: i64) -> MeshInput {
    let on_line = |i: usize| {
        let x = i as f64 * 0.37 * scale + scale;
        [x, 0.3 * x]
    };
    let mut points = vec![on_line(0)];
    points.extend((1..count).map(|i| {
        let [x, y] = on_line(i);
        [x, nudged(y, -width)]
    }));
    points.push(on_line(count));
    points.extend((1..count).rev().map(|i| {
        let [x, y] = on_line(i);
        [x, nudged(y, width)]
    }));
    let n = points.len() as i32;
    MeshInput {
        segments: (0..n).map(|i| [i + 1, (i + 1) % n + 1]).collect(),
        ..MeshInput::from_points(points)
    }
}

#[test]
fn thin_polygons_keep_their_area_at_every_scale() {
    for scale in [1.0, 1e-300, 1e200] {
        for (count, width) in [(12, 2), (30, 3), (7, 8)] {
            let input = thin_polygon(scale, count, width);
            check(
                &format!("thin polygon ({count} × {width} ulps at scale {scale:e})"),
                &input,
                "pQ",
                &["pq30Q", "pq30DQ", "pq33S100Q", "pqQ"],
            );
        }
    }
}
