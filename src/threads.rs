//! Whether work can be split over two threads: the one question every parallel path asks.

/// Whether a second core is available to this process (its CPU affinity counts: under
/// `taskset -c 0` there is one), so that splitting work over two threads can pay.
pub(crate) fn two_cores() -> bool {
    std::thread::available_parallelism().is_ok_and(|n| n.get() >= 2)
}
