//! Properties of our Delaunay refinement (`q`, `a`, `u`, `D`, `Y`, `YY`, `S`, the cancel flag) on
//! the classic shapes of tests/data/shapes/ (scaled by a power of two into the unit box, so that
//! one absolute area bound suits them all) and on random PSLGs (star-shaped polygons with holes
//! and islands, tests/common/pslg.rs):
//! - every output is a valid mesh of the domain, constrained Delaunay, with every input segment a
//!   chain of output segments, and the domain's area;
//! - `q<θ>` for θ in {20, 25, 28.6, 30, 33}: no angle below θ except in the triangles that small
//!   input angles force; the classic shapes reach 33° without a warning;
//! - `a<x>`, `a` (regional) and both: every triangle within its bound;
//! - `u`: the user's test false on every output triangle, through the global setter, the
//!   reentrant callback with user data, and `Hooks`; two threads with different callbacks at once;
//! - `D`: every edge locally Delaunay (segments included), every circumcentre in the domain;
//! - `Y` / `YY`: no new vertex on boundary segments / on any segment; `S<n>`: at most n new vertices;
//! - the cancel flag, set from another thread, ends refinement early with a valid mesh;
//! - the inputs that hang or crash Triangle (the letter A with `q40`, tiny angles between
//!   segments, `q35`…`q60`) give a result or a clear error within seconds.

mod common;

use std::collections::BTreeMap;
use std::os::raw::{c_int, c_void};
use std::sync::atomic::{AtomicBool, AtomicI32, AtomicUsize, Ordering};
use std::sync::{mpsc, Arc, Barrier};
use std::thread;
use std::time::Duration;

use common::call::MeshInput;
use common::pslg::{self, Pslg};
use common::pslg_checks::{check_constrained_delaunay, segment_chains, MeshView};
use common::quality::{
    area, area_bound, check_angles, check_areas, check_conforming_delaunay, engine,
    new_vertices_on_segments, normalized, ours_reentrant, smallest_angle, unrefined_points,
    Exemptions,
};
use common::{ours, Triangulation};
use triangle_rs::data::Hooks;

/// The minimum angles of the issue: up to and beyond the guaranteed 28.6°.
const ANGLES: [f64; 5] = [20.0, 25.0, 28.6, 30.0, 33.0];
const GUARANTEED_ANGLE: f64 = 28.6;

fn shapes() -> Vec<Pslg> {
    pslg::SHAPES
        .iter()
        .map(|name| normalized(pslg::shape(name)))
        .collect()
}

fn random_polygons() -> Vec<Pslg> {
    (1..=12).map(pslg::polygon_with_holes).collect()
}

fn all_inputs() -> Vec<Pslg> {
    shapes().into_iter().chain(random_polygons()).collect()
}

/// Checks what every refined mesh of `pslg` must be (valid, constrained Delaunay, segments as
/// chains, the domain's area), then runs `more` on it.
fn checked<R>(
    pslg: &Pslg,
    switches: &str,
    out: &Triangulation,
    more: impl FnOnce(&MeshView<'_>, &BTreeMap<usize, Vec<usize>>) -> R,
) -> R {
    let context = format!("{}, \"{switches}\"", pslg.name);
    let fail = |e: String| -> ! { panic!("{context}: {e}") };
    let mesh = MeshView::of(out).unwrap_or_else(|e| fail(e));
    assert!(!mesh.triangles.is_empty(), "{context}: no triangle");
    check_constrained_delaunay(&mesh).unwrap_or_else(|e| fail(e));
    let chains =
        segment_chains(&pslg.input, &mesh, switches.contains('c')).unwrap_or_else(|e| fail(e));
    if let Some(expected) = pslg.expected_area(switches) {
        let found = mesh.area();
        assert!(
            (found - expected).abs() <= 1e-9 * expected.abs(),
            "{context}: the triangles' area is {found}, the domain's {expected}"
        );
    }
    more(&mesh, &chains)
}

/// Ours through the C ABI, and the warnings of the same call through the engine (the C ABI only
/// prints them); both must give the same mesh.
fn refined(pslg: &Pslg, switches: &str) -> (Triangulation, Vec<String>) {
    let context = format!("{}, \"{switches}\"", pslg.name);
    let input = pslg.input_for(switches);
    let out = ours(switches, &input).unwrap_or_else(|e| panic!("{context}: {e}"));
    let (same, warnings) =
        engine(switches, &input, &Hooks::default()).unwrap_or_else(|e| panic!("{context}: {e}"));
    assert!(
        same.points == out.points && same.triangles == out.triangles,
        "{context}: the engine and the C ABI give different meshes"
    );
    (out, warnings)
}

#[test]
fn the_classic_shapes_reach_every_angle_up_to_33_degrees() {
    for pslg in shapes() {
        for theta in ANGLES {
            let switches = format!("pzq{theta}Q");
            let (out, warnings) = refined(&pslg, &switches);
            assert!(
                warnings.is_empty(),
                "{}, \"{switches}\": {warnings:?}",
                pslg.name
            );
            checked(&pslg, &switches, &out, |mesh, chains| {
                check_angles(mesh, &pslg.input, chains, theta, Exemptions::ShellRule)
                    .unwrap_or_else(|e| panic!("{}, \"{switches}\": {e}", pslg.name));
            });
        }
    }
}

#[test]
fn random_polygons_reach_every_angle_up_to_the_guaranteed_one() {
    for pslg in random_polygons() {
        for theta in ANGLES {
            let switches = format!("pzq{theta}Q");
            let (out, warnings) = refined(&pslg, &switches);
            let context = format!("{}, \"{switches}\"", pslg.name);
            checked(&pslg, &switches, &out, |mesh, chains| {
                if theta <= GUARANTEED_ANGLE || warnings.is_empty() {
                    assert!(warnings.is_empty(), "{context}: {warnings:?}");
                    check_angles(mesh, &pslg.input, chains, theta, Exemptions::ShellRule)
                        .unwrap_or_else(|e| panic!("{context}: {e}"));
                } else {
                    // Beyond 28.6° refinement may stop at its budget, and must say so.
                    assert!(
                        warnings
                            .iter()
                            .all(|w| w.contains("guaranteed to terminate")),
                        "{context}: {warnings:?}"
                    );
                }
            });
        }
    }
}

/// Beyond 28.6°, refinement that gives up on the asked angle must still meet the guaranteed
/// 28.6° (asking for more must not give less). Regression: `polygon_with_holes(9)` with `pzq33`
/// once stopped with a smallest angle of 17.6°.
#[test]
fn a_refinement_stopped_beyond_the_guaranteed_angle_keeps_the_guaranteed_angle() {
    for pslg in (1..=40).map(pslg::polygon_with_holes) {
        for theta in [30.0, 33.0, 34.0] {
            let switches = format!("pzq{theta}Q");
            let (out, _) = refined(&pslg, &switches);
            checked(&pslg, &switches, &out, |mesh, chains| {
                check_angles(
                    mesh,
                    &pslg.input,
                    chains,
                    GUARANTEED_ANGLE,
                    Exemptions::ShellRule,
                )
                .unwrap_or_else(|e| panic!("{}, \"{switches}\": {e}", pslg.name));
            });
        }
    }
}

#[test]
fn every_triangle_is_within_its_area_bound() {
    // Unit-box inputs: global bounds, regional bounds, both, and with an angle.
    let cases: &[(&str, Option<f64>, bool)] = &[
        ("pzAa0.01Q", Some(0.01), false),
        ("pzAq30a0.001Q", Some(0.001), false),
        ("pzAaQ", None, true),
        ("pzAaa0.002Q", Some(0.002), true),
    ];
    let mut refined_somewhere = false;
    for pslg in all_inputs() {
        let unrefined = ours("pzQ", &pslg.input).unwrap().counts.triangles;
        for &(switches, global, regional) in cases {
            let (out, warnings) = refined(&pslg, switches);
            let context = format!("{}, \"{switches}\"", pslg.name);
            assert!(warnings.is_empty(), "{context}: {warnings:?}");
            refined_somewhere |= regional && global.is_none() && out.counts.triangles > unrefined;
            checked(&pslg, switches, &out, |mesh, chains| {
                let bound = area_bound(&pslg.input, &out, global, regional);
                check_areas(mesh, &bound).unwrap_or_else(|e| panic!("{context}: {e}"));
                if switches.contains('q') {
                    check_angles(mesh, &pslg.input, chains, 30.0, Exemptions::ShellRule)
                        .unwrap_or_else(|e| panic!("{context}: {e}"));
                }
            });
        }
    }
    assert!(
        refined_somewhere,
        "regional bounds alone (`a`) refined no input: the test would not see them ignored"
    );
    // The classic shapes at their own scale, where the regions' bounds (0.25 to 2) and a global
    // 0.5 compete.
    for name in pslg::SHAPES {
        let pslg = pslg::shape(name);
        for switches in ["pzAaa0.5Q", "pzAq25aa0.5Q"] {
            let (out, warnings) = refined(&pslg, switches);
            let context = format!("{}, \"{switches}\"", pslg.name);
            assert!(warnings.is_empty(), "{context}: {warnings:?}");
            checked(&pslg, switches, &out, |mesh, _| {
                let bound = area_bound(&pslg.input, &out, Some(0.5), true);
                check_areas(mesh, &bound).unwrap_or_else(|e| panic!("{context}: {e}"));
            });
        }
    }
}

/// The triangles of a mesh as the `u` callback sees them: corners and area.
fn triangles_of(out: &Triangulation) -> Vec<([[f64; 2]; 3], f64)> {
    let mesh = MeshView::of(out).expect("a valid mesh");
    mesh.triangles
        .iter()
        .map(|c| {
            let [a, b, d] = c.map(|v| mesh.points[v]);
            ([a, b, d], area(a, b, d))
        })
        .collect()
}

fn centroid_x(corners: &[[f64; 2]; 3]) -> f64 {
    (corners[0][0] + corners[1][0] + corners[2][0]) / 3.0
}

/// Asserts `unsuitable` is false on every triangle of `out`, and true on some triangle of
/// `unrefined` (so the test is not vacuous).
fn assert_suitable(
    context: &str,
    out: &Triangulation,
    unrefined: &Triangulation,
    unsuitable: &dyn Fn(&[[f64; 2]; 3], f64) -> bool,
) {
    for (corners, area) in triangles_of(out) {
        assert!(
            !unsuitable(&corners, area),
            "{context}: triangle {corners:?} (area {area:e}) fails the user's test"
        );
    }
    assert!(
        triangles_of(unrefined)
            .iter()
            .any(|(corners, area)| unsuitable(corners, *area)),
        "{context}: the unrefined mesh passes the user's test already"
    );
}

/// The global callback's test: big triangles right of x = 0.
const GLOBAL_MAX_AREA: f64 = 0.002;

extern "C" fn too_big_right_of_zero(
    ox: f64,
    _oy: f64,
    dx: f64,
    _dy: f64,
    ax: f64,
    _ay: f64,
    area: f64,
) -> c_int {
    c_int::from(area > GLOBAL_MAX_AREA && (ox + dx + ax) / 3.0 > 0.0)
}

/// Clears the global callback when dropped, even when an assertion fails.
struct GlobalCallback;

impl GlobalCallback {
    fn set(f: triangle_rs::ffi::TriunsuitableFn) -> GlobalCallback {
        triangle_rs::ffi::triunsuitable_callback(Some(f));
        GlobalCallback
    }
}

impl Drop for GlobalCallback {
    fn drop(&mut self) {
        triangle_rs::ffi::triunsuitable_callback(None);
    }
}

/// The only test of this file that sets the process-wide callback.
#[test]
fn the_user_test_through_the_global_setter() {
    let _callback = GlobalCallback::set(too_big_right_of_zero);
    let unsuitable = |c: &[[f64; 2]; 3], area: f64| area > GLOBAL_MAX_AREA && centroid_x(c) > 0.0;
    for pslg in random_polygons() {
        let unrefined = ours("pzQ", &pslg.input).unwrap();
        for switches in ["pzuQ", "pzq25uQ"] {
            let context = format!("{}, \"{switches}\"", pslg.name);
            let out = ours(switches, &pslg.input).unwrap_or_else(|e| panic!("{context}: {e}"));
            checked(&pslg, switches, &out, |mesh, chains| {
                if switches.contains('q') {
                    check_angles(mesh, &pslg.input, chains, 25.0, Exemptions::ShellRule)
                        .unwrap_or_else(|e| panic!("{context}: {e}"));
                }
            });
            assert_suitable(&context, &out, &unrefined, &unsuitable);
            // Only the right half was refined: big triangles remain on the left.
            assert!(
                triangles_of(&out)
                    .iter()
                    .any(|(c, area)| *area > GLOBAL_MAX_AREA && centroid_x(c) < 0.0),
                "{context}: the left half was refined too"
            );
        }
    }
}

/// The reentrant callback's user data: its own test, and who called it.
struct Limit {
    max_area: f64,
    /// Only triangles whose centroid lies left of this are tested.
    left_of: f64,
    owner: thread::ThreadId,
    calls: AtomicUsize,
    foreign_calls: AtomicUsize,
}

impl Limit {
    fn new(max_area: f64, left_of: f64) -> Limit {
        Limit {
            max_area,
            left_of,
            owner: thread::current().id(),
            calls: AtomicUsize::new(0),
            foreign_calls: AtomicUsize::new(0),
        }
    }

    fn unsuitable(&self, corners: &[[f64; 2]; 3], area: f64) -> bool {
        area > self.max_area && centroid_x(corners) < self.left_of
    }

    fn as_user_data(&self) -> *mut c_void {
        self as *const Limit as *mut c_void
    }
}

extern "C" fn limit_callback(
    ox: f64,
    oy: f64,
    dx: f64,
    dy: f64,
    ax: f64,
    ay: f64,
    area: f64,
    user_data: *mut c_void,
) -> c_int {
    // SAFETY: every call passes a `Limit` that outlives it as `user_data`.
    let limit = unsafe { &*(user_data as *const Limit) };
    limit.calls.fetch_add(1, Ordering::Relaxed);
    if thread::current().id() != limit.owner {
        limit.foreign_calls.fetch_add(1, Ordering::Relaxed);
    }
    c_int::from(limit.unsuitable(&[[ox, oy], [dx, dy], [ax, ay]], area))
}

#[test]
fn the_user_test_through_the_reentrant_callback_with_user_data() {
    for pslg in random_polygons() {
        let unrefined = ours("pzQ", &pslg.input).unwrap();
        for (switches, max_area, left_of) in [("pzuQ", 0.001, 0.2), ("pzq28.6uQ", 0.003, -0.1)] {
            let context = format!("{}, \"{switches}\"", pslg.name);
            let limit = Limit::new(max_area, left_of);
            let out = ours_reentrant(
                switches,
                &pslg.input,
                Some(limit_callback),
                limit.as_user_data(),
                std::ptr::null(),
            )
            .unwrap_or_else(|e| panic!("{context}: {e}"));
            checked(&pslg, switches, &out, |mesh, chains| {
                if switches.contains('q') {
                    check_angles(mesh, &pslg.input, chains, 28.6, Exemptions::ShellRule)
                        .unwrap_or_else(|e| panic!("{context}: {e}"));
                }
            });
            assert_suitable(&context, &out, &unrefined, &|c, a| limit.unsuitable(c, a));
            assert!(
                limit.calls.load(Ordering::Relaxed) > 0,
                "{context}: never called"
            );
            assert_eq!(limit.foreign_calls.load(Ordering::Relaxed), 0, "{context}");
        }
    }
}

#[test]
fn the_user_test_through_hooks() {
    let centre = [0.1, -0.05];
    let near_centre = |c: &[[f64; 2]; 3]| {
        let (x, y) = (
            (c[0][0] + c[1][0] + c[2][0]) / 3.0,
            (c[0][1] + c[1][1] + c[2][1]) / 3.0,
        );
        (x - centre[0]).hypot(y - centre[1]) < 0.5
    };
    let unsuitable = |c: &[[f64; 2]; 3], area: f64| area > 0.0005 && near_centre(c);
    let test = |ox: f64, oy: f64, dx: f64, dy: f64, ax: f64, ay: f64, area: f64| {
        unsuitable(&[[ox, oy], [dx, dy], [ax, ay]], area)
    };
    let hooks = Hooks {
        unsuitable: Some(&test),
        ..Hooks::default()
    };
    for pslg in random_polygons() {
        let unrefined = ours("pzQ", &pslg.input).unwrap();
        for switches in ["pzuQ", "pzq20uQ"] {
            let context = format!("{}, \"{switches}\"", pslg.name);
            let (out, warnings) =
                engine(switches, &pslg.input, &hooks).unwrap_or_else(|e| panic!("{context}: {e}"));
            assert!(warnings.is_empty(), "{context}: {warnings:?}");
            checked(&pslg, switches, &out, |_, _| {});
            assert_suitable(&context, &out, &unrefined, &unsuitable);
        }
    }
}

/// Two threads refine at the same time with different reentrant callbacks: each mesh passes its
/// own test and not the other's, and each callback runs only on its own thread.
#[test]
fn two_threads_refine_at_once_with_different_callbacks() {
    let pslg = Arc::new(pslg::polygon_with_holes(3));
    let unrefined = Arc::new(ours("pzQ", &pslg.input).unwrap());
    let start = Arc::new(Barrier::new(2));
    // Left of 10 is everywhere: the first refines the whole polygon coarsely, the second its
    // left part finely.
    let tests = [(0.0002, 10.0), (0.00005, 0.0)];
    let handles: Vec<_> = tests
        .iter()
        .map(|&(max_area, left_of)| {
            let (pslg, unrefined, start) = (pslg.clone(), unrefined.clone(), start.clone());
            thread::spawn(move || {
                let limit = Limit::new(max_area, left_of);
                start.wait();
                let out = ours_reentrant(
                    "pzuQ",
                    &pslg.input,
                    Some(limit_callback),
                    limit.as_user_data(),
                    std::ptr::null(),
                )
                .unwrap_or_else(|e| panic!("thread with area {max_area}: {e}"));
                let context = format!("{}, thread with area {max_area}", pslg.name);
                checked(&pslg, "pzuQ", &out, |_, _| {});
                assert_suitable(&context, &out, &unrefined, &|c, a| limit.unsuitable(c, a));
                assert_eq!(limit.foreign_calls.load(Ordering::Relaxed), 0, "{context}");
                out
            })
        })
        .collect();
    let outs: Vec<Triangulation> = handles.into_iter().map(|h| h.join().unwrap()).collect();
    // Neither callback leaked into the other call: each mesh fails the other's test somewhere.
    let other = |i: usize| Limit::new(tests[1 - i].0, tests[1 - i].1);
    for (i, out) in outs.iter().enumerate() {
        let limit = other(i);
        assert!(
            triangles_of(out)
                .iter()
                .any(|(c, a)| limit.unsuitable(c, *a)),
            "the mesh of thread {i} passes the other thread's test too"
        );
    }
}

#[test]
fn conforming_delaunay_is_truly_delaunay_with_circumcentres_inside() {
    for pslg in all_inputs() {
        for switches in ["pzDQ", "pzq25DQ", "pzDa0.005Q"] {
            let (out, warnings) = refined(&pslg, switches);
            let context = format!("{}, \"{switches}\"", pslg.name);
            assert!(warnings.is_empty(), "{context}: {warnings:?}");
            checked(&pslg, switches, &out, |mesh, chains| {
                check_conforming_delaunay(mesh).unwrap_or_else(|e| panic!("{context}: {e}"));
                if switches.contains('q') {
                    check_angles(mesh, &pslg.input, chains, 25.0, Exemptions::ShellRule)
                        .unwrap_or_else(|e| panic!("{context}: {e}"));
                }
                if switches.contains('a') {
                    check_areas(mesh, &|_| Some(0.005))
                        .unwrap_or_else(|e| panic!("{context}: {e}"));
                }
            });
        }
    }
}

#[test]
fn no_new_vertex_on_boundary_segments_with_y_nor_on_any_segment_with_yy() {
    let mut on_interior_segments = 0;
    for pslg in all_inputs() {
        let allowed = unrefined_points(&pslg);
        let unrefined_segments = ours("pzQ", &pslg.input).unwrap().counts.segments;
        for switches in ["pzqYQ", "pza0.002YQ", "pzqYYQ", "pza0.002YYQ"] {
            let both = switches.contains("YY");
            let (out, _) = refined(&pslg, switches);
            let context = format!("{}, \"{switches}\"", pslg.name);
            checked(&pslg, switches, &out, |mesh, chains| {
                let forbidden = new_vertices_on_segments(mesh, chains, &allowed, !both);
                assert!(
                    forbidden.is_empty(),
                    "{context}: new vertices (input segment, place) {forbidden:?}"
                );
                if !both {
                    on_interior_segments +=
                        new_vertices_on_segments(mesh, chains, &allowed, false).len();
                }
            });
            if both {
                assert_eq!(
                    out.counts.segments, unrefined_segments,
                    "{context}: segments were split"
                );
            }
        }
    }
    assert!(
        on_interior_segments > 0,
        "`Y` put no vertex on interior segments: it may split them"
    );
}

#[test]
fn the_steiner_budget_caps_new_vertices() {
    for pslg in all_inputs() {
        let before = unrefined_points(&pslg).len();
        for budget in [0, 1, 5, 50] {
            let switches = format!("pzq30a0.001S{budget}Q");
            let (out, _) = refined(&pslg, &switches);
            checked(&pslg, &switches, &out, |_, _| {});
            let added = out.counts.points as usize - before;
            // These bounds need hundreds of new vertices: the budget is used up. It counts the
            // vertices inserted, as Triangle's does: those that Chew's rule deletes again (free
            // vertices in the diametral circle of a subsegment being split) do not give it back
            // (Triangle's `qS6` on diamond_02_00009.node leaves 5 of its 6).
            assert!(
                added <= budget && 4 * added >= 3 * budget,
                "{}, \"{switches}\": {added} new vertices",
                pslg.name
            );
        }
    }
}

/// A mesh refined in a translated frame (coordinates a local origin makes finer than the
/// caller's) is moved onto the caller's grid and made constrained Delaunay again there by
/// flips. Regression: the flips were started from the moved vertices' own edges only, and an
/// edge of a moved vertex's link, between two vertices that stayed, was left with the moved
/// vertex just inside its circle (exact `incircle` 6·10^-19) where nothing refined after the
/// move (an `S` budget spent, or no triangle left bad). Random equilateral triangles.
#[test]
fn a_mesh_moved_onto_the_callers_grid_is_constrained_delaunay() {
    let triangle = |name: &str, points: [[f64; 2]; 3]| {
        Pslg::new(
            name.into(),
            MeshInput {
                segments: vec![[0, 1], [1, 2], [2, 0]],
                ..MeshInput::from_points(points.to_vec())
            },
        )
    };
    let cases = [
        (
            triangle(
                "equilateral triangle 253",
                [
                    [-2.109987920179091, 1.045952067118226],
                    [-1.9918116177625265, 0.28727290672211053],
                    [-1.3938643427459236, 0.7689561669382253],
                ],
            ),
            ["pza0.02S14Q", "pza0.02S100000Q"].as_slice(),
        ),
        (
            triangle(
                "equilateral triangle 118",
                [
                    [-0.7188711251376675, -1.6054828902532614],
                    [-0.09020338209043316, -1.953042123927352],
                    [-0.10354212793243558, -1.2348202710715739],
                ],
            ),
            ["pza0.005Q"].as_slice(),
        ),
        (
            triangle(
                "equilateral triangle 281",
                [
                    [3.3123959673810672, -1.686967787813352],
                    [1.8745801853647688, -0.9837547730367702],
                    [1.9844877413045556, -2.580546273613364],
                ],
            ),
            ["pza0.02S100000Q"].as_slice(),
        ),
    ];
    for (pslg, all_switches) in &cases {
        for &switches in *all_switches {
            let (out, _) = refined(pslg, switches);
            checked(pslg, switches, &out, |_, _| {});
        }
    }
}

/// A refinement that never ends on its own (10^10 triangles), for the cancel tests.
const ENDLESS: &str = "pza1e-10Q";

/// Runs `work` on its own thread and waits at most `seconds` for it; `None` on time-out (the
/// thread is left running; the test then fails).
fn within<T: Send + 'static>(seconds: u64, work: impl FnOnce() -> T + Send + 'static) -> Option<T> {
    let (send, receive) = mpsc::channel();
    thread::spawn(move || {
        let _ = send.send(work());
    });
    receive.recv_timeout(Duration::from_secs(seconds)).ok()
}

/// The cancel flag of the C ABI, set from another thread once refinement is under way (its
/// callback has run), ends the call with a valid mesh.
#[test]
fn the_cancel_flag_set_from_another_thread_stops_refinement() {
    let pslg = pslg::polygon_with_holes(5);
    let cancel = Arc::new(AtomicI32::new(0));
    let started = Arc::new(AtomicBool::new(false));
    extern "C" fn note_start(
        _: f64,
        _: f64,
        _: f64,
        _: f64,
        _: f64,
        _: f64,
        _: f64,
        user_data: *mut c_void,
    ) -> c_int {
        // SAFETY: `user_data` is the `AtomicBool` kept alive by the test during the call.
        unsafe { &*(user_data as *const AtomicBool) }.store(true, Ordering::Relaxed);
        0
    }
    let canceller = {
        let (cancel, started) = (cancel.clone(), started.clone());
        thread::spawn(move || {
            while !started.load(Ordering::Relaxed) {
                thread::yield_now();
            }
            thread::sleep(Duration::from_millis(20));
            cancel.store(1, Ordering::Relaxed);
        })
    };
    let input = pslg.input.clone();
    let switches = format!("{ENDLESS}u");
    let out = within(20, move || {
        ours_reentrant(
            &switches,
            &input,
            Some(note_start),
            Arc::as_ptr(&started) as *mut c_void,
            cancel.as_ptr(),
        )
    })
    .expect("cancelled refinement returns within 20 s")
    .expect("a cancelled refinement succeeds");
    canceller.join().unwrap();
    checked(&pslg, ENDLESS, &out, |mesh, _| {
        assert!(
            check_areas(mesh, &|_| Some(1e-10)).is_err(),
            "the area bound was met: the refinement was not cancelled"
        );
    });
}

/// The same through `Hooks::cancel`, which also warns.
#[test]
fn the_cancel_hook_set_from_another_thread_stops_refinement() {
    let pslg = pslg::shape("letter_a");
    let cancelled = Arc::new(AtomicBool::new(false));
    let canceller = {
        let cancelled = cancelled.clone();
        thread::spawn(move || {
            thread::sleep(Duration::from_millis(50));
            cancelled.store(true, Ordering::Relaxed);
        })
    };
    let input = pslg.input.clone();
    let flag = cancelled.clone();
    let (out, warnings) = within(20, move || {
        let is_cancelled = move || flag.load(Ordering::Relaxed);
        let hooks = Hooks {
            cancel: Some(&is_cancelled),
            ..Hooks::default()
        };
        engine(ENDLESS, &input, &hooks)
    })
    .expect("cancelled refinement returns within 20 s")
    .expect("a cancelled refinement succeeds");
    canceller.join().unwrap();
    assert!(
        warnings.iter().any(|w| w.contains("cancelled")),
        "{warnings:?}"
    );
    checked(&pslg, ENDLESS, &out, |_, _| {});
}

/// Two segments from one vertex at `degrees`, inside the unit square.
fn vee(degrees: f64) -> MeshInput {
    fan(1, degrees)
}

/// `count` + 1 segments from (0.1, 0.5) spread over `degrees`, inside the unit square.
fn fan(count: usize, degrees: f64) -> MeshInput {
    let mut input = square();
    input.points.push([0.1, 0.5]);
    for k in 0..=count {
        let angle = (degrees * k as f64 / count as f64).to_radians();
        input
            .points
            .push([0.1 + 0.8 * angle.cos(), 0.5 + 0.8 * angle.sin()]);
        input.segments.push([4, input.points.len() as i32 - 1]);
    }
    input
}

/// Two segments crossing at `degrees` in the middle of the unit square.
fn crossing(degrees: f64) -> MeshInput {
    let t = 0.4 * (degrees.to_radians() / 2.0).tan();
    let mut input = square();
    input.points.extend([
        [0.1, 0.5 - t],
        [0.9, 0.5 + t],
        [0.1, 0.5 + t],
        [0.9, 0.5 - t],
    ]);
    input.segments.extend([[4, 5], [6, 7]]);
    input
}

fn square() -> MeshInput {
    MeshInput {
        points: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        segments: vec![[0, 1], [1, 2], [2, 3], [3, 0]],
        ..MeshInput::default()
    }
}

/// Each case (name, input zero-based, switches with `z`) returns within `seconds` with a valid
/// mesh or an error message; the results, in order.
fn all_return_within(
    seconds: u64,
    cases: Vec<(String, MeshInput, String)>,
) -> Vec<Result<Triangulation, String>> {
    let names: Vec<String> = cases
        .iter()
        .map(|(n, _, s)| format!("{n}, \"{s}\""))
        .collect();
    let results = within(seconds, move || {
        cases
            .into_iter()
            .map(|(_, input, switches)| ours(&switches, &input))
            .collect::<Vec<_>>()
    })
    .unwrap_or_else(|| panic!("these did not all return within {seconds} s: {names:?}"));
    for (name, result) in names.iter().zip(&results) {
        match result {
            Ok(out) => {
                MeshView::of(out).unwrap_or_else(|e| panic!("{name}: {e}"));
            }
            Err(message) => assert!(!message.trim().is_empty(), "{name}: an empty error"),
        }
    }
    results
}

/// Triangle never returns on the letter A with `q40`, loops or crashes on tiny angles between
/// segments, and may loop from `q35` on: ours returns a valid mesh (with a warning when it
/// stops early) within seconds.
#[test]
fn inputs_that_hang_or_crash_triangle_return_within_seconds() {
    let mut cases = Vec::new();
    let letter_a = pslg::shape("letter_a").input;
    cases.push(("letter A".to_string(), letter_a, "pzq40Q".to_string()));
    for (name, input) in [
        ("two segments at 0.5°".to_string(), vee(0.5)),
        ("a fan of 10 segments within 5°".to_string(), fan(9, 5.0)),
    ] {
        for switches in ["pzqQ", "pzq28.6Q", "pzq33Q"] {
            cases.push((name.clone(), input.clone(), switches.to_string()));
        }
    }
    for pslg in shapes() {
        for theta in [35, 40, 45, 50, 55, 60] {
            cases.push((
                pslg.name.clone(),
                pslg.input.clone(),
                format!("pzq{theta}Q"),
            ));
        }
    }
    let results = all_return_within(20, cases);
    assert!(
        results.iter().all(Result::is_ok),
        "no error is expected: a result with a warning instead"
    );
}

/// Segments that cross at a small angle (below θ) are protected like segments meeting at an
/// input vertex: the crossing is a corner for the concentric shells and the skinny triangles
/// between shells are left alone. The unit square with segments (0.1, 0.5 ∓ t)–(0.9, 0.5 ± t),
/// t = 0.4·tan(α/2), crossing at α at (0.5, 0.5). Regression: at 5° and `pzq20` this once ran
/// into the floating-point resolution around the crossing with about 1300 vertices (Triangle:
/// 37).
#[test]
fn segments_crossing_at_a_small_angle_are_protected() {
    for degrees in [25.0, 5.0, 2.0, 1.0, 0.5] {
        let input = crossing(degrees);
        let pslg = Pslg::new(format!("segments crossing at {degrees}°"), input);
        for theta in [20.0, 28.6] {
            let switches = format!("pzq{theta}Q");
            let (out, warnings) = refined(&pslg, &switches);
            let context = format!("{}, \"{switches}\"", pslg.name);
            assert!(warnings.is_empty(), "{context}: {warnings:?}");
            // Triangle: 58 to 264 triangles on these.
            assert!(
                out.counts.triangles <= 600,
                "{context}: {} triangles",
                out.counts.triangles
            );
            checked(&pslg, &switches, &out, |mesh, _| {
                // With `c` the hull's edges are segments, whose angles count as the input's.
                let hulled = pslg::with_hull_segments(&pslg.input);
                let chains = segment_chains(&hulled, mesh, true)
                    .unwrap_or_else(|e| panic!("{context}: {e}"));
                check_angles(mesh, &hulled, &chains, theta, Exemptions::ShellRule)
                    .unwrap_or_else(|e| panic!("{context}: {e}"));
            });
        }
    }
}

/// Small angles between segments at an input vertex: only the triangles they force have smaller
/// angles, and refinement stays small (Triangle: 28 to 122 triangles on these).
#[test]
fn small_angles_between_segments_at_a_vertex_are_protected() {
    for (name, input) in [
        ("two segments at 5°", vee(5.0)),
        ("two segments at 0.5°", vee(0.5)),
        ("a fan of 10 segments within 5°", fan(9, 5.0)),
        (
            "a wedge of 25°",
            MeshInput {
                points: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 25f64.to_radians().tan()]],
                segments: vec![[0, 1], [1, 2], [2, 0]],
                ..MeshInput::default()
            },
        ),
    ] {
        let pslg = Pslg::new(name.to_string(), input);
        for theta in [20.0, 28.6] {
            let switches = format!("pzq{theta}Q");
            let (out, warnings) = refined(&pslg, &switches);
            let context = format!("{name}, \"{switches}\"");
            assert!(warnings.is_empty(), "{context}: {warnings:?}");
            assert!(
                out.counts.triangles <= 600,
                "{context}: {} triangles",
                out.counts.triangles
            );
            checked(&pslg, &switches, &out, |mesh, chains| {
                let report = check_angles(mesh, &pslg.input, chains, theta, Exemptions::ShellRule)
                    .unwrap_or_else(|e| panic!("{context}: {e}"));
                assert!(
                    report.excused > 0 || smallest_angle(mesh) >= theta,
                    "{context}"
                );
            });
        }
    }
}

/// An input vertex lying exactly on a segment that another segment crosses: vertices
/// (1.5, 1.5), (2, 0.5), (2.5, 1.5), (0.5, 0.5), (1, 0.75) (on the second segment), segments 0–1
/// and 2–3. Regression: with `pczq20` this once looped forever, and with `pcza0.01` or `pczD` it
/// gave a triangle that is not counter-clockwise (a segment split rounded past the vertex).
#[test]
fn a_vertex_on_a_crossed_segment_gives_a_valid_mesh() {
    let input = MeshInput {
        points: vec![[1.5, 1.5], [2.0, 0.5], [2.5, 1.5], [0.5, 0.5], [1.0, 0.75]],
        segments: vec![[0, 1], [2, 3]],
        ..MeshInput::default()
    };
    let pslg = Pslg {
        convex: true,
        ..Pslg::new("a vertex on a crossed segment".into(), input)
    };
    for switches in ["pczq20Q", "pcza0.01Q", "pczDQ"] {
        let (out, _) = refined(&pslg, switches);
        checked(&pslg, switches, &out, |_, _| {});
    }
}

/// Random PSLGs with crossing segments and vertices on segments (with `c`): valid, refined
/// meshes without warnings (regressions: lattice seed 2 gave an invalid mesh; crossing seeds 4
/// and 5 a runaway refinement).
#[test]
fn random_crossings_and_vertices_on_segments_refine_correctly() {
    let inputs: Vec<Pslg> = (1..=5)
        .map(|seed| pslg::crossing_segments(seed, 12, 8))
        .chain((1..=10).map(|seed| pslg::vertices_on_segments(seed, 6, 8)))
        .collect();
    for pslg in inputs {
        for theta in [20.0, 28.6] {
            let switches = format!("pczq{theta}Q");
            let (out, warnings) = refined(&pslg, &switches);
            let context = format!("{}, \"{switches}\"", pslg.name);
            assert!(
                warnings.iter().all(|w| w.contains("coincident")),
                "{context}: {warnings:?}"
            );
            checked(&pslg, &switches, &out, |mesh, _| {
                // With `c` the hull's edges are segments, whose angles count as the input's.
                let hulled = pslg::with_hull_segments(&pslg.input);
                let chains = segment_chains(&hulled, mesh, true)
                    .unwrap_or_else(|e| panic!("{context}: {e}"));
                check_angles(mesh, &hulled, &chains, theta, Exemptions::ShellRule)
                    .unwrap_or_else(|e| panic!("{context}: {e}"));
            });
        }
    }
}

/// A domain a hair's breadth wide (points within 1e-9 of a line, `c`) needs about a billion
/// triangles for any minimum angle: refinement stops at its runaway limit with a warning and a
/// valid mesh, within seconds, instead of filling the memory.
#[test]
fn a_domain_too_thin_for_the_angle_stops_with_a_warning() {
    let points: Vec<[f64; 2]> = (0..12)
        .map(|i| {
            let x = (i * 37 % 12) as f64 / 11.0;
            [x, 0.5 * x + 1e-9 * ((i * 5 % 7) as f64 / 7.0)]
        })
        .collect();
    let input = MeshInput::from_points(points);
    let pslg = Pslg {
        convex: true,
        ..Pslg::new("nearly collinear points".into(), input)
    };
    let (out, warnings) = refined(&pslg, "pczqQ");
    assert!(
        warnings
            .iter()
            .any(|w| w.contains("far more than this input")),
        "{warnings:?}"
    );
    MeshView::of(&out).unwrap_or_else(|e| panic!("{e}"));
}

/// A vertex within rounding of a segment without lying on it in exact arithmetic (the lattice
/// point (0.4, 0.4) and the segment (0.8, 0)–(0.2, 0.6), in doubles) is on it for refinement:
/// left apart, the two would encroach on each other without end (Triangle stops with "Ran out
/// of precision"; we used to fill the sliver between them up to the runaway limit, or leave a 0°
/// triangle there). Here the vertex also ends a segment from the same corner, at an angle of
/// 10^-16 radians to the other; and a lattice where such segments cross a third one (see
/// `pslg::lattice_with_overlaps`).
#[test]
fn a_vertex_within_rounding_of_a_segment_is_on_it() {
    let lattice = |points: &[[i32; 2]]| {
        points
            .iter()
            .map(|p| [p[0] as f64 / 5.0, p[1] as f64 / 5.0])
            .collect::<Vec<_>>()
    };
    let cases = [
        // Only the segment and the vertex: no segment ends at the vertex.
        (
            lattice(&[[4, 0], [1, 3], [2, 2], [0, 0], [5, 5]]),
            vec![[0, 1]],
        ),
        // The vertex ends a second segment from the same corner, nearly along the first.
        (
            lattice(&[
                [4, 0],
                [1, 3],
                [5, 2],
                [0, 3],
                [3, 2],
                [0, 0],
                [2, 0],
                [4, 2],
                [2, 2],
                [4, 5],
                [0, 5],
                [1, 0],
                [0, 1],
                [0, 4],
            ]),
            vec![[2, 12], [1, 8], [11, 13], [1, 7], [0, 1]],
        ),
    ];
    let pslgs = cases
        .into_iter()
        .map(|(points, segments)| {
            let input = MeshInput {
                segments,
                ..MeshInput::from_points(points)
            };
            Pslg {
                convex: true,
                ..Pslg::new("lattice with a vertex by a segment".into(), input)
            }
        })
        .chain([pslg::lattice_with_overlaps()]);
    for pslg in pslgs {
        let switches = "pczqQ";
        let (out, warnings) = refined(&pslg, switches);
        assert!(
            warnings
                .iter()
                .all(|w| w.contains("duplicate") || w.contains("coincident")),
            "{warnings:?}"
        );
        checked(&pslg, switches, &out, |mesh, _| {
            assert!(
                mesh.triangles.len() < 300,
                "{} triangles",
                mesh.triangles.len()
            );
            let hulled = pslg::with_hull_segments(&pslg.input);
            let chains = segment_chains(&hulled, mesh, true).unwrap_or_else(|e| panic!("{e}"));
            check_angles(mesh, &hulled, &chains, 20.0, Exemptions::ShellRule)
                .unwrap_or_else(|e| panic!("{e}"));
        });
    }
}

/// `D` on point sets with decimal coordinates (multiples of 1/10, 1/5, 1/20, 1/3, which doubles
/// round): many vertices lie on or a rounding off the diametral circles of hull edges, where
/// only an exact decision keeps every Voronoi vertex inside (`check_conforming_delaunay`, exact).
#[test]
fn conforming_delaunay_on_rounded_decimal_point_sets_is_exact() {
    let mut rng = common::rng::SplitMix64::new(37);
    for case in 0..400 {
        let denominator = [10.0, 5.0, 20.0, 3.0][case % 4];
        let steps = denominator as usize;
        let mut points: Vec<[f64; 2]> = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        for _ in 0..(3 + rng.below(12)) {
            let (i, j) = (rng.below(steps + 1), rng.below(steps + 1));
            let p = [i as f64 / denominator, j as f64 / denominator];
            if !points.contains(&p) {
                points.push(p);
            }
        }
        let input = MeshInput::from_points(points);
        for switches in ["DzQ", "cDzQ", "q25DzQ"] {
            let context = format!("case {case}, \"{switches}\", points {:?}", input.points);
            let (out, warnings) = engine(switches, &input, &Hooks::default())
                .unwrap_or_else(|e| panic!("{context}: {e}"));
            assert!(warnings.is_empty(), "{context}: {warnings:?}");
            let mesh = MeshView::of(&out).unwrap_or_else(|e| panic!("{context}: {e}"));
            check_conforming_delaunay(&mesh).unwrap_or_else(|e| panic!("{context}: {e}"));
        }
    }
}

/// An `S` budget that stops refinement short of the bounds says so (one warning naming the
/// budget); one that stops nothing says nothing.
#[test]
fn an_s_budget_that_leaves_bad_triangles_warns_and_one_that_does_not_is_silent() {
    let input = pslg::shape("letter_a").input;
    let (_, warnings) = engine("pzq25S1Q", &input, &Hooks::default()).unwrap();
    assert!(
        warnings.len() == 1 && warnings[0].contains("S budget of 1 Steiner points"),
        "{warnings:?}"
    );
    let (_, warnings) = engine("pzq25S1000000Q", &input, &Hooks::default()).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
}
