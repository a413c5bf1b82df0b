# Stands in for ex7.py of the PyPI `triangle` package's documentation, which its source
# distribution does not ship: nested rectangles, each with a region point carrying an attribute,
# triangulated with `pA` and drawn next to the input (regions as stars, triangle attributes at
# the centroids). Written for triangle-rs; it uses the package only through `triangle`.
import matplotlib.pyplot as plt
import numpy as np

import triangle as tr

points, segments, regions = [], [], []


def rectangle(x0, y0, x1, y1, attribute):
    first = len(points)
    points.extend([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
    segments.extend((first + k, first + (k + 1) % 4) for k in range(4))
    regions.append((0.5 * (x0 + x1), 0.5 * (y0 + y1), attribute, 0))


rectangle(0, 0, 6, 4, 10)  # the outer one; its region point lies outside the inner ones
rectangle(0.5, 0.5, 2.5, 3.5, 20)
rectangle(3.5, 0.5, 5.5, 1.5, 30)
rectangle(3.5, 2.5, 5.5, 3.5, 40)

A = dict(vertices=np.array(points, dtype=float), segments=np.array(segments), regions=np.array(regions, dtype=float))
B = tr.triangulate(A, 'pA')
tr.compare(plt, A, B)
plt.show()
