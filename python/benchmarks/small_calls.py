"""The fixed cost of a call: small triangulations through the PyPI ``triangle`` package (Triangle
1.6, compiled into the process by Cython) and through ``triangle_rs`` (ctypes and numpy over the
triangle-rs library), timed alternately (issue 36, point 1).

Cases: the lecture's 5-vertex domain with the switches ``p``, ``pq30`` and ``pq30a0.01``
(``triangulate(dict, opts)``), and 10, 100 and 1000 uniform random points with ``delaunay(points)``
and ``triangulate({'vertices': points}, '')``. Each case calls the two packages one after the other,
``--repeat`` times (which one goes first alternates), and prints the best time of each and their
ratio (ours / PyPI's; below 1 is faster). Best-of-N, because the machine's other work only ever
adds time; alternating, so that both see the same machine.

Run from a checkout (the package in ``python/`` is used; the library is found as the package
finds it, e.g. ``TRIANGLE_RS_LIBRARY=$PWD/target/release/libtriangle_rs.so``)::

    python python/benchmarks/small_calls.py [--repeat 2000]
"""

from __future__ import annotations

import argparse
import os
import platform
import sys
import time
from pathlib import Path
from typing import Any, Callable

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))  # this checkout's triangle_rs

import triangle_rs  # noqa: E402

SEED = 36

#: The lecture's domain: the unit square with a notch at (0.8, 0.6).
LECTURE = {
    "vertices": [[0, 0], [1, 0], [1, 1], [0.8, 0.6], [0, 1]],
    "segments": [[0, 1], [1, 2], [2, 3], [3, 4], [4, 0]],
}


def cases() -> list[tuple[str, Callable[[Any], Any]]]:
    """(label, call(module)): each call runs one triangulation through ``module``."""
    rng = np.random.default_rng(SEED)
    result: list[tuple[str, Callable[[Any], Any]]] = [
        (f"lecture domain, '{opts}'", lambda m, opts=opts: m.triangulate(LECTURE, opts))
        for opts in ("p", "pq30", "pq30a0.01")
    ]
    for n in (10, 100, 1000):
        points = rng.random((n, 2))
        result.append((f"{n} points, delaunay", lambda m, points=points: m.delaunay(points)))
        vertices = {"vertices": points}
        result.append((f"{n} points, ''", lambda m, vertices=vertices: m.triangulate(vertices, "")))
    return result


def best_times(call: Callable[[Any], Any], reference: Any, repeat: int) -> tuple[float, float]:
    """The best time (seconds) of ``call(reference)`` and of ``call(triangle_rs)``, alternately."""
    clock = time.perf_counter
    best_reference = best_ours = float("inf")
    call(reference), call(triangle_rs)  # warm up (first use loads the library)
    for k in range(repeat):
        for module in (reference, triangle_rs) if k % 2 == 0 else (triangle_rs, reference):
            start = clock()
            call(module)
            elapsed = clock() - start
            if module is reference:
                best_reference = min(best_reference, elapsed)
            else:
                best_ours = min(best_ours, elapsed)
    return best_reference, best_ours


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=2000, help="calls per package and case (default 2000)")
    arguments = parser.parse_args()
    try:
        import triangle
    except ImportError:
        sys.exit("The PyPI package `triangle` is not installed: pip install triangle")
    print(
        f"best of {arguments.repeat}, alternating; Python {platform.python_version()}, numpy {np.__version__}, "
        f"{os.cpu_count()} CPUs; triangle_rs: {triangle_rs.library_path()}"
    )
    print(f"{'case':28s} {'PyPI triangle':>14s} {'triangle_rs':>12s} {'ratio':>6s}")
    for label, call in cases():
        reference, ours = best_times(call, triangle, arguments.repeat)
        print(f"{label:28s} {reference * 1e6:11.1f} µs {ours * 1e6:9.1f} µs {ours / reference:6.2f}")


if __name__ == "__main__":
    main()
