#!/usr/bin/env python3
"""Runs every example of the lecture notes on triangulations and writes one PNG per example.

    python python/examples/lecture_examples.py [OUTPUT_DIR] [--seed N] [--only NAME ...]

OUTPUT_DIR defaults to ``results/``. The examples are those of Triangulate.jl's notebook, in its
switch strings (0-based indices, as everywhere in triangle_rs): point sets (``Q``, ``cQ``, ``vQ``,
``vcDQ``, ``pcQ``) and a domain with a notch (``pQ``, ``pa0.05Q``, ``pa0.05DQ``, ``pa0.05q20Q``,
local refinement through the unsuitable callback ``pauq20Q``, two regions ``paAq20Q``, a square with
two square holes). An example that fails prints ``failed: <message>``; the others still run, and the
script exits with status 1. The mesh of the two regions is also written as ``domain_regions.vtu``
(VTK, with the region attribute per triangle) through meshio, when meshio is installed.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Callable, NamedTuple, Optional

import numpy as np

try:
    import triangle_rs
except ImportError:  # Run from a source checkout without installing: use the tree's package.
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
    import triangle_rs

from triangle_rs import TriangulateError, TriangulateIO, triangulate
from triangle_rs.plotting import plot_in_out


class Example(NamedTuple):
    name: str
    title: str
    switches: str
    #: Builds the input from a random generator (the point-set examples are random).
    make_input: Callable[[np.random.Generator], TriangulateIO]
    voronoi: bool = False
    circumcircles: bool = False
    unsuitable: Optional[Callable[..., bool]] = None
    #: Also write the mesh as a VTK file (``<name>.vtu``, through meshio).
    vtu: bool = False


def random_points(rng: np.random.Generator, n: int = 10, raster: int = 10) -> np.ndarray:
    """Up to ``n`` distinct random points on a ``raster`` x ``raster`` grid in (0, 1]^2 (the grid
    keeps points from coming too close), in the order drawn."""
    drawn = rng.integers(1, raster + 1, size=(n, 2)) / raster
    _, first = np.unique(drawn, axis=0, return_index=True)
    return drawn[np.sort(first)]


def point_set(rng: np.random.Generator) -> TriangulateIO:
    return TriangulateIO(pointlist=random_points(rng))


def point_set_with_segments(rng: np.random.Generator) -> TriangulateIO:
    points = random_points(rng)
    n = len(points)
    return TriangulateIO(
        pointlist=points,
        segmentlist=[[0, 1], [n - 2, n - 3], [0, n - 1]],
        segmentmarkerlist=[2, 3, 4],
    )


def notched_square(_rng: np.random.Generator) -> TriangulateIO:
    """The unit square with a notch reaching in to (0.6, 0.6); one marker per boundary segment."""
    return TriangulateIO(
        pointlist=[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.6, 0.6], [0.0, 1.0]],
        segmentlist=[[0, 1], [1, 2], [2, 3], [3, 4], [4, 0]],
        segmentmarkerlist=[1, 2, 3, 4, 5],
    )


def two_regions(_rng: np.random.Generator) -> TriangulateIO:
    """The notched square cut in two by the segment (0.5, 0) - (0.6, 0.6); each part has its own
    attribute (1, 2) and maximum area (0.01, 0.05)."""
    return TriangulateIO(
        pointlist=[[0.0, 0.0], [0.5, 0.0], [1.0, 0.0], [1.0, 1.0], [0.6, 0.6], [0.0, 1.0]],
        segmentlist=[[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [5, 0], [1, 4]],
        segmentmarkerlist=[1, 2, 3, 4, 5, 6, 7],
        regionlist=[[0.2, 0.2, 1.0, 0.01], [0.8, 0.2, 2.0, 0.05]],
    )


def square_with_two_holes(_rng: np.random.Generator) -> TriangulateIO:
    """The unit square (marker 1) with the square holes [0.2, 0.3]^2 (marker 2) and
    [0.6, 0.7]^2 (marker 3)."""
    def square(low: float, high: float) -> list[list[float]]:
        return [[low, low], [high, low], [high, high], [low, high]]

    def loop(first: int) -> list[list[int]]:
        return [[first + i, first + (i + 1) % 4] for i in range(4)]

    return TriangulateIO(
        pointlist=square(0.0, 1.0) + square(0.2, 0.3) + square(0.6, 0.7),
        segmentlist=loop(0) + loop(4) + loop(8),
        segmentmarkerlist=[1] * 4 + [2] * 4 + [3] * 4,
        holelist=[[0.25, 0.25], [0.65, 0.65]],
    )


def refine_near(center_x: float, center_y: float) -> Callable[..., bool]:
    """The lecture's local refinement test: split a triangle whose area exceeds a tenth of the
    squared distance from its barycentre to the centre (so triangles shrink towards it)."""

    def unsuitable(x1: float, y1: float, x2: float, y2: float, x3: float, y3: float, area: float) -> bool:
        dx = (x1 + x2 + x3) / 3.0 - center_x
        dy = (y1 + y2 + y3) / 3.0 - center_y
        squared_distance = dx * dx + dy * dy
        return squared_distance > 1.0e-5 and area > 0.1 * squared_distance

    return unsuitable


MAX_AREA = 0.05
MIN_ANGLE = 20.0

EXAMPLES = [
    Example("convex_hull", "Delaunay triangulation of a point set", "Q", point_set, circumcircles=True),
    Example("convex_hull_with_boundary", "... with its convex hull as segments", "cQ", point_set),
    Example("convex_hull_voronoi", "... with its Voronoi diagram", "vQ", point_set, voronoi=True),
    Example("convex_hull_voronoi_delaunay", "Conforming Delaunay with Voronoi diagram", "vcDQ", point_set, voronoi=True),
    Example("cdt", "Constrained Delaunay triangulation of a point set", "pcQ", point_set_with_segments),
    Example("domain_cdt", "Domain CDT", "pQ", notched_square),
    Example("domain_cdt_area", "Domain CDT with maximum area", f"pa{MAX_AREA!r}Q", notched_square, circumcircles=True),
    Example("domain_bcdt_area", "Boundary conforming Delaunay", f"pa{MAX_AREA!r}DQ", notched_square, circumcircles=True),
    Example("domain_qcdt_area", "Quality triangulation", f"pa{MAX_AREA!r}q{MIN_ANGLE!r}Q", notched_square),
    Example(
        "domain_localref", "Local refinement around (0.8, 0.6)", f"pauq{MIN_ANGLE!r}Q", notched_square,
        unsuitable=refine_near(0.8, 0.6),
    ),
    Example("domain_regions", "Two regions with their own areas", f"paAq{MIN_ANGLE!r}Q", two_regions, vtu=True),
    Example("domain_holes", "A square with two square holes", f"pa{MAX_AREA!r}q{MIN_ANGLE!r}Q", square_with_two_holes),
]


def run_example(example: Example, output_dir: Path, rng: np.random.Generator) -> Optional[Path]:
    """Runs one example and writes its PNG; returns the path, or ``None`` (after saying why) if
    the library refused the example."""
    triin = example.make_input(rng)
    try:
        triout, vorout = triangulate(example.switches, triin, unsuitable=example.unsuitable)
    except TriangulateError as error:
        print(f"{example.name} ({example.switches}): failed: {error}")
        return None
    figure = plot_in_out(
        triin,
        triout,
        voronoi=vorout if example.voronoi else None,
        circumcircles=example.circumcircles,
        title=f"{example.title}  [{example.switches}]",
    )
    path = output_dir / f"{example.name}.png"
    figure.savefig(path, dpi=100)
    print(
        f"{example.name} ({example.switches}): {triout.numberofpoints} points, "
        f"{triout.numberoftriangles} triangles, {triout.numberofsegments} segments -> {path}"
    )
    if example.vtu:
        write_vtu(triout, output_dir / f"{example.name}.vtu")
    return path


def write_vtu(mesh: TriangulateIO, path: Path) -> None:
    """The mesh as VTK through meshio (the package's optional [meshio] extra)."""
    try:
        import meshio  # noqa: F401
    except ImportError:
        print(f"{path.name}: not written (meshio is not installed: pip install \"./python[meshio]\")")
        return
    triangle_rs.to_meshio(mesh).write(path)
    print(f"{path.stem}: VTK mesh -> {path}")


def main(argv: Optional[list[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("output_dir", nargs="?", default="results", help="where to write the PNGs (default: results)")
    parser.add_argument("--seed", type=int, default=2024, help="seed of the random point sets")
    parser.add_argument("--only", nargs="+", metavar="NAME", choices=[e.name for e in EXAMPLES], help="run only these examples")
    args = parser.parse_args(argv)
    output_dir = Path(args.output_dir)
    output_dir.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(args.seed)
    written = failed = 0
    for example in EXAMPLES:
        if args.only and example.name not in args.only:
            continue
        if run_example(example, output_dir, rng) is None:
            failed += 1
        else:
            written += 1
    print(f"{written} PNGs written to {output_dir}, {failed} examples failed (library: {triangle_rs.library_path()})")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
