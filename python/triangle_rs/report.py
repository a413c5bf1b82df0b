"""What a call says besides its mesh: the library's warning lines (``triangulate_last_warning``,
one per line), sorted into *notes* and *problems*.

* **Notes** are what Triangle does silently under ``Q`` and tells only without it: a duplicate
  vertex ignored, a segment whose two endpoints are one vertex skipped.
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

#: The notes' first words (everything else is a problem).
DUPLICATE_VERTEX = "A duplicate vertex at ("
COINCIDENT_SEGMENT = "Endpoints of segment "
NOTE_PREFIXES = (DUPLICATE_VERTEX, COINCIDENT_SEGMENT)


class TriangulateWarning(RuntimeWarning):
    """The mesh a call returns is valid but falls short of what was asked (a quality bound not
    reached, a budget spent, refinement stopped). At most one per call, naming every problem."""


class Report:
    """What one call said besides its mesh (see the module docstring): :attr:`lines` (the
    library's, in order), sorted into :attr:`notes` and :attr:`problems`; :meth:`summary` counts
    the notes, one line per kind."""

    __slots__ = ("switches", "_text", "_problems", "_notes")

    def __init__(self, switches: str, text: str):
        #: The switches of the call, as passed to the library.
        self.switches = switches
        self._text = text
        self._problems: Optional[tuple[str, ...]] = None
        self._notes: Optional[tuple[str, ...]] = None

    @property
    def lines(self) -> tuple[str, ...]:
        """Every line the library wrote (``triangulate_last_warning``), in order."""
        return tuple(self._text.split("\n")) if self._text else ()

    @property
    def problems(self) -> tuple[str, ...]:
        """What changed the result asked for: the text of the call's warning, one library line
        a problem."""
        if self._problems is None:
            self._problems = library_problems(self._text)
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
