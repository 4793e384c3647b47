#!/usr/bin/env python3
"""A uDALES-style city of box buildings on a ground plane, as triangles (issue 23's urban
bench): a square of blocks x blocks plots on a grid of `cell` metres; each plot holds one
building of plot - street cells on a side with a height of 1 to max_height cells (a seeded
random draw: the same arguments give the same city, byte for byte), and streets of `street`
cells between them. The ground (cells not under a building, facing up), the walls (facing
out) and the roofs (facing up) are split into the grid's squares, each square into two
triangles: every triangle is one surface, as uDALES's facets are.

Writes binary STL, and with --vs3 the same triangles as a View3D 3.2 input (shared vertices,
encl=0: an open scene, its rows do not sum to 1) in the same order, so row k of both tools'
output is facet k. --blocks is chosen from --facets when given (the smallest city with at least
that many facets).

usage: city_stl.py OUT.stl [--blocks B | --facets N] [--plot 4] [--street 1] [--max-height 4]
                   [--cell 3.0] [--seed 1] [--vs3 OUT.vs3]
"""
import argparse
import random
import struct
import sys


def city_quads(blocks, plot, street, max_height, seed):
    """Quadrilaterals in grid units, corners counter-clockwise seen from the front."""
    rng = random.Random(seed)
    size = blocks * plot
    covered = set()
    quads = []
    for bx in range(blocks):
        for by in range(blocks):
            x0, y0 = bx * plot + street, by * plot + street  # the street on the low sides
            x1, y1 = (bx + 1) * plot, (by + 1) * plot
            h = rng.randint(1, max_height)
            for x in range(x0, x1):
                for y in range(y0, y1):
                    covered.add((x, y))
                    quads.append([(x, y, h), (x + 1, y, h), (x + 1, y + 1, h), (x, y + 1, h)])
            for z in range(h):
                for x in range(x0, x1):  # -y and +y walls
                    quads.append([(x, y0, z), (x + 1, y0, z), (x + 1, y0, z + 1), (x, y0, z + 1)])
                    quads.append([(x + 1, y1, z), (x, y1, z), (x, y1, z + 1), (x + 1, y1, z + 1)])
                for y in range(y0, y1):  # -x and +x walls
                    quads.append([(x0, y + 1, z), (x0, y, z), (x0, y, z + 1), (x0, y + 1, z + 1)])
                    quads.append([(x1, y, z), (x1, y + 1, z), (x1, y + 1, z + 1), (x1, y, z + 1)])
    for x in range(size):
        for y in range(size):
            if (x, y) not in covered:
                quads.append([(x, y, 0), (x + 1, y, 0), (x + 1, y + 1, 0), (x, y + 1, 0)])
    return quads


def triangles(quads, cell):
    for q in quads:
        p = [tuple(cell * c for c in v) for v in q]
        yield p[0], p[1], p[2]
        yield p[0], p[2], p[3]


def facet_count(blocks, plot, street, max_height, seed):
    return 2 * len(city_quads(blocks, plot, street, max_height, seed))


def write_stl(tris, path):
    with open(path, 'wb') as f:
        f.write(b'radflux bench/city_stl.py'.ljust(80, b' '))
        f.write(struct.pack('<I', len(tris)))
        for a, b, c in tris:
            u = [b[k] - a[k] for k in range(3)]
            v = [c[k] - a[k] for k in range(3)]
            n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            length = sum(x * x for x in n) ** 0.5
            f.write(struct.pack('<12fH', *[x / length for x in n], *a, *b, *c, 0))


def write_vs3(tris, path):
    index, verts = {}, []
    faces = []
    for t in tris:
        ids = []
        for p in t:
            if p not in index:
                verts.append(p)
                index[p] = len(verts)
            ids.append(index[p])
        faces.append(ids)
    with open(path, 'w') as f:
        f.write('T city of boxes (bench/city_stl.py)\n')
        f.write('C encl=0 list=0 eps=1.0e-4 out=0\nF 3\n')
        for k, p in enumerate(verts, 1):
            f.write('V %d %.9g %.9g %.9g\n' % (k, *p))
        for k, (a, b, c) in enumerate(faces, 1):
            f.write('S %d %d %d %d 0 0 0 0.9 f%d\n' % (k, a, b, c, k))
        f.write('E\n')


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('out')
    ap.add_argument('--blocks', type=int)
    ap.add_argument('--facets', type=int, help='choose --blocks for at least this many facets')
    ap.add_argument('--plot', type=int, default=4, help='grid cells per plot side')
    ap.add_argument('--street', type=int, default=1, help='grid cells of street per plot')
    ap.add_argument('--max-height', type=int, default=4, help='grid cells')
    ap.add_argument('--cell', type=float, default=3.0, help='metres per grid cell')
    ap.add_argument('--seed', type=int, default=1)
    ap.add_argument('--vs3', help='also write the triangles as View3D .vs3')
    a = ap.parse_args()
    if (a.blocks is None) == (a.facets is None):
        sys.exit('city_stl.py: give one of --blocks and --facets')
    if not 0 < a.street < a.plot or a.max_height < 1 or a.cell <= 0:
        sys.exit('city_stl.py: need 0 < street < plot, max-height >= 1, cell > 0')
    blocks = a.blocks
    if blocks is None:
        blocks = 1
        while facet_count(blocks, a.plot, a.street, a.max_height, a.seed) < a.facets:
            blocks += 1
    tris = list(triangles(city_quads(blocks, a.plot, a.street, a.max_height, a.seed), a.cell))
    write_stl(tris, a.out)
    if a.vs3:
        write_vs3(tris, a.vs3)
    print('%s: %d x %d blocks, %d facets' % (a.out, blocks, blocks, len(tris)))


if __name__ == '__main__':
    sys.exit(main())
