//! Large fresh arrays on huge pages: the one memory hint every large allocation asks for; and
//! pages faulted in ahead of a copy by a thread that would otherwise wait ([`prefault_while`]).
//!
//! A million points take some 100 MB of arrays that are written once, in fresh pages; with 4 KiB
//! pages that is 25 000 page faults, a quarter of a one-core triangulation's time (the kernel
//! zeroes and maps each page, and the TLB then misses on the random accesses of the point
//! location and the flips). Transparent huge pages (2 MiB) cut the faults 512-fold and the TLB
//! misses with them. Linux hands them out only where asked (`madvise` mode, the common default),
//! so each large array is asked for right after its allocation, before its pages are touched.
//!
//! Only where the work runs on one core: when a second core is free, the large arrays are
//! written by two threads at once (the halves of the Delaunay merge, the input copy), and there
//! huge pages measured slower on the project's machine (median of interleaved runs at 10^6
//! points: 0.26 s against 0.21 s; one core: 0.24 s against 0.30 s). A huge-page fault zeroes
//! 2 MiB at once, and on a virtual machine that returns free memory to its host it also waits
//! for the host to back those 2 MiB, while the other thread's faults and mappings queue.

/// The size of a transparent huge page on x86-64 and AArch64 (4 KiB base pages).
const HUGE_PAGE: usize = 2 << 20;

/// Arrays smaller than this are left alone: they hold at most one whole huge page, and small
/// allocations come from the heap, whose pages are already in place.
const WORTH_ASKING: usize = 4 << 20;

/// Asks the kernel to back the whole 2 MiB extents of the `bytes` bytes at `start` with
/// transparent huge pages when they are first touched. A hint: nothing changes where it is
/// refused or unsupported, and pages already touched stay as they are.
pub(crate) fn prefer_huge_pages(start: *const u8, bytes: usize) {
    if bytes < WORTH_ASKING || crate::threads::two_cores() {
        return;
    }
    let first = (start as usize).next_multiple_of(HUGE_PAGE);
    let end = (start as usize + bytes) / HUGE_PAGE * HUGE_PAGE;
    if end <= first {
        return;
    }
    #[cfg(target_os = "linux")]
    // SAFETY: the range lies within one live allocation of the caller's (whole 2 MiB extents
    // inside `start..start + bytes`); MADV_HUGEPAGE changes no contents, only how pages are
    // backed, and its failure is harmless.
    unsafe {
        libc::madvise(first as *mut libc::c_void, end - first, libc::MADV_HUGEPAGE);
    }
}

/// An empty vector with room for `capacity` elements, its pages to be huge ones.
pub(crate) fn with_capacity_on_huge_pages<T>(capacity: usize) -> Vec<T> {
    let v: Vec<T> = Vec::with_capacity(capacity);
    prefer_huge_pages(v.as_ptr().cast(), v.capacity() * std::mem::size_of::<T>());
    v
}

/// How much [`prefault_while`] faults in between two looks at whether to go on: some
/// hundred microseconds of work.
const PREFAULT_CHUNK: usize = 1 << 18;

/// Faults in, for writing, the pages of the address range `range` (inside one live allocation
/// of the caller's, about to be written), a chunk at a time while `keep_going()` says so: work
/// for a thread that would otherwise wait, so that a later copy into that memory finds its
/// pages in place (a fresh 4 KiB page costs some two microseconds of kernel time on the
/// project's machine; a copy of 24 MB into fresh pages spends most of its time there). A hint:
/// where the kernel lacks `MADV_POPULATE_WRITE` (Linux before 5.14, other systems) nothing
/// happens. The memory's contents never change, so a range whose allocation is freed meanwhile
/// is harmless too (the call fails, or faults in pages of whatever lies there now).
pub(crate) fn prefault_while(range: std::ops::Range<usize>, keep_going: impl Fn() -> bool) {
    const PAGE: usize = 4096;
    let (mut at, end) = (range.start.next_multiple_of(PAGE), range.end / PAGE * PAGE);
    while at < end && keep_going() {
        let chunk = PREFAULT_CHUNK.min(end - at);
        if !populate_for_writing(at, chunk) {
            return;
        }
        at += chunk;
    }
}

/// `MADV_POPULATE_WRITE` on whole pages at `at` (see [`prefault_while`]); false where it failed
/// or does not exist.
fn populate_for_writing(at: usize, bytes: usize) -> bool {
    #[cfg(target_os = "linux")]
    {
        // SAFETY: not a memory access: MADV_POPULATE_WRITE maps the pages as a write would,
        // without changing any contents (written or not, whatever allocation they belong to),
        // and its failure is harmless.
        unsafe { libc::madvise(at as *mut libc::c_void, bytes, libc::MADV_POPULATE_WRITE) == 0 }
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = (at, bytes);
        false
    }
}

/// Asks the processor to bring the cache line of `value` into the cache: a hint, no effect on
/// the program (nothing on other architectures).
#[inline(always)]
pub(crate) fn prefetch<T>(value: &T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: the address of a live reference; a prefetch reads nothing into the program.
    unsafe {
        std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>(
            (value as *const T).cast(),
        )
    };
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}
