#!/usr/bin/env python3
"""Writes the many-faces scene of issue 7's clustering measurements as OBJ + MTL: a 4 x 4 x 2
room (object "room", rho 0.5, faces inward), a 1 x 1 lamp under the ceiling's centre (object
"light"), and an n x n grid of closed floating cubes (object "cubes", rho 0.5, faces outward)
over [0.5, 3.5]^2, each 0.5 * 3 / n on a side, from z = 0.25. 6 n^2 + 7 faces. The same scene
as CubeGridRoom in tests/unit/hierarchical_test_scenes.h.

usage: cube_grid_scene.py N OUT.obj   (writes OUT.mtl beside it)
"""
import os
import sys


def main():
    n, path = int(sys.argv[1]), sys.argv[2]
    mtl = os.path.splitext(path)[0] + '.mtl'
    v, f = [], []

    def quad(obj, mat, corners):  # corners counter-clockwise seen from the front
        f.append((obj, mat, [len(v) + k + 1 for k in range(4)]))
        v.extend(corners)

    def box(obj, mat, lo, hi, inward):
        (x0, y0, z0), (x1, y1, z1) = lo, hi
        faces = [[(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)],  # -z
                 [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)],  # +z
                 [(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)],  # -y
                 [(x1, y1, z0), (x0, y1, z0), (x0, y1, z1), (x1, y1, z1)],  # +y
                 [(x0, y1, z0), (x0, y0, z0), (x0, y0, z1), (x0, y1, z1)],  # -x
                 [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)]]  # +x
        for c in faces:
            quad(obj, mat, c[::-1] if inward else c)

    box('room', 'white', (0, 0, 0), (4, 4, 2), inward=True)
    quad('light', 'lamp', [(1.5, 1.5, 1.99), (1.5, 2.5, 1.99), (2.5, 2.5, 1.99), (2.5, 1.5, 1.99)])
    cell = 3.0 / n
    side = 0.5 * cell
    for i in range(n):
        for j in range(n):
            x, y = 0.5 + (i + 0.25) * cell, 0.5 + (j + 0.25) * cell
            box('cubes', 'white', (x, y, 0.25), (x + side, y + side, 0.25 + side), inward=False)
    with open(mtl, 'w') as out:
        out.write('newmtl white\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 1 1 1\n')
    with open(path, 'w') as out:
        out.write('mtllib %s\n' % os.path.basename(mtl))
        for p in v:
            out.write('v %.9g %.9g %.9g\n' % p)
        current = None
        for obj, mat, idx in f:
            if obj != current:
                out.write('o %s\n' % obj)
                current = obj
            out.write('usemtl %s\nf %s\n' % (mat, ' '.join(map(str, idx))))


if __name__ == '__main__':
    main()
