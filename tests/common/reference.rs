//! Debian's Triangle 1.6 (`/usr/lib/libtriangle-1.6.so`), loaded with `libloading`, as the
//! oracle of the differential tests.
//!
//! Triangle keeps global state, so every call is serialized with one process-wide mutex. It also
//! calls `exit(1)` on bad input: only pass it input it accepts. When the library is missing the
//! tests skip with a message, except in CI (env `CI` set), where they fail.

use std::os::raw::{c_char, c_void};
use std::sync::{Mutex, OnceLock};

use triangle_rs::io::triangulateio::TriangulateIO;

use super::call::{run_call, MeshInput, Triangulation};

pub const REFERENCE_LIBRARY: &str = "/usr/lib/libtriangle-1.6.so";

type TriangulateFn =
    unsafe extern "C" fn(*mut c_char, *mut TriangulateIO, *mut TriangulateIO, *mut TriangulateIO);
type TrifreeFn = unsafe extern "C" fn(*mut c_void);

pub struct Reference {
    triangulate: TriangulateFn,
    trifree: TrifreeFn,
    _library: libloading::Library,
}

static REFERENCE: OnceLock<Option<Reference>> = OnceLock::new();
static REFERENCE_LOCK: Mutex<()> = Mutex::new(());

/// Reports a missing reference artefact: a printed skip locally, a panic in CI.
pub fn reference_missing(what: &str) {
    if std::env::var_os("CI").is_some() {
        panic!(
            "{what} is missing, and CI must not skip the differential tests (.ci/run installs it)"
        );
    }
    eprintln!("SKIPPED: {what} is missing (install Debian's triangle-bin and libtriangle-dev)");
}

/// The reference library, or `None` (after [`reference_missing`]) when it is not installed.
pub fn reference() -> Option<&'static Reference> {
    let loaded = REFERENCE.get_or_init(|| {
        // SAFETY: loading Debian's libtriangle runs no initialisers with preconditions.
        let library = unsafe { libloading::Library::new(REFERENCE_LIBRARY) }.ok()?;
        // SAFETY: Triangle 1.6's prototypes: void triangulate(char *, struct triangulateio *×3)
        // and void trifree(void *); the pointers stay valid while `_library` is alive (static).
        unsafe {
            let triangulate = *library.get::<TriangulateFn>(b"triangulate\0").ok()?;
            let trifree = *library.get::<TrifreeFn>(b"trifree\0").ok()?;
            Some(Reference {
                triangulate,
                trifree,
                _library: library,
            })
        }
    });
    if loaded.is_none() {
        reference_missing(REFERENCE_LIBRARY);
    }
    loaded.as_ref()
}

impl Reference {
    /// One raw call of Triangle's `triangulate` (serialized), for the benchmark.
    ///
    /// # Safety
    /// As Triangle's `triangulate`: valid switches and structs, input Triangle accepts.
    pub unsafe fn triangulate_raw(
        &self,
        switches: *mut c_char,
        input: *mut TriangulateIO,
        out: *mut TriangulateIO,
        vorout: *mut TriangulateIO,
    ) {
        let _serialized = REFERENCE_LOCK
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        // SAFETY: the caller's contract.
        unsafe { (self.triangulate)(switches, input, out, vorout) }
    }

    /// Triangle's `trifree`.
    ///
    /// # Safety
    /// `p` is NULL or an array Triangle allocated and not yet freed.
    pub unsafe fn trifree(&self, p: *mut c_void) {
        // SAFETY: the caller's contract.
        unsafe { (self.trifree)(p) }
    }

    /// Triangle's output for valid input (Triangle exits the process on invalid input).
    pub fn triangulate(&self, switches: &str, input: &MeshInput) -> Triangulation {
        self.triangulate_with(switches, input, true)
    }

    pub fn triangulate_with(
        &self,
        switches: &str,
        input: &MeshInput,
        with_vorout: bool,
    ) -> Triangulation {
        let _serialized = REFERENCE_LOCK
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let call = |s, i, o, v| {
            // SAFETY: valid switches and structs prepared by `run_call`; calls are serialized.
            unsafe { (self.triangulate)(s, i, o, v) };
            Ok(())
        };
        // SAFETY: arrays allocated by Debian's triangulate are freed with its trifree.
        let free = |p| unsafe { (self.trifree)(p) };
        run_call(&call, &free, switches, input, with_vorout)
            .expect("the reference call cannot fail")
    }
}
