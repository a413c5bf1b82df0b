"""The lecture examples script (the README's main job) runs and writes non-empty PNGs."""

import os
import re
import subprocess
import sys
from pathlib import Path

import meshio
import numpy as np
from matplotlib.image import imread

import triangle_rs

PYTHON_DIR = Path(__file__).resolve().parent.parent
SCRIPT = PYTHON_DIR / "examples" / "lecture_examples.py"

sys.path.insert(0, str(SCRIPT.parent))
import lecture_examples  # noqa: E402


def test_the_examples_cover_the_lecture():
    switches = {e.name: e.switches for e in lecture_examples.EXAMPLES}
    assert switches["convex_hull"] == "Q" and switches["convex_hull_with_boundary"] == "cQ"
    assert switches["convex_hull_voronoi"] == "vQ" and switches["convex_hull_voronoi_delaunay"] == "vcDQ"
    assert switches["domain_cdt"] == "pQ" and switches["domain_cdt_area"] == "pa0.05Q"
    assert switches["domain_bcdt_area"] == "pa0.05DQ" and switches["domain_localref"] == "pauq20.0Q"
    assert switches["domain_regions"] == "paAq20.0Q"
    assert "domain_holes" in switches and len(switches) == 12


def test_local_refinement_test_is_finer_near_the_centre():
    unsuitable = lecture_examples.refine_near(0.8, 0.6)
    near = (0.79, 0.59, 0.81, 0.59, 0.8, 0.61)
    far = (0.0, 0.0, 0.1, 0.0, 0.0, 0.1)
    assert unsuitable(*near, 0.001)
    assert not unsuitable(*far, 0.005)


def test_local_refinement_example_is_finer_near_the_centre():
    example = next(e for e in lecture_examples.EXAMPLES if e.name == "domain_localref")
    triin = example.make_input(np.random.default_rng(0))
    out, _ = triangle_rs.triangulate(example.switches, triin, unsuitable=example.unsuitable)
    corners = out.pointlist[out.trianglelist[:, :3]]
    centroids = corners.mean(axis=1)
    areas = 0.5 * np.abs(
        (corners[:, 1, 0] - corners[:, 0, 0]) * (corners[:, 2, 1] - corners[:, 0, 1])
        - (corners[:, 1, 1] - corners[:, 0, 1]) * (corners[:, 2, 0] - corners[:, 0, 0])
    )
    distance = np.hypot(centroids[:, 0] - 0.8, centroids[:, 1] - 0.6)
    near, far = areas[distance < 0.1], areas[distance > 0.4]
    assert len(near) > 0 and len(far) > 0
    assert near.max() < far.mean() / 10, (near.max(), far.mean())
    # The callback's rule holds for every output triangle (the refinement ran to the end).
    for c, area in zip(corners, areas):
        assert not example.unsuitable(*c.reshape(-1), area)


def test_script_writes_one_png_per_example(tmp_path):
    env = {**os.environ, "PYTHONPATH": str(PYTHON_DIR), "MPLBACKEND": "Agg"}
    result = subprocess.run(
        [sys.executable, str(SCRIPT), str(tmp_path / "results")],
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    lines = {line.split(" ", 1)[0]: line for line in result.stdout.splitlines()}
    for example in lecture_examples.EXAMPLES:
        line = lines[example.name]
        png = tmp_path / "results" / f"{example.name}.png"
        assert "failed:" not in line and line.endswith(str(png)), line
        assert png.stat().st_size > 10_000, line
        image = imread(png)
        assert (image[..., :3].sum(axis=2) < 2.0).mean() > 0.005, f"{png} looks blank"
    assert sorted(p.name for p in (tmp_path / "results").iterdir()) == sorted(
        [f"{e.name}.png" for e in lecture_examples.EXAMPLES] + ["domain_regions.vtu"]
    )
    vtu = meshio.read(tmp_path / "results" / "domain_regions.vtu")
    assert vtu.cells[0].type == "triangle" and len(vtu.cells[0].data) > 10
    assert set(np.unique(vtu.cell_data["triangle_attribute_0"][0])) == {1.0, 2.0}
    assert re.search(rf"^{len(lecture_examples.EXAMPLES)} PNGs written .*, 0 examples failed", result.stdout.splitlines()[-1])


def test_script_exits_with_an_error_when_an_example_fails(tmp_path, monkeypatch, capsys):
    broken = lecture_examples.EXAMPLES[0]._replace(switches="Qa0")  # a0: refused by the library
    monkeypatch.setattr(lecture_examples, "EXAMPLES", [broken])
    assert lecture_examples.main([str(tmp_path)]) == 1
    assert "failed:" in capsys.readouterr().out
    assert not list(tmp_path.iterdir())
