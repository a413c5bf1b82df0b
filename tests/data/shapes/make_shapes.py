#!/usr/bin/env python3
"""Writes the classic test shapes of tests/pslg_*.rs as Triangle .poly files.

Run from this directory: `python3 make_shapes.py`. The output is checked in; this script only
documents how it was made (the hand-written shapes are plain literals here too). Coordinates
computed from cos/sin are printed with 17 significant digits, so they read back exactly.

Every file numbers vertices and segments from 1, has a vertex-marker column and a segment-marker
column with non-trivial markers, and lists its holes (and regions where the shape has them).
Most shapes are deliberately a little asymmetric, so that their constrained Delaunay
triangulation is unique (symmetric shapes have cocircular vertex quadruples); `box_in_box` keeps
its axis-aligned boxes to exercise the cocircular case.
"""

import math


def g(x):
    return "%.17g" % x


def write_poly(name, comment, vertices, segments, holes, regions=(), attributes=0):
    """vertices: (x, y, [attributes...], marker); segments: (a, b, marker), 1-based."""
    lines = ["# " + line for line in comment.strip().splitlines()]
    lines.append("%d 2 %d 1" % (len(vertices), attributes))
    for i, v in enumerate(vertices, 1):
        x, y, attrs, marker = v
        fields = [str(i), g(x), g(y)] + [g(a) for a in attrs] + [str(marker)]
        lines.append("  ".join(fields))
    lines.append("%d 1" % len(segments))
    for i, (a, b, marker) in enumerate(segments, 1):
        lines.append("%d  %d %d  %d" % (i, a, b, marker))
    lines.append("%d" % len(holes))
    for i, (x, y) in enumerate(holes, 1):
        lines.append("%d  %s %s" % (i, g(x), g(y)))
    lines.append("%d" % len(regions))
    for i, (x, y, attribute, area) in enumerate(regions, 1):
        lines.append("%d  %s %s  %s %s" % (i, g(x), g(y), g(attribute), g(area)))
    with open(name + ".poly", "w") as f:
        f.write("\n".join(lines) + "\n")


def ring(first, count, marker):
    """Segments closing vertices first..first+count-1 into a loop."""
    return [(first + k, first + (k + 1) % count, marker) for k in range(count)]


def letter_a():
    outer = [(0.0, 0.0, 5), (0.93, 0.0, 0), (1.27, 1.12, 0), (2.74, 1.09, 0),
             (3.11, 0.0, 0), (4.03, 0.02, 5), (2.46, 5.04, 6), (1.53, 4.98, 6)]
    hole = [(1.51, 1.91, 0), (2.52, 1.88, 0), (2.03, 3.62, 7)]
    vertices = [(x, y, [], m) for x, y, m in outer + hole]
    segments = [(1, 2, 2), (2, 3, 3), (3, 4, 3), (4, 5, 3), (5, 6, 2), (6, 7, 4),
                (7, 8, 0), (8, 1, 4)]
    segments += [(9, 10, 9), (10, 11, 0), (11, 9, 9)]
    write_poly("letter_a", """
The letter A: an outline with a triangular hole above the crossbar.
Outer segment markers 2, 3, 4 (one 0: it gets 1 on the boundary); hole markers 9 and 0.""",
               vertices, segments, holes=[(2.02, 2.4)])


def box_in_box():
    outer = [(0, 0, 2), (10, 0, 2), (10, 8, 2), (0, 8, 2)]
    inner = [(2, 2, 0), (7, 2, 0), (7, 6, 0), (2, 6, 0)]
    hole = [(3, 3, 0), (5, 3, 0), (5, 5, 0), (3, 5, 0)]
    free = [(8.5, 4, 0), (1, 1, 3), (7, 4.5, 0)]
    vertices = [(x, y, [], m) for x, y, m in outer + inner + hole + free]
    segments = ring(1, 4, 11) + ring(5, 4, 12) + ring(9, 4, 0)
    segments[1] = (2, 3, 0)  # one outer side without a marker
    write_poly("box_in_box", """
A box, an inner box (its own region) and a square hole inside the inner box, plus three
free vertices (the last one lies on the inner box's right side). Axis-aligned boxes: many
cocircular quadruples, so the Delaunay triangulation is not unique there.""",
               vertices, segments, holes=[(4, 4)],
               regions=[(0.5, 7.5, 1.0, 2.0), (2.5, 5.5, 2.0, 0.5)])


def double_hexagon():
    def hexagon(cx, cy, r, phase):
        return [(cx + r * math.cos(phase + k * math.pi / 3), cy + r * math.sin(phase + k * math.pi / 3))
                for k in range(6)]
    # Two pointy-top hexagons of radius 1 side by side: the right one's corners 2 (upper left)
    # and 3 (lower left) are the left one's corners 0 and 5 (up to rounding), so the right one
    # reuses those two vertices and the shared side is one segment.
    phase = math.pi / 6
    left = hexagon(0.0, 0.0, 1.0, phase)
    right = hexagon(math.sqrt(3.0), 0.0, 1.0, phase)
    small = hexagon(0.05, -0.03, 0.45, 0.1)  # a rotated hole, off-centre
    pts = []
    pts += [(x, y, 1) for x, y in left]                 # 1..6
    pts += [(x, y, 0) for x, y in (right[0], right[1], right[4], right[5])]  # 7..10
    pts += [(x, y, 0) for x, y in small]                # 11..16
    vertices = [(x, y, [], m) for x, y, m in pts]
    segments = []
    segments += [(1, 2, 21), (2, 3, 21), (3, 4, 21), (4, 5, 21), (5, 6, 21)]
    segments += [(6, 1, 30)]  # the shared side
    # The right hexagon's corners 0..5 are vertices 7, 8, 1, 6, 9, 10.
    segments += [(7, 8, 22), (8, 1, 22), (6, 9, 22), (9, 10, 22), (10, 7, 0)]
    segments += ring(11, 6, 23)
    write_poly("double_hexagon", """
Two regular hexagons sharing a side (segment marker 30), each its own region, with a small
rotated hexagonal hole off the left one's centre.""",
               vertices, segments, holes=[(0.05, -0.03)],
               regions=[(-0.6, 0.1, 10.0, 0.3), (math.sqrt(3.0) + 0.1, 0.2, 20.0, -1.0)])


def spiral():
    turns, steps = 2.0, 40
    a, b, width = 0.3, 0.16, 0.45
    theta0 = 0.37
    near, far = [], []  # the strip's sides nearer to and farther from the centre
    for k in range(steps + 1):
        t = theta0 + 2.0 * math.pi * turns * k / steps
        r = a + b * t
        near.append((r * math.cos(t), r * math.sin(t), t))
        far.append(((r + width) * math.cos(t), (r + width) * math.sin(t), t))
    # Out along the far side, back along the near side: counter-clockwise. The turns are
    # 2πb ≈ 1.0 apart and the strip 0.45 wide, so the polygon is simple.
    ccw = far + near[::-1]
    vertices = [(x, y, [t, 1.0 + k], (31 if k == 0 else 0)) for k, (x, y, t) in enumerate(ccw)]
    n = len(vertices)
    segments = [(k + 1, (k + 1) % n + 1, 40 + (k % 3)) for k in range(n)]
    write_poly("spiral", """
A spiral strip (two turns): a thin non-convex polygon whose boundary is all segments. Two vertex
attributes: the spiral angle and a counter.""",
               vertices, segments, holes=[], attributes=2)


def square_with_circular_hole():
    count = 64
    vertices = [(-2.0, -2.0, [], 0), (2.0, -2.0, [], 0), (2.0, 2.0, [], 0), (-2.0, 2.0, [], 0)]
    cx, cy, r = 0.13, -0.07, 1.0
    for k in range(count):
        t = 2.0 * math.pi * k / count + 0.01
        vertices.append((cx + r * math.cos(t), cy + r * math.sin(t), [], 8 if k % 16 == 0 else 0))
    segments = [(1, 2, 2), (2, 3, 3), (3, 4, 4), (4, 1, 5)] + ring(5, count, 7)
    write_poly("square_circular_hole", """
A square with a circular hole of 64 segments (marker 7), the circle a little off-centre.
Side markers 2, 3, 4, 5.""",
               vertices, segments, holes=[(cx, cy)])


def three_regions():
    pts = [(0.0, 0.0, 1), (2.1, 0.0, 0), (3.9, 0.0, 0), (6.0, 0.0, 1),
           (6.0, 3.0, 1), (4.3, 3.0, 0), (2.2, 3.0, 0), (0.0, 3.0, 1),
           (1.8, 1.5, 0), (3.1, 1.45, 0)]
    vertices = [(x, y, [], m) for x, y, m in pts]
    segments = [(1, 2, 3), (2, 3, 3), (3, 4, 3), (4, 5, 4), (5, 6, 3), (6, 7, 3), (7, 8, 3),
                (8, 1, 4), (2, 9, 5), (9, 7, 5), (3, 6, 6)]
    # Vertex 10 is a free vertex inside the middle region.
    write_poly("three_regions", """
A rectangle cut by a bent chord (marker 5) and a straight chord (marker 6) into three regions
with attributes 1, 2, 3 and maximum areas 0.5, 0.25 and none (-1).""",
               vertices, segments, holes=[],
               regions=[(1.0, 1.5, 1.0, 0.5), (3.5, 2.5, 2.0, 0.25), (5.0, 1.5, 3.0, -1.0)])


def pinched():
    # A square with two diamond holes: the lower touches the square's bottom side at a vertex,
    # the upper touches the lower at a vertex and the top side at another. What is left of the
    # square is two parts that meet only at those three vertices (pinches).
    pts = [(0.0, 0.0, 1), (2.05, 0.0, 0), (4.0, 0.0, 1), (4.0, 4.1, 1), (1.95, 4.1, 0),
           (0.0, 4.1, 1),
           (3.02, 1.0, 0), (2.0, 2.03, 0), (0.98, 1.07, 0),
           (3.01, 3.05, 0), (1.03, 2.96, 0)]
    vertices = [(x, y, [], m) for x, y, m in pts]
    segments = [(1, 2, 2), (2, 3, 2), (3, 4, 3), (4, 5, 4), (5, 6, 4), (6, 1, 5)]
    segments += [(2, 7, 6), (7, 8, 6), (8, 9, 6), (9, 2, 6)]
    segments += [(8, 10, 7), (10, 5, 7), (5, 11, 7), (11, 8, 7)]
    write_poly("pinched", """
A square with two diamond holes that touch each other and the square's sides at vertices: the
domain is two parts meeting only at three pinch vertices (segment markers 2 to 7).""",
               vertices, segments, holes=[(2.0, 1.0), (2.0, 3.05)])


def bow_tie():
    # Two triangles joined at one vertex, and a third at the same vertex: three fans there; two
    # free vertices inside each.
    pts = [(0.0, 0.0, 1), (1.0, 0.48, 0), (0.05, 1.0, 1), (2.0, 0.02, 1), (1.97, 1.03, 1),
           (0.6, 1.9, 1), (1.45, 1.85, 1),
           (0.36, 0.44, 0), (0.21, 0.29, 0), (1.61, 0.55, 0), (1.76, 0.31, 0), (1.02, 1.41, 0),
           (0.87, 1.66, 0)]
    vertices = [(x, y, [], m) for x, y, m in pts]
    segments = [(1, 2, 2), (2, 3, 2), (3, 1, 3), (2, 4, 4), (4, 5, 5), (5, 2, 4),
                (2, 7, 6), (7, 6, 7), (6, 2, 6)]
    write_poly("bow_tie", """
Three triangles that share one vertex and nothing else (a bow tie with a third wing): three
parts of the domain meet at that vertex (segment markers 2 to 7); two free vertices in each.""",
               vertices, segments, holes=[])


if __name__ == "__main__":
    letter_a()
    box_in_box()
    double_hexagon()
    spiral()
    square_with_circular_hole()
    three_regions()
    pinched()
    bow_tie()
