#!/usr/bin/env python3
"""radflux viewfactors against View3D 3.2 on the same machine, in the same run (issue 23).

Writes a grid room as View3D .vs3: the unit cube room, n x n squares on each of its six walls
(facing inward), and a floating box [0.35, 0.65]^3 (six faces facing outward): 6 n^2 + 6
surfaces (n = 20: 2,406; n = 50: 15,006). Runs View3D (out=0, its text output) and
`radflux viewfactors --format view3d` on it, then reports each one's wall time and peak memory
and radflux's per-row relative L1 error against View3D: sum_j |F_ij - V_ij| / sum_j V_ij.

usage: view3d_compare.py --view3d PATH --radflux PATH [--n 20] [--workdir DIR]
                         [--skip-view3d] [-- extra radflux viewfactors arguments]
"""
import argparse
import os
import statistics
import subprocess
import sys
import time


def grid_room_vs3(n, path):
    verts, index, surfaces = [], {}, []

    def vertex(p):
        key = tuple(round(c, 12) for c in p)
        if key not in index:
            verts.append(key)
            index[key] = len(verts)
        return index[key]

    def quad(corners, kind='S'):  # counter-clockwise seen from the side that sees the others
        surfaces.append((kind, [vertex(c) for c in corners]))

    def wall(origin, u, v, inward):
        for a in range(n):
            for b in range(n):
                p = [tuple(origin[k] + u[k] * (a + da) / n + v[k] * (b + db) / n for k in range(3))
                     for da, db in ((0, 0), (1, 0), (1, 1), (0, 1))]
                quad(p[::-1] if inward else p)

    x, y, z = (1, 0, 0), (0, 1, 0), (0, 0, 1)
    wall((0, 0, 0), y, x, True)   # floor z = 0, facing +z
    wall((0, 0, 1), x, y, True)   # ceiling, facing -z
    wall((0, 0, 0), x, z, True)   # y = 0, facing +y
    wall((0, 1, 0), z, x, True)   # y = 1, facing -y
    wall((0, 0, 0), z, y, True)   # x = 0, facing +x
    wall((1, 0, 0), y, z, True)   # x = 1, facing -x
    lo, hi = 0.35, 0.65
    s = hi - lo
    for origin, u, v in (((lo, lo, lo), y, x), ((lo, lo, hi), x, y), ((lo, lo, lo), x, z),
                         ((lo, hi, lo), z, x), ((lo, lo, lo), z, y), ((hi, lo, lo), y, z)):
        corners = [tuple(origin[k] + s * (u[k] * da + v[k] * db) for k in range(3))
                   for da, db in ((0, 0), (1, 0), (1, 1), (0, 1))]
        quad(corners)  # the box faces outward: the room's winding, not reversed
    with open(path, 'w') as f:
        f.write('T grid room %d x %d per wall and a floating box\n' % (n, n))
        f.write('C encl=0 list=0 eps=1.0e-4 out=0\nF 3\n')
        for k, p in enumerate(verts, 1):
            f.write('V %d %.9g %.9g %.9g\n' % (k, *p))
        for k, (kind, vs) in enumerate(surfaces, 1):
            f.write('%s %d %s 0 0 0.9 s%d\n' % (kind, k, ' '.join(map(str, vs)), k))
        f.write('E\n')
    return len(surfaces)


def run(cmd, cwd, quiet=False):
    """Wall seconds, CPU seconds (user + system) and peak RSS (MiB) of one command. On a
    shared machine the wall time includes waiting for a core; the CPU time does not.
    quiet: drop its stderr too (View3D prints a progress line per surface there)."""
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, cwd=cwd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL if quiet else None)
    _, status, usage = os.wait4(proc.pid, 0)
    seconds = time.perf_counter() - start
    if status != 0:
        sys.exit('%s failed (status %d)' % (' '.join(cmd), status))
    return seconds, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024.0


def read_view3d(path, n):
    with open(path) as f:
        lines = f.read().split('\n')
    return [[float(v) for v in lines[2 + i].split()] for i in range(n)]


def row_errors(test, reference):
    errors = []
    for f, v in zip(test, reference):
        total = sum(v)
        if total > 0:
            errors.append(sum(abs(a - b) for a, b in zip(f, v)) / total)
    return errors


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--view3d', required=True)
    ap.add_argument('--radflux', required=True)
    ap.add_argument('--n', type=int, default=20)
    ap.add_argument('--workdir', default='/tmp/view3d_compare')
    ap.add_argument('--skip-view3d', action='store_true', help='reuse the last View3D output')
    ap.add_argument('extra', nargs='*')
    a = ap.parse_args()
    a.view3d, a.radflux = os.path.abspath(a.view3d), os.path.abspath(a.radflux)
    os.makedirs(a.workdir, exist_ok=True)
    model = os.path.join(a.workdir, 'room%d.vs3' % a.n)
    surfaces = grid_room_vs3(a.n, model)
    v3_out = os.path.join(a.workdir, 'room%d.view3d.vf' % a.n)
    rf_out = os.path.join(a.workdir, 'room%d.radflux.vf' % a.n)
    if not a.skip_view3d or not os.path.exists(v3_out):
        v3_s, v3_cpu, v3_mib = run([a.view3d, model, v3_out], a.workdir, quiet=True)
        print('View3D 3.2: %d surfaces, %.2f s wall, %.2f s CPU, peak %.0f MiB'
              % (surfaces, v3_s, v3_cpu, v3_mib))
    else:
        v3_s = None
    cmd = [a.radflux, 'viewfactors', model, '--format', 'view3d', '-o', rf_out, '-q'] + a.extra
    rf_s, rf_cpu, rf_mib = run(cmd, a.workdir)
    print('radflux %s: %.2f s wall, %.2f s CPU, peak %.0f MiB%s'
          % (' '.join(a.extra) or '(defaults)', rf_s, rf_cpu, rf_mib,
             ' (View3D / radflux wall time: %.1f)' % (v3_s / rf_s) if v3_s else ''))
    errors = row_errors(read_view3d(rf_out, surfaces), read_view3d(v3_out, surfaces))
    errors.sort()
    print('per-row relative L1 against View3D: median %.3f%%, 90th %.3f%%, worst %.3f%%'
          % (100 * statistics.median(errors), 100 * errors[int(0.9 * (len(errors) - 1))],
             100 * errors[-1]))


if __name__ == '__main__':
    sys.exit(main())
