//! Whether work can be split over two threads: the one question every parallel path asks.

use std::sync::OnceLock;

/// Whether a second core is available to this process (its CPU affinity counts: under
/// `taskset -c 0` there is one), so that splitting work over two threads can pay.
///
/// Asked once per process: the answer comes from the affinity mask and the cgroup's CPU quota
/// (`std::thread::available_parallelism` opens and reads some nine files), which cost some
/// 100 µs — a hundred times a small triangulation — when asked on every call.
pub(crate) fn two_cores() -> bool {
    static TWO_CORES: OnceLock<bool> = OnceLock::new();
    *TWO_CORES.get_or_init(|| std::thread::available_parallelism().is_ok_and(|n| n.get() >= 2))
}
