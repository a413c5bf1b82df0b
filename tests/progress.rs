//! Progress reports through the C ABI (`triangulate_progress`): every phase that runs reports its
//! start and end in order, refinement reports while it runs (where the cancel flag is polled),
//! the work done never goes back within a phase and ends equal to the estimate; and a cancel flag
//! set from the progress callback stops the refinement with a valid mesh.

mod common;

use std::os::raw::{c_int, c_void};
use std::sync::atomic::{AtomicI32, Ordering};

use common::pslg_checks::MeshView;
use common::{MeshInput, Triangulation};
use triangle_rs::io::triangulateio::TriangulateIO;

struct Seen {
    reports: Vec<(c_int, i64, i64)>,
    /// Set the cancel flag once refinement has reported this much work done.
    cancel_after: Option<i64>,
    cancel: AtomicI32,
}

unsafe extern "C" fn record(phase: c_int, done: i64, estimate: i64, user_data: *mut c_void) {
    // SAFETY: `user_data` is the `Seen` that `run` passes, alive and used by this thread only.
    let seen = unsafe { &mut *(user_data as *mut Seen) };
    seen.reports.push((phase, done, estimate));
    if phase == 2 && seen.cancel_after.is_some_and(|after| done >= after) {
        seen.cancel.store(1, Ordering::Relaxed);
    }
}

fn square(n_holes: usize) -> MeshInput {
    let mut points = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let mut segments = vec![[0, 1], [1, 2], [2, 3], [3, 0]];
    for h in 0..n_holes {
        let x = 0.2 + 0.3 * h as f64;
        let first = points.len() as i32;
        points.extend([[x, 0.4], [x + 0.1, 0.4], [x + 0.1, 0.5], [x, 0.5]]);
        segments.extend((0..4).map(|k| [first + k, first + (k + 1) % 4]));
    }
    MeshInput {
        points,
        segments,
        ..MeshInput::default()
    }
}

/// Runs `switches` on `input` through `triangulate_progress`; returns the result and the reports.
fn run(switches: &str, input: &MeshInput, cancel_after: Option<i64>) -> (Triangulation, Seen) {
    let mut seen = Seen {
        reports: Vec::new(),
        cancel_after,
        cancel: AtomicI32::new(0),
    };
    let seen_ptr = &mut seen as *mut Seen as *mut c_void;
    let cancel_ptr = seen.cancel.as_ptr() as *const c_int;
    let call = |s: *mut std::os::raw::c_char,
                i: *mut TriangulateIO,
                o: *mut TriangulateIO,
                v: *mut TriangulateIO| {
        // SAFETY: valid structs from `run_call`; `seen` outlives the call; the callback matches.
        common::call::ours_status(unsafe {
            triangle_rs::ffi::triangulate_progress(
                s,
                i,
                o,
                v,
                None,
                seen_ptr,
                cancel_ptr,
                Some(record),
            )
        })
    };
    // SAFETY: arrays returned by our `triangulate` are freed with our `trifree`.
    let free = |p: *mut c_void| unsafe { triangle_rs::ffi::trifree(p) };
    let out = common::call::run_call(&call, &free, switches, input, false)
        .unwrap_or_else(|e| panic!("\"{switches}\": {e}"));
    (out, seen)
}

/// The phases reported, in order, each with its reports: starts and ends present, done
/// non-decreasing, the last report's done equal to its estimate.
fn check_reports(switches: &str, reports: &[(c_int, i64, i64)]) -> Vec<(c_int, usize)> {
    let mut phases: Vec<(c_int, usize)> = Vec::new();
    for &(phase, _, _) in reports {
        match phases.last_mut() {
            Some((p, count)) if *p == phase => *count += 1,
            _ => phases.push((phase, 1)),
        }
    }
    let order: Vec<c_int> = phases.iter().map(|&(p, _)| p).collect();
    assert!(
        order.windows(2).all(|w| w[0] < w[1]),
        "\"{switches}\": phases out of order: {order:?}"
    );
    let mut at = 0;
    for &(phase, count) in &phases {
        let slice = &reports[at..at + count];
        at += count;
        assert!(
            count >= 2,
            "\"{switches}\": phase {phase} has no start and end: {slice:?}"
        );
        assert_eq!(
            slice[0].1, 0,
            "\"{switches}\": phase {phase} starts at {:?}",
            slice[0]
        );
        assert!(
            slice.windows(2).all(|w| w[0].1 <= w[1].1),
            "\"{switches}\": phase {phase} goes back: {slice:?}"
        );
        let last = slice[count - 1];
        assert_eq!(
            last.1, last.2,
            "\"{switches}\": phase {phase} ends at {last:?}"
        );
    }
    phases
}

#[test]
fn every_phase_reports_its_start_and_end_and_refinement_reports_while_it_runs() {
    let input = square(2);
    let (out, seen) = run("pzq30a0.00005Q", &input, None);
    MeshView::of(&out).unwrap();
    let phases = check_reports("pzq30a0.00005Q", &seen.reports);
    let order: Vec<c_int> = phases.iter().map(|&(p, _)| p).collect();
    assert_eq!(order, [0, 1, 2, 3], "{:?}", seen.reports);
    let refinement = phases[2].1;
    assert!(refinement >= 5, "refinement reported {refinement} times");
    // Refinement's total is the vertices it inserted: those kept, and above 28.6° (here 30°)
    // those of runs it tried and discarded (here, the order of the bad triangles it did not keep).
    let inserted = out.points.as_ref().unwrap().len() as i64 - input.points.len() as i64;
    let last = seen.reports.iter().rev().find(|r| r.0 == 2).unwrap();
    assert!(
        last.1 >= inserted && last.1 <= 3 * inserted,
        "{last:?}: {inserted} kept"
    );
    let (out20, seen20) = run("pzq20a0.00005Q", &input, None);
    let inserted20 = out20.points.as_ref().unwrap().len() as i64 - input.points.len() as i64;
    let last20 = seen20.reports.iter().rev().find(|r| r.0 == 2).unwrap();
    // One run below 28.6°: its vertices, those kept and the few that Chew's rule deleted again
    // (free vertices in the diametral circle of a subsegment being split).
    assert!(
        last20.1 >= inserted20 && last20.1 <= inserted20 + inserted20 / 10,
        "one run below 28.6°: {last20:?}, {inserted20} kept"
    );
    let delaunay = seen.reports.iter().find(|r| r.0 == 0).unwrap();
    assert_eq!(delaunay.2, input.points.len() as i64);

    // Without segments or refinement: only the Delaunay triangulation and the output.
    let (_, seen) = run("zQ", &input, None);
    let phases = check_reports("zQ", &seen.reports);
    assert_eq!(phases.iter().map(|&(p, _)| p).collect::<Vec<_>>(), [0, 3]);
}

#[test]
fn a_cancel_flag_set_from_the_progress_callback_stops_refinement() {
    let input = square(0);
    let (full, _) = run("pzq30a0.00002Q", &input, None);
    let (out, seen) = run("pzq30a0.00002Q", &input, Some(1000));
    let mesh = MeshView::of(&out).unwrap();
    let (ours, all) = (mesh.triangles.len(), full.counts.triangles as usize);
    assert!(ours < all / 2, "cancelled at {ours} triangles of {all}");
    assert!(seen.cancel.load(Ordering::Relaxed) == 1);
    check_reports("cancelled", &seen.reports);
}
