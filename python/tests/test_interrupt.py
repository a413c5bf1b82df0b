"""Ctrl-C during a long refinement, as a user presses it: a real SIGINT from outside, into a child
Python process that is 2 s into an endless refinement (switch ``u`` with a callback that splits
every triangle). The binding must set the cancel flag, wait for the library to return, and only
then raise KeyboardInterrupt. Raising earlier leaves a daemon thread inside the library, and the
process then dies at exit with "FATAL: exception not rethrown" (SIGABRT, status 134).

The child sets Python's own SIGINT handler first: a process started from a shell that ignores
SIGINT (a background job, `nohup`) inherits SIG_IGN, and Python then leaves it ignored, so Ctrl-C
would never reach the code under test."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

PYTHON_DIR = Path(__file__).resolve().parent.parent

CHILD = r"""
import signal
import sys

# The handler under test, whatever the parent left (a background job inherits SIG_IGN).
signal.signal(signal.SIGINT, signal.default_int_handler)
import triangle_rs
from triangle_rs import TriangulateIO, triangulate
from triangle_rs._library import Library

state = {"inside": False, "calls": 0, "code": None}
real_triangulate = Library.triangulate

def watched_triangulate(self, *arguments):
    state["inside"] = True
    try:
        state["code"] = real_triangulate(self, *arguments)
        return state["code"]
    finally:
        state["inside"] = False

Library.triangulate = watched_triangulate

def split_everything(*_):
    state["calls"] += 1
    if state["calls"] == 1:
        print("refining", flush=True)
    return True

try:
    triangulate("Qu", TriangulateIO(pointlist=[[0, 0], [1, 0], [1, 1], [0, 1]]), unsuitable=split_everything)
except KeyboardInterrupt:
    # Raised only once the library has returned (the cancel flag stops the refinement early,
    # with a valid mesh and code 0).
    assert not state["inside"], "KeyboardInterrupt raised while the library still runs"
    assert state["code"] is not None, "the library never returned"
    print("interrupted after", state["calls"], "callbacks; library returned", state["code"], flush=True)
    sys.exit(0)
print("the refinement ended by itself", flush=True)
sys.exit(2)
"""


def interrupt_child_after(seconds: float) -> subprocess.CompletedProcess:
    environment = dict(os.environ, PYTHONPATH=str(PYTHON_DIR))
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=environment
    )
    try:
        first_line = child.stdout.readline()
        assert first_line == "refining\n", first_line + child.stderr.read()
        time.sleep(seconds)
        child.send_signal(signal.SIGINT)
        stdout, stderr = child.communicate(timeout=30)
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
    return subprocess.CompletedProcess(child.args, child.returncode, first_line + stdout, stderr)


@pytest.mark.skipif(not hasattr(signal, "SIGINT") or sys.platform.startswith("win"), reason="POSIX signals")
@pytest.mark.parametrize("attempt", [1, 2, 3])
def test_ctrl_c_two_seconds_into_an_endless_refinement_exits_cleanly(attempt):
    result = interrupt_child_after(2.0)
    assert result.returncode == 0, f"status {result.returncode}\n{result.stdout}\n{result.stderr}"
    assert "interrupted after" in result.stdout and "library returned" in result.stdout, result.stdout
    assert "FATAL" not in result.stderr, result.stderr
