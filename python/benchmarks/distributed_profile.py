"""Where the time of ``triangle_rs.distributed.delaunay`` goes (issue 39, point 1).

Runs the benchmark's input (``distributed_bench.points``, uniform, seed 23) on a
``LocalCluster(n_workers=2, threads_per_worker=1)`` with the workers instrumented (the task
functions and the library call wrapped with timers, nothing else changed: the fingerprint is
checked against the single call's), and prints one JSON record per size:

* per task kind (``tile_round``, ``answer``, ``add``, ``split_chunk``, ...): calls, wall, process
  CPU (user/sys), minor page faults, output bytes;
* inside ``tile_round``: the library call (``Library.triangulate``: the engine, its two threads
  included), the ctypes glue around it (``core.run`` minus the call: input struct, output
  arrays), and the numpy glue (the rest: merging own and imported points, sorting by index,
  owned triangles, circumdisks, hull edges);
* points handed to the engine in all (how many times each point is triangulated);
* Dask's task stream: tasks, compute time, transfers (count, bytes, time), disk reads/writes
  (spilling), and per worker the time it was idle during the run;
* each worker process's and the client process's (driver and scheduler) user and sys CPU,
  minor faults and peak RSS over the run; the single call's in a fresh subprocess beside it.

``--cprofile`` also runs cProfile around every task on the workers and prints the top
functions by cumulative time (slower: use for the shares, not the totals). ``--spill`` runs
with ``distributed.worker.memory.target`` at a few MB so that managed data is spilled.

Usage: ``PYTHONPATH=python:python/benchmarks python python/benchmarks/distributed_profile.py
--sizes 1e6``.
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

import distributed_bench as bench

_TASKS = ("chunk_summary", "off_line", "split_chunk", "piece", "gather_tile", "tile_stats", "in_rectangle",
          "nothing_imported", "first", "second", "tile_round", "answer", "add")


def _proc_stat(pid: str = "self") -> dict:
    """utime, stime (s), minor and major faults of a process, from /proc/<pid>/stat."""
    fields = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
    tick = os.sysconf("SC_CLK_TCK")
    return {"user": int(fields[11]) / tick, "sys": int(fields[12]) / tick,
            "minflt": int(fields[7]), "majflt": int(fields[9])}


def _hwm(pid: str = "self") -> int:
    for line in open(f"/proc/{pid}/status"):
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) * 1024
    return -1


def _nbytes(value: Any) -> int:
    if isinstance(value, np.ndarray):
        return value.nbytes
    if isinstance(value, (tuple, list)):
        return sum(_nbytes(v) for v in value)
    if isinstance(value, dict):
        return sum(_nbytes(v) for v in value.values())
    return 0


def _install(with_cprofile: bool) -> str:
    """Runs on each worker: wraps the task functions, ``core.run`` and ``Library.triangulate``
    with timers accumulating into ``tasks._profile`` (results unchanged)."""
    import cProfile
    import resource

    from triangle_rs import _library, core
    from triangle_rs.distributed import tasks

    profile: dict = {"tasks": {}, "engine": {}, "run": {}, "engine_points": 0, "engine_calls": 0,
                     "round_points": [], "cprofile": cProfile.Profile() if with_cprofile else None}
    tasks._profile = profile

    def usage() -> tuple:
        r = resource.getrusage(resource.RUSAGE_SELF)
        return time.perf_counter(), r.ru_utime, r.ru_stime, r.ru_minflt

    def add(into: dict, start: tuple, extra: int = 0) -> None:
        end = usage()
        into["calls"] = into.get("calls", 0) + 1
        for k, name in enumerate(("wall", "user", "sys", "minflt")):
            into[name] = into.get(name, 0) + end[k] - start[k]
        into["out_bytes"] = into.get("out_bytes", 0) + extra

    def wrap_task(name: str) -> None:
        inner = getattr(tasks, name)
        if getattr(inner, "_profiled", False):
            return

        def wrapped(*args, **kwargs):
            start = usage()
            prof = profile["cprofile"]
            if prof is not None:
                prof.enable()
            try:
                result = inner(*args, **kwargs)
            finally:
                if prof is not None:
                    prof.disable()
            add(profile["tasks"].setdefault(name, {}), start, _nbytes(result))
            if name == "tile_round":
                profile["round_points"].append((len(args[0][0]), len(args[1][0])))
            return result

        wrapped._profiled = True
        wrapped.__name__ = name
        setattr(tasks, name, wrapped)

    for name in _TASKS:
        wrap_task(name)

    inner_run = core.run
    if not getattr(inner_run, "_profiled", False):
        def run(switches, tio, **kwargs):
            start = usage()
            result = inner_run(switches, tio, **kwargs)
            add(profile["run"], start)
            return result

        run._profiled = True
        tasks.run = run  # the name tasks._local_delaunay calls

    inner_call = _library.Library.triangulate
    if not getattr(inner_call, "_profiled", False):
        def triangulate(self, switches, tin, *args, **kwargs):
            start = usage()
            result = inner_call(self, switches, tin, *args, **kwargs)
            add(profile["engine"], start)
            profile["engine_calls"] += 1
            profile["engine_points"] += int(tin.numberofpoints)
            return result

        triangulate._profiled = True
        _library.Library.triangulate = triangulate
    return "ok"


def _collect(top: int) -> dict:
    """Runs on each worker: the profile so far (and the cProfile's top functions)."""
    import io
    import pstats

    from triangle_rs.distributed import tasks

    profile = dict(tasks._profile)
    prof = profile.pop("cprofile")
    if prof is not None:
        text = io.StringIO()
        stats = pstats.Stats(prof, stream=text)
        stats.sort_stats("tottime").print_stats(top)
        stats.print_callees("tile_round")
        profile["cprofile_text"] = text.getvalue()
    profile["stat"] = _proc_stat()
    profile["hwm"] = _hwm()
    return profile


def _transfer_log(dask_worker) -> list:
    log = getattr(dask_worker, "transfer_incoming_log", None)
    if log is None:
        log = getattr(dask_worker.state, "transfer_incoming_log", [])
    return [{"total": e.get("total", 0), "duration": e.get("duration", 0.0), "keys": len(e.get("keys", ()))}
            for e in log]


def single_call(n: int) -> dict:
    """In a fresh subprocess: the single call on the same points, with its CPU and faults."""
    import triangle_rs

    xy = np.asarray(bench.points(n).compute(scheduler="synchronous"))
    before, cpu0, start = _proc_stat(), time.process_time(), time.perf_counter()
    triangles = triangle_rs.delaunay(xy)
    wall, cpu = time.perf_counter() - start, time.process_time() - cpu0
    after = _proc_stat()
    prints = [bench.fingerprint(triangles[k : k + (1 << 22)]) for k in range(0, len(triangles), 1 << 22)]
    return {"wall": wall, "cpu": cpu, "user": after["user"] - before["user"], "sys": after["sys"] - before["sys"],
            "minflt": after["minflt"] - before["minflt"], "triangles": len(triangles),
            "fingerprint": bench.combine(prints)}


def distributed_run(n: int, with_cprofile: bool, spill: bool, top: int) -> dict:
    import dask
    from distributed import Client, LocalCluster, get_task_stream

    from triangle_rs import distributed as dd

    config = {"distributed.worker.memory.pause": False, "distributed.worker.memory.target": 0.2,
              "distributed.worker.memory.spill": 0.55}
    limit: Any = "8GiB"
    if spill:  # managed data past ~20 MB goes to disk
        limit = 2 * 2**30
        config["distributed.worker.memory.target"] = 0.01
    with dask.config.set(config):
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, memory_limit=limit,
                               dashboard_address=None, processes=True)
        client = Client(cluster)
        try:
            client.run(_install, with_cprofile)
            workers_before = client.run(_proc_stat)
            nanny_pids = [w.process.process.pid for w in cluster.workers.values()]
            client_before = _proc_stat()
            rounds_at = []
            start = time.perf_counter()
            stream_t0 = time.time()
            with get_task_stream(client) as stream:
                result = dd.delaunay(bench.points(n), client,
                                     after_round=lambda k: rounds_at.append(time.perf_counter() - start))
                triangulated = time.perf_counter() - start
                blocks = result.triangles.to_delayed().ravel()
                prints = client.gather(client.compute([dask.delayed(bench.fingerprint)(b) for b in blocks]))
            wall = time.perf_counter() - start
            client_after = _proc_stat()
            profiles = client.run(_collect, top)
            transfers = client.run(_transfer_log)
            workers = {}
            for address, p in profiles.items():
                b = workers_before[address]
                p["delta"] = {k: p["stat"][k] - b[k] for k in b}
                workers[address] = p
            return {
                "n": n, "wall": wall, "wall_to_result": triangulated, "rounds": result.rounds,
                "round_ends": rounds_at, "tiles": result.tiles, "fingerprint": bench.combine(prints),
                "workers": workers, "transfers": transfers, "stream": list(stream.data), "stream_t0": stream_t0,
                "client": {k: client_after[k] - client_before[k] for k in client_before},
                "nanny_pids": nanny_pids,
            }
        finally:
            client.close()
            cluster.close()


def summarize(one: dict, two: dict) -> dict:
    """The breakdown: sums over the workers, the task stream, the transfers."""
    n = two["n"]
    kinds: dict = {}
    engine: dict = {}
    run: dict = {}
    points = calls = 0
    round_points = []
    for p in two["workers"].values():
        for name, t in p["tasks"].items():
            k = kinds.setdefault(name, {})
            for key, v in t.items():
                k[key] = k.get(key, 0) + v
        for into, src in ((engine, p["engine"]), (run, p["run"])):
            for key, v in src.items():
                into[key] = into.get(key, 0) + v
        points += p["engine_points"]
        calls += p["engine_calls"]
        round_points += p["round_points"]
    tr = kinds.get("tile_round", {})
    cpu = lambda d: d.get("user", 0) + d.get("sys", 0)  # noqa: E731
    # The stream: per action, and compute per task prefix.
    actions: dict = {}
    compute_by_worker: dict = {}
    for rec in two["stream"]:
        for ss in rec.get("startstops", ()):
            a = actions.setdefault(ss["action"], {"count": 0, "seconds": 0.0})
            a["count"] += 1
            a["seconds"] += ss["stop"] - ss["start"]
            if ss["action"] in ("compute", "transfer", "disk-read", "disk-write", "deserialize"):
                w = rec.get("worker")
                compute_by_worker[w] = compute_by_worker.get(w, 0.0) + ss["stop"] - ss["start"]
    transfers = [e for log in two["transfers"].values() for e in log]
    # Compute per task prefix, and when each prefix ran (seconds from the run's start).
    t0 = two["stream_t0"]
    prefixes: dict = {}
    for rec in two["stream"]:
        prefix = str(rec["key"][0] if isinstance(rec["key"], tuple) else rec["key"]).rsplit("-", 1)[0]
        for ss in rec.get("startstops", ()):
            if ss["action"] != "compute":
                continue
            p = prefixes.setdefault(prefix, {"count": 0, "seconds": 0.0, "first": 1e9, "last": 0.0})
            p["count"] += 1
            p["seconds"] += ss["stop"] - ss["start"]
            p["first"] = min(p["first"], ss["start"] - t0)
            p["last"] = max(p["last"], ss["stop"] - t0)
    wall = two["wall"]
    workers_cpu = sum(p["delta"]["user"] + p["delta"]["sys"] for p in two["workers"].values())
    return {
        "n": n,
        "single": {"wall": one["wall"], "cpu": one["cpu"], "user": one["user"], "sys": one["sys"],
                   "minflt": one["minflt"]},
        "same_set": tuple(one["fingerprint"]) == tuple(two["fingerprint"]),
        "wall": wall, "wall_to_result": two["wall_to_result"], "rounds": two["rounds"],
        "round_ends": [round(t, 2) for t in two["round_ends"]], "tiles": two["tiles"],
        "workers_cpu": workers_cpu,
        "workers_user": sum(p["delta"]["user"] for p in two["workers"].values()),
        "workers_sys": sum(p["delta"]["sys"] for p in two["workers"].values()),
        "workers_minflt": sum(p["delta"]["minflt"] for p in two["workers"].values()),
        "workers_hwm_mb": [round(p["hwm"] / 2**20) for p in two["workers"].values()],
        "client_cpu": two["client"]["user"] + two["client"]["sys"], "client": two["client"],
        "engine": {"calls": calls, "points": points, "times_each_point": points / n, **engine},
        "run_glue_cpu": cpu(run) - cpu(engine),
        "run_glue_wall": run.get("wall", 0) - engine.get("wall", 0),
        "tile_round_numpy_cpu": cpu(tr) - cpu(run), "tile_round_numpy_wall": tr.get("wall", 0) - run.get("wall", 0),
        "tile_round_calls_points": round_points,
        "tasks": {name: {k: (round(v, 3) if isinstance(v, float) else v) for k, v in t.items()}
                  for name, t in sorted(kinds.items(), key=lambda kv: -kv[1].get("wall", 0))},
        "tasks_cpu_total": sum(cpu(t) for t in kinds.values()),
        "stream": {"tasks": len(two["stream"]), **{a: {"count": v["count"], "seconds": round(v["seconds"], 3)}
                                                     for a, v in actions.items()}},
        "by_prefix": {k: {a: round(b, 3) for a, b in v.items()} for k, v in sorted(prefixes.items(), key=lambda kv: kv[1]["first"])},
        "worker_busy": {str(w): round(s, 2) for w, s in compute_by_worker.items()},
        "transfers": {"count": len(transfers), "keys": sum(e["keys"] for e in transfers),
                      "bytes": sum(e["total"] for e in transfers),
                      "seconds": round(sum(e["duration"] for e in transfers), 3)},
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", nargs="+", type=float, default=[1e6])
    parser.add_argument("--cprofile", action="store_true")
    parser.add_argument("--spill", action="store_true")
    parser.add_argument("--top", type=int, default=25)
    parser.add_argument("--single-only", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.single_only:
        print(json.dumps(single_call(args.single_only)))
        return
    for size in args.sizes:
        n = int(size)
        out = subprocess.run([sys.executable, __file__, "--single-only", str(n)], check=True,
                             capture_output=True, text=True).stdout
        one = json.loads(out.strip().splitlines()[-1])
        two = distributed_run(n, args.cprofile, args.spill, args.top)
        print(json.dumps(summarize(one, two), indent=1, default=str), flush=True)
        if args.cprofile:
            for address, p in two["workers"].items():
                print(f"--- cProfile, worker {address} ---")
                print(p.get("cprofile_text", ""))


if __name__ == "__main__":
    main()
