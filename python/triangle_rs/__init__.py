"""triangle-rs for Python: 2-D Delaunay triangulations and quality meshes (Triangle 1.6 compatible).

Three APIs over one library call (``ctypes`` and ``numpy`` only; nothing is compiled at import):

* Triangulate.jl style: ``out, vorout = triangulate("pq30a0.01", TriangulateIO(pointlist=...,
  segmentlist=...))``, with a per-call ``unsuitable=`` callback for switch ``u``.
* The PyPI ``triangle`` package's: ``triangulate({'vertices': ...}, 'pq')``, ``delaunay``,
  ``convex_hull``, ``voronoi`` (``import triangle_rs as triangle`` runs existing code).
  Also its data files and plots: ``get_data``, ``loads``, ``load``, ``show_data``, ``plot``,
  ``compare`` and ``comparev``.
* Keywords: ``mesh(points, segments=..., holes=..., min_angle=30, max_area=1e-3)``.

Plots (matplotlib, imported only when used): ``plot_triangulateio`` and ``plot_in_out`` from
:mod:`triangle_rs.plotting`. meshio (imported only when used): ``to_meshio(out)``. Neither
``import triangle_rs`` nor ``from triangle_rs import *`` imports matplotlib or meshio.

All indices are 0-based. Errors raise :class:`TriangulateError` with the library's message. A call
warns at most once, with a :class:`TriangulateWarning` (a ``RuntimeWarning``) when its mesh falls
short of what was asked (a quality bound not reached, the ``S`` budget spent); what Triangle does
silently under ``Q`` (duplicate vertices ignored, a passing ``C`` check) is no warning: ``V``
prints it, and :func:`last_report` keeps it.
"""

from __future__ import annotations

from typing import Any, Mapping, Optional, Union, overload

import numpy as np

from . import compat, core
from ._library import ENVIRONMENT_VARIABLE, Library, load_library
from .compat import convex_hull, delaunay, voronoi
from .core import Progress, TriangulateError, Unsuitable
from .data import get_data, load, loads, show_data
from .meshing import MeshResult, mesh, mesh_switches
from .meshio_io import to_meshio
from .report import Report, TriangulateWarning, last_report
from .pypi_plot import compare, comparev, plot
from .triangulateio import TriangulateIO, numberofedges, numberofpoints, numberofsegments, numberoftriangles

__version__ = "0.1.0"

__all__ = [
    "ENVIRONMENT_VARIABLE",
    "Library",
    "MeshResult",
    "Report",
    "TriangulateError",
    "TriangulateWarning",
    "TriangulateIO",
    "Progress",
    "Unsuitable",
    "compare",
    "comparev",
    "convex_hull",
    "delaunay",
    "get_data",
    "last_report",
    "library_path",
    "load",
    "loads",
    "mesh",
    "mesh_switches",
    "numberofedges",
    "numberofpoints",
    "numberofsegments",
    "numberoftriangles",
    "plot",
    "plot_in_out",
    "plot_triangulateio",
    "show_data",
    "to_meshio",
    "triangulate",
    "voronoi",
]


@overload
def triangulate(
    switches: str,
    tio: TriangulateIO,
    *,
    unsuitable: Optional[Unsuitable] = None,
    progress: "Progress | bool | None" = None,
) -> tuple[TriangulateIO, TriangulateIO]: ...


@overload
def triangulate(
    tri: Mapping[str, Any],
    opts: str = "",
    *,
    unsuitable: Optional[Unsuitable] = None,
    progress: "Progress | bool | None" = None,
) -> dict[str, np.ndarray]: ...


def triangulate(
    first: Union[str, Mapping[str, Any]],
    second: Union[TriangulateIO, str] = "",
    *,
    unsuitable: Optional[Unsuitable] = None,
    progress: "Progress | bool | None" = None,
) -> Union[tuple[TriangulateIO, TriangulateIO], dict[str, np.ndarray]]:
    """Triangulates in either style, chosen by the arguments:

    * ``triangulate(switches: str, tio: TriangulateIO) -> (out, vorout)``: Triangulate.jl style
      (see :func:`triangle_rs.core.triangulate`);
    * ``triangulate(tri: dict, opts: str = '') -> dict``: the PyPI ``triangle`` package's
      (see :func:`triangle_rs.compat.triangulate`).

    ``unsuitable(x1, y1, x2, y2, x3, y3, area) -> bool`` is the per-call test of switch ``u``
    (without it, ``u`` applies Triangle's built-in test, as the PyPI package does).
    ``progress=True`` shows a progress bar (tqdm when installed); a callable
    ``progress(phase, done, estimate)`` is told of the call's progress instead.
    """
    if isinstance(first, str) and isinstance(second, TriangulateIO):
        return core.triangulate(first, second, unsuitable=unsuitable, progress=progress)
    if (type(first) is dict or isinstance(first, Mapping)) and isinstance(second, str):
        return compat.triangulate(first, second, unsuitable=unsuitable, progress=progress)
    raise TypeError(
        "triangulate takes (switches: str, tio: TriangulateIO) or (tri: dict, opts: str = ''), "
        f"got ({type(first).__name__}, {type(second).__name__})"
    )


def library_path() -> str:
    """The path of the shared library in use (loads it if needed)."""
    return load_library().path


def plot_triangulateio(ax: Any, tio: TriangulateIO, voronoi: Optional[TriangulateIO] = None, circumcircles: bool = False, **options: Any) -> Any:
    """Draws ``tio`` into the matplotlib axes ``ax``: see :func:`triangle_rs.plotting.plot_triangulateio`."""
    # Imported here: `import triangle_rs` (and `import *`) must not import matplotlib.
    from . import plotting

    return plotting.plot_triangulateio(ax, tio, voronoi, circumcircles, **options)


def plot_in_out(triin: TriangulateIO, triout: TriangulateIO, voronoi: Optional[TriangulateIO] = None, circumcircles: bool = False, **options: Any) -> Any:
    """Input and output side by side in a new figure: see :func:`triangle_rs.plotting.plot_in_out`."""
    from . import plotting

    return plotting.plot_in_out(triin, triout, voronoi, circumcircles, **options)
