#!/usr/bin/env python3
"""radflux viewfactors against View3D 3.2 on a city of boxes (bench/city_stl.py), in the same
run (issue 23's urban goal). radflux reads the STL and writes View3D's text format (and, with
--sparse, also times the uDALES outputs: sparse rows at --min-vf 0.01 and sky view factors);
View3D reads the same triangles as .vs3. Prints each tool's wall and CPU time and peak memory,
and radflux's per-row relative L1 error against View3D. --skip-view3d times radflux alone
(View3D grows as n^2 and takes hours at 23k facets).

usage: city_compare.py --radflux PATH --facets N (--view3d PATH | --skip-view3d)
                       [--workdir DIR] [--sparse] [--repeat K]
"""
import argparse
import os
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from view3d_compare import read_view3d, row_errors, run  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--view3d', help='View3D binary (required unless --skip-view3d)')
    ap.add_argument('--radflux', required=True)
    ap.add_argument('--facets', type=int, required=True)
    ap.add_argument('--workdir', default='/tmp/city_compare')
    ap.add_argument('--skip-view3d', action='store_true')
    ap.add_argument('--sparse', action='store_true', help='time the sparse + svf outputs instead')
    ap.add_argument('--repeat', type=int, default=1, help='alternate the two tools K times')
    a = ap.parse_args()
    if not a.skip_view3d and not a.view3d:
        ap.error('--view3d PATH is required unless --skip-view3d')
    os.makedirs(a.workdir, exist_ok=True)
    stem = os.path.join(a.workdir, 'city%d' % a.facets)
    here = os.path.dirname(os.path.abspath(__file__))
    out = subprocess.run([sys.executable, os.path.join(here, 'city_stl.py'), stem + '.stl',
                          '--facets', str(a.facets), '--vs3', stem + '.vs3'],
                         check=True, capture_output=True, text=True).stdout
    facets = int(out.split()[-2])
    print(out.strip())
    if a.sparse:
        rf_cmd = [a.radflux, 'viewfactors', stem + '.stl', '--format', 'sparse', '--min-vf', '0.01',
                  '--svf', stem + '.svf', '-o', stem + '.sparse', '-q']
    else:
        rf_cmd = [a.radflux, 'viewfactors', stem + '.stl', '--format', 'view3d', '-o',
                  stem + '.radflux.vf', '-q']
    v3_times, rf_times = [], []
    for _ in range(a.repeat):
        if not a.skip_view3d:
            v3 = run([os.path.abspath(a.view3d), stem + '.vs3', stem + '.view3d.vf'], a.workdir,
                     quiet=True)
            v3_times.append(v3[0])
            print('View3D 3.2: %.2f s wall, %.2f s CPU, peak %.0f MiB' % v3)
        rf = run(rf_cmd, a.workdir)
        rf_times.append(rf[0])
        print('radflux: %.2f s wall, %.2f s CPU, peak %.0f MiB' % rf)
    if v3_times:
        print('median wall: View3D %.2f s, radflux %.2f s (ratio %.1f)'
              % (statistics.median(v3_times), statistics.median(rf_times),
                 statistics.median(v3_times) / statistics.median(rf_times)))
        if not a.sparse:
            errors = sorted(row_errors(read_view3d(stem + '.radflux.vf', facets),
                                       read_view3d(stem + '.view3d.vf', facets)))
            print('per-row relative L1 against View3D: median %.3f%%, 90th %.3f%%, worst %.3f%%'
                  % (100 * statistics.median(errors), 100 * errors[int(0.9 * (len(errors) - 1))],
                     100 * errors[-1]))


if __name__ == '__main__':
    sys.exit(main())
