"""Benchmark of ``triangle_rs.distributed.delaunay`` against the single call (issue 23).

For each size (default 10^6, 10^7, 3·10^7 uniform points; choose with ``--sizes 1e6 1e7``):

* the single call, ``triangle_rs.delaunay`` (the library's Delaunay, switch Q), in a fresh
  subprocess that does only that: wall time and what it needs, its peak RSS over the RSS of the
  interpreter with the libraries imported, before the points (the points and the call);
* ``delaunay()`` on a ``LocalCluster(n_workers=2, threads_per_worker=1)``: wall time, peak RSS
  of each worker process (the kernel's high-water mark ``VmHWM``, read on the workers), rounds
  and tiles;
* for 10^7 (``--limited-sizes``), the same with ``memory_limit`` per worker = one fifth of what
  the single call needs and ``memory_per_worker`` set to it. The limit is Dask's: it counts
  the whole worker process (its own ~90 MB of interpreter, dask and libraries included).

The triangle sets are compared by an order-independent fingerprint computed block by block on
the workers (each triangle's corners sorted, hashed to 64 bits, the hashes summed modulo 2^64,
with the count): neither side's set is ever held whole by the client. Equal fingerprints mean
equal sets up to a 2^-64 collision.

Dask's memory thresholds are set for small limits: a worker's own RSS is ~90 MB, half of a
200 MB limit, so pausing (default 80%) is turned off, otherwise a worker whose freed memory the
allocator keeps would wait forever; managed data (tiles, imports, results) is spilled to disk
past 20% of the limit (``target``) or when the process passes 55% (``spill``), which leaves a
round its room; the nanny still kills at 95%.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from typing import Any

import numpy as np

SEED = 23


def fingerprint(triangles: np.ndarray) -> tuple:
    """``(count, sum of 64-bit hashes of the sorted rows mod 2^64)`` of a block."""
    t = np.sort(np.asarray(triangles, dtype=np.uint64), axis=1)
    # A multiply-xorshift mix per corner (splitmix64's constants): rows differ in their hash
    # with overwhelming probability, and the sum is independent of the rows' order.
    with np.errstate(over="ignore"):
        h = t[:, 0] * np.uint64(0x9E3779B97F4A7C15)
        h ^= h >> np.uint64(31)
        h = (h + t[:, 1]) * np.uint64(0xBF58476D1CE4E5B9)
        h ^= h >> np.uint64(29)
        h = (h + t[:, 2]) * np.uint64(0x94D049BB133111EB)
        h ^= h >> np.uint64(32)
        total = int(h.sum(dtype=np.uint64))
    return len(t), total


def combine(prints: list) -> tuple:
    return sum(p[0] for p in prints), sum(p[1] for p in prints) % 2**64


def points(n: int, chunk: int = 1 << 20) -> Any:
    """The benchmark's uniform points as a dask array, generated blockwise on the workers (and
    the same numbers when computed whole in the single call's subprocess)."""
    import dask.array as da

    return da.random.default_rng(SEED).random((n, 2), chunks=(chunk, 2))


def single_call(n: int) -> dict:
    """Run in a fresh subprocess: the points (the same as the workers'), one call, measures."""
    import resource

    import dask.array  # noqa: F401 - imported before the base RSS is read: not the call's

    import triangle_rs

    base = int(open("/proc/self/statm").read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    xy = np.asarray(points(n).compute(scheduler="synchronous"))
    start = time.perf_counter()
    triangles = triangle_rs.delaunay(xy)
    wall = time.perf_counter() - start
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    prints = [fingerprint(triangles[k : k + (1 << 22)]) for k in range(0, len(triangles), 1 << 22)]
    return {"wall": wall, "needs": peak - base, "peak_rss": peak, "fingerprint": combine(prints)}


def _peak_rss() -> int:
    """This process's peak RSS (VmHWM), in bytes."""
    for line in open("/proc/self/status"):
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) * 1024
    return -1


def distributed_run(n: int, memory_limit: Any, plan: bool) -> dict:
    """``delaunay()`` on two local workers limited to ``memory_limit``; with ``plan`` the tile
    count is ``tiles_for_memory``'s for that limit (else the default, ~2^20 points a tile)."""
    import dask
    from distributed import Client, LocalCluster

    from triangle_rs import distributed as dd

    with dask.config.set({"distributed.worker.memory.pause": False, "distributed.worker.memory.target": 0.2,
                          "distributed.worker.memory.spill": 0.55}):
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, memory_limit=memory_limit,
                               dashboard_address=None, processes=True)
        client = Client(cluster)
        try:
            baseline = client.run(_peak_rss)
            start = time.perf_counter()
            per_worker = int(memory_limit) if plan else None
            result = dd.delaunay(points(n), client, memory_per_worker=per_worker)
            blocks = result.triangles.to_delayed().ravel()
            prints = client.gather(client.compute([dask.delayed(fingerprint)(b) for b in blocks]))
            wall = time.perf_counter() - start
            peaks = client.run(_peak_rss)
            return {"wall": wall, "worker_peak_rss": sorted(peaks.values()), "worker_baseline_rss": sorted(baseline.values()),
                    "rounds": result.rounds, "tiles": result.tiles, "fingerprint": combine(prints)}
        finally:
            client.close()
            cluster.close()


def mb(b: float) -> str:
    return f"{b / 2**20:,.0f} MB"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", nargs="+", type=float, default=[1e6, 1e7, 3e7])
    parser.add_argument("--limited-sizes", nargs="*", type=float, default=[1e7],
                        help="sizes also run with memory_limit = what the single call needs / 5")
    parser.add_argument("--single-only", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.single_only:
        print(json.dumps(single_call(args.single_only)))
        return
    print("| points | run | wall | peak memory | tiles/rounds | same set |")
    print("|---|---|---|---|---|---|")
    for size in args.sizes:
        n = int(size)
        out = subprocess.run([sys.executable, __file__, "--single-only", str(n)], check=True,
                             capture_output=True, text=True).stdout
        one = json.loads(out.strip().splitlines()[-1])
        print(f"| {n:.0e} | single call | {one['wall']:.1f} s | needs {mb(one['needs'])} "
              f"(RSS {mb(one['peak_rss'])}) | | |", flush=True)
        runs = [("2 workers, limit 8 GiB each", "8GiB", False)]
        if any(int(s) == n for s in args.limited_sizes):
            runs.append((f"2 workers, limit {mb(one['needs'] / 5)} each (a fifth)", int(one["needs"] / 5), True))
        for label, limit, plan in runs:
            try:
                two = distributed_run(n, limit, plan)
            except Exception as error:  # report and go on with the next run
                print(f"| {n:.0e} | {label} | failed: {type(error).__name__}: {error} | | | |", flush=True)
                continue
            peaks = ", ".join(mb(p) for p in two["worker_peak_rss"])
            same = "yes" if tuple(two["fingerprint"]) == tuple(one["fingerprint"]) else "NO"
            print(f"| {n:.0e} | {label} | {two['wall']:.1f} s | {peaks} per worker "
                  f"(baseline {', '.join(mb(p) for p in two['worker_baseline_rss'])}) | {two['tiles']}/{two['rounds']} | {same} |",
                  flush=True)


if __name__ == "__main__":
    main()
