#!/usr/bin/env python3
"""Writes a test model as an ASCII STL, each quad as two facets (the view-factor tests):
   canyon  a 2 x 1 street: ground and two facing walls of height 1 (6 facets);
   yard    a 20 x 20 grid of unit ground squares and a wall along one side, facing the
           ground (802 facets).
Usage: write_stl.py MODEL PATH"""
import sys

MODELS = {
    "canyon": [((0, 0, 0), (2, 0, 0), (2, 1, 0), (0, 1, 0)),   # ground, up
               ((0, 0, 0), (0, 1, 0), (0, 1, 1), (0, 0, 1)),   # west wall, facing +x
               ((2, 0, 0), (2, 0, 1), (2, 1, 1), (2, 1, 0))],  # east wall, facing -x
    "yard": [((x, y, 0), (x + 1, y, 0), (x + 1, y + 1, 0), (x, y + 1, 0))
             for x in range(20) for y in range(20)]
            + [((0, 0, 0), (0, 20, 0), (0, 20, 5), (0, 0, 5))],
}

model, path = sys.argv[1], sys.argv[2]
with open(path, "w") as f:
    f.write(f"solid {model}\n")
    for a, b, c, d in MODELS[model]:
        for tri in ((a, b, c), (a, c, d)):
            f.write("facet normal 0 0 0\nouter loop\n")
            for v in tri:
                f.write("vertex %g %g %g\n" % v)
            f.write("endloop\nendfacet\n")
    f.write(f"endsolid {model}\n")
