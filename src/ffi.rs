//! The C ABI: Triangle 1.6's `triangulate`/`trifree`, Triangle_jll's `triangulate_catch_exit` and
//! `triunsuitable_callback`, and triangle-rs's reentrant `triangulate_reentrant` and
//! `triangulate_last_error`.
//!
//! This layer only converts and checks: it parses the switch string, borrows the input through
//! [`crate::io::triangulateio`], runs the safe engine ([`crate::pipeline::triangulate`]) and writes
//! the result back. No panic crosses it (`catch_unwind`), and nothing here calls `exit`.

use std::cell::RefCell;
use std::ffi::{CStr, CString};
use std::os::raw::{c_char, c_int, c_void};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicI32, AtomicPtr, Ordering};

use crate::data::{Hooks, Progress, ProgressFn, UnsuitableFn};
use crate::error::Error;
use crate::io::triangulateio::{input_from_raw, write_output, TriangulateIO};
use crate::options::{Options, SwitchSource};
use crate::pipeline;

/// Triangulate.jl's callback: org x, y, dest x, y, apex x, y, area; non-zero = unsuitable.
pub type TriunsuitableFn = extern "C" fn(f64, f64, f64, f64, f64, f64, f64) -> c_int;

/// The reentrant callback: as [`TriunsuitableFn`] plus the caller's `user_data` pointer last.
pub type TriunsuitableUserFn =
    extern "C" fn(f64, f64, f64, f64, f64, f64, f64, *mut c_void) -> c_int;

/// The callback set by `triunsuitable_callback` (Triangulate.jl's global setter). Each call of
/// `triangulate` reads it once at its start, so a concurrent change never tears a running call.
static GLOBAL_UNSUITABLE: AtomicPtr<c_void> = AtomicPtr::new(std::ptr::null_mut());

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
    static LAST_WARNING: RefCell<CString> = RefCell::new(CString::default());
}

fn set_message(slot: &'static std::thread::LocalKey<RefCell<CString>>, message: &str) {
    // The same text again (mostly none: every call clears the warning, and most have none)
    // stays without an allocation and a free.
    if slot.with(|slot| slot.borrow().as_bytes() == message.as_bytes()) {
        return;
    }
    let c = CString::new(message.replace('\0', " ")).unwrap_or_default();
    slot.with(|slot| *slot.borrow_mut() = c);
}

fn set_last_error(message: &str) {
    set_message(&LAST_ERROR, message);
}

/// A user pointer that may cross threads: the caller promises its callback is thread-safe.
#[derive(Clone, Copy)]
struct UserData(*mut c_void);
// SAFETY: the pointer is only handed back to the caller's own callback, as the caller asked.
unsafe impl Sync for UserData {}
unsafe impl Send for UserData {}

/// The body shared by every entry point.
///
/// # Safety
/// As `triangulate`.
unsafe fn run(
    switches: *const c_char,
    input: *mut TriangulateIO,
    output: *mut TriangulateIO,
    vorout: *mut TriangulateIO,
    callback: Option<&UnsuitableFn<'_>>,
    cancel: *const c_int,
    progress: Option<&ProgressFn<'_>>,
) -> Result<(), Error> {
    if switches.is_null() {
        return Err(Error::NullArgument("switches"));
    }
    // SAFETY: non-NULL and, by the C contract, a NUL-terminated string.
    let text = unsafe { CStr::from_ptr(switches) }
        .to_str()
        .map_err(|_| Error::BadSwitches)?;
    let options = Options::parse(text, SwitchSource::Library)?;
    let quiet = options.quiet;
    set_message(&LAST_WARNING, "");
    let result = (|| {
        if input.is_null() {
            return Err(Error::NullArgument("in"));
        }
        if output.is_null() {
            return Err(Error::NullArgument("out"));
        }
        if options.output.voronoi && vorout.is_null() {
            return Err(Error::NullArgument("vorout"));
        }
        // SAFETY: non-NULL; the caller owns these structs for the duration of the call.
        let in_ref: &TriangulateIO = unsafe { &*input };
        let cancel_flag = if cancel.is_null() {
            None
        } else {
            // SAFETY: non-NULL, aligned `int` that the caller keeps alive during the call;
            // AtomicI32 has the layout of i32 and other threads only store into it.
            Some(unsafe { AtomicI32::from_ptr(cancel as *mut i32) })
        };
        let is_cancelled = move || cancel_flag.is_some_and(|f| f.load(Ordering::Relaxed) != 0);
        let hooks = Hooks {
            unsuitable: callback,
            cancel: Some(&is_cancelled),
            progress,
        };
        let result = {
            // SAFETY: the arrays of `in` hold as many items as its counts say (C contract).
            let engine_input = unsafe { input_from_raw(in_ref, &options)? };
            pipeline::triangulate(&options, &engine_input, &hooks)?
            // `engine_input` ends here, before anything is written: `out` may alias `in`.
        };
        let (mut mesh, voronoi) = result;
        let warnings = std::mem::take(&mut mesh.warnings);
        let mesh_check = mesh.mesh_check.take();
        set_message(&LAST_WARNING, &warnings.join("\n"));
        let in_copy = *in_ref;
        // SAFETY: `out`/`vorout` are valid (checked non-NULL) and their non-NULL arrays are
        // large enough (Triangle's contract).
        unsafe {
            let vor = if vorout.is_null() {
                None
            } else {
                Some((voronoi, &mut *vorout))
            };
            write_output(&in_copy, mesh, &mut *output, vor)?;
        }
        if !quiet {
            for w in &warnings {
                eprintln!("Warning: {w}");
            }
            // `C`: the check's report on stdout, as Triangle's library prints it (a failed
            // check is among the warnings too; a passing one is not a warning).
            if let Some(check) = &mesh_check {
                for line in check.report() {
                    println!("  {line}");
                }
            }
        }
        Ok(())
    })();
    if let Err(e) = &result {
        if !quiet {
            eprintln!("triangle-rs: {e}");
        }
    }
    result
}

/// Runs `run` behind `catch_unwind` and maps the result to Triangle_jll's return code.
fn guarded(body: impl FnOnce() -> Result<(), Error>) -> c_int {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => {
            set_last_error("");
            0
        }
        Ok(Err(e)) => {
            set_last_error(&e.to_string());
            1
        }
        Err(panic) => {
            set_last_error(&Error::from_panic(panic).to_string());
            2
        }
    }
}

fn global_callback() -> Option<TriunsuitableFn> {
    let p = GLOBAL_UNSUITABLE.load(Ordering::Acquire);
    if p.is_null() {
        None
    } else {
        // SAFETY: only `triunsuitable_callback` stores here, and it stores a TriunsuitableFn.
        Some(unsafe { std::mem::transmute::<*mut c_void, TriunsuitableFn>(p) })
    }
}

/// Triangulates, meshes or refines as Triangle 1.6 does. Returns 0 on success; on failure a
/// non-zero code, with the message available from `triangulate_last_error`. The `u` test is the
/// callback set with `triunsuitable_callback`, or with none set Triangle's built-in test.
///
/// # Safety
/// `switches` is a NUL-terminated string; `in`, `out` and (with `v`) `vorout` point to valid
/// structs whose arrays hold as many items as their counts say; non-NULL output arrays are
/// large enough for what Triangle would write there.
#[no_mangle]
pub unsafe extern "C" fn triangulate(
    switches: *const c_char,
    r#in: *mut TriangulateIO,
    out: *mut TriangulateIO,
    vorout: *mut TriangulateIO,
) -> c_int {
    let callback = global_callback();
    let test = move |ox, oy, dx, dy, ax, ay, area| {
        callback.is_some_and(|f| f(ox, oy, dx, dy, ax, ay, area) != 0)
    };
    let callback_ref = callback.is_some().then_some(&test as &UnsuitableFn<'_>);
    // SAFETY: the caller's contract is this function's.
    guarded(|| unsafe {
        run(
            switches,
            r#in,
            out,
            vorout,
            callback_ref,
            std::ptr::null(),
            None,
        )
    })
}

/// The same call under the name Triangulate.jl uses (Triangle_jll's setjmp wrapper): 0 on
/// success, 1 on error. triangle-rs never exits, so no setjmp is needed.
///
/// # Safety
/// As [`triangulate`].
#[no_mangle]
pub unsafe extern "C" fn triangulate_catch_exit(
    switches: *const c_char,
    r#in: *mut TriangulateIO,
    out: *mut TriangulateIO,
    vorout: *mut TriangulateIO,
) -> c_int {
    // SAFETY: same contract.
    match unsafe { triangulate(switches, r#in, out, vorout) } {
        0 => 0,
        _ => 1,
    }
}

/// Reentrant triangulation: the `u` test is `unsuitable` (called with `user_data` last) for this
/// call only, and refinement stops early with a valid mesh once `*cancel` becomes non-zero (set it
/// from another thread with an atomic or volatile store; `cancel` may be NULL). No global state.
/// With `unsuitable` NULL, `u` applies Triangle's built-in test.
///
/// # Safety
/// As [`triangulate`]; `cancel` is NULL or points to an aligned `int` that outlives the call;
/// `unsuitable` may be called from this thread only, with `user_data` as given.
#[no_mangle]
pub unsafe extern "C" fn triangulate_reentrant(
    switches: *const c_char,
    r#in: *mut TriangulateIO,
    out: *mut TriangulateIO,
    vorout: *mut TriangulateIO,
    unsuitable: Option<TriunsuitableUserFn>,
    user_data: *mut c_void,
    cancel: *const c_int,
) -> c_int {
    // SAFETY: the same contract, without a progress callback.
    unsafe {
        triangulate_progress(
            switches, r#in, out, vorout, unsuitable, user_data, cancel, None,
        )
    }
}

/// The progress callback of [`triangulate_progress`]: the phase (0 Delaunay triangulation,
/// 1 segment insertion, 2 refinement, 3 output), the work done in it and an estimate of its
/// total (0 when unknown; for refinement: vertices inserted, and those plus the work waiting),
/// and the call's `user_data`.
pub type TriangulateProgressFn =
    unsafe extern "C" fn(phase: c_int, done: i64, estimate: i64, user_data: *mut c_void);

/// As [`triangulate_reentrant`], and `progress` (may be NULL) is told of the call's progress:
/// at the start and end of each phase, and during refinement where the cancel flag is polled
/// (every 1024 steps). Called on the calling thread with `user_data`, never after the return.
///
/// # Safety
/// As [`triangulate_reentrant`]; `progress` may be called from this thread only.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn triangulate_progress(
    switches: *const c_char,
    r#in: *mut TriangulateIO,
    out: *mut TriangulateIO,
    vorout: *mut TriangulateIO,
    unsuitable: Option<TriunsuitableUserFn>,
    user_data: *mut c_void,
    cancel: *const c_int,
    progress: Option<TriangulateProgressFn>,
) -> c_int {
    let data = UserData(user_data);
    let test = move |ox, oy, dx, dy, ax, ay, area| {
        let data = data;
        unsuitable.is_some_and(|f| f(ox, oy, dx, dy, ax, ay, area, data.0) != 0)
    };
    let callback_ref = unsuitable.is_some().then_some(&test as &UnsuitableFn<'_>);
    let report = move |p: Progress| {
        let data = data;
        if let Some(f) = progress {
            let clamp = |v: u64| v.min(i64::MAX as u64) as i64;
            // SAFETY: the caller's function pointer, called as its contract says.
            unsafe { f(p.phase as c_int, clamp(p.done), clamp(p.estimate), data.0) }
        }
    };
    let progress_ref = progress.is_some().then_some(&report as &ProgressFn<'_>);
    // SAFETY: the caller's contract is this function's.
    guarded(|| unsafe {
        run(
            switches,
            r#in,
            out,
            vorout,
            callback_ref,
            cancel,
            progress_ref,
        )
    })
}

/// Frees an array that `triangulate` allocated (libc `free`). NULL is ignored.
///
/// # Safety
/// `memptr` is NULL or a pointer returned by this library's allocation and not freed yet.
#[no_mangle]
pub unsafe extern "C" fn trifree(memptr: *mut c_void) {
    // SAFETY: the caller passes a pointer from libc malloc (or NULL).
    unsafe { libc::free(memptr) }
}

/// Sets the process-wide `u` callback (Triangulate.jl's `triunsuitable!`). NULL clears it: `u`
/// then applies Triangle's built-in test.
/// Prefer `triangulate_reentrant`, which takes the callback per call.
#[no_mangle]
pub extern "C" fn triunsuitable_callback(f: Option<TriunsuitableFn>) {
    let p = f.map_or(std::ptr::null_mut(), |f| f as *mut c_void);
    GLOBAL_UNSUITABLE.store(p, Ordering::Release);
}

/// The message of the last failed call on this thread ("" after a success). The pointer stays
/// valid until the next call on this thread.
#[no_mangle]
pub extern "C" fn triangulate_last_error() -> *const c_char {
    LAST_ERROR.with(|slot| slot.borrow().as_ptr())
}

/// The warnings of the last call on this thread, one per line ("" when it had none, or
/// failed), with or without `Q`: duplicate vertices, a `C` check that failed (one that passes
/// is no warning), and where a refined mesh falls short of what was asked (precision of the
/// coordinates exhausted, an angle above the guarantee not reached, cancelled, a runaway
/// stopped) although it is valid. The pointer stays valid until the next call on this thread.
#[no_mangle]
pub extern "C" fn triangulate_last_warning() -> *const c_char {
    LAST_WARNING.with(|slot| slot.borrow().as_ptr())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn last_warning() -> String {
        // SAFETY: the library's own NUL-terminated, thread-local string.
        unsafe { CStr::from_ptr(triangulate_last_warning()) }
            .to_string_lossy()
            .into_owned()
    }

    /// Triangulates `points` (x, y pairs) with `switches` and gives the call's warnings.
    fn warnings_of(switches: &CStr, points: &mut [f64]) -> String {
        let mut input = TriangulateIO {
            pointlist: points.as_mut_ptr(),
            numberofpoints: (points.len() / 2) as c_int,
            ..TriangulateIO::default()
        };
        let mut output = TriangulateIO::default();
        // SAFETY: a valid input of `points`, an empty output struct; no `v`.
        let code = unsafe {
            triangulate(
                switches.as_ptr(),
                &mut input,
                &mut output,
                std::ptr::null_mut(),
            )
        };
        assert_eq!(code, 0, "{switches:?}");
        // Holes and regions alias the input's (none here); every other array is this call's.
        for array in [
            output.pointlist as *mut c_void,
            output.pointattributelist as *mut c_void,
            output.pointmarkerlist as *mut c_void,
            output.trianglelist as *mut c_void,
            output.triangleattributelist as *mut c_void,
            output.neighborlist as *mut c_void,
            output.segmentlist as *mut c_void,
            output.segmentmarkerlist as *mut c_void,
            output.edgelist as *mut c_void,
            output.edgemarkerlist as *mut c_void,
        ] {
            // SAFETY: arrays this call allocated (or NULL).
            unsafe { trifree(array) };
        }
        last_warning()
    }

    /// `C` on a mesh that passes leaves `triangulate_last_warning()` empty; other warnings stay.
    #[test]
    fn a_passing_check_is_no_warning() {
        let square = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.3, 0.4];
        assert_eq!(warnings_of(c"QC", &mut square.clone()), "");
        assert_eq!(warnings_of(c"QCq", &mut square.clone()), "");
        let mut with_duplicate = square.to_vec();
        with_duplicate.extend_from_slice(&[0.3, 0.4]);
        let warnings = warnings_of(c"QC", &mut with_duplicate);
        assert_eq!(warnings.lines().count(), 1, "{warnings}");
        assert!(warnings.contains("duplicate"), "{warnings}");
    }
}
