#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Cuts the .vtu grids written by `auvloop mesh` with a plane normal to a body axis and writes
the cell edges in that plane as gnuplot segment files, one per grid and overset status.
Usage: grid_slice.py MESH_DIR AXIS VALUE XMIN XMAX YMIN YMAX OUT_PREFIX GRID...
(AXIS x, y or z; the window is in the two remaining axes, in their natural order)."""
import re
import sys


def arrays(text):
    out = {}
    for m in re.finditer(r'<DataArray([^>]*)>(.*?)</DataArray>', text, re.S):
        name = re.search(r'Name="([^"]*)"', m.group(1))
        key = name.group(1) if name else 'points'
        out[key] = [float(v) for v in m.group(2).split()]
    return out


def main():
    mesh, axis, value = sys.argv[1], 'xyz'.index(sys.argv[2]), float(sys.argv[3])
    lo_a, hi_a, lo_b, hi_b = map(float, sys.argv[4:8])
    prefix, grids = sys.argv[8], sys.argv[9:]
    a_axis, b_axis = [k for k in range(3) if k != axis]
    for grid in grids:
        data = arrays(open(f'{mesh}/{grid}.vtu').read())
        pts = data['points']
        faces = [int(v) for v in data['faces']]
        status = data.get('status', [0.0] * len(data['offsets']))
        files = {}
        pos = 0
        for cell in range(len(data['offsets'])):
            nfaces = faces[pos]
            pos += 1
            for _ in range(nfaces):
                n = faces[pos]
                ids = faces[pos + 1:pos + 1 + n]
                pos += 1 + n
                cut = []
                for k in range(n):
                    p = pts[3 * ids[k]:3 * ids[k] + 3]
                    q = pts[3 * ids[(k + 1) % n]:3 * ids[(k + 1) % n] + 3]
                    if (p[axis] - value) * (q[axis] - value) < 0:
                        t = (value - p[axis]) / (q[axis] - p[axis])
                        cut.append([p[i] + t * (q[i] - p[i]) for i in range(3)])
                if len(cut) != 2:
                    continue
                (u, v) = cut
                if not (lo_a < u[a_axis] < hi_a and lo_b < u[b_axis] < hi_b):
                    continue
                key = int(status[cell])
                if key not in files:
                    files[key] = open(f'{prefix}-{grid}-{key}.dat', 'w')
                files[key].write(f'{u[a_axis]} {u[b_axis]} {v[a_axis] - u[a_axis]} '
                                 f'{v[b_axis] - u[b_axis]}\n')
        for f in files.values():
            f.close()


main()
