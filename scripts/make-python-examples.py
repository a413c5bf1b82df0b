"""Writes the examples of this project's own making that ``triangle_rs.get_data`` falls back to
when the PyPI ``triangle`` package (whose data directory holds Triangle's example files) is not
installed: python/triangle_rs/data/. Same names as the examples the PyPI package's documentation
scripts use, geometry drawn for this project (no file of Triangle's is copied or derived).

Run from the repository: .venv/bin/python scripts/make-python-examples.py
(The meshes ``*.1.*`` are made with triangle-rs itself, so they follow the library in use.)
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

REPOSITORY = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPOSITORY / "python"))

import triangle_rs  # noqa: E402

OUT = REPOSITORY / "python" / "triangle_rs" / "data"
HEADER = "# triangle-rs example of its own making (scripts/make-python-examples.py)\n"


def number(value: float) -> str:
    return repr(float(value)) if value != int(value) else str(int(value))


def node_lines(vertices, markers=None, attributes=None) -> str:
    vertices = np.asarray(vertices, dtype=float)
    attributes = np.empty((len(vertices), 0)) if attributes is None else np.asarray(attributes, dtype=float).reshape(len(vertices), -1)
    lines = [f"{len(vertices)} 2 {attributes.shape[1]} {0 if markers is None else 1}"]
    for i, (x, y) in enumerate(vertices):
        row = [str(i + 1), number(x), number(y)] + [number(a) for a in attributes[i]]
        if markers is not None:
            row.append(str(int(np.ravel(markers)[i])))
        lines.append(" ".join(row))
    return "\n".join(lines) + "\n"


def write(name: str, text: str) -> None:
    (OUT / name).write_text(HEADER + text)


def write_poly(name: str, d: dict, *, with_vertices: bool = True) -> None:
    text = node_lines(d["vertices"], d.get("vertex_markers")) if with_vertices else "0 2 0 1\n"
    segments = np.asarray(d.get("segments", np.empty((0, 2))), dtype=int)
    markers = d.get("segment_markers")
    text += f"{len(segments)} {0 if markers is None else 1}\n"
    for i, (a, b) in enumerate(segments):
        text += f"{i + 1} {a + 1} {b + 1}" + (f" {int(np.ravel(markers)[i])}" if markers is not None else "") + "\n"
    holes = np.asarray(d.get("holes", np.empty((0, 2))), dtype=float)
    text += f"{len(holes)}\n" + "".join(f"{i + 1} {number(x)} {number(y)}\n" for i, (x, y) in enumerate(holes))
    regions = np.asarray(d.get("regions", np.empty((0, 4))), dtype=float)
    if len(regions):
        text += f"{len(regions)}\n" + "".join(
            f"{i + 1} {' '.join(number(v) for v in row)}\n" for i, row in enumerate(regions)
        )
    write(name + ".poly", text)


def write_mesh(name: str, d: dict) -> None:
    write(name + ".node", node_lines(d["vertices"], d.get("vertex_markers")))
    triangles = d["triangles"]
    write(name + ".ele", f"{len(triangles)} 3 0\n" + "".join(f"{i + 1} {a + 1} {b + 1} {c + 1}\n" for i, (a, b, c) in enumerate(triangles)))


def closed_loop(first: int, count: int) -> list[tuple[int, int]]:
    return [(first + k, first + (k + 1) % count) for k in range(count)]


def circle(count: int, radius: float, centre=(0.0, 0.0), phase: float = 0.0) -> np.ndarray:
    angles = phase + 2 * np.pi * np.arange(count) / count
    return np.column_stack([centre[0] + radius * np.cos(angles), centre[1] + radius * np.sin(angles)])


def letter_a() -> dict:
    # An "A": outline with a crossbar, and a triangular counter (a hole).
    outline = [(0, 0), (1, 0), (1.3, 1), (2.7, 1), (3, 0), (4, 0), (2.5, 5), (1.5, 5)]
    counter = [(1.6, 2), (2.4, 2), (2, 3.3)]
    vertices = np.array(outline + counter, dtype=float)
    return {
        "vertices": vertices,
        "vertex_markers": np.ones(len(vertices), dtype=int),
        "segments": np.array(closed_loop(0, 8) + closed_loop(8, 3)),
        "segment_markers": np.array([1] * 8 + [2] * 3),
        "holes": np.array([[2.0, 2.5]]),
    }


def framed_box() -> dict:
    outer = [(0, 0), (3, 0), (3, 3), (0, 3)]
    inner = [(1, 1), (2, 1), (2, 2), (1, 2)]
    loose = [(0.5, 2.5), (2.5, 0.5)]
    vertices = np.array(outer + inner + loose, dtype=float)
    return {
        "vertices": vertices,
        "vertex_markers": np.array([1] * 4 + [2] * 4 + [0] * 2),
        "segments": np.array(closed_loop(0, 4) + closed_loop(4, 4)),
        "segment_markers": np.array([1] * 4 + [2] * 4),
        "holes": np.array([[1.5, 1.5]]),
    }


def face() -> dict:
    head = circle(28, 100.0)
    eyes = [circle(6, 12.0, centre, np.pi / 6) for centre in ((-35.0, 30.0), (35.0, 30.0))]
    mouth = np.array([(-50, -30), (-25, -48), (0, -54), (25, -48), (50, -30)], dtype=float)
    nose = np.array([(0.0, 5.0)])
    vertices = np.vstack([head, *eyes, mouth, nose])
    segments = closed_loop(0, 28) + closed_loop(28, 6) + closed_loop(34, 6) + [(40 + k, 41 + k) for k in range(4)]
    markers = [1] * 28 + [2] * 12 + [3] * 4
    return {
        "vertices": vertices,
        "vertex_markers": np.array([1] * 28 + [2] * 12 + [3] * 5 + [0]),
        "segments": np.array(segments),
        "segment_markers": np.array(markers),
        "holes": np.array([[-35.0, 30.0], [35.0, 30.0]]),
    }


def layers() -> dict:
    # A cross-section through layered ground: four layers with wavy interfaces, each a region
    # with its own attribute and maximum area (five numbers a line, as Triangle documents).
    xs = np.linspace(0, 40, 9)
    depths = [0.0, -2.0, -5.0, -9.0, -12.0]
    rows = [np.column_stack([xs, d + (0.4 * np.sin(xs / 5 + k) if 0 < k < 4 else 0 * xs)]) for k, d in enumerate(depths)]
    vertices = np.vstack(rows)
    n = len(xs)
    segments = []
    for k in range(len(depths)):
        segments += [(k * n + i, k * n + i + 1) for i in range(n - 1)]
    for k in range(len(depths) - 1):
        segments += [(k * n, (k + 1) * n), (k * n + n - 1, (k + 1) * n + n - 1)]
    regions = [(20.0, (depths[k] + depths[k + 1]) / 2, k + 1, area) for k, area in enumerate([0.5, 1.0, 2.0, 4.0])]
    return {"vertices": vertices, "segments": np.array(segments), "regions": np.array(regions, dtype=float)}


def main() -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(2026)

    write_poly("A", letter_a())
    write_poly("box", framed_box())
    shape = face()
    write_poly("face", shape)
    meshed = triangle_rs.triangulate(shape, "pq25a300")
    write_mesh("face.1", meshed)
    write_poly("face.1", {k: meshed[k] for k in ("segments", "segment_markers", "holes")}, with_vertices=False)
    write_poly("la", layers())

    dots = rng.uniform(-0.9, 0.9, size=(60, 2))
    write("dots.node", node_lines(dots))
    turns = np.linspace(0.5, 4 * np.pi, 40)
    write("spiral.node", node_lines(np.column_stack([0.3 * turns * np.cos(turns), 0.3 * turns * np.sin(turns)])))

    # bbox.1: a coarse mesh of the 3 x 3 box with a maximum area per triangle (the .area file).
    box = triangle_rs.triangulate({"vertices": [[0, 0], [3, 0], [3, 3], [0, 3], [1.2, 1.7], [2.1, 0.9]]})
    write_mesh("bbox.1", box)
    areas = np.where(box["vertices"][box["triangles"]].mean(axis=1)[:, 0] < 1.5, 0.1, -1.0)
    write("bbox.1.area", f"{len(areas)}\n" + "".join(f"{i + 1} {number(a)}\n" for i, a in enumerate(areas)))

    # A diamond of points (a rotated lattice, slightly perturbed) and its Voronoi diagram.
    u, v = np.meshgrid(np.arange(-2, 3), np.arange(-2, 3))
    diamond = np.column_stack([(u - v).ravel(), (u + v).ravel()]) * 0.1 + 0.5 + rng.uniform(-0.01, 0.01, size=(25, 2))
    write("diamond_02_00009.node", node_lines(diamond))
    points, edges, ray_origins, ray_directions = triangle_rs.voronoi(diamond)
    write("diamond_02_00009.1.v.node", node_lines(points))
    lines = [f"{len(edges) + len(ray_origins)} 0"]
    lines += [f"{i + 1} {a + 1} {b + 1}" for i, (a, b) in enumerate(edges)]
    lines += [
        f"{len(edges) + i + 1} {o + 1} -1 {number(dx)} {number(dy)}" for i, (o, (dx, dy)) in enumerate(zip(ray_origins, ray_directions))
    ]
    write("diamond_02_00009.1.v.edge", "\n".join(lines) + "\n")

    ell = triangle_rs.triangulate({"vertices": [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], "segments": closed_loop(0, 6)}, "pq30a0.2")
    write_mesh("ell", ell)


if __name__ == "__main__":
    main()
