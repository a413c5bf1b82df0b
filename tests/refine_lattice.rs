//! Lattice seeding (`refine::lattice`): where a fixed area bound governs, the interior is seeded
//! with an equilateral lattice just under the bound before Delaunay refinement. On domains where
//! it applies (the refinement benchmark's square with a hole; two regions with bounds of their
//! own):
//! - the output is a valid constrained Delaunay mesh of the domain with every segment a chain of
//!   output segments; every triangle within its area bound; every angle ≥ θ (small input angles
//!   excepted as in refine_properties.rs);
//! - new vertices, lattice points included, carry the attributes interpolated linearly (the
//!   input's attributes are an affine function of position: so must every output vertex's be),
//!   boundary marker 0 off the segments, and the region attribute of the region they are in;
//! - the mesh has at most 0.8 times Triangle's triangles (the lattice's triangles are just under
//!   the bound where refinement leaves about 0.6 of it on average): the seeding took place.

mod common;

use common::call::MeshInput;
use common::pslg::{affine_attribute, polygon_area, square_with_hole, Pslg};
use common::pslg_checks::{check_constrained_delaunay, segment_chains, MeshView};
use common::quality::{area_bound, check_angles, check_areas, Exemptions};
use common::{ours, reference, Triangulation};

/// At most this fraction of Triangle's triangle count (measured: about 0.7).
const AT_MOST_OF_TRIANGLES: f64 = 0.8;

fn with_affine_attributes(mut input: MeshInput) -> MeshInput {
    input.attribute_count = 1;
    input.attributes = input.points.iter().map(|&p| affine_attribute(p)).collect();
    input
}

/// Checks `out`, the mesh of `pslg` with `switches` (zero-based: `z`), as the module says;
/// `global`: the `a<x>` bound, `regional`: regional bounds with `A`.
fn check(pslg: &Pslg, switches: &str, out: &Triangulation, global: Option<f64>, regional: bool) {
    let context = format!("{}, \"{switches}\"", pslg.name);
    let fail = |e: String| -> ! { panic!("{context}: {e}") };
    let mesh = MeshView::of(out).unwrap_or_else(|e| fail(e));
    check_constrained_delaunay(&mesh).unwrap_or_else(|e| fail(e));
    let chains = segment_chains(&pslg.input, &mesh, false).unwrap_or_else(|e| fail(e));
    let expected = pslg.area.expect("a domain of known area");
    let found = mesh.area();
    assert!(
        (found - expected).abs() <= 1e-9 * expected,
        "{context}: the triangles' area is {found}, the domain's {expected}"
    );
    let bound = area_bound(&pslg.input, out, global, regional);
    check_areas(&mesh, &bound).unwrap_or_else(|e| fail(e));
    if let Some(theta) = switches.split('q').nth(1).map(|rest| {
        rest.split(|c: char| c.is_ascii_alphabetic())
            .next()
            .unwrap()
    }) {
        let theta = if theta.is_empty() {
            20.0
        } else {
            theta.parse().unwrap()
        };
        check_angles(&mesh, &pslg.input, &chains, theta, Exemptions::ShellRule)
            .unwrap_or_else(|e| fail(e));
    }
    let points = out.points.as_ref().unwrap();
    let attributes = out.point_attributes.as_ref().unwrap();
    for (v, p) in points.iter().enumerate() {
        let expected = affine_attribute(*p);
        assert!(
            (attributes[v] - expected).abs() <= 1e-9 * (1.0 + expected.abs()),
            "{context}: vertex {v} at {p:?} has attribute {}, the affine function {expected}",
            attributes[v]
        );
    }
    // Vertices off every segment have marker 0.
    let on_segment: std::collections::HashSet<usize> = chains.values().flatten().copied().collect();
    let markers = out.point_markers.as_ref().unwrap();
    for v in (pslg.input.points.len()..points.len()).filter(|v| !on_segment.contains(v)) {
        assert_eq!(markers[v], 0, "{context}: new interior vertex {v}'s marker");
    }
}

/// Ours has at most [`AT_MOST_OF_TRIANGLES`] of Triangle's triangles.
fn fewer_than_triangle(pslg: &Pslg, switches: &str, ours: &Triangulation) {
    let Some(triangle) = reference() else { return };
    let theirs = triangle.triangulate(switches, &pslg.input);
    let (o, t) = (ours.counts.triangles, theirs.counts.triangles);
    assert!(
        f64::from(o) <= AT_MOST_OF_TRIANGLES * f64::from(t),
        "{}, \"{switches}\": {o} triangles, Triangle {t}: no lattice seeding?",
        pslg.name
    );
}

#[test]
fn the_square_with_a_hole_is_seeded_under_a_global_bound() {
    let mut pslg = square_with_hole(64);
    pslg.input = with_affine_attributes(pslg.input);
    let bound = 2e-5;
    for switches in [
        "pzq30a0.00002Q",
        "pzq20a0.00002Q",
        "pza0.00002Q",
        "pzDq25a0.00002Q",
    ] {
        let out = ours(switches, &pslg.input).unwrap_or_else(|e| panic!("{switches}: {e}"));
        check(&pslg, switches, &out, Some(bound), false);
        fewer_than_triangle(&pslg, switches, &out);
    }
}

/// The unit square cut by a segment at x = 0.4 into two regions (attributes 1 and 2) with bounds
/// of their own, the right one finer; a few free vertices and a short segment inside.
fn two_regions() -> Pslg {
    let input = MeshInput {
        points: vec![
            [0.0, 0.0],
            [0.4, 0.0],
            [1.0, 0.0],
            [1.0, 1.0],
            [0.4, 1.0],
            [0.0, 1.0],
            [0.7, 0.3],
            [0.75, 0.45],
            [0.2, 0.61],
            [0.83, 0.77],
        ],
        segments: vec![
            [0, 1],
            [1, 2],
            [2, 3],
            [3, 4],
            [4, 5],
            [5, 0],
            [1, 4],
            [6, 7],
        ],
        regions: vec![[0.2, 0.5, 1.0, 2e-4], [0.6, 0.5, 2.0, 5e-5]],
        ..MeshInput::default()
    };
    let polygon = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    Pslg {
        area: Some(polygon_area(&polygon)),
        ..Pslg::new("two regions".into(), with_affine_attributes(input))
    }
}

#[test]
fn regions_are_seeded_each_under_its_own_bound() {
    let pslg = two_regions();
    for (switches, global) in [
        ("pzAq30aQ", None),
        ("pzAaQ", None),
        ("pzAq25aa0.0001Q", Some(1e-4)),
    ] {
        let out = ours(switches, &pslg.input).unwrap_or_else(|e| panic!("{switches}: {e}"));
        check(&pslg, switches, &out, global, true);
        fewer_than_triangle(&pslg, switches, &out);
        // Every triangle carries the attribute of the region its centroid is in.
        let mesh = MeshView::of(&out).unwrap();
        let width = out.counts.triangle_attributes as usize;
        let attributes = out.triangle_attributes.as_ref().unwrap();
        for (t, corners) in mesh.triangles.iter().enumerate() {
            let x = corners.iter().map(|&v| mesh.points[v][0]).sum::<f64>() / 3.0;
            let expected = if x < 0.4 { 1.0 } else { 2.0 };
            assert_eq!(
                attributes[t * width + width - 1],
                expected,
                "\"{switches}\": triangle {t}'s region attribute"
            );
        }
    }
}
