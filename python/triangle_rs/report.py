"""What a call says besides its mesh: the library's warning lines (``triangulate_last_warning``,
one per line), sorted into *notes* and *problems*.

* **Notes** are what Triangle does silently under ``Q`` and tells only without it: a duplicate
  vertex ignored, a segment whose two endpoints are one vertex skipped, a passing ``C`` check.
  The mesh is the one asked for. They are never a Python warning: ``V`` in the switches prints
  them, counted (``VV``: every line), to stdout, and :func:`last_report` keeps them.
* **Problems** change the result asked for: a quality bound not reached (an angle above the
  guarantee, the precision of the coordinates exhausted, bad triangles left by ``Y``), the ``S``
  budget of Steiner points spent short of the bounds, the runaway limit, a cancelled refinement, a
  failed ``C`` check. A call that has any warns once: one :class:`TriangulateWarning` (a
  ``RuntimeWarning``) that says them all, attributed to the caller's own line.

A line the library may add in a later version and this module does not know is a problem: better
one warning too many than a problem hidden.
"""

from __future__ import annotations

import sys
import threading
from typing import Optional

import numpy as np

#: The notes' first words (everything else is a problem).
DUPLICATE_VERTEX = "A duplicate vertex at ("
COINCIDENT_SEGMENT = "Endpoints of segment "
PASSING_CHECK = "Mesh check: the mesh appears to be consistent"
NOTE_PREFIXES = (DUPLICATE_VERTEX, COINCIDENT_SEGMENT, PASSING_CHECK)


class TriangulateWarning(RuntimeWarning):
    """The mesh a call returns is valid but falls short of what was asked (a quality bound not
    reached, a budget spent, refinement stopped). At most one per call, naming every problem."""


class Report:
    """What one call said besides its mesh (see the module docstring): :attr:`lines` (the
    library's, in order), sorted into :attr:`notes` and :attr:`problems`; :meth:`summary` counts
    the notes, one line per kind."""

    __slots__ = ("switches", "_text", "_extra", "_problems", "_notes")

    def __init__(self, switches: str, text: str, extra_problems: tuple[str, ...] = ()):
        #: The switches of the call, as passed to the library.
        self.switches = switches
        self._text = text
        self._extra = tuple(extra_problems)
        self._problems: Optional[tuple[str, ...]] = None
        self._notes: Optional[tuple[str, ...]] = None

    @property
    def lines(self) -> tuple[str, ...]:
        """Every line the library wrote (``triangulate_last_warning``), in order."""
        return tuple(self._text.split("\n")) if self._text else ()

    @property
    def problems(self) -> tuple[str, ...]:
        """What changed the result asked for: the text of the call's warning, one item a problem
        (the library's lines, then what this package found, e.g. the ``S`` budget)."""
        if self._problems is None:
            self._problems = library_problems(self._text) + self._extra
        return self._problems

    @property
    def notes(self) -> tuple[str, ...]:
        """What Triangle does silently under ``Q``, one library line each (uncounted)."""
        if self._notes is None:
            self._notes = tuple(line for line in self.lines if line.startswith(NOTE_PREFIXES))
        return self._notes

    @property
    def duplicate_vertices(self) -> int:
        """How many input vertices were ignored as duplicates of earlier ones."""
        return _count_lines(self._text, DUPLICATE_VERTEX)

    @property
    def skipped_segments(self) -> int:
        """How many input segments were skipped because their two endpoints are one vertex."""
        return _count_lines(self._text, COINCIDENT_SEGMENT)

    def summary(self) -> list[str]:
        """The notes counted, one line per kind (what ``V`` prints), e.g. ``"1,532 duplicate
        vertices were ignored; the first at (0.5, 0.25) (vertex 7 duplicates vertex 2)."``."""
        lines = []
        notes = self.notes
        duplicates = [line for line in notes if line.startswith(DUPLICATE_VERTEX)]
        if len(duplicates) == 1:
            lines.append(duplicates[0])
        elif duplicates:
            lines.append(f"{len(duplicates):,} duplicate vertices were ignored; the first {_duplicate_detail(duplicates[0])}")
        skipped = [line for line in notes if line.startswith(COINCIDENT_SEGMENT)]
        if len(skipped) == 1:
            lines.append(skipped[0])
        elif skipped:
            lines.append(
                f"{len(skipped):,} segments whose two endpoints are one vertex were skipped; the first: {skipped[0]}"
            )
        lines += [line for line in notes if line.startswith(PASSING_CHECK)]
        return lines

    def warning_message(self) -> str:
        """The text of the call's one warning ("" when it has no problem)."""
        return " ".join(self.problems)

    def __repr__(self) -> str:
        return f"Report(switches={self.switches!r}, notes={len(self.notes)}, problems={list(self.problems)!r})"


def _count_lines(text: str, prefix: str) -> int:
    if not text:
        return 0
    return text.count("\n" + prefix) + text.startswith(prefix)


def library_problems(text: str) -> tuple[str, ...]:
    """The library's lines that are not notes. Cheap when every line is a note (10,000
    duplicates): the lines are counted in C (``str.count``), never split."""
    if not text:
        return ()
    lines = text.count("\n") + 1
    notes = 0
    for prefix in NOTE_PREFIXES:  # duplicates first: usually the only notes, and the most
        notes += _count_lines(text, prefix)
        if notes == lines:
            return ()
    return tuple(line for line in text.split("\n") if line and not line.startswith(NOTE_PREFIXES))


def _duplicate_detail(line: str) -> str:
    """``at (x, y) (vertex i duplicates vertex j).`` from a duplicate's line."""
    head = "A duplicate vertex "
    middle = " appeared and was ignored "
    if line.startswith(head) and middle in line:
        where, why = line[len(head):].split(middle, 1)
        return f"{where} {why}"
    return f": {line}"


# --- The report of the last call, per thread ------------------------------------------------------

_last = threading.local()


def set_last_report(report: Optional[Report]) -> None:
    _last.report = report


def last_report() -> Optional[Report]:
    """The :class:`Report` of the last call made on this thread (``None`` before the first, and
    after a call that raised): its notes (duplicate vertices ignored, ...), counted by
    :meth:`Report.summary`, and its problems, the text of the warning it gave if any.

    >>> import triangle_rs
    >>> triangles = triangle_rs.delaunay([[0, 0], [1, 0], [0, 1], [0, 0]])
    >>> report = triangle_rs.last_report()
    >>> report.duplicate_vertices, report.problems
    (1, ())
    >>> report.summary()
    ['A duplicate vertex at (0, 0) appeared and was ignored (vertex 3 duplicates vertex 0).']
    """
    return getattr(_last, "report", None)


def print_notes(report: Report, verbosity: int) -> None:
    """``V``: the notes, counted, to stdout (Triangle prints its reports there); ``VV``: every line."""
    lines = report.notes if verbosity > 1 else report.summary()
    if lines:
        sys.stdout.write("".join(f"  {line}\n" for line in lines))


# --- The S budget -----------------------------------------------------------------------------------


class Switches:
    """What :func:`budget_shortfall` needs of a switch string, read as the library reads it:
    ``q``, ``a`` and ``S`` take the number that follows (digits and dots, then an optional
    exponent), ``o2`` is one switch, every other character a switch of its own."""

    def __init__(self, switches: str):
        self.letters: set[str] = set()
        self.min_angle: Optional[float] = None
        self.max_area: Optional[float] = None
        self.max_steiner: Optional[int] = None
        self.verbosity = 0
        #: Where the last ``S`` and its number are in the string (``None``: no ``S``).
        self.steiner_span: Optional[tuple[int, int]] = None
        i = 0
        while i < len(switches):
            c = switches[i]
            i += 1
            if c in "qaS":
                start = i - 1
                value, i = _number(switches, i)
                if c == "q":
                    self.min_angle = 20.0 if value is None else value
                elif c == "a" and value is not None:
                    self.max_area = value
                elif c == "S":
                    self.max_steiner = int(value) if value is not None and value > 0 else 0
                    self.steiner_span = (start, i)
            elif c == "o" and switches[i : i + 1] == "2":
                i += 1
            elif c == "V":
                self.verbosity += 1
            self.letters.add(c)


def _number(text: str, start: int) -> tuple[Optional[float], int]:
    """The number after a switch letter at ``text[start:]`` and the index after it (``None``: no
    number): the run of digits and dots, read to its longest decimal prefix, then an exponent
    (``e``, optional sign, digits) if the whole run was decimal."""
    end = start
    while end < len(text) and (text[end].isdigit() or text[end] == "."):
        end += 1
    if end == start:
        return None, start
    run = text[start:end]
    dot = run.find(".")
    if dot < 0:
        prefix = run
    else:
        digits = dot + 1
        while digits < len(run) and run[digits].isdigit():
            digits += 1
        prefix = run[:digits]
    if prefix == run and end < len(text) and text[end] in "eE":
        k = end + 1
        if k < len(text) and text[k] in "+-":
            k += 1
        digits_start = k
        while k < len(text) and text[k].isdigit():
            k += 1
        if k > digits_start:
            prefix, end = prefix + text[end:k], k
    mantissa = prefix.split("e")[0].split("E")[0]
    if not any(ch.isdigit() for ch in mantissa):
        return 0.0, end
    try:
        return float(prefix), end
    except ValueError:
        return 0.0, end


def budget_shortfall(switches: Switches, points: np.ndarray, triangles: np.ndarray, segments: np.ndarray) -> Optional[str]:
    """With ``S`` and ``q`` or ``a<area>``: whether the mesh misses those bounds, said as a
    problem (``None`` when it meets them, or there is no budget). The library does not say
    whether the budget stopped refinement, so this looks at the mesh: triangles with an angle
    below the minimum (except at a corner between two segments, which refinement never splits)
    or an area above the maximum. Regional areas and the test of ``u`` are not checked."""
    if switches.max_steiner is None or (switches.min_angle is None and switches.max_area is None):
        return None
    if len(triangles) == 0:
        return None
    corners = np.asarray(triangles)[:, :3].astype(np.int64)
    a, b, c = (points[corners[:, k]] for k in range(3))
    twice_area = np.abs((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
    found = []
    if switches.min_angle is not None and switches.min_angle > 0:
        # Edge k is opposite corner k; the smallest angle is opposite the shortest edge, and its
        # sine is twice the area over the product of the other two edges' lengths.
        lengths = np.stack(
            [np.hypot(*(b - c).T), np.hypot(*(c - a).T), np.hypot(*(a - b).T)], axis=1
        )
        shortest = np.argmin(lengths, axis=1)
        rows = np.arange(len(corners))
        others = lengths[rows, (shortest + 1) % 3] * lengths[rows, (shortest + 2) % 3]
        with np.errstate(divide="ignore", invalid="ignore"):
            sine = np.clip(twice_area / others, 0.0, 1.0)
        angle = np.degrees(np.arcsin(np.nan_to_num(sine)))
        bad = angle < switches.min_angle - 1e-6
        if np.any(bad) and len(segments):
            # Corners between two segments: both edges at the corner of the smallest angle.
            n = np.int64(len(points))
            seg = np.sort(np.asarray(segments, dtype=np.int64), axis=1)
            keys = np.unique(seg[:, 0] * n + seg[:, 1])
            apex = corners[rows, shortest]
            first, second = corners[rows, (shortest + 1) % 3], corners[rows, (shortest + 2) % 3]

            def is_segment(u: np.ndarray, v: np.ndarray) -> np.ndarray:
                return np.isin(np.minimum(u, v) * n + np.maximum(u, v), keys)

            bad &= ~(is_segment(apex, first) & is_segment(apex, second))
        count = int(np.count_nonzero(bad))
        if count:
            found.append(f"{count} triangle{'s have' if count > 1 else ' has'} an angle below {switches.min_angle:g}°")
    if switches.max_area is not None:
        count = int(np.count_nonzero(0.5 * twice_area > switches.max_area * (1 + 1e-12)))
        if count:
            found.append(f"{count} triangle{'s are' if count > 1 else ' is'} larger than the maximum area {switches.max_area:g}")
    if not found:
        return None
    return (
        f"The mesh falls short of the quality asked: {' and '.join(found)}; the S switch limits "
        f"refinement to {switches.max_steiner} Steiner points (the mesh is valid)."
    )
