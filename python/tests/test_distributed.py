"""Tile and merge on Dask (``triangle_rs.distributed``): the same triangle set as the single call.

Each test compares the distributed result, computed on a ``LocalCluster`` of two worker
processes that the module starts and stops itself, with one ``triangle_rs.delaunay`` call on
all the points: as sets of triangles (corners sorted), with every triangle counter-clockwise
and each given once. Inputs: uniform, clustered, lattices (cocircular everywhere: ties), heavy
duplicates, more tiles than points can fill, and the bad inputs of the single call; a worker
killed mid-run; the writers and the readers of chunk directories.
"""

import os
import warnings

import numpy as np
import pytest

dask = pytest.importorskip("dask", reason="the [distributed] extra (dask, distributed, scipy)")
import dask.array as da  # noqa: E402
from distributed import Client, LocalCluster  # noqa: E402

import triangle_rs  # noqa: E402
from triangle_rs import TriangulateError  # noqa: E402
from triangle_rs import distributed as dd  # noqa: E402


@pytest.fixture(scope="module")
def client():
    cluster = LocalCluster(
        n_workers=2, threads_per_worker=1, memory_limit="2GiB", dashboard_address=None, processes=True
    )
    client = Client(cluster)
    yield client
    client.close()
    cluster.close()


def triangle_set(triangles: np.ndarray) -> set:
    return set(map(tuple, np.sort(np.asarray(triangles, dtype=np.int64), axis=1).tolist()))


def single(points: np.ndarray) -> np.ndarray:
    return triangle_rs.delaunay(points[:, :2])


def assert_same_as_single_call(points: np.ndarray, result: "dd.DistributedTriangulation") -> None:
    ours = np.asarray(result.triangles.compute())
    reference = single(points)
    assert len(ours) == len(triangle_set(ours)), "a triangle is given twice"
    xy = points[:, :2]
    xy = xy / 2.0 ** np.frexp(np.abs(xy).max())[1]  # exact: no product overflows or vanishes
    a, b, c = xy[ours[:, 0]], xy[ours[:, 1]], xy[ours[:, 2]]
    orientation = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    assert (orientation > 0).all(), "a triangle is not counter-clockwise"
    assert triangle_set(ours) == triangle_set(reference)


def lattice(rows: int, columns: int, *, step=(1.0, 1.0), shear=0.0, origin=(0.0, 0.0)) -> np.ndarray:
    i, j = np.meshgrid(np.arange(columns), np.arange(rows))
    x = origin[0] + step[0] * i + shear * j
    y = origin[1] + step[1] * j
    return np.column_stack([x.ravel(), y.ravel()]).astype(np.float64)


RNG = np.random.default_rng(23)


@pytest.mark.parametrize(
    "name, points, tiles",
    [
        ("uniform 10^4", RNG.random((10_000, 2)), 4),
        ("uniform 10^5", RNG.random((100_000, 2)), 9),
        (
            "clustered 10^5",
            np.concatenate([RNG.normal(0.3, 0.002, (60_000, 2)), RNG.normal(0.7, 0.05, (30_000, 2)), RNG.random((10_000, 2))]),
            9,
        ),
        ("square lattice 300x300", lattice(300, 300), 9),
        ("sheared lattice (cocircular rows)", lattice(120, 200, step=(0.5, 0.25), shear=0.25, origin=(1e3, -7.0)), 6),
        ("duplicates (coordinates on a 1/64 grid)", np.round(RNG.random((100_000, 2)) * 64) / 64, 9),
        ("concentric circles", np.concatenate([
            np.column_stack([r * np.cos(t), r * np.sin(t)])
            for r in (1.0, 2.0, 3.0, 4.0)
            for t in [np.linspace(0, 2 * np.pi, 96, endpoint=False)]
        ]), 4),
        ("more tiles than points fill", RNG.random((40, 2)), 16),
        ("far from the origin", 1e7 + RNG.random((20_000, 2)), 4),
        # Magnitudes where products of coordinates overflow or vanish in floating point.
        ("huge coordinates (10^300)", RNG.random((20_000, 2)) * 1e300, 9),
        ("tiny coordinates (10^-300)", RNG.random((20_000, 2)) * 1e-300, 9),
        ("a strip 10^-9 thin", np.column_stack([RNG.random(10_000), RNG.random(10_000) * 1e-9]), 9),
        ("two clusters 10^6 apart", np.concatenate([RNG.random((3000, 2)), RNG.random((3000, 2)) + 1e6]), 9),
        ("nearly collinear (10^-12 off a line)", np.column_stack([np.arange(3000.0), (np.arange(3000) % 2) * 1e-12]), 9),
    ],
    ids=lambda v: v if isinstance(v, str) else "",
)
def test_same_triangles_as_the_single_call(client, name, points, tiles):
    chunks = max(1, len(points) // 5)
    result = dd.delaunay(da.from_array(points, chunks=(chunks, 2)), client, tiles=tiles)
    assert result.tiles >= 1
    assert_same_as_single_call(points, result)


def test_a_million_points_on_two_workers(client):
    points = da.random.default_rng(7).random((1_000_000, 2), chunks=(250_000, 2))
    result = dd.delaunay(points, client, tiles=8)
    assert_same_as_single_call(points.compute(), result)


def test_duplicates_are_counted_without_a_warning(client):
    # As in the single call: ignored silently (Triangle does so under Q), counted on the result.
    points = np.concatenate([RNG.random((1000, 2)), RNG.random((1000, 2))[:10]])
    points = np.concatenate([points, points[:25]])
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        result = dd.delaunay(points, client, tiles=4)
    assert not [w for w in record if issubclass(w.category, RuntimeWarning)], [str(w.message) for w in record]
    assert result.duplicates == 25
    assert_same_as_single_call(points, result)


def test_bad_inputs_are_refused_as_by_the_single_call(client):
    points = RNG.random((1000, 2))
    points[617, 1] = np.nan
    with pytest.raises(TriangulateError, match="617"):
        dd.delaunay(points, client)
    points[617, 1] = np.inf
    with pytest.raises(TriangulateError, match="NaN or infinite"):
        dd.delaunay(points, client)
    with pytest.raises(TriangulateError, match="three"):
        dd.delaunay(np.array([[0.0, 0.0], [1.0, 1.0]]), client)
    with pytest.raises(TriangulateError, match="shape"):
        dd.delaunay(np.zeros((5, 1)), client)


def test_collinear_points_give_no_triangle_as_the_single_call(client):
    t = RNG.permutation(2000).astype(np.float64)  # exactly on one line (small integers)
    points = np.column_stack([3 * t + 1, -2 * t - 2])
    assert len(single(points)) == 0
    result = dd.delaunay(points, client, tiles=4)
    assert result.triangles.compute().shape == (0, 3)
    # One point off the line: triangles, the same as the single call's.
    points[1000] += [0.0, 0.5]
    assert_same_as_single_call(points, dd.delaunay(points, client, tiles=4))


def test_tiles_with_points_on_a_line_widen_their_halo(client):
    # A column of collinear points in each tile's middle, and a few points elsewhere.
    line = np.column_stack([np.full(500, 0.5), np.linspace(0, 1, 500)])
    points = np.concatenate([line, [[0.1, 0.1], [0.9, 0.9], [0.05, 0.95]]])
    assert_same_as_single_call(points, dd.delaunay(points, client, tiles=4))


def test_attributes_are_carried_and_written(client, tmp_path):
    points = np.column_stack([RNG.random((3000, 2)), np.arange(3000.0)])
    result = dd.delaunay(da.from_array(points, chunks=(700, 3)), client, tiles=4)
    assert_same_as_single_call(points, result)
    node, ele = result.to_triangle_files(str(tmp_path / "mesh"))
    mesh = triangle_rs.load(str(tmp_path), "mesh")
    assert np.array_equal(mesh["vertices"], points[:, :2])
    assert np.array_equal(mesh["vertex_attributes"].ravel(), points[:, 2])
    assert triangle_set(mesh["triangles"]) == triangle_set(single(points))
    paths = result.to_npy(str(tmp_path / "blocks"))
    assert triangle_set(np.concatenate([np.load(p) for p in paths])) == triangle_set(single(points))


def test_a_directory_of_npy_chunks(client, tmp_path):
    points = RNG.random((20_000, 2))
    for k, chunk in enumerate(np.array_split(points, 7)):
        np.save(tmp_path / f"part-{k:03d}.npy", chunk)
    result = dd.delaunay(str(tmp_path), client, tiles=4)
    assert_same_as_single_call(points, result)


def test_a_worker_killed_mid_run_loses_nothing():
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, memory_limit="2GiB", dashboard_address=None)
    client = Client(cluster)
    try:
        points = da.random.default_rng(11).random((200_000, 2), chunks=(50_000, 2))
        killed = []

        def kill_one(round_number: int) -> None:
            if round_number == 1 and not killed:
                victim = sorted(client.scheduler_info()["workers"])[0]
                killed.append(victim)
                try:
                    client.run(os._exit, 1, workers=[victim])
                except Exception:
                    pass  # the worker died before it could answer

        result = dd.delaunay(points, client, tiles=6, after_round=kill_one)
        assert killed
        assert_same_as_single_call(points.compute(), result)
    finally:
        client.close()
        cluster.close()


def test_tiles_for_memory_fits_one_tile_in_a_worker():
    # No cluster needed: the planner is arithmetic on the documented per-point costs.
    limit = 2 * 2**30
    tiles = dd.tiles_for_memory(10_000_000, limit, workers=2)
    points_per_tile = 10_000_000 / tiles * 1.25
    assert dd._WORKER_BASELINE_BYTES + points_per_tile * dd._BYTES_PER_TILE_POINT <= 0.95 * limit
    assert dd.tiles_for_memory(10_000_000, limit // 5, workers=2) > tiles
    assert dd.tiles_for_memory(100, limit, workers=3) == 3  # at least one tile per worker
    with pytest.raises(ValueError, match="no room"):
        dd.tiles_for_memory(10_000, 100 * 2**20)


def test_memory_per_worker_chooses_the_tile_count(client):
    points = RNG.random((20_000, 2))
    limit = int((dd._WORKER_BASELINE_BYTES + 2**20) / 0.85) + 1  # 1 MB of room: many tiles
    result = dd.delaunay(points, client, memory_per_worker=limit)
    assert result.tiles >= dd.tiles_for_memory(len(points), limit, 2)  # a grid of columns x rows
    assert result.tiles > 4
    assert_same_as_single_call(points, result)


@pytest.mark.parametrize("shape", ["uniform", "clustered", "a line", "one place"])
def test_the_grid_finds_every_point_in_every_disk(shape):
    # No cluster needed: the tile's grid against a brute-force distance test.
    from triangle_rs.distributed.grid import grid_order, points_in_disks

    rng = np.random.default_rng(5)
    xy = {
        "uniform": rng.random((5000, 2)),
        "clustered": np.concatenate([rng.normal(0.5, 1e-4, (4000, 2)), rng.random((1000, 2))]),
        "a line": np.column_stack([np.linspace(0, 1, 5000), np.full(5000, 0.25)]),
        "one place": np.full((50, 2), 0.5),
    }[shape]
    order, grid = grid_order(xy)
    xy = xy[order]
    disks = np.column_stack([rng.random(400) * 1.4 - 0.2, rng.random(400) * 1.4 - 0.2, rng.random(400) ** 3])
    disks = np.concatenate([disks, [[0.5, 0.5, 0.0], [0.5, 0.25, 1e-9], [0.0, 0.0, np.inf], [0.5, 0.5, 10.0]]])
    found = set(points_in_disks(xy, grid, disks).tolist())
    finite = disks[np.isfinite(disks[:, 2])]
    d2 = ((xy[:, None, :] - finite[None, :, :2]) ** 2).sum(axis=2)
    expected = set(np.flatnonzero((d2 <= finite[None, :, 2] ** 2).any(axis=1)).tolist())
    assert found == expected


def test_the_hull_hint_holds_every_hull_vertex():
    from triangle_rs.distributed.tasks import _hull_positions

    rng = np.random.default_rng(6)
    for xy in (rng.random((3000, 2)), rng.normal(size=(3000, 2)), lattice(20, 30)):
        hull = set(_hull_positions(xy).tolist())
        # A point is a hull vertex when some direction makes it the unique farthest one.
        for angle in np.linspace(0, 2 * np.pi, 720, endpoint=False):
            reach = xy @ np.array([np.cos(angle), np.sin(angle)])
            top = np.flatnonzero(reach == reach.max())
            if len(top) == 1:
                assert int(top[0]) in hull
